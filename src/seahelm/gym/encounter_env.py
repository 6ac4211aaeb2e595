"""Collision avoidance as a gymnasium environment: an own ship meets a target ship
(:mod:`seahelm.encounters`), N encounters of Monte-Carlo geometry stepped together.

:class:`EncounterVectorEnv` is a native :class:`gymnasium.vector.VectorEnv` over an
:class:`~seahelm.encounters.Encounter` of N encounters: its vessels are runs of the encounter's
simulators (one per distinct ship), stepped one action period at a time, and the loop between
two steps is the encounter's (:meth:`Encounter.run <seahelm.encounters.Encounter.run>`): the
vessels' heading autopilot (:class:`~seahelm.encounters.HeadingAutopilot`, a PD law between
intervals) steers each vessel for its desired heading -- the target's route course, or its
avoidance method's heading; the own ship's the agent's action added to its route course. So a
constant action of 0 is the encounter with avoidance off, bit for bit, and a constant action a
the encounter whose own ship steers its route course + a.

The action is ``course_change`` [rad], the own ship's desired heading relative to its route
course, in ±45° by default (clipped, NaN refused as in :class:`~seahelm.gym.ShipVectorEnv`).
Observations, reward terms and the episode's end: :mod:`seahelm.gym.collision`. Autoreset:
gymnasium's next-step mode (or ``"Disabled"`` with ``reset(options={"reset_mask": m})``); each
new episode is a new encounter drawn from the environment's generator.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._optional import optional_import
from ..encounters import AIS, Encounter, HeadingAutopilot, Vessel
from ..encounters.encounter import DEFAULT_MAX_RUDDER
from ..encounters.geometry import wrap_pi
from ..errors import ParameterError
from ..ships import get_ship
from ..simulation.stepping import Simulator
from ..simulation.stepping_reference import restart_clock, restart_runs
from .ais import EpisodeAIS
from .collision import CollisionAvoidance
from .plant import check_env_memory, episode_named

#: Memory of one sub-environment [B], about twice what one takes (peak RSS over 1,000 and
#: 100,000 sub-environments of CollisionAvoidance-v0, KVLCC2 L7, 2026-12-02: 4.8 kB).
_BYTES_PER_ENCOUNTER = 10_000

gym = optional_import("gymnasium", extra="rl", purpose="seahelm.gym")
from gymnasium import spaces  # noqa: E402
from gymnasium.vector import AutoresetMode  # noqa: E402
from gymnasium.vector.utils import batch_space  # noqa: E402

from .base import BatchEnv, OneEnv  # noqa: E402
from .base import autoreset_mode as autoreset_mode_of  # noqa: E402

__all__ = ["EncounterVectorEnv", "EncounterEnv"]
_TASK_KEYS = ("detection_range", "dcpa", "route_scale", "port_tolerance", "domain")


def _ship(value: Any, name: str) -> Any:
    if not isinstance(value, str):
        return value
    try:
        return get_ship(value)
    except (ValueError, FileNotFoundError) as exc:
        raise ParameterError(f": {exc}", field=name, value=value) from None


def _max_rudder(ship: Any) -> float:
    try:  # (as the encounter's autopilot: 35° for a ship without a steering gear)
        return float(ship.max_rudder)
    except ParameterError:
        return DEFAULT_MAX_RUDDER


class EncounterVectorEnv(BatchEnv):
    """N encounters of an own ship and a target ship, the own ship steered by the agent.

    Parameters
    ----------
    num_envs : int
        Encounters (sub-environments).
    ship : Ship or str
        The own ship (default ``"kvlcc2-l7"``).
    target_ship : Ship or str, optional
        The target (default: the own ship's ship).
    target_avoidance : str or object, optional
        The target's avoidance method (:data:`seahelm.encounters.AVOIDANCE`, e.g.
        ``"rule-based"``); default None: the target keeps its course.
    dt, action_period : float
        Integration step and time between actions [s] (default 0.1 and 1.0; the vessels'
        autopilot acts every ``action_period``).
    episode_seconds : float, optional
        Episode length [s] (default: 1.5 times the longest detection range over the own
        speed, in whole action periods).
    autopilot : HeadingAutopilot, optional
        The vessels' heading autopilot (default K_p = 1, T_d = 1.5 L/U).
    sensor : AIS, optional
        What the agent (and an avoiding target) sees of the other vessel: its AIS reports
        (:class:`~seahelm.encounters.AIS`: ``update_interval``, ``delay`` [s], noise, ``seed``;
        :mod:`seahelm.gym.ais`), on each episode's clock. Default None: the other vessel's
        true state every interval. The rewards and the episode's end are the true geometry's.
        Until an episode's first report has arrived (``delay`` after its start) the target's
        six observations are 0.
    action_bounds : (low, high), optional
        Of ``course_change`` [rad] (default ±45°).
    reward : mapping term -> weight, optional
        Reward weights (:mod:`seahelm.gym.collision`).
    autoreset_mode : str or AutoresetMode
        ``"NextStep"`` (default) or ``"Disabled"``.
    render_mode : None
        No rendering.
    **options
        Of :class:`~seahelm.gym.collision.CollisionAvoidance`: ``detection_range``, ``dcpa``
        [own ship lengths], ``route_scale`` [m], ``port_tolerance`` [rad], ``domain``.

    Attributes
    ----------
    observation_labels, observation_units, action_labels, action_units : tuple of str
    task : CollisionAvoidance
    encounter : Encounter
        The encounters as first drawn (their problems are the simulators').
    elapsed : ndarray (num_envs,)
        Each encounter's time in its episode [s] (the simulators' runs are kept at one step:
        an encounter started again sets every run's clock back to 0, the models being
        time-invariant).
    start_geometry : dict
        The target's start of each encounter's episode now: ``north``, ``east`` [m],
        ``course`` [rad] (num_envs,) (the own ship at the origin, heading north).
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(self, num_envs: int = 1, *, ship: Any = "kvlcc2-l7", target_ship: Any = None,
                 target_avoidance: Any = None, dt: float = 0.1, action_period: float = 1.0,
                 episode_seconds: float | None = None,
                 autopilot: HeadingAutopilot | None = None, sensor: Any = None,
                 action_bounds: Any = None,
                 reward: Any = None, autoreset_mode: Any = AutoresetMode.NEXT_STEP,
                 render_mode: str | None = None, **options: Any) -> None:
        mode = autoreset_mode_of(autoreset_mode, render_mode)
        for key in options:
            if key not in _TASK_KEYS:
                raise ParameterError(f": unknown keyword {key!r} of task CollisionAvoidance; "
                                     f"valid: {', '.join(_TASK_KEYS)}", field=key)
        if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) \
                or num_envs < 1:
            raise ParameterError(f"must be an integer >= 1, got {num_envs!r}", field="num_envs",
                                 value=num_envs)
        check_env_memory(int(num_envs), _BYTES_PER_ENCOUNTER)
        for name, v in (("dt", dt), ("action_period", action_period)):
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ParameterError(f"must be > 0 [s], got {v!r}", field=name, unit="s",
                                     value=v)
        own, tgt = _ship(ship, "ship"), _ship(target_ship if target_ship is not None else ship,
                                              "target_ship")
        n = self.num_envs = int(num_envs)
        self.task = CollisionAvoidance(n, own_length=own.length, target_length=tgt.length,
                                       own_speed=own.approach_speed,
                                       target_speed=tgt.approach_speed, reward=reward,
                                       **options)
        if episode_seconds is None:
            longest = self.task.detection_range[1] * own.length / own.approach_speed
            episode_seconds = math.ceil(1.5 * longest / action_period) * action_period
        self.episode_seconds = float(episode_seconds)
        if sensor is not None and not isinstance(sensor, AIS):
            raise ParameterError(f"must be a seahelm.encounters.AIS, got "
                                 f"{type(sensor).__name__}", field="sensor", value=sensor)
        geo = self.task.draw(n, np.random.default_rng(0))
        self.encounter = Encounter(
            [Vessel(ship=own, north=0.0, east=0.0, course=0.0, name="own"),
             Vessel(ship=tgt, north=geo["north"], east=geo["east"], course=geo["course"],
                    avoid=target_avoidance is not None, name="target")],
            t_final=self.episode_seconds, dt=dt, controller_dt=action_period,
            avoidance=target_avoidance, autopilot=autopilot, record_every=1,
            **({} if sensor is None else {"sensor": sensor}))
        enc = self.encounter
        #: The AIS reports the agent sees (None: the true state).
        self._ais = None if sensor is None else EpisodeAIS(
            sensor, n, enc.n_vessels, enc.controller_dt, self.episode_seconds)
        self.render_mode = None
        self.metadata = {**type(self).metadata, "autoreset_mode": mode}
        self._setup_spaces(own, action_bounds)
        with episode_named(self.episode_seconds):
            self._build_loop(enc)
        self._done = np.zeros(n, dtype=bool)
        #: Each encounter's time in its episode [s] (num_envs,).
        self.elapsed = np.zeros(n)
        self._horizon = self.episode_seconds + 1e-9
        self._started = False
        self._clock = 0.0
        self._rng = np.random.default_rng()

    # --------------------------------------------------------------------------------------
    def _setup_spaces(self, own: Any, bounds: Any) -> None:
        lo, hi = (-0.25 * math.pi, 0.25 * math.pi) if bounds is None else bounds
        lo, hi = float(lo), float(hi)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ParameterError(f"must be finite with low < high [rad], got {bounds!r}",
                                 field="action_bounds", unit="rad", value=bounds)
        self.action_labels, self.action_units = ("course_change",), ("rad",)
        self._low, self._high = np.array([lo]), np.array([hi])
        self.single_action_space = spaces.Box(np.float32(lo), np.float32(hi), (1,),
                                              dtype=np.float32)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.observation_labels = self.task.observation_labels
        self.observation_units = self.task.observation_units
        low, high = self.task.observation_bounds(self.episode_seconds, _max_rudder(own))
        self.single_observation_space = spaces.Box(low.astype(np.float32),
                                                   high.astype(np.float32), dtype=np.float32)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)

    def _build_loop(self, enc: Encounter) -> None:
        """The encounter's simulators and the per-run arrays of its loop (as in its run)."""
        nv = enc.n_vessels
        n_runs = enc.n_encounters * nv
        self._sims: list[Simulator] = []
        #: each simulator's last observation (its step's, or its restart's)
        self._obs: list[Any] = []
        self._cmds: list[np.ndarray] = []
        self._rudder_j: list[int] = []
        self._out_j: list[dict[str, int]] = []
        self._index = enc.run_index
        self._e_lim, self._td = np.zeros(n_runs), np.zeros(n_runs)
        self._group = np.zeros(n_runs, dtype=np.int64)
        self._row = np.zeros(n_runs, dtype=np.int64)
        for gi, (problem, opened, index) in enumerate(zip(enc.problems,
                                                         enc.uncoupled_problems(),
                                                         self._index)):
            sim = Simulator(problem)
            self._obs.append(sim.reset())
            self._sims.append(sim)
            labels = sim.command_labels
            ship = problem.ship
            if "rudder_command" not in labels:
                raise ParameterError(f": ship {ship.name!r} takes no rudder_command "
                                     f"(commands: {', '.join(labels)})", field="ship",
                                     value=ship.name)
            c = np.zeros((index.size, len(labels)))
            if "propeller_rps" in labels:
                j = labels.index("propeller_rps")
                c[:, j] = opened.reference[:, 0, j]
            self._cmds.append(c)
            self._rudder_j.append(labels.index("rudder_command"))
            self._e_lim[index] = _max_rudder(ship)
            self._td[index] = enc.autopilot.derivative_time * ship.length / ship.approach_speed
            self._out_j.append({name: j for j, name in enumerate(sim.output_labels)})
            self._group[index], self._row[index] = gi, np.arange(index.size)
        self._x0 = [np.array(p.x0, dtype=float) for p in enc.problems]
        self._course0 = enc.course0.copy()
        self._avoid_state = None
        if enc.avoidance is not None:
            self._fresh_avoid = enc.avoidance.start(enc.n_encounters, nv, enc.avoid, enc)
        self.start_geometry = {k: np.full(enc.n_encounters, np.nan)
                               for k in ("north", "east", "course")}
        self._rudder = np.zeros(n_runs)
        self._truth = np.zeros((n_runs, 6))
        self._uv = np.zeros((n_runs, 2))

    # --------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Start every encounter's episode (or those of ``options["reset_mask"]``), each a
        new Monte-Carlo geometry.

        Parameters
        ----------
        seed : int, optional
            Seeds the geometries' draws (and numbers the AIS reports' episodes from 0 again,
            their noise with them): the same seed and actions give the same episodes.
        options : dict, optional
            ``{"reset_mask": bool array (num_envs,)}``: start only those.

        Returns
        -------
        observations (num_envs, observations), info (empty dict)
        """
        sel = self._reset_start(seed, options)
        if seed is not None and self._ais is not None:  # (the same seed: the same noise too)
            self._ais.renumber()
        if not self._started:
            self._clock = 0.0
            if self.encounter.avoidance is not None:
                self._avoid_state = {k: (v.copy() if isinstance(v, np.ndarray) else v)
                                     for k, v in self._fresh_avoid.items()}
        self._begin(sel)
        self._started = True
        return self._cast(self._evaluate()[0]), {}

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                                           dict[str, Any]]:
        """Steer each own ship for ``action_period`` seconds.

        Parameters
        ----------
        actions : array_like (num_envs, 1)
            ``course_change`` [rad]; clipped to the action space, NaN or infinite refused.

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
        n, enc = self.num_envs, self.encounter
        nv = enc.n_vessels
        truth = self._truth
        route = self._course0
        desired = route
        if self._avoid_state is not None:
            seen = truth[:, :5] if self._ais is None else self._ais.view
            desired = enc.avoidance.desired(self._clock, truth.reshape(n, nv, 6),
                                            seen.reshape(n, nv, 5), route, self._avoid_state)
        desired = desired.copy()
        desired[:, 0] = route[:, 0] + a[:, 0]
        kp, td = enc.autopilot.gain, self._td
        rudder = np.clip(kp * wrap_pi(desired.reshape(-1) - truth[:, 4])
                         - kp * td * truth[:, 5], -self._e_lim, self._e_lim)
        # every run stepped (one call of the loop a simulator: the runs stay at one step);
        # the encounters restarting now are started again after it
        for g, (sim, cmd, index) in enumerate(zip(self._sims, self._cmds, self._index)):
            if sim.time[0] + enc.controller_dt > self._horizon:
                restart_clock(sim)  # (the horizon reached: the clock back to 0)
            cmd[:, self._rudder_j[g]] = rudder[index]
            self._obs[g] = sim.step(cmd)
        self._rudder[:] = rudder
        self.elapsed += enc.controller_dt
        if self._ais is not None:
            self._ais.advance()
        if restart.any():
            self._begin(np.flatnonzero(restart))
        self._clock += enc.controller_dt
        self._observe()
        if self._ais is not None:  # (the restarted encounters' first reports: sent in _begin)
            self._ais.update(truth[:, :5], np.flatnonzero(~np.repeat(restart, nv)))
        obs, terms, collided, passed = self._evaluate()
        diverged = np.zeros(n * nv, dtype=bool)
        for sim, index in zip(self._sims, self._index):
            diverged[index] = sim.status != 0
        diverged = diverged.reshape(n, nv).any(axis=1)
        failed = collided | diverged
        terms["collision"] = -failed.astype(float)
        reward = self.task.reward(terms)
        terminated = failed | passed
        truncated = ~terminated & (self.elapsed >= self.episode_seconds - 1e-9)
        return self._step_end(obs, reward, terminated, truncated, restart)

    @property
    def target_view(self) -> np.ndarray:
        """What the own ship knows of the target now: its north, east [m], course over ground
        [rad], speed over ground [m/s] and heading [rad], (num_envs, 5) (a copy): the latest
        AIS report received (NaN before the episode's first), or with no ``sensor`` its true
        state."""
        nv = self.encounter.n_vessels
        if self._ais is None:
            return self._truth[1::nv, :5].copy()
        return self._ais.view[1::nv].copy()

    @property
    def vessel_states(self) -> np.ndarray:
        """Every vessel's north, east [m], course over ground [rad], speed over ground [m/s],
        heading [rad] and yaw rate [rad/s] now, (num_envs, vessels, 6) (a copy; vessel 0 the
        own ship)."""
        return self._truth.reshape(self.num_envs, self.encounter.n_vessels, 6).copy()

    def close(self, **kwargs: Any) -> None:
        """End the simulators' thread pools."""
        for sim in self._sims:
            sim.close()
        self.closed = True

    # --------------------------------------------------------------------------------------
    def _begin(self, sel: np.ndarray) -> None:
        """Start the episodes of ``sel``: new geometries, the runs reset, the task's start."""
        nv = self.encounter.n_vessels
        geo = self.task.draw(sel.size, self._rng)
        runs = (sel[:, None] * nv + np.arange(nv)[None, :]).reshape(-1)
        targets = sel * nv + 1  # (the own ship starts where the problem has it)
        others = np.setdiff1d(runs, targets)
        for g, sim in enumerate(self._sims):
            # from the start, observed alone (the others kept, every clock back to 0)
            rows = self._row[others[self._group[others] == g]]
            if rows.size:
                self._obs[g] = restart_runs(sim, rows)
            mine = self._group[targets] == g
            if mine.any():
                self._obs[g] = restart_runs(sim, self._row[targets[mine]],
                                            {"north": geo["north"][mine],
                                             "east": geo["east"][mine],
                                             "heading": geo["course"][mine]})
        self._course0[sel, 1] = geo["course"]
        self.elapsed[sel] = 0.0
        for key in ("north", "east", "course"):
            self.start_geometry[key][sel] = geo[key]
        self._rudder[runs] = 0.0
        self._done[sel] = False
        if self._avoid_state is not None:
            for key, fresh in self._fresh_avoid.items():
                live = self._avoid_state[key]
                if isinstance(live, np.ndarray) and live.ndim >= 2 \
                        and live.shape[0] == self.num_envs:
                    live[sel] = fresh[sel]
        self._observe()
        own, target = self._truth[sel * nv], self._truth[sel * nv + 1]
        self.task.begin(sel, own, target)
        if self._ais is not None:  # (the episode's first reports, sent at its start)
            self._ais.begin(sel)
            self._ais.update(self._truth[:, :5], runs)

    def _observe(self) -> None:
        """Every vessel's (north, east, course, speed, heading, yaw rate) and surge/sway
        speeds from the simulators' outputs (as the encounter's loop computes them)."""
        truth = self._truth
        for obs, idx, index in zip(self._obs, self._out_j, self._index):
            vals = obs.values
            psi = vals[:, idx["heading"]]
            u = vals[:, idx["surge_speed"]] if "surge_speed" in idx else vals[:, idx["speed"]]
            v = vals[:, idx["sway_speed"]] if "sway_speed" in idx else 0.0 * u
            vn = u * np.cos(psi) - v * np.sin(psi)
            ve = u * np.sin(psi) + v * np.cos(psi)
            r = vals[:, idx["yaw_rate"]] if "yaw_rate" in idx else 0.0 * u
            truth[index] = np.stack([vals[:, idx["north"]], vals[:, idx["east"]],
                                     np.arctan2(ve, vn), np.hypot(vn, ve), psi, r], axis=1)
            self._uv[index] = np.stack([u, v], axis=1)

    def _evaluate(self):
        nv = self.encounter.n_vessels
        own, target = self._truth[::nv], self._truth[1::nv]
        start = np.zeros((self.num_envs, 2))
        args = (self._uv[::nv], self._rudder[::nv], start)
        result = self.task.evaluate(own, target, *args)
        if self._ais is None:
            return result
        # the agent observes the target as reported; the rewards and the end are the truth's
        seen = np.concatenate([self._ais.view[1::nv], target[:, 5:]], axis=1)
        obs = self.task.evaluate(own, seen, *args)[0]
        return (obs, *result[1:])

    def __repr__(self) -> str:
        names = self.encounter.names
        return f"EncounterVectorEnv({names[0]} meets {names[1]}, num_envs={self.num_envs})"


