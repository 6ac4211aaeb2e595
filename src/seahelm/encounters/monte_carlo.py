"""A Monte-Carlo of encounter geometry: relative bearing, range and CPA at detection, target
speed (and the target course they imply) as batch axes.

The own ship starts at the origin on course 0 (north) at speed ``U_o``. A target is drawn at
relative bearing β₀ and range R₀ ("at detection") with speed ``V_t`` and a signed CPA distance
``d`` (positive: the target passes ahead of / to starboard of the relative line of sight as
seen from the own ship, i.e. the relative velocity turned clockwise from the line of sight to
the target). Its course follows: the relative velocity ``w = v_t - v_o`` must point from the
target's position along the line that passes the own ship at distance ``|d|``, so ``w``'s
direction is that of ``-r₀`` turned by ``asin(d/R₀)``, and its length ``s`` solves
``|v_o + s·ŵ| = V_t``, ``s = -(v_o·ŵ) + sqrt((v_o·ŵ)² - U_o² + V_t²)`` (the target closes:
``s > 0``). Geometries without a real positive root (a target too slow to close from that
bearing) are drawn again.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .encounter import Vessel

__all__ = ["sample_geometry", "monte_carlo_vessels"]


def _range(name: str, value: Any, unit: str, lo: float = -math.inf) -> tuple[float, float]:
    a = np.atleast_1d(np.asarray(value, dtype=float))
    if a.size == 1:
        a = np.array([a[0], a[0]])
    if a.shape != (2,) or not np.isfinite(a).all() or a[0] > a[1] or a[0] < lo:
        raise ParameterError(f"must be a value or a range (low, high) with low >= {lo:g} "
                             f"[{unit}], got {value!r}", field=name, unit=unit, value=value)
    return float(a[0]), float(a[1])


def sample_geometry(n: int, *, own_speed: float, bearing: Any = (0.0, 2 * math.pi),
                    detection_range: Any = 11112.0, target_speed: Any = (3.0, 9.0),
                    dcpa: Any = (-926.0, 926.0), tcpa: Any = (0.0, math.inf),
                    seed: int | None = None) -> dict[str, np.ndarray]:
    """Draw ``n`` target geometries uniformly in the given ranges (module notes).

    Parameters
    ----------
    n : int
        Encounters.
    own_speed : float
        U_o [m/s].
    bearing : float or (low, high)
        Relative bearing β₀ of the target at detection [rad] (default all round).
    detection_range : float or (low, high)
        R₀ [m] (default 11112 m, 6 nmi).
    target_speed : float or (low, high)
        V_t [m/s] (default 3 ... 9).
    dcpa : float or (low, high)
        Signed CPA distance at detection [m] (default ±926 m, ±0.5 nmi).
    tcpa : (low, high)
        Keep only geometries whose TCPA at detection is in this range [s] (default all).
    seed : int, optional

    Returns
    -------
    dict
        ``bearing``, ``range``, ``target_speed``, ``dcpa`` (as drawn), ``north``, ``east``
        [m], ``course`` [rad] of the target, ``tcpa`` [s].
    """
    if not (isinstance(n, int) and n >= 1):
        raise ParameterError(f"must be an integer >= 1, got {n!r}", field="n", value=n)
    if not (math.isfinite(own_speed) and own_speed > 0):
        raise ParameterError(f"must be > 0 [m/s], got {own_speed!r}", field="own_speed",
                             unit="m/s", value=own_speed)
    b = _range("bearing", bearing, "rad")
    r = _range("detection_range", detection_range, "m", 0.0)
    v = _range("target_speed", target_speed, "m/s", 0.0)
    d = _range("dcpa", dcpa, "m")
    t_lo, t_hi = (float(tcpa[0]), float(tcpa[1])) if np.ndim(tcpa) == 1 and len(tcpa) == 2 \
        else (math.nan, math.nan)
    if not (t_lo >= 0 and t_hi > t_lo):
        raise ParameterError(f"must be a range (low, high) with 0 <= low < high [s], got "
                             f"{tcpa!r}", field="tcpa", unit="s", value=tcpa)
    if max(abs(d[0]), abs(d[1])) >= r[0]:
        raise ParameterError(f"|dcpa| must be smaller than the detection range ({r[0]:g} m) "
                             f"[m], got {dcpa!r}", field="dcpa", unit="m", value=dcpa)
    rng = np.random.default_rng(seed)
    out: dict[str, list[np.ndarray]] = {k: [] for k in ("bearing", "range", "target_speed",
                                                        "dcpa", "north", "east", "course",
                                                        "tcpa")}
    have, tries = 0, 0
    while have < n:
        tries += 1
        if tries > 100:
            raise ParameterError(": no target in these ranges can close on the own ship "
                                 "(target_speed too low for the bearings, or no TCPA in range) [m/s]",
                                 field="target_speed", unit="m/s", value=target_speed)
        m = 2 * (n - have) + 16
        beta = rng.uniform(*b, m)
        r0 = rng.uniform(*r, m)
        vt = rng.uniform(*v, m)
        dc = rng.uniform(*d, m)
        pn, pe = r0 * np.cos(beta), r0 * np.sin(beta)
        turn = np.arcsin(dc / r0)
        ang = np.arctan2(-pe, -pn) + turn  # direction of w: -r0 turned clockwise by asin(d/R0)
        wn, we = np.cos(ang), np.sin(ang)
        vo_w = own_speed * wn
        disc = vo_w ** 2 - own_speed ** 2 + vt ** 2
        with np.errstate(invalid="ignore"):
            s = -vo_w + np.sqrt(disc)
        ok = (disc >= 0) & (s > 1e-6)
        vn, ve = own_speed + s * wn, s * we
        course = np.arctan2(ve, vn)
        t_cpa = r0 * np.cos(turn) / np.where(ok, s, 1.0)
        ok &= (t_cpa >= t_lo) & (t_cpa <= t_hi)
        for key, val in (("bearing", beta), ("range", r0), ("target_speed", vt), ("dcpa", dc),
                         ("north", pn), ("east", pe), ("course", course), ("tcpa", t_cpa)):
            out[key].append(val[ok])
        have += int(ok.sum())
    return {k: np.concatenate(vals)[:n] for k, vals in out.items()}


def monte_carlo_vessels(n: int, *, own_ship: Any, target_ship: Any, own_speed: float | None = None,
                        seed: int | None = None, targets_avoid: bool = False,
                        **ranges: Any) -> tuple[list[Vessel],
                                                                         dict[str, np.ndarray]]:
    """The vessels of ``n`` drawn encounters: the own ship (avoiding) and one target.

    Parameters
    ----------
    n : int
        Encounters.
    own_ship, target_ship : Ship or str
        The ships.
    own_speed : float, optional
        U_o [m/s] (default the own ship's approach speed).
    seed : int, optional
    targets_avoid : bool, optional
        The target runs the encounter's avoidance too (default False: it keeps its course).
    **ranges
        ``bearing``, ``detection_range``, ``target_speed``, ``dcpa`` of :func:`sample_geometry`.

    Returns
    -------
    (vessels, geometry)
        The two :class:`~seahelm.encounters.encounter.Vessel` and the drawn geometry.
    """
    from ..ships import Ship, get_ship

    ship = own_ship if isinstance(own_ship, Ship) else get_ship(own_ship)
    speed = round(float(own_speed if own_speed is not None else ship.approach_speed), 2)
    geo = sample_geometry(n, own_speed=speed, seed=seed, **ranges)
    own = Vessel(ship=ship, north=0.0, east=0.0, course=0.0, speed=speed, avoid=True,
                 name="own")
    target = Vessel(ship=target_ship, north=geo["north"], east=geo["east"],
                    course=geo["course"], speed=np.round(geo["target_speed"], 2),
                    avoid=bool(targets_avoid), name="target")
    return [own, target], geo
