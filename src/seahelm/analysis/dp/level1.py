"""DP station-keeping capability, level 1 (quasi-static), after DNV-ST-0111's method.

For each environment direction θ (relative to the bow, 0 head-on, positive from starboard)
and each failure case (intact, each thruster lost in turn), the capability is the largest
wind speed U [m/s, 10 m] whose mean environmental load the constrained allocation
(:class:`seahelm.control.dp_allocation.ConstrainedAllocation`, static: the best convex piece
of each azimuth's allowed arcs) balances with no demand unmet: τ_c = −(F_wind + F_drift +
F_current). U is found by bisection (the loads grow with U) within the wind speeds of the
Beaufort table below.

Environment (collinear wind, waves and current from θ). DNV-ST-0111's own Beaufort table
(wind, Hs, Tz and current per Beaufort number) was not reachable from here, so:

* **wind**: the WMO Beaufort scale's upper wind speed of each number (WMO-No. 306 / the
  WMO Manual on Codes; 10 m, 10-min mean): :data:`BEAUFORT_WIND`; the search stops at
  Beaufort 11's 32.6 m/s.
* **waves**: a fully developed Pierson–Moskowitz sea, Hs = 0.21 U₁₉.₅²/g and
  ω_p = 0.877 g/U₁₉.₅ (Pierson & Moskowitz 1964, J. Geophys. Res. 69(24)), with
  U₁₉.₅ = U (19.5/10)^{1/7} (the 1/7 power law of the wind profile).
* **current**: a constant speed (``current_speed``, default 0.5 m/s — seahelm's choice,
  not the standard's), from the same direction.

Loads (stated models):

* wind: Blendermann (1994) through :func:`seahelm.environment.blendermann.blendermann_wind_loads`
  with the vessel's windage;
* mean wave drift: the fully reflecting vertical wall bound ρ g ζ_a²/2 per unit length in
  regular waves (Faltinsen 1990, *Sea loads on ships and offshore structures*, ch. 5), with
  the irregular-sea mean ζ_a² = Hs²/8: X = −(ρ g Hs²/16) B cos θ, Y = −(ρ g Hs²/16) L sin θ,
  no yaw moment (an upper bound on the drift force; a vessel's drift coefficients replace it);
* current: quadratic cross-flow drag, X = −½ ρ v² B T C_x cos θ abs(cos θ),
  Y = −½ ρ v² L T C_y sin θ abs(sin θ), no moment, C_x = 0.1 and C_y = 1.0 (stated defaults).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...constants import GRAVITY, RHO_SEAWATER
from ...control.dp_allocation import ConstrainedAllocation, ThrusterLayout
from ...environment.blendermann import blendermann_wind_loads
from ...errors import ParameterError

__all__ = ["BEAUFORT_WIND", "DpVessel", "dp_vessel", "CapabilityResult", "level1_capability",
           "environment_loads", "sea_from_wind"]

#: WMO Beaufort scale: upper wind speed [m/s] (10 m) of Beaufort 0 … 11.
BEAUFORT_WIND: tuple[float, ...] = (0.2, 1.5, 3.3, 5.4, 7.9, 10.7, 13.8, 17.1, 20.7, 24.4,
                                    28.4, 32.6)


@dataclass(frozen=True)
class DpVessel:
    """What the level-1 capability needs of a vessel: thrusters, main dimensions, windage.

    Parameters
    ----------
    name : str
    layout : ThrusterLayout
    length, beam, draft : float
        Waterline length, beam, draft [m] (wave drift and current).
    frontal_area, lateral_area : float
        Projected wind areas above water [m²].
    lateral_centre : float
        Centre of the lateral wind area forward of midships [m].
    wind_type : str
        Blendermann vessel type.
    current_cx, current_cy : float
        Current drag coefficients [-].
    """

    name: str
    layout: ThrusterLayout
    length: float
    beam: float
    draft: float
    frontal_area: float
    lateral_area: float
    lateral_centre: float = 0.0
    wind_type: str = "offshore-supply-vessel"
    current_cx: float = 0.1
    current_cy: float = 1.0


def sea_from_wind(wind_speed: Any) -> tuple[np.ndarray, np.ndarray]:
    """Hs [m] and peak period Tp [s] of a fully developed Pierson–Moskowitz sea (see module).

    Parameters
    ----------
    wind_speed : array_like
        U [m/s] at 10 m.

    Returns
    -------
    hs, tp : numpy.ndarray
    """
    u195 = np.asarray(wind_speed, dtype=float) * (19.5 / 10.0) ** (1.0 / 7.0)
    hs = 0.21 * u195**2 / GRAVITY
    with np.errstate(divide="ignore"):
        tp = np.where(u195 > 0, 2.0 * math.pi * u195 / (0.877 * GRAVITY), 0.0)
    return hs, tp


def environment_loads(vessel: DpVessel, wind_speed: Any, direction: Any,
                      current_speed: float = 0.5, *, waves: bool = True) -> np.ndarray:
    """Mean environmental load (surge [N], sway [N], yaw [N·m]), shape (..., 3) (see module).

    Parameters
    ----------
    vessel : DpVessel
    wind_speed : array_like
        U [m/s].
    direction : array_like
        θ [rad], where the environment comes from, relative to the bow (positive starboard).
    current_speed : float, optional
        v [m/s].
    waves : bool, optional
        Include the mean wave drift (default True).
    """
    u, th = np.broadcast_arrays(np.asarray(wind_speed, dtype=float),
                                np.asarray(direction, dtype=float))
    w = blendermann_wind_loads(u, th, vessel.wind_type, frontal_area=vessel.frontal_area,
                               lateral_area=vessel.lateral_area,
                               length_overall=vessel.length,
                               lateral_centre=vessel.lateral_centre)
    out = np.stack([np.asarray(w[0]), np.asarray(w[1]), np.asarray(w[2])], axis=-1)
    c, s = np.cos(th), np.sin(th)
    if waves:
        hs, _ = sea_from_wind(u)
        q = RHO_SEAWATER * GRAVITY * hs**2 / 16.0
        out[..., 0] -= q * vessel.beam * c
        out[..., 1] -= q * vessel.length * s
    qc = 0.5 * RHO_SEAWATER * current_speed**2 * vessel.draft
    out[..., 0] -= qc * vessel.beam * vessel.current_cx * c * np.abs(c)
    out[..., 1] -= qc * vessel.length * vessel.current_cy * s * np.abs(s)
    return out


@dataclass
class CapabilityResult:
    """Level-1 capability: the largest wind speed held per direction and failure case."""

    vessel: str
    #: environment directions θ [rad], relative to the bow
    directions: np.ndarray
    #: case names: "intact", then "without <thruster>"
    cases: tuple
    #: largest wind speed held [m/s], shape (cases, directions); 0: not even calm held
    wind_speed: np.ndarray
    #: Beaufort number of that wind (the largest whose upper speed it reaches), same shape
    beaufort: np.ndarray
    current_speed: float
    assumptions: tuple = field(default_factory=tuple)


def _beaufort(u):
    edges = np.asarray(BEAUFORT_WIND)
    return np.searchsorted(edges, np.asarray(u) + 1e-12, side="right") - 1


def level1_capability(vessel: DpVessel, *, headings: int = 36, failures: Any = "each",
                      current_speed: float = 0.5, waves: bool = True,
                      iterations: int = 40, tolerance: float = 1e-7) -> CapabilityResult:
    """DNV-ST-0111-style level-1 capability rose (see module).

    Parameters
    ----------
    vessel : DpVessel
    headings : int, optional
        Directions over 360° (default 36, every 10°).
    failures : "each", "none" or sequence of str, optional
        Single failures: each thruster lost in turn (default), none, or the named thrusters.
    current_speed : float, optional
        v [m/s] (default 0.5, not the standard's value).
    waves : bool, optional
        Include the wave drift.
    iterations : int, optional
        Bisection steps (default 40: 32.6 m/s / 2⁴⁰).
    tolerance : float, optional
        Largest unmet demand counted as met, in the allocation's scaled units.

    Returns
    -------
    CapabilityResult
    """
    headings = int(headings)
    if headings < 1:
        raise ParameterError(f"must be ≥ 1 [-], got {headings}", field="headings",
                             unit="-", value=headings)
    if not (current_speed >= 0 and math.isfinite(current_speed)):
        raise ParameterError(f"must be ≥ 0 [m/s], got {current_speed!r}",
                             field="current_speed", unit="m/s", value=current_speed)
    if current_speed > 3.0:
        raise ParameterError(f"beyond the environment tables (≤ 3 m/s) "
                             f"[m/s], got {current_speed!r}", field="current_speed",
                             unit="m/s", value=current_speed)
    lay = vessel.layout
    if isinstance(failures, str) and failures == "each":
        lost = list(lay.names)
    elif isinstance(failures, str) and failures == "none":
        lost = []
    else:
        lost = list(failures)
    layouts = [("intact", lay)] + [(f"without {nm}", lay.without(nm)) for nm in lost]
    theta = np.arange(headings) * (2.0 * math.pi / headings)
    umax = BEAUFORT_WIND[-1]
    out = np.zeros((len(layouts), headings))
    for ci, (_, lyt) in enumerate(layouts):
        try:
            alloc = ConstrainedAllocation(lyt)
        except ParameterError:
            continue                                    # a failure that leaves rank < 3
        scale = alloc.demand_scale

        def met(u):
            tau = -environment_loads(vessel, u, theta, current_speed, waves=waves)
            res = alloc.capacity(tau)
            return np.max(np.abs(res.unmet) * scale, axis=1) <= tolerance

        lo = np.zeros(headings)
        hi = np.full(headings, umax)
        ok_hi = met(hi)
        ok_lo = met(lo)
        for _ in range(int(iterations)):
            mid = 0.5 * (lo + hi)
            ok = met(mid)
            lo = np.where(ok, mid, lo)
            hi = np.where(ok, hi, mid)
        u = np.where(ok_hi, umax, lo)
        out[ci] = np.where(ok_lo, u, 0.0)
    assumptions = (
        "wind: WMO Beaufort scale upper speeds (DNV-ST-0111's table not reachable here)",
        "waves: fully developed Pierson-Moskowitz sea, Hs = 0.21 U19.5^2/g, U19.5 = U (1.95)^(1/7)",
        f"current: {current_speed} m/s collinear (seahelm's default, not DNV's)",
        "wave drift: fully reflecting wall bound rho g Hs^2/16 per unit projected length",
        "current load: quadratic drag, C_x = %g, C_y = %g" % (vessel.current_cx,
                                                            vessel.current_cy),
    )
    return CapabilityResult(vessel.name, theta, tuple(nm for nm, _ in layouts), out,
                            _beaufort(out), float(current_speed), assumptions)


def dp_vessel(ship: Any) -> DpVessel:
    """The DP vessel of a ship with thrusters: a catalog name, a ship file or a :class:`Ship`.

    The ship must declare its thrusters (a ship file's ``[[thrusters]]``) and its particulars
    (L, B, T and the windage areas, for the environment's loads). The catalog's DP vessels:
    ``supply`` (Fossen's supply vessel) and ``shushlyapin2017-dp`` (the seed paper's catamaran).

    Parameters
    ----------
    ship : str, path-like or Ship

    Returns
    -------
    DpVessel

    Raises
    ------
    ParameterError
        A ship without thrusters, or without the particulars the loads need (naming what is
        missing); an unknown name (listing the catalog).
    """
    from ...ships.catalog import get

    try:
        sh = get(ship)
    except ParameterError:
        raise
    except ValueError as exc:
        raise ParameterError(str(exc), field="SHIP", value=ship) from None
    if sh.thrusters is None:
        with_thrusters = _catalog_dp_ships()
        raise ParameterError(f"ship {sh.name!r} declares no thrusters ([[thrusters]] in its "
                             f"ship file); ships with thrusters: {', '.join(with_thrusters)}",
                             field="SHIP", value=sh.name)
    part = sh.particulars
    need = ("frontal_area", "lateral_area")
    missing = ["particulars"] if part is None else \
        [f"particulars.{n}" for n in need if getattr(part, n, None) is None]
    if missing:
        raise ParameterError(f"ship {sh.name!r} lacks {', '.join(missing)} (length, beam, "
                             "draft and windage areas [m, m²]: the environment's loads need "
                             "them)", field="SHIP", value=sh.name)
    return DpVessel(sh.name, sh.thrusters, float(part.length), float(part.beam),
                    float(part.draft), frontal_area=float(part.frontal_area),
                    lateral_area=float(part.lateral_area),
                    lateral_centre=float(part.windage_centre or 0.0),
                    wind_type=part.vessel_type or "offshore-supply-vessel")


def _catalog_dp_ships() -> tuple[str, ...]:
    """The catalog ships whose files declare thrusters (their TOML tables only)."""
    import tomllib

    from ...ships.catalog import DATA_DIR, names

    out = []
    for name in names():
        path = DATA_DIR / f"{name}.toml"
        if path.exists():
            with open(path, "rb") as fh:
                if "thrusters" in tomllib.load(fh):
                    out.append(name)
    return tuple(out)
