"""Design in python-control, simulate batched in seahelm: the Mariner's LQ-integral autopilot.

1. seahelm linearises the Mariner (nonlinear model and its steering gear) at its straight run
   and hands the linear model to python-control with its signal names;
2. python-control designs three LQ-integral heading autopilots (``control.lqr``, Bryson's rule
   at three allowed heading errors) as named state-space controllers (inputs
   ``heading_error``, ``yaw_rate``, ``sway_speed``; output ``rudder_command``) and predicts
   their course changes on the linear model, sampled at the controller period;
3. seahelm wraps the controllers (:func:`seahelm.control.state_space.state_space_controller`)
   and runs the three designs and two course changes as one batch on the nonlinear Mariner.

Run: ``python examples/python_control_roundtrip.py``. It prints, per design, the overshoot and
the 2 % settling time of python-control's linear prediction and of seahelm's nonlinear batch,
and the largest difference of the two headings.
"""

from __future__ import annotations

import math
import time

import control as ct
import numpy as np

from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.analysis.equilibria.linearisation import linearize
from seahelm.control.state_space import state_space_controller
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate

STEPS = (math.radians(1.0), math.radians(10.0))  # course changes [rad]
DT, TF = 0.5, 400.0  # controller period, duration [s]

# 1. the linear model, named, in python-control
ship = get_ship("mariner-nonlinear")
lin = linearize(ship)  # ship + steering gear: input rudder_command
plant = lin.select(states=[s for s in lin.state_labels if s not in ("north", "east")],
                   outputs=["heading", "yaw_rate", "sway_speed"]).to_control()
print(f"linearised {lin.name}: inputs {plant.input_labels}, outputs {plant.output_labels}")

# 2. LQ-integral designs in python-control: states (∫ψ̃, ψ̃, v, r) of the bare ship's block
bare = linearize(ship, actuator=False).select(states=["sway_speed", "yaw_rate"],
                                              inputs=["rudder_angle"])
A = np.zeros((4, 4))
A[0, 1] = 1.0
A[1, 3] = 1.0
A[2:, 2:] = bare.A
B = np.concatenate([[0.0, 0.0], bare.B[:, 0]])[:, None]
designs = {}
for allowed_deg in (5.0, 10.0, 20.0):
    e = math.radians(allowed_deg)
    k, _, _ = ct.lqr(A, B, np.diag([1 / (100 * e) ** 2, 1 / e ** 2, 0, 0]),
                     [[1 / ship.max_rudder ** 2]])
    ki, kpsi, kv, kr = np.asarray(k)[0]
    # δ_c = k_i ∫e + k_ψ e − k_v v − k_r r with e = ψ* − ψ: one state, three named inputs
    designs[allowed_deg] = ct.ss([[0.0]], [[1.0, 0.0, 0.0]], [[ki]], [[kpsi, -kr, -kv]],
                                 inputs=["heading_error", "yaw_rate", "sway_speed"],
                                 outputs="rudder_command", name=f"lq{allowed_deg:g}")

# the linear prediction: the plant sampled by zero-order hold, the controller by Tustin
t = np.arange(0.0, TF + DT / 2, DT)
error = ct.summing_junction(inputs=["heading_reference", "-heading"], outputs="heading_error",
                            dt=DT)
predicted = {}
for name, c in designs.items():
    loop = ct.interconnect([plant.sample(DT), c.sample(DT, method="tustin"), error],
                           inputs="heading_reference", outputs="heading")
    predicted[name] = ct.forced_response(loop, T=t, U=np.ones(t.size)).outputs  # per radian

# 3. seahelm: one controller (one compilation), a design per run, the nonlinear ship
ctl = state_space_controller(designs[5.0], DT, method="tustin")
# the linear controller works in deviations from the straight run it was designed at: its
# command is relative to the rudder that holds the Mariner straight (δ₀ = −1.1°, its
# single-screw bias) and its sway input to the drift there (v₀ = 0.009 m/s): the operating
# point, as output_offset u₀ and input_offset w₀
start = approach_state(ship, trim=True)
rudder0 = start.inputs["rudder_angle"]
w0 = [0.0, 0.0, lin.y0[lin.output_labels.index("sway_speed")]]
params = [ctl.params_for(c, input_offset=w0, output_offset=[rudder0]) for c in designs.values()]
runs = [(step, name, p) for step in STEPS for name, p in zip(designs, params)]
reference = np.array([[[step]] for step, _, _ in runs])  # (runs, 1, channels)
clock = time.perf_counter()
res = simulate(ship=ship, x0=start.state, actuator_x0=[rudder0], t_final=TF, dt=0.1,
               controller=ctl, controller_params=[p for _, _, p in runs], record_every=5,
               reference=reference)
wall = time.perf_counter() - clock
assert res.ok.all(), res.messages()
print(f"seahelm: {len(runs)} runs (3 designs x 2 course changes) in one batch on the nonlinear "
      f"Mariner: {wall:.2f} s\n  controller '{ctl.name}': {ctl.description}")


def overshoot_and_settling(psi: np.ndarray, step: float) -> tuple[float, float]:
    over = max(0.0, (psi.max() - step) / step * 100.0)
    outside = np.nonzero(np.abs(psi - step) > 0.02 * step)[0]
    return over, (float(t[outside[-1] + 1]) if outside[-1] + 1 < t.size else math.inf) \
        if outside.size else 0.0


print(f"{'course change, design':30} {'python-control (linear)':>24} {'seahelm (nonlinear)':>22}"
      f" {'max |Δψ|':>24}")
for i, (step, name, _) in enumerate(runs):
    psi, lin_psi = res["heading"][i], step * predicted[name]
    o_lin, s_lin = overshoot_and_settling(lin_psi, step)
    o_nl, s_nl = overshoot_and_settling(psi, step)
    diff = np.abs(psi - lin_psi).max()
    print(f"{math.degrees(step):4g} deg, LQ {name:4g} deg{'':12} {o_lin:7.2f} % {s_lin:7.1f} s "
          f"{o_nl:9.2f} % {s_nl:7.1f} s {100 * diff / step:11.3g} % of the step")
