"""The registry of the closed loop's stages (:mod:`seahelm.simulation.stage`).

A loop runs, in this order, every stage its problem asks for
(:meth:`~seahelm.simulation.stage.Stage.from_problem`); their outputs follow the model's in
this order. Adding a stage is its module and one line here.
"""

from __future__ import annotations

from typing import Any

from .environment_stage import EnvironmentStage
from .sensor_stage import SensorStage
from .stage import Stage
from .wave_motion_stage import FirstOrderStage

__all__ = ["STAGES", "stages_of"]

#: Stage name -> its class, in the order the loop runs them.
STAGES: dict[str, type[Stage]] = {
    "environment": EnvironmentStage,
    "first_order": FirstOrderStage,
    "sensors": SensorStage,
}


def stages_of(problem: Any) -> tuple[Stage, ...]:
    """The stages a problem's loop runs (those it asks for, in the registry's order).

    Parameters
    ----------
    problem : Problem

    Returns
    -------
    tuple of Stage
    """
    found = []  # (a loop: two generators cost a step each per stage at every call)
    for cls in STAGES.values():
        stage = cls.from_problem(problem)
        if stage is not None:
            found.append(stage)
    return tuple(found)
