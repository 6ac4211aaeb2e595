"""What the engine takes from a combination of components and stages alone.

:func:`~seahelm.simulation.engine.prepare` needs, besides the problem's arrays, the loop's state
labels, the disturbance and output channels (the model's, then each stage's), the state bounds
and a few sizes. They depend on the wiring (model, actuator, controller) and the stages only,
all frozen, so :func:`_frame` makes them once per combination (issue 46: a circle's batch of one
run spent a fifth of ``prepare`` rebuilding them at every call).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np

__all__: list[str] = []


@dataclasses.dataclass(frozen=True)
class _Frame:
    """What :func:`prepare` takes from a combination of components and stages alone (their
    labels, units, bounds and sizes): :func:`_frame`."""

    labels: tuple[str, ...]
    dist_labels: tuple[str, ...]
    dist_units: tuple[str, ...]
    out_labels: tuple[str, ...]
    out_units: tuple[str, ...]
    stage_names: tuple[str, ...]
    n_states: int
    n_actuator_states: int
    n_commands: int
    controller_width: int
    actuator_command_width: int
    channels: int
    lower: np.ndarray
    upper: np.ndarray


@functools.lru_cache(maxsize=256)
def _frame(wiring: Any, stages: tuple[Any, ...]) -> _Frame:
    """The :class:`_Frame` of a wiring (:class:`~seahelm.simulation.composition.Composition`,
    frozen: its model, actuator and controller) and the loop's stages (frozen dataclasses),
    made once per combination: a batch of one run spent a fifth of :func:`prepare` on them.
    Its ``lower``/``upper`` are read-only (:func:`prepare` copies them)."""
    model, actuator, controller = wiring.model, wiring.actuator, wiring.controller
    dist_labels, dist_units = model.disturbance_labels, model.disturbance_units
    out_labels, out_units = model.output_labels, model.output_units
    for stage in stages:
        (sig, sig_units), (outs, outs_units) = stage.signals(), stage.outputs(model)
        dist_labels, dist_units = dist_labels + sig, dist_units + sig_units
        out_labels, out_units = out_labels + outs, out_units + outs_units
    n_act = actuator.n_states
    lower = np.array(list(model.state_lower) + [-np.inf] * n_act, dtype=float)
    upper = np.array(list(model.state_upper) + [np.inf] * n_act, dtype=float)
    lower.flags.writeable = upper.flags.writeable = False
    n_commands = len(wiring.commands) + len(controller.output_labels)
    return _Frame(
        labels=model.state_labels + actuator.state_labels, dist_labels=dist_labels,
        dist_units=dist_units, out_labels=out_labels, out_units=out_units,
        stage_names=tuple(stage.name for stage in stages), n_states=model.n_states,
        n_actuator_states=n_act, n_commands=n_commands,
        controller_width=max(controller.n_states, 1),
        actuator_command_width=max(len(wiring.actuator_commands), 1),
        channels=(model.n_states + n_act + len(out_labels) + n_commands
                  + len(wiring.references) + len(dist_labels)),
        lower=lower, upper=upper)
