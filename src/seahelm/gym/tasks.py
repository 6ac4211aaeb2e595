"""The tasks of :mod:`seahelm.gym`: what a sub-environment observes, how it is rewarded, when
its episode ends. Vectorised over the sub-environments (numpy, no per-environment loop).

Each task keeps per-environment arrays (a target heading, a route leg), draws them at the start
of an episode (:meth:`Task.begin`) and turns the simulator's outputs into named observations,
reward terms and the end of an episode (:meth:`Task.evaluate`).

Reward
------
The reward of a step is ``sum(weight[name] * term[name])`` over the task's terms
(:attr:`Task.terms`); every term is dimensionless, with L the ship length, U_0 the approach
speed, δ_max the largest rudder command:

=================  ================================================  =========================
term               value                                             task
=================  ================================================  =========================
``heading``        exp(-(ψ̃ / σ_ψ)²), ψ̃ heading error (wrapped)         both (path: to the leg)
``cross_track``    exp(-(e / σ_e)²), e cross-track error              path following
``yaw_rate``       -(r L / U_0)²                                      both
``rudder``         -(δ_c / δ_max)²                                    both
``rudder_rate``    -((δ_c - δ_c,previous) / δ_max)²                   both
``failure``        -1 on the step an episode fails (else 0)           both
=================  ================================================  =========================

σ_ψ (``heading_scale``, default 10°) and σ_e (``cross_track_scale``, default L/2) set how
sharply the two bounded terms reward accuracy; bounded positive tracking terms keep "end the
episode early" from paying (a negative-only reward would). A failure is a heading error above
``max_heading_error`` (heading keeping), a cross-track error above ``max_cross_track`` (path
following), or a run that diverged.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

from ..errors import ParameterError

__all__ = ["Task", "Weighted", "HeadingKeeping", "PathFollowing", "TASKS", "wrap", "reward_weights",
           "weighted_sum"]


def wrap(angle: np.ndarray) -> np.ndarray:
    """Angles wrapped to [-π, π).

    Parameters
    ----------
    angle : ndarray
        [rad]

    Returns
    -------
    ndarray
        [rad]
    """
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def reward_weights(task: str, defaults: Mapping[str, float],
                   reward: Mapping[str, float] | None) -> dict[str, float]:
    """A task's reward weights: ``defaults`` with those of ``reward`` (term -> weight).

    Parameters
    ----------
    task : str
        The task's name (in the messages).
    defaults : mapping
        Every term's default weight.
    reward : mapping, optional
        The weights given (the terms not named keep their defaults).

    Returns
    -------
    dict
        Term -> weight.

    Raises
    ------
    ParameterError
        Naming ``reward``: not a mapping, an unknown term, a weight not a finite number.
    """
    weights = dict(defaults)
    if reward is not None and not isinstance(reward, Mapping):
        raise ParameterError(f"must be a mapping term -> weight, got {reward!r}",
                             field="reward", value=reward)
    for key, w in (reward or {}).items():
        if key not in defaults:
            raise ParameterError(f": unknown reward term {key!r} of {task}; terms: "
                                 f"{', '.join(defaults)}", field="reward", value=key)
        try:
            v = float(w)
        except (TypeError, ValueError):
            raise ParameterError(f"[{key!r}] must be a number, got {w!r}", field="reward",
                                 value=w) from None
        if not math.isfinite(v):
            raise ParameterError(f"[{key!r}] must be finite, got {w!r}", field="reward",
                                 value=w)
        weights[key] = v
    return weights


def weighted_sum(weights: Mapping[str, float], terms: Mapping[str, np.ndarray],
                 n: int) -> np.ndarray:
    """The reward Σ weight · term (n,) over the terms of non-zero weight.

    Parameters
    ----------
    weights : mapping
        Term -> weight.
    terms : mapping
        Term -> (n,) or a number.
    n : int
        Sub-environments.

    Returns
    -------
    ndarray (n,)
    """
    total = np.zeros(n)
    for key, w in weights.items():
        if w:
            total += w * terms[key]  # (in place: 0 + ... as the sum always began)
    return total


def _bell(x: np.ndarray, scale: float) -> np.ndarray:
    """exp(-(x / scale)²), in place on one new array."""
    y = x / scale
    np.square(y, out=y)
    np.negative(y, out=y)
    return np.exp(y, out=y)


def _positive(name: str, value: Any, unit: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=name, unit=unit,
                             value=value)
    return v


class Weighted:
    """A task's reward, Σ weight · term (``weights``, ``default_weights``, ``n`` set by the
    task)."""

    default_weights: ClassVar[dict[str, float]] = {}
    weights: dict[str, float]
    n: int

    @property
    def terms(self) -> tuple[str, ...]:
        """The reward terms."""
        return tuple(self.default_weights)

    def reward(self, terms: Mapping[str, np.ndarray]) -> np.ndarray:
        """The reward Σ weight · term.

        Parameters
        ----------
        terms : mapping
            Reward term name -> (envs,), as :meth:`evaluate` gives them.

        Returns
        -------
        ndarray (envs,)
        """
        return weighted_sum(self.weights, terms, self.n)


class Task(Weighted):
    """What a sub-environment is asked to do (base class: see the module's table).

    Parameters
    ----------
    num_envs : int
    length, speed, max_rudder : float
        Ship length L [m], approach speed U_0 [m/s], largest rudder command δ_max [rad].
    reward : mapping name -> weight, optional
        Weights of the reward terms (the terms not named keep :attr:`default_weights`).
    heading_scale : float
        σ_ψ [rad] (default 10°).
    """

    #: The task's name in ``gymnasium.make("seahelm/<Name>-v0")``.
    name: ClassVar[str] = ""
    #: Observations, their units.
    observation_labels: ClassVar[tuple[str, ...]] = ()
    observation_units: ClassVar[tuple[str, ...]] = ()
    #: Reward terms and their default weights.
    default_weights: ClassVar[dict[str, float]] = {}
    #: Default episode length [s].
    default_episode_seconds: ClassVar[float] = 120.0
    #: The simulator's outputs :meth:`evaluate` reads (None: not declared); when they are
    #: states the loop outputs unchanged the environment reads the states instead
    #: (:func:`seahelm.gym.plant.state_views`).
    reads: ClassVar[tuple[str, ...] | None] = None

    #: The methods that read the simulator's outputs: a class that defines one of them ahead of
    #: the class declaring :attr:`reads` (a subclass or a mixin before it) may read others.
    _READERS: ClassVar[tuple[str, ...]] = ("evaluate", "_evaluate", "_common_terms",
                                           "_along_across")

    @classmethod
    def declared_reads(cls) -> tuple[str, ...] | None:
        """:attr:`reads` where it holds for this class's own evaluation, else None.

        A class that defines an evaluation method (:meth:`evaluate`, :meth:`_evaluate` or a
        helper they call with the outputs) ahead of the class declaring ``reads`` in its MRO —
        a subclass overriding it, a mixin listed first — without declaring ``reads`` anew may
        read outputs the declaration does not name (the environment would hand it only those
        states): its reads are then undeclared, and the environment hands it the loop's whole
        observation. (A ``reads`` set on an instance is the environment's to honour.)
        """
        mro = cls.__mro__
        owner = next(k for k, c in enumerate(mro) if "reads" in c.__dict__)
        if any(name in c.__dict__ for c in mro[:owner] for name in cls._READERS):
            return None
        return cls.reads

    def __init__(self, num_envs: int, *, length: float, speed: float, max_rudder: float,
                 reward: Mapping[str, float] | None = None,
                 heading_scale: float = math.radians(10.0)) -> None:
        self.n, self.length, self.speed, self.max_rudder = num_envs, length, speed, max_rudder
        self.heading_scale = _positive("heading_scale", heading_scale, "rad")
        self.weights = reward_weights(self.name, self.default_weights, reward)

    def begin(self, sel: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
        """Draw the episodes of some sub-environments.

        Parameters
        ----------
        sel : ndarray of int
            The sub-environments starting an episode.
        rng : numpy.random.Generator
            The draws' source.

        Returns
        -------
        dict
            Their initial states by state label, values (len(sel),) [SI]; the states not
            named keep the approach's.
        """
        return self._draw(sel, rng)

    def evaluate(self, out: Mapping[str, np.ndarray], rudder: np.ndarray,
                 previous_rudder: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray],
                                                        np.ndarray, np.ndarray]:
        """Observations, reward terms and the end of the episodes after a step.

        Parameters
        ----------
        out : mapping
            The simulator's outputs by name, arrays (envs,) [SI].
        rudder, previous_rudder : ndarray (envs,)
            The rudder commands of this step and of the one before [rad].

        Returns
        -------
        observations : ndarray (envs, observations)
            By :attr:`observation_labels`.
        terms : dict
            Reward term name -> (envs,).
        failed, done : ndarray of bool (envs,)
            The episode failed; it ended without failure (a route completed).
        """
        return self._evaluate(out, rudder, previous_rudder)

    def reference_direction(self) -> np.ndarray:
        """The direction a heading set-point action is relative to, per sub-environment
        (envs,) [rad]: the target heading (heading keeping), the current leg's direction (path
        following)."""
        raise NotImplementedError

    def _draw(self, sel: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
        raise NotImplementedError

    def _evaluate(self, out: Mapping[str, np.ndarray], rudder: np.ndarray,
                  previous_rudder: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray],
                                                         np.ndarray, np.ndarray]:
        raise NotImplementedError

    def _common_terms(self, out: Mapping[str, np.ndarray], rudder: np.ndarray,
                      previous_rudder: np.ndarray) -> dict[str, np.ndarray]:
        # (in place on each term's own new array: temporaries cost more than the work)
        r_nd = out["yaw_rate"] * (self.length / self.speed)
        rel = rudder / self.max_rudder
        rate = rudder - previous_rudder
        rate /= self.max_rudder
        for x in (r_nd, rel, rate):
            np.square(x, out=x)
            np.negative(x, out=x)
        return {"yaw_rate": r_nd, "rudder": rel, "rudder_rate": rate}


class HeadingKeeping(Task):
    """Keep a target heading ψ_d (in the wind and waves of the environment).

    Each episode draws ψ_d uniformly in [-π, π) (so the weather comes from any side) and starts
    the ship on the straight approach with a heading error uniform in ±``initial_heading_error``.

    Parameters
    ----------
    initial_heading_error : float
        Largest initial heading error [rad] (default 20°).
    max_heading_error : float
        A heading error above it fails the episode [rad] (default 90°).
    **kw
        Of :class:`Task`.
    """

    name = "HeadingKeeping"
    observation_labels = ("heading_error", "yaw_rate", "surge_speed", "sway_speed",
                          "rudder_command")
    observation_units = ("rad", "rad/s", "m/s", "m/s", "rad")
    default_weights = {"heading": 1.0, "yaw_rate": 0.1, "rudder": 0.05, "rudder_rate": 0.05,
                       "failure": 50.0}
    default_episode_seconds = 120.0
    reads = ("heading", "yaw_rate", "surge_speed", "sway_speed")

    def __init__(self, num_envs: int, *, initial_heading_error: float = math.radians(20.0),
                 max_heading_error: float = math.radians(90.0), **kw: Any) -> None:
        super().__init__(num_envs, **kw)
        self.initial_heading_error = float(initial_heading_error)
        if not (math.isfinite(self.initial_heading_error) and 0 <= self.initial_heading_error
                <= math.pi):
            raise ParameterError(f"must be in [0, π] [rad], got {initial_heading_error!r}",
                                 field="initial_heading_error", unit="rad",
                                 value=initial_heading_error)
        self.max_heading_error = _positive("max_heading_error", max_heading_error, "rad")
        self.target = np.zeros(num_envs)

    def _draw(self, sel: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
        target = rng.uniform(-np.pi, np.pi, sel.size)
        error = rng.uniform(-1.0, 1.0, sel.size) * self.initial_heading_error
        self.target[sel] = target
        return {"heading": target + error}

    def reference_direction(self) -> np.ndarray:
        """The target headings ψ_d (envs,) [rad]."""
        return self.target

    def _evaluate(self, out, rudder, previous_rudder):
        error = wrap(out["heading"] - self.target)
        obs = np.stack([error, out["yaw_rate"], out["surge_speed"], out["sway_speed"], rudder],
                       axis=1)
        failed = np.abs(error) > self.max_heading_error
        terms = self._common_terms(out, rudder, previous_rudder)
        terms["heading"] = _bell(error, self.heading_scale)
        terms["failure"] = -failed.astype(float)
        return obs, terms, failed, np.zeros(self.n, dtype=bool)


class PathFollowing(Task):
    """Follow a route of straight legs: cross-track error e to the current leg.

    The route is a polyline of waypoints (north, east) [m], default four waypoints 0, 20 L,
    (40 L, 10 L), (60 L, 10 L) along north (two turns of 26.6°). A leg is done when the ship's
    along-track distance passes the leg's length; the episode ends (without failure) after the
    last leg. Each episode starts the ship on the approach at the first waypoint moved across
    the first leg by a cross-track offset uniform in ±``initial_cross_track`` and a heading
    error uniform in ±``initial_heading_error``.

    Observations: the cross-track error e [m] (positive: the route is to port, the ship to
    starboard of it), the heading error to the leg's direction [rad], yaw rate, speeds, the
    rudder command and the turn to the next leg [rad] (0 on the last).

    Parameters
    ----------
    route : array_like (waypoints, 2), optional
        Waypoints (north, east) [m], at least two, consecutive ones apart.
    cross_track_scale : float, optional
        σ_e [m] (default L/2).
    max_cross_track : float, optional
        A cross-track error above it fails the episode [m] (default 5 L).
    initial_cross_track : float, optional
        [m] (default L/2).
    initial_heading_error : float
        [rad] (default 20°).
    **kw
        Of :class:`Task`.
    """

    name = "PathFollowing"
    observation_labels = ("cross_track_error", "heading_error", "yaw_rate", "surge_speed",
                          "sway_speed", "rudder_command", "next_turn")
    observation_units = ("m", "rad", "rad/s", "m/s", "m/s", "rad", "rad")
    default_weights = {"cross_track": 1.0, "heading": 0.2, "yaw_rate": 0.1, "rudder": 0.05,
                       "rudder_rate": 0.05, "failure": 50.0}
    default_episode_seconds = 400.0
    reads = ("north", "east", "heading", "yaw_rate", "surge_speed", "sway_speed")

    def __init__(self, num_envs: int, *, route: Any = None, cross_track_scale: float | None = None,
                 max_cross_track: float | None = None, initial_cross_track: float | None = None,
                 initial_heading_error: float = math.radians(20.0), **kw: Any) -> None:
        super().__init__(num_envs, **kw)
        L = self.length
        if route is None:
            route = np.array([[0.0, 0.0], [20.0, 0.0], [40.0, 10.0], [60.0, 10.0]]) * L
        wp = np.asarray(route, dtype=float)
        if wp.ndim != 2 or wp.shape[1] != 2 or wp.shape[0] < 2 or not np.isfinite(wp).all():
            raise ParameterError(f"must be finite waypoints (north, east) [m] of shape "
                                 f"(waypoints >= 2, 2), got shape {wp.shape}", field="route",
                                 unit="m", value=wp.shape)
        d = np.diff(wp, axis=0)
        self.leg_length = np.hypot(d[:, 0], d[:, 1])
        if (self.leg_length <= 0).any():
            i = int(np.argmax(self.leg_length <= 0))
            raise ParameterError(f": waypoints {i} and {i + 1} coincide", field="route",
                                 unit="m", value=wp[i].tolist())
        self.route = wp
        self.leg_angle = np.arctan2(d[:, 1], d[:, 0])
        self.turn = np.append(wrap(np.diff(self.leg_angle)), 0.0)
        self.cross_track_scale = _positive("cross_track_scale", cross_track_scale or L / 2, "m")
        self.max_cross_track = _positive("max_cross_track", max_cross_track or 5 * L, "m")
        self.initial_cross_track = float(L / 2 if initial_cross_track is None
                                         else initial_cross_track)
        self.initial_heading_error = float(initial_heading_error)
        self.leg = np.zeros(num_envs, dtype=np.int64)

    def _draw(self, sel: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
        self.leg[sel] = 0
        offset = rng.uniform(-1.0, 1.0, sel.size) * self.initial_cross_track
        error = rng.uniform(-1.0, 1.0, sel.size) * self.initial_heading_error
        a = self.leg_angle[0]
        return {"north": self.route[0, 0] - offset * math.sin(a),
                "east": self.route[0, 1] + offset * math.cos(a), "heading": a + error}

    def reference_direction(self) -> np.ndarray:
        """The current legs' directions (envs,) [rad]."""
        return self.leg_angle[self.leg]

    def _along_across(self, out):
        k = self.leg
        a = self.leg_angle[k]
        dn = out["north"] - self.route[k, 0]
        de = out["east"] - self.route[k, 1]
        along = dn * np.cos(a) + de * np.sin(a)
        across = -dn * np.sin(a) + de * np.cos(a)
        return along, across

    def _evaluate(self, out, rudder, previous_rudder):
        along, across = self._along_across(out)
        last = self.leg_length.size - 1
        passed = along > self.leg_length[self.leg]
        advance = passed & (self.leg < last)
        if advance.any():  # (one leg a step is plenty at one action a second)
            self.leg[advance] += 1
            along, across = self._along_across(out)
        done = passed & ~advance & (self.leg == last)
        error = wrap(out["heading"] - self.leg_angle[self.leg])
        obs = np.stack([across, error, out["yaw_rate"], out["surge_speed"], out["sway_speed"],
                        rudder, self.turn[self.leg]], axis=1)
        failed = np.abs(across) > self.max_cross_track
        terms = self._common_terms(out, rudder, previous_rudder)
        terms["cross_track"] = _bell(across, self.cross_track_scale)
        terms["heading"] = _bell(error, self.heading_scale)
        terms["failure"] = -failed.astype(float)
        return obs, terms, failed, done


#: The tasks by name (``gymnasium.make("seahelm/<name>-v0")``).
TASKS: dict[str, type[Task]] = {t.name: t for t in (HeadingKeeping, PathFollowing)}
