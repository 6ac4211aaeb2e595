"""Waypoint routes and line-of-sight path following: proportional LOS and integral LOS.

A route is a polyline of waypoints p_0, …, p_{n−1} (north, east) [m]. Following segment k
(from p_k to p_{k+1}), with path-tangential angle π_k = atan2(E_{k+1} − E_k, N_{k+1} − N_k),
the along-track distance and the cross-track error of the ship at (N, E) are (Fossen 2021,
*Handbook of Marine Craft Hydrodynamics and Motion Control*, 2nd ed., §12.4, eq. 12.52)::

    x_e =  (N − N_k) cos π_k + (E − E_k) sin π_k
    y_e = −(N − N_k) sin π_k + (E − E_k) cos π_k      (positive: starboard of the path)

and the guidance laws give the heading to steer (§12.4.2):

* **LOS** (proportional): ψ_d = π_k − atan(y_e / Δ), with look-ahead distance Δ > 0;
* **ILOS** (integral LOS, Børhaug, Pavlov & Pettersen 2008; Fossen 2021 eq. 12.108–12.110):
  ψ_d = π_k − atan((y_e + κ y_int)/Δ), ẏ_int = Δ y_e / (Δ² + (y_e + κ y_int)²), κ > 0. The
  integral state removes the steady cross-track offset that a constant drift (current, wind)
  leaves under LOS; it is integrated at the controller's sample period (explicit Euler).
  y_int is in seconds and κ in m/s: linearised on a straight leg at speed U, the cross-track
  error obeys s² + (U/Δ) s + κU/Δ² = 0, critically damped at κ = U/4 (faster convergence needs
  a shorter look-ahead, not a larger κ).

The look-ahead may vary with the cross-track error, Δ(y_e) = (Δ_max − Δ_min) e^{−γ y_e²} + Δ_min
(Fossen 2021 eq. 12.76; ``lookahead`` = Δ_max, ``lookahead_min`` = Δ_min, ``lookahead_gamma``
= γ; constant when Δ_min = Δ_max, the default).

Waypoint switching: the active segment moves on to k + 1 when the ship is inside the
acceptance circle of p_{k+1} (radius R), or has passed the normal to the segment through
p_{k+1} (x_e ≥ segment length: a ship that misses the circle still goes on). After the last
waypoint the ship keeps to the extension of the last leg; the route counts as complete from
the moment the last waypoint is reached.

The laws are components of a guided heading controller
(:func:`seahelm.control.guided.guided`), which feeds ψ_d to any heading controller (PID,
compensated PID) as its heading reference and records ``heading_reference`` [rad],
``cross_track_error`` [m], ``along_track_distance`` [m] (along the active leg) and
``waypoint_index`` (the active leg's start, 0-based; n − 1 when the route is complete).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numba import njit

from .._validate import as_float_array, lookup_name
from ..errors import ParameterError
from ..parameters import Params, param, signal_indices

__all__ = ["MAX_WAYPOINTS", "GuidanceLaw", "RouteParams", "LOSParams", "ILOSParams", "LOS", "ILOS",
           "GUIDANCE_LAWS", "get_guidance_law", "route_params", "cross_track"]

#: Waypoints a route can hold (the route is a fixed-size vector parameter of the run).
MAX_WAYPOINTS = 32

GUIDANCE_STATES = ("segment", "integral", "complete")
GUIDANCE_OUTPUTS = ("heading_reference", "cross_track_error", "along_track_distance",
                    "waypoint_index")
GUIDANCE_OUTPUT_UNITS = ("rad", "m", "m", "")
GUIDANCE_MEASUREMENTS = ("north", "east")
_S = signal_indices(GUIDANCE_STATES)
_O = signal_indices(GUIDANCE_OUTPUTS)


@dataclasses.dataclass(frozen=True, kw_only=True)
class RouteParams(Params):
    """A route: waypoints and the acceptance circle (the fields every route follower has)."""

    route_north: tuple = param((0.0,) * MAX_WAYPOINTS, unit="m", symbol="N_k",
                               size=MAX_WAYPOINTS, doc="waypoint north coordinates (padded)")
    route_east: tuple = param((0.0,) * MAX_WAYPOINTS, unit="m", symbol="E_k",
                              size=MAX_WAYPOINTS, doc="waypoint east coordinates (padded)")
    n_waypoints: float = param(2.0, unit="-", symbol="n", low=2.0, high=float(MAX_WAYPOINTS),
                               doc="number of waypoints of the route")
    acceptance_radius: float = param(100.0, unit="m", symbol="R", low=0.0,
                                     low_inclusive=False, doc="waypoint acceptance circle")

    def validate(self) -> None:
        n = self.n_waypoints
        if n != int(n):
            raise ParameterError(f"`n_waypoints` must be a whole number [-], got {n!r}")
        pts = np.column_stack([self.route_north, self.route_east])[:int(n)]
        legs = np.hypot(*np.diff(pts, axis=0).T)
        if (legs == 0.0).any():
            k = int(np.argmax(legs == 0.0))
            raise ParameterError(
                f"route: waypoints {k} and {k + 1} are the same point ({pts[k, 0]:g}, "
                f"{pts[k, 1]:g}) [m]; consecutive waypoints must differ")
        longest = float(legs.max())
        if self.acceptance_radius >= longest:
            # every waypoint would be "reached" at once: the route would complete at t = 0
            raise ParameterError(
                f"must be shorter than the route's legs [m]: {self.acceptance_radius!r} >= the "
                f"longest leg, {longest:.6g} m (a waypoint inside its circle counts as "
                "reached, so the route would be complete at once)", field="acceptance_radius",
                unit="m", value=self.acceptance_radius)


@dataclasses.dataclass(frozen=True, kw_only=True)
class LOSParams(RouteParams):
    """A route and the proportional LOS law (module docstring)."""

    lookahead: float = param(500.0, unit="m", symbol="Δ", low=0.0, low_inclusive=False,
                             doc="look-ahead distance (Δ_max if it varies)")
    lookahead_min: float = param(0.0, unit="m", symbol="Δ_min", low=0.0,
                                 doc="smallest look-ahead distance (0: constant Δ)")
    lookahead_gamma: float = param(0.0, unit="1/m²", symbol="γ", low=0.0,
                                   doc="decay of the look-ahead with y_e² (0: constant Δ)")

    def validate(self) -> None:
        if self.lookahead_min > self.lookahead:
            raise ParameterError(
                f"`lookahead_min` must not exceed `lookahead` [m], got {self.lookahead_min!r} > "
                f"{self.lookahead!r}")
        super().validate()


@dataclasses.dataclass(frozen=True, kw_only=True)
class ILOSParams(LOSParams):
    """A route and the integral LOS law (module docstring)."""

    kappa: float = param(2.0, unit="m/s", symbol="κ", low=0.0, low_inclusive=False,
                         doc="integral gain of ILOS (critically damped near κ = U/4)")


def route_params(waypoints: Any, *, law: "GuidanceLaw | None" = None,
                 params_type: "type[RouteParams] | None" = None, **values: Any) -> Params:
    """The parameter set of a guidance law for a route given as a list of (north, east) points.

    Parameters
    ----------
    waypoints : array_like, shape (n, 2)
        Waypoints (north, east) [m], 2 ≤ n ≤ :data:`MAX_WAYPOINTS`, consecutive ones distinct.
    law : GuidanceLaw, optional
        The law (default :data:`LOS`).
    params_type : type, optional
        A :class:`RouteParams` class to fill instead of the law's (the parameters of a
        controller that follows the route itself, e.g. the LQ cross-track controller's).
    **values
        Its other parameters (``acceptance_radius``, ``lookahead``, ``kappa``, ...).

    Returns
    -------
    RouteParams
        LOSParams or ILOSParams for a law, else ``params_type``.

    Raises
    ------
    ParameterError
        For fewer than two or more than :data:`MAX_WAYPOINTS` waypoints, a shape other than
        (n, 2), duplicate consecutive waypoints, non-finite coordinates or bad law parameters.
    """
    law = LOS if law is None else law
    pts = as_float_array("waypoints", waypoints, "m")
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ParameterError(f"`waypoints` must be a list of (north, east) points [m], got shape "
                             f"{pts.shape}")
    n = pts.shape[0]
    if not 2 <= n <= MAX_WAYPOINTS:
        raise ParameterError(f"`waypoints`: a route needs 2 to {MAX_WAYPOINTS} waypoints, got {n}")
    north = np.zeros(MAX_WAYPOINTS)
    east = np.zeros(MAX_WAYPOINTS)
    north[:n], east[:n] = pts[:, 0], pts[:, 1]
    cls = law.params_type if params_type is None else params_type
    return cls(route_north=tuple(north), route_east=tuple(east), n_waypoints=float(n), **values)


# ------------------------------------------------------------------------------------------
# compiled: geometry, switching, the two laws
# ------------------------------------------------------------------------------------------
@njit(cache=True)
def cross_track(p, k, north, east):  # pragma: no cover - compiled
    """(π_k, x_e, y_e, leg length) of the ship at (north, east) on leg k of the route in p."""
    n0 = p.route_north[k]
    e0 = p.route_east[k]
    dn = p.route_north[k + 1] - n0
    de = p.route_east[k + 1] - e0
    pi_k = math.atan2(de, dn)
    c = math.cos(pi_k)
    s = math.sin(pi_k)
    x_e = (north - n0) * c + (east - e0) * s
    y_e = -(north - n0) * s + (east - e0) * c
    return pi_k, x_e, y_e, math.sqrt(dn * dn + de * de)


@njit(cache=True)
def _advance_waypoints(p, gs, north, east):  # pragma: no cover - compiled
    """Switch legs while the next waypoint is reached; returns the active leg k."""
    n = int(p.n_waypoints)
    k = int(gs[_S.segment])
    r2 = p.acceptance_radius * p.acceptance_radius
    while gs[_S.complete] == 0.0:
        dn = p.route_north[k + 1] - north
        de = p.route_east[k + 1] - east
        _, x_e, _, length = cross_track(p, k, north, east)
        if dn * dn + de * de <= r2 or x_e >= length:
            if k + 2 < n:
                k += 1
                gs[_S.segment] = k
            else:
                gs[_S.complete] = 1.0
        else:
            break
    return k


@njit(cache=True)
def _lookahead(p, y_e):  # pragma: no cover - compiled
    if p.lookahead_gamma > 0.0 and p.lookahead_min > 0.0:
        return (p.lookahead - p.lookahead_min) * math.exp(-p.lookahead_gamma * y_e * y_e) \
            + p.lookahead_min
    return p.lookahead


@njit(cache=True)
def _outputs(p, gs, k, psi_d, x_e, y_e, out):  # pragma: no cover - compiled
    out[_O.heading_reference] = psi_d
    out[_O.cross_track_error] = y_e
    out[_O.along_track_distance] = x_e
    out[_O.waypoint_index] = p.n_waypoints - 1.0 if gs[_S.complete] != 0.0 else float(k)


@njit(cache=True)
def los_init(p, gs, north, east):  # pragma: no cover - compiled
    gs[_S.segment] = 0.0
    gs[_S.integral] = 0.0
    gs[_S.complete] = 0.0


@njit(cache=True)
def los_step(dt, p, gs, north, east, out):  # pragma: no cover - compiled
    """Proportional LOS: ψ_d = π_k − atan(y_e/Δ); writes the outputs, returns ψ_d."""
    k = _advance_waypoints(p, gs, north, east)
    pi_k, x_e, y_e, _ = cross_track(p, k, north, east)
    psi_d = pi_k - math.atan(y_e / _lookahead(p, y_e))
    psi_d = (psi_d + math.pi) % (2.0 * math.pi) - math.pi
    _outputs(p, gs, k, psi_d, x_e, y_e, out)
    return psi_d


@njit(cache=True)
def ilos_step(dt, p, gs, north, east, out):  # pragma: no cover - compiled
    """Integral LOS: ψ_d = π_k − atan((y_e + κ y_int)/Δ), ẏ_int = Δ y_e/(Δ² + (y_e + κ y_int)²).

    The integral is reset when the active leg changes (its offset belongs to the leg's
    direction relative to the drift)."""
    k_before = gs[_S.segment]
    k = _advance_waypoints(p, gs, north, east)
    if gs[_S.segment] != k_before:
        gs[_S.integral] = 0.0
    pi_k, x_e, y_e, _ = cross_track(p, k, north, east)
    delta = _lookahead(p, y_e)
    y_int = gs[_S.integral]
    arg = y_e + p.kappa * y_int
    psi_d = pi_k - math.atan(arg / delta)
    psi_d = (psi_d + math.pi) % (2.0 * math.pi) - math.pi
    gs[_S.integral] = y_int + dt * delta * y_e / (delta * delta + arg * arg)
    _outputs(p, gs, k, psi_d, x_e, y_e, out)
    return psi_d


@dataclasses.dataclass(frozen=True, eq=False)
class GuidanceLaw:
    """A path-following law: its parameters (a route and gains) and compiled functions.

    ``init(p, gs, north, east)`` fills the guidance state ``gs`` (``GUIDANCE_STATES``);
    ``step(dt, p, gs, north, east, out)`` updates it, writes the outputs
    (``GUIDANCE_OUTPUTS``) into ``out`` and returns the heading reference ψ_d [rad].
    """

    name: str
    description: str
    params_type: type[Params]
    init: Any
    step: Any
    state_labels: tuple[str, ...] = GUIDANCE_STATES
    measurement_labels: tuple[str, ...] = GUIDANCE_MEASUREMENTS
    output_labels: tuple[str, ...] = GUIDANCE_OUTPUTS
    output_units: tuple[str, ...] = GUIDANCE_OUTPUT_UNITS


LOS = GuidanceLaw(name="los", description="proportional line-of-sight path following "
                  "(Fossen 2021, §12.4.2)", params_type=LOSParams, init=los_init, step=los_step)
ILOS = GuidanceLaw(name="ilos", description="integral line-of-sight path following (Børhaug et "
                   "al. 2008; Fossen 2021, eq. 12.108-12.110)", params_type=ILOSParams,
                   init=los_init, step=ilos_step)

#: The guidance laws by name.
GUIDANCE_LAWS: dict[str, GuidanceLaw] = {law.name: law for law in (LOS, ILOS)}


def get_guidance_law(law: "str | GuidanceLaw") -> GuidanceLaw:
    """A guidance law by name (or the law itself); an unknown name lists the valid ones.

    Parameters
    ----------
    law : str or GuidanceLaw
        ``"los"``, ``"ilos"`` or a :class:`GuidanceLaw`.

    Returns
    -------
    GuidanceLaw

    Raises
    ------
    ParameterError
        For an unknown name.
    """
    if isinstance(law, GuidanceLaw):
        return law
    return lookup_name("guidance law", GUIDANCE_LAWS, law, error=ParameterError)
