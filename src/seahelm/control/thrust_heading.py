"""Heading autopilot of a twin-propeller craft (the Otter USV): PID by pole placement, a
third-order reference model, and differential-thrust allocation.

Per controller sample (period h), with the reference-model states (ψ_d, r_d, a_d) and the
integral z (Fossen 2021, §15.3 PID pole placement, §12.1 reference models; the Otter
example of Fossen's MSS/PythonVehicleSimulator)::

    e = wrap(ψ − ψ_d),  ė = r − r_d
    K_p = m ω_n² − k,  K_d = 2 ζ ω_n m − d,  K_i = (ω_n/10) K_p
    τ_N = −K_p e − K_d ė − K_i z
    z ← z + h e
    j_d = ω_d³ wrap(ψ_ref − ψ_d) − (2ζ_d + 1) ω_d² r_d − (2ζ_d + 1) ω_d a_d
    ψ_d ← ψ_d + h r_d,  r_d ← sat(r_d + h a_d, ±r_max),  a_d ← a_d + h j_d

for the yaw model m ṙ + d r + k ψ = τ_N (Otter: m = 41.4 kg·m² with added inertia, d = m/T,
T = 1 s, k = 0). The surge force τ_X is a reference (``surge_force`` [N]). Allocation: the two
propellers at y₁, y₂ with thrust k_pos n|n| give [τ_X, τ_N] = k_pos [[1, 1], [−y₁, −y₂]] u,
u_i = n_i|n_i|, so u = B⁻¹ τ and n_i = sign(u_i) √|u_i| (the square, non-redundant case of the
weighted pseudo-inverse, :func:`seahelm.vessels.six_dof.thrusters.allocate`), then limited to
[n_min, n_max].

The heading error and the reference model's input ψ_ref − ψ_d are wrapped to [−π, π) (the
published autopilot takes both as they are; the two agree while they stay below 180°, and
with LOS guidance, whose ψ_ref jumps by 360° where it wraps, the unwrapped reference model
would turn the craft a full circle). ψ_d starts at the measured heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param, signal_indices
from .base import Controller, wrap_pi
from .heading_reference import heading_reference_init, heading_reference_step

__all__ = ["ThrustHeadingParams", "THRUST_HEADING"]


@dataclass(frozen=True, kw_only=True)
class ThrustHeadingParams(Params):
    """Parameters of the twin-propeller heading autopilot (defaults: the Otter's, Fossen)."""

    yaw_inertia: float = param(41.4, unit="kg·m²", symbol="m", low=0.0, low_inclusive=False,
                               doc="yaw moment of inertia with added inertia (design model)")
    yaw_damping: float = param(41.4, unit="N·m·s", symbol="d", low=0.0,
                               doc="linear yaw damping of the design model (m/T, T = 1 s)")
    yaw_stiffness: float = param(0.0, unit="N·m", symbol="k", low=0.0,
                                 doc="yaw stiffness of the design model")
    natural_frequency: float = param(2.5, unit="rad/s", symbol="ω_n", low=0.0,
                                     low_inclusive=False, doc="closed-loop natural frequency")
    damping_ratio: float = param(1.0, unit="-", symbol="ζ", low=0.0, low_inclusive=False,
                                 doc="closed-loop relative damping")
    reference_frequency: float = param(0.5, unit="rad/s", symbol="ω_d", low=0.0,
                                       low_inclusive=False, doc="reference-model frequency")
    reference_damping: float = param(1.0, unit="-", symbol="ζ_d", low=0.0, low_inclusive=False,
                                     doc="reference-model relative damping")
    max_yaw_rate: float = param(math.radians(10.0), unit="rad/s", symbol="r_max", low=0.0,
                                low_inclusive=False, doc="reference-model yaw-rate limit")
    thrust_coefficient: float = param(0.02216 / 2.0, unit="N·s²", symbol="k_pos", low=0.0,
                                      low_inclusive=False, doc="k_pos of each propeller")
    port_lever: float = param(-0.395, unit="m", symbol="y₁", high=0.0,
                              doc="y of the port propeller (≤ 0)")
    starboard_lever: float = param(0.395, unit="m", symbol="y₂", low=0.0, low_inclusive=False,
                                   doc="y of the starboard propeller (> 0)")
    max_speed: float = param(math.sqrt(0.5 * 24.4 * 9.81 / (0.02216 / 2.0)), unit="rad/s",
                             symbol="n_max", low=0.0, low_inclusive=False,
                             doc="shaft-speed command limit ahead")
    min_speed: float = param(-math.sqrt(0.5 * 13.6 * 9.81 / (0.01289 / 2.0)), unit="rad/s",
                             symbol="n_min", high=0.0,
                             doc="shaft-speed command limit astern")


MEASUREMENTS: tuple[str, ...] = ("heading", "yaw_rate")
REFERENCES: tuple[str, ...] = ("heading", "surge_force")
COMMANDS: tuple[str, ...] = ("propeller_port_speed_command", "propeller_starboard_speed_command")
STATES: tuple[str, ...] = ("heading_error_integral", "desired_heading", "desired_yaw_rate",
                           "desired_yaw_acceleration")
OUTPUTS: tuple[str, ...] = ("yaw_moment_command",)

_M = signal_indices(MEASUREMENTS)
_R = signal_indices(REFERENCES)
_C = signal_indices(COMMANDS)
_S = signal_indices(STATES)
_O = signal_indices(OUTPUTS)


@njit(cache=True)
def thrust_heading_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_S.heading_error_integral] = 0.0
    heading_reference_init(cs, _S.desired_heading, _S.desired_yaw_rate,
                           _S.desired_yaw_acceleration, y[_M.heading])


