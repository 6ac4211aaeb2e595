"""Throughput of seeded wave-disturbance generation (seahelm.environment.shaping).

Measures samples per second (runs × time steps of the wave ordinate) of

* the batched shaping-filter generator (exact discretisation, numba kernel, one thread per
  run up to the CPU count), and
* a vectorised sum-of-harmonics generator ζ(t) = Σ a_i cos(ω_i t + φ_i) with
  a_i = √(2 S₁(ω_i) Δω) (numpy, float64), the usual alternative,

in the same process, reporting the median of several repeats and the ratio. Target for the
filter: ≥ 5e7 samples/s on 2 cores.

Run:  .venv/bin/python benchmarks/bench_waves.py [--repeats 5] [--runs 8] [--steps 2000000]

``--quick`` (the test suite's smoke run): tiny sizes, 1 repeat.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

from seahelm.environment.shaping import shaping_filter
from seahelm.environment.spectra import spectrum_from_wave_height


def sum_of_harmonics(spectrum, *, n_steps: int, dt: float, runs: int, n_harmonics: int, seed: int) -> np.ndarray:
    """Sum-of-harmonics realisations, shape (runs, n_steps) (vectorised over time chunks)."""
    rng = np.random.default_rng(seed)
    w_max = 6.0
    dw = w_max / n_harmonics
    omega = (np.arange(n_harmonics) + 0.5) * dw
    amp = np.sqrt(2.0 * spectrum.one_sided(omega) * dw)
    out = np.empty((runs, n_steps))
    chunk = 4096
    for r in range(runs):
        phase = rng.uniform(0.0, 2.0 * np.pi, n_harmonics)
        for start in range(0, n_steps, chunk):
            t = np.arange(start, min(start + chunk, n_steps)) * dt
            out[r, start : start + t.size] = np.cos(np.outer(t, omega) + phase) @ amp
    return out


def timed(fn, repeats: int) -> list[float]:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return times


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--runs", type=int, default=8)
    ap.add_argument("--steps", type=int, default=2_000_000)
    ap.add_argument("--harmonics", type=int, default=256)
    ap.add_argument("--h3", type=float, default=3.0)
    ap.add_argument("--dt", type=float, default=0.1)
    ap.add_argument("--quick", action="store_true",
                    help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = ap.parse_args()
    if args.quick:
        args.repeats, args.runs, args.steps = 1, 2, 20_000

    spec = spectrum_from_wave_height("rakhmanin-firsov-2", args.h3)
    filt = shaping_filter(spec)
    filt.sample(n_steps=1000, dt=args.dt, seed=0, runs=2)  # compile / warm up
    n_filter = args.runs * args.steps
    t_filter = timed(lambda: filt.sample(n_steps=args.steps, dt=args.dt, seed=1, runs=args.runs), args.repeats)

    filt2 = shaping_filter(spec, ("ordinate", "slope"))  # two outputs: state form, 2 normals/step
    filt2.sample(n_steps=1000, dt=args.dt, seed=0, runs=2)
    t_filter2 = timed(lambda: filt2.sample(n_steps=args.steps, dt=args.dt, seed=1, runs=args.runs), args.repeats)

    # the harmonic generator is ~100× slower: time a smaller batch, report per-sample rates
    h_runs, h_steps = 2, max(1000, args.steps // 100)
    sum_of_harmonics(spec, n_steps=1000, dt=args.dt, runs=1, n_harmonics=args.harmonics, seed=0)
    t_harm = timed(
        lambda: sum_of_harmonics(spec, n_steps=h_steps, dt=args.dt, runs=h_runs, n_harmonics=args.harmonics, seed=1),
        args.repeats,
    )
    rate_filter = n_filter / statistics.median(t_filter)
    rate_harm = h_runs * h_steps / statistics.median(t_harm)
    form = filt.discretize(args.dt).form
    print(f"seahelm bench_waves  (CPUs: {os.cpu_count()}, load avg: {os.getloadavg()[0]:.2f})")
    print(f"shaping filter ({form} form): {args.runs} runs x {args.steps} steps, "
          f"median {statistics.median(t_filter):.3f} s of {args.repeats} -> {rate_filter:.3e} samples/s "
          f"(target 5e7: {'met' if rate_filter >= 5e7 else 'NOT met'})")
    rate2 = n_filter / statistics.median(t_filter2)
    print(f"shaping filter, ordinate + slope ({filt2.discretize(args.dt).form} form): "
          f"median {statistics.median(t_filter2):.3f} s -> {rate2:.3e} time steps/s")
    print(f"sum of {args.harmonics} harmonics: {h_runs} runs x {h_steps} steps, "
          f"median {statistics.median(t_harm):.3f} s -> {rate_harm:.3e} samples/s")
    print(f"ratio filter / harmonics: {rate_filter / rate_harm:.1f}x")
    print("all filter times [s]: " + ", ".join(f"{t:.3f}" for t in t_filter))


if __name__ == "__main__":
    main()
