"""The plug-in interface of an actuator (servo between controller and vessel).

An actuator turns the controller's commands into vessel inputs, by name: it declares the
command channels it takes (``command_labels``, e.g. ``rudder_command``) and the signals it
produces (``output_labels``, e.g. ``rudder_angle``); the composer
(:mod:`seahelm.simulation.composition`) connects controller commands to its command channels and
its outputs to the model inputs of the same name. It may have states of its own (integrated
together with the vessel's) and is a bundle of numba-compiled functions:

``rhs(t, xa, ca, p, dxa)``
    writes the actuator state derivative; ``ca`` are its (zero-order-held) command channels.
``output(xa, ca, p, ya)``
    writes its outputs (``output_labels`` order).
``advance(h, xa, ca, p, out)`` (optional)
    writes into ``out`` the state ``h`` seconds after ``xa`` under the constant commands
    ``ca``, in closed form. The engine then takes the actuator states from it at every stage of
    the step instead of integrating ``rhs`` with the step's tableau: exact, and without the
    stability bound a fast servo (a lag of 0.1 s) puts on an explicit step.

``p`` is the run's parameter record (``p.max_rate``). A *pass-through* actuator (``DIRECT``)
has no channels of its own: the composer gives it one channel per model input it feeds, and it
copies command to input.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ..parameters import Params

__all__ = ["Actuator"]


@dataclasses.dataclass(frozen=True, eq=False)
class Actuator:
    """An actuator usable by the simulation engine (see the module docstring).

    Attributes
    ----------
    name, description : str
        Registry name and one line on what it is.
    params_type : type[Params]
        Frozen parameter dataclass.
    state_labels, state_units : tuple of str
        Its own states (integrated with the vessel's).
    command_labels, command_units : tuple of str
        Command channels it takes from the controller.
    output_labels, output_units : tuple of str
        What it feeds to the vessel (names of model inputs).
    rhs, output : numba dispatchers
        See the module docstring.
    passthrough : bool
        No channels of its own: one channel per model input it feeds, output = command.
    advance : numba dispatcher or None
        The closed-form state after a time under constant commands (see the module docstring),
        or None: the engine integrates ``rhs``.
    """

    name: str
    description: str
    params_type: type[Params]
    state_labels: tuple[str, ...]
    state_units: tuple[str, ...]
    command_labels: tuple[str, ...]
    command_units: tuple[str, ...]
    rhs: Any
    output: Any
    output_labels: tuple[str, ...] = ()
    output_units: tuple[str, ...] = ()
    passthrough: bool = False
    advance: Any = None

    def __post_init__(self) -> None:
        for attr, ref in (("state_units", self.state_labels),
                          ("command_units", self.command_labels),
                          ("output_units", self.output_labels)):
            if len(getattr(self, attr)) != len(ref):
                raise ValueError(f"{self.name}: {attr} has the wrong length")
        if not self.passthrough and not self.output_labels:
            raise ValueError(f"{self.name}: an actuator must declare its output_labels")

    @property
    def n_states(self) -> int:
        return len(self.state_labels)

    @property
    def n_commands(self) -> int:
        return len(self.command_labels)

    @property
    def n_outputs(self) -> int:
        return len(self.output_labels)

    def signals(self) -> list[tuple[str, str, str]]:
        """Every declared signal as ``(kind, name, unit)``: states, commands, outputs.

        A pass-through actuator lists none beyond its states (its channels are the model
        inputs it is wired to).

        Returns
        -------
        list of tuple of str
        """
        return [(kind, n, u) for kind, names, units in (
            ("state", self.state_labels, self.state_units),
            ("command", self.command_labels, self.command_units),
            ("output", self.output_labels, self.output_units)) for n, u in zip(names, units)]