@njit(cache=True)
def _shaft_speed(u, lo, hi):  # pragma: no cover - compiled
    n = math.sqrt(u) if u >= 0.0 else -math.sqrt(-u)
    return lo if n < lo else (hi if n > hi else n)


@njit(cache=True)
def thrust_heading_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    m = p.yaw_inertia
    wn = p.natural_frequency
    kp = m * wn * wn - p.yaw_stiffness
    kd = 2.0 * p.damping_ratio * wn * m - p.yaw_damping
    ki = 0.1 * wn * kp
    psi_d = cs[_S.desired_heading]
    r_d = cs[_S.desired_yaw_rate]
    a_d = cs[_S.desired_yaw_acceleration]
    e = wrap_pi(y[_M.heading] - psi_d)
    tau_n = -kp * e - kd * (y[_M.yaw_rate] - r_d) - ki * cs[_S.heading_error_integral]
    cs[_S.heading_error_integral] += dt * e
    # third-order reference model, forward Euler, yaw-rate limit
    heading_reference_step(cs, _S.desired_heading, _S.desired_yaw_rate,
                           _S.desired_yaw_acceleration, ref[_R.heading], p.reference_frequency,
                           p.reference_damping, p.max_yaw_rate, dt)
    # allocation: [τ_X, τ_N] = k [[1, 1], [−y₁, −y₂]] (n₁|n₁|, n₂|n₂|)
    k = p.thrust_coefficient
    y1, y2 = p.port_lever, p.starboard_lever
    tau_x = ref[_R.surge_force]
    det = k * k * (y1 - y2)  # det of k [[1, 1], [−y₁, −y₂]] = k² (−y₂ + y₁)
    u1 = (-k * y2 * tau_x - k * tau_n) / det
    u2 = (k * y1 * tau_x + k * tau_n) / det
    cmd[_C.propeller_port_speed_command] = _shaft_speed(u1, p.min_speed, p.max_speed)
    cmd[_C.propeller_starboard_speed_command] = _shaft_speed(u2, p.min_speed, p.max_speed)
    cmd[len(COMMANDS) + _O.yaw_moment_command] = tau_n


THRUST_HEADING = Controller(
    name="thrust-heading",
    description="heading autopilot of a twin-propeller craft (Otter USV): PID by pole placement, "
    "third-order reference model, differential-thrust allocation (Fossen 2021)",
    params_type=ThrustHeadingParams,
    state_labels=STATES,
    state_units=("rad·s", "rad", "rad/s", "rad/s²"),
    reference_labels=REFERENCES,
    reference_units=("rad", "N"),
    command_labels=COMMANDS,
    command_units=("rad/s", "rad/s"),
    init=thrust_heading_init,
    step=thrust_heading_step,
    measurement_labels=MEASUREMENTS,
    output_labels=OUTPUTS,
    output_units=("N·m",),
)
