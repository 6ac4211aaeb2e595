"""Crash stops: the time of a 1,000-run stopping batch (KVLCC2 full scale, mmg-4q).

:func:`seahelm.analysis.maneuvers.crash_stop` of the catalog ``kvlcc2-full`` (the MMG ship
given its engine estimate by :func:`~seahelm.analysis.maneuvers.stopping_ship`), full astern
from 15.5 kn with the rudder amidships, end to end (approach, one compiled batch, metrics
Dataset): 1,000 runs as 40 approach speeds from 8 to 16 kn × 25 engine orders from −1 to −0.4,
1,200 s at the default step (0.2 s; 6,000 RK4 steps per run), recorded every 10 s. One run
(the IMO test) is timed too, and its track reach printed as a check. Medians of ``--repeats``
runs, after one warm-up (numba's compile cache).

    python benchmarks/bench_stopping.py [--repeats 5] [--quick]

``--quick`` runs 50 runs of 300 s once (the smoke test of ``tests``).
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from seahelm.analysis.maneuvers import crash_stop

SHIP = "kvlcc2-full"
KNOT = 1852.0 / 3600.0  # [m/s]


def _time(func, repeats: int) -> tuple[float, object]:
    out = func()  # warm-up (compile cache, approaches)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        out = func()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="timed runs (median)")
    parser.add_argument("--quick", action="store_true", help="50 short runs, once")
    args = parser.parse_args()
    if args.quick:
        speeds, orders, t_final, repeats = np.linspace(8, 16, 5) * KNOT, \
            np.linspace(-1.0, -0.4, 10), 300.0, 1
    else:
        speeds, orders, t_final, repeats = np.linspace(8, 16, 40) * KNOT, \
            np.linspace(-1.0, -0.4, 25), 1200.0, args.repeats
    one, single = _time(lambda: crash_stop(SHIP), repeats)
    m = single.metrics
    print(f"one crash stop of {SHIP} (IMO test, {m.attrs['t_final']:.0f} s, dt "
          f"{m.attrs['dt']:g} s): {one * 1e3:.1f} ms; track reach "
          f"{float(m['track_reach']) / float(m['length']):.3f} L, head reach "
          f"{float(m['head_reach']) / float(m['length']):.3f} L")
    n = speeds.size * orders.size
    batch, result = _time(lambda: crash_stop(SHIP, speed=speeds, order=orders,
                                             t_final=t_final, record_dt=10.0), repeats)
    done = int(result.metrics["complete"].sum())
    print(f"{n} crash stops in one batch ({speeds.size} speeds x {orders.size} orders, "
          f"{t_final:.0f} s each): {batch:.2f} s (median of {repeats}), "
          f"{batch / n * 1e3:.2f} ms per run; {done} of {n} dead in the water within "
          f"t_final")


if __name__ == "__main__":
    main()
