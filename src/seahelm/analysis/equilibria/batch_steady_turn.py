"""Steady turns of a whole batch of ships and rudder angles in one vectorised solve.

:func:`steady_turns` is :func:`~seahelm.analysis.equilibria.equilibrium.steady_turn` for many
(parameter set, rudder angle, rps) runs of one model at once — the four zig-zag turns of every
member of a Monte-Carlo study — with the same equations, the same continuation and the same answer
to the solvers' tolerance (``tests/test_analysis_batch_steady_turn.py``). It solves with the
machinery of :mod:`.batch_equilibrium` (the model's compiled right-hand side over all active
runs per evaluation, :func:`~seahelm.analysis.equilibria.batch_equilibrium._newton`'s damped
Newton):

1. **straight run** at the rps (r = 0, solved for u, v, δ from (U_ref, 0, 0)), once per
   distinct (parameter set, rps): the trim of :mod:`.batch_equilibrium`;
2. **continuation in r** (Δr L/U_ref = 0.01) along the spiral curve δ(r), once per distinct
   (parameter set, rps, side): every run of that line (e.g. 10° and 20° to starboard) takes its
   bracket [r_k−1, r_k] where δ(r) first passes its rudder angle. A prescribed yaw rate has one
   equilibrium, so each point is the one-run solve's whatever the start; the next start is the
   line through the last two points, and these points stop at a residual of 10⁻¹¹ (they only
   start later solves). As in the one-run solve, a step that fails or moves δ by more than
   ``rudder_step`` hands the run to stage 4 from the last good point;
3. **the turn at δ**: u̇ = v̇ = ṙ = 0 solved for (u, v, r) from the point interpolated in the
   bracket, to the round-off floor (the one-run solve finds r in the bracket by brentq and
   polishes at δ: the same root). A root outside the bracket is another branch: the run
   fails (``OUTSIDE_BRACKET``);
4. **continuation in δ** from the last good point in rudder steps of at most
   ``rudder_step`` (where δ(r) is steep, near the largest yaw rate the rudder gives).

A run that fails in the batch is solved again one at a time by scipy's continuation
(:mod:`seahelm.analysis.equilibria.fallback`; ``fallback=True``, the default): its result, or
the message of its :class:`~seahelm.analysis.equilibria.equilibrium.EquilibriumError`
(``NO_STEADY_TURN``), is the run's. Constant-speed models (:mod:`.constant_speed`, no surge
equation; microseconds a turn) and models with a roll state (their heel is balanced in every
evaluation, :mod:`.heel`) are solved one run after the other by that one-run code.
:func:`~seahelm.analysis.equilibria.equilibrium.steady_turn` is this function for a batch of one.

Bad arguments (a rudder angle beyond ``max_rudder``, a missing or non-positive rps) raise
:class:`~seahelm.errors.ParameterError` for the batch, as the one-run function does.
"""

from __future__ import annotations

import dataclasses
import enum
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..._validate import check_positive, check_range
from ...errors import ParameterError
from ...parameters import Params
from ...vessels.base import VesselModel, _batched_output
from .batch_equilibrium import (
    ApproachStatus,
    _newton,
    _newton_failure,
    _trim,
)
from .constant_speed import is_constant_speed
from . import fallback
from .plant import EquilibriumError, Plant
from .heel import heel_balance

__all__ = ["TurnStatus", "BatchSteadyTurn", "steady_turns", "steady_turn_states"]

#: Residual at which a continuation point is taken (it only starts the next solves).
STEP_RESIDUAL = 1e-11
#: Continuation steps in r before giving up (r L/U_ref = 3, as the one-run solve).
MAX_R_STEPS = 300


class TurnStatus(enum.IntEnum):
    """Outcome of one run's steady turn (0 is success)."""

    OK = 0
    STRAIGHT_RUN = 1
    """The straight run (r = 0) at the rps was not found."""
    NOT_FINITE = 3
    """The right-hand side was NaN or infinite at the start of the turn's solve."""
    SINGULAR = 4
    """The Jacobian of the turn's equations is singular."""
    LINE_SEARCH = 5
    """The line search found no decrease of the residual."""
    MAX_ITERATIONS = 6
    """Not converged within ``max_iterations``."""
    NO_CROSSING = 7
    """δ(r) did not reach the rudder angle up to r L/U_ref = 3."""
    OUTSIDE_BRACKET = 8
    """The turn at δ left the bracket of the crossing (another branch)."""
    NOT_AHEAD = 9
    """The turn's surge speed is ≤ 0."""
    NO_STEADY_TURN = 10
    """The one-at-a-time solve (fallback, or a model solved run by run) raised: its message."""


