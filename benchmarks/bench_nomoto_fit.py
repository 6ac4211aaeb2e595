"""Nomoto identification of a one-hour 10 Hz zig-zag record: seahelm against a scipy baseline.

The record: a first-order Nomoto ship (K 0.05 1/s, T 30 s, δ_0 0.5°) in 10° zig-zags with a
150 s period for one hour, sampled at 10 Hz (36,000 samples), heading noise σ 0.2°. seahelm's
:func:`seahelm.identification.nomoto_fit.fit_nomoto` (equation-error start, output error on the
compiled engine, the Jacobian as one batched run) against the baseline a user would write:
:func:`scipy.optimize.least_squares` from the same start with its own finite-difference
Jacobian and the heading simulated by :func:`scipy.integrate.solve_ivp` (RK45, rtol 1e-8) with
the rudder interpolated. Both estimates are printed (the baseline's are biased where RK45 steps
over the rudder's switches); the time is the median of ``--repeats`` runs, and the ratio is
measured in the same run. Target (issue 30): ≤ 1 s.

    python benchmarks/bench_nomoto_fit.py [--repeats 3] [--quick]
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from seahelm.identification.nomoto_fit import equation_error_start, fit_nomoto, simulate_records
from seahelm.identification.records import record_from_arrays

TRUTH = np.array([0.05, 30.0, math.radians(0.5)])


def make_record(duration: float, rate: float):
    t = np.arange(0.0, duration, 1.0 / rate)
    delta = math.radians(10.0) * np.sign(np.sin(2 * np.pi * t / 150.0 + 0.01))
    base = record_from_arrays("zigzag", t, delta, heading=np.zeros_like(t))[0]
    psi = simulate_records(1, TRUTH[None], np.zeros((1, 2)), base, "heading")[0]
    noise = np.random.default_rng(1).normal(0.0, math.radians(0.2), t.size)
    return record_from_arrays("zigzag", t, delta, heading=psi + noise)[0]


def baseline(record) -> np.ndarray:
    from scipy.integrate import solve_ivp
    from scipy.optimize import least_squares

    t, delta, psi = record.time, record.rudder_angle, record.heading

    def heading(x):
        k, tc, d0, psi0, r0 = x

        def rhs(tt, y):
            return [y[1], (k * (np.interp(tt, t, delta) + d0) - y[1]) / tc]

        sol = solve_ivp(rhs, (t[0], t[-1]), [psi0, r0], t_eval=t, rtol=1e-8, atol=1e-10)
        return sol.y[0]

    start = equation_error_start([record], 1)
    x0 = np.concatenate([start, [psi[0], 0.0]])
    sol = least_squares(lambda x: psi - heading(x), x0, x_scale="jac", diff_step=1e-5)
    return sol.x[:3]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="a 5-minute record, 1 repeat")
    args = parser.parse_args()
    duration, repeats = (300.0, 1) if args.quick else (3600.0, args.repeats)
    record = make_record(duration, 10.0)
    fit_nomoto(record)  # compile / warm
    times, base_times = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fit = fit_nomoto(record)
        times.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        ref = baseline(record)
        base_times.append(time.perf_counter() - t0)
    ts, tb = statistics.median(times), statistics.median(base_times)
    print(f"record: {record.time.size} samples ({duration / 3600:g} h at 10 Hz)")
    print(f"seahelm fit_nomoto: {ts:.3f} s (median of {repeats}); K {fit.values[0]:.5f} 1/s, "
          f"T {fit.values[1]:.3f} s, delta_0 {math.degrees(fit.values[2]):.4f} deg")
    print(f"scipy least_squares + solve_ivp: {tb:.3f} s; K {ref[0]:.5f}, T {ref[1]:.3f}, "
          f"delta_0 {math.degrees(ref[2]):.4f} deg")
    print(f"baseline / seahelm: {tb / ts:.1f}x (target: seahelm <= 1 s)")


if __name__ == "__main__":
    main()
