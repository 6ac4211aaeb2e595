"""LQ-integral heading autopilot: state feedback on heading error, its integral, yaw rate, sway.

The command (a rudder angle [rad]) is the linear-quadratic optimal state feedback of the
steering model augmented with the integral of the heading error (Fossen 2021, §15.3.3
"LQ optimal control with integral action")::

    e   = wrap(ψ* − ψ)
    δ_c = sat(k_i ∫e dt + k_ψ e − k_r (r − r*) − k_v v, δ_max)

with the gains of :func:`seahelm.control.autopilot_design.lq_heading` (k_v = 0 for a model
without sway, e.g. Nomoto's). ``lq-heading-rps`` also holds a constant propeller rps (the
self-propulsion rps of the straight run it was designed at), for models with rudder and
propeller inputs (MMG), as ``pid-heading-rps`` does for the PID. Anti-windup by conditional integration as in
:mod:`seahelm.control.pid`. Sign convention of :mod:`seahelm.vessels.base`: positive rudder →
positive yaw rate.

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §15.3 (LQ with integral action).
Åström, K. J., Hägglund, T. (2006). Advanced PID Control, §3.5 (anti-windup).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param, signal_indices
from .base import Controller, wrap_pi
from .held_rps import with_held_rps
from .pid import pid_heading_init, saturate_integrating

__all__ = ["LQHeadingParams", "LQHeadingRpsParams", "LQ_HEADING", "LQ_HEADING_RPS"]


@dataclass(frozen=True, kw_only=True)
class LQHeadingParams(Params):
    """Gains of the LQ-integral heading autopilot."""

    k_integral: float = param(0.0, unit="1/s", symbol="k_i", doc="gain on ∫e dt")
    k_heading: float = param(1.0, unit="rad/rad", symbol="k_ψ", doc="gain on the heading error")
    k_yaw_rate: float = param(0.0, unit="s", symbol="k_r", doc="gain on the yaw rate")
    k_sway: float = param(0.0, unit="rad·s/m", symbol="k_v", doc="gain on the sway speed")
    max_command: float = param(math.radians(35.0), unit="rad", symbol="δ_max", low=0.0,
                               low_inclusive=False, doc="command saturation (anti-windup)")


MEASUREMENTS: tuple[str, ...] = ("heading", "yaw_rate", "sway_speed")
REFERENCES: tuple[str, ...] = ("heading",)
COMMANDS: tuple[str, ...] = ("rudder_command",)
STATES: tuple[str, ...] = ("heading_error_integral",)

_M = signal_indices(MEASUREMENTS)
_R = signal_indices(REFERENCES + ("yaw_rate",))
_C = signal_indices(COMMANDS)
_S = signal_indices(STATES)


@njit(cache=True)
def lq_heading_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    e = wrap_pi(ref[_R.heading] - y[_M.heading])
    r_ref = ref[_R.yaw_rate] if ref.shape[0] > _R.yaw_rate else 0.0
    integral = cs[_S.heading_error_integral]
    u_unsat = (p.k_integral * integral + p.k_heading * e - p.k_yaw_rate * (y[_M.yaw_rate] - r_ref)
               - p.k_sway * y[_M.sway_speed])
    cmd[_C.rudder_command], cs[_S.heading_error_integral] = saturate_integrating(
        u_unsat, p.max_command, e, integral, dt)


LQ_HEADING = Controller(
    name="lq-heading",
    description="LQ-integral heading autopilot (state feedback on e, ∫e, r, v), conditional-"
    "integration anti-windup",
    params_type=LQHeadingParams,
    state_labels=STATES,
    reference_labels=REFERENCES,
    reference_units=("rad",),
    command_labels=COMMANDS,
    command_units=("rad",),
    state_units=("rad·s",),
    init=pid_heading_init,  # (the same state: ∫e dt = 0)
    step=lq_heading_step,
    measurement_labels=MEASUREMENTS,
)


#: ``lq-heading`` holding a constant propeller rps (:func:`~seahelm.control.held_rps.
#: with_held_rps`), for models with rudder and propeller inputs (MMG).
LQ_HEADING_RPS = with_held_rps(LQ_HEADING, description=(
    "LQ-integral heading autopilot (as 'lq-heading') that also holds a constant propeller "
    "rps, for models with rudder and propeller inputs (MMG)"))
#: Gains of the LQ-integral heading autopilot and the propeller rps it holds.
LQHeadingRpsParams = LQ_HEADING_RPS.params_type
