"""Baseline steering laws for comparison with the final-state controllers.

The two laws of the introduction of Shushlyapin et al. (2017), from Russian patents, with
"undetermined coefficients" k1, k2, k3, and a PID yaw-rate loop. All three drive a vessel whose
input is the thruster (or rudder) rate dδ/dt, such as :data:`seahelm.vessels.catamaran.CATAMARAN`
with the ``direct`` actuator (command ``thruster_rate_command``); they read the state
z = (V_x, V_y, ω, x, y, K, δ, ...), the heading law also the measurements ``heading`` and
``yaw_rate``, the PID ``yaw_rate``.

``heading-rate-baseline`` — Dorri, Ostretsov & Roshchin (patent RU 2465169, 2012)::

    dδ/dt = k1 (K − K*) + k2 ω − k3 δ

    with K − K* wrapped to [−π, π). The law is implemented as printed: the signs are in the
    coefficients. For the catamaran (positive δ turns to starboard, positive ω) the law is
    stabilising with k1 < 0, k2 < 0, k3 ≥ 0. The defaults k1 = −0.035 1/s, k2 = −1, k3 =
    0.02 1/s place the quasi-static loop (ω ≈ g δ, g ≈ 0.069 1/s for the listing's ship) at
    s² + (k3 − k2 g) s − k1 g = 0, ω_n ≈ 0.05 rad/s, ζ ≈ 0.9; |k2| must stay below about 1.6
    at a 0.01 s sample period (the same bound as T_u·h of eq. (21), k2 ↔ −J_ω/(T_u h L T_v)).

``drift-thruster-baseline`` — Ostretsov, Klyachko & Pamukhin (patent RU 2483973, 2013)::

    dP/dt = k1 β + k2 ∫β dt − k3 P

    a lateral control force P [N] (bow thruster) from the drift angle β (the paper's
    β = atan2(V_y, V_x)), integrated by the controller at its sample period. The catamaran has
    no bow thruster; the force is produced by turning both thrusters, δ_P = asin(P / 2T_v),
    and the command is the thruster rate u = (δ_P − δ)/T_t. With ``force_output`` = 1 the
    command is P itself (for a vessel with a lateral-force input). For the catamaran the
    steady drift has the opposite sign of the side force (β ≈ −5.2e-6 rad/N · P: the yaw
    moment of the thrusters turns the ship, and the turn sets the drift), so the stabilising
    coefficients are k2 > 0, k1 c + k3 > 0; the defaults k1 = 0, k2 = 1900 N/(rad·s²),
    k3 = 0.14 1/s give ω_n ≈ 0.1 rad/s, ζ ≈ 0.7. The reference is a wanted drift angle β*
    (β − β* enters the law).

``pid-yaw-rate`` — a PID loop on the yaw-rate error e = ω* − ω::

    δ_c = sat(K_p e + K_i ∫e dt + K_d de/dt, δ_max),    u = dδ/dt = (δ_c − δ)/T_t

    with conditional-integration anti-windup and the derivative on the measured yaw rate.
    Note that eq. (21) of the final-state method is itself an integral yaw-rate controller,
    dδ/dt = (ω* − ω) J_ω / (T_u h L T_v cos δ), with its gain scheduled on cos δ.

References
----------
Shushlyapin, E. A., Karapetyan, V. A., Bezuglaya, A. E., Afonina, A. A. (2017), SPIIRAS
Proceedings 4(53), introduction. Åström, K. J., Hägglund, T. (2006). Advanced PID Control, §3.5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param, signal_indices
from ..vessels.catamaran import STATES as CATAMARAN_STATES
from .base import Controller, wrap_pi

__all__ = [
    "HeadingRateBaselineParams",
    "DriftThrusterBaselineParams",
    "PIDYawRateParams",
    "HEADING_RATE_BASELINE",
    "DRIFT_THRUSTER_BASELINE",
    "PID_YAW_RATE",
]


#: The closed-loop state z starts with the catamaran's states; the laws read the thruster angle δ
#: and the velocity (V_x, V_y) from it.
_Z = signal_indices(CATAMARAN_STATES)
_COMMANDS: tuple[str, ...] = ("thruster_rate_command",)
_C = signal_indices(_COMMANDS)


# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class HeadingRateBaselineParams(Params):
    """dδ/dt = k1 (K − K*) + k2 ω − k3 δ (Dorri et al., 2012); signs in the coefficients."""

    k1: float = param(-0.035, unit="1/s", symbol="k1", doc="heading-error coefficient")
    k2: float = param(-1.0, unit="-", symbol="k2", doc="yaw-rate coefficient")
    k3: float = param(0.02, unit="1/s", symbol="k3", doc="thruster-angle coefficient")
    max_angle: float = param(math.radians(89.0), unit="rad", symbol="δ_max", low=0.0,
                             low_inclusive=False, high=math.pi,
                             doc="no turning beyond ±δ_max")


@njit(cache=True)
def heading_rate_baseline_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    pass


_HR_MEASUREMENTS: tuple[str, ...] = ("heading", "yaw_rate")
_HR_REFERENCES: tuple[str, ...] = ("heading",)
_HR_M = signal_indices(_HR_MEASUREMENTS)
_HR_R = signal_indices(_HR_REFERENCES)


@njit(cache=True)
def heading_rate_baseline_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    d = z[_Z.thruster_angle]
    u = (p.k1 * wrap_pi(y[_HR_M.heading] - ref[_HR_R.heading]) + p.k2 * y[_HR_M.yaw_rate]
         - p.k3 * d)
    if (d >= p.max_angle and u > 0.0) or (d <= -p.max_angle and u < 0.0):
        u = 0.0
    cmd[_C.thruster_rate_command] = u


HEADING_RATE_BASELINE = Controller(
    name="heading-rate-baseline",
    description="patent baseline dδ/dt = k1 (K − K*) + k2 ω − k3 δ (Dorri et al., 2012)",
    params_type=HeadingRateBaselineParams,
    state_labels=(),
    reference_labels=_HR_REFERENCES,
    reference_units=("rad",),
    command_labels=_COMMANDS,
    command_units=("rad/s",),
    state_units=(),
    init=heading_rate_baseline_init,
    step=heading_rate_baseline_step,
    measurement_labels=_HR_MEASUREMENTS,
)


# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class DriftThrusterBaselineParams(Params):
    """dP/dt = k1 β + k2 ∫β dt − k3 P (Ostretsov et al., 2013), P realised by the thrusters."""

    k1: float = param(0.0, unit="N/(rad·s)", symbol="k1", doc="drift-angle coefficient")
    k2: float = param(1900.0, unit="N/(rad·s²)", symbol="k2", doc="drift-integral coefficient")
    k3: float = param(0.14, unit="1/s", symbol="k3", doc="force decay coefficient")
    thrust: float = param(20400.0, unit="N", symbol="T_v", low=0.0, low_inclusive=False,
                          doc="thrust of one thruster (P = 2 T_v sin δ)")
    tracking_time: float = param(1.0, unit="s", symbol="T_t", low=0.0, low_inclusive=False,
                                 doc="time constant of the thruster-angle tracking")
    force_output: float = param(0.0, unit="-", low=0.0, high=1.0,
                                doc="1: the command is P [N]; 0: the thruster rate")


_DT_STATES: tuple[str, ...] = ("lateral_force", "drift_angle_integral")
_DT_REFERENCES: tuple[str, ...] = ("drift_angle",)
_DT_S = signal_indices(_DT_STATES)
_DT_R = signal_indices(_DT_REFERENCES)


@njit(cache=True)
def drift_thruster_baseline_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_DT_S.lateral_force] = 0.0  # P
    cs[_DT_S.drift_angle_integral] = 0.0  # ∫β dt


@njit(cache=True)
def drift_thruster_baseline_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    a = z[_Z.surge_speed]
    b = z[_Z.sway_speed_port]
    beta = math.atan2(b, a) if a * a + b * b > 0.0 else 0.0
    beta -= ref[_DT_R.drift_angle]
    P = cs[_DT_S.lateral_force]
    dP = p.k1 * beta + p.k2 * cs[_DT_S.drift_angle_integral] - p.k3 * P
    cs[_DT_S.drift_angle_integral] += beta * dt
    P += dP * dt
    cs[_DT_S.lateral_force] = P
    if p.force_output != 0.0:
        cmd[_C.thruster_rate_command] = P
        return
    s = P / (2.0 * p.thrust)
    s = min(max(s, -1.0), 1.0)
    cmd[_C.thruster_rate_command] = (math.asin(s) - z[_Z.thruster_angle]) / p.tracking_time


DRIFT_THRUSTER_BASELINE = Controller(
    name="drift-thruster-baseline",
    description="patent baseline dP/dt = k1 β + k2 ∫β dt − k3 P (Ostretsov et al., 2013), "
    "P from the azimuth thrusters",
    params_type=DriftThrusterBaselineParams,
    state_labels=_DT_STATES,
    reference_labels=_DT_REFERENCES,
    reference_units=("rad",),
    command_labels=_COMMANDS,
    command_units=("rad/s",),
    state_units=("N", "rad·s"),
    init=drift_thruster_baseline_init,
    step=drift_thruster_baseline_step,
)


# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class PIDYawRateParams(Params):
    """PID on the yaw-rate error; the thruster angle tracks the PID output."""

    kp: float = param(0.5, unit="s", symbol="K_p", low=0.0, doc="proportional gain [rad/(rad/s)]")
    ki: float = param(1.0, unit="-", symbol="K_i", low=0.0, doc="integral gain [rad/rad]")
    kd: float = param(0.0, unit="s²", symbol="K_d", low=0.0, doc="derivative gain (on ω)")
    max_angle: float = param(math.radians(89.0), unit="rad", symbol="δ_max", low=0.0,
                             low_inclusive=False, high=math.pi / 2,
                             doc="thruster-angle saturation (anti-windup)")
    tracking_time: float = param(1.0, unit="s", symbol="T_t", low=0.0, low_inclusive=False,
                                 doc="time constant of the thruster-angle tracking")


_YR_STATES: tuple[str, ...] = ("yaw_rate_error_integral", "previous_yaw_rate")
_YR_MEASUREMENTS: tuple[str, ...] = ("yaw_rate",)
_YR_REFERENCES: tuple[str, ...] = ("yaw_rate",)
_YR_S = signal_indices(_YR_STATES)
_YR_M = signal_indices(_YR_MEASUREMENTS)
_YR_R = signal_indices(_YR_REFERENCES)


@njit(cache=True)
def pid_yaw_rate_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_YR_S.yaw_rate_error_integral] = 0.0  # ∫e dt
    cs[_YR_S.previous_yaw_rate] = y[_YR_M.yaw_rate]  # derivative on measurement


@njit(cache=True)
def pid_yaw_rate_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    w = y[_YR_M.yaw_rate]
    e = ref[_YR_R.yaw_rate] - w
    dw = (w - cs[_YR_S.previous_yaw_rate]) / dt
    cs[_YR_S.previous_yaw_rate] = w
    dc_unsat = p.kp * e + p.ki * cs[_YR_S.yaw_rate_error_integral] - p.kd * dw
    umax = p.max_angle
    dc = min(max(dc_unsat, -umax), umax)
    if dc == dc_unsat or e * dc_unsat < 0.0:
        cs[_YR_S.yaw_rate_error_integral] += e * dt
    cmd[_C.thruster_rate_command] = (dc - z[_Z.thruster_angle]) / p.tracking_time


PID_YAW_RATE = Controller(
    name="pid-yaw-rate",
    description="PID yaw-rate loop with anti-windup; the thruster angle tracks its output",
    params_type=PIDYawRateParams,
    state_labels=_YR_STATES,
    reference_labels=_YR_REFERENCES,
    reference_units=("rad/s",),
    command_labels=_COMMANDS,
    command_units=("rad/s",),
    state_units=("rad", "rad/s"),
    init=pid_yaw_rate_init,
    step=pid_yaw_rate_step,
    measurement_labels=_YR_MEASUREMENTS,
)
