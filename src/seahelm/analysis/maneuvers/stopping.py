"""The stopping (crash-stop) test: full astern from a steady approach, batched.

From a steady straight approach at U_0 (the MMG ship's self-propulsion point, as in every
manoeuvre of :mod:`seahelm.analysis.maneuvers.common`) the engine is ordered full astern at
t = 0 (``order`` = −1; a part-astern order −1 < e < 0 may be given instead) and the **rudder
is held amidships** (ordered to 0 at t = 0 and kept there: the IMO stopping test prescribes no
rudder, and counter-rudder would be a rule of its own). The engine goes through the reversal
sequence of :mod:`seahelm.vessels.engine_shaft` (fuel cut and windmilling for the reversal
delay t_d, the air brake, the astern start), the four-quadrant propeller of
:mod:`seahelm.vessels.mmg_four_quadrant` decelerates the ship, and the run ends after
``t_final``.

The ship runs on the ``mmg-4q`` model. A ship of the plain ``mmg`` model (its propeller's
rps is an input there, not an engine) is converted by :func:`stopping_ship`, which adds the
engine and shaft estimate of :func:`seahelm.vessels.mmg_four_quadrant.from_mmg`; a ship
without a propeller cannot be stopped and is refused (ParameterError naming ``ship``).

Dead in the water
    The ship is taken to be dead in the water when its headway — the surge speed u through
    the water — has fallen to ``dead_fraction`` × U_0 (default 5 %, 0.78 kn for the KVLCC2's
    15.5 kn); ``dead_fraction=0`` measures to the moment the ahead speed changes sign. The
    distances below are measured there (MSC.137(76): track reach "to the position at which the
    ship stops in the water"; MSC/Circ.1053 for head reach and lateral deviation).

Metrics (per run; distances of the midship point from the position at the order)
    ``head_reach`` [m] along the original course; ``track_reach`` [m] along the track (the
    chord sum of :func:`~seahelm.analysis.maneuvers.track_distance`); ``lateral_deviation``
    [m] across the original course, positive to starboard; ``max_lateral_deviation`` [m] the
    largest |lateral deviation| up to then; ``heading_change`` [rad] at the dead point (positive
    to starboard); ``time_dead`` [s] the time to dead in the water; ``time_astern`` [s] the
    time at which the shaft first turns astern; ``speed_dead`` [m/s] the speed through the
    water U = √(u² + v²) at the dead point (the sway that is left). Event times and positions
    are interpolated linearly between the two recorded samples that bracket the event.

A run that is not dead in the water within ``t_final`` reports NaN for what depends on it,
``complete`` False and a ``message`` saying so; it is not an error.

Range
    The MMG hull polynomials were fitted at small drift and ahead speed. With the default hull
    (``hull_model`` 0) the low-speed cross-flow model of Yoshimura et al. (2009) takes over
    beyond |β| = 30° or |r'| = 1 (:mod:`seahelm.vessels.mmg_four_quadrant`); it is stated for
    Fn ≤ 0.1, and the analysis warns (:func:`seahelm.errors.warn_validity`, an error in strict
    mode) when a run uses it faster (:func:`seahelm.hydrodynamics.low_speed_hull.check_range`).
    With the mirrored MMG hull (``hull_model`` 1) it warns when a run's drift angle exceeds 30°
    while its speed is above 20 % of U_0 before it is dead in the water (the ship then swings
    out of the range the hull model was fitted for).

References
----------
IMO (2002). Resolution MSC.137(76), Standards for ship manoeuvrability, §§ 4.2.4, 5.4.
IMO (2002). MSC/Circ.1053, Explanatory notes to the Standards for ship manoeuvrability
(stopping test: head reach, track reach, lateral deviation).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Any

import numpy as np

from ...constants import GRAVITY
from ...errors import ParameterError, ValidityRangeWarning, warn_validity
from ...hydrodynamics.low_speed_hull import check_range
from ...ships import Propulsion, Ship
from .common import Plan, final_time, record_every_for, usual_time_step, value_axis
from .result import ManeuverResult
from .turning_circle import _at_crossings, _crossings, track_distance

__all__ = ["crash_stop", "stopping_ship", "stopping_metrics", "MODEL_SCALE_LENGTH"]

# The Froude scale λ of a model's engine timings (the reversal delay, brake time and governor
# time constant are full-scale values divided by √λ) is what its ship declares
# (Particulars.model_scale: the catalog's L7 KVLCC2s, 45.7); a ship that declares none is
# taken at full scale unless ``scale`` is given.
_KVLCC2_L7_GEOMETRY = (7.0, 0.216)
#: A ship shorter than this [m] without a known scale warns that full-scale engine timings are
#: applied to it.
MODEL_SCALE_LENGTH = 50.0
#: Drift angle [rad] and speed fraction of U_0 beyond which the hull model is extrapolated.
DRIFT_RANGE = math.radians(30.0)
SPEED_RANGE = 0.2

_ENGINE_FIELDS = ("shaft_inertia", "rated_rps", "max_power", "astern_rps", "reversal_time",
                  "reversal_delay", "reversal_rps", "governor_time_constant", "R_0_astern",
                  "backing_side_force")
_HULL_SOURCES = {
    "hull_model": "the default (0: cross-flow; 1 the mirrored MMG hull)",
    "cross_flow_drag": "C_D matched to the MMG sway force Y'_v v' + Y'_vvv v'^3 at 30 deg of "
                       "drift (Yoshimura's regression was not available)",
    "C_rY": "1, plain strip theory (no fitted value for this ship)",
    "C_rN": "1, plain strip theory (no fitted value for this ship)"}


def stopping_ship(ship: Any, *, scale: float | None = None, **engine: float) -> Ship:
    """The ship that the stopping test runs: an ``mmg`` ship with its engine (``mmg-4q``).

    An ``mmg-4q`` ship is returned as it is (``engine`` changes its fields). An ``mmg`` ship
    with a propeller gets the engine, shaft and reversal estimate of
    :func:`seahelm.vessels.mmg_four_quadrant.from_mmg` (:data:`~seahelm.vessels.
    mmg_four_quadrant.KVLCC2_ENGINE_NOTE`: MCR from the approach at 85 % MCR on the propeller
    law, full astern at 70 % of the rated rps, reversal delay 60 s, brake time 40 s and governor
    2 s at full scale, Froude-scaled for a model), the four-quadrant propeller and the astern
    hull; everything else (steering gear, particulars, test speed, water depth) is kept.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path) or Params
        The ship.
    scale : float, optional
        Froude scale λ ≥ 1 of a model (its engine timings are full-scale ones / √λ). Default:
        the scale the ship declares (:attr:`~seahelm.vessels.particulars.Particulars.
        model_scale`: 45.7 for the catalog's model-scale KVLCC2s) and 45.7 for any
        ship with the L7 model's length and propeller (7 m, 0.216 m), else 1 (with a warning
        for a ship shorter than :data:`MODEL_SCALE_LENGTH`).
    **engine : float
        Any :class:`~seahelm.vessels.mmg_four_quadrant.MMG4QParams` field to set instead of the
        estimate (e.g. ``reversal_delay=90.0``).

    Returns
    -------
    Ship
        On the ``mmg-4q`` model, with the engine fields' sources in ``coefficient_sources``.

    Raises
    ------
    ParameterError
        ``field="ship"`` for a ship without a propeller or not on the MMG model; the field's
        name for an invalid engine value or ``scale``.
    """
    from ...vessels.mmg import MMGParams
    from ...vessels.mmg_four_quadrant import KVLCC2_ENGINE_NOTE, MMG4QParams, from_mmg

    from .ships import maneuver_ship

    s = maneuver_ship(ship)
    if scale is not None and not (isinstance(scale, (int, float)) and math.isfinite(scale)
                                  and scale >= 1.0):
        raise ParameterError(f"must be a Froude scale >= 1 [-], got {scale!r}", field="scale",
                             unit="-", value=scale)
    if isinstance(s.params, MMG4QParams):
        return s.replace(params=engine) if engine else s
    if (not s.model.supports("engine-estimate") or not isinstance(s.params, MMGParams)
            or not s.has_propeller):
        what = ("has no propeller" if not s.has_propeller else
                f"is on model '{s.model.name}', not 'mmg'")
        raise ParameterError(
            f": ship '{s.name}' {what}: the stopping test needs an MMG ship with a propeller "
            "(model 'mmg', converted to 'mmg-4q' with an engine estimate) or an 'mmg-4q' ship",
            field="ship", value=s.name)
    if scale is None:
        scale = None if s.particulars is None else s.particulars.model_scale
        geometry = (float(s.params.length), float(s.params.propeller_diameter))
        if scale is None and geometry == _KVLCC2_L7_GEOMETRY:  # a variant of the L7 model
            scale = 45.7
        if scale is None:
            scale = 1.0
            if s.length < MODEL_SCALE_LENGTH:
                warnings.warn(
                    f"ship '{s.name}' (L = {s.length:g} m) is given full-scale engine timings "
                    "(reversal delay 60 s, brake 40 s); for a model pass `scale` (its Froude "
                    "scale) or the timings", ValidityRangeWarning, stacklevel=2)
    unknown = sorted(set(engine) - set(MMG4QParams.field_names()))
    if unknown:
        raise ParameterError(f"names no field of MMG4QParams: {', '.join(unknown)}",
                             field="engine", value=unknown)
    params = from_mmg(s.params, scale=scale, **engine)
    deep = (None if s.deep_water_params is None
            else from_mmg(s.deep_water_params, scale=scale, **engine))
    note = KVLCC2_ENGINE_NOTE + f" Froude scale of the timings used here: {scale:g}."
    sources = dict(s.coefficient_sources)
    for name in _ENGINE_FIELDS:
        sources[name] = ("given" if name in engine else note)
    hull_note = ("low-speed cross-flow hull of Yoshimura, Nakao & Ishibashi (2009) "
                 "(seahelm.hydrodynamics.low_speed_hull): ")
    for name, why in _HULL_SOURCES.items():
        sources[name] = "given" if name in engine else hull_note + why
    validity = tuple(v for v in s.validity if "ahead motion only" not in v) + (
        "engine, shaft and reversal sequence: estimates (seahelm.vessels.mmg_four_quadrant."
        "from_mmg), not the ship's engine data",
        "astern and at large drift (|drift| > 30 deg or |r'| > 1) the hull is the low-speed "
        "cross-flow model of Yoshimura et al. (2009), stated for Fn <= 0.1 (the stopping test "
        "warns above); hull_model = 1 keeps the mirrored MMG hull")
    propulsion = Propulsion(
        kind="single fixed-pitch propeller, reversible engine and shaft",
        inputs=("engine_order",),
        provenance="four-quadrant Wageningen B4-70 series scaled to the ship's K_T(0) "
                   "(Roddy, Hess & Faller 2006); " + note)
    return dataclasses.replace(
        s, model="mmg-4q", params=params, deep_water_params=deep, propulsion=propulsion,
        coefficient_sources=tuple(sources.items()), validity=validity,
        description=(s.description + " with engine and reversal (mmg-4q)").strip())


def _mmg_counterpart(ship: Ship) -> Ship:
    """The ``mmg`` ship of an ``mmg-4q`` ship (the same hull, the rps an input): its steady
    approach is the four-quadrant ship's, which equals it ahead."""
    from ...vessels.mmg import MMGParams

    fields = MMGParams.field_names()
    params = MMGParams(**{f: getattr(ship.params, f) for f in fields})
    deep = (None if ship.deep_water_params is None else
            MMGParams(**{f: getattr(ship.deep_water_params, f) for f in fields}))
    return dataclasses.replace(ship, model="mmg", params=params, deep_water_params=deep,
                               propulsion=None, coefficient_sources=())


