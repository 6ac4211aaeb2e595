"""Reinforcement-learning environments of any seahelm ship (optional extra ``seahelm[rl]``).

* :class:`~seahelm.gym.vector.ShipVectorEnv`: a native :class:`gymnasium.vector.VectorEnv`,
  N sub-environments as N runs of one :class:`~seahelm.Simulator` (one compiled loop, stepped
  together);
* :class:`~seahelm.gym.env.ShipEnv`: the same with one sub-environment, a
  :class:`gymnasium.Env`;
* tasks (:mod:`seahelm.gym.tasks`): heading keeping in wind and waves, path following on a
  route (cross-track error), with named observations and documented reward terms;
* collision avoidance (:mod:`seahelm.gym.collision`): an own ship meets a target ship of
  :mod:`seahelm.encounters`, :class:`~seahelm.gym.encounter_env.EncounterVectorEnv` over N
  encounters of Monte-Carlo geometry (and :class:`~seahelm.gym.encounter_env.EncounterEnv`).

Importing :mod:`seahelm.gym` registers ``seahelm/HeadingKeeping-v0``,
``seahelm/PathFollowing-v0`` and ``seahelm/CollisionAvoidance-v0`` with gymnasium::

    import gymnasium
    import seahelm.gym  # noqa: F401  (registers the environments)

    env = gymnasium.make("seahelm/HeadingKeeping-v0", ship="kvlcc2-l7", wind_speed=3.0)
    envs = gymnasium.make_vec("seahelm/HeadingKeeping-v0", num_envs=1024, ship="kvlcc2-l7")

(``gymnasium.make("seahelm.gym:seahelm/HeadingKeeping-v0")`` imports it on the way.)
"""

from __future__ import annotations

from .._optional import optional_import
from .collision import CollisionAvoidance
from .encounter_env import EncounterEnv, EncounterVectorEnv
from .env import ShipEnv
from .tasks import TASKS, HeadingKeeping, PathFollowing, Task
from .vector import ShipVectorEnv

__all__ = ["ShipEnv", "ShipVectorEnv", "Task", "HeadingKeeping", "PathFollowing", "TASKS",
           "CollisionAvoidance", "EncounterEnv", "EncounterVectorEnv", "register"]


def register() -> None:
    """Register ``seahelm/<Task>-v0`` for every task of :data:`~seahelm.gym.tasks.TASKS` and
    ``seahelm/CollisionAvoidance-v0`` (done on import; again is harmless)."""
    gym = optional_import("gymnasium", extra="rl", purpose="seahelm.gym")
    for name in TASKS:
        env_id = f"seahelm/{name}-v0"
        if env_id in gym.registry:
            continue
        gym.register(id=env_id, entry_point="seahelm.gym.env:ShipEnv",
                     vector_entry_point="seahelm.gym.vector:ShipVectorEnv",
                     kwargs={"task": name, "ship": "kvlcc2-l7"})
    if "seahelm/CollisionAvoidance-v0" not in gym.registry:
        gym.register(id="seahelm/CollisionAvoidance-v0",
                     entry_point="seahelm.gym.encounter_env:EncounterEnv",
                     vector_entry_point="seahelm.gym.encounter_env:EncounterVectorEnv",
                     kwargs={"ship": "kvlcc2-l7"})


register()
