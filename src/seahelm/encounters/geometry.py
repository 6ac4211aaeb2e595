"""Encounter geometry: CPA/TCPA, relative bearing, the COLREG situation of a pair, ship domains.

Everything here is closed form and vectorised by numpy broadcasting: positions and velocities
are arrays whose last axis is (north, east) [m], [m/s]; every leading axis (a batch of
encounters, vessels, time) broadcasts. Angles are radians inside, measured clockwise from north
(headings) or from the bow (relative bearings), as in the NED frame of the vessel models.

Closest point of approach (straight-line motion)
------------------------------------------------
With the target's position relative to the own ship ``r = p_t - p_o`` and its relative
velocity ``w = v_t - v_o``, the distance ``|r + w t|`` is least at

    TCPA = -(r . w) / |w|^2,        DCPA = |r + w TCPA|

(``TCPA = 0``, ``DCPA = |r|`` when ``w = 0``: the range never changes). A negative TCPA means the
closest point is past (the pair is opening). This is the standard relation of radar plotting
(e.g. Lenart 1983, "Collision threat parameters for a new radar display and plot technique",
J. Navigation 36(3)).

COLREG situations (COLREGs 1972, Rules 13-15)
---------------------------------------------
From the own ship's view, with β the relative bearing of the target (from the own bow,
clockwise, in [0°, 360°)) and α the relative bearing of the own ship from the target's bow:

- **Rule 13 (overtaking)**: "a vessel shall be deemed to be overtaking when coming up with
  another vessel from a direction more than 22.5 degrees abaft her beam" — the stern sector
  ``112.5° < bearing < 247.5°`` (:attr:`ColregSectors.overtaking`, 22.5° by default). The own
  ship is *overtaking* when it is in the target's stern sector (α) and the target is not in
  its own (β); it is *being overtaken* in the converse case. Both in each other's stern sector:
  moving apart, no situation. Rule 13 applies "notwithstanding" Rules 14 and 15: it is tested
  first.
- **Rule 14 (head-on)**: "on reciprocal or nearly reciprocal courses ... when a vessel sees the
  other ahead or nearly ahead": each sees the other within ±θ of its bow, θ =
  :attr:`ColregSectors.head_on` (6° by default: the rule states no number; 6° is a common
  choice in the collision-avoidance literature and is a parameter here).
- **Rule 15 (crossing)**: otherwise, "the vessel which has the other on her own starboard side
  shall keep out of the way": target at ``0° < β ≤ 112.5°`` → own ship *give-way*; target at
  ``247.5° ≤ β < 360°`` → own ship *stand-on* (Rule 17). A target dead ahead (β = 0) that is not
  head-on is taken as on the starboard side (give-way: the cautious reading).

The rules are applied to each vessel's own view; the two views of a pair are mirror images
(a reflection of the whole geometry swaps port and starboard: give-way ↔ stand-on, checked in
the tests), but the rules do not force one give-way and one stand-on in every geometry (two
vessels 10° on each other's starboard bow are both give-way: both turn to starboard).

Ship domain
-----------
:class:`FujiiDomain`: the ellipse of Fujii & Tanaka (1971), "Traffic capacity", J. Navigation
24(4), 543-552: centred on the ship, major axis along its heading, axes 8 L × 3.2 L in open
water (semi-axes 4 L and 1.6 L); a target inside it is a domain intrusion (a near miss).
"""

from __future__ import annotations

import dataclasses
import enum
import math
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["Situation", "ColregSectors", "FujiiDomain", "cpa_tcpa", "relative_bearing",
           "classify", "classify_bearings", "velocity", "wrap_pi", "GIVE_WAY", "STAND_ON"]

_TWO_PI = 2.0 * math.pi


class Situation(enum.IntEnum):
    """The COLREG situation of a pair, from one vessel's view (codes stored in results)."""

    NONE = 0           #: no situation (moving apart: each in the other's stern sector)
    HEAD_ON = 1        #: Rule 14: both alter to starboard
    CROSSING_GIVE_WAY = 2  #: Rule 15: the other is on the starboard side: keep out of the way
    CROSSING_STAND_ON = 3  #: Rule 15/17: the other is on the port side: keep course and speed
    OVERTAKING = 4     #: Rule 13: this vessel overtakes: keep out of the way
    OVERTAKEN = 5      #: Rule 13/17: this vessel is overtaken: keep course and speed


#: Situations in which this vessel must keep out of the way (Rules 13, 14, 15, 16).
GIVE_WAY = (Situation.HEAD_ON, Situation.CROSSING_GIVE_WAY, Situation.OVERTAKING)
#: Situations in which this vessel must keep course and speed (Rule 17).
STAND_ON = (Situation.CROSSING_STAND_ON, Situation.OVERTAKEN)


def wrap_pi(angle: Any) -> np.ndarray:
    """Angles wrapped to [-π, π) [rad].

    Parameters
    ----------
    angle : array_like
        Angles [rad].
    """
    return (np.asarray(angle, dtype=float) + math.pi) % _TWO_PI - math.pi


