"""6-DOF throughput: the Otter USV under its heading autopilot (thrust-heading), RK4, h = 0.02 s.

Vessel-steps per second through :func:`seahelm.simulation.engine.simulate` at batch 1 and
10,000 (recording the first and last state), and one run against PythonVehicleSimulator's own
simulation loop (``lib/mainLoop.simulate``: forward Euler, a Python loop over steps) on the same
scenario and step, when a PVS snapshot is given (``SEAHELM_PVS_SOURCE``, the directory holding
``python_vehicle_simulator``). All measured in the same run; medians of several repetitions.

    python benchmarks/bench_six_dof.py [--repeats 3] [--quick]

``--quick`` (the test suite's smoke run): small sizes, 1 repeat.

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
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    repeats = 1 if args.quick else args.repeats
    big, steps_big = (200, 500) if args.quick else (10_000, 3000)
    steps_one = 500 if args.quick else 3000
    run_engine(2, 10)  # compile (or load the cached kernel)
    one = statistics.median(run_engine(1, steps_one) for _ in range(repeats))
    many = statistics.median(run_engine(big, steps_big) for _ in range(repeats))
    print(f"Otter, thrust-heading, RK4 h = {DT} s")
    print(f"  seahelm, 1 run      : {steps_one / one:12.3e} steps/s  ({one:.4f} s for "
          f"{steps_one} steps)")
    print(f"  seahelm, batch {big:<5d}: {big * steps_big / many:12.3e} steps/s  ({many:.3f} s)")
    pvs = run_pvs(steps_one)
    if pvs is None:
        print("  PVS mainLoop        : not measured (set SEAHELM_PVS_SOURCE)")
    else:
        print(f"  PVS mainLoop, 1 run : {steps_one / pvs:12.3e} steps/s  ({pvs:.3f} s); "
              f"seahelm {pvs / one:.0f} x faster")


if __name__ == "__main__":
    main()
