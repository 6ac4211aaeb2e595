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

Overtaking (Rule 13) closes slowly and from narrow sectors, so a draw all round with one own
speed has almost none (the own ship at its service speed: no target slower than it ever
closes from astern). A share ``overtaking`` of the draws is therefore made as overtaking
geometries, half each way, at ranges ``overtaking_range`` (closer: they close at a few m/s):

- **own ship overtaking**: the target ahead (β₀ within ±22.5° of the bow) at 0.3 ... 0.7 of the
  own speed, on the course of the *smaller* root ``s = -(v_o·ŵ) - sqrt(...)`` (the target
  going the own ship's way, overtaken by it: a faster own ship);
- **own ship overtaken**: the target astern (β₀ within ±22.5° of the stern) and the own ship
  at half its speed ``U_o/2`` (rounded to 0.01 m/s), the target at 1.5 ... 2 times that.

Which COLREG situation a draw is follows from its geometry (:func:`~.geometry.classify`), not
from how it was drawn. Without ``overtaking`` (the default) the draws are those of before.
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
                    overtaking: float = 0.0, overtaking_range: Any = None,
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
    overtaking : float, optional
        Share of the draws made as overtaking geometries (module notes; default 0).
    overtaking_range : float or (low, high), optional
        R₀ of those [m] (default ``detection_range``).
    seed : int, optional

    Returns
    -------
    dict
        ``bearing``, ``range``, ``target_speed``, ``dcpa`` (as drawn), ``north``, ``east``
        [m], ``course`` [rad] of the target, ``tcpa`` [s], ``own_speed`` [m/s] and ``kind``
        (0 all round, 1 drawn as the own ship overtaking, 2 as overtaken).
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
    if not (isinstance(overtaking, (int, float)) and 0.0 <= overtaking <= 1.0):
        raise ParameterError(f"must be a share in 0 ... 1 [-], got {overtaking!r}",
                             field="overtaking", unit="-", value=overtaking)
    ro = r if overtaking_range is None else _range("overtaking_range", overtaking_range, "m",
                                                   0.0)
    if overtaking > 0 and max(abs(d[0]), abs(d[1])) >= ro[0]:
        raise ParameterError(f"|dcpa| must be smaller than the overtaking range ({ro[0]:g} m) "
                             f"[m], got {dcpa!r}", field="dcpa", unit="m", value=dcpa)
    if max(abs(d[0]), abs(d[1])) >= r[0]:
        raise ParameterError(f"|dcpa| must be smaller than the detection range ({r[0]:g} m) "
                             f"[m], got {dcpa!r}", field="dcpa", unit="m", value=dcpa)
    rng = np.random.default_rng(seed)
    n_over = int(round(overtaking * n))
    counts = (n - n_over, n_over - n_over // 2, n_over // 2)  # all round, overtaking, overtaken
    parts = [_draw(rng, k, c, own_speed, b, r if k == 0 else ro, v, d, (t_lo, t_hi),
                   target_speed) for k, c in enumerate(counts) if c > 0]
    geo = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    if n_over:  # (mixed, so that the first encounters are not all of one kind)
        order = rng.permutation(n)
        geo = {k: val[order] for k, val in geo.items()}
    return geo


def _draw(rng: np.random.Generator, kind: int, n: int, own_speed: float,
          b: tuple[float, float], r: tuple[float, float], v: tuple[float, float],
          d: tuple[float, float], t: tuple[float, float], target_speed: Any
          ) -> dict[str, np.ndarray]:
    """``n`` geometries of one kind (0 all round, 1 own ship overtaking, 2 overtaken; module
    notes), drawn again until they close within the TCPA range ``t``."""
    out: dict[str, list[np.ndarray]] = {k: [] for k in ("bearing", "range", "target_speed",
                                                        "dcpa", "north", "east", "course",
                                                        "tcpa", "own_speed", "kind")}
    u = own_speed if kind != 2 else round(0.5 * own_speed, 2)
    have, tries = 0, 0
    while have < n:
        tries += 1
        if tries > 100 and kind:
            raise ParameterError(f": no {'overtaking' if kind == 1 else 'overtaken'} geometry "
                                 f"at {r[0]:g} ... {r[1]:g} m closes within the TCPA range "
                                 f"({t[0]:g} ... {t[1]:g} s): a longer horizon or a shorter "
                                 "range [m]", field="overtaking_range", unit="m", value=r)
        if tries > 100:
            raise ParameterError(": no target in these ranges can close on the own ship "
                                 "(target_speed too low for the bearings, or no TCPA in range) [m/s]",
                                 field="target_speed", unit="m/s", value=target_speed)
        m = 2 * (n - have) + 16
        if kind == 0:
            beta = rng.uniform(*b, m)
            r0 = rng.uniform(*r, m)
            vt = rng.uniform(*v, m)
        else:
            sector = rng.uniform(-math.pi / 8, math.pi / 8, m)
            beta = sector % (2 * math.pi) if kind == 1 else math.pi + sector
            r0 = rng.uniform(*r, m)
            vt = u * (rng.uniform(0.3, 0.7, m) if kind == 1 else rng.uniform(1.5, 2.0, m))
        dc = rng.uniform(*d, m)
        pn, pe = r0 * np.cos(beta), r0 * np.sin(beta)
        turn = np.arcsin(dc / r0)
        ang = np.arctan2(-pe, -pn) + turn  # direction of w: -r0 turned clockwise by asin(d/R0)
        wn, we = np.cos(ang), np.sin(ang)
        vo_w = u * wn
        disc = vo_w ** 2 - u ** 2 + vt ** 2
        with np.errstate(invalid="ignore"):
            s = -vo_w + (-1.0 if kind == 1 else 1.0) * np.sqrt(disc)
        ok = (disc >= 0) & (s > 1e-6)
        vn, ve = u + s * wn, s * we
        course = np.arctan2(ve, vn)
        t_cpa = r0 * np.cos(turn) / np.where(ok, s, 1.0)
        ok &= (t_cpa >= t[0]) & (t_cpa <= t[1])
        for key, val in (("bearing", beta), ("range", r0), ("target_speed", vt), ("dcpa", dc),
                         ("north", pn), ("east", pe), ("course", course), ("tcpa", t_cpa),
                         ("own_speed", np.full(m, u)), ("kind", np.full(m, kind, np.int8))):
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
        ``bearing``, ``detection_range``, ``target_speed``, ``dcpa``, ``tcpa``,
        ``overtaking``, ``overtaking_range`` of :func:`sample_geometry`.

    Returns
    -------
    (vessels, geometry)
        The two :class:`~seahelm.encounters.encounter.Vessel` and the drawn geometry.
    """
    from ..ships import Ship, get_ship

    ship = own_ship if isinstance(own_ship, Ship) else get_ship(own_ship)
    speed = round(float(own_speed if own_speed is not None else ship.approach_speed), 2)
    geo = sample_geometry(n, own_speed=speed, seed=seed, **ranges)
    own = Vessel(ship=ship, north=0.0, east=0.0, course=0.0,
                 speed=speed if not (geo["kind"] == 2).any() else geo["own_speed"], avoid=True,
                 name="own")
    target = Vessel(ship=target_ship, north=geo["north"], east=geo["east"],
                    course=geo["course"], speed=np.round(geo["target_speed"], 2),
                    avoid=bool(targets_avoid), name="target")
    return [own, target], geo