def _wrap_2pi(angle: Any) -> np.ndarray:
    return np.asarray(angle, dtype=float) % _TWO_PI


def velocity(course: Any, speed: Any) -> np.ndarray:
    """The (north, east) velocity [m/s] of a course over ground and a speed.

    Parameters
    ----------
    course : array_like
        Course over ground [rad] (clockwise from north).
    speed : array_like
        Speed over ground [m/s].

    Returns
    -------
    ndarray (..., 2)
    """
    course = np.asarray(course, dtype=float)
    speed = np.asarray(speed, dtype=float)
    return np.stack([speed * np.cos(course), speed * np.sin(course)], axis=-1)


def cpa_tcpa(own_position: Any, own_velocity: Any, target_position: Any,
             target_velocity: Any) -> tuple[np.ndarray, np.ndarray]:
    """Distance and time of the closest point of approach of two straight-line motions.

    Parameters
    ----------
    own_position, target_position : array_like (..., 2)
        (north, east) [m].
    own_velocity, target_velocity : array_like (..., 2)
        (north, east) [m/s]. Leading axes broadcast (a batch, time).

    Returns
    -------
    dcpa : ndarray (...)
        Distance at the closest point of approach [m].
    tcpa : ndarray (...)
        Time to it [s] from now (negative: past, the pair is opening; 0 when the relative
        velocity is zero).

    Notes
    -----
    ``TCPA = -(r·w)/|w|²``, ``DCPA = |r + w·TCPA|`` with ``r = p_t - p_o``, ``w = v_t - v_o``
    (module notes).
    """
    r = np.asarray(target_position, dtype=float) - np.asarray(own_position, dtype=float)
    w = np.asarray(target_velocity, dtype=float) - np.asarray(own_velocity, dtype=float)
    if r.shape[-1:] != (2,) or w.shape[-1:] != (2,):
        raise ParameterError(f"positions and velocities must end in an axis of 2 (north, "
                             f"east), got {r.shape} and {w.shape}", field="position")
    ww = w[..., 0] * w[..., 0] + w[..., 1] * w[..., 1]
    rw = r[..., 0] * w[..., 0] + r[..., 1] * w[..., 1]
    moving = ww > 0.0
    tcpa = np.where(moving, -rw / np.where(moving, ww, 1.0), 0.0)
    dn = r[..., 0] + w[..., 0] * tcpa
    de = r[..., 1] + w[..., 1] * tcpa
    return np.hypot(dn, de), tcpa


def relative_bearing(own_position: Any, own_heading: Any, target_position: Any) -> np.ndarray:
    """Bearing of the target from the own bow, clockwise, in [0, 2π) [rad].

    Parameters
    ----------
    own_position, target_position : array_like (..., 2)
        (north, east) [m].
    own_heading : array_like (...)
        Own heading [rad] (clockwise from north).
    """
    r = np.asarray(target_position, dtype=float) - np.asarray(own_position, dtype=float)
    true_bearing = np.arctan2(r[..., 1], r[..., 0])
    return _wrap_2pi(true_bearing - np.asarray(own_heading, dtype=float))


@dataclasses.dataclass(frozen=True, kw_only=True)
class ColregSectors:
    """The thresholds of the COLREG situations (module notes).

    Attributes
    ----------
    head_on : float
        Half-width θ of "ahead or nearly ahead" of Rule 14 [rad] (default 6°), in (0°, 22.5°].
    overtaking : float
        How far abaft the beam the stern sector of Rule 13 begins [rad] (default 22.5°, the
        rule's number), in [0°, 90°).
    """

    head_on: float = math.radians(6.0)
    overtaking: float = math.radians(22.5)

    def __post_init__(self) -> None:
        for name, lo, hi, lo_open, hi_open in (("head_on", 0.0, 22.5, True, False),
                                              ("overtaking", 0.0, 90.0, False, True)):
            v = getattr(self, name)
            deg = math.degrees(v) if isinstance(v, (int, float)) else math.nan
            ok = (lo < deg if lo_open else lo <= deg) and (deg < hi if hi_open else deg <= hi)
            if not ok:
                raise ParameterError(f"must be in {'(' if lo_open else '['}{lo:g}, {hi:g}"
                                     f"{')' if hi_open else ']'} [deg], got {deg!r} deg "
                                     f"({v!r} rad)", field=name, unit="rad", value=v)

    @property
    def stern_start(self) -> float:
        """Relative bearing where the stern sector starts, 90° + :attr:`overtaking` [rad]."""
        return 0.5 * math.pi + self.overtaking


