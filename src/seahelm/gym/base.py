"""What the environments of :mod:`seahelm.gym` share: a native vector environment's checks of
its modes and actions, its autoreset bookkeeping and the cast of its observations
(:class:`BatchEnv`, the base of :class:`~seahelm.gym.vector.ShipVectorEnv` and
:class:`~seahelm.gym.encounter_env.EncounterVectorEnv`), and the single environment that is
such a vector environment of one sub-environment (:class:`OneEnv`, the base of
:class:`~seahelm.gym.env.ShipEnv` and :class:`~seahelm.gym.encounter_env.EncounterEnv`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._optional import optional_import
from ..errors import ParameterError
from ._fused import clip_actions
from .plant import reset_selection

gym = optional_import("gymnasium", extra="rl", purpose="seahelm.gym")
from gymnasium.vector import AutoresetMode, VectorEnv  # noqa: E402

__all__ = ["BatchEnv", "OneEnv", "autoreset_mode"]

_MODES = {m.value: m for m in AutoresetMode}

#: The dtypes of actions clipped in one compiled pass (:func:`~seahelm.gym._fused.clip_actions`).
_FLOATS = (np.dtype(np.float32), np.dtype(np.float64))


def autoreset_mode(mode: Any, render_mode: Any) -> AutoresetMode:
    """The autoreset mode of a vector environment, checked (and that it renders nothing).

    Parameters
    ----------
    mode : str or AutoresetMode
        ``"NextStep"`` or ``"Disabled"``.
    render_mode : None
        No rendering.

    Returns
    -------
    AutoresetMode

    Raises
    ------
    ParameterError
        Naming ``render_mode`` or ``autoreset_mode``.
    """
    if render_mode is not None:
        raise ParameterError(f": no render modes, got {render_mode!r}", field="render_mode",
                             value=render_mode)
    m = _MODES.get(mode, mode)
    if m not in (AutoresetMode.NEXT_STEP, AutoresetMode.DISABLED):
        raise ParameterError(f"must be 'NextStep' or 'Disabled', got {mode!r}",
                             field="autoreset_mode", value=mode)
    return m


class BatchEnv(VectorEnv):
    """The shared part of seahelm's native vector environments (module docstring).

    A subclass sets ``num_envs``, ``action_labels``, ``action_units``, the bounds ``_low``,
    ``_high`` (actions,), ``single_observation_space``, ``metadata["autoreset_mode"]``,
    ``_done`` (num_envs,) and ``_started``.
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def _actions(self, actions: Any) -> np.ndarray:
        """The actions (num_envs, actions) checked and clipped to the box: an array of that
        shape (or of as many numbers, flat; (actions, num_envs) of one action); NaN or
        infinite refused naming ``actions`` and the sub-environment."""
        n, k = self.num_envs, len(self.action_labels)
        if type(actions) is np.ndarray and actions.shape == (n, k) \
                and actions.dtype in _FLOATS:  # (a policy's batch: one compiled pass)
            out = np.empty((n, k))
            if clip_actions(actions, self._low, self._high, out) < 0:
                return out
        if actions is None:  # (numpy makes None a NaN: "is nan" said nothing of the cause)
            raise ParameterError(f": missing (None); step() needs an array of shape ({n}, {k}) "
                                 f"(envs, {', '.join(self.action_labels)} "
                                 f"[{', '.join(self.action_units)}])", field="actions")
        try:
            a = np.asarray(actions, dtype=np.float64)
        except (TypeError, ValueError):
            raise ParameterError(f"must be numbers of shape ({n}, {k}) "
                                 f"({', '.join(self.action_labels)}), got {actions!r}",
                                 field="actions") from None
        if a.shape != (n, k):
            if a.size == n * k and (a.ndim <= 1 or a.shape == (k, n) and k == 1):
                a = a.reshape(n, k)
            else:
                raise ParameterError(f"must have shape ({n}, {k}) (envs, "
                                     f"{', '.join(self.action_labels)}), got {a.shape}",
                                     field="actions", value=a.shape)
        if not math.isfinite(a.sum()) and not np.isfinite(a).all():  # (a finite sum can overflow)
            bad = np.argwhere(~np.isfinite(a))[0]
            raise ParameterError(f": action {self.action_labels[bad[1]]!r} of sub-environment "
                                 f"{int(bad[0])} is {float(a[tuple(bad)])!r}; actions must be "
                                 f"finite [{self.action_units[bad[1]]}]", field="actions",
                                 value=float(a[tuple(bad)]), run=int(bad[0]))
        return np.minimum(np.maximum(a, self._low), self._high)

    def _reset_start(self, seed: int | None, options: Any) -> np.ndarray:
        """``reset``'s seeding (the episodes' generator from ``seed``, or gymnasium's first
        one) and the sub-environments it starts (:func:`~seahelm.gym.plant.reset_selection`)."""
        super().reset(seed=seed)
        if seed is not None or not self._started:
            self._rng = self.np_random
        return reset_selection(options, self.num_envs, self._started)

    def _step_start(self, actions: Any) -> tuple[np.ndarray, np.ndarray]:
        """A step's checked actions and the sub-environments it restarts (next-step
        autoreset: those whose episode ended at the step before; none when disabled)."""
        if not self._started:
            raise ParameterError(": call reset() before step()", field="reset")
        a = self._actions(actions)
        if self.metadata["autoreset_mode"] is AutoresetMode.NEXT_STEP:
            return a, self._done.copy()
        return a, np.zeros(self.num_envs, dtype=bool)

    def _step_end(self, obs: np.ndarray, reward: np.ndarray, terminated: np.ndarray,
                  truncated: np.ndarray, restart: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """A step's return: the restarted sub-environments with reward 0 and both flags
        False (gymnasium's next-step rule), the episodes ended noted for the next step."""
        if restart.any():
            reward[restart] = 0.0
            terminated[restart] = False
            truncated[restart] = False
        self._done = terminated | truncated
        return self._cast(obs), reward, terminated, truncated, {}

    def _cast(self, obs: np.ndarray) -> np.ndarray:
        """The observations as float32 within the box (a diverged run, NaN: 0)."""
        if not math.isfinite(obs.sum()):
            obs = np.nan_to_num(obs, nan=0.0)
        box = self.single_observation_space
        # (np.minimum/np.maximum: np.clip's Python wrapper costs more than the work; in
        # place: ``obs`` is the task's own new array, and temporaries cost more than the work)
        np.maximum(obs, box.low, out=obs)
        np.minimum(obs, box.high, out=obs)
        return obs.astype(np.float32)


class OneEnv(gym.Env):
    """A :class:`gymnasium.Env` that is a :class:`BatchEnv` of one sub-environment, without
    autoreset (a subclass builds it and defines ``reset``).

    Parameters
    ----------
    vec : BatchEnv
        The vector environment of one sub-environment.
    """

    metadata = {"render_modes": []}

    def __init__(self, vec: BatchEnv) -> None:
        self._vec = vec
        self.observation_space = vec.single_observation_space
        self.action_space = vec.single_action_space
        self.observation_labels, self.observation_units = vec.observation_labels, \
            vec.observation_units
        self.action_labels, self.action_units = vec.action_labels, vec.action_units
        self.task = vec.task
        self.render_mode = None

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Start an episode.

        Parameters
        ----------
        seed : int, optional
            Seeds the episode's draws (a target, initial errors, an encounter's geometry): the
            same seed and actions give the same episode.
        options : dict, optional
            Not used.

        Returns
        -------
        observation (observations,), info (empty dict)
        """
        super().reset(seed=seed)
        self._vec._rng = self.np_random
        return self._start(), {}

    def _start(self) -> np.ndarray:
        """The vector environment's one episode started; its first observation."""
        raise NotImplementedError

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
        """End the simulators' thread pools."""
        self._vec.close()
