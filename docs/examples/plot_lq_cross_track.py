"""
LQ-integral cross-track control beside integral LOS
====================================================

The Mariner (nonlinear model, its steering gear: 40°, 5°/s) on a straight route due north,
starting 200 m to starboard of it in calm water, and on it in a 1 m/s cross current setting
east. The LQ-integral cross-track controller (:mod:`seahelm.control.lq_cross_track`) is
designed from the Mariner linearised at 7.72 m/s (Bryson's weights 50 m, 20°, 40° of rudder);
ILOS (look-ahead 800 m, κ = U/4) steers the PID heading autopilot (kp 3, kd 60). The same
design in the shell::

    seahelm autopilot tune mariner-nonlinear --design lq-cross-track \\
        --max-cross-track 50 --max-heading-error 20 --out route.toml
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.analysis.equilibria.linearisation import linearize
from seahelm.control.guided import guided
from seahelm.control.lq_cross_track import LQ_CROSS_TRACK, lq_cross_track
from seahelm.control.path_following import ILOS, route_params
from seahelm.control.pid import PID_HEADING
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate

ship = get_ship("mariner-nonlinear")
lin = linearize(ship, actuator=False)
block = lin.select(states=["sway_speed", "yaw_rate"], inputs=["rudder_angle"])
surge = lin.A[lin.state_labels.index("east"), lin.state_labels.index("heading")]
design = lq_cross_track(block.A, block.B[:, 0], block.state_labels, surge, max_cross_track=50.0,
                        max_heading_error=math.radians(20.0), max_rudder=ship.max_rudder)
print("gains:", {k: f"{v:.4g}" for k, v in design.gains.items()})
print("poles [1/s]:", np.round(design.poles, 4))

# %%
# Two runs per controller in one batch each: 200 m off in calm water; on the line in a current.
route = [[0.0, 0.0], [30000.0, 0.0]]
start = approach_state(ship, trim=True)
x0 = np.tile(start.state, (2, 1))
x0[0, ship.model.state_labels.index("east")] = 200.0
current = np.zeros((2, 1, 1))
current[1] = 1.0
ilos = guided(ILOS, PID_HEADING)
controllers = {
    "LQ-integral cross-track": (LQ_CROSS_TRACK, design.params(route)),
    "ILOS + PID": (ilos, ilos.params_type(**route_params(
        route, law=ILOS, lookahead=800.0, kappa=ship.test_speed / 4).as_dict(),
        kp=3.0, ki=0.0, kd=60.0)),
}
results = {name: simulate(ship=ship, x0=x0, actuator_x0=[start.inputs["rudder_angle"]],
                          t_final=2000.0, dt=0.1, controller=ctl, controller_params=params,
                          controller_dt=0.5, record_every=5,
                          disturbance={"current_east": current})
           for name, (ctl, params) in controllers.items()}

fig, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharex=True)
for (name, res), color in zip(results.items(), ("C0", "C1")):
    t = res.time
    for i, case in enumerate(("200 m off, calm water", "on the line, 1 m/s cross current")):
        xte = res["cross_track_error"][i]
        rms = math.sqrt(np.mean(xte ** 2))
        big = np.nonzero(np.abs(xte) > 1.0)[0]
        inside = t[big[-1] + 1] if big.size and big[-1] + 1 < t.size else math.nan
        print(f"{case:34} {name:24} max {np.abs(xte).max():6.1f} m, overshoot "
              f"{max(0.0, -xte.min()) if i == 0 else 0.0:5.1f} m, RMS {rms:5.1f} m, within 1 m "
              f"after {inside:6.1f} s, rudder up to "
              f"{math.degrees(np.abs(res['rudder_angle'][i]).max()):4.1f} deg")
        axes[0, i].plot(t, xte, color=color, label=name)
        axes[1, i].plot(t, np.degrees(res["rudder_angle"][i]), color=color)
        axes[0, i].set_title(case)
axes[0, 0].set_ylabel("cross-track error [m]")
axes[1, 0].set_ylabel("rudder angle [deg]")
for ax in axes[1]:
    ax.set_xlabel("time [s]")
axes[0, 0].legend()
fig.tight_layout()
plt.show()