@dataclasses.dataclass(frozen=True)
class BatchSteadyTurn:
    """Steady turns of a batch of runs (arrays over ``runs``; NaN where failed).

    The first six fields are those of :class:`~seahelm.analysis.equilibria.equilibrium.SteadyTurn`.
    """

    surge_speed: np.ndarray
    """Surge speed u [m/s] (total, U_0 + u for a perturbation model)."""
    sway_speed: np.ndarray
    """Sway speed v [m/s]."""
    yaw_rate: np.ndarray
    """Yaw rate r [rad/s] (positive to starboard)."""
    speed: np.ndarray
    """Speed U [m/s]."""
    drift_angle: np.ndarray
    """Drift angle β [rad]."""
    radius: np.ndarray
    """Turning radius U/|r| [m] (inf for r = 0)."""
    rudder: np.ndarray
    """The runs' rudder angles δ [rad]."""
    status: np.ndarray
    """:class:`TurnStatus` per run (int)."""
    message: tuple[str, ...]
    """'ok' or the reason of the failure, per run."""
    fallback: np.ndarray
    """Whether the run was solved one at a time (bool)."""

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the runs whose steady turn was found."""
        return self.status == TurnStatus.OK

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.status.size)


def steady_turns(model: VesselModel, params: Params | Sequence[Params], rudder: Any,
                 rps: Any = None, *, max_rudder: Any = math.radians(35.0),
                 rudder_step: float = math.radians(2.5), max_iterations: int = 50,
                 fallback: bool = True) -> BatchSteadyTurn:
    """Steady turns of many (parameter set, rudder angle, rps) runs in one vectorised solve.

    The batch form of :func:`~seahelm.analysis.equilibria.equilibrium.steady_turn` (see the module
    docstring for the method): the same turns to the solvers' tolerance.

    Parameters
    ----------
    model : VesselModel
        The model every parameter set belongs to.
    params : Params or sequence of Params
        One parameter set per run, or one for all runs (one type).
    rudder : float or array_like
        Rudder angle δ [rad] per run, or one for all; positive turns to starboard.
    rps : float or array_like, optional
        Propeller rps [1/s] per run or one for all, > 0: required for a model with a
        ``propeller_rps`` input, not allowed for one without.
    max_rudder : float or array_like, optional
        Largest admissible |δ| [rad] per run or one for all (default 35°).
    rudder_step : float, optional
        Largest rudder change per continuation step [rad] (default 2.5°).
    max_iterations : int, optional
        Newton iterations of each solve (default 50).
    fallback : bool, optional
        Solve the runs that fail in the batch again one at a time (default True); False keeps
        the batch's own status and message.

    Returns
    -------
    BatchSteadyTurn
        Per-run surge and sway speed, yaw rate, speed, drift angle, radius, status, message.

    Raises
    ------
    ParameterError
        If there are no runs, the arguments do not broadcast to one length, a rudder angle is
        beyond ``max_rudder``, ``rps`` is missing, not allowed or not > 0, ``rudder_step`` is
        not > 0, or the model lacks the signals :func:`steady_turn` needs.
    """
    plist = [params] if isinstance(params, Params) else list(params)
    delta = np.atleast_1d(np.asarray(rudder, dtype=float))
    n = max(len(plist), delta.size)
    if not plist or delta.size == 0:
        raise ParameterError(": no runs", field="params")
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, int) \
            or max_iterations < 1:
        raise ParameterError(f"must be a whole number >= 1, got {max_iterations!r}",
                             field="max_iterations", value=max_iterations)
    if len(plist) == 1:
        plist = plist * n
    elif len(plist) != n:
        raise ParameterError(f"must be one parameter set or one per run ({n}), got "
                             f"{len(plist)}", field="params")
    delta = _per_run("rudder", delta, n)
    limit = _per_run("max_rudder", max_rudder, n)
    check_positive("max_rudder", limit, "rad")
    check_positive("rudder_step", rudder_step, "rad")
    for lim in np.unique(limit):  # (one message per limit, as the one-run solve's)
        check_range("rudder", delta[limit == lim], -float(lim), float(lim), "rad")
    has_rps = "propeller_rps" in model.input_labels and not is_constant_speed(model)
    if rps is not None and not has_rps:
        raise ParameterError(f": model '{model.name}' has no propeller_rps input, got {rps!r}",
                             field="rps", unit="1/s", value=rps)
    if has_rps and rps is None:
        raise ParameterError(f"`rps` [1/s] is required for model '{model.name}'")
    n_rps = _per_run("rps", rps, n) if has_rps else None
    if n_rps is not None:
        check_positive("rps", n_rps, "1/s")
    out = _Out(n, delta)
    if is_constant_speed(model) or heel_balance(model) is not None:
        todo = np.arange(n)
    else:
        _solve(model, plist, delta, n_rps, float(rudder_step), max_iterations, out)
        todo = np.flatnonzero(out.status != TurnStatus.OK) if fallback else np.arange(0)
    for i in todo.tolist():  # one at a time: the one-run solve's result or its message
        try:
            t = _one_run_turn(model, plist[i], float(delta[i]), None if n_rps is None else
                              float(n_rps[i]), float(limit[i]), float(rudder_step))[0]
        except EquilibriumError as exc:
            text = str(exc)
            out.fail(np.array([i]), TurnStatus.NO_STEADY_TURN, lambda _i: text, force=True)
            continue
        out.fields[:, i] = t
        out.status[i] = TurnStatus.OK
        out.reason.pop(i, None)
        out.fallback[i] = True
    return out.result()


def steady_turn_states(model: VesselModel, params: Params | Sequence[Params], rudder: Any,
                       rps: Any = None, *, max_rudder: Any = math.radians(35.0)
                       ) -> tuple[np.ndarray, BatchSteadyTurn]:
    """State vectors of the steady turns of a batch (e.g. the starts of pull-outs).

    The batch form of :func:`~seahelm.analysis.equilibria.equilibrium.steady_turn_state` at heading
    0: the turns of :func:`steady_turns`, as states at the origin; a constant-speed model or a
    model with roll is solved one run after the other by ``steady_turn_state`` itself.

    Parameters
    ----------
    model : VesselModel
        The model every parameter set belongs to.
    params : Params or sequence of Params
        One parameter set per run, or one for all runs.
    rudder : float or array_like
        Rudder angle δ [rad] per run, or one for all.
    rps : float or array_like, optional
        Propeller rps [1/s] per run or one for all (a model with a propeller input only).
    max_rudder : float or array_like, optional
        Largest admissible |δ| [rad] per run or one for all (default 35°).

    Returns
    -------
    (numpy.ndarray, BatchSteadyTurn)
        States (runs, n_states) in the model's order (NaN where the turn failed) and the
        turns with their status and message.

    Raises
    ------
    ParameterError
        As :func:`steady_turns`.
    """
    turns = steady_turns(model, params, rudder, rps, max_rudder=max_rudder)
    n = turns.n_runs
    states = np.full((n, model.n_states), np.nan)
    if is_constant_speed(model) or heel_balance(model) is not None:
        plist = [params] * n if isinstance(params, Params) else list(params)
        plist = plist * n if len(plist) == 1 else plist
        n_rps = None if rps is None else _per_run("rps", rps, n)
        limit = _per_run("max_rudder", max_rudder, n)
        for i in np.flatnonzero(turns.ok).tolist():
            try:
                states[i] = _one_run_turn(model, plist[i], float(turns.rudder[i]),
                                          None if n_rps is None else float(n_rps[i]),
                                          float(limit[i]), math.radians(2.5))[1]
            except EquilibriumError:  # pragma: no cover - its steady turn was found
                continue
        return states, turns
    b_states = model.state_labels
    ok = turns.ok
    states[ok] = 0.0
    i_u = (b_states.index("surge_speed") if "surge_speed" in b_states
           else b_states.index("surge_perturbation"))
    offset = 0.0
    if "surge_speed" not in b_states:
        plist = [params] if isinstance(params, Params) else list(params)
        offset = np.broadcast_to(np.array([float(p.nominal_speed) for p in plist]), (n,))[ok]
    states[ok, i_u] = turns.surge_speed[ok] - offset
    states[ok, model.state_index("sway_speed")] = turns.sway_speed[ok]
    states[ok, model.state_index("yaw_rate")] = turns.yaw_rate[ok]
    return states, turns


def _one_run_turn(model: VesselModel, params: Params, delta: float, rps: float | None,
                  max_rudder: float, rudder_step: float) -> tuple[np.ndarray, np.ndarray]:
    """One run's steady turn by the one-run code (:mod:`.fallback`): its
    :class:`~seahelm.analysis.equilibria.equilibrium.SteadyTurn` fields and its state at the origin,
    heading 0 (heel balanced for a model with roll), or its EquilibriumError."""
    cs = fallback.constant_speed_plant(params, model, rps)
    if cs is not None:
        fields, steering = cs.steady_turns(delta, max_rudder, rudder_step)
        return fields, cs.state(steering, 0.0)
    plant = Plant(model, [params])
    f = fallback.turn_fields(plant, np.array([delta]), rps, rudder_step)[:, 0]
    return f, plant.state(f[0], f[1], f[2], 0.0, plant.inputs(delta, rps))


def _per_run(name: str, value: Any, n: int) -> np.ndarray:
    """``value`` as one float per run (a scalar broadcast)."""
    try:
        return np.broadcast_to(np.asarray(value, dtype=float), (n,)).copy()
    except (TypeError, ValueError):
        raise ParameterError(f"must be a number or one per run ({n}), got {value!r}",
                             field=name, value=value) from None


class _Out:
    """The batch's results as they are filled in."""

    def __init__(self, n: int, delta: np.ndarray) -> None:
        self.delta = delta
        self.fields = np.full((6, n), np.nan)
        self.status = np.zeros(n, dtype=np.int64)
        self.reason: dict[int, str] = {}
        self.fallback = np.zeros(n, dtype=bool)

    def fail(self, rows: np.ndarray, code: int, text: Any, force: bool = False) -> None:
        """Record ``code`` and ``text(i)`` for the runs ``rows`` not failed yet."""
        for i in np.asarray(rows).tolist():
            if force or self.status[i] == TurnStatus.OK:
                self.status[i] = code
                self.reason[i] = text(i)

    def result(self) -> BatchSteadyTurn:
        bad = self.status != TurnStatus.OK
        self.fields[:, bad] = np.nan
        return BatchSteadyTurn(*self.fields, rudder=self.delta, status=self.status,
                               message=tuple(self.reason.get(i, "ok")
                                             for i in range(self.status.size)),
                               fallback=self.fallback)


