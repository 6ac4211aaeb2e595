"""Engine throughput: vessel-steps per second of the Nomoto + servo + PID closed loop (RK4).

Batch sizes 1, 100 and 10,000 through :func:`seahelm.simulation.engine.simulate`, against a
plain per-step Python loop of the same closed loop (the way most existing ship simulators run),
measured in the same run. Prints medians of several repetitions and the ratios.

    python benchmarks/bench_engine.py [--repeats 5] [--quick]

``--quick`` (the test suite's smoke run): tiny batches and step counts, 1 repeat.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np

from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.simulation.engine import simulate
from seahelm.ships import get_ship
from seahelm.vessels.nomoto import NOMOTO2

DT = 0.1
GAINS = PIDHeadingParams(kp=3.0, ki=0.001, kd=90.0)


def run_engine(n_runs: int, n_steps: int) -> float:
    p = get_ship("mariner-nomoto2").params
    x0 = np.zeros((n_runs, 5))
    x0[:, 2] = np.linspace(-0.1, 0.1, n_runs)
    t0 = time.perf_counter()
    simulate(NOMOTO2, p, x0, t_final=n_steps * DT, dt=DT, controller=PID_HEADING,
             controller_params=GAINS, reference=[math.radians(20.0)], record_every=n_steps)
    return time.perf_counter() - t0


def run_python_loop(n_steps: int) -> float:
    """The same closed loop (Nomoto-2, servo, PID every step, RK4) as a per-step Python loop."""
    p = get_ship("mariner-nomoto2").params
    k, t1, t2, t3, u_speed = p.gain, p.t1, p.t2, p.t3, p.speed
    a = k * t3 / (t1 * t2)
    dmax, rmax, tau = math.radians(35.0), math.radians(2.33), 1.0

    def f(z, cmd):
        n, e, psi, r, xi, d = z
        target = min(max(cmd, -dmax), dmax)
        ddot = min(max((target - d) / tau, -rmax), rmax)
        rdot = xi + a * d
        return np.array([u_speed * math.cos(psi), u_speed * math.sin(psi), r, rdot,
                         (k * d - (t1 + t2) * rdot - r) / (t1 * t2), ddot])

    z = np.zeros(6)
    integral = 0.0
    ref = math.radians(20.0)
    t0 = time.perf_counter()
    for _ in range(n_steps):
        err = (ref - z[2] + math.pi) % (2 * math.pi) - math.pi
        cmd = GAINS.kp * err + GAINS.ki * integral - GAINS.kd * z[3]
        integral += err * DT
        k1 = f(z, cmd)
        k2 = f(z + 0.5 * DT * k1, cmd)
        k3 = f(z + 0.5 * DT * k2, cmd)
        k4 = f(z + DT * k3, cmd)
        z = z + DT / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--quick", action="store_true",
                        help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = parser.parse_args()
    sizes = ((1, 2_000_000), (100, 200_000), (10_000, 5_000))
    py_steps = 20_000
    if args.quick:
        args.repeats, sizes, py_steps = 1, ((1, 2_000), (10, 200), (100, 50)), 500
    run_engine(2, 10)  # compile (or load from the kernel cache) outside the timing
    print(f"seahelm engine benchmark, {os.cpu_count()} cores, Nomoto-2 + servo + PID, RK4, "
          f"dt = {DT} s; medians of {args.repeats} runs")
    py = statistics.median(run_python_loop(py_steps) for _ in range(args.repeats))
    py_rate = py_steps / py
    print(f"{'per-step Python loop':>28}: {py_rate:12.3e} steps/s")
    for n_runs, n_steps in sizes:
        wall = statistics.median(run_engine(n_runs, n_steps) for _ in range(args.repeats))
        rate = n_runs * n_steps / wall
        print(f"{'engine, batch ' + format(n_runs, ','):>28}: {rate:12.3e} vessel-steps/s "
              f"({rate / py_rate:8.0f}x the Python loop)")


if __name__ == "__main__":
    main()
