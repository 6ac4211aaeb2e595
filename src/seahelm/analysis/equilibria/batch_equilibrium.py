"""Steady straight approaches of a whole batch of parameter sets in one vectorised solve.

:func:`approach_states` is :func:`~seahelm.analysis.equilibria.equilibrium.approach_state` (with
``trim=True`` by default) for many parameter sets of one model at once — a Monte-Carlo
study's ships, or one ship at many speeds. Each run has two stages, solved for all runs
together with the model's own compiled right-hand side (one compiled loop over the
still-active runs per evaluation, each run's parameter record read in place):

1. **self-propulsion rps** (models with a ``propeller_rps`` input): the closed form where
   the model declares one (:mod:`.closed_forms`; the MMG model) and its right-hand side
   vanishes there; otherwise the zero of the surge
   acceleration f(n) at u = U_0, v = r = δ = 0, bracketed from n = 0 upwards by doubling (as
   :func:`~seahelm.analysis.equilibria.equilibrium.self_propulsion_rps`), then a safeguarded Newton
   iteration (forward-difference derivative; bisection whenever the step leaves the bracket)
   down to |Δn| ≤ 10⁻¹⁴ + 4 ε |n|, brentq's tolerance in the one-run solve;
2. **trim** (``trim=True``): u̇ = v̇ = ṙ = 0 with r = 0 solved for (u, v, δ) at that rps by
   Newton's method with a backtracking (Armijo) line search on ½‖F‖², F the accelerations
   scaled as the one-run solve scales them (z = (u/U, v/U, δ), F = (u̇, v̇, ṙ L) L/U²), the
   Jacobian by central differences, from (U_0, 0, 0) — the one-run solve's start. It stops
   when a step is below 10⁻¹⁴ (1 + ‖z‖) or F vanishes, and accepts ‖F‖∞ ≤ 10⁻⁹ (the one-run
   solve's acceptance; it iterates to the round-off floor, ~10⁻¹⁶, before stopping).

Why not ``scipy.optimize.root`` per run, or a compiled Newton? The one-run solve spends its
~2.5 ms per KVLCC2 approach in Python overhead (scipy's hybrd calls back into Python for every
residual); a numpy Newton over the batch makes ~40 vectorised evaluations whatever the batch
size (the compiled batch right-hand side costs ~0.3 µs a run), so the Python overhead is paid
once per batch, not per run. A numba kernel taking the model's ``rhs`` as an argument would not
be cacheable (a first-class dispatcher argument) and would compile anew in every process — a
second or so, more than the whole solve of 10⁴ runs takes here.

Failures are recorded per run (``status``, ``message``), never raised for the batch: the
surge force not negative with the propeller stopped, no rps up to ``max_rps``, a non-finite
right-hand side, a singular Jacobian, a line search without decrease, too many iterations.
Bad arguments (a speed ≤ 0, a perturbation model at another speed than its own) raise
:class:`~seahelm.errors.ParameterError` as the one-run functions do.

Constant-speed models (:mod:`seahelm.analysis.equilibria.constant_speed`) have no surge equation;
their approaches are solved one after the other by the one-run code (they cost microseconds).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from ...errors import ParameterError
from ...parameters import Params
from ...vessels.base import VesselModel, _batched_output
from .constant_speed import is_constant_speed
from .approach import ApproachStatus, BatchApproach
from . import closed_forms, fallback
from .plant import EquilibriumError, Plant

__all__ = ["ApproachStatus", "BatchApproach", "approach_states"]

#: Accepted scaled residual ‖F‖∞ (as the one-run solve, :func:`.fallback.solve`).
RESIDUAL_TOL = 1e-9
#: Relative Newton step below which the trim has converged.
STEP_TOL = 1e-14
#: brentq's tolerances of the one-run self-propulsion solve: |Δn| ≤ XTOL + RTOL |n|.
RPS_XTOL, RPS_RTOL = 1e-14, 4 * np.finfo(float).eps


def approach_states(model: VesselModel, params: Params | Sequence[Params], speed: Any = None,
                    *, trim: bool = True, heading: float = 0.0, max_rps: float = 1000.0,
                    max_iterations: int = 50) -> BatchApproach:
    """Steady straight approaches of many parameter sets in one vectorised solve.

    The batch form of :func:`~seahelm.analysis.equilibria.equilibrium.approach_state` (see the
    module docstring for the method): the same results to the solvers' tolerance (within 10⁻¹¹
    relative on the catalog ships and Monte-Carlo sets, 10⁻¹⁵ to 10⁻¹³ measured; see
    ``tests/test_analysis_batch_equilibrium.py``).

    Parameters
    ----------
    model : VesselModel
        The model every parameter set belongs to.
    params : Params or sequence of Params
        One parameter set per run (one type).
    speed : float or array_like, optional
        Approach speed U_0 [m/s] per run, or one for all (default: each parameter set's
        ``approach_speed``, or ``nominal_speed`` of a perturbation model).
    trim : bool, optional
        Trim with the rudder (and surge and sway) to an exact straight equilibrium with zero
        yaw rate (default True).
    heading : float, optional
        Heading ψ of the states [rad] (default 0).
    max_rps : float, optional
        Upper end of the rps search [1/s] (default 1000).
    max_iterations : int, optional
        Newton iterations of each stage (default 50).

    Returns
    -------
    BatchApproach
        Per-run states, rudder, rps, speed, drift angle, status and message.

    Raises
    ------
    ParameterError
        If ``params`` is empty or of several types, a speed is not > 0 or differs from a
        perturbation model's nominal speed, ``heading`` is not finite, or ``max_rps`` /
        ``max_iterations`` is not > 0.
    """
    plist = [params] if isinstance(params, Params) else list(params)
    if not plist:
        raise ParameterError(": no parameter sets", field="params")
    n = len(plist)
    if not (isinstance(heading, (int, float)) and math.isfinite(heading)):
        raise ParameterError(f"must be finite [rad], got {heading!r}", field="heading",
                             unit="rad", value=heading)
    if not (isinstance(max_rps, (int, float)) and max_rps > 0):
        raise ParameterError(f"must be > 0 [1/s], got {max_rps!r}", field="max_rps",
                             unit="1/s", value=max_rps)
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, int) \
            or max_iterations < 1:
        raise ParameterError(f"must be a whole number >= 1, got {max_iterations!r}",
                             field="max_iterations", value=max_iterations)
    if is_constant_speed(model):
        return _constant_speed(model, plist, speed, trim, float(heading))
    b = Plant(model, plist)
    U0 = _speeds(b, speed, n)
    status = np.zeros(n, dtype=np.int64)
    reason: dict[int, str] = {}
    rps = np.full(n, np.nan)
    iterations = np.zeros(n, dtype=np.int64)
    residual = np.zeros(n)
    if b.j_rps is not None:
        rps_iter, rps_res = _self_propulsion(b, U0, float(max_rps), max_iterations, status,
                                             reason, rps)
        iterations, residual = rps_iter, rps_res
    surge, v, rudder = U0.copy(), np.zeros(n), np.zeros(n)
    if trim:
        iterations = np.zeros(n, dtype=np.int64)
        _trim(b, surge, v, rudder, rps if b.j_rps is not None else None, max_iterations,
              status, reason, iterations, residual)
    bad = status != ApproachStatus.OK
    state = np.zeros((n, model.n_states))
    state[:, b.i_u] = surge - b.u_offset
    state[:, b.i_v] = v
    if b.i_psi is not None:
        state[:, b.i_psi] = heading
    state[bad] = np.nan
    rudder[bad] = np.nan
    rps[bad] = np.nan
    drift = _drift(b, state, rudder, rps, surge, v)
    messages = tuple(reason.get(i, "ok") for i in range(n))
    return BatchApproach(state=state, rudder=rudder, rps=rps, speed=U0, drift_angle=drift,
                         status=status, message=messages, iterations=iterations,
                         residual=residual)


def _speeds(b: Plant, speed: Any, n: int) -> np.ndarray:
    """Each run's approach speed, validated as the one-run solve validates it."""
    if speed is None:
        U0 = b.u_ref.copy()
    else:
        try:
            U0 = np.broadcast_to(np.asarray(speed, dtype=float), (n,)).copy()
        except (TypeError, ValueError):
            raise ParameterError(f"must be a number or one per run ({n}) [m/s], got "
                                 f"{speed!r}", field="speed", unit="m/s", value=speed) from None
    bad = ~(np.isfinite(U0) & (U0 > 0.0))
    if bad.any():
        i = int(np.argmax(bad))
        raise ParameterError(f"must be > 0 [m/s], got {float(U0[i])!r}", field="speed", unit="m/s",
                             value=float(U0[i]), run=i)
    pert = b.u_offset != 0.0
    off = pert & ~np.isclose(U0, b.u_offset, rtol=1e-12, atol=0.0)
    if off.any():
        i = int(np.argmax(off))
        raise ParameterError(
            f"must be the nominal speed U_0 = {float(b.u_offset[i])!r} [m/s] of the perturbation "
            f"model '{b.model.name}', got {float(U0[i])!r}", field="speed", unit="m/s",
            value=float(U0[i]), run=i)
    # (the one-run solve then uses the nominal speed exactly)
    U0[pert] = b.u_offset[pert]
    return U0


