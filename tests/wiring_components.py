"""Small linear components with several named channels, for the engine's wiring tests.

The model's inputs are declared in the *opposite* order of the actuator's outputs, and the
controller's commands in yet another, so only wiring by name gives the right answer. Every
signal has a closed form for constant commands and disturbances.
"""

from __future__ import annotations

from dataclasses import dataclass

from numba import njit

from seahelm.actuators.base import Actuator
from seahelm.control.base import Controller
from seahelm.parameters import Params, param, signal_indices
from seahelm.vessels.base import VesselModel

STATES = ("speed", "turn")
INPUTS = ("propeller_rps", "rudder_angle")
DISTURBANCES = ("force_x", "moment_z")
OUTPUTS = ("turn", "speed", "thrust")
S = signal_indices(STATES)
U = signal_indices(INPUTS)
D = signal_indices(DISTURBANCES)
Y = signal_indices(OUTPUTS)


@dataclass(frozen=True, kw_only=True)
class TwinParams(Params):
    """ẋ_speed = −a·speed + b·rps + force_x,  ẋ_turn = −c·turn + e·rudder + moment_z."""

    a: float = param(0.5, unit="1/s", low=0.0)
    b: float = param(2.0, unit="m/s²·s")
    c: float = param(0.25, unit="1/s", low=0.0)
    e: float = param(3.0, unit="1/s²")


@njit(cache=True)
def twin_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    dx[S.speed] = -p.a * x[S.speed] + p.b * u[U.propeller_rps] + d[D.force_x]
    dx[S.turn] = -p.c * x[S.turn] + p.e * u[U.rudder_angle] + d[D.moment_z]


@njit(cache=True)
def twin_output(t, x, u, p, y):  # pragma: no cover - compiled
    y[Y.turn] = x[S.turn]
    y[Y.speed] = x[S.speed]
    y[Y.thrust] = p.b * u[U.propeller_rps]


TWIN = VesselModel(
    name="twin-test", description="two decoupled first-order channels (tests)",
    params_type=TwinParams, state_labels=STATES, state_units=("m/s", "rad/s"),
    input_labels=INPUTS, input_units=("1/s", "rad"),
    disturbance_labels=DISTURBANCES, disturbance_units=("m/s²", "rad/s²"),
    output_labels=OUTPUTS, output_units=("rad/s", "m/s", "m/s²"),
    rhs=twin_rhs, output=twin_output,
)

A_CMD = ("rudder_command", "propeller_rps_command")
A_OUT = ("rudder_angle", "propeller_rps")
AC = signal_indices(A_CMD)
AO = signal_indices(A_OUT)


@dataclass(frozen=True, kw_only=True)
class GainParams(Params):
    """Static gains of the two actuator channels."""

    rudder_gain: float = param(1.0, unit="-")
    rps_gain: float = param(1.0, unit="-")


@njit(cache=True)
def gain_rhs(t, xa, ca, p, dxa):  # pragma: no cover - compiled
    pass


@njit(cache=True)
def gain_output(xa, ca, p, ya):  # pragma: no cover - compiled
    ya[AO.rudder_angle] = p.rudder_gain * ca[AC.rudder_command]
    ya[AO.propeller_rps] = p.rps_gain * ca[AC.propeller_rps_command]


TWO_CHANNEL = Actuator(
    name="two-channel-test", description="two static gains (tests)", params_type=GainParams,
    state_labels=(), state_units=(), command_labels=A_CMD, command_units=("rad", "1/s"),
    output_labels=A_OUT, output_units=("rad", "1/s"), rhs=gain_rhs, output=gain_output,
)

C_REF = ("speed", "turn")
C_CMD = ("propeller_rps_command", "rudder_command")
C_MEAS = ("speed", "turn")
CR = signal_indices(C_REF)
CC = signal_indices(C_CMD)
CM = signal_indices(C_MEAS)


@dataclass(frozen=True, kw_only=True)
class PParams(Params):
    """Proportional gains per channel."""

    k_speed: float = param(1.0, unit="-")
    k_turn: float = param(1.0, unit="-")


@njit(cache=True)
def p_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    pass


@njit(cache=True)
def p_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    cmd[CC.propeller_rps_command] = p.k_speed * (ref[CR.speed] - y[CM.speed])
    cmd[CC.rudder_command] = p.k_turn * (ref[CR.turn] - y[CM.turn])


P_TWIN = Controller(
    name="p-twin-test", description="proportional control of both channels (tests)",
    params_type=PParams, state_labels=(), reference_labels=C_REF,
    reference_units=("m/s", "rad/s"), command_labels=C_CMD, init=p_init, step=p_step,
    measurement_labels=C_MEAS,
)
