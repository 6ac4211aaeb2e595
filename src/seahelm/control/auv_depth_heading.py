"""Depth and heading autopilots of a torpedo-shaped AUV (the REMUS 100), after Fossen (2021).

Per controller sample (period h); the defaults are Fossen's REMUS 100 example (MSS/PVS
``remus100.depthHeadingAutopilot``).

Depth, by successive loop closure (Fossen 2021, §16.x): a first-order low-pass of the depth
command, a PI law for the wanted pitch, and a PID pitch law with heave-velocity feedback on
the stern planes::

    z_d ← e^{−h ω_z} z_d + (1 − e^{−h ω_z}) z_ref
    θ_d = K_pz ((z − z_d) + z_I / T_z)
    δ_s = K_pθ wrap(θ − θ_d) + K_dθ q + K_iθ θ_I + K_w w        (stern-plane command)
    z_I ← z_I + h (z − z_d),  θ_I ← θ_I + h wrap(θ − θ_d)

(the published law computes −δ_s and hands its negative to the stern planes; this is that.)

Heading, by integral sliding-mode control on a Nomoto model (T ṙ + r = K δ) with a
third-order reference model (ψ_d, r_d, a_d) (Fossen 2021, eq. 16.479 as cited by PVS)::

    ẽ = wrap(ψ − ψ_d), ė = r − r_d
    σ = ė + 2λ ẽ + λ² e_I,  r_r = r_d − 2λ ẽ − λ² e_I,  ṙ_r = a_d − 2λ ė − λ² ẽ
    δ_r = (T ṙ_r + r_r − K_d σ − K_σ sat(σ/φ_b)) / K
    e_I ← e_I + h ẽ; reference model as in :mod:`seahelm.control.thrust_heading` (wrapped)

The propeller command is the reference ``propeller_speed`` [rad/s]. The fin commands are not
limited here (the fins saturate in the model). z_d and ψ_d start at the measured depth and
heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param, signal_indices
from .base import Controller, wrap_pi
from .heading_reference import heading_reference_init, heading_reference_step

__all__ = ["AuvDepthHeadingParams", "AUV_DEPTH_HEADING"]


@dataclass(frozen=True, kw_only=True)
class AuvDepthHeadingParams(Params):
    """Gains of the AUV depth and heading autopilots (defaults: Fossen's REMUS 100)."""

    depth_filter_frequency: float = param(0.02, unit="rad/s", symbol="ω_z", low=0.0,
                                          low_inclusive=False, doc="depth-command low-pass")
    depth_gain: float = param(0.1, unit="rad/m", symbol="K_pz", low=0.0,
                              doc="wanted pitch per depth error")
    depth_integral_time: float = param(100.0, unit="s", symbol="T_z", low=0.0,
                                       low_inclusive=False, doc="depth integral time")
    pitch_kp: float = param(5.0, unit="-", symbol="K_pθ", low=0.0, doc="pitch proportional gain")
    pitch_kd: float = param(2.0, unit="s", symbol="K_dθ", low=0.0, doc="pitch-rate gain")
    pitch_ki: float = param(0.3, unit="1/s", symbol="K_iθ", low=0.0, doc="pitch integral gain")
    heave_gain: float = param(5.0, unit="s/m", symbol="K_w", low=0.0,
                              doc="heave-velocity feedback")
    nomoto_gain: float = param(0.25, unit="1/s", symbol="K", low=0.0, low_inclusive=False,
                               doc="Nomoto gain of the design model (r_max/δ_max)")
    nomoto_time_constant: float = param(1.0, unit="s", symbol="T", low=0.0, low_inclusive=False,
                                        doc="Nomoto time constant of the design model")
    smc_lambda: float = param(0.1, unit="1/s", symbol="λ", low=0.0, low_inclusive=False,
                              doc="sliding-surface bandwidth")
    smc_boundary: float = param(0.1, unit="rad/s", symbol="φ_b", low=0.0, low_inclusive=False,
                                doc="boundary-layer thickness")
    smc_kd: float = param(0.5, unit="-", symbol="K_d", low=0.0, doc="sliding-surface gain")
    smc_switching_gain: float = param(0.05, unit="rad/s", symbol="K_σ", low=0.0,
                                      doc="switching gain")
    reference_frequency: float = param(0.1, unit="rad/s", symbol="ω_d", low=0.0,
                                       low_inclusive=False, doc="heading reference model")
    reference_damping: float = param(1.0, unit="-", symbol="ζ_d", low=0.0, low_inclusive=False,
                                     doc="heading reference-model damping")
    max_yaw_rate: float = param(math.radians(5.0), unit="rad/s", symbol="r_max", low=0.0,
                                low_inclusive=False, doc="reference-model yaw-rate limit")


MEASUREMENTS: tuple[str, ...] = ("depth", "pitch", "heading", "heave_speed", "pitch_rate",
                                 "yaw_rate")
REFERENCES: tuple[str, ...] = ("depth", "heading", "propeller_speed")
COMMANDS: tuple[str, ...] = ("propeller_speed_command", "rudder_command", "stern_plane_command")
STATES: tuple[str, ...] = ("filtered_depth", "depth_integral", "pitch_integral",
                           "heading_error_integral", "desired_heading", "desired_yaw_rate",
                           "desired_yaw_acceleration")
OUTPUTS: tuple[str, ...] = ("desired_pitch",)

_M = signal_indices(MEASUREMENTS)
_R = signal_indices(REFERENCES)
_C = signal_indices(COMMANDS)
_S = signal_indices(STATES)
_O = signal_indices(OUTPUTS)


@njit(cache=True)
def auv_depth_heading_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_S.filtered_depth] = y[_M.depth]
    cs[_S.depth_integral] = 0.0
    cs[_S.pitch_integral] = 0.0
    cs[_S.heading_error_integral] = 0.0
    heading_reference_init(cs, _S.desired_heading, _S.desired_yaw_rate,
                           _S.desired_yaw_acceleration, y[_M.heading])