def _fail(status: np.ndarray, reason: dict[int, str], rows: np.ndarray, code: ApproachStatus,
          text: Any) -> None:
    """Record ``code`` and the text (a function of the run index) for ``rows``."""
    for i in rows.tolist():
        if status[i] == ApproachStatus.OK:
            status[i] = code
            reason[i] = text(i)


def _self_propulsion(b: Plant, U0: np.ndarray, max_rps: float, max_iterations: int,
                     status: np.ndarray, reason: dict[int, str], out: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Stage 1: the self-propulsion rps of every run into ``out`` (failures recorded)."""
    n = U0.size
    zeros = np.zeros(n)

    def f(rows: np.ndarray, rate: np.ndarray) -> np.ndarray:
        return b.accelerations(rows, U0[rows], zeros[rows], zeros[rows], rate)[:, 0]

    every = np.arange(n)
    iterations = np.zeros(n, dtype=np.int64)
    f_lo = f(every, zeros)
    _fail(status, reason, every[~np.isfinite(f_lo)], ApproachStatus.NOT_FINITE,
          lambda i: f"the surge force is not finite at `speed` = {float(U0[i])!r} [m/s] with the "
                    "propeller stopped")
    _fail(status, reason, every[f_lo >= 0.0], ApproachStatus.NO_SELF_PROPULSION,
          lambda i: f"at `speed` = {float(U0[i])!r} [m/s] the surge force is not negative with the "
                    "propeller stopped: no self-propulsion point")
    # a closed form the model declares, where its right-hand side vanishes (closed_forms)
    closed = closed_forms.self_propulsion_rps(b, U0)
    take = every[(status == ApproachStatus.OK) & np.isfinite(closed) & (closed > 0.0)
                 & (closed <= max_rps)]
    solved = np.zeros(n, dtype=bool)
    fx = np.full(n, np.nan)
    if take.size:
        fc = f(take, closed[take])
        good = np.abs(fc) * b.length[take] / b.u_ref[take] ** 2 <= closed_forms.RESIDUAL_TOL
        solved[take[good]] = True
        fx[take[good]] = fc[good]
    lo = np.zeros(n)
    hi = np.ones(n)
    f_hi = np.full(n, np.nan)
    active = every[(status == ApproachStatus.OK) & ~solved]
    while active.size:  # bracket: double hi until the propeller pushes
        f_hi[active] = f(active, hi[active])
        nan = active[~np.isfinite(f_hi[active])]
        _fail(status, reason, nan, ApproachStatus.NOT_FINITE,
              lambda i: f"the surge force is not finite at `speed` = {float(U0[i])!r} [m/s], "
                        f"{hi[i]:.6g} [1/s]")
        short = active[f_hi[active] <= 0.0]
        _fail(status, reason, short[hi[short] >= max_rps], ApproachStatus.RPS_OUT_OF_RANGE,
              lambda i: f"no propeller rps in (0, {max_rps:g}] [1/s] gives zero surge force "
                        f"at `speed` = {float(U0[i])!r} [m/s]")
        active = short[status[short] == ApproachStatus.OK]
        hi[active] = np.minimum(2.0 * hi[active], max_rps)
    active = every[(status == ApproachStatus.OK) & ~solved]
    # start from the secant of the bracket, then Newton with bisection as a safeguard
    with np.errstate(all="ignore"):
        x = lo - f_lo * (hi - lo) / (f_hi - f_lo)
    x = np.where(np.isfinite(x) & (x > lo) & (x < hi), x, 0.5 * (lo + hi))
    x[solved] = closed[solved]
    for _ in range(4 * max_iterations):
        if not active.size:
            break
        fa = f(active, x[active])
        fx[active] = fa
        iterations[active] += 1
        nan = active[~np.isfinite(fa)]
        _fail(status, reason, nan, ApproachStatus.NOT_FINITE,
              lambda i: f"the surge force is not finite at `speed` = {float(U0[i])!r} [m/s], "
                        f"{x[i]:.6g} [1/s]")
        active = active[np.isfinite(fa) & (fa != 0.0)]  # (f = 0: converged)
        fa = fx[active]
        neg = fa < 0.0
        lo[active[neg]] = x[active[neg]]
        hi[active[~neg]] = x[active[~neg]]
        xa = x[active]
        h = 1e-7 * np.maximum(np.abs(xa), 1e-3)
        slope = (f(active, xa + h) - fa) / h
        with np.errstate(all="ignore"):
            step = -fa / slope
        new = xa + step
        tol = RPS_XTOL + RPS_RTOL * np.abs(xa)
        conv = (np.abs(step) <= tol) | (hi[active] - lo[active] <= tol)
        out_of = ~conv & ~(np.isfinite(new) & (new > lo[active]) & (new < hi[active]))
        new = np.where(out_of, 0.5 * (lo[active] + hi[active]), new)
        x[active] = np.clip(new, lo[active], hi[active])
        active = active[~conv]
    else:
        _fail(status, reason, active, ApproachStatus.MAX_ITERATIONS,
              lambda i: f"the self-propulsion rps at `speed` = {float(U0[i])!r} [m/s] did not "
                        f"converge in {4 * max_iterations} iterations")
    ok = status == ApproachStatus.OK
    out[ok] = x[ok]
    scale = b.u_ref ** 2 / b.length
    return iterations, np.abs(fx) / scale


class _Newton(NamedTuple):
    """Outcome of :func:`_newton` per row: the last iterate ``z`` (k, 3) and residual ``F``
    there, the :class:`ApproachStatus` ``code`` (OK, NOT_FINITE at the start, SINGULAR,
    LINE_SEARCH, MAX_ITERATIONS), whether a MAX_ITERATIONS row ran out of iterations
    (``exhausted``; else it stopped above :data:`RESIDUAL_TOL`) and its ``iterations``."""

    z: np.ndarray
    F: np.ndarray
    code: np.ndarray
    exhausted: np.ndarray
    iterations: np.ndarray


def _newton(F: Callable[[np.ndarray, np.ndarray], np.ndarray], rows: np.ndarray,
            z0: np.ndarray, max_iterations: int, *, tol: float = 0.0,
            forward: bool = False) -> _Newton:
    """Newton's method with a backtracking (Armijo) line search on ½‖F‖², for every row at once.

    ``F(rows, z)`` is the scaled residual (k, 3) of the runs ``rows`` (a run may repeat) at the
    scaled unknowns ``z`` (k, 3). The Jacobian is by central differences (``forward``: forward
    differences, half the evaluations, for iterates that only start a later solve), all of its
    evaluations in one call of ``F``. A row stops when its residual is ≤ ``tol`` (0: iterate to
    the round-off floor), a step is below 10⁻¹⁴ (1 + ‖z‖), or the line search finds no decrease
    with the residual already ≤ :data:`RESIDUAL_TOL`; it is OK if its residual is then
    ≤ :data:`RESIDUAL_TOL`.
    """
    k = rows.size
    z = np.array(z0, dtype=float, copy=True)
    Fz = np.full((k, 3), np.nan)
    code = np.zeros(k, dtype=np.int64)
    exhausted = np.zeros(k, dtype=bool)
    iterations = np.zeros(k, dtype=np.int64)
    if k:
        Fz[:] = F(rows, z)
    active = np.flatnonzero(np.isfinite(Fz).all(axis=1))
    code[np.setdiff1d(np.arange(k), active)] = ApproachStatus.NOT_FINITE
    n_jac = 3 if forward else 6
    for _ in range(max_iterations):
        res = np.max(np.abs(Fz[active]), axis=1)
        active = active[res > tol]
        if not active.size:
            break
        iterations[active] += 1
        za, Fa = z[active], Fz[active]
        m = active.size
        # the Jacobian's evaluations in one call: +h for each unknown (then -h if central)
        zs = np.repeat(za[None], n_jac, axis=0)
        h = np.empty((3, m))
        for j in range(3):
            h[j] = 1e-6 * np.maximum(1.0, np.abs(za[:, j]))
            zs[j, :, j] += h[j]
            if not forward:
                zs[3 + j, :, j] -= h[j]
        Fs = F(np.tile(rows[active], n_jac), zs.reshape(n_jac * m, 3)).reshape(n_jac, m, 3)
        J = np.empty((m, 3, 3))
        for j in range(3):
            J[:, :, j] = ((Fs[j] - Fa) / h[j][:, None] if forward
                          else (Fs[j] - Fs[3 + j]) / (2.0 * h[j][:, None]))
        with np.errstate(all="ignore"):
            cond = np.linalg.cond(J)
        singular = ~(np.isfinite(cond) & (cond < 1e13))
        code[active[singular]] = ApproachStatus.SINGULAR
        keep = ~singular
        active, za, Fa, J = active[keep], za[keep], Fa[keep], J[keep]
        if not active.size:
            break
        dz = -np.linalg.solve(J, Fa[:, :, None])[:, :, 0]
        # a step at the round-off floor is taken as it is (no decrease is left to find)
        small = np.max(np.abs(dz), axis=1) <= STEP_TOL * (1.0 + np.max(np.abs(za), axis=1))
        phi = 0.5 * np.sum(Fa * Fa, axis=1)
        t = np.ones(active.size)
        accepted = np.zeros(active.size, dtype=bool)
        z_new, F_new = za.copy(), Fa.copy()
        pending = np.arange(active.size)
        while pending.size:  # backtracking: halve the step until ½‖F‖² decreases enough
            zt = za[pending] + t[pending, None] * dz[pending]
            Ft = F(rows[active[pending]], zt)
            phit = 0.5 * np.sum(Ft * Ft, axis=1)
            good = np.isfinite(phit) & ((phit <= (1.0 - 2e-4 * t[pending]) * phi[pending])
                                        | small[pending])
            idx = pending[good]
            z_new[idx], F_new[idx], accepted[idx] = zt[good], Ft[good], True
            pending = pending[~good]
            t[pending] *= 0.5
            pending = pending[t[pending] >= 2.0 ** -30]
        z[active], Fz[active] = z_new, F_new
        floor = ~accepted & (np.max(np.abs(Fa), axis=1) <= RESIDUAL_TOL)
        stuck = ~accepted & ~floor
        code[active[stuck]] = ApproachStatus.LINE_SEARCH
        active = active[~(small | floor | stuck)]
    else:
        code[active] = ApproachStatus.MAX_ITERATIONS
        exhausted[active] = True
    res = np.max(np.abs(Fz), axis=1)
    high = (code == ApproachStatus.OK) & ~(res <= RESIDUAL_TOL)
    code[high] = ApproachStatus.MAX_ITERATIONS
    return _Newton(z, Fz, code, exhausted, iterations)


def _trim(b: Plant, surge: np.ndarray, v: np.ndarray, rudder: np.ndarray,
          rps: np.ndarray | None, max_iterations: int, status: np.ndarray,
          reason: dict[int, str], iterations: np.ndarray, residual: np.ndarray) -> None:
    """Stage 2: (surge, v, rudder) with u̇ = v̇ = ṙ = 0 at r = 0, in place."""
    s = np.stack([b.u_ref, b.u_ref, np.ones_like(b.u_ref)], axis=1)
    acc_scale = (np.stack([np.ones_like(b.length), np.ones_like(b.length), 1.0 / b.length],
                          axis=1) * (b.u_ref ** 2 / b.length)[:, None])

    def F(rows: np.ndarray, zr: np.ndarray) -> np.ndarray:
        y = zr * s[rows]
        acc = b.accelerations(rows, y[:, 0], y[:, 1], y[:, 2],
                              None if rps is None else rps[rows])
        return acc / acc_scale[rows]

    active = np.flatnonzero(status == ApproachStatus.OK)
    z = np.stack([surge, v, rudder], axis=1) / s
    sol = _newton(F, active, z[active], max_iterations)
    z[active] = sol.z
    iterations[active] = sol.iterations
    Fz = np.full(z.shape, np.nan)
    Fz[active] = sol.F
    code = np.zeros(z.shape[0], dtype=np.int64)
    code[active] = sol.code
    exhausted = np.zeros(z.shape[0], dtype=bool)
    exhausted[active] = sol.exhausted
    res = np.max(np.abs(Fz), axis=1)
    residual[:] = res
    for i in active[sol.code != ApproachStatus.OK].tolist():
        y = z[i] * s[i]
        status[i] = code[i]
        reason[i] = _newton_failure(
            "no equilibrium found for surge, v, rudder with r = 0"
            + (f", rps = {rps[i]:.6g} [1/s]" if rps is not None else ""), code[i], exhausted[i],
            res[i], max_iterations,
            f"surge = {y[0]:.6g} [m/s], v = {y[1]:.6g} [m/s], rudder = {y[2]:.6g} [rad]")
    y = z * s
    surge[:], v[:], rudder[:] = y[:, 0], y[:, 1], y[:, 2]


def _newton_failure(what: str, code: int, exhausted: bool, res: float, max_iterations: int,
                    at: str) -> str:
    """``what`` and why :func:`_newton` failed (``code``; ``at``: the iterate, for a singular
    Jacobian)."""
    if code == ApproachStatus.NOT_FINITE:
        return f"{what} (the accelerations are not finite at the start)"
    if code == ApproachStatus.SINGULAR:
        return f"{what} (the Jacobian is singular at {at})"
    if code == ApproachStatus.LINE_SEARCH:
        return f"{what} (the line search found no decrease; residual {res:.3g})"
    if exhausted:
        return (f"{what} (not converged in {max_iterations} Newton iterations; residual "
                f"{res:.3g})")
    return f"{what} (residual {res:.3g} > {RESIDUAL_TOL:g})"


def _drift(b: Plant, state: np.ndarray, rudder: np.ndarray, rps: np.ndarray,
           surge: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The model's ``drift_angle`` output (β = atan2(−v, u) without one); NaN where failed."""
    m = b.model
    ok = np.isfinite(state).all(axis=1)
    out = np.full(state.shape[0], np.nan)
    if "drift_angle" not in m.output_labels:
        out[ok] = np.arctan2(-v[ok], surge[ok])
        return out
    rows = np.flatnonzero(ok)
    if not rows.size:
        return out
    u = np.zeros((rows.size, m.n_inputs))
    u[:, b.j_delta] = rudder[rows]
    if b.j_rps is not None:
        u[:, b.j_rps] = rps[rows]
    y = np.empty((rows.size, m.n_outputs))
    recs = b.records if rows.size == b.records.size else b.records[rows]
    _batched_output(m.output, 0.0, np.ascontiguousarray(state[rows]), u, recs, y)
    out[rows] = y[:, m.output_index("drift_angle")]
    return out


def _constant_speed(model: VesselModel, plist: list[Params], speed: Any, trim: bool,
                    heading: float) -> BatchApproach:
    """A constant-speed model's approaches, one run after the other (see the module)."""
    n = len(plist)
    speeds = (np.full(n, np.nan) if speed is None
              else np.broadcast_to(np.asarray(speed, dtype=float), (n,)))
    state = np.full((n, model.n_states), np.nan)
    rudder = np.full(n, np.nan)
    U0 = np.array([float(getattr(p, "speed", np.nan)) for p in plist])
    status = np.zeros(n, dtype=np.int64)
    messages = []
    for i, p in enumerate(plist):
        cs = fallback.constant_speed_plant(p, model)
        if cs is None:  # (not the model's parameter type: the plant says so)
            Plant(model, [p])
        try:
            state[i], rudder[i] = cs.approach(None if speed is None else float(speeds[i]),
                                              heading=heading, trim=trim)
        except EquilibriumError as exc:
            status[i] = ApproachStatus.NO_EQUILIBRIUM
            messages.append(str(exc))
            continue
        messages.append("ok")
    drift = np.where(status == 0, 0.0, np.nan)
    if "drift_angle" in model.state_labels:
        drift = state[:, model.state_index("drift_angle")]
    return BatchApproach(state=state, rudder=rudder, rps=np.full(n, np.nan), speed=U0,
                         drift_angle=drift, status=status, message=tuple(messages),
                         iterations=np.zeros(n, dtype=np.int64), residual=np.zeros(n))
