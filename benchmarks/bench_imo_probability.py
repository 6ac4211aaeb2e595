"""The IMO check over a Monte-Carlo ensemble at scale: members/s, and the steady turns batched.

:func:`seahelm.analysis.imo.probability.imo_probabilities` of ``--members`` Monte-Carlo copies
of the KVLCC2 L7 (Y'_v, Y'_r, N'_v, N'_r drawn, 10 % standard deviation — issue 32's case):
the 35° and 10° turning circles and the 10/10 and 20/20 zig-zags to both sides and the crash
stop of every member. Timed in one process, warm (the kernels compiled or loaded before):

* ``imo_probabilities``: end to end, with the time inside the engine's batches
  (:meth:`Plan.simulate <seahelm.analysis.maneuvers.common.Plan.simulate>`) said apart —
  the rest is the steady approaches and turns, the parameter sets and the metrics;
* ``one pass of 1.5x`` (first repeat only): the same check with every member's runs 1.5 times
  the reference's durations at once (``FIRST_PASS = LAST_PASS``, no adapted first pass), what
  the check did before it ran a shorter first pass and again only the members that missed an
  event;
* ``zig-zag steady turns, batched``: what a zig-zag solves by default to check that its triggers
  are reached (the steady yaw rate at ±10° and ±20° of every member,
  :func:`~seahelm.analysis.maneuvers.ships.steady_yaw_rates`, one batch); the ensemble skips
  them now (``zigzag(check_reachable=False)``);
* ``zig-zag steady turns, one at a time``: the same turns by
  :func:`~seahelm.analysis.maneuvers.ships.steady_yaw_rate` one after the other (scipy's root
  per continuation point, the path before issue 32) on the first ``--baseline-members``
  members, scaled to all; the batched rates are checked against it (1e-9 relative);
* ``before issue 32 (estimated)``: one pass of 1.5x + the one-at-a-time turns.

Medians of ``--repeats`` runs (the baseline in the first repeat only); ratios within one
repeat. On a machine shared with other jobs the figures move by tens of per cent.

    python benchmarks/bench_imo_probability.py [--members 1000 10000] [--repeats 3]
        [--baseline-members 100] [--quick]

``--quick`` (the test suite's smoke run): 20 members, 1 repeat, a baseline of 1 member.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np

from seahelm.analysis.imo import probability as imo_probability
from seahelm.analysis.imo.probability import imo_probabilities, monte_carlo_ships
from seahelm.analysis.maneuvers import maneuver_ship
from seahelm.analysis.maneuvers import common as maneuver_common
from seahelm.analysis.maneuvers.ships import (
    clear_approaches,
    steady_approaches,
    steady_yaw_rate,
    steady_yaw_rates,
)
from seahelm.ships import get_ship

PAIRS = tuple(math.radians(d) for d in (10.0, 20.0))


class _EngineClock:
    """Time spent inside :meth:`Plan.simulate` while installed."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self._real = maneuver_common.Plan.simulate

    def __enter__(self) -> "_EngineClock":
        real, clock = self._real, self

        def timed(plan, *args, **kwargs):
            t0 = time.perf_counter()
            try:
                return real(plan, *args, **kwargs)
            finally:
                clock.seconds += time.perf_counter() - t0

        maneuver_common.Plan.simulate = timed
        return self

    def __exit__(self, *exc) -> None:
        maneuver_common.Plan.simulate = self._real


def _groups(ships: list) -> list:
    """The zig-zags' (ship, signed rudder, approach) of every member, as zigzag builds them."""
    approaches = steady_approaches(ships[0].model, [s.params for s in ships],
                                   [s.approach_speed for s in ships])
    return [(s, side * d, a) for s, a in zip(ships, approaches)
            for d in PAIRS for side in (1, -1)]


