"""PID heading autopilot with heading-error wrapping and anti-windup.

The command (a rudder angle [rad]) is::

    e   = wrap(ψ* − ψ)                      heading error wrapped to [−π, π)
    δ_c = sat(K_p e + K_i ∫e dt + K_d (r* − r), δ_max)

with the derivative taken on the measured yaw rate r (no derivative kick on set-point
steps) and r* = 0 unless the reference supplies a wanted yaw rate. Anti-windup by conditional
integration (clamping): the integral is frozen while the command is saturated and the error
would drive it further into saturation (Åström & Hägglund, *Advanced PID Control*, 2006, §3.5).
The integral still collects the error of an unsaturated course change; with a small K_i it
then unwinds slowly (the demo's 0.02° after 600 s), while a constant disturbance is rejected
exactly (see the tests).

Sign convention as in :mod:`seahelm.vessels.base`: positive rudder → positive yaw rate.

:func:`pid_gains_from_nomoto` gives pole-placement gains for a first-order Nomoto ship
(Fossen, 2021, §15.2): K_p = T ω_n²/K, K_d = (2ζω_n T − 1)/K, K_i = K_p ω_n/10.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from .._validate import check_positive
from ..parameters import Params, param, signal_indices
from .base import Controller, wrap_pi
from .held_rps import with_held_rps

__all__ = ["PIDHeadingParams", "PIDHeadingRpsParams", "PID_HEADING", "PID_HEADING_RPS",
           "pid_gains_from_nomoto"]


@dataclass(frozen=True, kw_only=True)
class PIDHeadingParams(Params):
    """Gains of the PID heading autopilot."""

    kp: float = param(1.0, unit="rad/rad", symbol="K_p", low=0.0, doc="proportional gain")
    ki: float = param(0.0, unit="1/s", symbol="K_i", low=0.0, doc="integral gain")
    kd: float = param(0.0, unit="s", symbol="K_d", low=0.0, doc="derivative gain (on yaw rate)")
    max_command: float = param(math.radians(35.0), unit="rad", symbol="δ_max", low=0.0,
                               low_inclusive=False, doc="command saturation (anti-windup)")


MEASUREMENTS: tuple[str, ...] = ("heading", "yaw_rate")
REFERENCES: tuple[str, ...] = ("heading",)
COMMANDS: tuple[str, ...] = ("rudder_command",)
STATES: tuple[str, ...] = ("heading_error_integral",)

_M = signal_indices(MEASUREMENTS)
# the declared reference, then an optional trailing wanted yaw rate r* (read only if given)
_R = signal_indices(REFERENCES + ("yaw_rate",))
_C = signal_indices(COMMANDS)
_S = signal_indices(STATES)


@njit(cache=True)
def pid_heading_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_S.heading_error_integral] = 0.0


@njit(cache=True)
def pid_heading_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    kp = p.kp
    ki = p.ki
    kd = p.kd
    umax = p.max_command
    e = wrap_pi(ref[_R.heading] - y[_M.heading])
    r_ref = ref[_R.yaw_rate] if ref.shape[0] > _R.yaw_rate else 0.0
    integral = cs[_S.heading_error_integral]
    u_unsat = kp * e + ki * integral + kd * (r_ref - y[_M.yaw_rate])
    cmd[_C.rudder_command], cs[_S.heading_error_integral] = saturate_integrating(
        u_unsat, umax, e, integral, dt)


@njit(cache=True)
def saturate_integrating(u_unsat, umax, error, integral, dt):  # pragma: no cover - compiled
    """The command saturated to ±``umax`` and the error integral after conditional integration.

    Anti-windup by conditional integration (Åström & Hägglund 2006, §3.5): the integral takes
    ``error`` dt unless the command is saturated and the error pushes it further out. Used by
    every heading autopilot with an integral of the heading error (``pid-heading``,
    ``lq-heading``).

    Parameters
    ----------
    u_unsat : float
        The unsaturated command.
    umax : float
        The saturation (> 0), in the command's unit.
    error : float
        The error being integrated.
    integral : float
        Its integral so far.
    dt : float
        The controller's step [s].

    Returns
    -------
    (float, float)
        The command min(max(u_unsat, −umax), umax) and the integral to keep.
    """
    u = min(max(u_unsat, -umax), umax)
    if u == u_unsat or error * u_unsat < 0.0:
        integral = integral + error * dt
    return u, integral


PID_HEADING = Controller(
    name="pid-heading",
    description="PID heading autopilot, wrapped heading error, conditional-integration anti-windup",
    params_type=PIDHeadingParams,
    state_labels=STATES,
    reference_labels=REFERENCES,
    reference_units=("rad",),
    command_labels=COMMANDS,
    command_units=("rad",),
    state_units=("rad·s",),
    init=pid_heading_init,
    step=pid_heading_step,
    measurement_labels=MEASUREMENTS,
)


#: ``pid-heading`` holding a constant propeller rps (:func:`~seahelm.control.held_rps.
#: with_held_rps`), for models with rudder and propeller inputs (MMG).
PID_HEADING_RPS = with_held_rps(PID_HEADING, description=(
    "PID heading autopilot (as 'pid-heading') that also holds a constant propeller rps, for "
    "models with rudder and propeller inputs (MMG)"))
#: Gains of the PID heading autopilot and the propeller rps it holds (``propeller_rps``
#: [1/s]).
PIDHeadingRpsParams = PID_HEADING_RPS.params_type


def pid_gains_from_nomoto(
    gain: float,
    time_constant: float,
    natural_frequency: float,
    damping: float = 0.8,
    *,
    max_command: float = math.radians(35.0),
) -> PIDHeadingParams:
    """Pole-placement PID gains for a first-order Nomoto ship (Fossen, 2021, §15.2).

    Parameters
    ----------
    gain : float
        Nomoto gain K [1/s].
    time_constant : float
        Nomoto time constant T [s].
    natural_frequency : float
        Wanted closed-loop natural frequency ω_n [rad/s].
    damping : float
        Wanted relative damping ζ [-].
    max_command : float, optional
        Saturation of the rudder command [rad] (default 35°).

    Returns
    -------
    PIDHeadingParams
        K_p [-], K_i [1/s], K_d [s] and ``max_command``.
    """
    check_positive("gain", gain, "1/s")
    check_positive("time_constant", time_constant, "s")
    check_positive("natural_frequency", natural_frequency, "rad/s")
    check_positive("damping", damping, "-")
    kp = time_constant * natural_frequency**2 / gain
    kd = max((2.0 * damping * natural_frequency * time_constant - 1.0) / gain, 0.0)
    ki = kp * natural_frequency / 10.0
    return PIDHeadingParams(kp=kp, ki=ki, kd=kd, max_command=max_command)