class EncounterEnv(OneEnv):
    """One encounter, the own ship steered by an agent
    (``gymnasium.make("seahelm/CollisionAvoidance-v0", ...)``): the
    :class:`EncounterVectorEnv` of one sub-environment, without autoreset.

    Parameters
    ----------
    render_mode : None
        No rendering.
    **kwargs
        Of :class:`EncounterVectorEnv`, except ``num_envs`` and ``autoreset_mode``.
    """

    def __init__(self, render_mode: str | None = None, **kwargs: Any) -> None:
        super().__init__(EncounterVectorEnv(1, autoreset_mode="Disabled",
                                            render_mode=render_mode, **kwargs))
        self.encounter = self._vec.encounter

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Start an episode (a new Monte-Carlo geometry).

        Parameters
        ----------
        seed : int, optional
            Seeds the episode's draws (the geometry, and the AIS reports' noise numbered from
            the first episode again): the same seed and actions give the same episode.
        options : dict, optional
            Not used.

        Returns
        -------
        observation (observations,), info (empty dict)
        """
        if seed is not None and self._vec._ais is not None:
            self._vec._ais.renumber()
        return super().reset(seed=seed, options=options)

    def _start(self) -> np.ndarray:
        v = self._vec
        if not v._started and v.encounter.avoidance is not None:
            v._avoid_state = {k: (x.copy() if isinstance(x, np.ndarray) else x)
                              for k, x in v._fresh_avoid.items()}
        v._started = True
        v._begin(np.arange(1))
        return v._cast(v._evaluate()[0])[0]