def _distinct(keys: list[tuple[Any, ...]]) -> tuple[np.ndarray, list[int]]:
    """Index of each key's group and the first member of each group."""
    first: dict[tuple[Any, ...], int] = {}
    group = np.empty(len(keys), dtype=np.int64)
    members: list[int] = []
    for i, key in enumerate(keys):
        g = first.setdefault(key, len(first))
        if g == len(members):
            members.append(i)
        group[i] = g
    return group, members


def _solve(model: VesselModel, plist: list[Params], delta: np.ndarray,
           n_rps: np.ndarray | None, rudder_step: float, max_iterations: int,
           out: _Out) -> None:
    """Stages 1–4 of the module docstring for a model with a surge equation, into ``out``."""
    n = delta.size
    # 1. the straight run, once per distinct (parameter set, rps)
    rps_list = [None] * n if n_rps is None else n_rps.tolist()
    plant, members = _distinct([(id(p), r) for p, r in zip(plist, rps_list)])
    b = Plant(model, [plist[i] for i in members])
    rps_p = None if n_rps is None else n_rps[members]
    n_p = len(members)
    p_status = np.zeros(n_p, dtype=np.int64)
    p_reason: dict[int, str] = {}
    trim = np.stack([b.u_ref, np.zeros(n_p), np.zeros(n_p)], axis=1)
    _trim(b, trim[:, 0], trim[:, 1], trim[:, 2], rps_p, max_iterations, p_status, p_reason,
          np.zeros(n_p, dtype=np.int64), np.zeros(n_p))
    failed = p_status[plant] != ApproachStatus.OK
    out.fail(np.flatnonzero(failed), TurnStatus.STRAIGHT_RUN, lambda i: p_reason[plant[i]])
    d0 = trim[plant, 2]
    sign = np.sign(delta - d0)
    # the solution per run: (surge, v, r); a run at the trim angle is the straight run
    sol = np.full((n, 3), np.nan)
    at_trim = ~failed & (sign == 0.0)
    sol[at_trim] = np.column_stack([trim[plant[at_trim], :2], np.zeros(at_trim.sum())])
    runs = np.flatnonzero(~failed & ~at_trim)
    s = _Scales(b)
    # 2. continuation in r, once per line (plant, side)
    polish, switch = _continue_in_r(b, s, plant, trim, sign, delta, runs, rps_p,
                                    rudder_step, max_iterations, out)
    # 3. the turn at δ from the bracket; 4. continuation in δ from the last good point
    _turn_at_rudder(b, s, plant, delta, rps_p, polish, max_iterations, out, sol)
    _continue_in_rudder(b, s, plant, delta, rps_p, switch, rudder_step, max_iterations, out,
                        sol)
    ok = np.flatnonzero(out.status == TurnStatus.OK)
    surge = sol[ok, 0]
    ahead = surge > 0.0
    out.fail(ok[~ahead], TurnStatus.NOT_AHEAD,
             lambda i: f"the steady turn at `rudder` = {float(delta[i])!r} [rad] "
                       f"({math.degrees(delta[i]):.4g} deg) has surge speed {sol[i, 0]:.6g} "
                       "[m/s] <= 0")
    ok = ok[ahead]
    _outputs(b, plant, ok, delta, rps_p, sol, out)


