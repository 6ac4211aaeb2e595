"""Open-loop controller: the reference signals are passed through as the commands.

Used for rudder schedules and standard manoeuvres (zig-zag, turning circle, the multi-step
rudder manoeuvres of steady-turn identification), where the "reference" is the commanded
rudder angle itself. It is a *pass-through* controller: it has no channels of its own, the
composer (:mod:`seahelm.simulation.composition`) gives it one reference and one command per
channel downstream needs, named after it (``rudder_command`` for the rudder servo, the model
input itself, e.g. ``thruster_rate``, with the ``direct`` actuator).
"""

from __future__ import annotations

from dataclasses import dataclass

from numba import njit

from ..parameters import Params
from .base import Controller

__all__ = ["OPEN_LOOP", "OpenLoopParams"]


@dataclass(frozen=True, kw_only=True)
class OpenLoopParams(Params):
    """The open-loop controller has no parameters."""


@njit(cache=True)
def open_loop_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    pass


@njit(cache=True)
def open_loop_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    """Command j is reference j, over all channels."""
    for j in range(cmd.shape[0]):
        cmd[j] = ref[j]


OPEN_LOOP = Controller(
    name="open-loop",
    description="open loop: the reference signals are the commands (rudder schedules, manoeuvres)",
    params_type=OpenLoopParams,
    state_labels=(),
    reference_labels=(),
    reference_units=(),
    command_labels=(),
    init=open_loop_init,
    step=open_loop_step,
    passthrough=True,
)
