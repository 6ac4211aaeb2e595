"""The plug-in interface of an actuator (servo between controller and vessel).

An actuator turns the controller's commands into the vessel's inputs. It may have states of
its own (integrated together with the vessel's) and is a bundle of numba-compiled functions:

``rhs(t, xa, cmd, p, dxa)``
    writes the actuator state derivative; ``cmd`` is the (zero-order-held) command.
``output(xa, cmd, p, u)``
    writes the vessel inputs.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ..parameters import Params

__all__ = ["Actuator"]


@dataclasses.dataclass(frozen=True, eq=False)
class Actuator:
    """An actuator usable by the simulation engine (see the module docstring)."""

    name: str
    description: str
    params_type: type[Params]
    state_labels: tuple[str, ...]
    state_units: tuple[str, ...]
    command_labels: tuple[str, ...]
    command_units: tuple[str, ...]
    rhs: Any
    output: Any

    @property
    def n_states(self) -> int:
        return len(self.state_labels)

    @property
    def n_commands(self) -> int:
        return len(self.command_labels)
