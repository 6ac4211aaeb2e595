"""6-DOF throughput: the Otter USV under its heading autopilot (thrust-heading), RK4, h = 0.02 s.

Vessel-steps per second through :func:`seahelm.simulation.engine.simulate` at batch 1 and
10,000 (recording the first and last state), and one run against PythonVehicleSimulator's own
simulation loop (``lib/mainLoop.simulate``: forward Euler, a Python loop over steps) on the same
scenario and step, when a PVS snapshot is given (``SEAHELM_PVS_SOURCE``, the directory holding
``python_vehicle_simulator``). All measured in the same run; medians of several repetitions.

    python benchmarks/bench_six_dof.py [--repeats 3] [--pairs 7] [--batch 10000] [--quick]

The one-run comparison times a seahelm run and a PVS run alternately, ``--pairs`` times, and
gives the median of the ratios of each pair, for the loop (``wall_time_s``) and for the whole
call (building the :class:`~seahelm.simulation.problem.Problem`, ``simulate``, the result).
``--batch 0`` skips the batch figure. ``--quick`` (the test suite's smoke run): small sizes,
1 repeat.

Targets (2 cores): ≥ 1e6 vessel-steps/s at batch 10,000; one run ≥ 100 × PVS's loop.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time

import numpy as np

from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem

DT = 0.02
REFERENCE = {"heading": math.radians(100.0), "surge_force": 120.0}


def run_engine(n_runs: int, n_steps: int) -> float:
    x0 = np.zeros((n_runs, 14))
    x0[:, 5] = np.linspace(-0.5, 0.5, n_runs)
    res = simulate(Problem(ship="otter", x0=x0, t_final=n_steps * DT, dt=DT,
                           controller="thrust-heading", actuator="direct", reference=REFERENCE,
                           record_every=n_steps))
    assert res.ok.all()
    return res.metadata["wall_time_s"]


def run_one(n_steps: int) -> tuple[float, float]:
    """One run: (the simulation's wall time, the whole call's: Problem, simulate, result)."""
    t0 = time.perf_counter()
    wall = run_engine(1, n_steps)
    return wall, time.perf_counter() - t0


def run_pvs(n_steps: int) -> float | None:
    source = os.environ.get("SEAHELM_PVS_SOURCE", "")
    if not source or not os.path.isdir(os.path.join(source, "python_vehicle_simulator")):
        return None
    sys.path.insert(0, source)
    from python_vehicle_simulator.lib.mainLoop import simulate as pvs_simulate
    from python_vehicle_simulator.vehicles.otter import otter

    vehicle = otter("headingAutopilot", 100.0, 0.0, 0.0, 120.0)
    t0 = time.perf_counter()
    pvs_simulate(n_steps, DT, vehicle)
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--pairs", type=int, default=7,
                    help="one seahelm run and one PVS run timed alternately, this many times")
    ap.add_argument("--batch", type=int, default=10_000,
                    help="runs of the batch figure (0: skip it)")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    repeats = 1 if args.quick else args.repeats
    big, steps_big = (200, 500) if args.quick else (args.batch, 3000)
    steps_one = 500 if args.quick else 3000
    pairs = 1 if args.quick else max(1, args.pairs)
    run_engine(2, 10)  # compile (or load the cached kernel)
    one = statistics.median(run_engine(1, steps_one) for _ in range(repeats))
    print(f"Otter, thrust-heading, RK4 h = {DT} s")
    print(f"  seahelm, 1 run      : {steps_one / one:12.3e} steps/s  ({one:.4f} s for "
          f"{steps_one} steps)")
    if big:
        many = statistics.median(run_engine(big, steps_big) for _ in range(repeats))
        print(f"  seahelm, batch {big:<5d}: {big * steps_big / many:12.3e} steps/s  "
              f"({many:.3f} s)")
    if run_pvs(10) is None:
        print("  PVS mainLoop        : not measured (set SEAHELM_PVS_SOURCE)")
        return
    # one run each, alternating, so that a load that comes and goes slows both alike
    rows = []
    for _ in range(pairs):
        wall, whole = run_one(steps_one)
        rows.append((wall, whole, run_pvs(steps_one)))
    pvs = statistics.median(r[2] for r in rows)
    loop = [r[2] / r[0] for r in rows]
    call = [r[2] / r[1] for r in rows]
    print(f"  PVS mainLoop, 1 run : {steps_one / pvs:12.3e} steps/s  ({pvs:.3f} s, median of "
          f"{pairs} alternating with seahelm's)")
    print(f"  seahelm / PVS, one run of {steps_one} steps: loop {statistics.median(loop):.0f} x "
          f"(range {min(loop):.0f}-{max(loop):.0f}), whole call (Problem, simulate, result) "
          f"{statistics.median(call):.0f} x (range {min(call):.0f}-{max(call):.0f}); "
          f"the call's fixed cost {1e3 * statistics.median(r[1] - r[0] for r in rows):.2f} ms")


if __name__ == "__main__":
    main()
