"""Wiring components by signal name: controller → actuator → vessel model.

:func:`compose` connects the components of a closed loop once, checks every name and count, and
returns a :class:`Composition` from which the engine generates the compiled loop. The rules
(python-control's ``interconnect`` by signal name, specialised to one controller, one actuator
and one model):

* every **model input** ``X`` is fed by the actuator output named ``X``, or else directly by a
  controller command named ``X`` or ``X_command`` (no actuator dynamics on that channel);
* every **actuator command channel** is fed by the controller command of the same name;
* every **controller command** feeds something, every actuator output is a model input, and
  every **measurement** a controller declares is a model output (routed to it by name);
* a *pass-through* actuator (``direct``) gets one channel per model input it feeds, named after
  the input; a *pass-through* controller (``open-loop``) gets one command (and reference) per
  channel downstream needs, named after it.

Anything else is a :class:`~seahelm.errors.ParameterError` that names the signals involved and
lists what is available. A model with several inputs (rudder angle and propeller rps, two
thruster angles) is wired the same way as one with a single input.
"""

from __future__ import annotations

import dataclasses
import functools

from ..actuators.base import Actuator
from ..control.base import Controller
from ..errors import ParameterError
from ..vessels.base import VesselModel

__all__ = ["Composition", "compose"]

COMMAND_SUFFIX = "_command"


@dataclasses.dataclass(frozen=True)
class Composition:
    """A checked closed loop: who feeds whom, by index (see :func:`compose`).

    Attributes
    ----------
    model, actuator, controller
        The components.
    commands : tuple of str
        Controller commands (resolved for a pass-through controller).
    references, reference_units : tuple of str
        Controller reference channels and their units.
    actuator_commands, actuator_outputs, actuator_output_units : tuple of str
        Actuator command channels and outputs (resolved for a pass-through actuator).
    actuator_command_from : tuple of int
        For each actuator command channel, the index of the controller command feeding it.
    input_from : tuple of (str, int)
        For each model input, ``("actuator", j)`` (actuator output j) or ``("command", j)``
        (controller command j, fed directly).
    measurement_from : tuple of int
        For each controller measurement, the index of the model output it reads.
    command_units : tuple of str
        The unit of each controller command: that of the actuator channel or model input it
        feeds (a controller declares its commands' names, not their units).
    """

    model: VesselModel
    actuator: Actuator
    controller: Controller
    commands: tuple[str, ...]
    references: tuple[str, ...]
    reference_units: tuple[str, ...]
    actuator_commands: tuple[str, ...]
    actuator_outputs: tuple[str, ...]
    actuator_output_units: tuple[str, ...]
    actuator_command_from: tuple[int, ...]
    input_from: tuple[tuple[str, int], ...]
    measurement_from: tuple[int, ...]
    command_units: tuple[str, ...] = ()

    def describe(self) -> str:
        """The wiring as text, one connection per line (for ``seahelm models`` and errors).

        Returns
        -------
        str
        """
        lines = []
        for j, name in enumerate(self.actuator_commands):
            lines.append(f"controller.{self.commands[self.actuator_command_from[j]]} -> "
                         f"actuator.{name}")
        for i, (kind, j) in enumerate(self.input_from):
            src = (f"actuator.{self.actuator_outputs[j]}" if kind == "actuator"
                   else f"controller.{self.commands[j]}")
            lines.append(f"{src} -> model.{self.model.input_labels[i]}")
        for i, j in enumerate(self.measurement_from):
            lines.append(f"model.{self.model.output_labels[j]} -> "
                         f"controller.{self.controller.measurement_labels[i]}")
        return "\n".join(lines)


def _names(labels: tuple[str, ...]) -> str:
    return ", ".join(labels) if labels else "none"


def _feeds(command: str, target: str) -> bool:
    return command == target or command == target + COMMAND_SUFFIX


