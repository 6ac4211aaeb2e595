"""
Your own ship from its main particulars, in deep and shallow water
==================================================================

A 120 m general cargo ship known only by L, B, T, C_b and its speed: ``seahelm ship estimate``
builds its MMG model (every coefficient from a published regression, with its source), and
the 35° turning circle is run in deep water and at 10 m depth (h/T = 1.43). The same in the
shell::

    seahelm ship estimate --length 120 --beam 18 --draft 7 --cb 0.70 --speed 6.5 -o my.toml
    seahelm imo my.toml
    seahelm maneuver turning --ship my.toml --depth 10
"""

import math

import matplotlib.pyplot as plt

from seahelm.analysis.maneuvers import turning_circle
from seahelm.ships.estimate import Design, estimate_ship

ship = estimate_ship(Design(name="cargo120", length=120, beam=18, draft=7,
                            block_coefficient=0.70, speed=6.5))
print(ship.source_of("Y_v"))
print(ship.source_of("R_0"))

# %%
# One batch: the deep-water ship and the same ship at 10 m, 35° rudder to starboard.
result = turning_circle([ship, ship.at_depth(10.0)], math.radians(35.0), sides=1)
for name, td in zip(("deep water", "h = 10 m"), result.metrics["tactical_diameter"].values):
    print(f"{name}: tactical diameter {td / ship.length:.2f} L")

fig, ax = plt.subplots(figsize=(6, 5), layout="constrained")
for i, label in enumerate(("deep water", "h = 10 m (h/T = 1.43)")):
    run = result.runs.isel(ship=i)
    ax.plot(run["east"] / ship.length, run["north"] / ship.length, label=label)
ax.set_xlabel("transfer y/L (east)")
ax.set_ylabel("advance x/L (north)")
ax.set_aspect("equal")
ax.grid(alpha=0.3)
ax.legend()
ax.set_title("cargo120 estimated from L, B, T, C_b: 35° turning circle")
