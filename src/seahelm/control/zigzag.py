"""Zig-zag (Kempf) manoeuvre controller: reverse the rudder when the heading passes a trigger.

The standard zig-zag test (IMO Resolution MSC.137(76), explanatory notes MSC/Circ.1053; ITTC
Recommended Procedure 7.5-04-02-01): from a steady straight approach on the base heading ψ_0
the rudder is put to δ_z on the first side s_1 (+1 starboard, −1 port); when the heading has
changed by the trigger angle ψ_z to that side, the rudder is reversed to δ_z on the other side;
when the heading has passed ψ_z on the other side of ψ_0, it is reversed again; and so on::

    s ← −1   if s = +1 and ψ − ψ_0 ≥ +ψ_z
    s ← +1   if s = −1 and ψ − ψ_0 ≤ −ψ_z
    δ_c = s δ_z

(with ψ predicted half a controller step ahead, see "Sampling" below).

The rudder sign s is the controller's state (``rudder_side``), initialised to s_1. The command
is the rudder order δ_c [rad] for the steering gear (``rudder_command``); the rate-limited
servo turns it into the rudder angle. The heading is the model's continuous (unwrapped)
heading output, so the test may run through any number of turns.

Sampling: the controller sees the heading every Δt (its sample period) and its order is held
in between, so a reversal can only happen at a sample. Reversing at the first sample *after*
the crossing would delay every execute by Δt/2 on average, and the overshoots with it (a
first-order bias: about r Δt/2, 0.05° of a 5° overshoot of the KVLCC2 L7 at Δt = 0.05 s).
The controller therefore reverses at the sample **nearest** to the crossing, predicting the
deviation half a step ahead with the measured yaw rate r::

    reverse at t_k  if  s (ψ_k − ψ_0 + r_k Δt/2) ≥ ψ_z

which leaves an unbiased timing error within ±Δt/2. The manoeuvre metrics
(:mod:`seahelm.analysis.maneuvers.zigzag`) time the executes by interpolating the recorded
heading, not by the sample.

Two controllers share the step code:

:data:`ZIGZAG`
    commands ``rudder_command`` only — a model with one input (the Mariner);
:data:`ZIGZAG_RPS`
    also commands a constant ``propeller_rps`` (its parameter) — a model with a rudder and a
    propeller input (the MMG model), fed directly (no shaft dynamics).

Sign convention as in :mod:`seahelm.vessels.base`: positive rudder → positive (starboard) yaw
rate, heading clockwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..errors import ParameterError
from ..parameters import Params, param, signal_indices
from .base import Controller
from .held_rps import with_held_rps

__all__ = ["ZigZagParams", "ZigZagRpsParams", "ZIGZAG", "ZIGZAG_RPS"]


@dataclass(frozen=True, kw_only=True)
class ZigZagParams(Params):
    """Parameters of the zig-zag controller (angles in radians)."""

    rudder_amplitude: float = param(math.radians(10.0), unit="rad", symbol="δ_z", low=0.0,
                                    low_inclusive=False, high=math.pi / 2,
                                    doc="rudder angle ordered to either side")
    heading_trigger: float = param(math.radians(10.0), unit="rad", symbol="ψ_z", low=0.0,
                                   low_inclusive=False, high=math.pi,
                                   doc="heading change from the base heading that reverses "
                                       "the rudder")
    first_side: float = param(1.0, unit="-", symbol="s_1", low=-1.0, high=1.0,
                              doc="side of the first execute: +1 starboard, -1 port")
    base_heading: float = param(0.0, unit="rad", symbol="ψ_0",
                                doc="heading of the approach, from which the trigger counts")

    def validate(self) -> None:
        """The first side is +1 or −1."""
        if self.first_side not in (-1.0, 1.0):
            raise ParameterError(
                f"`first_side` must be +1 (starboard) or -1 (port) [-], got {self.first_side!r}")


MEASUREMENTS: tuple[str, ...] = ("heading", "yaw_rate")
STATES: tuple[str, ...] = ("rudder_side",)
COMMANDS: tuple[str, ...] = ("rudder_command",)
COMMANDS_RPS: tuple[str, ...] = ("rudder_command", "propeller_rps")

_M = signal_indices(MEASUREMENTS)
_S = signal_indices(STATES)
_C = signal_indices(COMMANDS_RPS)  # rudder_command first in both command vectors


@njit(cache=True)
def zigzag_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    """The rudder starts on the first side."""
    cs[_S.rudder_side] = p.first_side


@njit(cache=True)
def zigzag_rudder(dt, y, p, cs):  # pragma: no cover - compiled
    """Update the rudder side from the heading deviation half a sample period ahead; return
    the rudder order [rad]."""
    deviation = y[_M.heading] - p.base_heading + 0.5 * dt * y[_M.yaw_rate]
    side = cs[_S.rudder_side]
    if side > 0.0 and deviation >= p.heading_trigger:
        side = -1.0
    elif side < 0.0 and deviation <= -p.heading_trigger:
        side = 1.0
    cs[_S.rudder_side] = side
    return side * p.rudder_amplitude


@njit(cache=True)
def zigzag_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    """Rudder order only (one-input models)."""
    cmd[_C.rudder_command] = zigzag_rudder(dt, y, p, cs)


ZIGZAG = Controller(
    name="zigzag",
    description="zig-zag manoeuvre: rudder ±δ_z reversed when the heading passes ±ψ_z "
    "(IMO MSC.137(76)); rudder command only",
    params_type=ZigZagParams,
    state_labels=STATES,
    reference_labels=(),
    reference_units=(),
    command_labels=COMMANDS,
    command_units=("rad",),
    state_units=("-",),
    init=zigzag_init,
    step=zigzag_step,
    measurement_labels=MEASUREMENTS,
)

#: ``zigzag`` commanding a constant propeller rps throughout (:func:`~seahelm.control.held_rps.
#: with_held_rps`), for models with rudder and propeller inputs (MMG).
ZIGZAG_RPS = with_held_rps(ZIGZAG, description=(
    "zig-zag manoeuvre (as 'zigzag') that also commands a constant propeller rps, for models "
    "with rudder and propeller inputs (MMG)"))
#: Zig-zag parameters plus the constant propeller rps commanded throughout.
ZigZagRpsParams = ZIGZAG_RPS.params_type
