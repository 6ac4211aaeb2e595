"""Two-ship encounters at scale: the coupled, avoiding batch against the same ships uncoupled.

``--encounters`` (default 10,000) two-ship KVLCC2 encounters (catalog ``kvlcc2-full``) of
``--t-final`` (default 20 min), dt 0.1 s, a controller interval of 1 s, geometry drawn by
:func:`seahelm.encounters.monte_carlo.monte_carlo_vessels` (relative bearing all round, 6-9 km
at detection, CPA within ±0.5 nmi, target 3-8 m/s), side by side in one run of this script:

* ``uncoupled``: the same 2 × n ships from the same starts, ``simulate`` of one batch over the
  whole horizon (rudder held at zero, propeller at its self-propulsion rate);
* ``encounter, no avoidance``: :class:`seahelm.encounters.Encounter` stepped one interval at
  a time, every vessel's AIS view, autopilot and guidance computed between intervals;
* ``encounter, velocity obstacles``: the own ship avoiding (Kuwata et al. 2014), target on
  course.

Target (issue 51): the avoiding encounters ≤ 2 × the uncoupled batch. Medians of
``--repeats``; every kernel compiled before the clock starts.

    python benchmarks/bench_encounters.py [--encounters 10000] [--t-final 1200] [--repeats 1]
                                          [--quick]

``--quick`` (the test suite's smoke run): 20 encounters of 300 s.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from seahelm import simulate
from seahelm.encounters import Encounter
from seahelm.encounters.monte_carlo import monte_carlo_vessels


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--encounters", type=int, default=10_000)
    ap.add_argument("--t-final", type=float, default=1200.0)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    n, tf = args.encounters, args.t_final
    ranges = dict(detection_range=(6000.0, 9000.0), tcpa=(300.0, 0.6 * tf))
    if args.quick:
        n, tf, args.repeats = 20, 300.0, 1
        ranges = dict(detection_range=(2000.0, 3000.0), tcpa=(60.0, 250.0))
    vessels, _ = monte_carlo_vessels(n, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                     target_speed=(3.0, 8.0), seed=51, **ranges)
    record = 60

    def uncoupled() -> float:
        (problem,) = Encounter(vessels, t_final=tf, record_every=record).uncoupled_problems()
        t = time.perf_counter()
        res = simulate(problem)
        wall = time.perf_counter() - t
        assert res.ok.all()
        return wall

    def coupled(avoidance):
        def run() -> float:
            enc = Encounter(vessels, t_final=tf, avoidance=avoidance, record_every=record)
            t = time.perf_counter()
            res = enc.run()
            wall = time.perf_counter() - t
            assert (res.status == 0).all()
            run.result = res
            return wall
        return run

    # compile everything first (short horizons)
    warm = monte_carlo_vessels(2, own_ship="kvlcc2-full", target_ship="kvlcc2-full", seed=1,
                               detection_range=2500.0, tcpa=(10.0, 400.0))[0]
    Encounter(warm, t_final=20.0, avoidance="velocity-obstacles").run()
    rows = []
    for name, fn in (("uncoupled (simulate, one batch)", uncoupled),
                     ("encounter, no avoidance", coupled(None)),
                     ("encounter, velocity obstacles", coupled("velocity-obstacles"))):
        walls = [fn() for _ in range(args.repeats)]
        rows.append((name, statistics.median(walls)))
    base = rows[0][1]
    print(f"{n} two-ship KVLCC2 encounters ({2 * n} ships), {tf:g} s, dt 0.1 s, "
          f"controller 1 s; medians of {args.repeats}")
    print(f"{'':34s} {'wall [s]':>10s} {'ratio':>8s}")
    for name, wall in rows:
        print(f"{name:34s} {wall:10.3f} s {wall / base:7.2f} x")
    print(f"target: encounter with avoidance <= 2 x uncoupled: "
          f"{'met' if rows[2][1] <= 2 * base else 'NOT met'} ({rows[2][1] / base:.2f} x)")


if __name__ == "__main__":
    main()