@njit(cache=True)
def auv_depth_heading_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    # depth: low-pass command, PI for the wanted pitch, PID pitch law on the stern planes
    f = math.exp(-dt * p.depth_filter_frequency)
    zd = f * cs[_S.filtered_depth] + (1.0 - f) * ref[_R.depth]
    cs[_S.filtered_depth] = zd
    ez = y[_M.depth] - zd
    theta_d = p.depth_gain * (ez + cs[_S.depth_integral] / p.depth_integral_time)
    eth = wrap_pi(y[_M.pitch] - theta_d)
    stern = (p.pitch_kp * eth + p.pitch_kd * y[_M.pitch_rate] + p.pitch_ki * cs[_S.pitch_integral]
             + p.heave_gain * y[_M.heave_speed])
    cs[_S.depth_integral] += dt * ez
    cs[_S.pitch_integral] += dt * eth
    # heading: integral SMC with a third-order reference model
    lam = p.smc_lambda
    psi_d = cs[_S.desired_heading]
    r_d = cs[_S.desired_yaw_rate]
    a_d = cs[_S.desired_yaw_acceleration]
    e = wrap_pi(y[_M.heading] - psi_d)
    er = y[_M.yaw_rate] - r_d
    ei = cs[_S.heading_error_integral]
    rr_dot = a_d - 2.0 * lam * er - lam * lam * e
    rr = r_d - 2.0 * lam * e - lam * lam * ei
    sigma = er + 2.0 * lam * e + lam * lam * ei
    s = sigma / p.smc_boundary
    s = -1.0 if s < -1.0 else (1.0 if s > 1.0 else s)
    rudder = (p.nomoto_time_constant * rr_dot + rr - p.smc_kd * sigma
              - p.smc_switching_gain * s) / p.nomoto_gain
    cs[_S.heading_error_integral] = ei + dt * e
    heading_reference_step(cs, _S.desired_heading, _S.desired_yaw_rate,
                           _S.desired_yaw_acceleration, ref[_R.heading], p.reference_frequency,
                           p.reference_damping, p.max_yaw_rate, dt)
    cmd[_C.propeller_speed_command] = ref[_R.propeller_speed]
    cmd[_C.rudder_command] = rudder
    cmd[_C.stern_plane_command] = stern
    cmd[len(COMMANDS) + _O.desired_pitch] = theta_d


AUV_DEPTH_HEADING = Controller(
    name="auv-depth-heading",
    description="AUV depth (successive loop closure, stern planes) and heading (integral SMC, "
    "rudder) autopilots with reference models (Fossen 2021; REMUS 100 example)",
    params_type=AuvDepthHeadingParams,
    state_labels=STATES,
    state_units=("m", "m·s", "rad·s", "rad·s", "rad", "rad/s", "rad/s²"),
    reference_labels=REFERENCES,
    reference_units=("m", "rad", "rad/s"),
    command_labels=COMMANDS,
    command_units=("rad/s", "rad", "rad"),
    init=auv_depth_heading_init,
    step=auv_depth_heading_step,
    measurement_labels=MEASUREMENTS,
    output_labels=OUTPUTS,
    output_units=("rad",),
)