class _Scales:
    """The one-run solve's scaling: unknowns (u, v) by U_ref, r by U_ref/L, δ by 1; the
    accelerations by (1, 1, 1/L) U_ref²/L — per plant."""

    def __init__(self, b: Plant) -> None:
        self.speed = b.u_ref
        self.rate = b.u_ref / b.length
        self.acc = (np.stack([np.ones_like(b.length), np.ones_like(b.length), 1.0 / b.length],
                             axis=1) * (b.u_ref ** 2 / b.length)[:, None])


def _continue_in_r(b: Plant, s: _Scales, plant: np.ndarray, trim: np.ndarray,
                   sign: np.ndarray, delta: np.ndarray, runs: np.ndarray,
                   rps_p: np.ndarray | None, rudder_step: float, max_iterations: int,
                   out: _Out) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """Stage 2: the bracket of each run's crossing (``polish``: runs, lo/hi (u, v, δ) and r)
    or the last good point of a run handed to the continuation in δ (``switch``)."""
    line, heads = _distinct([(int(plant[i]), float(sign[i])) for i in runs.tolist()])
    lp = plant[runs[heads]]  # each line's plant and side
    lsign = sign[runs[heads]]
    m = len(heads)
    dr = 0.01 * s.rate[lp]
    prev = trim[lp].copy()  # (surge, v, δ) at r_{k-1}
    older = prev.copy()  # at r_{k-2}
    pending = np.ones(runs.size, dtype=bool)
    polish = {k: [] for k in ("run", "lo", "hi", "r_lo", "r_hi")}
    switch = {k: [] for k in ("run", "start", "r")}
    active = np.arange(m)
    for k in range(1, MAX_R_STEPS + 1):
        if not active.size:
            break
        r = lsign[active] * k * dr[active]
        guess = prev[active] if k == 1 else 2.0 * prev[active] - older[active]
        rows = lp[active]
        F = _residual(b, s, rps_p, rows, fixed_r=r)
        sc = F.scale
        sol = _newton(F, np.arange(active.size), guess / sc, max_iterations,
                      tol=STEP_RESIDUAL, forward=True)
        z = sol.z * sc
        good = (sol.code == ApproachStatus.OK) & (np.abs(z[:, 2] - prev[active, 2])
                                                  <= rudder_step)
        # runs of these lines still looking for their crossing
        here = pending & np.isin(line, active)
        pos = np.searchsorted(active, line[here])
        idx_runs = np.flatnonzero(here)
        g = good[pos]
        # a failed or too steep step: on in δ from the last good point
        for t, p_ in zip(idx_runs[~g].tolist(), pos[~g].tolist()):
            switch["run"].append(runs[t])
            switch["start"].append(prev[active[p_]].copy())
            switch["r"].append(lsign[active[p_]] * (k - 1) * dr[active[p_]])
        pending[idx_runs[~g]] = False
        idx_runs, pos = idx_runs[g], pos[g]
        crossed = sign[runs[idx_runs]] * (z[pos, 2] - delta[runs[idx_runs]]) >= 0.0
        for t, p_ in zip(idx_runs[crossed].tolist(), pos[crossed].tolist()):
            ln = active[p_]
            polish["run"].append(runs[t])
            polish["lo"].append(prev[ln].copy())
            polish["hi"].append(z[p_].copy())
            polish["r_lo"].append(lsign[ln] * (k - 1) * dr[ln])
            polish["r_hi"].append(r[p_])
        pending[idx_runs[crossed]] = False
        older[active] = prev[active]
        prev[active[good]] = z[good]
        still = np.unique(line[pending])
        active = active[np.isin(active, still) & good]
    left = runs[pending]
    out.fail(left, TurnStatus.NO_CROSSING,
             lambda i: f"no steady turn found at `rudder` = {float(delta[i])!r} [rad] "
                       f"({math.degrees(delta[i]):.4g} deg) up to r L/U_0 = 3")
    return ({k: np.array(v) for k, v in polish.items()},
            {k: np.array(v) for k, v in switch.items()})


