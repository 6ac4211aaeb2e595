"""Rudder (or azimuth-thruster) servo: first-order lag with angle and rate limits.

The commanded angle δ_c is saturated to ±δ_max, the servo follows it as a first-order lag with
time constant T_δ, and the rate is clipped to ±δ̇_max::

    δ̇ = clip((sat(δ_c, δ_max) − δ) / T_δ, −δ̇_max, δ̇_max)

This is the usual steering-machine model (Fossen, *Handbook of Marine Craft Hydrodynamics and
Motion Control*, 2nd ed., 2021, §9.4; van Amerongen, 1982). IMO requires hard-over to
hard-over (35° to 30° the other side) within 28 s, i.e. δ̇_max ≈ 2.3 °/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param
from .base import Actuator

__all__ = ["ServoParams", "RUDDER_SERVO", "DIRECT", "DirectParams"]


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
def servo_rhs(t, xa, cmd, p, dxa):  # pragma: no cover - compiled
    """δ̇ of the rate- and angle-limited first-order servo, one channel per state."""
    max_angle = p.max_angle
    max_rate = p.max_rate
    tau = p.time_constant
    for j in range(xa.shape[0]):
        target = min(max(cmd[j], -max_angle), max_angle)
        rate = (target - xa[j]) / tau
        dxa[j] = min(max(rate, -max_rate), max_rate)


@njit(cache=True)
def servo_output(xa, cmd, p, u):  # pragma: no cover - compiled
    for j in range(xa.shape[0]):
        u[j] = xa[j]


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
    output_labels=("rudder_angle",),
    output_units=("rad",),
)


@dataclass(frozen=True, kw_only=True)
class DirectParams(Params):
    """The direct actuator has no parameters."""


@njit(cache=True)
def direct_rhs(t, xa, cmd, p, dxa):  # pragma: no cover - compiled
    pass


@njit(cache=True)
def direct_output(xa, cmd, p, u):  # pragma: no cover - compiled
    for j in range(u.shape[0]):
        u[j] = cmd[j]


DIRECT = Actuator(
    name="direct",
    description="no actuator dynamics: the command is the vessel input",
    params_type=DirectParams,
    state_labels=(),
    state_units=(),
    command_labels=("command",),
    command_units=("",),
    rhs=direct_rhs,
    output=direct_output,
    passthrough=True,
)
