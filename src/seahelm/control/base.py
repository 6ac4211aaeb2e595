"""The plug-in interface of a controller (sampled, zero-order hold).

A controller is stepped by the engine at its own sample period ``dt`` (an integer multiple of
the integration step) and its command is held constant in between. It is a bundle of
numba-compiled functions over one run:

``init(z, y, ref, p, cs)``
    fills the controller's internal state ``cs`` at t = 0.
``step(t, dt, z, y, ref, p, cs, cmd)``
    reads the full closed-loop state ``z`` (vessel states then actuator states), the vessel's
    navigation outputs ``y`` (:data:`seahelm.vessels.base.NAV_OUTPUTS`), the reference vector
    ``ref`` at time ``t``; updates ``cs`` in place and writes the command ``cmd``.

This is the ``init``/``step`` protocol of python-control's sampled systems and of diffrax's
solvers: pure functions with the state passed explicitly.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from numba import njit

from ..parameters import Params

__all__ = ["Controller", "wrap_pi"]


@njit(cache=True)
def wrap_pi(angle):  # pragma: no cover - compiled
    """Wrap a scalar angle [rad] to [−π, π) inside compiled controllers
    (:func:`seahelm.constants.wrap_angle` is the numpy version)."""
    if -math.pi <= angle < math.pi:  # the common case: no division
        return angle
    wrapped = (angle + math.pi) % (2.0 * math.pi) - math.pi
    return wrapped - 2.0 * math.pi if wrapped >= math.pi else wrapped


@dataclasses.dataclass(frozen=True, eq=False)
class Controller:
    """A controller usable by the simulation engine (see the module docstring)."""

    name: str
    description: str
    params_type: type[Params]
    state_labels: tuple[str, ...]
    reference_labels: tuple[str, ...]
    reference_units: tuple[str, ...]
    command_labels: tuple[str, ...]
    init: Any
    step: Any

    @property
    def n_states(self) -> int:
        return len(self.state_labels)

    @property
    def n_references(self) -> int:
        return len(self.reference_labels)

    @property
    def n_commands(self) -> int:
        return len(self.command_labels)
