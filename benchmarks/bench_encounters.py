"""Two-ship encounters at scale: the coupled, avoiding batch against the same ships uncoupled.

``--encounters`` (default 10,000) two-ship KVLCC2 encounters (catalog ``kvlcc2-full``) of
``--t-final`` (default 20 min), dt 0.1 s, a controller interval of 1 s, geometry drawn by
:func:`seahelm.encounters.monte_carlo.monte_carlo_vessels` (relative bearing all round, 6-9 km
at detection, CPA within ±0.5 nmi, target 3-8 m/s), side by side in one run of this script:

* ``uncoupled, rudder at zero``: the same 2 × n ships from the same starts, ``simulate`` of
  one batch over the whole horizon (rudder held at zero, propeller at its self-propulsion
  rate: :meth:`~seahelm.encounters.Encounter.uncoupled_problems`);
* ``uncoupled, same autopilot``: the same batch steered by the encounter's heading autopilot
  in the compiled loop, each ship on its initial course
  (:meth:`~seahelm.encounters.Encounter.autopilot_problems`): the ships as they steer in the
  encounter, without the coupling -- the like-for-like reference, and the target's;
* ``encounter, no avoidance``: :class:`seahelm.encounters.Encounter` stepped one interval at
  a time, every vessel's AIS view, autopilot and guidance computed between intervals;
* ``encounter, velocity obstacles``: the own ship avoiding (Kuwata et al. 2014), target on
  course.

Target (issue 51): the avoiding encounters ≤ 2 × the same ships uncoupled in one batch
(both ratios printed). Medians of ``--repeats``, the rows interleaved in each repeat (on a
shared machine the load drifts); wall time, and the CPU time of the process (the compiled
loop runs on every core, the coupling in one thread). Every kernel is compiled before the
clock starts.

    python benchmarks/bench_encounters.py [--encounters 10000] [--t-final 1200] [--repeats 1]
                                          [--quick]

``--quick`` (the test suite's smoke run): 20 encounters of 300 s.
"""

from __future__ import annotations

import argparse
import os
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

    def batch(kind: str):
        def run() -> tuple[float, float]:
            enc = Encounter(vessels, t_final=tf, record_every=record)
            (problem,) = (enc.uncoupled_problems() if kind == "zero"
                          else enc.autopilot_problems())
            t, c = time.perf_counter(), time.process_time()
            res = simulate(problem)
            wall, cpu = time.perf_counter() - t, time.process_time() - c
            assert res.ok.all()
            return wall, cpu
        return run

    def coupled(avoidance):
        def run() -> tuple[float, float]:
            enc = Encounter(vessels, t_final=tf, avoidance=avoidance, record_every=record)
            t, c = time.perf_counter(), time.process_time()
            res = enc.run()
            wall, cpu = time.perf_counter() - t, time.process_time() - c
            assert (res.status == 0).all()
            return wall, cpu
        return run

    # compile everything first (short horizons)
    warm = monte_carlo_vessels(2, own_ship="kvlcc2-full", target_ship="kvlcc2-full", seed=1,
                               detection_range=2500.0, tcpa=(10.0, 400.0))[0]
    enc = Encounter(warm, t_final=20.0, avoidance="velocity-obstacles")
    enc.run()
    for problem in enc.uncoupled_problems() + enc.autopilot_problems():
        simulate(problem)
    rows = {"uncoupled, rudder at zero": batch("zero"),
            "uncoupled, same autopilot": batch("autopilot"),
            "encounter, no avoidance": coupled(None),
            "encounter, velocity obstacles": coupled("velocity-obstacles")}
    times: dict[str, list[tuple[float, float]]] = {name: [] for name in rows}
    for _ in range(args.repeats):
        for name, fn in rows.items():
            times[name].append(fn())
    wall = {name: statistics.median(w for w, _ in v) for name, v in times.items()}
    cpu = {name: statistics.median(c for _, c in v) for name, v in times.items()}
    zero, auto = wall["uncoupled, rudder at zero"], wall["uncoupled, same autopilot"]
    print(f"{n} two-ship KVLCC2 encounters ({2 * n} ships), {tf:g} s, dt 0.1 s, "
          f"controller 1 s; medians of {args.repeats}; load {os.getloadavg()[0]:.1f}")
    print(f"{'':32s} {'wall [s]':>10s} {'cpu [s]':>9s} {'/ zero':>8s} {'/ autopilot':>12s}")
    for name in rows:
        print(f"{name:32s} {wall[name]:8.3f} s {cpu[name]:7.2f} s {wall[name] / zero:6.2f} x "
              f"{wall[name] / auto:10.2f} x")
    vo = wall["encounter, velocity obstacles"]
    for what, base in (("the same autopilot", auto), ("the rudder at zero", zero)):
        print(f"target: encounter with avoidance <= 2 x uncoupled with {what}: "
              f"{'met' if vo <= 2 * base else 'NOT met'} ({vo / base:.2f} x)")


if __name__ == "__main__":
    main()
