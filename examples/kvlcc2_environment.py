"""KVLCC2 (L7 model) 35° turning circles in calm water, in wind and waves, and in a current.

Three batches of the same manoeuvre (both sides) from the calm-water straight approach; the
weather acts from the rudder order on and its loads follow each run's live heading and speed:

* calm water;
* wind and waves from the starboard beam (east): Blendermann's coefficients of a loaded tanker,
  3 m/s (20 m/s at full scale), and Lvov's mean loads of regular waves h3% = 0.066 m
  (3 m at full scale), λ = 2.6 m;
* a uniform current of 0.1 m/s setting east: the track is the calm-water track carried by the
  current (Fossen 2021, Property 10.1).

Prints advance, transfer and tactical diameter (over ground, in ship lengths) and writes
``kvlcc2_environment.png`` (the tracks) into the directory given (default: the current one).

    python examples/kvlcc2_environment.py [OUT_DIR]
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

from seahelm.analysis.maneuvers import turning_circle
from seahelm.environment.loads import Conditions, environment, ship_load_params
from seahelm.ships import get_ship
from seahelm.errors import ValidityRangeWarning

SHIP = get_ship("kvlcc2-l7")  # its particulars give the windage and hull data


def weather() -> Conditions:
    """Wind 3 m/s and regular waves h3% = 0.066 m, both from the east."""
    env = environment(wind="blendermann", waves="lvov")
    with warnings.catch_warnings():
        # the KVLCC2's C_b 0.81 is just above the 0.6-0.8 of Lvov's eq. (5)-(7)
        warnings.simplefilter("ignore", ValidityRangeWarning)
        params = ship_load_params(SHIP, env, wind_speed=3.0, wind_direction=math.radians(90.0),
                                  wave_height=0.066, wave_length=2.6,
                                  wave_direction=math.radians(90.0))
    return Conditions(env, params)


def main(out: Path) -> None:
    cases = {
        "calm water": None,
        "wind 3 m/s + waves from E": weather(),
        "current 0.1 m/s setting E": Conditions(current_speed=0.1,
                                                current_direction=math.radians(90.0)),
    }
    results = {name: turning_circle(SHIP, math.radians(35.0), speed=1.179, t_final=120.0,
                                    conditions=c) for name, c in cases.items()}
    print(f"{'case':28s} {'side':>5s} {'advance':>8s} {'transfer':>9s} {'tactical':>9s}  [L]")
    for name, res in results.items():
        m = res.metrics
        for k, side in enumerate(m.side.values):
            L = float(m.length[k])
            print(f"{name:28s} {('stbd' if side > 0 else 'port'):>5s} "
                  f"{float(m.advance[k]) / L:8.3f} {float(m.transfer[k]) / L:9.3f} "
                  f"{float(m.tactical_diameter[k]) / L:9.3f}")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8.0, 4.4), layout="constrained")
    for (name, res), style in zip(results.items(), ("-", "--", ":")):
        runs = res.runs
        L = float(res.metrics.length[0])
        for k in range(runs.sizes["side"]):
            ax.plot(runs.east.isel(side=k) / L, runs.north.isel(side=k) / L, style, color="C0"
                    if "calm" in name else ("C1" if "wind" in name else "C2"),
                    label=(name + (" (drifts W)" if "wind" in name else " (drifts E)"
                                   if "current" in name else "")) if k == 0 else None)
    ax.set_xlabel("east / L")
    ax.set_ylabel("north / L")
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title("KVLCC2 L7, 35° turning circles to both sides from the same approach "
                 "(heading north)", fontsize=10)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "kvlcc2_environment.png"
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
