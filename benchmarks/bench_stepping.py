"""Stepping from outside against the whole horizon: the same runs, the same compiled loop.

KVLCC2 L7 (MMG, rudder servo) turning at 35° rudder, dt 0.1 s, a controller interval of 1 s:

* ``whole horizon``: ``simulate(problem)`` of ``--runs`` runs (default 1,000) and of 1 run;
* ``stepped``: a :class:`seahelm.Simulator` of the same problem stepped one 1 s interval at a
  time over the same horizon (``step()``: the commands from the problem's controller), and
  with the commands given by the caller (``step(commands)``: an external controller);
* ``per-interval overhead`` at batch 1: what a stepped interval costs beyond the interval's
  share of the whole-horizon run; and the intervals per second of a Nomoto ship driven from a
  Python loop (the figure a single-vessel environment of reinforcement learning sees).

Prints medians of ``--repeats`` repetitions and the ratios, from one run of this script (every
kernel compiled before the clock starts).

    python benchmarks/bench_stepping.py [--runs 1000] [--t-final 300] [--repeats 5] [--quick]

``--quick`` (the test suite's smoke run): 20 runs, 30 s, 1 repeat.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from seahelm import Problem, Simulator, simulate
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.ships import get_ship
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

DT, CONTROLLER_DT = 0.1, 1.0
RUDDER = math.radians(35.0)


def kvlcc2_problem(n_runs: int, t_final: float) -> Problem:
    ship = get_ship("kvlcc2-l7")
    start = approach_state(ship, trim=True)
    x0 = np.repeat(start.state[None], n_runs, axis=0)
    x0[:, 2] = np.linspace(0.0, 0.5, n_runs)  # headings apart (the runs differ)
    rudder = np.full((n_runs, 1, 1), RUDDER)
    return Problem(ship=ship, x0=x0, actuator_x0=[start.inputs["rudder_angle"]],
                   t_final=t_final, dt=DT, controller_dt=CONTROLLER_DT,
                   reference={"rudder_command": rudder,
                              "propeller_rps": start.inputs["propeller_rps"]},
                   record_every=10)


def whole(problem: Problem) -> float:
    """The whole horizon's loop [s] (``metadata["wall_time_s"]``: the compiled loop's own
    time, without building the arrays and the result around it)."""
    return float(simulate(problem).metadata["wall_time_s"])


def whole_end_to_end(problem: Problem) -> float:
    t0 = time.perf_counter()
    simulate(problem)
    return time.perf_counter() - t0


def stepped(sim: Simulator, commands: np.ndarray | None = None) -> float:
    t0 = time.perf_counter()
    sim.reset()
    for _ in range(sim.n_intervals):
        sim.step(commands)
    return time.perf_counter() - t0


def nomoto_problem(t_final: float) -> Problem:
    return Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0),
                   x0=np.zeros(4), t_final=t_final, dt=DT, controller_dt=CONTROLLER_DT,
                   record_every=10)


def median(f, repeats: int) -> float:
    return statistics.median(f() for _ in range(repeats))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--t-final", type=float, default=300.0)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    if args.quick:
        args.runs, args.t_final, args.repeats = 20, 30.0, 1
    n_int = int(round(args.t_final / CONTROLLER_DT))
    print(f"KVLCC2 L7 MMG + servo, 35° rudder, dt {DT} s, {n_int} controller intervals of "
          f"{CONTROLLER_DT} s; medians of {args.repeats}")
    rows = []
    for n in (1, args.runs):
        problem = kvlcc2_problem(n, args.t_final)
        whole(problem)  # compile/load before the clock
        with Simulator(problem) as sim:
            given = {"rudder_command": RUDDER,
                     "propeller_rps": float(problem.reference["propeller_rps"])}
            cmds = np.tile([given[name] for name in sim.command_labels], (n, 1))
            stepped(sim)
            stepped(sim, cmds)
            t_whole = median(lambda: whole(problem), args.repeats)
            t_e2e = median(lambda: whole_end_to_end(problem), args.repeats)
            t_step = median(lambda: stepped(sim), args.repeats)
            t_ext = median(lambda: stepped(sim, cmds), args.repeats)
        rows.append((n, t_whole, t_e2e, t_step, t_ext))
    print("throughput of the stepped runs as a share of the whole horizon's loop (simulate's "
          "wall_time_s; end to end in brackets)")
    print(f"{'runs':>6} {'whole horizon':>14} {'(end to end)':>14} {'stepped':>10} {'ratio':>7}"
          f" {'commands given':>15} {'ratio':>7}")
    for n, t_whole, t_e2e, t_step, t_ext in rows:
        print(f"{n:>6} {t_whole:>12.4f} s {t_e2e:>12.4f} s {t_step:>8.4f} s "
              f"{t_whole / t_step:>6.0%} {t_ext:>13.4f} s {t_whole / t_ext:>6.0%}")
    n1 = rows[0]
    over = (n1[3] - n1[1]) / n_int
    print(f"per-interval overhead at batch 1 (stepped - whole horizon, per interval): "
          f"{over * 1e6:.1f} µs = {over * 1e3:.4f} ms")
    nomoto = nomoto_problem(args.t_final)
    with Simulator(nomoto) as sim:
        stepped(sim, np.array([0.1]))
        t_nom = median(lambda: stepped(sim, np.array([0.1])), args.repeats)
        t_nom_whole = median(lambda: whole(nomoto), args.repeats)
        b = sim._batch  # the machine's call cost now: a 0-step call of the compiled loop
        t0 = time.perf_counter()
        for _ in range(2000):
            b.slices.run(0, 0, b.n_steps, b.dt, b.ctrl_every, b.record_every, 1)
        t_call = (time.perf_counter() - t0) / 2000
    print(f"Nomoto-1, one run stepped from Python: {n_int / t_nom:,.0f} intervals/s "
          f"({t_nom / n_int * 1e6:.1f} µs an interval; the whole horizon "
          f"{t_nom_whole / n_int * 1e6:.1f} µs an interval)")
    print(f"calibration: one 0-step call of the compiled loop costs {t_call * 1e6:.1f} µs here "
          "now (about 4 µs on an idle core); a stepped interval makes one such call (the loop "
          "leaves the outputs at the interval's end) and some Python")


if __name__ == "__main__":
    main()