def _astern_thrust(p: Any, order: float) -> float:
    """|T| [N] of the scaled series at the commanded astern rps, u = 0 (bollard astern)."""
    from ...hydrodynamics.four_quadrant import thrust_coefficient_4q
    from ...vessels.mmg_four_quadrant import KT0_SERIES

    n = -order * p.astern_rps
    dp = p.propeller_diameter
    w = 0.7 * math.pi * n * dp
    ct = float(thrust_coefficient_4q(math.atan2(0.0, w)))
    return abs(p.k_0 / KT0_SERIES * ct * 0.5 * p.rho * w * w * 0.25 * math.pi * dp * dp)


def _estimate_t_final(ships: list[Ship], speeds: np.ndarray, orders: np.ndarray) -> float:
    """1.2 × (t_d + t_rev + M U_0 / |T_astern|) of the slowest-stopping run (momentum
    estimate with the bollard astern thrust: an upper bound of the time to stop, since the
    resistance, left out, and the larger astern thrust at ahead speed only shorten it; the
    KVLCC2 is dead in the water at about a third of it)."""
    t = 0.0
    for s in ships:
        p = s.params
        mass = p.rho * p.displacement + p.m_x * 0.5 * p.rho * p.length ** 2 * p.draft
        for order in orders:
            thrust = _astern_thrust(p, float(order))
            t = max(t, 1.2 * (p.reversal_delay + p.reversal_time
                              + mass * float(np.max(speeds)) / thrust))
    return t


