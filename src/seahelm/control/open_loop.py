"""Open-loop controller: the reference signal is passed through as the command.

Used for rudder schedules and standard manoeuvres (zig-zag, turning circle, the multi-step
rudder manoeuvres of steady-turn identification), where the "reference" is the commanded
rudder angle itself.
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
    for j in range(cmd.shape[0]):
        cmd[j] = ref[j]


OPEN_LOOP = Controller(
    name="open-loop",
    description="open loop: the reference signal is the command (rudder schedules, manoeuvres)",
    params_type=OpenLoopParams,
    state_labels=(),
    reference_labels=("command",),
    reference_units=("rad",),
    command_labels=("rudder_command",),
    init=open_loop_init,
    step=open_loop_step,
    passthrough=True,
)
