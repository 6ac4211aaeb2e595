"""Collision avoidance between controller intervals: a rule-based baseline and velocity
obstacles with COLREG constraints (Kuwata et al. 2014), vectorised over the batch.

A method is an object with ``start(n_encounters, n_vessels, avoid, encounter) -> state`` and
``desired(time, truth, view, route_heading, state) -> heading``: from each vessel's own true
state (encounters, vessels, 6: north, east, course, speed, heading, yaw rate), the AIS view of
every vessel (encounters, vessels, 5: north, east, course, speed, heading; NaN before the
first report), and the heading its route asks for (encounters, vessels) [rad], it gives the
heading to steer; only the vessels with ``avoid`` True are changed. Adding a method is a class
with these two methods and a line in :data:`AVOIDANCE`.

Both work on the pairs (encounters, own vessel i, other vessel j) at once, with the COLREG
situation of :func:`~seahelm.encounters.geometry.classify` of i's true state and j's reported
one.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from .._validate import lookup_name
from ..errors import ParameterError
from ._vo_search import vo_pick
from .geometry import (GIVE_WAY, STAND_ON, ColregSectors, Situation, classify, cpa_tcpa,
                       velocity, wrap_pi)

__all__ = ["AvoidanceMethod", "RuleBased", "VelocityObstacles", "StandOnRules", "AVOIDANCE",
           "resolve_avoidance"]


def _positive(obj: Any, *names_units: tuple[str, str]) -> None:
    for name, unit in names_units:
        v = getattr(obj, name)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {v!r}", field=f"avoidance.{name}",
                                 unit=unit, value=v)


def _pairs(own: np.ndarray, av: np.ndarray, view: np.ndarray):
    """The avoiding vessels' true position/velocity (e, a, 1, 2), every vessel's reported
    (e, 1, j, 2), and the pairs that count (e, a, j): j is another vessel that has been heard
    from. ``own`` is ``truth[:, av]``."""
    nv = view.shape[1]
    p_o = own[:, :, None, 0:2]
    v_o = velocity(own[:, :, 2], own[:, :, 3])[:, :, None, :]
    p_t = view[:, None, :, 0:2]
    v_t = velocity(view[:, :, 2], view[:, :, 3])[:, None, :, :]
    other = av[:, None] != np.arange(nv)[None, :]
    valid = np.isfinite(view).all(-1)[:, None, :] & other[None]
    return p_o, v_o, p_t, v_t, valid


def _situations(own: np.ndarray, view: np.ndarray, sectors: ColregSectors) -> np.ndarray:
    v = np.nan_to_num(view)
    return classify(own[:, :, None, 0:2], own[:, :, None, 4], v[:, None, :, 0:2],
                    v[:, None, :, 4], sectors)


@dataclasses.dataclass(frozen=True, kw_only=True)
class StandOnRules:
    """When and how a stand-on vessel may act on its own (COLREG Rule 17), for
    :class:`VelocityObstacles`.

    Rule 17(a)(i): the stand-on vessel keeps her course and speed. (a)(ii): she *may* act
    "as soon as it becomes apparent to her that the vessel required to keep out of the way is
    not taking appropriate action". (b): she *shall* act when "collision cannot be avoided by
    the action of the give-way vessel alone". (c): in a crossing situation she shall, "if the
    circumstances of the case admit, not alter course to port for a vessel on her own port
    side". The rules give no numbers; these are ours (stated, configurable):

    - *apparent* (17(a)(ii)): the pair has been at risk (the route's velocity inside the
      other's velocity obstacle) for ``observe`` seconds -- time for the give-way vessel to
      act -- and the give-way vessel has not acted (its reported course within
      ``alteration`` and its speed within ``speed_change`` of those it had when the risk
      was first seen), and still the CPA at the present velocities is closer than the
      method's ``radius`` with a TCPA below ``act_tcpa``;
    - *must act* (17(b)): the TCPA is below the method's ``emergency`` and the CPA at the
      present velocities closer than ``close``, whatever the time observed or the other
      did (a give-way vessel that is acting but too little, or too late);
    - *side* (17(c)): in a crossing situation, for a vessel on her port side (relative
      bearing 180° ... 360°) when she starts to act, no heading to port of her route's;
      otherwise (a vessel overtaking her, to which 17(c) does not apply: turning away from
      one on the quarter may turn into its path) no heading that would have the other pass
      on her other side than it passes when she starts to act (the sign of ``r × w``, line
      of sight × relative velocity, kept until the pair has passed: she does not cross the
      other's relative track, nor swing from one side to the other as the velocity obstacles
      alone did).

    Attributes
    ----------
    act_tcpa : float
        TCPA below which an unresolved risk makes the give-way's inaction apparent [s]
        (default 600 s, 10 min).
    observe : float
        Time a risk must have lasted before the give-way's inaction is apparent [s] (default
        120 s).
    alteration : float
        A change of the give-way's course larger than this is an action [rad] (default 10°).
    speed_change : float
        A relative change of the give-way's speed larger than this is an action [-] (default
        0.2).
    close : float
        CPA below which, with the TCPA below ``emergency``, the stand-on must act [m]
        (default 926 m, 0.5 nmi).
    keep_side : bool
        Apply the side rule above (default True; False: the velocity obstacles alone choose
        the side).

    References
    ----------
    IMO (1972, as amended). Convention on the International Regulations for Preventing
    Collisions at Sea (COLREG), Rule 17.
    """

    act_tcpa: float = 600.0
    observe: float = 120.0
    alteration: float = math.radians(10.0)
    speed_change: float = 0.2
    close: float = 926.0
    keep_side: bool = True

    def __post_init__(self) -> None:
        _positive(self, ("act_tcpa", "s"), ("alteration", "rad"), ("speed_change", "-"),
                  ("close", "m"))
        v = self.observe
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
            raise ParameterError(f"must be >= 0 [s], got {v!r}", field="avoidance.observe",
                                 unit="s", value=v)


class AvoidanceMethod:
    """What an avoidance method implements (:data:`AVOIDANCE` lists them): a frozen dataclass
    of its settings with :meth:`start` (its state for a batch) and :meth:`desired` (the heading
    each avoiding vessel steers next), called by the encounter's loop between controller
    intervals."""

    sectors: ColregSectors | None = None

    def start(self, n_encounters: int, n_vessels: int, avoid: np.ndarray,
              encounter: Any) -> dict[str, Any]:
        """The method's state for a batch.

        Parameters
        ----------
        n_encounters, n_vessels : int
            The batch's shape.
        avoid : ndarray of bool (vessels,)
            The vessels that avoid.
        encounter : Encounter
            The encounter (its ``sectors`` are the default).
        """
        raise NotImplementedError

    def desired(self, time: float, truth: np.ndarray, view: np.ndarray,
                route_heading: np.ndarray, state: dict[str, Any]) -> np.ndarray:
        """The heading each vessel steers next (the others keep ``route_heading``).

        Parameters
        ----------
        time : float
            Time [s].
        truth : ndarray (encounters, vessels, 6)
            Own true north, east [m], course [rad], speed [m/s], heading [rad], yaw rate
            [rad/s].
        view : ndarray (encounters, vessels, 5)
            The AIS view of every vessel (north, east, course, speed, heading; NaN unheard).
        route_heading : ndarray (encounters, vessels)
            The heading the route asks for [rad].
        state : dict
            From :meth:`start`, updated in place.

        Returns
        -------
        ndarray (encounters, vessels)
            Desired heading [rad].
        """
        raise NotImplementedError

    def _pair_state(self, n_encounters: int, n_vessels: int, avoid: np.ndarray,
                    encounter: Any) -> dict[str, Any]:
        """The state every method keeps: the avoiding vessels ``av``, the situation
        thresholds, and per pair the situation latched at first risk and whether the pair
        is engaged."""
        av = np.flatnonzero(avoid)
        return {"av": av, "sectors": self.sectors or encounter.sectors,
                "latched": np.zeros((n_encounters, av.size, n_vessels), dtype=np.int8),
                "engaged": np.zeros((n_encounters, av.size, n_vessels), dtype=bool)}


@dataclasses.dataclass(frozen=True, kw_only=True)
class RuleBased(AvoidanceMethod):
    """The baseline: turn to starboard by ``turn`` when give-way with a close CPA; resume.

    A vessel that is give-way to another (head-on, crossing from starboard, overtaking: Rules
    13-15) whose CPA (at the present velocities) is closer than ``dcpa`` within ``tcpa`` turns
    ``turn`` to starboard of its route's heading, and keeps that offset while steering its
    route would bring any vessel within ``dcpa`` again (a CPA at the route's velocity closer
    than ``dcpa`` and ahead in time); then it resumes the route. The situation of a pair is the
    one it had when its risk (CPA closer than ``dcpa`` within ``tcpa``) was first detected,
    kept until the pair has passed (TCPA < 0): a crossing target from port that draws ahead
    to starboard while passing does not make the stand-on vessel give way.

    Attributes
    ----------
    turn : float
        Course alteration to starboard [rad] (default 30°: large enough to be readily apparent,
        Rule 8(b)).
    dcpa : float
        CPA distance below which the give-way vessel acts [m] (default 1852 m, 1 nmi).
    tcpa : float
        Look-ahead [s] (default 1200 s).
    sectors : ColregSectors, optional
        The situation thresholds (default: those of the encounter).
    """

    turn: float = math.radians(30.0)
    dcpa: float = 1852.0
    tcpa: float = 1200.0
    sectors: ColregSectors | None = None

    def __post_init__(self) -> None:
        _positive(self, ("turn", "rad"), ("dcpa", "m"), ("tcpa", "s"))

    def start(self, n_encounters: int, n_vessels: int, avoid: np.ndarray,
              encounter: Any) -> dict[str, Any]:
        state = self._pair_state(n_encounters, n_vessels, avoid, encounter)
        return {**state, "active": np.zeros((n_encounters, state["av"].size), dtype=bool)}

    def desired(self, time: float, truth: np.ndarray, view: np.ndarray,
                route_heading: np.ndarray, state: dict[str, Any]) -> np.ndarray:
        av = state["av"]
        own, route = truth[:, av], route_heading[:, av]
        p_o, v_o, p_t, v_t, valid = _pairs(own, av, view)
        with np.errstate(invalid="ignore"):
            dcpa, tcpa = cpa_tcpa(p_o, v_o, p_t, v_t)
            risk = valid & (tcpa > 0) & (tcpa < self.tcpa) & (dcpa < self.dcpa)
            latched = np.where(valid & (tcpa > 0), state["latched"], 0)
            fresh = risk & (latched == 0)
            if fresh.any():  # (the situations only when a pair's risk is first seen)
                latched = np.where(fresh, _situations(own, view, state["sectors"]), latched)
            state["latched"] = latched.astype(np.int8)
            threat = risk & np.isin(latched, GIVE_WAY)
            v_route = velocity(route, own[:, :, 3])[:, :, None, :]
            d_r, t_r = cpa_tcpa(p_o, v_route, p_t, v_t)
            unsafe = valid & (t_r > 0) & (t_r < self.tcpa) & (d_r < self.dcpa)
        active = (state["active"] | threat.any(-1)) & unsafe.any(-1)
        state["active"] = active
        out = route_heading.copy()
        out[:, av] = np.where(active, route + self.turn, route)
        return out


@dataclasses.dataclass(frozen=True, kw_only=True)
class VelocityObstacles(AvoidanceMethod):
    """Velocity obstacles with COLREG constraints, after Kuwata et al. (2014).

    Every ``every`` seconds each avoiding vessel picks, from headings ``offsets`` about its
    route's heading at its present speed, the one closest to the route's that is

    - outside the velocity obstacle of every other vessel: not (``0 < TCPA < horizon`` and
      ``DCPA < radius``) for the relative motion at that velocity (the collision cone of
      Kuwata et al. 2014, truncated at the time horizon);
    - for a vessel to which it is give-way (head-on, crossing from starboard, overtaking) and
      whose velocity obstacle holds the route's velocity: on the COLREG side, passing with that
      vessel on its port side -- ``r × (v_own - v_other) ≥ 0`` with ``r`` the line of sight
      (north-east cross product): the COLREG constraint of Kuwata et al. (2014), which
      excludes the half plane of passing on the wrong side;
    - a stand-on vessel keeps its route (Rule 17(a)(i)) until the give-way vessel's inaction
      is apparent (17(a)(ii)) or the TCPA is shorter than ``emergency`` (17(b)), by the
      thresholds of ``stand_on`` (:class:`StandOnRules`); from then on it avoids that
      vessel until they have passed, never to port for a crossing vessel on its port side
      (17(c)), and otherwise letting the other pass on the side it passed when it started.

    Only headings within ``reach`` of the present one are candidates (a dynamic window: a
    large ship cannot turn through 150° at once). When every one is excluded, the one with the
    largest least DCPA is taken. Ties go to starboard. Against chattering (Kuwata et al. 2014 use hysteresis too): a pair's situation
    is latched when its risk first appears and kept until the pair has passed (TCPA at the
    present velocities < 0), and while a vessel is off its route the obstacles' radius is
    ``1 + hysteresis`` times larger (it returns to the route only with that margin).

    Attributes
    ----------
    horizon : float
        Time horizon of the obstacles [s] (default 1200 s).
    radius : float
        Combined safety radius [m] (default 1852 m, 1 nmi).
    offsets : tuple of float
        Candidate headings about the route's [rad] (default -60° ... 90° every 5°).
    every : float
        Time between decisions [s] (default 5 s); the heading is held in between.
    emergency : float
        TCPA below which a stand-on vessel acts too [s] (default 300 s; Rule 17(b)).
    hysteresis : float
        Relative margin on ``radius`` while off the route [-] (default 0.2).
    reach : float
        Candidates more than this from the present heading are not taken [rad] (default 60°:
        the reachable headings of a slow-turning ship, a dynamic window).
    sectors : ColregSectors, optional
    stand_on : StandOnRules
        When a stand-on vessel may act and to which side (default :class:`StandOnRules`).

    References
    ----------
    Kuwata, Y., Wolf, M. T., Zarzhitsky, D., Huntsberger, T. L. (2014). Safe maritime
    autonomous navigation with COLREGS, using velocity obstacles. IEEE Journal of Oceanic
    Engineering 39(1), 110-119.
    """

    horizon: float = 1200.0
    radius: float = 1852.0
    offsets: tuple[float, ...] = tuple(np.radians(np.arange(-60.0, 91.0, 5.0)).tolist())
    every: float = 5.0
    emergency: float = 300.0
    hysteresis: float = 0.2
    reach: float = math.radians(60.0)
    sectors: ColregSectors | None = None
    stand_on: StandOnRules = StandOnRules()

    def __post_init__(self) -> None:
        if not isinstance(self.stand_on, StandOnRules):
            raise ParameterError(f"must be a StandOnRules, got {type(self.stand_on).__name__}",
                                 field="avoidance.stand_on", value=self.stand_on)
        _positive(self, ("horizon", "s"), ("radius", "m"), ("every", "s"),
                  ("emergency", "s"), ("hysteresis", "-"), ("reach", "rad"))
        off = np.asarray(self.offsets, dtype=float)
        if off.ndim != 1 or off.size == 0 or not np.isfinite(off).all() or not (off == 0).any():
            raise ParameterError(f"must be finite headings [rad] including 0, got "
                                 f"{self.offsets!r}", field="avoidance.offsets", unit="rad")

    def start(self, n_encounters: int, n_vessels: int, avoid: np.ndarray,
              encounter: Any) -> dict[str, Any]:
        state = self._pair_state(n_encounters, n_vessels, avoid, encounter)
        shape = state["latched"].shape
        return {**state, "offset": np.zeros((n_encounters, n_vessels)), "next": 0.0,
                "since": np.full(shape, np.nan), "side": np.zeros(shape, dtype=np.int8),
                "seen": np.full((*shape, 2), np.nan)}

    def desired(self, time: float, truth: np.ndarray, view: np.ndarray,
                route_heading: np.ndarray, state: dict[str, Any]) -> np.ndarray:
        if time + 1e-9 >= state["next"]:
            state["next"] = time + self.every
            av = state["av"]
            state["offset"][:, av] = self._choose(time, truth[:, av], view,
                                                  route_heading[:, av], state)
        return route_heading + state["offset"]

    def _choose(self, time: float, own: np.ndarray, view: np.ndarray,
                route_heading: np.ndarray, state: dict[str, Any]) -> np.ndarray:
        """The offsets (e, a) of the avoiding vessels (``own = truth[:, av]``).

        The pairs' state (situation latched, Rule 17, the side) is numpy over (e, a, j); the
        candidates (e, a, c, j) are searched in one compiled pass (:mod:`._vo_search`)."""
        av = state["av"]
        p_o, _, p_t, v_t, valid = _pairs(own, av, view)  # (e, a, 1, 2), (e, 1, j, 2)
        off = np.asarray(self.offsets, dtype=float)
        i0 = int(np.flatnonzero(off == 0)[0])
        speed = own[:, :, 3]
        heading0 = route_heading + off[i0]  # (e, a): the route's candidate
        v0 = velocity(heading0, speed)[:, :, None, :]  # (e, a, 1, 2)
        radius = np.where(state["offset"][:, av] != 0.0, self.radius * (1.0 + self.hysteresis),
                          self.radius)  # (e, a)
        with np.errstate(invalid="ignore"):
            # the route's candidate for every pair: is it at risk?
            dcpa0, tcpa0 = cpa_tcpa(p_o, v0, p_t, v_t)  # (e, a, j)
            r = p_t - p_o  # (e, a, j, 2)
            rr = np.hypot(r[..., 0], r[..., 1])
            rad = radius[:, :, None]
            in_vo0 = ((tcpa0 > 0) & (tcpa0 < self.horizon) & (dcpa0 < rad)) | (
                (rr < rad) & (tcpa0 > 0))
            risk = in_vo0 & valid
            # the situation, latched from the first risk until the pair has passed
            v_now = velocity(own[:, :, 2], own[:, :, 3])[:, :, None, :]  # (e, a, 1, 2)
            d_now, t_now = cpa_tcpa(p_o, v_now, p_t, v_t)  # (e, a, j)
            now = _situations(own, view, state["sectors"])
            ahead = valid & (t_now > 0)
            latched = np.where(ahead, state["latched"], 0)
            fresh = risk & (latched == 0)
            latched = np.where(fresh, now, latched)
            state["latched"] = latched.astype(np.int8)
            since = np.where(ahead, state["since"], np.nan)
            since = np.where(fresh, time, since)
            state["since"] = since
            # the other's course and speed when the risk was first seen
            other = np.broadcast_to(view[:, None, :, 2:4], (*since.shape, 2))
            seen = np.where(fresh[..., None], other, state["seen"])
            state["seen"] = seen
            sit = np.where(latched == 0, now, latched)
            give_way = risk & np.isin(sit, GIVE_WAY)
            # Rule 17: a stand-on vessel acts once the give-way's inaction is apparent (a)(ii)
            # or in the emergency (b), and from then on until the pair has passed
            rule = self.stand_on
            stand_on = risk & np.isin(sit, STAND_ON)
            kept = ((np.abs(wrap_pi(other[..., 0] - seen[..., 0])) <= rule.alteration)
                    & (np.abs(other[..., 1] - seen[..., 1])
                       <= rule.speed_change * seen[..., 1]))
            apparent = ((time - since >= rule.observe) & kept & (d_now < self.radius)
                        & (t_now < rule.act_tcpa))
            before = state["engaged"] & (t_now > 0)
            must = (t_now < self.emergency) & (d_now < rule.close)
            engaged = before | (stand_on & (apparent | must))
            state["engaged"] = engaged
            calm_stand_on = valid & np.isin(sit, STAND_ON) & ~engaged
            # the side (17(c)): 2 starboard only (a crossing vessel on the port side);
            # +1 / -1 the other passing with r x w of that sign only; 0 free
            side = np.where(before, state["side"], 0)
            if rule.keep_side:
                port = (r[..., 1] * np.cos(own[:, :, 4, None])
                        - r[..., 0] * np.sin(own[:, :, 4, None])) < 0  # (e, a, j)
                crossing = sit == Situation.CROSSING_STAND_ON
                w0 = v_now - v_t  # (e, a, j, 2)
                passing = np.where(r[..., 0] * w0[..., 1] - r[..., 1] * w0[..., 0] < 0, -1, 1)
                start = engaged & ~before
                side = np.where(start, np.where(port & crossing, 2, passing), side)
            side = side.astype(np.int8)
            counted = valid & ~calm_stand_on
            # the route's candidate is taken where it is admissible (its cost, 0, the least):
            # not in a counted obstacle, not on the wrong side, not barred, within reach; the
            # other candidates are searched only where it is not
            s0 = v0 - v_t
            cross0 = r[..., 0] * s0[..., 1] - r[..., 1] * s0[..., 0]  # (e, a, j)
            bad0 = ((in_vo0 & counted) | ((cross0 < 0) & give_way)).any(-1)
            barred0 = (((side == 2) & (off[i0] < 0))
                       | ((np.abs(side) == 1) & (cross0 * side < 0))).any(-1)
            far0 = np.abs(wrap_pi(heading0 - own[:, :, 4])) > self.reach
        pick = np.full(speed.shape, i0)
        e = np.flatnonzero((bad0 | barred0 | far0).any(-1))  # (the encounters searched)
        if e.size:
            heading = route_heading[e, :, None] + off  # (e', a, c)
            sp = speed[e, :, None]
            far = np.abs(wrap_pi(heading - own[e, :, 4, None])) > self.reach
            far &= ~far.all(-1, keepdims=True)  # (none reachable: all are)
            c = np.ascontiguousarray  # (one compiled signature)
            pick[e] = vo_pick(sp * np.cos(heading), sp * np.sin(heading), c(p_o[e, :, 0]),
                              c(p_t[e, 0]), c(v_t[e, 0]), c(rr[e]), c(radius[e]),
                              float(self.horizon), c(valid[e]), c(counted[e]),
                              c(give_way[e]), c(side[e]), c(far), c(off))
        state["side"] = side
        return off[pick]


#: Avoidance methods by name.
AVOIDANCE: dict[str, type] = {"rule-based": RuleBased, "velocity-obstacles": VelocityObstacles}


def resolve_avoidance(method: Any) -> Any:
    """An avoidance method: by name (default settings), an object, or None.

    Parameters
    ----------
    method : str, object or None
        A name of :data:`AVOIDANCE` or an object with ``start`` and ``desired``.

    Returns
    -------
    object or None
    """
    if method is None:
        return None
    if isinstance(method, str):
        return lookup_name("avoidance method", AVOIDANCE, method, error=ParameterError,
                           field="avoidance", value=method)()
    if not (callable(getattr(method, "start", None)) and callable(getattr(method, "desired",
                                                                          None))):
        raise ParameterError(f"must be a name ({', '.join(AVOIDANCE)}) or an object with "
                             f"start() and desired(), got {type(method).__name__}",
                             field="avoidance", value=method)
    return method