def _check_order(order: Any) -> Any:
    axis = value_axis("order", order, "1")
    if not np.all((axis.values >= -1.0) & (axis.values < 0.0)):
        bad = float(axis.values[~((axis.values >= -1.0) & (axis.values < 0.0))][0])
        raise ParameterError(f"must be an astern engine order in [-1, 0) [-] (-1 full astern), "
                             f"got {bad!r}", field="order", unit="1", value=bad)
    axis.attrs = {"long_name": "engine order (-1 full astern)"}
    return axis


def crash_stop(ship: Any, *, order: Any = -1.0, speed: Any = None,
               t_final: float | None = None, dt: float | None = None,
               record_dt: float | None = None, dead_fraction: float = 0.05,
               conditions: Any = None) -> ManeuverResult:
    """Stopping tests (full astern, rudder amidships), batched over ships, speeds and orders.

    Parameters
    ----------
    ship : Ship, str, Params or a sequence of them
        The ship(s): ``mmg`` ships with a propeller (converted by :func:`stopping_ship`) or
        ``mmg-4q`` ships; a sequence gives a ``ship`` dimension.
    order : float or sequence of float, optional
        Engine order e in [−1, 0) given at t = 0 (default −1, full astern); a sequence gives an
        ``order`` dimension.
    speed : float or sequence of float, optional
        Approach speed(s) U_0 [m/s] (default: the ship's test speed); a sequence gives an
        ``approach_speed`` dimension.
    t_final : float, optional
        Duration [s] (default: 1.2 × the momentum estimate t_d + t_rev + M U_0/|T_astern| with
        the bollard astern thrust, M the mass with the surge added mass: an upper bound).
    dt : float, optional
        Integration step [s] (default :func:`~seahelm.analysis.maneuvers.default_time_step`).
    record_dt : float, optional
        Recording interval [s], a whole multiple of ``dt`` (default: every step up to 4,000
        samples, then the smallest multiple that keeps to 4,000).
    dead_fraction : float, optional
        Dead in the water when the surge speed is ≤ this fraction of U_0, in [0, 1) (default
        0.05).
    conditions : Conditions, optional
        Wind, waves and current from t = 0 on (:class:`seahelm.environment.loads.Conditions`).

    Returns
    -------
    ManeuverResult
        ``maneuver = "stopping"``; ``metrics`` variables ``head_reach``, ``track_reach``,
        ``lateral_deviation``, ``max_lateral_deviation`` [m], ``heading_change`` [rad],
        ``time_dead``, ``time_astern`` [s], ``speed_dead`` [m/s], ``approach_speed_value`` [m/s],
        ``propeller_rps`` [1/s] (of the approach), ``reversal_delay`` [s], ``length`` [m],
        ``complete``, ``message`` (module docstring).

    Raises
    ------
    ParameterError
        For a ship that cannot be stopped (``field="ship"``), an order outside [−1, 0), a
        ``dead_fraction`` outside [0, 1), a speed ≤ 0 or invalid timing.
    """
    if not (isinstance(dead_fraction, (int, float)) and 0.0 <= dead_fraction < 1.0):
        raise ParameterError(f"must be in [0, 1) [-], got {dead_fraction!r}",
                             field="dead_fraction", unit="1", value=dead_fraction)
    order_axis = _check_order(order)
    if isinstance(ship, (list, tuple)):
        ships = [stopping_ship(s) for s in ship]
        plan = Plan([_mmg_counterpart(s) for s in ships], speed, None, [order_axis])
    else:
        ships = [stopping_ship(ship)]
        plan = Plan(_mmg_counterpart(ships[0]), speed, None, [order_axis])
    speeds = np.array([a.speed for a in plan.approaches.values()])
    if dt is None:
        dt = usual_time_step(plan.ships, speeds)
    if t_final is None:
        t_final = _estimate_t_final(ships, speeds, order_axis.values)
    t_final = final_time(float(t_final), float(dt))
    if record_dt is None:
        record_every = max(1, math.ceil(t_final / dt / 4000.0))
    else:
        record_every = record_every_for(float(dt), record_dt, float(t_final))
    plan.ships = ships  # the approach is the mmg ship's; the run is the engine's
    approaches = plan.run_approaches()
    x0 = np.stack([np.concatenate([a.state, [a.rps, 0.0]]) for a in approaches])
    rudder0 = np.array([[a.rudder] for a in approaches])
    reference = {"rudder_command": np.zeros((plan.n_runs, 1, 1)),
                 "engine_order": plan.run_values("order").reshape(-1, 1, 1)}
    result = plan.simulate(x0=x0, actuator_x0=rudder0, reference=reference, t_final=t_final,
                           dt=dt, record_every=record_every, metadata={"maneuver": "stopping"},
                           controller_every=record_every, conditions=conditions)
    metrics = _metrics(plan, result, float(dead_fraction))
    return ManeuverResult("stopping", metrics, tuple(ships), result,
                          lambda: plan.runs_dataset(result))


