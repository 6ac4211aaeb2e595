"""Turning circles (and the initial turning test) over batches of ships, speeds, rudders, sides.

Definitions of IMO Resolution MSC.137(76) and its explanatory notes (MSC/Circ.1053), all
measured at the model's reference point (midship for the MMG and the Mariner models) from the
position and heading at the moment the rudder is **ordered** (t = 0; the rudder's travel time
counts):

advance
    distance along the original course when the heading has changed by 90°;
transfer
    distance across the original course at the 90° heading change;
tactical diameter
    distance across the original course at the 180° heading change;
times to 90° and 180°
    when those heading changes are reached;
initial turning
    time to a 10° heading change and the distance travelled along the track until then
    (MSC.137(76) initial turning ability, judged with 10° rudder: ≤ 2.5 L);
steady turn
    at the end of the run (by default after an estimated 360° heading change): turning radius
    U/|r| of the reference point, speed U and speed loss 1 − U/U_0, drift angle β, yaw rate r;
    ``steady`` says whether the yaw rate changed by less than 1 % over the last 90° of heading.
heel (models with roll only, :func:`seahelm.analysis.equilibria.heel.heel_metrics`)
    ``max_heel_angle``, the heel of largest magnitude over the run, and ``steady_heel_angle``
    at its end (signed, positive starboard down: outward heel has the yaw rate's opposite sign).

Event times and the positions at them are interpolated by the cubic through the four recorded
samples around the heading change (the time where it reaches the level, then every signal
there), not rounded to a sample; the error is of order h⁴ in the recording interval h, so the
default recording every L/(20 U_0) measures the events to ~10⁻⁷ m on the KVLCC2 L7 (linear
interpolation between samples at every step, as before, was good to ~10⁻⁵ m). The distance
along the track is the arc of the cubic spline through the positions (:func:`track_distance`).

A run that does not reach a heading change reports NaN for what depends on it, ``complete``
False and a ``message`` saying what was not reached; it is not an error.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...simulation.frame import keep_inputs
from ..equilibria.constant_speed import is_constant_speed
from ..equilibria.heel import heel_metrics
from .common import (
    Plan,
    check_rudder,
    usual_time_step,
    final_time,
    record_every_for,
    side_axis,
    value_axis,
)
from .prepared import keep, ready, request_key
from .ships import steady_yaw_rates, yaw_lag
from .result import ManeuverResult
from .track import _arc_distances, _gauss3, distance_until, track_distance
from .turning_kernels import (  # noqa: F401 (the compiled passes, used and tested from here)
    _bracket, _completion, _event_nodes, _first_crossings, _first_pass, _front, _newton,
    _steady_ends,
)

__all__ = ["turning_circle", "track_distance", "default_record_every", "SAMPLES_PER_LENGTH"]

_DEG10 = math.radians(10.0)
#: Powers 0..3 of a cubic (and offsets of its four nodes).
_POWERS = np.arange(4)
#: What the metrics of a constant-speed model (:mod:`seahelm.analysis.equilibria.constant_speed`)
#: say.
CONSTANT_SPEED_NOTE = ("constant-speed model: the speed does not change in the turn, the "
                       "speed loss is not modelled")


def _estimate_t_final(plan: Plan, signed: dict[tuple[int, int], list[float]],
                      heading_change: float) -> float:
    """Rudder travel + 1.3 × heading change / slowest steady yaw rate of the grid."""
    t = 0.0
    groups = [(plan.ships[i_ship], np.array(rudders), plan.approaches[(i_ship, j_speed)])
              for (i_ship, j_speed), rudders in signed.items()]
    for (ship, rudders, a), rates in zip(groups, steady_yaw_rates(groups)):  # one batch
        travel = max(abs(d - a.rudder) for d in rudders) / ship.servo.max_rate
        t = max(t, travel + 1.3 * heading_change / float(np.min(rates)) + 3.0 * yaw_lag(ship))
    return t


def turning_circle(ship: Any, rudder: Any = math.radians(35.0), *, sides: Any = (1, -1),
                   speed: Any = None, rps: Any = None, t_final: float | None = None,
                   dt: float | None = None, record_dt: float | None = None,
                   heading_change: float = 2.0 * math.pi,
                   conditions: Any = None) -> ManeuverResult:
    """Turning circles to both sides (or one), batched over ships, speeds and rudder angles.

    From a steady straight approach the rudder is ordered to ``side × rudder`` at t = 0 and held;
    the metrics of the module docstring are measured on the recorded track.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path), Params, or a sequence of them
        The ship(s) (:func:`~seahelm.analysis.maneuvers.maneuver_ship`); a sequence gives a
        ``ship`` dimension (all on one model).
    rudder : float or sequence of float, optional
        Rudder angle magnitude(s) δ [rad], in (0, steering-gear limit] (default 35°); a sequence
        gives a ``rudder`` dimension.
    sides : int or sequence of int, optional
        +1 starboard, −1 port (default both: a ``side`` dimension).
    speed : float or sequence of float, optional
        Approach speed(s) U_0 [m/s] (default: the parameter set's; the Mariner admits only its
        nominal speed); a sequence gives an ``approach_speed`` dimension.
    rps : float or sequence of float, optional
        Instead of ``speed``: propeller rps [1/s] of the approach (MMG), the speed being that
        of the straight run at this rps.
    t_final : float, optional
        Duration [s] (default: rudder travel time + 1.3 × ``heading_change`` / the slowest
        steady yaw rate of the grid, from
        :func:`~seahelm.analysis.equilibria.equilibrium.steady_turn`; for a constant-speed model
        plus 3 × its yaw time constant, T of Nomoto 1, so that the turn is steady at the end).
    dt : float, optional
        Integration step [s] (default :func:`~seahelm.analysis.maneuvers.default_time_step`).
    record_dt : float, optional
        Recording interval [s], a whole number of steps. Default: the largest whole number of
        steps within L/(20 U_0) of the shortest ship and slowest approach of the batch
        (:func:`default_record_every`; the events are interpolated by cubics, to far below
        the integration error); every step for a model with roll (its maximum heel is a
        recorded sample).
    heading_change : float, optional
        Heading change [rad] the default ``t_final`` aims at (default 2π, for the steady turn).

    conditions : Conditions, optional
        Wind, waves and a uniform current (:class:`seahelm.environment.loads.Conditions`)
        acting from t = 0 on; the approach is the calm-water one, and the metrics are measured
        on the track over ground (default: calm water).

    Returns
    -------
    ManeuverResult
        ``metrics`` variables: ``advance``, ``transfer``, ``tactical_diameter`` [m],
        ``time_90``, ``time_180`` [s], ``time_10`` [s], ``distance_10`` [m], ``steady_radius``
        [m], ``steady_speed`` [m/s], ``speed_loss`` [-], ``steady_drift_angle`` [rad],
        ``steady_yaw_rate`` [rad/s], ``steady`` (bool), ``final_heading_change`` [rad],
        ``approach_speed_value`` [m/s], ``propeller_rps`` [1/s], ``length`` [m],
        ``complete`` (bool), ``message`` (str).

    Raises
    ------
    ParameterError
        If a rudder angle is not within the steering gear's limit, a speed or rps is not
        > 0, ``speed`` and ``rps`` are both given, or the timing is invalid.
    """
    # a request seen before: its grid and validated batch as they were made (prepared.py)
    request = None if conditions is not None else request_key(
        "turning-circle", ship, rudder, sides, speed, rps, t_final, dt, record_dt,
        heading_change)
    prepared = ready(request)
    if prepared is None:
        rudder_axis = value_axis("rudder", rudder, "rad")
        side = side_axis(sides)
        plan = Plan(ship, speed, rps, [rudder_axis, side])
        check_rudder(plan.ships, "rudder", rudder_axis.values, positive=True)
        check_positive_change(heading_change)
        if dt is None:
            dt = usual_time_step(plan.ships, [a.speed for a in plan.approaches.values()])
        if t_final is None:
            signed: dict[tuple[int, int], list[float]] = {}
            for key in plan.approaches:
                if key in plan.failed:  # (not run)
                    continue
                signed[key] = [float(s_) * float(np.min(rudder_axis.values))
                               for s_ in side.values]
            t_final = _estimate_t_final(plan, signed, heading_change)
        t_final = final_time(float(t_final), float(dt))
        approaches = plan.run_approaches()
        record_every = (record_every_for(float(dt), record_dt, float(t_final))
                        if record_dt is not None
                        or "roll_angle" in plan.model.output_labels
                        or "roll_angle" in plan.model.state_labels
                        else min(default_record_every(  # (of the runs that run)
                            float(dt), *_of_runs_that_run(plan, plan.run_lengths(),
                                                          [a.speed for a in approaches])),
                            # (a t_final shorter than one default sample: every step; it was
                            # "`controller_dt` = 0.25 s exceeds t_final", an option never given)
                            max(1, int(round(float(t_final) / float(dt))))))

        x0 = np.array([a.state for a in approaches], dtype=float)  # (np.stack: runs, states)
        rudder0 = np.array([[a.rudder] for a in approaches])
        orders = plan.run_values("side") * plan.run_values("rudder")
        reference: dict[str, Any] = {"rudder_command": orders.reshape(-1, 1, 1)}
        if plan.ships[0].has_propeller:
            reference["propeller_rps"] = np.array([a.rps for a in approaches]).reshape(
                -1, 1, 1)
        problem = plan.problem(x0=x0, actuator_x0=rudder0, reference=reference, t_final=t_final,
                               dt=dt, record_every=record_every,
                               metadata={"maneuver": "turning-circle"},
                               controller_every=record_every, conditions=conditions)
        if not plan.warned:  # (its checked inputs kept too; its grid's values read-only)
            keep(request, (plan.freeze(), keep_inputs(problem)))
    else:
        plan, problem = prepared
    result = plan.run(problem)
    metrics = _metrics(plan, result)
    return ManeuverResult("turning-circle", metrics, tuple(plan.ships), result,
                          lambda: plan.runs_dataset(result))


def _of_runs_that_run(plan: Plan, lengths: np.ndarray, speeds: list[float]
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The runs' lengths and approach speeds, of the runs with an approach only (all of
    them, without a boolean selection, when every approach was found)."""
    if not plan.failed:
        return lengths, np.array(speeds)
    return lengths[plan.run_ok], np.array(speeds)[plan.run_ok]


