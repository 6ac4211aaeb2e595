"""MCMC of the MMG posterior (issue 30: 10,000 samples <= 5 minutes) against a scipy baseline.

The record: the catalog KVLCC2 L7 in a 20/20 zig-zag (one side, 10 Hz), white noise of 0.5 %
of U_0 on u, v and 0.5 % of U_0/L on r. The fit: :func:`seahelm.identification.mmg_fit.identify_mmg`
(regression, output error, the identifiable subset). The MCMC:
:func:`seahelm.identification.mmg_posterior.mmg_posterior` (``emcee``, the default walkers, 300 steps
of burn-in, thinned by 5) drawing 10,000 retained samples; every likelihood evaluation of a
half-ensemble is one batched run of the compiled engine. The baseline is the same likelihood
evaluated per walker, the record simulated by :func:`scipy.integrate.solve_ivp` (RK45, rtol
1e-6) of seahelm's MMG right-hand side (:meth:`VesselModel.derivative`) with δ and n
interpolated; it is timed on a few walkers and projected to the same number of evaluations.
Times are medians of ``--repeats`` runs; the ratio is measured in the same run.

    python benchmarks/bench_mmg_posterior.py [--repeats 3] [--samples 10000] [--quick]
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from seahelm.analysis.maneuvers import zigzag
from seahelm.identification.mmg_fit import _scaled_outputs, identify_mmg, refine_mmg
from seahelm.identification.mmg_posterior import mmg_posterior, output_error_log_likelihood
from seahelm.identification.records import record_from_arrays
from seahelm.ships import get_ship

NOISE = 0.005


def make_record(ship):
    ds = zigzag(ship, math.radians(20.0), math.radians(20.0), sides=1, record_dt=0.1).runs
    t = ds["time"].values
    U0, L = float(np.mean(ds["surge_speed"].values)), ship.params.length
    rng = np.random.default_rng(1)

    def noisy(name, scale):
        return ds[name].values + rng.normal(0.0, NOISE * scale, t.size)

    return record_from_arrays("zz20", t, ds["rudder_angle"].values, ds["heading"].values,
                              noisy("yaw_rate", U0 / L), surge_speed=noisy("surge_speed", U0),
                              sway_speed=noisy("sway_speed", U0),
                              propeller_rps=ds["propeller_rps"].values)[0]


def baseline_log_likelihood(fit, record, sigma):
    """The likelihood of one walker: solve_ivp of VesselModel.derivative over the record."""
    from scipy.integrate import solve_ivp

    from seahelm.registry import get_model

    model = get_model("mmg")
    t = record.time
    delta, rps = record.rudder_angle, record.channels["propeller_rps"]
    scales, measured = _scaled_outputs([record], fit.params.length)
    x0 = model.initial_state(surge_speed=measured[0][0, 0], sway_speed=measured[0][1, 0],
                             yaw_rate=measured[0][2, 0])

    def log_likelihood(theta):
        p = fit.params.replace(**dict(zip(fit.names, map(float, theta))))

        def rhs(tt, x):
            u = np.array([np.interp(tt, t, delta), np.interp(tt, t, rps)])
            return model.derivative(tt, x, u, p)

        sol = solve_ivp(rhs, (t[0], t[-1]), x0, t_eval=t, rtol=1e-6, atol=1e-9)
        r = (measured[0] - sol.y[:3]) / scales[:, None]
        return -0.5 * float(np.sum(r * r)) / sigma ** 2

    return log_likelihood


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--samples", type=int, default=10_000)
    parser.add_argument("--quick", action="store_true",
                        help="four derivatives, 200 samples, 50 burn-in steps, 1 repeat")
    args = parser.parse_args()
    ship = get_ship("kvlcc2-l7")
    record = make_record(ship)
    if args.quick:
        fit = refine_mmg(ship, [record], names=("Y_v", "Y_r", "N_v", "N_r"))
        samples, burn, repeats, n_base = 200, 50, 1, 2
    else:
        fit = identify_mmg([record], ship)
        samples, burn, repeats, n_base = args.samples, 300, args.repeats, 5
    mmg_posterior(fit, [record], n=8, method="mcmc", burn=1, seed=0)  # compile / warm
    times, post = [], None
    for k in range(repeats):
        t0 = time.perf_counter()
        post = mmg_posterior(fit, [record], n=samples, method="mcmc", burn=burn, seed=k)
        times.append(time.perf_counter() - t0)
    ts = statistics.median(times)
    evaluations = post.walkers * post.steps
    sigma = output_error_log_likelihood(fit, [record]).sigma
    base = baseline_log_likelihood(fit, record, sigma)
    base_times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for theta in post.samples[:n_base]:
            base(theta)
        base_times.append((time.perf_counter() - t0) / n_base)
    tb = statistics.median(base_times) * evaluations
    tau = post.autocorr_time
    print(f"record: {record.time.size} samples, 20/20 zig-zag of {ship.name}; "
          f"{len(fit.names)} derivatives sampled, {len(fit.fixed)} held at the base")
    print(f"MCMC: {post.walkers} walkers x {post.steps} steps ({post.burn} burn-in, thin "
          f"{post.thin}) = {evaluations} likelihood evaluations; acceptance "
          f"{post.acceptance_fraction:.2f}, autocorrelation time max {np.max(tau):.3g} steps")
    print(f"seahelm: {ts:.2f} s for {samples} retained samples (median of {repeats}): "
          f"{samples / ts:.1f} samples/s retained, {evaluations / ts:.1f} samples/s in the "
          f"chain; projected 10,000 retained samples: {10_000 / samples * ts:.1f} s "
          "(target <= 300 s)")
    print(f"baseline (solve_ivp per walker): {tb / evaluations * 1e3:.1f} ms per evaluation "
          f"(median of {repeats} x {n_base}), projected {tb:.1f} s for the same chain")
    print(f"baseline / seahelm: {tb / ts:.1f}x")


if __name__ == "__main__":
    main()