def _residual(b: Plant, s: _Scales, rps_p: np.ndarray | None, plants: np.ndarray, *,
              fixed_r: np.ndarray | None = None, fixed_rudder: np.ndarray | None = None
              ) -> Any:
    """The scaled residual F(j, z) of the rows j of a solve whose row j is a run of plant
    ``plants[j]``: unknowns (u, v, δ) at the yaw rates ``fixed_r``, or (u, v, r) at the rudder
    angles ``fixed_rudder`` (one per row)."""
    if fixed_r is not None:
        scale = np.stack([s.speed, s.speed, np.ones_like(s.speed)], axis=1)[plants]
    else:
        scale = np.stack([s.speed, s.speed, s.rate], axis=1)[plants]

    def F(j: np.ndarray, z: np.ndarray) -> np.ndarray:
        idx = plants[j]
        y = z * scale[j]
        rps = None if rps_p is None else rps_p[idx]
        if fixed_r is not None:
            acc = b.accelerations(idx, y[:, 0], y[:, 1], y[:, 2], rps, fixed_r[j])
        else:
            acc = b.accelerations(idx, y[:, 0], y[:, 1], fixed_rudder[j], rps, y[:, 2])
        return acc / s.acc[idx]

    F.scale = scale  # type: ignore[attr-defined]
    return F


