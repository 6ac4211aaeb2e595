"""A native :class:`gymnasium.vector.VectorEnv` over N runs of one
:class:`~seahelm.Simulator`: every sub-environment is a run of the same compiled loop, all
stepped by one call (no wrapper of N single environments, no Python per sub-environment).

Autoreset follows gymnasium 1.x's *next-step* mode (``metadata["autoreset_mode"]``): the step
after a sub-environment's episode ends (terminated or truncated), its action is ignored, it
starts a new episode and returns that episode's first observation with reward 0 and both flags
False. ``autoreset_mode="Disabled"`` leaves the restart to ``reset(options={"reset_mask": m})``.

Actions are the actuator's commands, in their units (``rudder_command`` [rad],
``propeller_rps`` [1/s]), in a bounded ``Box`` -- or, with ``autopilot=`` a heading autopilot
(e.g. ``"pid-heading-rps"``), a heading set-point ``heading_setpoint`` [rad] that the autopilot
steers for inside the compiled loop (the set-point is relative to the task's reference
direction: the target heading, the current leg's direction); with a ``-rps`` autopilot also
the propeller rps it holds, ``rps_setpoint`` (n = n_0 (1 + a), n_0 the approach's rps; no
registered controller takes a speed set-point: the speed follows the rps). An action outside the box is clipped to it (what
:class:`gymnasium.wrappers.ClipAction` would do; a policy's Gaussian sample routinely is out of
bounds); an action that is NaN or infinite is refused with a
:class:`~seahelm.errors.ParameterError` naming ``actions`` and the sub-environment (nothing is
stepped).
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._optional import optional_import
from ..errors import ParameterError
from ..simulation.stepping_reference import (advance_unobserved, held_commands, restart_clock,
                                              restart_runs, set_controller_param,
                                              set_reference)
from .plant import WEATHER_KEYS, Plant, build_plant, state_views
from .tasks import TASKS, HeadingKeeping, Task

gym = optional_import("gymnasium", extra="rl", purpose="seahelm.gym")
from gymnasium import spaces  # noqa: E402
from gymnasium.vector import AutoresetMode  # noqa: E402
from gymnasium.vector.utils import batch_space  # noqa: E402

from ._fused import heading_error_pass, heading_keeping_end  # noqa: E402
from .base import BatchEnv  # noqa: E402
from .base import autoreset_mode as autoreset_mode_of  # noqa: E402

__all__ = ["ShipVectorEnv"]

#: Default bounds of the commands an action may set, from the ship: (low, high) given the
#: largest rudder δ_max [rad] and the approach's rps n_0 [1/s].
_BOUNDS = {"rudder_command": lambda d, n0: (-d, d),
           "propeller_rps": lambda d, n0: (0.0, 1.5 * n0),
           "heading_setpoint": lambda d, n0: (-0.25 * math.pi, 0.25 * math.pi),
           "rps_setpoint": lambda d, n0: (-0.5, 0.5)}

#: The action of a set-point environment (``autopilot=...``): the heading set-point relative to
#: the task's reference direction [rad].
SETPOINT = "heading_setpoint"

#: The second action a ``-rps`` autopilot takes: the propeller rps it holds (its parameter
#: ``propeller_rps``), relative to the approach's n_0: n = n_0 (1 + a) [-] (symmetric about
#: the approach, as gymnasium recommends a Box to be). No registered controller takes a
#: *speed* set-point (the ``-rps`` autopilots hold a constant rps:
#: :mod:`seahelm.control.held_rps`), so the agent sets the rps the autopilot holds and the
#: speed follows through the ship's dynamics.
RPS_SETPOINT = "rps_setpoint"

class ShipVectorEnv(BatchEnv):
    """N sub-environments of one ship and task, stepped together in the compiled loop.

    Parameters
    ----------
    num_envs : int
        Sub-environments (runs of the simulator).
    task : str
        ``"HeadingKeeping"`` or ``"PathFollowing"`` (:data:`seahelm.gym.tasks.TASKS`).
    ship : Ship or str
        Catalog name or ship file (default ``"kvlcc2-l7"``).
    actions : sequence of str, optional
        The commands the agent sets (default ``("rudder_command",)``; add
        ``"propeller_rps"`` for a ship with a propeller); the others stay at the approach's.
        With an ``autopilot``: ``("heading_setpoint",)`` (the default then), or
        ``("heading_setpoint", "rps_setpoint")`` with a ``-rps`` autopilot: the propeller rps
        it holds too, n = n_0 (1 + a) [-] (no registered controller takes a speed set-point).
    action_bounds : mapping command -> (low, high), optional
        Bounds of the action space in the command's units (default: ±δ_max of the steering
        gear for the rudder, [0, 1.5 n_0] for the rps, ±45° for the heading set-point,
        ±0.5 for the rps set-point: 0.5 to 1.5 n_0).
    autopilot : Controller or str, optional
        A heading autopilot (references include ``heading``: ``"pid-heading-rps"``,
        ``"lq-heading-rps"``, ... or a Controller) that runs inside the compiled loop every
        ``dt`` (or at its own sample period); the action is then its heading set-point
        ``heading_setpoint`` [rad], relative to the task's reference direction (heading
        keeping: the target heading; path following: the current leg's direction), held over
        ``action_period``. Default None: the actions are the commands.
    autopilot_params : Params, optional
        Its parameters (default :func:`seahelm.gym.plant.autopilot_params_for`: K_p = 1,
        K_d = 1.5 L/U_0, the rudder limit and the approach rps).
    dt, action_period : float
        Integration step and time between actions [s] (default 0.1 and 1.0).
    episode_seconds : float, optional
        Episode length [s] (default: the task's, 120 s heading keeping, 400 s path following);
        an episode is truncated there.
    integrator : str or ButcherTableau
        Fixed-step method (default ``"rk4"``; ``"euler"``: explicit Euler).
    reward : mapping term -> weight, optional
        Reward weights (:mod:`seahelm.gym.tasks`).
    autoreset_mode : str or AutoresetMode
        ``"NextStep"`` (default) or ``"Disabled"``.
    render_mode : None
        No rendering.
    **options
        Weather (:data:`seahelm.gym.plant.WEATHER_KEYS`: ``wind_speed`` [m/s],
        ``wind_direction`` [rad], ``wave_height`` [m], ``wave_length`` [m],
        ``wave_direction`` [rad]) and the task's keywords (:class:`~seahelm.gym.tasks.Task`).

    Attributes
    ----------
    observation_labels, observation_units, action_labels, action_units : tuple of str
    plant : Plant
        The ship, its simulator and approach.
    task : Task
    elapsed : ndarray (num_envs,)
        Each sub-environment's time in its episode [s]. (The simulator's runs are kept at
        one step, the batch stepped by one call of the loop: a sub-environment started again
        is reset in the simulator at the batch's time -- or, on the observed path, every
        run's clock set back to 0 -- the model being time-invariant; so the simulator's
        ``time`` is not the episodes'.)
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(self, num_envs: int = 1, *, task: str = "HeadingKeeping",
                 ship: Any = "kvlcc2-l7", actions: Any = None,
                 action_bounds: Mapping[str, tuple[float, float]] | None = None,
                 autopilot: Any = None, autopilot_params: Any = None,
                 dt: float = 0.1, action_period: float = 1.0,
                 episode_seconds: float | None = None, integrator: Any = "rk4",
                 reward: Mapping[str, float] | None = None,
                 autoreset_mode: Any = AutoresetMode.NEXT_STEP,
                 render_mode: str | None = None, **options: Any) -> None:
        if task not in TASKS:
            raise ParameterError(f": unknown task {task!r}; tasks: {', '.join(TASKS)}",
                                 field="task", value=task)
        mode = autoreset_mode_of(autoreset_mode, render_mode)
        task_cls = TASKS[task]
        weather = {k: options.pop(k) for k in list(options) if k in WEATHER_KEYS}
        allowed = (set(inspect.signature(task_cls.__init__).parameters)
                   | set(inspect.signature(Task.__init__).parameters)) - {"self", "num_envs",
                                                                          "kw", "length",
                                                                          "speed", "max_rudder",
                                                                          "reward"}
        for key in options:
            if key not in allowed:
                raise ParameterError(f": unknown keyword {key!r} of task {task}; valid: "
                                     f"{', '.join(sorted(allowed | set(WEATHER_KEYS)))}",
                                     field=key)
        seconds = task_cls.default_episode_seconds if episode_seconds is None \
            else episode_seconds
        self.plant: Plant = build_plant(ship, num_envs=num_envs, episode_seconds=seconds,
                                        dt=dt, action_period=action_period, weather=weather,
                                        integrator=integrator, autopilot=autopilot,
                                        autopilot_params=autopilot_params)
        p = self.plant
        self.task: Task = task_cls(int(num_envs), length=p.length, speed=p.speed,
                                   max_rudder=p.max_rudder, reward=reward, **options)
        self.num_envs = int(num_envs)
        self.render_mode = None
        self.metadata = {**type(self).metadata, "autoreset_mode": mode}
        self.episode_seconds = float(seconds)
        if actions is None:
            actions = (SETPOINT,) if p.autopilot is not None else ("rudder_command",)
        self._setup_actions(actions, action_bounds or {})
        self.observation_labels = self.task.observation_labels
        self.observation_units = self.task.observation_units
        low, high = self._observation_bounds()
        self.single_observation_space = spaces.Box(low, high, dtype=np.float32)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        sim = p.simulator
        self._sim = sim
        #: The states the task reads, live views by label, when the loop outputs them
        #: unchanged: then a step observes nothing (the loop skips the outputs at its end)
        #: and the task reads the states; else None, the loop's observation.
        self._states = state_views(sim, self.task.reads if "reads" in vars(self.task)
                                   else self.task.declared_reads())
        self._fused = self._states is not None and type(self.task) is HeadingKeeping \
            and tuple(self.task.weights) == tuple(HeadingKeeping.default_weights)
        if self._fused:  # (the compiled end of a step: seahelm.gym._fused)
            lab = sim.state_labels
            self._z = sim._z
            self._j_heading = lab.index("heading")
            self._cols = np.array([lab.index(n) for n in ("yaw_rate", "surge_speed",
                                                          "sway_speed")], dtype=np.int64)
            self._box = (self.single_observation_space.low.astype(np.float64),
                         self.single_observation_space.high.astype(np.float64))
            self._error, self._bell = np.zeros(self.num_envs), np.zeros(self.num_envs)
        self._cmd = np.repeat(p.command_start[None], self.num_envs, axis=0)
        self._rudder_col = sim.command_labels.index("rudder_command")
        self._previous = self._cmd[:, self._rudder_col].copy()
        self._done = np.zeros(self.num_envs, dtype=bool)
        #: Each sub-environment's time in its episode [s] (num_envs,).
        self.elapsed = np.zeros(self.num_envs)
        self._horizon = float(p.simulator.problem.t_final) + 1e-9
        self._dt = sim._batch.dt  # (the simulator's time: its step count times this)
        self._started = False
        self._rng = np.random.default_rng()

    # --------------------------------------------------------------------------------------
    def _setup_actions(self, actions: Any, bounds: Mapping[str, tuple[float, float]]) -> None:
        p = self.plant
        names = (actions,) if isinstance(actions, str) else tuple(actions)
        if not names or len(set(names)) != len(names):
            raise ParameterError(f"must be distinct command names, got {actions!r}",
                                 field="actions", value=actions)
        if "rudder_command" not in p.command_labels:
            raise ParameterError(f": the ship's commands ({', '.join(p.command_labels)}) have "
                                 "no rudder_command; the tasks steer with the rudder",
                                 field="ship", value=getattr(p.ship, "name", p.ship))
        for key in bounds:
            if key not in names:
                raise ParameterError(f": {key!r} is not an action; actions: "
                                     f"{', '.join(names)}", field="action_bounds", value=key)
        low, high = [], []
        holds_rps = p.autopilot is not None and "propeller_rps" in \
            p.autopilot.params_type.field_names()
        if p.autopilot is not None and names not in ((SETPOINT,), (SETPOINT, RPS_SETPOINT)):
            raise ParameterError(f"must be ({SETPOINT!r},) or ({SETPOINT!r}, {RPS_SETPOINT!r}) "
                                 f"with an autopilot (it computes the commands), got "
                                 f"{actions!r}", field="actions", value=actions)
        if RPS_SETPOINT in names and not holds_rps:
            raise ParameterError(f": {RPS_SETPOINT!r} needs an autopilot that holds the "
                                 "propeller rps (a '-rps' controller: 'pid-heading-rps', ...); "
                                 "without one the action 'propeller_rps' sets the rps command",
                                 field="actions", value=RPS_SETPOINT)
        if p.autopilot is None and SETPOINT in names:
            raise ParameterError(f": {SETPOINT!r} needs an autopilot (autopilot="
                                 "'pid-heading-rps', ...)", field="actions", value=SETPOINT)
        units = {SETPOINT: "rad", RPS_SETPOINT: "-"}
        for name in names:
            if name in units:
                unit = units[name]
            elif name not in p.command_labels:
                raise ParameterError(f": unknown command {name!r}; the ship's commands: "
                                     f"{', '.join(p.command_labels)}", field="actions",
                                     value=name)
            else:
                unit = p.command_units[p.command_labels.index(name)]
                units[name] = unit
            if name in bounds:
                lo, hi = (float(v) for v in bounds[name])
            elif name in _BOUNDS:
                n0 = p.command_start[p.command_labels.index("propeller_rps")] \
                    if "propeller_rps" in p.command_labels else 0.0
                lo, hi = _BOUNDS[name](p.max_rudder, n0)
            else:
                raise ParameterError(f": give the bounds of {name!r} [{unit}] in action_bounds",
                                     field="action_bounds", value=name)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise ParameterError(f"[{name!r}] must be finite with low < high [{unit}], got "
                                     f"({lo!r}, {hi!r})", field="action_bounds", unit=unit,
                                     value=(lo, hi))
            if name == RPS_SETPOINT and lo <= -1:
                raise ParameterError(f"[{name!r}] must have low > -1 (n = n_0 (1 + a): the "
                                     f"autopilot holds a turning propeller), got ({lo!r}, "
                                     f"{hi!r})", field="action_bounds", unit="-", value=(lo, hi))
            low.append(lo)
            high.append(hi)
        self.action_labels = names
        self._rps_setpoint = RPS_SETPOINT in names
        #: The rps the autopilot holds by its parameters, n_0 of the rps set-point [1/s].
        self._rps0 = float(p.simulator.problem.controller_params.propeller_rps) \
            if self._rps_setpoint else math.nan
        self.action_units = tuple(units[n] for n in names)
        self._act_cols = np.array([p.command_labels.index(n) for n in names
                                   if n in p.command_labels], dtype=np.int64)
        self._low = np.array(low)
        self._high = np.array(high)
        self.single_action_space = spaces.Box(self._low.astype(np.float32),
                                              self._high.astype(np.float32), dtype=np.float32)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

    def _observation_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        p = self.plant
        rudder = [p.max_rudder, abs(p.command_start[p.command_labels.index("rudder_command")])]
        if "rudder_command" in self.action_labels:
            j = self.action_labels.index("rudder_command")
            rudder += [abs(self._low[j]), abs(self._high[j])]
        # bounds no run reaches (a gymnasium Box had best be finite), the angles' exact
        U, L = p.speed, p.length
        known = {"heading_error": math.pi, "next_turn": math.pi, "rudder_command": max(rudder),
                 "yaw_rate": 10.0 * U / L, "surge_speed": 10.0 * U, "sway_speed": 10.0 * U,
                 "cross_track_error": 2.0 * getattr(self.task, "max_cross_track", 0.0)}
        high = np.array([known[n] for n in self.observation_labels])
        return -high.astype(np.float32), high.astype(np.float32)

    # --------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Start every sub-environment's episode (or those of ``options["reset_mask"]``).

        Parameters
        ----------
        seed : int, optional
            Seeds the episodes' draws (targets, initial errors): the same seed and actions give
            the same episodes.
        options : dict, optional
            ``{"reset_mask": bool array (num_envs,)}``: start only those.

        Returns
        -------
        observations (num_envs, observations), info (empty dict)
        """
        sel = self._reset_start(seed, options)
        out = self._begin(sel)
        self._started = True
        return self._observe_now(out)

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                                           dict[str, Any]]:
        """Apply one action per sub-environment for ``action_period`` seconds.

        Parameters
        ----------
        actions : array_like (num_envs, actions)
            By :attr:`action_labels` in :attr:`action_units`; clipped to the action space;
            NaN or infinite refused.

        Returns
        -------
        observations, rewards, terminations, truncations (num_envs,), info (empty dict)

        Raises
        ------
        ParameterError
            Before :meth:`reset`, on a wrong shape, or a NaN/infinite action (nothing is
            stepped).
        """
        a, restart = self._step_start(actions)
        sim = self._sim
        self._previous[:] = self._cmd[:, self._rudder_col]
        every = self.plant.intervals_per_action
        setpoint = self.plant.autopilot is not None
        if setpoint:  # (the autopilot's set-point: absolute, from the task's direction)
            rps = self._rps0 * (1.0 + a[:, 1]) if self._rps_setpoint else None
            a = self.task.reference_direction() + a[:, 0]
        if sim._k[0] * self._dt + self.plant.action_period > self._horizon:  # (sim.time[0])
            restart_clock(sim)  # (the simulator's horizon reached: its clock back to 0)
        # every run stepped (one call of the loop; the runs stay at the same step): those
        # restarting now are started again after it, from their new episode's start
        states = self._states
        if setpoint:
            set_reference(sim, a[:, None])
            if self._rps_setpoint:
                set_controller_param(sim, "propeller_rps", rps)
            if states is None or not advance_unobserved(sim, None, every):
                out = sim.step(None, n=every)
            self._cmd[:] = held_commands(sim)  # (the autopilot's rudder: observed, rewarded)
        else:
            self._cmd[:, self._act_cols] = a
            if states is None or not advance_unobserved(sim, self._cmd, 1):
                out = sim.step(self._cmd)
        self.elapsed += self.plant.action_period
        if restart.any():  # (observed: the restarted runs; the others as the step left them)
            out = self._begin(np.flatnonzero(restart))
        if self._fused:
            return self._fused_end(restart)
        if states is not None:
            out = states
        obs, terms, failed, success = self.task.evaluate(out, self._cmd[:, self._rudder_col],
                                                         self._previous)
        diverged = sim._status != 0
        if diverged.any():
            failed = failed | diverged
            terms["failure"] = -failed.astype(float)
        reward = self.task.reward(terms)
        terminated = failed | success
        truncated = ~terminated & (self.elapsed >= self.episode_seconds - 1e-9)
        return self._step_end(obs, reward, terminated, truncated, restart)

    def _fused_end(self, restart: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                        np.ndarray, dict[str, Any]]:
        """The end of a heading-keeping step in two compiled passes and numpy's exp
        (:mod:`seahelm.gym._fused`): the numbers of ``task.evaluate``, ``task.reward``,
        ``_step_end`` and ``_cast``, bit for bit."""
        task, n = self.task, self.num_envs
        error, bell = self._error, self._bell
        heading_error_pass(self._z, self._j_heading, task.target, task.heading_scale, error,
                           bell)
        np.exp(bell, out=bell)
        w = task.weights
        weights = np.array([w["heading"], w["yaw_rate"], w["rudder"], w["rudder_rate"],
                            w["failure"]])
        consts = np.array([task.length / task.speed, task.max_rudder, task.max_heading_error,
                           self.episode_seconds - 1e-9, 1.0])
        obs = np.empty((n, 5), dtype=np.float32)
        reward = np.empty(n)
        terminated = np.empty(n, dtype=bool)
        truncated = np.empty(n, dtype=bool)
        heading_keeping_end(self._z, self._cols, self._cmd, self._rudder_col, self._previous,
                            error, bell, self._sim._status, self.elapsed, restart, consts,
                            weights, *self._box, obs, reward, terminated, truncated, self._done)
        return obs, reward, terminated, truncated, {}

    def close(self, **kwargs: Any) -> None:
        """End the simulator's thread pool."""
        self._sim.close()
        self.closed = True

    # --------------------------------------------------------------------------------------
    def _begin(self, sel: np.ndarray) -> Any:
        """Start the episodes of ``sel``: the runs reset, the task's draws set, every run's
        clock at the same step again (:func:`~seahelm.simulation.stepping_reference.
        restart_runs`: the batch goes on as one call of the loop a step); returns the
        simulator's observation (the runs of ``sel`` at their new start), or the state views
        when the task reads the states."""
        p = self.plant
        self._cmd[sel] = p.command_start
        self._previous[sel] = p.command_start[self._rudder_col]
        self._done[sel] = False
        self.elapsed[sel] = 0.0
        if self._rps_setpoint:  # (the autopilot's own rps until the first action)
            set_controller_param(self._sim, "propeller_rps", self._rps0, sel)
        # (sel from the start, the others kept: all at t = 0)
        # (reading the states: nothing observed, the clocks kept -- the model being
        # time-invariant, restart_runs checks it)
        observed = self._states is None
        out = restart_runs(self._sim, sel, self.task.begin(sel, self._rng),
                           observe=observed, clock=observed)
        return self._states if out is None else out

    def _observe_now(self, out: Any = None) -> tuple[np.ndarray, dict[str, Any]]:
        """The observations now, without stepping (after a reset: its observation)."""
        if out is None:
            out = self._sim.observe() if self._states is None else self._states
        obs, _, _, _ = self.task.evaluate(out, self._cmd[:, self._rudder_col], self._previous)
        return self._cast(obs), {}

    def __repr__(self) -> str:
        return (f"ShipVectorEnv({self.task.name}, {getattr(self.plant.ship, 'name', '?')}, "
                f"num_envs={self.num_envs}, actions={', '.join(self.action_labels)})")
