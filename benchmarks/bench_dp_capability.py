"""DP capability level 3: the closed-loop batch in process vs on 1 and 2 local Dask workers.

``level3_capability("supply", ...)`` (seahelm.analysis.dp.level3): failure cases ×
directions × wind speeds as one batch of the dp-pid closed loop (the constrained allocation QP
in the loop at every control step) under level 1's mean loads, ``--duration`` s at 0.5 s.
Timed end to end, medians of ``--repeats``:

* ``in process``: ``workers=None`` (the compiled engine, a thread per core);
* ``1 worker``, ``2 workers``: ``workers=N``, chunks on a local Dask cluster of N processes,
  the cluster's start-up included (each call starts its own: what ``seahelm dp capability
  --workers N`` costs a user); printed with the in-process time's ratio.

The issue's grid (36 directions × 12 winds × 7 cases of the supply vessel, 30 min each:
3,024 runs) is ``--headings 36 --winds 12 --duration 1800``; the target is ≤ 10 min on 2
cores. On a machine shared with other jobs the figures move by tens of per cent.

    python benchmarks/bench_dp_capability.py [--headings 12] [--winds 12] [--duration 600]
        [--repeats 1] [--no-dask] [--quick]

``--quick`` (the test suite's smoke run): 2 directions, 1 wind, intact only, 60 s, no Dask.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from seahelm.analysis.dp.level3 import level3_capability


def _time(kw: dict, workers: int | None, repeats: int) -> tuple[float, object]:
    times, res = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = level3_capability("supply", workers=workers, **kw)
        times.append(time.perf_counter() - t0)
    return statistics.median(times), res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--headings", type=int, default=12)
    ap.add_argument("--winds", type=int, default=12,
                    help="wind speeds, 4 to 32.6 m/s (the Beaufort table's end)")
    ap.add_argument("--duration", type=float, default=600.0, help="[s] per run")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--no-dask", action="store_true", help="in process only")
    ap.add_argument("--quick", action="store_true",
                    help="smoke run (the test suite's): 2 x 1 x intact, 60 s, no dask")
    args = ap.parse_args()
    failures = "each"
    if args.quick:
        args.headings, args.winds, args.duration, args.repeats = 2, 1, 60.0, 1
        args.no_dask, failures = True, "none"
    winds = [10.0] if args.winds == 1 else list(np.linspace(4.0, 32.6, args.winds))
    kw = dict(headings=args.headings, wind_speeds=winds, failures=failures,
              duration=args.duration, dt=0.5)
    level3_capability("supply", **{**kw, "headings": 1, "wind_speeds": [10.0],
                                   "failures": "none", "duration": 10.0})  # (the kernel)
    here, res = _time(kw, None, args.repeats)
    n_runs = len(res.cases) * len(res.directions) * len(res.wind_speeds)
    print(f"level 3, supply: {len(res.cases)} cases x {len(res.directions)} directions x "
          f"{len(res.wind_speeds)} winds = {n_runs} runs of {args.duration:g} s at 0.5 s")
    print(f"  in process : {here:8.2f} s  ({n_runs / here:.1f} runs/s)")
    if not args.no_dask:
        for n in (1, 2):
            there, other = _time(kw, n, args.repeats)
            same = bool(np.array_equal(other.held, res.held))
            print(f"  {n} worker{'s' if n > 1 else ' '}  : {there:8.2f} s  "
                  f"({here / there:.2f} x in process; same held grid: {same})")


if __name__ == "__main__":
    main()
