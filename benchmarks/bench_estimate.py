"""A ship from its main particulars: how long the estimate takes, and that the estimated ship
runs at the speed of the catalog MMG ship (the same compiled kernel).

1. ``estimate_ship`` of a 120 m cargo ship (every regression, the B-series fit, Holtrop's
   resistance), in-process, warm: median of ``--repeats`` runs of 20 estimates each; and
   ``seahelm ship estimate ... -o FILE`` end to end as a user runs it (a new interpreter).
2. 1,000 turning circles in one batch (500 rudder angles 20°–35° × both sides, 1 s records)
   of the estimated KVLCC2 L7 against the catalog ``kvlcc2-l7``: the medians and their ratio.

    python benchmarks/bench_estimate.py [--repeats 5] [--quick]

``--quick`` (the test suite's smoke run): 1 repeat of 2 estimates, 10 turning circles.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np

from seahelm.analysis.maneuvers import turning_circle
from seahelm.ships import get_ship
from seahelm.ships.estimate import Design, estimate_ship

CARGO = Design(name="cargo120", length=120, beam=18, draft=7, block_coefficient=0.70, speed=6.5)
L7 = Design(name="kvlcc2-l7-estimated", length=7.0, beam=1.27, draft=0.46,
            block_coefficient=0.8098, displacement=3.27, x_G=0.25, speed=1.179,
            propeller_diameter=0.216, pitch_ratio=0.721, area_ratio=0.431, blades=4,
            rudder_area=0.0539, rudder_span=0.345, max_rudder=math.radians(35.0),
            rudder_rate=math.radians(15.8), rho=1000.0, lcb=3.48)


def _median(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--quick", action="store_true",
                        help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = parser.parse_args()
    per_rep, n_rudders = 20, 500
    if args.quick:
        args.repeats, per_rep, n_rudders = 1, 2, 5
    warnings.simplefilter("ignore")

    estimate_ship(CARGO)  # warm the imports
    per = _median(lambda: [estimate_ship(CARGO) for _ in range(per_rep)],
                  args.repeats) / per_rep
    print(f"estimate_ship (in-process, warm): {per * 1e3:.2f} ms per ship "
          f"(median of {args.repeats} x {per_rep})")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "my.toml")
        cmd = [sys.executable, "-m", "seahelm", "ship", "estimate", "--length", "120", "--beam",
               "18", "--draft", "7", "--cb", "0.7", "--speed", "6.5", "-o", out, "--force"]
        if not args.quick:
            subprocess.run(cmd, check=True, capture_output=True)  # warm the caches
        cli = _median(lambda: subprocess.run(cmd, check=True, capture_output=True),
                      args.repeats)
    print(f"seahelm ship estimate ... -o FILE (new interpreter): {cli:.2f} s "
          f"(median of {args.repeats}; target < 1 s)")

    rudders = np.radians(np.linspace(20.0, 35.0, n_rudders))
    ships = {"catalog kvlcc2-l7": get_ship("kvlcc2-l7"), "estimated L7": estimate_ship(L7)}
    runs = {}
    for name, ship in ships.items():
        def run(ship=ship):
            turning_circle(ship, rudders, sides=(1, -1), t_final=90.0, record_dt=1.0)
        run()  # compile / warm
        runs[name] = run
    samples: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(args.repeats):  # interleaved, so a busy moment hits both
        for name, run in runs.items():
            t0 = time.perf_counter()
            run()
            samples[name].append(time.perf_counter() - t0)
    times = {name: statistics.median(v) for name, v in samples.items()}
    for name, t in times.items():
        print(f"{2 * n_rudders:,} turning circles, {name}: {t:.3f} s (median of "
              f"{args.repeats})")
    ratio = times["estimated L7"] / times["catalog kvlcc2-l7"]
    print(f"estimated / catalog: {ratio:.2f} (same kernel: ~1 expected)")


if __name__ == "__main__":
    main()
