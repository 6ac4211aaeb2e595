"""Catamaran closed-loop throughput: model + eq. (21) final-state controller, RK4.

Vessel-steps per second of the twin-thruster catamaran (Shushlyapin et al., 2017; listing
parameters) under the simplified final-state yaw-rate controller eq. (21), controller every
step, through :func:`seahelm.simulation.engine.simulate` at batch 1 and 10,000 (recording only
the first and last state), against

* a per-step Python loop of the same closed loop (the same model and controller code run as
  plain Python through the numba functions' ``py_func``, RK4), and
* a hand-fused numba kernel of the same closed loop with the same model and controller
  functions inlined, compiled with numba's ``fastmath=True`` (no recording, no disturbance,
  bounds or NaN handling) — the ceiling the engine's generic loop could reach; the difference
  is engine overhead. (The engine itself uses fastmath without ``nnan``/``ninf``/``nsz`` so
  that its NaN/inf detection stays exact.)

All measured in the same run; medians of several repetitions.

    python benchmarks/bench_catamaran.py [--repeats 5] [--quick]

``--quick`` (the test suite's smoke run): tiny sizes, 1 repeat.

Targets (2 cores): ≥ 3e6 steps/s single run, ≥ 1e7 vessel-steps/s at batch 10,000.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np
from numba import njit, prange

from seahelm.actuators.servo import DIRECT
from seahelm.control.final_state import FSM_YAW_RATE_SIMPLE, fsm_thruster_rate, yaw_rate_params
from seahelm.parameters import as_records
from seahelm.simulation.engine import simulate
from seahelm.vessels.catamaran import CATAMARAN, catamaran_drift, catamaran_rhs, paper_params

DT = 0.001
REF = 0.00072
P = paper_params()
CP = yaw_rate_params(P, time_constant=1.0, step=0.01)


def _x0(n: int) -> np.ndarray:
    x0 = np.zeros((n, 7))
    x0[:, 0] = P.straight_speed()
    x0[:, 5] = np.linspace(-0.1, 0.1, n)
    return x0


def run_engine(n_runs: int, n_steps: int) -> float:
    res = simulate(CATAMARAN, P, _x0(n_runs), t_final=n_steps * DT, dt=DT,
                   controller=FSM_YAW_RATE_SIMPLE, controller_params=CP, actuator=DIRECT,
                   reference=[REF], record_every=n_steps)
    assert res.ok.all()
    return res.metadata["wall_time_s"]


def run_python_loop(n_steps: int) -> float:
    """The same closed loop as a per-step Python loop (numba functions run as Python)."""
    rhs = catamaran_rhs.py_func
    ctrl = fsm_thruster_rate.py_func
    # the compiled drift takes a record; the Python controller reads the dataclass's fields
    mp, cp = P.to_record(), CP
    z = _x0(1)[0]
    d = np.empty(0)
    u = np.empty(1)
    k1, k2, k3, k4 = (np.empty(7) for _ in range(4))
    t0 = time.perf_counter()
    for _ in range(n_steps):
        u[0] = ctrl(z, REF, cp, False, DT)
        rhs(0.0, z, u, d, mp, k1)
        rhs(0.0, z + 0.5 * DT * k1, u, d, mp, k2)
        rhs(0.0, z + 0.5 * DT * k2, u, d, mp, k3)
        rhs(0.0, z + DT * k3, u, d, mp, k4)
        z = z + DT / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return time.perf_counter() - t0


_drift = njit(inline="always")(catamaran_drift.py_func)
_thruster_rate = njit(inline="always")(fsm_thruster_rate.py_func)


@njit(cache=True, parallel=True, fastmath=True)
def _fused(Z, MP, CP, n_steps, dt, ref):  # pragma: no cover - compiled
    for i in prange(Z.shape[0]):
        mp = MP[0]  # records read in place inside the parallel loop, as the engine does
        cp = CP[0]
        z = Z[i].copy()  # thread-local, as the engine does (no false sharing)
        k1 = np.empty(7)
        k2 = np.empty(7)
        k3 = np.empty(7)
        k4 = np.empty(7)
        tmp = np.empty(7)
        for _ in range(n_steps):
            u = _thruster_rate(z, ref, cp, False, dt)
            _drift(z, mp, k1)
            k1[6] = u
            for j in range(7):
                tmp[j] = z[j] + 0.5 * dt * k1[j]
            _drift(tmp, mp, k2)
            k2[6] = u
            for j in range(7):
                tmp[j] = z[j] + 0.5 * dt * k2[j]
            _drift(tmp, mp, k3)
            k3[6] = u
            for j in range(7):
                tmp[j] = z[j] + dt * k3[j]
            _drift(tmp, mp, k4)
            k4[6] = u
            for j in range(7):
                z[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
        for j in range(7):
            Z[i, j] = z[j]


def run_fused(n_runs: int, n_steps: int) -> float:
    Z = _x0(n_runs)
    t0 = time.perf_counter()
    _fused(Z, as_records(P.to_array(), type(P)), as_records(CP.to_array(), type(CP)), n_steps,
           DT, REF)
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--quick", action="store_true",
                        help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = parser.parse_args()
    sizes = ((1, 2_000_000), (10_000, 1_000))
    py_steps = 5_000
    if args.quick:
        args.repeats, sizes, py_steps = 1, ((1, 2_000), (100, 20)), 200
    run_engine(2, 10)  # compile (or load from the kernel cache) outside the timing
    run_fused(2, 10)
    print(f"catamaran benchmark, {os.cpu_count()} cores, catamaran + eq. (21) every step, RK4, "
          f"dt = {DT} s; medians of {args.repeats} runs")
    py = statistics.median(run_python_loop(py_steps) for _ in range(args.repeats))
    py_rate = py_steps / py
    print(f"{'per-step Python loop':>32}: {py_rate:12.3e} steps/s")
    for n_runs, n_steps in sizes:
        wall = statistics.median(run_engine(n_runs, n_steps) for _ in range(args.repeats))
        rate = n_runs * n_steps / wall
        fwall = statistics.median(run_fused(n_runs, n_steps) for _ in range(args.repeats))
        frate = n_runs * n_steps / fwall
        print(f"{'engine, batch ' + format(n_runs, ','):>32}: {rate:12.3e} vessel-steps/s "
              f"({rate / py_rate:8.0f}x the Python loop)")
        print(f"{'hand-fused kernel, batch ' + format(n_runs, ','):>32}: {frate:12.3e} "
              f"vessel-steps/s (engine at {rate / frate:5.0%} of it)")


if __name__ == "__main__":
    main()
