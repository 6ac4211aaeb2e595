"""
Shallow water at a fixed propeller rps: the speed falls
=======================================================

The propeller turns at the rps of the deep-water test speed; the straight-run speed is found
at each water depth h (``straight_run_speed``). Seahelm's tanker is estimated from the
particulars of Fossen's MSS ``tanker.m`` (Van Berlekom & Goddard 1972: L 304.8 m, B 47.17 m,
T 18.46 m, ∇ 220 000 m³, 8.23 m/s); the KVLCC2 is the captive-test model at full scale. The
crosses are MSS's tanker at 80 rpm: 8.23 and 6.63 m/s (deep, h/T = 1.2) as quoted in issue 45,
between them the same model's equations evaluated at h/T = 3, 2, 1.5.
"""

import math
import warnings

import matplotlib.pyplot as plt
import numpy as np

from seahelm.analysis.equilibria.equilibrium import straight_run_speed
from seahelm.errors import ValidityRangeWarning
from seahelm.ships import get_ship
from seahelm.ships.estimate import Design, estimate_ship
from seahelm.vessels.mmg_four_quadrant import self_propulsion_rps

tanker = estimate_ship(Design(name="tanker", length=304.8, beam=47.17, draft=18.46,
                              block_coefficient=0.83, speed=8.23, displacement=220000.0))
ships = {"tanker (estimated)": tanker, "KVLCC2 (captive model)": get_ship("kvlcc2-full")}
ratios = np.linspace(1.2, 6.0, 49)

fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
for label, ship in ships.items():
    rps = self_propulsion_rps(ship.params, ship.params.approach_speed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)
        speeds = [float(straight_run_speed(ship.at_depth(r * ship.particulars.draft).params,
                                           rps, model=ship.model)) for r in ratios]
    line, = ax.plot(ratios, speeds, label=f"{label}, {rps * 60:.0f} rpm")
    ax.axhline(ship.params.approach_speed, color=line.get_color(), ls=":", lw=1)
    print(f"{label}: " + ", ".join(f"h/T {r:g} {u:.2f} m/s" for r, u in zip(ratios, speeds)
                                   if any(math.isclose(r, x) for x in (1.2, 1.5, 2.0, 3.0))))
ax.plot([1.2, 1.5, 2.0, 3.0], [6.63, 7.45, 7.81, 8.01], "kx", label="MSS tanker.m, 80 rpm")
ax.set_xlabel("h/T (dotted: the deep-water speed)")
ax.set_ylabel("straight-run speed at fixed rps [m/s]")
ax.grid(alpha=0.3)
ax.legend()
ax.set_title("Shallow water at a fixed propeller rps")