def stopping_metrics(time: Any, north: Any, east: Any, heading: Any, surge_speed: Any,
                     approach_speed: Any, *, speed: Any = None, propeller_rps: Any = None,
                     dead_fraction: float = 0.05) -> dict[str, np.ndarray]:
    """The stopping metrics of recorded runs (module docstring), from the order at ``time[0]``.

    Parameters
    ----------
    time : array_like, shape (steps,)
        Time [s]; the engine order is at ``time[0]``.
    north, east, heading, surge_speed : array_like, shape (runs, steps) or (steps,)
        Midship position [m], heading ψ [rad] and surge speed u [m/s].
    approach_speed : float or array_like, shape (runs,)
        U_0 [m/s], > 0.
    speed : array_like, optional
        Speed through the water U [m/s] (default: |u|).
    propeller_rps : array_like, optional
        Shaft speed n [1/s] (``time_astern`` is NaN without it).
    dead_fraction : float, optional
        Dead in the water at u ≤ this × U_0 (default 0.05).

    Returns
    -------
    dict of str to numpy.ndarray
        ``head_reach``, ``track_reach``, ``lateral_deviation``, ``max_lateral_deviation``,
        ``heading_change``, ``time_dead``, ``time_astern``, ``speed_dead``, each (runs,), NaN
        where not reached.
    """
    t = np.asarray(time, dtype=float)
    north, east, psi, u = (np.atleast_2d(np.asarray(a, dtype=float))
                           for a in (north, east, heading, surge_speed))
    U0 = np.broadcast_to(np.asarray(approach_speed, dtype=float), (u.shape[0],))
    if not np.all(U0 > 0):
        raise ParameterError(f"must be > 0 [m/s], got {approach_speed!r}",
                             field="approach_speed", unit="m/s")
    speed = np.abs(u) if speed is None else np.atleast_2d(np.asarray(speed, dtype=float))
    dn, de = north - north[:, :1], east - east[:, :1]
    c0, s0 = np.cos(psi[:, :1]), np.sin(psi[:, :1])
    along, across = dn * c0 + de * s0, -dn * s0 + de * c0
    times = np.broadcast_to(t, psi.shape)
    dist = track_distance(north, east)
    # dead in the water: 1 - u/U0 rises through 1 - dead_fraction
    k, w = _crossings(1.0 - u / U0[:, None], np.array([1.0 - dead_fraction]))
    head, lateral, t_dead, track, heading_change, u_dead = _at_crossings(
        np.stack([along, across, times, dist, psi - psi[:, :1], speed]), k, w)[:, 0]
    t_astern = np.full(u.shape[0], np.nan)
    if propeller_rps is not None:
        rps = np.atleast_2d(np.asarray(propeller_rps, dtype=float))
        ka, wa = _crossings(-rps, np.array([np.finfo(float).tiny]))
        t_astern = _at_crossings(times[None], ka, wa)[0, 0]
    before = times <= np.where(np.isfinite(t_dead), t_dead, t[-1])[:, None]
    max_lateral = np.where(np.isfinite(t_dead),
                           np.max(np.where(before, np.abs(across), 0.0), axis=1), np.nan)
    return {"head_reach": head, "track_reach": track, "lateral_deviation": lateral,
            "max_lateral_deviation": max_lateral, "heading_change": heading_change,
            "time_dead": t_dead, "time_astern": t_astern, "speed_dead": u_dead}