def classify(own_position: Any, own_heading: Any, target_position: Any, target_heading: Any,
             sectors: ColregSectors | None = None) -> np.ndarray:
    """The COLREG situation of each pair from the own ship's view (:class:`Situation` codes).

    Parameters
    ----------
    own_position, target_position : array_like (..., 2)
        (north, east) [m].
    own_heading, target_heading : array_like (...)
        Headings [rad]. (The rules speak of headings and lights, so the bow direction is used,
        not the course over ground.)
    sectors : ColregSectors, optional
        The thresholds (default 6° head-on, 22.5° abaft the beam).

    Returns
    -------
    ndarray of int8 (...)
        :class:`Situation` codes.

    Notes
    -----
    Sector boundaries: the stern sector is open, ``stern_start < bearing < 2π - stern_start``
    ("more than 22.5° abaft the beam"); head-on is closed, ``|bearing| ≤ θ`` for both; the
    starboard side of Rule 15 is ``0 ≤ β ≤ stern_start``, the port side ``2π - stern_start ≤ β
    < 2π``. Order: Rule 13, then 14, then 15 (module notes).
    """
    beta = relative_bearing(own_position, own_heading, target_position)
    alpha = relative_bearing(target_position, target_heading, own_position)
    return classify_bearings(beta, alpha, sectors)


def classify_bearings(beta: Any, alpha: Any, sectors: ColregSectors | None = None) -> np.ndarray:
    """:func:`classify` from the two relative bearings (for a caller that has them).

    Parameters
    ----------
    beta : array_like (...)
        Relative bearing of the target from the own bow, in [0, 2π) [rad]
        (:func:`relative_bearing` of the own ship).
    alpha : array_like (...)
        Relative bearing of the own ship from the target's bow, in [0, 2π) [rad].
    sectors : ColregSectors, optional
        The thresholds (default 6° head-on, 22.5° abaft the beam).

    Returns
    -------
    ndarray of int8 (...)
        :class:`Situation` codes.
    """
    s = sectors or ColregSectors()
    beta, alpha = np.asarray(beta, dtype=float), np.asarray(alpha, dtype=float)
    lo, hi = s.stern_start, _TWO_PI - s.stern_start
    own_astern_of_target = (alpha > lo) & (alpha < hi)
    target_astern = (beta > lo) & (beta < hi)
    theta = s.head_on
    ahead_b = (beta <= theta) | (beta >= _TWO_PI - theta)
    ahead_a = (alpha <= theta) | (alpha >= _TWO_PI - theta)
    out = np.where(beta <= lo, Situation.CROSSING_GIVE_WAY, Situation.CROSSING_STAND_ON)
    out = np.where(ahead_a & ahead_b, Situation.HEAD_ON, out)
    out = np.where(own_astern_of_target & ~target_astern, Situation.OVERTAKING, out)
    out = np.where(target_astern & ~own_astern_of_target, Situation.OVERTAKEN, out)
    out = np.where(target_astern & own_astern_of_target, Situation.NONE, out)
    return np.asarray(out, dtype=np.int8)


@dataclasses.dataclass(frozen=True, kw_only=True)
class FujiiDomain:
    """The elliptical ship domain of Fujii & Tanaka (1971) (module notes).

    Attributes
    ----------
    along : float
        Semi-axis along the heading, in ship lengths (default 4.0: an 8 L major axis, open
        water; Fujii & Tanaka give 6 L × 1.6 L axes in harbours and channels).
    across : float
        Semi-axis athwartships, in ship lengths (default 1.6: a 3.2 L minor axis).
    """

    along: float = 4.0
    across: float = 1.6

    def __post_init__(self) -> None:
        for name in ("along", "across"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ParameterError(f"must be > 0 [ship lengths], got {v!r}", field=name,
                                     unit="ship lengths", value=v)

    def distance(self, own_position: Any, own_heading: Any, length: Any,
                 target_position: Any) -> np.ndarray:
        """The target's elliptical distance from the own ship: < 1 inside the domain [-].

        ``sqrt((x/a)² + (y/b)²)`` with ``(x, y)`` the target's position in the own body axes
        (forward, starboard) and ``a = along·L``, ``b = across·L``.

        Parameters
        ----------
        own_position, target_position : array_like (..., 2)
            (north, east) [m].
        own_heading : array_like (...)
            Own heading [rad].
        length : array_like
            Own ship's length L [m].
        """
        r = np.asarray(target_position, dtype=float) - np.asarray(own_position, dtype=float)
        psi = np.asarray(own_heading, dtype=float)
        c, s = np.cos(psi), np.sin(psi)
        x = c * r[..., 0] + s * r[..., 1]
        y = -s * r[..., 0] + c * r[..., 1]
        length = np.asarray(length, dtype=float)
        return np.hypot(x / (self.along * length), y / (self.across * length))

    def intruded(self, own_position: Any, own_heading: Any, length: Any,
                 target_position: Any) -> np.ndarray:
        """Whether the target is inside the own ship's domain (bool, ...).

        Parameters
        ----------
        own_position, target_position : array_like (..., 2)
            (north, east) [m].
        own_heading : array_like (...)
            Own heading [rad].
        length : array_like
            Own ship's length L [m].
        """
        return self.distance(own_position, own_heading, length, target_position) < 1.0