def _what(delta: float, rps_p: np.ndarray | None, plant: int) -> str:
    return (f"no equilibrium found for surge, v, r with rudder = {delta:.6g}"
            + (f", rps = {rps_p[plant]:.6g} [1/s]" if rps_p is not None else ""))


def _record(runs: np.ndarray, result: Any, F: Any, delta_of: Any, plant: np.ndarray,
            rps_p: np.ndarray | None, max_iterations: int, out: _Out) -> np.ndarray:
    """Record the failed rows of a solve at fixed rudder angles; the rows that converged."""
    res = np.max(np.abs(result.F), axis=1)
    y = result.z * F.scale
    bad = np.flatnonzero(result.code != ApproachStatus.OK)
    for j in bad.tolist():
        i = int(runs[j])
        out.fail(np.array([i]), int(result.code[j]),
                 lambda _i, j=j, i=i: _newton_failure(
                     _what(float(delta_of[j]), rps_p, int(plant[i])), int(result.code[j]),
                     bool(result.exhausted[j]), float(res[j]), max_iterations,
                     f"surge = {y[j, 0]:.6g} [m/s], v = {y[j, 1]:.6g} [m/s], "
                     f"r = {y[j, 2]:.6g} [rad/s]"))
    return result.code == ApproachStatus.OK


