"""Pull-out tests (rudder to zero after a steady turn, both sides) over batches.

The pull-out test (Burcher 1972; ITTC 7.5-04-02-01): after a steady turn with rudder δ the
rudder is returned to zero (midship) and the yaw rate is followed until it settles. A
course-stable ship returns to a straight course from both sides (the residual yaw rates of
both sides agree, at zero for a ship symmetric at rest); a course-unstable ship keeps turning,
with residual yaw rates of opposite sign whose difference is the height of the spiral
loop at δ = 0.

Each run starts exactly in the steady turn
(:func:`seahelm.analysis.equilibria.equilibrium.steady_turn_state` at the approach's propeller rps —
the end of a long turning circle) with the rudder at ±δ; at t = 0 the rudder is ordered to 0 and
moves there through the steering gear. Metrics: the initial (steady) and residual yaw rates
— the mean over the last 5 % of the run — whether the yaw rate had settled (its change over the
last 10 % of the run below 1 % of the initial yaw rate), the time for the yaw rate to fall to
half its initial value (interpolated), and, when both sides are in the batch, the difference
of the residual yaw rates of the starboard and the port turn (``residual_gap``, a variable
without the ``side`` dimension).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..equilibria.batch_steady_turn import steady_turn_states
from ..equilibria.equilibrium import EquilibriumError
from .common import (
    Plan,
    check_rudder,
    usual_time_step,
    final_time,
    record_every_for,
    side_axis,
    value_axis,
)
from .result import ManeuverResult

__all__ = ["pull_out"]


def pull_out(ship: Any, rudder: Any = math.radians(20.0), *, sides: Any = (1, -1),
             speed: Any = None, rps: Any = None, t_final: float | None = None,
             dt: float | None = None, record_dt: float | None = None,
             conditions: Any = None) -> ManeuverResult:
    """Pull-out tests from steady turns to both sides, batched over ships, speeds, rudders.

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path), Params, or a sequence of them
        The ship(s); a sequence gives a ``ship`` dimension (one model).
    rudder : float or sequence of float, optional
        Rudder angle of the steady turn [rad], in (0, steering-gear limit] (default 20°).
    sides : int or sequence of int, optional
        Side of the turn, +1 starboard, −1 port (default both: a ``side`` dimension).
    speed : float or sequence of float, optional
        Approach speed(s) [m/s] whose self-propulsion rps the turn keeps (default: the
        parameter set's).
    rps : float or sequence of float, optional
        Instead of ``speed``: the propeller rps [1/s] (MMG).
    t_final : float, optional
        Duration after the rudder order [s] (default 60 L/U_0).
    dt : float, optional
        Integration step [s] (default :func:`~seahelm.analysis.maneuvers.default_time_step`).
    record_dt : float, optional
        Recording interval [s] (default: every step).

    conditions : Conditions, optional
        Wind, waves and a uniform current (:class:`seahelm.environment.loads.Conditions`)
        acting from t = 0 on; the approach is the calm-water one, and the metrics are measured
        on the track over ground (default: calm water).

    Returns
    -------
    ManeuverResult
        ``metrics`` variables: ``initial_yaw_rate``, ``residual_yaw_rate`` [rad/s],
        ``settled`` (bool), ``half_time`` [s], ``residual_gap`` [rad/s] (starboard minus port,
        when both sides are in the batch), ``approach_speed_value``, ``propeller_rps``,
        ``length``, ``complete``, ``message``.

    Raises
    ------
    ParameterError
        If a rudder angle is beyond the steering gear's limit, or a speed/rps is invalid.
    """
    rudder_axis = value_axis("rudder", rudder, "rad")
    side = side_axis(sides)
    plan = Plan(ship, speed, rps, [rudder_axis, side])
    check_rudder(plan.ships, "rudder", rudder_axis.values, positive=True)
    n = plan.n_runs
    if dt is None:
        dt = usual_time_step(plan.ships, [a.speed for a in plan.approaches.values()])
    if t_final is None:
        t_final = max(60.0 * plan.ship(i).length / plan.approach(i).speed for i in range(n))
    t_final = final_time(float(t_final), float(dt))
    record_every = record_every_for(float(dt), record_dt, float(t_final))
    # one steady turn per (ship, speed, signed rudder): its first run, and each run's turn
    x0, rudder0, slot = [], [], []
    groups: dict[tuple[int, int, float], int] = {}
    first: list[int] = []
    for i in range(n):
        idx = plan.index[i]
        delta = float(plan.value(i, "side") * plan.value(i, "rudder"))
        key = (idx["ship"], idx.get("approach_speed", idx.get("approach_rps", 0)), delta)
        rudder0.append([delta])
        if plan.run_failure(i) is not None:  # left out of the batch: any state
            x0.append(plan.approach(i).state)
            slot.append(-1)
            continue
        if key not in groups:
            groups[key] = len(first)
            first.append(i)
        x0.append(None)
        slot.append(groups[key])
    if first:  # the steady turns, one batch solve
        has_rps = plan.ships[0].has_propeller
        states, turns = steady_turn_states(
            plan.model, [plan.ship(i).params for i in first],
            np.array([key[2] for key in groups]),
            np.array([plan.approach(i).rps for i in first], dtype=float) if has_rps else None,
            max_rudder=np.array([plan.ship(i).max_rudder for i in first]))
        if not turns.ok.all():  # the first in order, as the one-at-a-time solve raised
            raise EquilibriumError(turns.message[int(np.argmin(turns.ok))])
        for i in range(n):
            if slot[i] >= 0:
                x0[i] = states[slot[i]]
    x0_arr = np.stack(x0)
    reference: dict[str, Any] = {"rudder_command": np.zeros((n, 1, 1))}
    if plan.ships[0].has_propeller:
        reference["propeller_rps"] = np.array(
            [plan.approach(i).rps for i in range(n)]).reshape(-1, 1, 1)
    result = plan.simulate(x0=x0_arr, actuator_x0=np.array(rudder0), reference=reference,
                           t_final=t_final, dt=dt, record_every=record_every,
                           metadata={"maneuver": "pull-out"},
                           controller_every=record_every, conditions=conditions)
    t = result.time
    r = result["yaw_rate"]
    r0 = x0_arr[:, plan.model.state_index("yaw_rate")]
    tail = t >= t[-1] * 0.95
    residual = np.mean(r[:, tail], axis=1)
    k10 = int(np.searchsorted(t, 0.9 * t[-1]))
    settled = np.abs(r[:, -1] - r[:, k10]) <= 0.01 * np.abs(r0)
    half = np.full(n, np.nan)
    for i in range(n):
        ratio = r[i] / r0[i]
        hit = np.flatnonzero(ratio <= 0.5)
        if hit.size and hit[0] > 0:
            k = int(hit[0])
            w = (0.5 - ratio[k - 1]) / (ratio[k] - ratio[k - 1])
            half[i] = t[k - 1] + w * (t[k] - t[k - 1])
    status = result.messages()
    messages = []
    for i in range(n):
        text = [] if status[i] == "ok" else [status[i]]
        if not settled[i]:
            text.append(f"yaw rate not settled within t_final = {t[-1]:.6g} s")
        messages.append("; ".join(text) if text else "ok")
    variables = {
        "initial_yaw_rate": (r0, "rad/s", "yaw rate of the steady turn before the pull-out"),
        "residual_yaw_rate": (residual, "rad/s", "mean yaw rate over the last 5 % of the run"),
        "settled": (settled, "", "yaw rate changed < 1 % of the initial over the last 10 %"),
        "half_time": (half, "s", "time for the yaw rate to fall to half its initial value"),
        "approach_speed_value": (np.array([plan.approach(i).speed for i in range(n)]), "m/s",
                                 "approach speed U_0 (whose self-propulsion rps is kept)"),
        "propeller_rps": (np.array([np.nan if plan.approach(i).rps is None
                                    else plan.approach(i).rps for i in range(n)]), "1/s",
                          "propeller rps (constant; NaN: no propeller input)"),
        "length": (np.array([plan.ship(i).length for i in range(n)]), "m", "ship length L"),
        "complete": (np.array([m == "ok" for m in messages]), "", "settled, not diverged"),
        "message": (np.array(messages, dtype=object), "", "what was not reached, or ok"),
    }
    attrs = {"maneuver": "pull-out", "dt": float(dt), "t_final": float(t_final),
             "start": "steady turn at the rudder angle (equilibrium), rudder ordered to 0 at t = 0"}
    metrics = plan.dataset(variables, attrs=attrs)
    if "side" in metrics.dims and {1, -1} <= set(metrics["side"].values.tolist()):
        gap = (metrics["residual_yaw_rate"].sel(side=1)
               - metrics["residual_yaw_rate"].sel(side=-1))
        metrics["residual_gap"] = gap.drop_vars("side", errors="ignore").assign_attrs(
            units="rad/s", long_name="residual yaw rate, starboard minus port (0: course "
                                     "stable; > 0: a spiral loop at zero rudder)")
    return ManeuverResult("pull-out", metrics, tuple(plan.ships), result,
                          lambda: plan.runs_dataset(result))