def measure(members: int, repeats: int, baseline: int) -> dict[str, list[float]]:
    ships = [maneuver_ship(s) for s in monte_carlo_ships(get_ship("kvlcc2-l7"), members,
                                                         seed=1)]
    times: dict[str, list[float]] = {k: [] for k in (
        "imo_probabilities", "  inside the engine", "  outside the engine", "one pass of 1.5x",
        "zig-zag steady turns, batched", "zig-zag steady turns, one at a time",
        "before issue 32 (estimated)")}
    for rep in range(repeats):
        clear_approaches()
        with _EngineClock() as clock:
            t0 = time.perf_counter()
            imo_probabilities(ships)
            total = time.perf_counter() - t0
        times["imo_probabilities"].append(total)
        times["  inside the engine"].append(clock.seconds)
        times["  outside the engine"].append(total - clock.seconds)
        if rep == 0:
            clear_approaches()
            passes = imo_probability.FIRST_PASS, imo_probability.LEARN
            # every member once, 1.5 times the reference's durations (no adapted first pass)
            imo_probability.FIRST_PASS = imo_probability.LAST_PASS
            imo_probability.LEARN = 2 ** 62
            try:
                t0 = time.perf_counter()
                imo_probabilities(ships)
                times["one pass of 1.5x"].append(time.perf_counter() - t0)
            finally:
                imo_probability.FIRST_PASS, imo_probability.LEARN = passes
        groups = _groups(ships)
        t0 = time.perf_counter()
        batched = steady_yaw_rates(groups)
        times["zig-zag steady turns, batched"].append(time.perf_counter() - t0)
        if rep == 0:
            some = groups[:4 * min(baseline, members)]
            t0 = time.perf_counter()
            one = [steady_yaw_rate(*g) for g in some]
            old = (time.perf_counter() - t0) * len(groups) / len(some)
            times["zig-zag steady turns, one at a time"].append(old)
            np.testing.assert_allclose(np.array(batched[:len(some)], dtype=float),
                                       np.array(one, dtype=float), rtol=1e-9)
            times["before issue 32 (estimated)"].append(times["one pass of 1.5x"][-1] + old)
        print(f"  {members} members, repeat {rep + 1}: " + ", ".join(
            f"{k.strip()} {v[-1]:.3g} s" for k, v in times.items() if len(v) > rep),
            flush=True)
    return times


def report(members: int, times: dict[str, list[float]], repeats: int, baseline: int) -> None:
    med = {k: statistics.median(v) for k, v in times.items() if v}
    print(f"\nimo_probabilities of {members:,} KVLCC2 L7 members (Y'_v, Y'_r, N'_v, N'_r drawn),"
          f" {os.cpu_count()} cores, medians of {repeats} (baseline: 1 run on "
          f"{min(baseline, members)} members, scaled)")
    for name, t in med.items():
        print(f"  {name:38s} {t:9.3f} s  {members / t:10.1f} members/s")
    turns = (statistics.median(times["zig-zag steady turns, one at a time"])
             / statistics.median(times["zig-zag steady turns, batched"][:1]))
    whole = (times["before issue 32 (estimated)"][0] / times["imo_probabilities"][0])
    share = statistics.median(
        e / t for e, t in zip(times["  inside the engine"], times["imo_probabilities"]))
    passes = times["one pass of 1.5x"][0] / times["imo_probabilities"][0]
    print(f"  steady turns: batched {turns:.0f} x faster than one at a time; two passes "
          f"{passes:.2f} x faster than one of 1.5x; whole check {whole:.1f} x faster than "
          f"before issue 32; the engine's share {100 * share:.0f} %")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--members", type=int, nargs="+", default=[1_000, 10_000])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--baseline-members", type=int, default=100)
    ap.add_argument("--quick", action="store_true",
                    help="smoke run: 20 members, 1 repeat, a baseline of 1 member")
    args = ap.parse_args()
    if args.quick:
        args.members, args.repeats, args.baseline_members = [20], 1, 1
    warm = [maneuver_ship(s) for s in monte_carlo_ships(get_ship("kvlcc2-l7"), 3, seed=99)]
    imo_probabilities(warm)  # compile / load the kernels
    steady_yaw_rates(_groups(warm))
    for members in args.members:
        times = measure(members, args.repeats, args.baseline_members)
        report(members, times, args.repeats, args.baseline_members)


if __name__ == "__main__":
    main()
