"""The collision-avoidance task of :mod:`seahelm.gym`: an own ship meets a target ship
(:mod:`seahelm.encounters`), what the own ship's agent observes, how it is rewarded, when its
episode ends. Vectorised over the encounters (numpy, no per-encounter loop).

Each episode is one encounter drawn by Monte-Carlo geometry
(:func:`seahelm.encounters.sample_geometry`): the own ship starts at the origin heading north
on its route (a straight track, course 0), the target at a relative bearing drawn all round, a
range of ``detection_range`` ship lengths and a CPA within ±``dcpa`` ship lengths, at its
approach speed, on a course that brings it there. The target keeps its course, or avoids by an
:mod:`~seahelm.encounters.avoidance` method (``target_avoidance="rule-based"``).

Observations
------------
Own: ``heading_error`` ψ − χ_route [rad], ``cross_track_error`` e [m] (to the route's track,
positive: the ship to starboard of it), ``yaw_rate`` [rad/s], ``surge_speed``, ``sway_speed``
[m/s], ``rudder_command`` [rad]. The target, as sensed (exact, every interval): its relative
bearing from the bow ``target_bearing`` in [−π, π) [rad], ``target_range`` [m], the CPA distance
``target_dcpa`` [m] and time ``target_tcpa`` [s] at the present velocities
(:func:`~seahelm.encounters.cpa_tcpa`), its heading relative to the own heading
``target_relative_heading`` [rad] and its ``target_speed`` over ground [m/s].

Reward
------
Σ weight · term over dimensionless terms, with L the own ship's length:

=================  ===================================================================  ======
term               value                                                                weight
=================  ===================================================================  ======
``collision``      −1 on the step the range falls below (L_own + L_target)/2              100
``domain``         −max(0, 1 − d), d the target's distance in the own ship's Fujii          1
                   domain (:class:`~seahelm.encounters.FujiiDomain`, < 1 inside)
``colreg_side``    −1 on a step where the own ship, give-way at the start (head-on or      0.5
                   crossing with the target to starboard, Rules 14-15), is turned more
                   than ``port_tolerance`` (5°) to port of its route before the CPA
``route``          −(1 − exp(−(e/σ_e)²)), e the cross-track error,                       0.2
                   σ_e = ``route_scale`` (default 2 L)
=================  ===================================================================  ======

The episode terminates at a collision (failed) or once the target has passed (TCPA < 0 and the
target outside the domain), and is truncated at ``episode_seconds``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

from ..encounters import FujiiDomain, classify, cpa_tcpa, relative_bearing, velocity
from ..encounters.geometry import Situation, wrap_pi
from ..errors import ParameterError
from .tasks import Weighted, reward_weights

__all__ = ["CollisionAvoidance"]

_GIVE_WAY_SIDE = (int(Situation.HEAD_ON), int(Situation.CROSSING_GIVE_WAY))


def _positive(name: str, value: Any, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not (math.isfinite(v) and v > 0):
        raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=name, unit=unit,
                             value=value)
    return v


def _range(name: str, value: Any, unit: str) -> tuple[float, float]:
    a = np.atleast_1d(np.asarray(value, dtype=float))
    if a.size == 1:
        a = np.array([a[0], a[0]])
    if a.shape != (2,) or not np.isfinite(a).all() or a[0] > a[1] or a[0] <= 0:
        raise ParameterError(f"must be a value or a range (low, high), 0 < low <= high "
                             f"[{unit}], got {value!r}", field=name, unit=unit, value=value)
    return float(a[0]), float(a[1])


class CollisionAvoidance(Weighted):
    """Meet a target ship without collision, clear of its domain, to starboard as the rules
    say, close to the route (module docstring: observations, reward table, episode end).

    Parameters
    ----------
    num_envs : int
        Encounters.
    own_length, target_length : float
        L_own, L_target [m].
    own_speed, target_speed : float
        Approach speeds [m/s].
    reward : mapping term -> weight, optional
        Weights (the terms not named keep :attr:`default_weights`).
    detection_range : float or (low, high)
        Range of the target at the start [own ship lengths] (default 12 ... 20).
    dcpa : float
        The CPA at the start is drawn in ±``dcpa`` [own ship lengths] (default 1: a collision
        course unless someone acts).
    route_scale : float, optional
        σ_e of the ``route`` term [m] (default 2 L).
    port_tolerance : float
        Turn to port [rad] the ``colreg_side`` term allows (default 5°).
    domain : FujiiDomain, optional
        The own ship's domain (default 4 L × 1.6 L semi-axes).
    """

    name: ClassVar[str] = "CollisionAvoidance"
    observation_labels: ClassVar[tuple[str, ...]] = (
        "heading_error", "cross_track_error", "yaw_rate", "surge_speed", "sway_speed",
        "rudder_command", "target_bearing", "target_range", "target_dcpa", "target_tcpa",
        "target_relative_heading", "target_speed")
    observation_units: ClassVar[tuple[str, ...]] = (
        "rad", "m", "rad/s", "m/s", "m/s", "rad", "rad", "m", "m", "s", "rad", "m/s")
    default_weights: ClassVar[dict[str, float]] = {"collision": 100.0, "domain": 1.0,
                                                   "colreg_side": 0.5, "route": 0.2}

    def __init__(self, num_envs: int, *, own_length: float, target_length: float,
                 own_speed: float, target_speed: float,
                 reward: Mapping[str, float] | None = None,
                 detection_range: Any = (12.0, 20.0), dcpa: float = 1.0,
                 route_scale: float | None = None, port_tolerance: float = math.radians(5.0),
                 domain: FujiiDomain | None = None) -> None:
        self.n = num_envs
        self.own_length, self.target_length = float(own_length), float(target_length)
        self.own_speed, self.target_speed = float(own_speed), float(target_speed)
        self.detection_range = _range("detection_range", detection_range, "ship lengths")
        self.dcpa = _positive("dcpa", dcpa, "ship lengths")
        if self.dcpa >= self.detection_range[0]:
            raise ParameterError(f"must be smaller than the detection range "
                                 f"({self.detection_range[0]:g} ship lengths) [ship lengths], "
                                 f"got {dcpa!r}", field="dcpa", unit="ship lengths", value=dcpa)
        L = self.own_length
        self.route_scale = _positive("route_scale", 2.0 * L if route_scale is None
                                     else route_scale, "m")
        self.port_tolerance = _positive("port_tolerance", port_tolerance, "rad")
        if domain is not None and not isinstance(domain, FujiiDomain):
            raise ParameterError(f"must be a FujiiDomain, got {type(domain).__name__}",
                                 field="domain", value=domain)
        self.domain = domain or FujiiDomain()
        self.touch = 0.5 * (self.own_length + self.target_length)
        self.weights = reward_weights(self.name, self.default_weights, reward)
        #: each encounter's own route course χ_route [rad] and the own ship's COLREG
        #: situation at the start (:class:`~seahelm.encounters.Situation` codes)
        self.route_course = np.zeros(num_envs)
        self.situation = np.zeros(num_envs, dtype=np.int8)

    def observation_bounds(self, episode_seconds: float, max_rudder: float
                           ) -> tuple[np.ndarray, np.ndarray]:
        """Bounds of the observations, (low, high) by :attr:`observation_labels` (bounds no
        run reaches, the angles' exact).

        Parameters
        ----------
        episode_seconds : float
            Episode length [s].
        max_rudder : float
            Largest rudder command [rad].

        Returns
        -------
        low, high : ndarray (observations,)
        """
        L, U, V = self.own_length, self.own_speed, self.target_speed
        far = 10.0 * (self.detection_range[1] * L + (U + V) * episode_seconds)
        high = np.array([math.pi, far, 10.0 * U / L, 10.0 * U, 10.0 * U, max_rudder, math.pi,
                         far, far, 100.0 * episode_seconds, math.pi, 10.0 * V])
        low = -high
        low[[7, 8, 11]] = 0.0
        return low, high

    def draw(self, n: int, rng: np.random.Generator) -> dict[str, np.ndarray]:
        """Draw ``n`` encounters' geometries (module docstring).

        Parameters
        ----------
        n : int
            Encounters.
        rng : numpy.random.Generator
            The draws' source (one seed taken from it).

        Returns
        -------
        dict
            The target's ``north``, ``east`` [m] and ``course`` [rad] (n,), the own ship at
            the origin heading north.
        """
        from ..encounters import sample_geometry

        L = self.own_length
        geo = sample_geometry(int(n), own_speed=self.own_speed,
                              detection_range=tuple(r * L for r in self.detection_range),
                              target_speed=self.target_speed,
                              dcpa=(-self.dcpa * L, self.dcpa * L),
                              seed=int(rng.integers(2 ** 63 - 1)))
        return {k: geo[k] for k in ("north", "east", "course")}

    def begin(self, sel: np.ndarray, own: np.ndarray, target: np.ndarray) -> None:
        """Start the episodes of ``sel``: their route and COLREG situation.

        Parameters
        ----------
        sel : ndarray of int
            The encounters starting.
        own, target : ndarray (len(sel), 6)
            Own and target (north, east, course, speed, heading, yaw rate) at the start.
        """
        self.route_course[sel] = own[:, 4]
        self.situation[sel] = classify(own[:, 0:2], own[:, 4], target[:, 0:2], target[:, 4],
                                       None)

    def evaluate(self, own: np.ndarray, target: np.ndarray, surge_sway: np.ndarray,
                 rudder: np.ndarray, start: np.ndarray
                 ) -> tuple[np.ndarray, dict[str, np.ndarray], np.ndarray, np.ndarray]:
        """Observations, reward terms and the end of the episodes.

        Parameters
        ----------
        own, target : ndarray (envs, 6)
            Own and target (north, east, course, speed, heading, yaw rate) [SI].
        surge_sway : ndarray (envs, 2)
            The own surge and sway speeds [m/s].
        rudder : ndarray (envs,)
            The own rudder commands [rad].
        start : ndarray (envs, 2)
            The own route's start (north, east) [m].

        Returns
        -------
        observations : ndarray (envs, observations)
        terms : dict
            Reward term name -> (envs,).
        collided, passed : ndarray of bool (envs,)
        """
        p_o, p_t = own[:, 0:2], target[:, 0:2]
        psi = own[:, 4]
        dcpa, tcpa = cpa_tcpa(p_o, velocity(own[:, 2], own[:, 3]), p_t,
                              velocity(target[:, 2], target[:, 3]))
        rng = np.hypot(p_t[:, 0] - p_o[:, 0], p_t[:, 1] - p_o[:, 1])
        bearing = wrap_pi(relative_bearing(p_o, psi, p_t))
        chi = self.route_course
        dn, de = p_o[:, 0] - start[:, 0], p_o[:, 1] - start[:, 1]
        across = -dn * np.sin(chi) + de * np.cos(chi)
        error = wrap_pi(psi - chi)
        obs = np.stack([error, across, own[:, 5], surge_sway[:, 0], surge_sway[:, 1], rudder,
                        bearing, rng, dcpa, tcpa, wrap_pi(target[:, 4] - psi), target[:, 3]],
                       axis=1)
        d = self.domain.distance(p_o, psi, self.own_length, p_t)
        collided = rng < self.touch
        passed = (tcpa < 0) & (d > 1.0) & ~collided
        give_way = np.isin(self.situation, _GIVE_WAY_SIDE)
        to_port = (tcpa > 0) & give_way & (error < -self.port_tolerance)
        terms = {"collision": -collided.astype(float),
                 "domain": -np.maximum(0.0, 1.0 - d),
                 "colreg_side": -to_port.astype(float),
                 "route": -(1.0 - np.exp(-(across / self.route_scale) ** 2))}
        return obs, terms, collided, passed
