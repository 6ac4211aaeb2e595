"""Rudder (or azimuth-thruster) servo: first-order lag with angle and rate limits.

The commanded angle δ_c is saturated to ±δ_max, the servo follows it as a first-order lag with
time constant T_δ, and the rate is clipped to ±δ̇_max::

    δ̇ = clip((sat(δ_c, δ_max) − δ) / T_δ, −δ̇_max, δ̇_max)

This is the usual steering-machine model (Fossen, *Handbook of Marine Craft Hydrodynamics and
Motion Control*, 2nd ed., 2021, §9.4; van Amerongen, 1982). IMO requires hard-over to
hard-over (35° to 30° the other side) within 28 s, i.e. δ̇_max ≈ 2.3 °/s.

``rudder-propeller`` adds the propeller shaft of a 3-DOF ship as the same kind of element: the
commanded shaft speed n_c [1/s] is saturated to ±n_max and followed with time constant T_n,
the shaft acceleration clipped to ±ṅ_max::

    ṅ = clip((sat(n_c, n_max) − n) / T_n, −ṅ_max, ṅ_max)

(a first-order shaft lag with an acceleration limit, Fossen, 2021, §9.4 for the analogous
steering machine). ``direct`` is no actuator at all: the commands are the vessel inputs.

Both servos have a closed-form step (``advance``, :func:`limited_lag_advance`): under a held
command the value ramps at the rate limit, then decays exponentially. The engine takes the
actuator states from it at every stage, so a step is not bounded by the lag (explicit RK4 is
unstable beyond 2.8 T: 0.28 s for the KVLCC2 model's 0.1 s steering-gear lag).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param, signal_indices
from .base import Actuator

__all__ = ["ServoParams", "RUDDER_SERVO", "DIRECT", "DirectParams", "RudderPropellerParams",
           "RUDDER_PROPELLER"]


@dataclass(frozen=True, kw_only=True)
class ServoParams(Params):
    """Parameters of the rudder servo (angles in radians inside)."""

    max_angle: float = param(math.radians(35.0), unit="rad", symbol="δ_max", low=0.0,
                             low_inclusive=False, high=math.pi, doc="angle limit")
    max_rate: float = param(math.radians(2.33), unit="rad/s", symbol="δ̇_max", low=0.0,
                            low_inclusive=False, doc="rate limit")
    time_constant: float = param(1.0, unit="s", symbol="T_δ", low=0.0, low_inclusive=False,
                                 doc="first-order lag time constant")


@njit(cache=True)
def limited_lag_rate(command, value, limit, time_constant, rate_limit):  # pragma: no cover
    """Rate of a first-order lag towards ``command`` saturated to ±``limit``, the rate clipped to
    ±``rate_limit`` (compiled; one channel)."""
    target = min(max(command, -limit), limit)
    rate = (target - value) / time_constant
    return min(max(rate, -rate_limit), rate_limit)


@njit(cache=True)
def limited_lag_advance(command, value, limit, time_constant, rate_limit, h):  # pragma: no cover
    """The value ``h`` seconds on of the limited lag of :func:`limited_lag_rate`, exactly.

    With the target g = sat(command, ±limit) held and the error e = g − value: while
    |e| > δ̇_max T the rate is clipped and the value ramps at ±δ̇_max, for (|e| − δ̇_max T)/δ̇_max
    seconds; within that band the lag decays the error as e·exp(−t/T). Compiled; one channel.
    """
    target = min(max(command, -limit), limit)
    e = target - value
    if e == 0.0 or h <= 0.0:  # on the target (the shaft at constant rps), or no time: as is
        return value
    band = rate_limit * time_constant  # |error| above which the rate is clipped
    if abs(e) > band:
        ramp = (abs(e) - band) / rate_limit  # time at the rate limit
        if h <= ramp:
            return value + math.copysign(rate_limit * h, e)
        e = math.copysign(band, e)
        h = h - ramp
    return target - e * math.exp(-h / time_constant)


@njit(cache=True)
def servo_rhs(t, xa, ca, p, dxa):  # pragma: no cover - compiled
    """δ̇ of the rate- and angle-limited first-order servo, one channel per state."""
    for j in range(xa.shape[0]):
        dxa[j] = limited_lag_rate(ca[j], xa[j], p.max_angle, p.time_constant, p.max_rate)


@njit(cache=True)
def servo_advance(h, xa, ca, p, out):  # pragma: no cover - compiled
    """δ after ``h`` seconds under the held command, in closed form
    (:func:`limited_lag_advance`)."""
    for j in range(xa.shape[0]):
        out[j] = limited_lag_advance(ca[j], xa[j], p.max_angle, p.time_constant, p.max_rate, h)


@njit(cache=True)
def servo_output(xa, ca, p, ya):  # pragma: no cover - compiled
    for j in range(xa.shape[0]):
        ya[j] = xa[j]


RUDDER_SERVO = Actuator(
    name="rudder-servo",
    description="rudder servo: first-order lag with angle and rate limits",
    params_type=ServoParams,
    state_labels=("rudder_angle",),
    state_units=("rad",),
    command_labels=("rudder_command",),
    command_units=("rad",),
    rhs=servo_rhs,
    output=servo_output,
    advance=servo_advance,
    output_labels=("rudder_angle",),
    output_units=("rad",),
)


# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class RudderPropellerParams(ServoParams):
    """Rudder servo (the :class:`ServoParams` fields) plus a first-order propeller-shaft lag.

    The propeller fields have no defaults: they depend on the engine and the ship.
    """

    propeller_time_constant: float = param(unit="s", symbol="T_n", low=0.0, low_inclusive=False,
                                           doc="time constant of the shaft-speed lag")
    max_rps: float = param(unit="1/s", symbol="n_max", low=0.0, low_inclusive=False,
                           doc="shaft-speed limit (ahead and astern)")
    max_rps_rate: float = param(unit="1/s²", symbol="ṅ_max", low=0.0, low_inclusive=False,
                                doc="shaft acceleration limit")


RUDDER_PROPELLER_STATES: tuple[str, ...] = ("rudder_angle", "propeller_rps")
RUDDER_PROPELLER_COMMANDS: tuple[str, ...] = ("rudder_command", "propeller_rps_command")
RUDDER_PROPELLER_OUTPUTS: tuple[str, ...] = ("rudder_angle", "propeller_rps")

_RP_X = signal_indices(RUDDER_PROPELLER_STATES)
_RP_C = signal_indices(RUDDER_PROPELLER_COMMANDS)
_RP_Y = signal_indices(RUDDER_PROPELLER_OUTPUTS)


@njit(cache=True)
def rudder_propeller_rhs(t, xa, ca, p, dxa):  # pragma: no cover - compiled
    """δ̇ of the rudder servo and ṅ of the shaft lag (see the module docstring)."""
    dxa[_RP_X.rudder_angle] = limited_lag_rate(
        ca[_RP_C.rudder_command], xa[_RP_X.rudder_angle], p.max_angle, p.time_constant,
        p.max_rate)
    dxa[_RP_X.propeller_rps] = limited_lag_rate(
        ca[_RP_C.propeller_rps_command], xa[_RP_X.propeller_rps], p.max_rps,
        p.propeller_time_constant, p.max_rps_rate)


@njit(cache=True)
def rudder_propeller_advance(h, xa, ca, p, out):  # pragma: no cover - compiled
    """δ and n after ``h`` seconds under the held commands, in closed form
    (:func:`limited_lag_advance`)."""
    out[_RP_X.rudder_angle] = limited_lag_advance(
        ca[_RP_C.rudder_command], xa[_RP_X.rudder_angle], p.max_angle, p.time_constant,
        p.max_rate, h)
    out[_RP_X.propeller_rps] = limited_lag_advance(
        ca[_RP_C.propeller_rps_command], xa[_RP_X.propeller_rps], p.max_rps,
        p.propeller_time_constant, p.max_rps_rate, h)


@njit(cache=True)
def rudder_propeller_output(xa, ca, p, ya):  # pragma: no cover - compiled
    ya[_RP_Y.rudder_angle] = xa[_RP_X.rudder_angle]
    ya[_RP_Y.propeller_rps] = xa[_RP_X.propeller_rps]


RUDDER_PROPELLER = Actuator(
    name="rudder-propeller",
    description="rudder servo (first-order lag, angle and rate limits) and propeller shaft "
    "(first-order lag, rps and rps-rate limits) of a 3-DOF ship",
    params_type=RudderPropellerParams,
    state_labels=RUDDER_PROPELLER_STATES,
    state_units=("rad", "1/s"),
    command_labels=RUDDER_PROPELLER_COMMANDS,
    command_units=("rad", "1/s"),
    rhs=rudder_propeller_rhs,
    output=rudder_propeller_output,
    advance=rudder_propeller_advance,
    output_labels=RUDDER_PROPELLER_OUTPUTS,
    output_units=("rad", "1/s"),
)


# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class DirectParams(Params):
    """The direct actuator has no parameters."""


@njit(cache=True)
def direct_rhs(t, xa, ca, p, dxa):  # pragma: no cover - compiled
    pass


@njit(cache=True)
def direct_output(xa, ca, p, ya):  # pragma: no cover - compiled
    """Command channel j is output j (the composer gives one channel per model input fed)."""
    for j in range(ya.shape[0]):
        ya[j] = ca[j]


DIRECT = Actuator(
    name="direct",
    description="no actuator dynamics: the commands are the vessel inputs (one channel per input)",
    params_type=DirectParams,
    state_labels=(),
    state_units=(),
    command_labels=(),
    command_units=(),
    rhs=direct_rhs,
    output=direct_output,
    passthrough=True,
)