def _metrics(plan: Plan, result: Any, dead_fraction: float) -> Any:
    t = result.time
    u, speed = result["surge_speed"], result["speed"]
    approaches = plan.run_approaches()
    U0 = np.array([a.speed for a in approaches])
    n0 = np.array([a.rps for a in approaches])
    found = stopping_metrics(t, result["north"], result["east"], result["heading"], u, U0,
                             speed=speed, propeller_rps=result["propeller_rps"],
                             dead_fraction=dead_fraction)
    t_dead = found["time_dead"]
    n = plan.n_runs
    before = t[None, :] <= np.where(np.isfinite(t_dead), t_dead, t[-1])[:, None]
    from ...vessels.mmg_four_quadrant import HULL_MIRROR
    beta = result["drift_angle"]
    params = [plan.ship(i).params for i in range(n)]
    mirror = np.array([getattr(p, "hull_model", HULL_MIRROR) == HULL_MIRROR for p in params])
    outside = mirror & np.any(before & (np.abs(beta) > DRIFT_RANGE)
                              & (speed > SPEED_RANGE * U0[:, None]), axis=1)
    cross = ~mirror
    beyond = np.zeros(n, dtype=bool)
    if cross.any():  # the cross-flow hull: its own range (Fn <= 0.1 where it is used)
        beyond[cross] = check_range(
            np.asarray(speed)[cross], np.asarray(beta)[cross],
            np.asarray(result["yaw_rate"])[cross],
            np.array([params[i].length for i in np.flatnonzero(cross)]),
            np.array([params[i].min_froude_number * math.sqrt(GRAVITY * params[i].length)
                      for i in np.flatnonzero(cross)]), where="the stopping test", stacklevel=4)
    status = result.messages()
    messages, complete = [], np.zeros(n, dtype=bool)
    for i in range(n):
        text = [] if status[i] == "ok" else [status[i]]
        if not math.isfinite(t_dead[i]):
            text.append(f"not dead in the water within t_final = {t[-1]:.6g} s (surge speed at "
                        f"the end {u[i, -1]:.4g} m/s = {u[i, -1] / U0[i]:.3g} U0)")
        complete[i] = not text
        if outside[i]:
            text.append("drift angle beyond 30 deg above 20 % of U0: hull forces extrapolated")
        if beyond[i]:
            text.append("low-speed cross-flow hull used above Fn 0.1: outside its range")
        messages.append("; ".join(text) if text else "ok")
    if outside.any():
        warn_validity(
            f"{int(outside.sum())} of {n} stopping run(s) swing beyond 30 deg of drift while "
            "faster than 20 % of the approach speed: the MMG hull polynomials are extrapolated "
            "there (fitted at small drift; hull_model = 1, the mirrored hull)", stacklevel=4)
    head, track, lateral, max_lateral, heading, t_astern, u_dead = (found[k] for k in (
        "head_reach", "track_reach", "lateral_deviation", "max_lateral_deviation",
        "heading_change", "time_astern", "speed_dead"))
    variables = {
        "head_reach": (head, "m", "head reach: along the original course to dead in the water"),
        "track_reach": (track, "m", "track reach: along the track to dead in the water"),
        "lateral_deviation": (lateral, "m",
                              "lateral deviation at dead in the water (+ to starboard)"),
        "max_lateral_deviation": (max_lateral, "m",
                                  "largest |lateral deviation| up to dead in the water"),
        "heading_change": (heading, "rad", "heading change at dead in the water (+ starboard)"),
        "time_dead": (t_dead, "s", "time from the order to dead in the water"),
        "time_astern": (t_astern, "s", "time from the order to astern shaft rotation"),
        "speed_dead": (u_dead, "m/s", "speed through the water at dead in the water"),
        "approach_speed_value": (U0, "m/s", "approach speed U_0"),
        "propeller_rps": (n0, "1/s", "propeller rps of the approach"),
        "reversal_delay": (np.array([plan.ship(i).params.reversal_delay for i in range(n)]),
                           "s", "reversal delay t_d of the engine (order to air start)"),
        "length": (plan.run_lengths(), "m", "ship length L"),
        "complete": (complete, "", "dead in the water within t_final, the run did not diverge"),
        "message": (np.array(messages, dtype=object), "", "what was not reached, or ok"),
    }
    attrs = {"maneuver": "stopping", "dt": float(result.metadata["dt"]),
             "t_final": float(result.metadata["t_final"]),
             "dead_fraction": dead_fraction,
             "dead_in_the_water": f"surge speed <= {dead_fraction:g} x U0",
             "rudder": "held amidships (0) from the order",
             "reference_point": "midship (the model's origin)",
             "measured_from": "engine order at t = 0",
             "interpolation": "linear between the recorded samples bracketing each event"}
    return plan.dataset(variables, attrs=attrs)
