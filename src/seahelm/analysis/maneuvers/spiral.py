"""Spiral tests: the steady r–δ curve and its hysteresis loop.

:func:`direct_spiral` (Dieudonné 1953)
    simulated: from a steady approach the rudder is set to a sequence of angles from starboard
    to port and back (default 20°, 15°, 10°, 5°, 3°, 2°, 1°, 0.5°, 0°, −0.5°, ..., −20°, then
    up again to 20°), each held for ``hold`` seconds; the steady yaw rate of each step is the
    mean over the last 10 % of its hold. A course-unstable ship keeps turning to one side
    after the rudder has passed zero, and jumps to the other branch only beyond a critical
    rudder angle: the curves of the two legs differ by the hysteresis loop. Its width here is
    the distance between the rudder angles at which r changes sign on the descending and the
    ascending leg (each interpolated linearly between the program's steps, so it is resolved
    to the step of the program near zero).
:func:`reverse_spiral` (Bech 1966)
    the rudder angle needed for a sequence of yaw rates. Bech's test holds the yaw rate with a
    controller and measures the mean rudder angle; here the same points are computed as the
    **equilibria** of the model at the prescribed yaw rates
    (:func:`seahelm.analysis.equilibria.equilibrium.rudder_for_yaw_rate`, continuation in r) — the
    limit a perfect yaw-rate controller reaches, without transients or controller tuning, and
    including the part of the curve that is unstable at fixed rudder. The loop width is exact: the
    rudder angles of the local extrema of δ(r) (refined on a fine grid of r around each), the
    band in which a fixed rudder angle has three steady turns. A course-stable ship has a
    monotonic δ(r) and width 0.

Both batch over ships and approach speeds (the MMG propeller keeps the approach's
self-propulsion rps).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._validate import as_float_array
from ...errors import ParameterError
from ...simulation.engine import check_record_memory
from ..equilibria.equilibrium import rudder_for_yaw_rate, steady_turn
from .common import (
    Plan,
    check_rudder,
    usual_time_step,
    final_time,
)
from .result import ManeuverResult

__all__ = ["DEFAULT_SPIRAL_RUDDERS_DEG", "direct_spiral", "reverse_spiral", "spiral_loop", "spirals"]

_DOWN = (20.0, 15.0, 10.0, 5.0, 3.0, 2.0, 1.0, 0.5, 0.0, -0.5, -1.0, -2.0, -3.0, -5.0, -10.0,
         -15.0, -20.0)
#: The default program of the direct spiral [deg]: starboard to port and back.
DEFAULT_SPIRAL_RUDDERS_DEG: tuple[float, ...] = _DOWN + tuple(reversed(_DOWN[:-1]))


def _legs(rudders: np.ndarray) -> np.ndarray:
    """−1 on a descending step, +1 on an ascending one, 0 for the first step."""
    legs = np.zeros(rudders.size, dtype=np.int64)
    for j in range(1, rudders.size):
        diff = rudders[j] - rudders[j - 1]
        legs[j] = -1 if diff < 0 else (1 if diff > 0 else legs[j - 1])
    if rudders.size > 1:
        legs[0] = legs[1]
    return legs


def _sign_change(delta: np.ndarray, r: np.ndarray) -> float:
    """Rudder angle of the first sign change of r along a leg (linear interpolation)."""
    for j in range(1, r.size):
        if np.isfinite(r[j - 1]) and np.isfinite(r[j]) and r[j - 1] * r[j] <= 0.0 \
                and r[j - 1] != r[j]:
            w = r[j - 1] / (r[j - 1] - r[j])
            return float(delta[j - 1] + w * (delta[j] - delta[j - 1]))
    return math.nan


def direct_spiral(ship: Any, rudders: Any = None, *, speed: Any = None, rps: Any = None,
                  hold: float | None = None, dt: float | None = None,
                  samples_per_hold: int = 100) -> ManeuverResult:
    """Dieudonné's direct spiral: steady yaw rate over a rudder program, both ways.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path), Params, or a sequence of them
        The ship(s); a sequence gives a ``ship`` dimension (one model).
    rudders : sequence of float, optional
        Absolute rudder angles [rad] in the order they are set (default
        :data:`DEFAULT_SPIRAL_RUDDERS_DEG` in radians), each within the steering gear's limit.
    speed : float or sequence of float, optional
        Approach speed(s) [m/s] (default: the parameter set's).
    rps : float or sequence of float, optional
        Instead of ``speed``: the propeller rps [1/s] (MMG).
    hold : float, optional
        Time each rudder angle is held [s] (default 50 L/U_0 of the slowest ship of the grid).
    dt : float, optional
        Integration step [s] (default :func:`~seahelm.analysis.maneuvers.default_time_step`).
    samples_per_hold : int, optional
        Recorded samples per hold (default 100).

    Returns
    -------
    ManeuverResult
        ``metrics`` over the batch dims and ``step`` (coordinates ``step_rudder(step)`` [rad]
        and ``leg(step)``: −1 descending, +1 ascending): ``yaw_rate`` [rad/s], ``yaw_rate_nd``
        (r L/U) [-], ``speed`` [m/s], ``settled`` (bool); and per ship/speed
        ``loop_width`` [rad], ``zero_crossing_down``, ``zero_crossing_up`` [rad],
        ``complete``, ``message``.

    Raises
    ------
    ParameterError
        If a rudder angle is beyond the steering gear's limit, the program has fewer than two
        steps, or ``hold``/``samples_per_hold`` is not positive.
    """
    deltas = np.radians(DEFAULT_SPIRAL_RUDDERS_DEG) if rudders is None else \
        as_float_array("rudders", rudders, "rad")
    if deltas.ndim != 1 or deltas.size < 2:
        raise ParameterError(
            f"must be a 1-D sequence of at least 2 angles [rad], got shape "
            f"{deltas.shape}", field="rudders")
    if isinstance(samples_per_hold, bool) or int(samples_per_hold) != samples_per_hold \
            or samples_per_hold < 10:
        raise ParameterError(
            f"must be a whole number >= 10, got {samples_per_hold!r}", field="samples_per_hold")
    plan = Plan(ship, speed, rps, [])
    check_rudder(plan.ships, "rudders", deltas, allow_zero=True)
    n = plan.n_runs
    if dt is None:
        dt = usual_time_step(plan.ships, [a.speed for a in plan.approaches.values()])
    if hold is None:
        hold = max(50.0 * plan.ship(i).length / plan.approach(i).speed for i in range(n))
    if not (isinstance(hold, (int, float)) and hold > 0):
        raise ParameterError(f"must be > 0 [s], got {hold!r}", field="hold")
    hold = final_time(float(hold), float(dt), "hold")
    steps_per_hold = int(round(hold / dt))
    n_steps = steps_per_hold * deltas.size
    try:  # the rudder program is given on every step: it must fit
        check_record_memory(1, n_steps + 1, 2)
    except ParameterError:
        raise ParameterError(
            f": {deltas.size} holds of {hold:g} s at dt = {dt:g} s are {n_steps:,} steps, "
            "more than a rudder program in memory can span; shorten `hold` or enlarge `dt` "
            "[s]", field="hold") from None
    record_every = max(1, steps_per_hold // int(samples_per_hold))
    while steps_per_hold % record_every:
        record_every -= 1
    t_final = hold * deltas.size
    program = deltas[np.minimum(np.arange(n_steps + 1) // steps_per_hold, deltas.size - 1)]
    reference: dict[str, Any] = {"rudder_command": program.reshape(1, -1, 1)}
    if plan.ships[0].has_propeller:
        reference["propeller_rps"] = np.array(
            [plan.approach(i).rps for i in range(n)]).reshape(-1, 1, 1)
    x0 = np.stack([plan.approach(i).state for i in range(n)])
    rudder0 = np.array([[plan.approach(i).rudder] for i in range(n)])
    result = plan.simulate(x0=x0, actuator_x0=rudder0, reference=reference, t_final=t_final,
                           dt=dt, record_every=record_every,
                           metadata={"maneuver": "direct-spiral"},
                           controller_every=record_every)
    t = result.time
    r, U = result["yaw_rate"], result["speed"]
    legs = _legs(deltas)
    m = deltas.size
    yaw = np.full((n, m), np.nan)
    spd = np.full((n, m), np.nan)
    settled = np.zeros((n, m), dtype=bool)
    for j in range(m):
        last = (t > (j + 0.9) * hold - 1e-9) & (t <= (j + 1) * hold + 1e-9)
        before = (t > (j + 0.8) * hold - 1e-9) & (t <= (j + 0.9) * hold + 1e-9)
        yaw[:, j] = np.mean(r[:, last], axis=1)
        spd[:, j] = np.mean(U[:, last], axis=1)
        r_before = np.mean(r[:, before], axis=1)
        scale = np.array([plan.approach(i).speed / plan.ship(i).length for i in range(n)])
        settled[:, j] = np.abs(yaw[:, j] - r_before) <= np.maximum(0.01 * np.abs(yaw[:, j]),
                                                                   1e-4 * scale)
    length = np.array([plan.ship(i).length for i in range(n)])
    down_mask, up_mask = legs < 0, legs > 0
    cross_down = np.array([_sign_change(deltas[down_mask], yaw[i, down_mask]) for i in range(n)])
    cross_up = np.array([_sign_change(deltas[up_mask], yaw[i, up_mask]) for i in range(n)])
    status = result.messages()
    messages = []
    for i in range(n):
        text = [] if status[i] == "ok" else [status[i]]
        if not settled[i].all():
            bad = ", ".join(f"{math.degrees(d):g}" for d in deltas[~settled[i]])
            text.append(f"yaw rate not settled within the hold of {hold:.6g} s at rudder "
                        f"{bad} deg")
        if np.isnan(cross_down[i]) or np.isnan(cross_up[i]):
            text.append("the yaw rate does not change sign on both legs: no loop width")
        messages.append("; ".join(text) if text else "ok")
    variables = {
        "yaw_rate": (yaw, "rad/s", "steady yaw rate (mean over the last 10 % of the hold)"),
        "yaw_rate_nd": (yaw * length[:, None] / spd, "1", "non-dimensional yaw rate r L/U"),
        "speed": (spd, "m/s", "steady speed (mean over the last 10 % of the hold)"),
        "settled": (settled, "", "yaw rate changed < 1 % between the last two tenths"),
        "zero_crossing_down": (cross_down, "rad", "rudder angle where r changes sign on the "
                                                 "descending leg"),
        "zero_crossing_up": (cross_up, "rad", "rudder angle where r changes sign on the "
                                             "ascending leg"),
        "loop_width": (np.abs(cross_up - cross_down), "rad",
                       "hysteresis loop width |crossing up - crossing down| (resolution: the "
                       "program's step near zero)"),
        "length": (length, "m", "ship length L"),
        "complete": (np.array([m_ == "ok" for m_ in messages]), "", "settled, not diverged"),
        "message": (np.array(messages, dtype=object), "", "what was not reached, or ok"),
    }
    extra = {k: ("step", m) for k in ("yaw_rate", "yaw_rate_nd", "speed", "settled")}
    attrs = {"maneuver": "direct-spiral", "dt": float(dt), "hold": float(hold),
             "t_final": float(t_final)}
    metrics = plan.dataset(variables, extra_dims=extra, attrs=attrs, coords={
        "step": ("step", np.arange(m)),
        "step_rudder": ("step", deltas, {"units": "rad",
                                         "long_name": "rudder angle of the step"}),
        "leg": ("step", legs, {"long_name": "-1 descending (starboard to port), +1 ascending"})})
    return ManeuverResult("direct-spiral", metrics, tuple(plan.ships), result,
                          lambda: plan.runs_dataset(result))


def spiral_loop(params: Any, yaw_rate: np.ndarray, rudder: np.ndarray, rps: float | None = None,
                *, model: Any = None, refine: int = 41) -> tuple[float, float, float]:
    """The hysteresis loop of a spiral curve δ(r): (width, rudder low, rudder high) [rad].

    The local maxima and minima of δ(r) (sampled at increasing ``yaw_rate``) are refined on a
    grid of ``refine`` yaw rates between their neighbours
    (:func:`~seahelm.analysis.equilibria.equilibrium.rudder_for_yaw_rate`); the loop spans from the
    smallest local minimum to the largest local maximum of δ. A monotonic curve has no loop:
    (0, NaN, NaN).

    Parameters
    ----------
    params : Params, Ship or str
        Parameter set.
    yaw_rate : numpy.ndarray, shape (k,)
        Yaw rates [rad/s], increasing.
    rudder : numpy.ndarray, shape (k,)
        Rudder angles δ(r) of the steady turns [rad].
    rps : float, optional
        Propeller rps [1/s] (models with a propeller input).
    model : VesselModel, optional
        The model (default: the one for the parameter type).
    refine : int, optional
        Points of the refining grid (default 41).

    Returns
    -------
    tuple of float
        Loop width [rad], lower and upper rudder angle of the loop [rad].
    """
    r = np.asarray(yaw_rate, dtype=float)
    d = np.asarray(rudder, dtype=float)
    if r.ndim != 1 or r.shape != d.shape or np.any(np.diff(r) <= 0):
        raise ParameterError("must be increasing and `rudder` of its shape", field="yaw_rate")
    maxima, minima = [], []
    for k in range(1, r.size - 1):
        if d[k] > d[k - 1] and d[k] >= d[k + 1]:
            maxima.append(k)
        elif d[k] < d[k - 1] and d[k] <= d[k + 1]:
            minima.append(k)
    if not maxima or not minima:
        return 0.0, math.nan, math.nan
    highs, lows = [], []
    for group, pick, out in ((maxima, np.max, highs), (minima, np.min, lows)):
        for k in group:
            fine = np.linspace(r[k - 1], r[k + 1], refine)
            curve = rudder_for_yaw_rate(params, fine, rps, model=model)
            out.append(float(pick(np.append(curve.rudder, d[k]))))
    hi, lo = max(highs), min(lows)
    return hi - lo, lo, hi


def reverse_spiral(ship: Any, yaw_rates: Any = None, *, speed: Any = None, rps: Any = None,
                   max_rudder: float = math.radians(20.0), points: int = 41) -> ManeuverResult:
    """Bech's reverse spiral from the model's equilibria: δ needed for each yaw rate.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path), Params, or a sequence of them
        The ship(s); a sequence gives a ``ship`` dimension.
    yaw_rates : sequence of float, optional
        Yaw rates r [rad/s], increasing (default: ``points`` values evenly between the steady
        yaw rates at −``max_rudder`` and +``max_rudder``, and 0).
    speed : float or sequence of float, optional
        Approach speed(s) [m/s] (default: the parameter set's).
    rps : float or sequence of float, optional
        Instead of ``speed``: the propeller rps [1/s] (MMG).
    max_rudder : float, optional
        Rudder angle [rad] whose steady yaw rates bound the default yaw rates (default 20°).
    points : int, optional
        Number of default yaw rates (default 41).

    Returns
    -------
    ManeuverResult
        ``runs`` None; ``metrics`` over the batch dims and ``point``: ``yaw_rate`` [rad/s],
        ``rudder_angle`` [rad], ``speed`` [m/s], ``drift_angle`` [rad], ``yaw_rate_nd``
        (r L/U) [-]; and per ship/speed ``loop_width``, ``loop_rudder_low``,
        ``loop_rudder_high`` [rad], ``complete``, ``message``.

    Raises
    ------
    ParameterError
        On invalid yaw rates, speeds or ``max_rudder``.
    EquilibriumError
        If a yaw rate has no steady turn (beyond what the hull and rudder can balance).
    """
    if isinstance(points, bool) or int(points) != points or points < 5:
        raise ParameterError(f"must be a whole number >= 5, got {points!r}", field="points")
    given = None
    if yaw_rates is not None:
        given = as_float_array("yaw_rates", yaw_rates, "rad/s")
        if given.ndim != 1 or given.size < 3 or np.any(np.diff(given) <= 0):
            raise ParameterError(
                "must be an increasing 1-D sequence of at least 3 values [rad/s]",
                field="yaw_rates")
    plan = Plan(ship, speed, rps, [])
    check_rudder(plan.ships, "max_rudder", np.array([max_rudder]))
    n = plan.n_runs
    k = given.size if given is not None else int(points) + 1
    cols = {name: np.full((n, k), np.nan) for name in
            ("yaw_rate", "rudder_angle", "speed", "drift_angle", "yaw_rate_nd")}
    width = np.full(n, np.nan)
    low = np.full(n, np.nan)
    high = np.full(n, np.nan)
    for i in np.flatnonzero(plan.run_ok).tolist():
        s, a = plan.ship(i), plan.approach(i)
        if given is None:
            ends = steady_turn(s.params, np.array([-max_rudder, max_rudder]), a.rps,
                               model=s.model, max_rudder=s.max_rudder).yaw_rate
            rates = np.union1d(np.linspace(ends[0], ends[1], int(points)), [0.0])
        else:
            rates = given
        curve = rudder_for_yaw_rate(s.params, rates, a.rps, model=s.model)
        cols["yaw_rate"][i, :rates.size] = rates
        cols["rudder_angle"][i, :rates.size] = curve.rudder
        cols["speed"][i, :rates.size] = curve.speed
        cols["drift_angle"][i, :rates.size] = curve.drift_angle
        cols["yaw_rate_nd"][i, :rates.size] = rates * s.length / curve.speed
        width[i], low[i], high[i] = spiral_loop(s.params, rates, curve.rudder, a.rps,
                                                model=s.model)
    variables = {
        "yaw_rate": (cols["yaw_rate"], "rad/s", "prescribed yaw rate"),
        "rudder_angle": (cols["rudder_angle"], "rad", "rudder angle of the steady turn"),
        "speed": (cols["speed"], "m/s", "speed of the steady turn"),
        "drift_angle": (cols["drift_angle"], "rad", "drift angle of the steady turn"),
        "yaw_rate_nd": (cols["yaw_rate_nd"], "1", "non-dimensional yaw rate r L/U"),
        "loop_width": (width, "rad", "hysteresis loop width (0: course stable)"),
        "loop_rudder_low": (low, "rad", "lower rudder angle of the loop"),
        "loop_rudder_high": (high, "rad", "upper rudder angle of the loop"),
        "length": (np.array([plan.ship(i).length for i in range(n)]), "m", "ship length L"),
        "complete": (np.ones(n, dtype=bool), "", "every equilibrium found"),
        "message": (np.array(["ok"] * n, dtype=object), "", "ok"),
    }
    extra = {name: ("point", k) for name in cols}
    attrs = {"maneuver": "reverse-spiral",
             "method": "equilibria of the model at prescribed yaw rates (continuation in r); "
                       "the limit of Bech's test with a perfect yaw-rate controller"}
    metrics = plan.dataset(variables, extra_dims=extra, attrs=attrs,
                           coords={"point": ("point", np.arange(k))})
    return ManeuverResult("reverse-spiral", metrics, tuple(plan.ships))



def spirals(ship: Any, max_rudder: float = math.radians(20.0), *, speed: Any = None,
            rps: Any = None, hold: float | None = None, dt: float | None = None
            ) -> tuple[ManeuverResult, ManeuverResult]:
    """Both spiral tests of a ship up to a rudder angle: the direct and the reverse spiral.

    The direct spiral runs :data:`DEFAULT_SPIRAL_RUDDERS_DEG` scaled so that its largest
    angle is ``max_rudder``; the reverse spiral spans the yaw rates of ±``max_rudder``.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path) or Params
        The ship (:func:`~seahelm.analysis.maneuvers.maneuver_ship`).
    max_rudder : float, optional
        Largest rudder angle [rad], within the steering gear's limit (default 20°).
    speed, rps : float, optional
        Approach speed [m/s] or propeller rps [1/s] (default: the parameter set's speed).
    hold : float, optional
        Time each rudder angle of the direct spiral is held [s] (default 50 L/U_0).
    dt : float, optional
        Integration step [s] of the direct spiral.

    Returns
    -------
    (ManeuverResult, ManeuverResult)
        :func:`direct_spiral`'s and :func:`reverse_spiral`'s results.
    """
    top = float(max_rudder)
    program = np.radians(DEFAULT_SPIRAL_RUDDERS_DEG) * (top / math.radians(20.0))
    direct = direct_spiral(ship, program, speed=speed, rps=rps, hold=hold, dt=dt)
    reverse = reverse_spiral(ship, speed=speed, rps=rps, max_rudder=top)
    return direct, reverse
