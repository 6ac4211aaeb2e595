"""MMG output-error fit over four manoeuvres (issue 30: <= 60 s on 2 cores) against scipy.

The records: the catalog KVLCC2 L7's 10/10 and 20/20 zig-zags (starboard first), its 20/20
zig-zag to port and its 35° starboard turning circle (:func:`seahelm.analysis.maneuvers`, 10 Hz),
with white noise of 0.5 % of U_0 on u, v and 0.5 % of U_0/L on r. The fit:
:func:`seahelm.identification.mmg_fit.identify_mmg` (regression on accelerations, the output-error
refinement over the four records at once, and the identifiable subset), timed end to end, median
of ``--repeats``; every residual and Jacobian of the refinement simulates its parameter sets as
one batch of the compiled engine (``mmg_fit._simulate``).

The baseline is the same fit (the same ``scipy.optimize.least_squares`` problem, the same
start and Jacobian steps) with every parameter set's record simulated one at a time by
:func:`scipy.integrate.solve_ivp` (RK45, rtol 1e-6) of seahelm's MMG right-hand side
(:meth:`VesselModel.derivative`, δ and n interpolated linearly between the record's samples, as
the fit's first-order hold does): the time of one such simulation of each record (median of
``--baseline-runs``) times the number of simulations the seahelm fit made of it, so the
projection counts the same work. Ratios are taken in the same run.

    python benchmarks/bench_mmg_fit.py [--repeats 3] [--baseline-runs 3] [--quick]

``--quick`` (the test suite's smoke run): two short records (the 10/10 and the turning circle
cut at 30 s), one repeat, one baseline run.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from seahelm.identification import mmg_fit
from seahelm.analysis.maneuvers import turning_circle, zigzag
from seahelm.identification.records import record_from_arrays
from seahelm.ships import get_ship

NOISE = 0.005
DEG = math.pi / 180.0


def _record(name: str, ds, ship, seed: int, t_max: float | None = None):
    t = ds["time"].values
    keep = t <= (t[-1] if t_max is None else t_max)
    t = t[keep]
    U0, L = float(np.mean(ds["surge_speed"].values)), ship.params.length
    rng = np.random.default_rng(seed)

    def noisy(key: str, scale: float) -> np.ndarray:
        return ds[key].values.reshape(-1)[keep] + rng.normal(0.0, NOISE * scale, t.size)

    return record_from_arrays(name, t, ds["rudder_angle"].values.reshape(-1)[keep],
                              ds["heading"].values.reshape(-1)[keep],
                              noisy("yaw_rate", U0 / L), surge_speed=noisy("surge_speed", U0),
                              sway_speed=noisy("sway_speed", U0),
                              propeller_rps=ds["propeller_rps"].values.reshape(-1)[keep])[0]


def make_records(ship, quick: bool) -> list:
    zz10 = zigzag(ship, 10 * DEG, sides=1, record_dt=0.1).runs
    turn = turning_circle(ship, 35 * DEG, sides=1, record_dt=0.1).runs
    if quick:
        return [_record("zz10", zz10, ship, 1, 30.0), _record("turn35", turn, ship, 2, 30.0)]
    zz20 = zigzag(ship, 20 * DEG, sides=1, record_dt=0.1).runs
    zz20p = zigzag(ship, 20 * DEG, sides=-1, record_dt=0.1).runs
    return [_record("zz10", zz10, ship, 1), _record("zz20", zz20, ship, 2),
            _record("zz20-port", zz20p, ship, 3), _record("turn35", turn, ship, 4)]


class _Count:
    """Counts the parameter-set simulations of each record that ``mmg_fit._simulate`` makes."""

    def __init__(self) -> None:
        self.runs: dict[str, int] = {}
        self._real = mmg_fit._simulate

    def __enter__(self) -> "_Count":
        def counted(params_list, record):
            self.runs[record.name] = self.runs.get(record.name, 0) + len(params_list)
            return self._real(params_list, record)

        mmg_fit._simulate = counted
        return self

    def __exit__(self, *exc) -> None:
        mmg_fit._simulate = self._real


def solve_ivp_simulation(params, record) -> np.ndarray:
    """u, v, r of one parameter set over the record by solve_ivp (the baseline)."""
    from scipy.integrate import solve_ivp

    from seahelm.registry import get_model

    model = get_model("mmg")
    t = record.time
    delta, rps = record.rudder_angle, record.channels["propeller_rps"]
    x0 = model.initial_state(surge_speed=record.channels["surge_speed"][0],
                             sway_speed=record.channels["sway_speed"][0],
                             yaw_rate=record.yaw_rate[0])

    def rhs(tt, x):
        return model.derivative(tt, x, np.array([np.interp(tt, t, delta),
                                                 np.interp(tt, t, rps)]), params)

    sol = solve_ivp(rhs, (t[0], t[-1]), x0, t_eval=t, rtol=1e-6, atol=1e-9)
    return sol.y[:3]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--baseline-runs", type=int, default=3)
    ap.add_argument("--quick", action="store_true",
                    help="smoke run: two 30 s records, 1 repeat, 1 baseline run")
    args = ap.parse_args()
    if args.quick:
        args.repeats, args.baseline_runs = 1, 1
    ship = get_ship("kvlcc2-l7")
    records = make_records(ship, args.quick)
    mmg_fit.refine_mmg(ship, records[:1], names=("N_r",))  # compile / load the kernel
    times, counts, fit = [], {}, None
    for _ in range(args.repeats):
        with _Count() as count:
            t0 = time.perf_counter()
            fit = mmg_fit.identify_mmg(records, ship)
            times.append(time.perf_counter() - t0)
        counts = count.runs
    seahelm = statistics.median(times)
    per_record = {}
    for rec in records:
        runs = []
        for _ in range(args.baseline_runs):
            t0 = time.perf_counter()
            solve_ivp_simulation(fit.params, rec)
            runs.append(time.perf_counter() - t0)
        per_record[rec.name] = statistics.median(runs)
    baseline = sum(per_record[name] * counts.get(name, 0) for name in per_record)
    samples = sum(r.time.size for r in records)
    print(f"KVLCC2 L7, {len(records)} records ({', '.join(r.name for r in records)}; "
          f"{samples} samples at 10 Hz, {100 * NOISE:g} % noise)")
    print(f"  identify_mmg (regression + output error + subset): {seahelm:.2f} s "
          f"(median of {args.repeats}; {len(fit.names)} derivatives fitted, "
          f"{sum(counts.values())} parameter-set simulations of a record) — target <= 60 s")
    print("  baseline, solve_ivp per parameter set: " + ", ".join(
        f"{k} {v * 1e3:.0f} ms" for k, v in per_record.items())
          + f" per simulation; projected {baseline:.0f} s for the same simulations")
    print(f"  baseline / seahelm: {baseline / seahelm:.0f} x")


if __name__ == "__main__":
    main()