def _turn_at_rudder(b: Plant, s: _Scales, plant: np.ndarray, delta: np.ndarray,
                    rps_p: np.ndarray | None, polish: dict[str, np.ndarray],
                    max_iterations: int, out: _Out, sol: np.ndarray) -> None:
    """Stage 3: (u, v, r) at each run's δ from the point interpolated in its bracket."""
    runs = polish["run"].astype(np.int64)
    if not runs.size:
        return
    lo, hi, r_lo, r_hi = polish["lo"], polish["hi"], polish["r_lo"], polish["r_hi"]
    d = delta[runs]
    with np.errstate(all="ignore"):
        w = (d - lo[:, 2]) / (hi[:, 2] - lo[:, 2])
    w = np.clip(np.where(np.isfinite(w), w, 1.0), 0.0, 1.0)
    guess = np.column_stack([lo[:, 0] + w * (hi[:, 0] - lo[:, 0]),
                             lo[:, 1] + w * (hi[:, 1] - lo[:, 1]),
                             r_lo + w * (r_hi - r_lo)])
    F = _residual(b, s, rps_p, plant[runs], fixed_rudder=d)
    result = _newton(F, np.arange(runs.size), guess / F.scale, max_iterations)
    good = _record(runs, result, F, d, plant, rps_p, max_iterations, out)
    y = result.z * F.scale
    # the one-run solve's root lies in the bracket (brentq on r, then polished at δ)
    slack = 1e-9 * np.abs(r_hi - r_lo)
    inside = ((y[:, 2] >= np.minimum(r_lo, r_hi) - slack)
              & (y[:, 2] <= np.maximum(r_lo, r_hi) + slack))
    outside = good & ~inside
    out.fail(runs[outside], TurnStatus.OUTSIDE_BRACKET,
             lambda i: f"the steady turn at `rudder` = {float(delta[i])!r} [rad] left the "
                       "bracket of its crossing on the spiral curve (another branch)")
    keep = good & inside
    sol[runs[keep]] = y[keep]


def _continue_in_rudder(b: Plant, s: _Scales, plant: np.ndarray, delta: np.ndarray,
                        rps_p: np.ndarray | None, switch: dict[str, np.ndarray],
                        rudder_step: float, max_iterations: int, out: _Out,
                        sol: np.ndarray) -> None:
    """Stage 4: (u, v, r) continued in δ from the last good point, in steps of at most
    ``rudder_step``."""
    runs = switch["run"].astype(np.int64)
    if not runs.size:
        return
    start, r0 = switch["start"], switch["r"]
    d_from, d_to = start[:, 2], delta[runs]
    steps = np.maximum(1, np.ceil(np.abs(d_to - d_from) / rudder_step)).astype(np.int64)
    y = np.column_stack([start[:, 0], start[:, 1], r0])
    alive = np.ones(runs.size, dtype=bool)
    for k in range(1, int(steps.max()) + 1):
        j = np.flatnonzero(alive & (steps >= k))
        if not j.size:
            break
        d_k = np.where(steps[j] == k, d_to[j], d_from[j] + k * (d_to[j] - d_from[j]) / steps[j])
        F = _residual(b, s, rps_p, plant[runs[j]], fixed_rudder=d_k)
        result = _newton(F, np.arange(j.size), y[j] / F.scale, max_iterations)
        good = _record(runs[j], result, F, d_k, plant, rps_p, max_iterations, out)
        y[j] = result.z * F.scale
        alive[j[~good]] = False
    sol[runs[alive]] = y[alive]


def _outputs(b: Plant, plant: np.ndarray, ok: np.ndarray, delta: np.ndarray,
             rps_p: np.ndarray | None, sol: np.ndarray, out: _Out) -> None:
    """The SteadyTurn fields of the runs ``ok`` from the model's outputs."""
    if not ok.size:
        return
    m = b.model
    p = plant[ok]
    x = np.zeros((ok.size, m.n_states))
    x[:, b.i_u] = sol[ok, 0] - b.u_offset[p]
    x[:, b.i_v] = sol[ok, 1]
    x[:, b.i_r] = sol[ok, 2]
    u = np.zeros((ok.size, m.n_inputs))
    u[:, b.j_delta] = delta[ok]
    if b.j_rps is not None and rps_p is not None:
        u[:, b.j_rps] = rps_p[p]
    y = np.empty((ok.size, m.n_outputs))
    _batched_output(m.output, 0.0, x, u, b.records[p], y)
    speed = y[:, m.output_index("speed")]
    r = sol[ok, 2]
    with np.errstate(divide="ignore"):
        radius = np.where(r != 0.0, speed / np.abs(r), np.inf)
    out.fields[:, ok] = np.stack([y[:, m.output_index("surge_speed")], sol[ok, 1], r, speed,
                                  y[:, m.output_index("drift_angle")], radius])