@functools.lru_cache(maxsize=None)
def compose(model: VesselModel, actuator: Actuator, controller: Controller) -> Composition:
    """Connect controller commands → actuator channels → model inputs by name, and check.

    Parameters
    ----------
    model : VesselModel
        The vessel model.
    actuator : Actuator
        The actuator (``direct`` for none).
    controller : Controller
        The controller (``open-loop`` for a schedule).

    Returns
    -------
    Composition

    Raises
    ------
    ParameterError
        If a model input is not fed, an actuator output or a controller command feeds nothing,
        an actuator channel has no command, or a measurement is not a model output; the message
        names the signals and lists the available ones.
    """
    inputs = model.input_labels
    where = f"model '{model.name}', actuator '{actuator.name}', controller '{controller.name}'"

    # --- actuator outputs -> model inputs ---------------------------------------------------
    if actuator.passthrough:
        if controller.passthrough:
            fed_by_actuator = inputs
        else:
            fed_by_actuator = tuple(
                x for x in inputs if any(_feeds(c, x) for c in controller.command_labels))
        act_out = fed_by_actuator
        act_out_units = tuple(model.input_units[inputs.index(x)] for x in act_out)
        act_cmd = act_out
        act_cmd_units = act_out_units
    else:
        for name in actuator.output_labels:
            if name not in inputs:
                raise ParameterError(
                    f"{where}: actuator output '{name}' is not an input of the model "
                    f"(model inputs: {_names(inputs)})")
        act_out, act_out_units = actuator.output_labels, actuator.output_units
        act_cmd, act_cmd_units = actuator.command_labels, actuator.command_units

    direct = tuple(x for x in inputs if x not in act_out)

    # --- controller commands ------------------------------------------------------------------
    if controller.passthrough:
        commands = act_cmd + direct
        units = act_cmd_units + tuple(model.input_units[inputs.index(x)] for x in direct)
        references, reference_units = commands, units
    else:
        commands = controller.command_labels
        references, reference_units = controller.reference_labels, controller.reference_units

    # actuator channels from commands (a pass-through actuator's channel X takes X or X_command)
    act_from = []
    for name in act_cmd:
        match = [k for k, c in enumerate(commands)
                 if (c == name if not actuator.passthrough else _feeds(c, name))]
        if not match:
            raise ParameterError(
                f"{where}: actuator channel '{name}' gets no command; the controller gives "
                f"{_names(commands)}")
        if len(match) > 1:
            raise ParameterError(
                f"{where}: actuator channel '{name}' is fed by several commands: "
                f"{_names(tuple(commands[k] for k in match))}")
        act_from.append(match[0])

    input_from: list[tuple[str, int]] = []
    for x in inputs:
        if x in act_out:
            input_from.append(("actuator", act_out.index(x)))
            continue
        match = [k for k, c in enumerate(commands) if _feeds(c, x)]
        if not match:
            raise ParameterError(
                f"{where}: model input '{x}' is not fed: no actuator output and no controller "
                f"command named '{x}' or '{x}{COMMAND_SUFFIX}' (actuator outputs: "
                f"{_names(act_out)}; controller commands: {_names(commands)})")
        if len(match) > 1:
            raise ParameterError(
                f"{where}: model input '{x}' is fed by several commands: "
                f"{_names(tuple(commands[k] for k in match))}")
        input_from.append(("command", match[0]))

    used = set(act_from) | {j for kind, j in input_from if kind == "command"}
    unused = [c for k, c in enumerate(commands) if k not in used]
    if unused:
        raise ParameterError(
            f"{where}: controller command(s) {_names(tuple(unused))} feed nothing: no actuator "
            f"channel (channels: {_names(act_cmd)}) and no model input (inputs: "
            f"{_names(inputs)}) of that name")

    meas_from = []
    for name in controller.measurement_labels:
        if name not in model.output_labels:
            raise ParameterError(
                f"{where}: the controller measures '{name}', which the model does not output "
                f"(model outputs: {_names(model.output_labels)})")
        meas_from.append(model.output_labels.index(name))

    command_units = [""] * len(commands)  # (the unit of what each command feeds)
    for j, k in enumerate(act_from):
        command_units[k] = act_cmd_units[j]
    for i, (kind, k) in enumerate(input_from):
        if kind == "command":
            command_units[k] = model.input_units[i]

    return Composition(
        model=model, actuator=actuator, controller=controller,
        commands=tuple(commands), references=tuple(references),
        reference_units=tuple(reference_units),
        actuator_commands=tuple(act_cmd), actuator_outputs=tuple(act_out),
        actuator_output_units=tuple(act_out_units),
        actuator_command_from=tuple(act_from), input_from=tuple(input_from),
        measurement_from=tuple(meas_from), command_units=tuple(command_units),
    )