#: Recorded samples per ship length travelled at the approach speed, by default.
SAMPLES_PER_LENGTH = 20


def default_record_every(dt: float, lengths: Any, speeds: Any) -> int:
    """Steps per recorded sample of a turning circle by default: the largest whole number of
    steps ``dt`` within L/(:data:`SAMPLES_PER_LENGTH` U) of the shortest time L/U of the
    batch (at least 1).

    Parameters
    ----------
    dt : float
        Integration step [s].
    lengths, speeds : array_like
        Each run's ship length L [m] and approach speed U [m/s].

    Returns
    -------
    int
    """
    scale = np.asarray(lengths, dtype=float) / np.asarray(speeds, dtype=float)
    scale = scale[np.isfinite(scale) & (scale > 0)]
    if not scale.size:
        return 1
    return max(1, int(math.floor(float(scale.min()) / SAMPLES_PER_LENGTH / dt + 1e-9)))


def check_positive_change(heading_change: float) -> None:
    """``heading_change`` must be > π (the tactical diameter needs 180°)."""
    if not (isinstance(heading_change, (int, float)) and heading_change >= math.pi):
        raise ParameterError(
            f"must be >= pi [rad] (180 deg, for the tactical diameter), got "
            f"{heading_change!r}", field="heading_change")


def _crossings(change: np.ndarray, levels: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First sample k with ``change >= level`` per level and run, and the weight w of sample k
    in the linear interpolation with sample k − 1 (k = −1, w = NaN where never reached).

    ``change`` has the shape (runs, steps), ``levels`` (levels,); k and w (levels, runs).
    """
    levels = np.ascontiguousarray(levels, dtype=float)
    k = np.empty((levels.size, change.shape[0]), dtype=np.int64)
    w = np.empty(k.shape)
    _first_crossings(np.ascontiguousarray(change, dtype=float), levels, k, w)
    return k, w


def _at_crossings(values: np.ndarray, k: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Signals (signals, runs, steps) linearly interpolated at the crossings of
    :func:`_crossings`: (signals, levels, runs)."""
    rows = np.arange(values.shape[1])
    cur = values[:, rows, np.maximum(k, 0)]
    prev = values[:, rows, np.maximum(k - 1, 0)]
    out = np.where(k > 0, prev + w * (cur - prev), cur)
    return np.where(k >= 0, out, np.nan)


def _cubic_crossings(times: np.ndarray, change: np.ndarray, levels: np.ndarray,
                     k: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The crossings of :func:`_crossings` refined by cubic (Lagrange) interpolation through
    the four samples around each: the first sample j0 of the four and the weights of the four
    at the crossing (levels, runs, 4), which give every signal there (:func:`_at_cubic`).

    Within the bracketing interval [t_{k−1}, t_k] the cubic through the heading change at
    j0 … j0 + 3 (j0 = k − 2, moved inside the record at its ends) is solved for the level by
    Newton's method from the linear estimate, kept inside the interval. The error is of
    order h⁴ in the recording interval h (linear interpolation: h²), so a turning circle
    recorded every L/(20 U) measures its events to far below the integration error.
    """
    j0, s_nodes, c_nodes, good, s = _bracket_arrays(k.shape)
    _bracket(times, np.ascontiguousarray(change, dtype=float), k, w, j0, s_nodes, c_nodes,
             good, s)
    return _cubic_weights(levels, j0, s_nodes, c_nodes, good, s)


def _bracket_arrays(shape: tuple[int, ...]) -> tuple[np.ndarray, ...]:
    """The outputs of :func:`_bracket` for (levels, runs) ``shape``: j0, s_nodes, c_nodes,
    good, s."""
    return (np.empty(shape, dtype=np.int64), np.empty(shape + (4,)), np.empty(shape + (4,)),
            np.empty(shape, dtype=np.bool_), np.empty(shape))


def _cubic_weights(levels: np.ndarray, j0: np.ndarray, s_nodes: np.ndarray,
                   c_nodes: np.ndarray, good: np.ndarray, s: np.ndarray,
                   every_good: bool | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_cubic_crossings` from the brackets :func:`_bracket` found: the cubic's power
    coefficients, Newton's method on it, the weights of the four nodes at the crossing.
    ``every_good``: ``good.all()`` if the caller knows it (:func:`_front` says)."""
    if every_good is None:
        every_good = bool(good.all())
    vander = s_nodes[..., None] ** _POWERS  # (levels, runs, 4 nodes, 4 powers)
    if not every_good:  # (every event inside the record: no placeholder to set)
        vander[~good] = np.eye(4)  # (placeholders: never used)
    # (one error state for both solves, _solve's: Newton's method is compiled, the powers of
    # s in [0, 1] or NaN raise no flag; the transposed view is np.swapaxes(vander, -1, -2))
    with np.errstate(all="ignore"):
        coef = _solve(vander, c_nodes[..., None], quiet=True)[..., 0]  # power coefficients
        _newton(np.ascontiguousarray(coef), levels, s)
        powers = s[..., None] ** _POWERS
        weights = _solve(vander.transpose(0, 1, 3, 2), powers[..., None], quiet=True)[..., 0]
    return j0, weights if every_good else np.where(good[..., None], weights, np.nan)


def _solve(a: np.ndarray, b: np.ndarray, quiet: bool = False) -> np.ndarray:
    """``np.linalg.solve(a, b)`` of stacked real 4 × 4 systems (float64, b of shape
    (..., 4, 1)): the LAPACK ``gesv`` gufunc that ``np.linalg.solve`` calls, called directly
    (its argument checks and error state cost ten times the solves of a turning circle's
    three events, issue 46 item 6); the same numbers. Where that gufunc is not found, or a
    system is singular (a NaN in the solution: the nodes are distinct times, so never in a
    manoeuvre), ``np.linalg.solve`` itself, which raises ``LinAlgError`` as before.
    ``quiet``: the caller holds ``np.errstate(all="ignore")`` already (not set again here)."""
    if _GESV is not None and a.dtype == np.float64 and b.dtype == np.float64:
        if quiet:
            out = _GESV(a, b, signature="dd->d")
        else:
            with np.errstate(all="ignore"):  # (as np.linalg.solve, without its raising call)
                out = _GESV(a, b, signature="dd->d")
        if np.isfinite(out).all():
            return out
    return np.linalg.solve(a, b)


def _gesv() -> Any:
    """numpy's stacked ``solve`` gufunc (None where this numpy does not have it)."""
    try:
        from numpy.linalg import _umath_linalg
    except ImportError:  # pragma: no cover - another numpy
        return None
    gufunc = getattr(_umath_linalg, "solve", None)
    return gufunc if isinstance(gufunc, np.ufunc) else None


_GESV = _gesv()


def _at_cubic(values: np.ndarray, k: np.ndarray, w: np.ndarray, j0: np.ndarray,
              weights: np.ndarray) -> np.ndarray:
    """Signals (signals, runs, steps) at the crossings, by the cubic weights of
    :func:`_cubic_crossings` (linear where fewer than four samples): (signals, levels,
    runs)."""
    steps = values.shape[2]
    if steps < 4:
        return _at_crossings(values, k, w)
    idx = j0[..., None] + _POWERS
    rows = np.arange(values.shape[1])[None, :, None]
    return _weigh(values[:, rows, idx], k, w, weights, lambda: values)


def _weigh(nodes: np.ndarray, k: np.ndarray, w: np.ndarray, weights: np.ndarray,
           full: Any) -> np.ndarray:
    """The signals at the crossings from their values at the four nodes of each, ``nodes``
    (signals, levels, runs, 4), by the cubic weights (:func:`_at_cubic`); where a crossing
    has no cubic (not reached, or at the record's start) the linear interpolation of the
    whole signals ``full()`` (signals, runs, steps), asked for only then."""
    finite = np.isfinite(weights)
    every = bool(finite.all())  # (the usual case: no NaN weight to zero)
    out = np.einsum("slrj,lrj->slr", nodes, weights if every else np.nan_to_num(weights))
    cubic = (k >= 0) & finite[..., 0]
    if cubic.all():  # (every event reached inside the record: no linear fallback to take)
        return out
    return np.where(cubic, out, _at_crossings(full(), k, w))


def _event_values(north: np.ndarray, east: np.ndarray, psi: np.ndarray, times: np.ndarray,
                  dist: np.ndarray, k: np.ndarray, w: np.ndarray, j0: np.ndarray,
                  weights: np.ndarray) -> np.ndarray:
    """The distances along and across the original course (from the position at the order),
    the time and the distance along the track at every event (:func:`_at_cubic` of the four
    signals): (4, levels, runs).

    The distances are formed at the four nodes of each event only, each element by the same
    operations as over the whole record (so the same numbers), and gathered into the memory
    layout :func:`_at_cubic`'s gather of the stacked signals has (signal innermost: the
    weighted sum runs as it did). Where some event has no cubic (not reached: the linear
    fallback) the whole record is formed and :func:`_at_cubic` takes it, as before.
    """
    n0, e0 = north[:, :1], east[:, :1]
    c0, s0 = np.cos(psi[:, :1]), np.sin(psi[:, :1])

    def full() -> np.ndarray:
        dn, de = north - n0, east - e0
        return np.stack([dn * c0 + de * s0, np.abs(-dn * s0 + de * c0), times, dist])

    if north.shape[1] < 4:
        return _at_cubic(full(), k, w, j0, weights)
    buf = np.empty(k.shape + (4, 4))  # (levels, runs, nodes, signals)
    found = _event_nodes(north, east, np.ascontiguousarray(times, dtype=float),
                         np.ascontiguousarray(dist, dtype=float), k, j0,
                         np.ascontiguousarray(weights), c0[:, 0].copy(), s0[:, 0].copy(), buf)
    if found == 0:  # (an event without a cubic: the linear fallback needs the whole record)
        return _at_cubic(full(), k, w, j0, weights)
    if found == 2:  # (every weight finite, every event reached: _weigh's first path)
        return np.einsum("slrj,lrj->slr", buf.transpose(3, 0, 1, 2), weights)
    return _weigh(buf.transpose(3, 0, 1, 2), k, w, weights, full)


#: Heading changes of the events: 90 deg (advance, transfer), 180 deg (tactical diameter),
#: 10 deg (initial turning).
_LEVELS = np.array([0.5 * math.pi, math.pi, _DEG10])
#: The three-point Gauss-Legendre nodes of the track distance (:mod:`.track`).
_GAUSS_NODES = _gauss3()[0]
_NOT_STEADY = ("ok; the turn was not yet steady at the end (yaw rate still changing by > 1 % "
               "over the last 90 deg): steady values are the last sample's")


def _metrics(plan: Plan, result: Any) -> Any:
    t = result.time
    north, east, psi = result["north"], result["east"], result["heading"]
    speed = result["speed"]
    r = result["yaw_rate"]
    # (one run: the time row itself, contiguous; a batch: broadcast, then a contiguous copy)
    times = np.ascontiguousarray(t.reshape(1, -1) if psi.shape[0] == 1
                                 else np.broadcast_to(t, psi.shape))
    # the heading change, the crossings (_crossings), their brackets (_cubic_crossings), the
    # steady end of each turn and the speeds along the track up to the 10 deg event (the
    # distance along the track is read there only: its four samples j0..) in one compiled
    # call (_front; five before, and distance_until's checks)
    n, (runs, samples) = plan.n_runs, psi.shape
    k = np.empty((_LEVELS.size, runs), dtype=np.int64)
    w = np.empty(k.shape)
    j0, s_nodes, c_nodes, good, s = _bracket_arrays(k.shape)
    radius, steady = np.empty(n), np.empty(n, dtype=np.bool_)
    change, h, rates = np.empty((runs, samples)), np.empty(samples - 1), np.empty(
        (samples - 1, 3, runs))
    width, every_good = _front(psi, _LEVELS, t, times, r, speed, north, east, _GAUSS_NODES, 2,
                               change, k, w, j0, s_nodes, c_nodes, good, s, radius, steady, h,
                               rates)
    j0, weights = _cubic_weights(_LEVELS, j0, s_nodes, c_nodes, good, s, every_good)
    dist = (_arc_distances(h, rates, width, samples) if width >= 0
            else distance_until(north, east, t, until=j0[2] + 3))  # (the general form's)
    # every signal at every event (a few are not needed: all cost one gather)
    (along_at, across_at, time_at, dist_at) = _event_values(north, east, psi, times, dist, k,
                                                            w, j0, weights)
    advance, transfer, time_90 = along_at[0], across_at[0], time_at[0]
    tactical_diameter, time_180 = across_at[1], time_at[1]
    time_10, distance_10 = time_at[2], dist_at[2]
    constant = is_constant_speed(plan.model)
    # a constant-speed model has no drift angle unless it declares one (Voitkunsky's β)
    try:  # (a channel of the result: what result.channel_names() lists)
        beta = result["drift_angle"]
    except KeyError:
        beta = np.full_like(r, np.nan)
    approaches = plan.run_approaches()
    U0 = np.array([a.speed for a in approaches])
    rps = np.array([np.nan if (x := a.rps) is None else x for a in approaches])
    length = plan.run_lengths()
    steady_r = r[:, -1]
    steady_U = speed[:, -1]
    # (radius: U/|r| at the end, inf where r = 0; steady: |r| changed by <= 1 % since the
    # last sample 90 deg of heading before the end: _steady_ends, in _first_pass)
    # complete: every event reached and the run went well, its status 0 (message "ok"), in
    # one compiled pass (most runs: nothing more to say, their message set for all at once;
    # the loop below is over the others only, with the runs' messages)
    complete = np.empty(n, dtype=bool)
    missing = _completion(time_at, result.status, complete)
    status = result.messages() if missing else []
    messages = ["ok" if steady_i else _NOT_STEADY for steady_i in steady.tolist()]
    for i in (np.flatnonzero(~complete).tolist() if missing else []):
        missing = [f"{name} heading change" for name, value in
                   (("10 deg", time_10[i]), ("90 deg", time_90[i]), ("180 deg", time_180[i]))
                   if np.isnan(value)]
        text = []
        if status[i] != "ok":
            text.append(status[i])
        if missing:
            text.append(f"{', '.join(missing)} not reached within t_final = {t[-1]:.6g} s "
                        f"(final heading change {math.degrees(change[i, -1]):.4g} deg)")
        messages[i] = "; ".join(text)  # (not complete: something to say)
    variables = {
        "advance": (advance, "m", "advance at 90 deg heading change"),
        "transfer": (transfer, "m", "transfer at 90 deg heading change"),
        "tactical_diameter": (tactical_diameter, "m",
                              "tactical diameter (transfer at 180 deg heading change)"),
        "time_90": (time_90, "s", "time to 90 deg heading change"),
        "time_180": (time_180, "s", "time to 180 deg heading change"),
        "time_10": (time_10, "s", "time to 10 deg heading change"),
        "distance_10": (distance_10, "m",
                        "distance along the track to 10 deg heading change"),
        "steady_radius": (radius, "m", "turning radius U/|r| at the end of the run"),
        "steady_speed": (steady_U, "m/s", "speed at the end of the run"),
        "speed_loss": (np.full(n, np.nan) if constant else 1.0 - steady_U / U0, "1",
                       "speed loss 1 - U/U_0 at the end of the run"
                       + (f" (NaN: {CONSTANT_SPEED_NOTE})" if constant else "")),
        "steady_drift_angle": (beta[:, -1], "rad", "drift angle at the end of the run"
                               + (" (NaN: the model has no drift angle)"
                                  if constant and np.isnan(beta[:, -1]).all() else "")),
        "steady_yaw_rate": (steady_r, "rad/s", "yaw rate at the end of the run"),
        "steady": (steady, "", "yaw rate changed < 1 % over the last 90 deg of heading"),
        "final_heading_change": (change[:, -1], "rad", "heading change at the end of the run"),
        "approach_speed_value": (U0, "m/s", "approach speed U_0"),
        "propeller_rps": (rps, "1/s", "propeller rps (constant; NaN: no propeller input)"),
        "length": (length, "m", "ship length L"),
        "complete": (complete, "", "every event reached and the run did not diverge"),
        "message": (np.array(messages, dtype=object), "", "what was not reached, or ok"),
    }
    variables.update(heel_metrics(result))  # a model with roll: maximum and steady heel
    attrs = {"maneuver": "turning-circle", "dt": float(result.metadata["dt"]),
             "t_final": float(result.metadata["t_final"]),
             "reference_point": "midship (the model's origin)",
             "measured_from": "rudder order at t = 0",
             "interpolation": ("cubic through the four recorded samples around each event "
                               "(linear with fewer than four)"),
             "record_dt": float(result.time[1] - result.time[0]) if result.time.size > 1
             else float(result.metadata["dt"])}
    if constant:
        attrs["speed"] = CONSTANT_SPEED_NOTE
    return plan.dataset(variables, attrs=attrs)
