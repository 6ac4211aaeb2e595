"""Zig-zag tests (any δ/ψ pair, either first side) over batches, and their metrics.

The test (IMO Resolution MSC.137(76) and its explanatory notes MSC/Circ.1053; ITTC 7.5-04-02-01):
from a steady straight approach on the base heading ψ_0 the rudder is ordered to δ_z on the
first side s (first execute, t = 0); when the heading deviation ψ − ψ_0 has reached s ψ_z the
rudder is reversed to −s δ_z (second execute); when it has reached −s ψ_z the rudder is reversed
again (third execute); and so on. The reversals are made by the compiled controller
:data:`seahelm.control.zigzag.ZIGZAG` (or ``ZIGZAG_RPS`` for a model with a propeller input, the
propeller held at the approach rps).

Metrics (:func:`zigzag_metrics`, on the recorded heading alone):

execute times t_2, t_3, t_4
    when the heading deviation crosses +s ψ_z, −s ψ_z, +s ψ_z in turn (linear interpolation
    between the bracketing samples); the **initial turning time** is t_2 (from the order);
overshoot angles o_1, o_2, o_3
    the heading excursion beyond the trigger after executes 2, 3, 4: at the first extreme of
    the deviation after the execute, |ψ_ext − ψ_0| − ψ_z (≥ 0); the extreme and its time are
    the vertex of the parabola through the largest sample and its two neighbours;
overshoot times
    the times of those extremes (from the order);
time to check yaw
    from the second execute to the first extreme, t_ext,1 − t_2;
period
    t_4 − t_2, from the second execute to the next reversal to the same side (one full cycle
    of the heading).

The rudder reversals themselves fall on the controller's samples: the controller reverses at
the sample nearest to the crossing (:mod:`seahelm.control.zigzag`), an unbiased timing error
within ±Δt/2, which moves an overshoot by up to about r Δt/2 (r the yaw rate at the execute).
At the default step (0.025 s for the KVLCC2 L7, 0.1 s for the Mariner) that is within ±0.03°;
a smaller ``dt`` reduces it in proportion.

Anything not reached within the run is NaN, with ``complete`` False and a ``message`` naming it.
Before a run, a trigger that the steady turn at δ_z cannot reach in the given ``t_final``
(even turning at the steady yaw rate from the order) is refused with a
:class:`~seahelm.errors.ParameterError`.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from ..._validate import as_float_array
from ...control.zigzag import ZIGZAG, ZIGZAG_RPS, ZigZagParams, ZigZagRpsParams
from ...errors import ParameterError
from .common import (
    Axis,
    Plan,
    check_rudder,
    usual_time_step,
    final_time,
    record_every_for,
    side_axis,
)
from .ships import steady_yaw_rates, yaw_lag
from .result import ManeuverResult

__all__ = ["ZigZagMetrics", "zigzag_metrics", "zigzag"]

N_OVERSHOOTS = 3


class ZigZagMetrics(NamedTuple):
    """Zig-zag metrics per run (NaN where not reached); angles [rad], times [s]."""

    execute_time: np.ndarray
    """(runs, 3): times of the 2nd, 3rd and 4th executes (rudder reversals) [s]."""
    overshoot: np.ndarray
    """(runs, 3): 1st, 2nd, 3rd overshoot angles [rad] (≥ 0)."""
    overshoot_time: np.ndarray
    """(runs, 3): times of the heading extremes of the three overshoots [s]."""
    extreme_heading: np.ndarray
    """(runs, 3): heading deviations ψ − ψ_0 at those extremes [rad] (signed)."""
    initial_turning_time: np.ndarray
    """(runs,): time from the order to the 2nd execute [s]."""
    time_to_check_yaw: np.ndarray
    """(runs,): from the 2nd execute to the first heading extreme [s]."""
    period: np.ndarray
    """(runs,): from the 2nd to the 4th execute [s]."""
    message: list[str]
    """Per run: 'ok' or what was not reached."""


def _crossing(t: np.ndarray, y: np.ndarray, level: float, start: int) -> tuple[int, float]:
    """First k ≥ start with y[k] ≥ level, and the interpolated crossing time (−1, NaN)."""
    hit = np.flatnonzero(y[start:] >= level)
    if hit.size == 0:
        return -1, math.nan
    k = start + int(hit[0])
    if k == 0 or y[k] == level:
        return k, float(t[k])
    w = (level - y[k - 1]) / (y[k] - y[k - 1])
    return k, float(t[k - 1] + w * (t[k] - t[k - 1]))


def _first_maximum(t: np.ndarray, y: np.ndarray, start: int) -> tuple[int, float, float]:
    """First local maximum of y at or after ``start`` with its parabolic vertex (−1 if the
    signal is still rising at the end)."""
    falling = np.flatnonzero(np.diff(y[start:]) < 0.0)
    if falling.size == 0:
        return -1, math.nan, math.nan
    m = start + int(falling[0])
    if m == 0:
        return m, float(t[0]), float(y[0])
    t0, t1, t2 = t[m - 1], t[m], t[m + 1]
    y0, y1, y2 = y[m - 1], y[m], y[m + 1]
    # parabola through the three samples, in local time s = t − t1 (any spacing)
    a_, b_ = t0 - t1, t2 - t1
    d0, d2 = y0 - y1, y2 - y1
    den = a_ * b_ * (a_ - b_)
    A = (d0 * b_ - d2 * a_) / den
    B = (d2 * a_ * a_ - d0 * b_ * b_) / den
    if A >= 0.0:  # not concave (flat top): the largest sample itself
        return m, float(t1), float(y1)
    s = -B / (2.0 * A)
    s = min(max(s, a_), b_)
    return m, float(t1 + s), float(y1 + A * s * s + B * s)


def zigzag_metrics(time: Any, heading: Any, *, trigger: Any, first_side: Any = 1,
                   base_heading: Any = 0.0, order_time: float = 0.0) -> ZigZagMetrics:
    """Executes, overshoots, initial turning time, time to check yaw and period of zig-zags.

    Works on the recorded heading alone (see the module docstring for the definitions); the
    rudder is assumed reversed at each trigger crossing.

    Parameters
    ----------
    time : array_like, shape (steps,)
        Recording times [s], increasing.
    heading : array_like, shape (steps,) or (runs, steps)
        Continuous (unwrapped) heading ψ [rad].
    trigger : float or array_like, shape (runs,)
        Heading trigger ψ_z [rad], > 0.
    first_side : int or array_like, shape (runs,), optional
        Side of the first execute, +1 starboard (heading increasing) or −1 port (default +1).
    base_heading : float or array_like, shape (runs,), optional
        Heading of the approach ψ_0 [rad] (default 0).
    order_time : float, optional
        Time of the first execute [s] (default 0); events are searched from it and times are
        measured from it.

    Returns
    -------
    ZigZagMetrics

    Raises
    ------
    ParameterError
        On shapes that do not match, a trigger not > 0 or a side not ±1.
    """
    t = as_float_array("time", time, "s")
    psi = np.atleast_2d(as_float_array("heading", heading, "rad", finite=False))
    if t.ndim != 1 or psi.shape[-1] != t.size or t.size < 3:
        raise ParameterError(
            f"must be 1-D with at least 3 samples and the length of the last axis of "
            f"`heading`, got {t.shape} and {psi.shape}", field="time")
    runs = psi.shape[0]
    trig = np.broadcast_to(as_float_array("trigger", trigger, "rad"), (runs,))
    if not np.all(trig > 0):
        raise ParameterError(f"must be > 0 [rad], got {trigger!r}", field="trigger")
    sides = np.broadcast_to(np.asarray(first_side, dtype=float), (runs,))
    if not np.all(np.isin(sides, (-1.0, 1.0))):
        raise ParameterError(f"must be +1 or -1 [-], got {first_side!r}", field="first_side")
    base = np.broadcast_to(as_float_array("base_heading", base_heading, "rad"), (runs,))
    if not t[0] <= order_time <= t[-1]:
        raise ParameterError(
            f"must lie in [{t[0]:g}, {t[-1]:g}] [s], got {order_time!r}", field="order_time")
    k0 = int(np.searchsorted(t, order_time, side="left"))
    nan3 = np.full((runs, N_OVERSHOOTS), np.nan)
    executes, overshoots, times, extremes = nan3.copy(), nan3.copy(), nan3.copy(), nan3.copy()
    messages = []
    names = ("second", "third", "fourth")
    for i in range(runs):
        s = sides[i]
        start = k0
        missing = ""
        for j in range(N_OVERSHOOTS):
            dev = s * (psi[i] - base[i])  # positive in the direction the ship is turning
            k, t_exec = _crossing(t, dev, trig[i], start)
            if k < 0:
                missing = f"{names[j]} execute (heading {'+' if s > 0 else '-'}" \
                          f"{math.degrees(trig[i]):.4g} deg) not reached"
                break
            executes[i, j] = t_exec - order_time
            m, t_ext, y_ext = _first_maximum(t, dev, k)
            if m < 0 or m + 1 >= t.size:
                missing = f"overshoot {j + 1} not reached (heading still changing at the end)"
                break
            overshoots[i, j] = y_ext - trig[i]
            times[i, j] = t_ext - order_time
            extremes[i, j] = s * y_ext
            s, start = -s, m
        messages.append(f"{missing} within t = {t[-1] - order_time:.6g} s" if missing else "ok")
    return ZigZagMetrics(
        execute_time=executes, overshoot=overshoots, overshoot_time=times,
        extreme_heading=extremes, initial_turning_time=executes[:, 0].copy(),
        time_to_check_yaw=times[:, 0] - executes[:, 0], period=executes[:, 2] - executes[:, 0],
        message=messages)


def zigzag(ship: Any, rudder: Any = math.radians(10.0), heading: Any = None, *,
           sides: Any = (1, -1), speed: Any = None, rps: Any = None,
           t_final: float | None = None, dt: float | None = None,
           record_dt: float | None = None, conditions: Any = None,
           check_reachable: bool = True) -> ManeuverResult:
    """Zig-zag tests to either first side, batched over ships, speeds and δ/ψ pairs.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path), Params, or a sequence of them
        The ship(s); a sequence gives a ``ship`` dimension (one model).
    rudder : float or sequence of float, optional
        Rudder angle δ_z [rad], in (0, steering-gear limit] (default 10°).
    heading : float or sequence of float, optional
        Heading trigger ψ_z [rad], in (0, π) (default: equal to ``rudder``, the usual 10°/10°,
        20°/20° tests). ``rudder`` and ``heading`` given as sequences of one length are
        **pairs** (e.g. 10/10, 20/20, 20/10): a ``pair`` dimension with the coordinates
        ``rudder(pair)`` and ``trigger(pair)``.
    sides : int or sequence of int, optional
        Side of the first execute, +1 starboard, −1 port (default both: a ``side`` dimension).
    speed : float or sequence of float, optional
        Approach speed(s) [m/s] (default: the parameter set's); a sequence gives an
        ``approach_speed`` dimension.
    rps : float or sequence of float, optional
        Instead of ``speed``: the approach's propeller rps [1/s] (MMG).
    t_final : float, optional
        Duration [s] (default: 4 rudder swings + 4 × 6 ψ_z / the slowest steady yaw rate at
        δ_z, about a third more than the third overshoot of the KVLCC2 and the Mariner needs;
        for a constant-speed model plus 6 × its yaw time constant, T of Nomoto 1).
    dt : float, optional
        Integration step [s]; the controller samples every step (default: half of
        :func:`~seahelm.analysis.maneuvers.default_time_step`, since the reversals fall on
        samples — see the module docstring).
    record_dt : float, optional
        Recording interval [s] (default: every step).

    conditions : Conditions, optional
        Wind, waves and a uniform current (:class:`seahelm.environment.loads.Conditions`)
        acting from t = 0 on; the approach is the calm-water one, and the metrics are measured
        on the track over ground (default: calm water).
    check_reachable : bool, optional
        With a given ``t_final``: refuse a trigger that the steady turn at δ_z cannot reach
        in it (default True; one batched steady-turn solve of every ship). False skips that
        solve: such a run ends with its execute not reached (NaN, ``complete`` False, the
        ``message`` says so) — what an ensemble wants, where one member must not stop the
        others (:func:`~seahelm.analysis.imo.probability.imo_probabilities`).

    Returns
    -------
    ManeuverResult
        ``metrics`` variables: ``overshoot``, ``overshoot_time``, ``extreme_heading``,
        ``execute_time`` over a trailing dim ``n`` (1, 2, 3), ``initial_turning_time``,
        ``time_to_check_yaw``, ``period`` [s], ``length``, ``approach_speed_value``,
        ``propeller_rps``, ``complete``, ``message``.

    Raises
    ------
    ParameterError
        If a rudder angle is beyond the steering gear's limit, a trigger is not in (0, π),
        ``rudder`` and ``heading`` do not pair, or a trigger cannot be reached within the given
        ``t_final`` even at the steady yaw rate of δ_z.
    """
    d = as_float_array("rudder", rudder, "rad")
    h = d if heading is None else as_float_array("heading", heading, "rad")
    if d.ndim > 1 or h.ndim > 1 or d.shape != h.shape or d.size == 0:
        raise ParameterError(
            "and `heading` must be numbers or 1-D sequences of one length (pairs) "
            f"[rad], got shapes {d.shape} and {h.shape}", field="rudder")
    if not np.all((h > 0) & (h < math.pi)):
        raise ParameterError(f"trigger must be in (0, pi) [rad], got {heading!r}", field="heading")
    if t_final is None and not check_reachable:
        raise ParameterError("can be False only with a given `t_final` (the default duration "
                             "is made from the steady turns)", field="check_reachable")
    is_pair = d.ndim == 1
    pair = Axis(name="pair", values=np.arange(max(d.size, 1)), is_dim=is_pair,
                coords={"rudder": (np.atleast_1d(d), {"units": "rad",
                                                      "long_name": "rudder angle delta_z"}),
                        "trigger": (np.atleast_1d(h), {"units": "rad",
                                                       "long_name": "heading trigger psi_z"})})
    side = side_axis(sides)
    plan = Plan(ship, speed, rps, [pair, side])
    check_rudder(plan.ships, "rudder", np.atleast_1d(d), positive=True)
    if dt is None:
        dt = 0.5 * usual_time_step(plan.ships, [a.speed for a in plan.approaches.values()])
    n = plan.n_runs
    # each run's values gathered along the grid's axes at once (a 10,000-sample study asked
    # each run's position as a dict, several times per run)
    pair_of = plan.run_values("pair")
    amp = np.atleast_1d(d)[pair_of]
    trig = np.atleast_1d(h)[pair_of]
    first = plan.run_values("side").astype(float)
    ship_of = plan._positions[0].tolist()  # (each run's ship and speed index)
    speed_of = plan._positions[1].tolist()
    ships = [plan.ships[j] for j in ship_of]
    approaches = plan.run_approaches()
    # steady yaw rate at ±δ_z per (ship, speed, pair, side): reachability and default t_final
    # (all of them in one batch solve; NaN: a run left out, without an approach)
    rates = np.full(n, np.nan)
    keys: dict[tuple[int, int, float], int] = {}
    runs, slot, groups = np.flatnonzero(plan.run_ok), [], []
    for i in runs.tolist():
        key = (ship_of[i], speed_of[i], float(first[i] * amp[i]))
        if key not in keys:
            keys[key] = len(groups)
            groups.append((ships[i], key[2], approaches[i]))
        slot.append(keys[key])
    if groups and check_reachable:
        rates[runs] = np.array([float(r) for r in steady_yaw_rates(groups)])[slot]
    swing = np.array([2.0 * amp[i] / ships[i].servo.max_rate for i in range(n)])
    if t_final is None:
        lag_of = [yaw_lag(s_) for s_ in plan.ships]  # (one per ship)
        lags = np.array([lag_of[j] for j in ship_of])
        t_final = float(np.nanmax(4.0 * swing + 4.0 * 6.0 * trig / rates + 6.0 * lags))
    elif check_reachable:
        need = 0.5 * swing + trig / rates
        bad = np.flatnonzero(need > t_final)
        if bad.size:
            i = int(bad[0])
            raise ParameterError(
                f"trigger {math.degrees(trig[i]):.4g} deg is not reached within "
                f"`t_final` = {t_final!r} [s] with {math.degrees(amp[i]):.4g} deg rudder: "
                f"the steady turn of '{ships[i].name}' at that rudder angle turns at "
                f"{math.degrees(rates[i]):.4g} deg/s, which needs at least {need[i]:.4g} s",
                field="heading")
    t_final = final_time(float(t_final), float(dt))
    record_every = record_every_for(float(dt), record_dt, float(t_final))
    x0 = np.stack([a.state for a in approaches])
    rudder0 = np.array([[a.rudder] for a in approaches])
    if plan.ships[0].has_propeller:
        controller = ZIGZAG_RPS
        cparams = [ZigZagRpsParams(rudder_amplitude=float(amp[i]),
                                   heading_trigger=float(trig[i]), first_side=float(first[i]),
                                   base_heading=float(x0[i, plan.model.state_index("heading")]),
                                   propeller_rps=float(approaches[i].rps))
                   for i in range(n)]
    else:
        controller = ZIGZAG
        cparams = [ZigZagParams(rudder_amplitude=float(amp[i]), heading_trigger=float(trig[i]),
                                first_side=float(first[i]),
                                base_heading=float(x0[i, plan.model.state_index("heading")]))
                   for i in range(n)]
    result = plan.simulate(x0=x0, actuator_x0=rudder0, controller=controller,
                           controller_params=cparams, t_final=t_final, dt=dt,
                           record_every=record_every, metadata={"maneuver": "zigzag"},
                           conditions=conditions)
    psi0 = x0[:, plan.model.state_index("heading")]
    zm = zigzag_metrics(result.time, result["heading"], trigger=trig, first_side=first,
                        base_heading=psi0)
    status = result.messages()
    messages = [m if s_ == "ok" else f"{s_}; {m}" for s_, m in zip(status, zm.message)]
    complete = np.array([m == "ok" for m in messages])
    U0 = np.array([a.speed for a in approaches])
    rps_v = np.array([np.nan if (x := a.rps) is None else x for a in approaches])
    variables = {
        "overshoot": (zm.overshoot, "rad", "overshoot angle beyond the trigger"),
        "overshoot_time": (zm.overshoot_time, "s", "time of the heading extreme, from the order"),
        "extreme_heading": (zm.extreme_heading, "rad", "heading deviation at the extreme"),
        "execute_time": (zm.execute_time, "s",
                         "time of the 2nd, 3rd, 4th execute (rudder reversal), from the order"),
        "initial_turning_time": (zm.initial_turning_time, "s",
                                 "time from the order to the second execute"),
        "time_to_check_yaw": (zm.time_to_check_yaw, "s",
                              "from the second execute to the first heading extreme"),
        "period": (zm.period, "s", "from the second to the fourth execute"),
        "steady_yaw_rate_at_rudder": (rates * first, "rad/s",
                                      "yaw rate of the steady turn at the first rudder order"),
        "approach_speed_value": (U0, "m/s", "approach speed U_0"),
        "propeller_rps": (rps_v, "1/s", "propeller rps (constant; NaN: no propeller input)"),
        "length": (plan.run_lengths(), "m", "ship length L"),
        "complete": (complete, "", "every event reached and the run did not diverge"),
        "message": (np.array(messages, dtype=object), "", "what was not reached, or ok"),
    }
    extra = {k: ("n", N_OVERSHOOTS) for k in ("overshoot", "overshoot_time", "extreme_heading",
                                              "execute_time")}
    attrs = {"maneuver": "zigzag", "dt": float(dt), "t_final": float(t_final),
             "controller": controller.name,
             "measured_from": "rudder order (first execute) at t = 0",
             "interpolation": "executes: linear between samples; extremes: parabola through "
                              "the largest sample and its neighbours"}
    metrics = plan.dataset(variables, extra_dims=extra, attrs=attrs,
                           coords={"n": ("n", np.arange(1, N_OVERSHOOTS + 1))})
    return ManeuverResult("zigzag", metrics, tuple(plan.ships), result,
                          lambda: plan.runs_dataset(result))
