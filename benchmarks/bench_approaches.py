"""Monte-Carlo turning circles at scale: batched steady approaches against the one-run solve.

The KVLCC2 L7 35° starboard turning circle (80 s, RK4 at the default 0.05 s, or ``--dt``; 0.5 s
is the step at which bench_maneuvers compares with shipmmg at equal accuracy) over ``--runs``
Monte-Carlo samples with Y'_v and N'_r drawn (normal, 10 % standard deviation) — issue 32's
case. For each sample count, timed in one process (warm: the kernel compiled or loaded before):

* ``ships``: the samples' ships (:meth:`~seahelm.scenario.ManeuverJob.ships`: drawn values,
  parameter sets validated, steering gears);
* ``approaches, one run at a time``: :func:`seahelm.analysis.equilibria.equilibrium.approach_state`
  (``trim=True``) per sample — the solve the manoeuvres made before issue 32 (the old
  ``steady_approach``);
* ``approaches, batched``: :func:`seahelm.analysis.equilibria.batch_equilibrium.approach_states` of
  all samples at once;
* ``bare batch``: the simulation alone (:meth:`Plan.simulate` of the grid: the engine's batch
  with the approaches given);
* ``manoeuvre``: :func:`~seahelm.analysis.maneuvers.turning_circle` of the ships (approaches,
  simulation, metrics Dataset; the memo of approaches cleared first);
* ``end to end``: :func:`seahelm.sweep.run_sweep` in-process (ships, approaches, runs,
  metrics, the Zarr store and its summary).

Medians of ``--repeats`` runs (the one-run solve of 10,000 approaches takes ~25 s: it is timed
``--old-repeats`` times, default 1); ratios are taken within one repeat. ``--quick`` (the test
suite's smoke run): 20 samples, 1 repeat, no one-run solve beyond 20 approaches.

    python benchmarks/bench_approaches.py [--runs 1000 10000] [--repeats 3] [--old-repeats 1]
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from seahelm.analysis.equilibria.batch_equilibrium import approach_states
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.analysis.maneuvers import turning_circle
from seahelm.analysis.maneuvers.common import Plan, side_axis, value_axis
from seahelm.analysis.maneuvers.ships import clear_approaches
from seahelm.scenario import parse_scenario
from seahelm.ships import get_ship
from seahelm.sweep import run_sweep

DERIVATIVES = ("Y_v", "N_r")
RUDDER = math.radians(35.0)
T_FINAL = 80.0
#: The manoeuvres' default step for the KVLCC2 L7 [s]; ``--dt`` takes another.
DT = 0.05


def scenario(runs: int, seed: int = 1, dt: float = DT) -> str:
    params = get_ship("kvlcc2-l7").params
    draws = "\n".join(
        f'"vessel.params.{n}" = {{ distribution = "normal", mean = {getattr(params, n)!r}, '
        f'std = {abs(0.1 * getattr(params, n))!r} }}' for n in DERIVATIVES)
    return ('title = "bench: KVLCC2 L7 35 deg turning, Y_v and N_r drawn"\n'
            '[vessel]\ncatalog = "kvlcc2-l7"\n[maneuver]\nkind = "turning"\nrudder_deg = 35\n'
            f'sides = "starboard"\nt_final = {T_FINAL}\ndt = {dt!r}\n'
            f"[batch.monte_carlo]\nruns = {runs}\nseed = {seed}\n"
            f"[batch.monte_carlo.draws]\n{draws}\n")


def _old(ships: list) -> float:
    t0 = time.perf_counter()
    for s in ships:
        approach_state(s.params, s.approach_speed, model=s.model, trim=True)
    return time.perf_counter() - t0


def _bare(ships: list, dt: float) -> float:
    """The simulation of the grid alone, as turning_circle builds it (recorded every
    L/(20 U0), its default)."""
    from seahelm.analysis.maneuvers.turning_circle import default_record_every

    plan = Plan(ships, None, None, [value_axis("rudder", RUDDER, "rad"), side_axis(1)])
    approaches = plan.run_approaches()
    x0 = np.stack([a.state for a in approaches])
    reference = {"rudder_command": np.full((plan.n_runs, 1, 1), RUDDER),
                 "propeller_rps": np.array([a.rps for a in approaches]).reshape(-1, 1, 1)}
    every = default_record_every(dt, plan.run_lengths(), [a.speed for a in approaches])
    t0 = time.perf_counter()
    plan.simulate(x0=x0, actuator_x0=np.array([[a.rudder] for a in approaches]),
                  reference=reference, t_final=T_FINAL, dt=dt, record_every=every)
    return time.perf_counter() - t0


def measure(runs: int, repeats: int, old_repeats: int, old_limit: int | None,
            work: Path, dt: float = DT) -> dict[str, list[float]]:
    text = scenario(runs, dt=dt)
    path = work / f"bench-{runs}.toml"
    path.write_text(text)
    times: dict[str, list[float]] = {k: [] for k in (
        "ships", "approaches, one run at a time", "approaches, batched", "bare batch",
        "manoeuvre", "end to end")}
    for rep in range(repeats):
        # (parsed again: a job keeps its samples' draws once drawn, a repeat would not draw)
        job = parse_scenario(text, source=str(path))
        t0 = time.perf_counter()
        ships = job.ships()
        times["ships"].append(time.perf_counter() - t0)
        if rep < old_repeats:
            some = ships if old_limit is None else ships[:old_limit]
            times["approaches, one run at a time"].append(_old(some) * len(ships) / len(some))
        t0 = time.perf_counter()
        batch = approach_states(ships[0].model, [s.params for s in ships])
        times["approaches, batched"].append(time.perf_counter() - t0)
        assert batch.ok.all(), batch.message
        clear_approaches()
        times["bare batch"].append(_bare(ships, dt))
        clear_approaches()
        t0 = time.perf_counter()
        metrics = turning_circle(ships, RUDDER, sides=1, t_final=T_FINAL, dt=dt).metrics
        times["manoeuvre"].append(time.perf_counter() - t0)
        if rep == 0 and dt != DT:  # the accuracy of the larger step against the default's
            clear_approaches()
            fine = turning_circle(ships, RUDDER, sides=1, t_final=T_FINAL).metrics
            err = max(float(np.nanmax(np.abs(metrics[k].values / fine[k].values - 1.0)))
                      for k in ("advance", "tactical_diameter"))
            print(f"  dt = {dt:g} s: advance and tactical diameter within {100 * err:.3g} % of "
                  f"the default {DT:g} s step's (largest over the {runs} samples)")
        clear_approaches()
        store = work / f"here-{runs}-{rep}.zarr"
        t0 = time.perf_counter()
        run_sweep(path, store, text=text)
        times["end to end"].append(time.perf_counter() - t0)
        shutil.rmtree(store, ignore_errors=True)
        print(f"  {runs} runs, repeat {rep + 1}: " + ", ".join(
            f"{k} {v[-1]:.3g} s" for k, v in times.items() if len(v) > rep), flush=True)
    return times


def report(runs: int, times: dict[str, list[float]], repeats: int) -> None:
    med = {k: statistics.median(v) for k, v in times.items() if v}
    print(f"\nKVLCC2 L7 35 deg turning, {runs:,} Monte-Carlo samples (Y'_v, N'_r drawn), "
          f"{os.cpu_count()} cores, medians of {repeats}")
    for name, t in med.items():
        print(f"  {name:31s} {t:8.3f} s  {runs / t:10.0f} runs/s")
    n_old = len(times["approaches, one run at a time"])
    speedup = [o / b for o, b in zip(times["approaches, one run at a time"],
                                     times["approaches, batched"][:n_old])]
    e2e = [e / b for e, b in zip(times["end to end"], times["bare batch"])]
    man = [m / b for m, b in zip(times["manoeuvre"], times["bare batch"])]
    if speedup:  # (none with --old-repeats 0)
        print(f"  approaches: batched {statistics.median(speedup):.0f} x faster than one run "
              "at a time")
    print(f"  manoeuvre / bare batch: {statistics.median(man):.2f} x; end to end / bare batch: "
          f"{statistics.median(e2e):.2f} x (issue 32: <= 4 x, and <= 3 s at 10,000)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, nargs="+", default=[1_000, 10_000])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--old-repeats", type=int, default=1,
                    help="timings of the one-run-at-a-time solve (0: skip it)")
    ap.add_argument("--dt", type=float, default=DT,
                    help="RK4 step [s] (default 0.05, the manoeuvres'; 0.5 is the step of equal "
                         "accuracy in bench_maneuvers: advance and tactical diameter within 0.1 %%)")
    ap.add_argument("--quick", action="store_true",
                    help="smoke run: 20 samples, 1 repeat (what the test suite runs)")
    args = ap.parse_args()
    old_limit = None
    if args.quick:
        args.runs, args.repeats, args.old_repeats, old_limit = [20], 1, 1, 20

    work = Path(tempfile.mkdtemp(prefix="seahelm-bench-approaches-"))
    try:
        warm = parse_scenario(scenario(4, seed=99, dt=args.dt))  # compile / load the kernel
        warm.run_ships(warm.ships())
        run_sweep(work / "warm.toml", work / "warm.zarr", text=scenario(4, seed=99, dt=args.dt))
        for runs in args.runs:
            times = measure(runs, args.repeats, args.old_repeats, old_limit, work, args.dt)
            report(runs, times, args.repeats)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
