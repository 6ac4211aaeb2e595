"""KVLCC2 (L7 model) 35° turning circle to starboard: a two-input 3-DOF model wired by name.

The MMG standard model (Yasukawa & Yoshimura 2015) has two inputs, rudder angle and propeller
rps. The rudder servo feeds `rudder_angle`; the open-loop controller's references are named
after what they feed (`rudder_command` for the servo, `propeller_rps` directly). The approach is
a steady straight run at the self-propulsion rps; the turning metrics are measured at the
midship point from the rudder order (IMO MSC.137(76)).

    python examples/kvlcc2_turning.py
"""

from __future__ import annotations

import numpy as np

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.analysis.maneuvers.advance_transfer import turning_metrics
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.simulation.engine import simulate
from seahelm.ships import get_ship
from seahelm.vessels.mmg import KVLCC2_L7_SERVO, MMG

kvlcc2 = get_ship("kvlcc2-l7").params
approach = approach_state(kvlcc2, 1.179)  # steady straight run at 1.179 m/s (Fn 0.142)
result = simulate(
    MMG, kvlcc2, approach.state, t_final=80.0, dt=0.02,
    actuator=RUDDER_SERVO, actuator_params=KVLCC2_L7_SERVO, controller=OPEN_LOOP,
    reference={"rudder_command": np.radians(35.0),
               "propeller_rps": approach.inputs["propeller_rps"]},
)
m = turning_metrics(result.time, result["north"], result["east"], result["heading"])
L = kvlcc2.length
print(f"self-propulsion rps {approach.inputs['propeller_rps']:.4f} 1/s")
print(f"advance {m.advance[0] / L:.3f} L, transfer {m.transfer[0] / L:.3f} L, "
      f"tactical diameter {m.tactical_diameter[0] / L:.3f} L")
print(f"time to 90° {m.time_90[0]:.1f} s, to 180° {m.time_180[0]:.1f} s; "
      f"drift at the end {np.degrees(result['drift_angle'][0, -1]):.1f}°")
