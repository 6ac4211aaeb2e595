"""A :class:`gymnasium.Env` of one ship: the :class:`~seahelm.gym.vector.ShipVectorEnv` with one
sub-environment (the same simulator, task and reward), without autoreset (gymnasium's single
environments are reset by the caller)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._optional import optional_import
from ..errors import ParameterError
from .vector import ShipVectorEnv

gym = optional_import("gymnasium", extra="rl", purpose="seahelm.gym")

__all__ = ["ShipEnv"]


class ShipEnv(gym.Env):
    """One ship steered by an agent (``gymnasium.make("seahelm/HeadingKeeping-v0", ...)``).

    Parameters
    ----------
    **kwargs
        Of :class:`~seahelm.gym.vector.ShipVectorEnv` (``task``, ``ship``, ``actions``,
        ``action_bounds``, ``autopilot``, ``autopilot_params``, ``dt``, ``action_period``,
        ``episode_seconds``, ``integrator``, ``reward``, the weather and the task's keywords),
        except ``num_envs`` and ``autoreset_mode``.

    Notes
    -----
    Actions outside the space are clipped, NaN or infinite ones refused (``ParameterError``),
    as in the vector environment. After an episode has ended, :meth:`step` returns the final
    observation again (reward 0 for a truncated episode's further steps is not given: call
    :meth:`reset`).
    """

    metadata = {"render_modes": []}

    def __init__(self, render_mode: str | None = None, **kwargs: Any) -> None:
        self._vec = ShipVectorEnv(1, autoreset_mode="Disabled", render_mode=render_mode,
                                  **kwargs)
        v = self._vec
        self.observation_space = v.single_observation_space
        self.action_space = v.single_action_space
        self.observation_labels, self.observation_units = v.observation_labels, \
            v.observation_units
        self.action_labels, self.action_units = v.action_labels, v.action_units
        self.plant, self.task = v.plant, v.task
        self.render_mode = None

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Start an episode.

        Parameters
        ----------
        seed : int, optional
            Seeds the episode's draws (target, initial errors): the same seed and actions give
            the same episode.
        options : dict, optional
            Not used.

        Returns
        -------
        observation (observations,), info (empty dict)
        """
        super().reset(seed=seed)
        self._vec._rng = self.np_random
        self._vec._started = True
        obs, _ = self._vec._observe_now(self._vec._begin(np.arange(1)))
        return obs[0], {}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Apply one action for ``action_period`` seconds.

        Parameters
        ----------
        action : array_like (actions,)
            By :attr:`action_labels`, in :attr:`action_units`; clipped to the action space,
            NaN or infinite refused (``ParameterError``).

        Returns
        -------
        observation, reward, terminated, truncated, info (empty dict)
        """
        if action is None:
            k = len(self.action_labels)
            raise ParameterError(f": missing (None); step() needs an array of shape ({k},) "
                                 f"({', '.join(self.action_labels)} "
                                 f"[{', '.join(self.action_units)}])", field="action")
        obs, reward, terminated, truncated, _ = self._vec.step([action])
        return obs[0], float(reward[0]), bool(terminated[0]), bool(truncated[0]), {}

    def close(self) -> None:
        """End the simulator's thread pool."""
        self._vec.close()
