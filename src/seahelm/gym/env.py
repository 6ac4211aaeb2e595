"""A :class:`gymnasium.Env` of one ship: the :class:`~seahelm.gym.vector.ShipVectorEnv` with one
sub-environment (the same simulator, task and reward), without autoreset (gymnasium's single
environments are reset by the caller)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .base import OneEnv
from .vector import ShipVectorEnv

__all__ = ["ShipEnv"]


class ShipEnv(OneEnv):
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

    def __init__(self, render_mode: str | None = None, **kwargs: Any) -> None:
        super().__init__(ShipVectorEnv(1, autoreset_mode="Disabled", render_mode=render_mode,
                                       **kwargs))
        self.plant = self._vec.plant

    def _start(self) -> np.ndarray:
        v = self._vec
        v._started = True
        obs, _ = v._observe_now(v._begin(np.arange(1)))
        return obs[0]
