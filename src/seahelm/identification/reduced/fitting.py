"""Fitting the reduced steady-turn model to steady turns (Romanov & Chirkova, eq. (5)).

:func:`fit_lsq` (exact weighted linear least squares with covariance, standard errors and
condition number), :func:`fit_robust` (soft-L1 loss) and :func:`fit_brute_force` (the paper's
eq. (5), with a squared criterion) — registry :data:`FIT_METHODS`, :func:`fit_steady_turns` by
name; :func:`identify_from_time_series` extracts the steady segments of a log
(:mod:`seahelm.identification.reduced.segments`) and fits them. Each fit takes any form of
:data:`~seahelm.identification.reduced.forms.REDUCED_FORMS` and returns a
:class:`~seahelm.identification.reduced.forms.SteadyTurnFit`.

Notes
-----
**Identification.** The residual N_i = a ω_i² + b ω_i + α_i(1 + c ω_i) of eq. (5) is linear in
(a, b, c): the design row is (ω², ω, αω) and the target −α. The paper minimises the plain sum
of N_i, which is not a criterion (it is unbounded below); we minimise Σ w_i N_i². With
measurement noise σ_ω, σ_α on the points, the effective-variance weights
w_i = 1 / (F_ω² σ_ω² + F_α² σ_α²) (F the left-hand side, derivatives at the current estimate,
iterated) make the covariance (XᵀWX)⁻¹ absolute; without them the covariance is scaled by the
residual variance. Noise on ω also enters the design (errors in variables), which biases the
estimates at second order in σ_ω / (spread of ω) — negligible against the standard error for
realistic sensors.

References
----------
Romanov, A. V., Chirkova, M. M. Transforming the mathematical model of ship manoeuvrability to
minimise the time to estimate its coefficients (in Russian), VGAVT. Eq. (1)-(5).
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from ..._validate import as_finite_series, check_positive, lookup_name
from ...errors import ParameterError
from ...registry import lookup
from .criteria import CRITERIA, Criterion
from .forms import ReducedForm, SteadyTurnFit, get_form
from .segments import SteadySegments, extract_steady_segments

__all__ = [
    "fit_lsq",
    "fit_robust",
    "fit_brute_force",
    "FIT_METHODS",
    "fit_steady_turns",
    "identify_from_time_series",
]


# --------------------------------------------------------------------------------------------
# Fitting
# --------------------------------------------------------------------------------------------
#: Turns count as being to both sides when each side has one whose |ω| is at least this
#: fraction of the largest (a slightly negative ω near zero rudder is one side's asymmetry).
BOTH_SIDES_FRACTION = 0.25


def _check_one_sided(w: np.ndarray, form: ReducedForm) -> None:
    """A form that is not odd describes turns to one side (its a ω² term keeps its sign):
    fitted to turns to both sides it gave a ≈ 0, c ≈ 0 and exit 0 (issue 43)."""
    if form.odd or w.size == 0:
        return
    big = np.abs(w) >= BOTH_SIDES_FRACTION * float(np.max(np.abs(w)))
    n_pos, n_neg = int(np.count_nonzero(big & (w > 0))), int(np.count_nonzero(big & (w < 0)))
    if n_pos and n_neg:
        raise ParameterError(
            f"'{form.name}' is the steady-turn equation of turns to one side (its a ω² and "
            f"c ω α terms do not change sign with the side), but the turns are to both sides "
            f"({n_pos} with ω > 0, {n_neg} with ω < 0): give form '{form.name}-odd', or the "
            "turns of one side", field="form", value=form.name)


def _check_points(yaw_rate: Any, rudder_angle: Any, n_coef: int,
                  form: ReducedForm | None = None) -> tuple[np.ndarray, np.ndarray]:
    arrs = []
    for name, v, unit in (("yaw_rate", yaw_rate, "rad/s"), ("rudder_angle", rudder_angle, "rad")):
        arrs.append(as_finite_series(name, v, unit, what="point(s)"))
    w, al = arrs
    if w.size != al.size:
        raise ParameterError(
            f"`yaw_rate` and `rudder_angle` must have equal length, got {w.size} and {al.size}"
        )
    informative = {(float(x), float(y)) for x, y in zip(w, al) if not (x == 0.0 and y == 0.0)}
    if len(informative) < n_coef:
        raise ParameterError(
            f"need at least {n_coef} distinct steady points (ω, α) away from (0, 0) to fit "
            f"{n_coef} coefficients, got {len(informative)}"
        )
    if np.ptp(al) == 0.0:
        raise ParameterError(
            f"degenerate design: all points at the same rudder angle ({al[0]!r} rad); "
            "steady turns at different rudder angles are needed"
        )
    if form is not None:
        _check_one_sided(w, form)
    return w, al


def _check_weights(weights: Any, n: int) -> np.ndarray:
    if weights is None:
        return np.ones(n)
    wt = np.broadcast_to(np.asarray(weights, dtype=float), (n,)).copy()
    check_positive("weights", wt)
    return wt


def _solve_weighted(x: np.ndarray, y: np.ndarray, wt: np.ndarray) -> tuple[np.ndarray, ...]:
    sw = np.sqrt(wt)
    xw = x * sw[:, None]
    yw = y * sw
    norms = np.linalg.norm(xw, axis=0)
    if np.any(norms == 0.0):
        raise ParameterError(
            "degenerate design: a column of the design matrix is zero (e.g. all yaw rates 0)"
        )
    xs = xw / norms
    u, sv, vt = np.linalg.svd(xs, full_matrices=False)
    tol = sv[0] * max(xs.shape) * np.finfo(float).eps
    rank = int(np.sum(sv > tol))
    if rank < x.shape[1]:
        raise ParameterError(
            f"degenerate design: the design matrix has rank {rank} < {x.shape[1]} "
            "(the points do not determine the coefficients)"
        )
    coef_s = vt.T @ ((u.T @ yw) / sv)
    coef = coef_s / norms
    inv_s = (vt.T / sv**2) @ vt  # (XsᵀXs)⁻¹
    xtwx_inv = inv_s / np.outer(norms, norms)
    cond_scaled = float(sv[0] / sv[-1])
    cond = float(np.linalg.cond(xw))
    return coef, xtwx_inv, cond, cond_scaled


def _finish(coef, xtwx_inv, cond, cond_s, w, al, wt, form, method, absolute, scale_dof, t0):
    """``scale_dof``: scale (XᵀWX)⁻¹ by the residual variance unless ``absolute``; else the
    covariance is taken as given."""
    res = form.residual(coef, w, al)
    n, p = w.size, form.n_coef
    if absolute or not scale_dof:
        cov = xtwx_inv
    elif n > p:
        s2 = float(np.sum(wt * res**2) / (n - p))
        cov = s2 * xtwx_inv
    else:
        cov = np.full((p, p), np.nan)
    return SteadyTurnFit(
        coef=np.asarray(coef, dtype=float),
        covariance=cov,
        stderr=np.sqrt(np.diag(cov)),
        residuals=res,
        residual_rms=float(np.sqrt(np.mean(res**2))),
        condition_number=cond,
        condition_number_scaled=cond_s,
        yaw_rate=w,
        rudder_angle=al,
        weights=wt,
        method=method,
        form=form,
        absolute_sigma=absolute,
        elapsed=_time.perf_counter() - t0,
    )


def fit_lsq(
    yaw_rate: Any,
    rudder_angle: Any,
    *,
    form: str | ReducedForm = "paper",
    weights: Any = None,
    sigma_yaw_rate: Any = None,
    sigma_rudder_angle: Any = None,
    iterations: int = 3,
) -> SteadyTurnFit:
    """Exact weighted linear least squares for the reduced steady-turn model.

    Parameters
    ----------
    yaw_rate, rudder_angle : array_like, shape (n,)
        Steady turns ω_i [rad/s], α_i [rad]; n ≥ number of coefficients, distinct points.
    form : str or ReducedForm
        Equation form, see :data:`~.REDUCED_FORMS` ("paper" = eq. (4)).
    weights : array_like, optional
        Relative weights w_i > 0 of the squared equation residuals (ignored when noise levels
        are given).
    sigma_yaw_rate, sigma_rudder_angle : float or array_like, optional
        Standard deviations of the measured ω_i [rad/s] and α_i [rad]. If either is given the
        weights are the effective-variance weights 1/(F_ω²σ_ω² + F_α²σ_α²), re-evaluated
        ``iterations`` times, and the covariance is absolute.
    iterations : int
        Re-weighting passes for the effective-variance weights.

    Returns
    -------
    SteadyTurnFit
        Covariance (XᵀWX)⁻¹, scaled by the weighted residual variance Σw r²/(n − p) unless the
        noise levels were given; NaN for an exact fit (n = p) without them.

    Raises
    ------
    ParameterError
        Non-finite values, unequal lengths, fewer distinct points than coefficients, all points
        at one rudder angle, a rank-deficient design, non-positive weights or noise levels.
    """
    t0 = _time.perf_counter()
    f = get_form(form)
    w, al = _check_points(yaw_rate, rudder_angle, f.n_coef, f)
    x, y = f.design(w, al)
    absolute = sigma_yaw_rate is not None or sigma_rudder_angle is not None
    if absolute:
        sw2 = _sigma2("sigma_yaw_rate", sigma_yaw_rate, w.size, "rad/s")
        sa2 = _sigma2("sigma_rudder_angle", sigma_rudder_angle, w.size, "rad")
        coef, *_ = _solve_weighted(x, y, np.ones(w.size))
        for _ in range(max(int(iterations), 1)):
            fw, fa = f.partials(coef, w, al)
            var = fw**2 * sw2 + fa**2 * sa2
            if np.any(var <= 0):
                raise ParameterError("effective variance is zero at some point; give noise > 0")
            wt = 1.0 / var
            coef, xtwx_inv, cond, cond_s = _solve_weighted(x, y, wt)
    else:
        wt = _check_weights(weights, w.size)
        coef, xtwx_inv, cond, cond_s = _solve_weighted(x, y, wt)
    return _finish(coef, xtwx_inv, cond, cond_s, w, al, wt, f, "lsq", absolute, True, t0)


def _sigma2(name: str, value: Any, n: int, unit: str) -> np.ndarray:
    if value is None:
        return np.zeros(n)
    arr = np.broadcast_to(np.asarray(value, dtype=float), (n,))
    check_positive(name, arr, unit)
    return arr**2


def fit_robust(
    yaw_rate: Any,
    rudder_angle: Any,
    *,
    form: str | ReducedForm = "paper",
    weights: Any = None,
    f_scale: float | None = None,
    loss: str = "soft_l1",
    max_subsets: int = 2000,
    seed: int = 0,
) -> SteadyTurnFit:
    """Robust fit with :func:`scipy.optimize.least_squares` and a soft-L1 (or other) loss.

    Starts from the least-median-of-squares solution over the exact fits through p-point
    subsets (all of them for small n, else ``max_subsets`` random ones from ``seed``), whose
    residuals also give the default ``f_scale`` [rad] — the residual size beyond which points
    are down-weighted: Rousseeuw's 1.4826·(1 + 5/(n − p))·median|r| (at least 1e-12). A
    least-squares start and scale would be dragged by the very outliers to be resisted. The
    covariance is the Gauss-Newton approximation s²(JᵀJ)⁻¹ with the loss-modified Jacobian,
    s² = 2·cost/(n − p) — approximate. Note that every point is a leverage point here (ω and α
    both enter the design row), so a gross error is down-weighted but still pulls the fit.

    Parameters
    ----------
    yaw_rate : array_like, shape (n,)
        Steady yaw rates ω_i [rad/s].
    rudder_angle : array_like, shape (n,)
        Rudder angles α_i [rad] of the steady turns.
    form : str or ReducedForm, optional
        Reduced model, a name of :data:`~.REDUCED_FORMS` or the form itself (default "paper",
        eq. (4)).
    weights : array_like, shape (n,), optional
        Positive weights of the points (default: all 1).
    f_scale : float, optional
        Residual scale of the loss [rad] (default: from the least-median-of-squares start).
    loss : str, optional
        Loss of :func:`scipy.optimize.least_squares` (default "soft_l1").
    max_subsets : int, optional
        Largest number of p-point subsets tried for the start (default 2000).
    seed : int, optional
        Seed of the random subsets (default 0).

    Returns
    -------
    SteadyTurnFit
    """
    from scipy.optimize import least_squares

    t0 = _time.perf_counter()
    f = get_form(form)
    w, al = _check_points(yaw_rate, rudder_angle, f.n_coef, f)
    wt = _check_weights(weights, w.size)
    x, y = f.design(w, al)
    coef0, _, cond, cond_s = _solve_weighted(x, y, wt)
    sw = np.sqrt(wt)
    coef0, med = _lmeds_start(x * sw[:, None], y * sw, coef0, max_subsets, seed)
    if f_scale is None:
        n, p = x.shape
        f_scale = max(1.4826 * (1.0 + 5.0 / max(n - p, 1)) * med, 1e-12)
    check_positive("f_scale", f_scale, "rad")
    # Orthogonalise the weighted design (X_w = Q R, θ' = R θ): the robust solver then works on a
    # perfectly conditioned problem (the raw design is ill-conditioned, cond ~ 1e2-1e3).
    q_mat, r_mat = np.linalg.qr(x * sw[:, None])
    yw = y * sw

    def fun(theta: np.ndarray) -> np.ndarray:
        return q_mat @ theta - yw

    sol = least_squares(fun, r_mat @ coef0, jac=lambda th: q_mat, loss=loss, f_scale=f_scale,
                        method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=10000)
    coef = np.linalg.solve(r_mat, sol.x)
    n, p = w.size, f.n_coef
    jac = np.asarray(sol.jac) @ np.linalg.inv(r_mat)
    if n > p:
        try:
            cov = 2.0 * sol.cost / (n - p) * np.linalg.inv(jac.T @ jac)
        except np.linalg.LinAlgError:
            cov = np.full((p, p), np.nan)
    else:
        cov = np.full((p, p), np.nan)
    return _finish(coef, cov, cond, cond_s, w, al, wt, f, "robust", False, False, t0)


def _lmeds_start(x: np.ndarray, y: np.ndarray, coef_ls: np.ndarray, max_subsets: int,
                 seed: int) -> tuple[np.ndarray, float]:
    """Least median of squares over exact p-point fits; returns (coef, median |residual|)."""
    import itertools

    n, p = x.shape
    if math.comb(n, p) <= max_subsets:
        subsets = np.array(list(itertools.combinations(range(n), p)))
    else:
        rng = np.random.default_rng(seed)
        subsets = np.array([rng.choice(n, p, replace=False) for _ in range(max_subsets)])
    best = coef_ls
    best_med = float(np.median(np.abs(x @ coef_ls - y)))
    xs, ys = x[subsets], y[subsets]
    ok = np.abs(np.linalg.det(xs)) > 1e-300
    if ok.any():
        coefs = np.linalg.solve(xs[ok], ys[ok][..., None])[..., 0]
        meds = np.median(np.abs(coefs @ x.T - y), axis=1)
        k = int(np.argmin(meds))
        if meds[k] < best_med:
            best, best_med = coefs[k], float(meds[k])
    return best, best_med


def fit_brute_force(
    yaw_rate: Any,
    rudder_angle: Any,
    *,
    form: str | ReducedForm = "paper",
    bounds: Sequence[tuple[float, float]] | None = None,
    n_grid: int = 41,
    criterion: str | Criterion = "squared",
    chunk: int = 200_000,
) -> SteadyTurnFit:
    """The paper's brute-force search, eq. (5), with a proper criterion — a baseline.

    Every point of a regular grid of ``n_grid`` values per coefficient inside ``bounds`` is
    evaluated and the one minimising Σ N_i² (``criterion="squared"``) or Σ|N_i|
    ("absolute") is returned. (The paper's plain Σ N_i has no minimum: passed as
    :data:`seahelm.studies.romanov_chirkova.PRINTED_EQ5`, the search ends on the grid's
    boundary.) The accuracy is
    limited by the grid spacing; the cost is n_grid^p · n.

    Default bounds come from the data alone: b ∈ ±3 b₀, a ∈ ±3 b₀/ω_m, c ∈ ±3/ω_m (d ∈ ±3),
    with b₀ = median |α/ω| and ω_m = max |ω|.

    The returned covariance and standard errors are NaN (a grid search gives none).

    Parameters
    ----------
    yaw_rate : array_like, shape (n,)
        Steady yaw rates ω_i [rad/s].
    rudder_angle : array_like, shape (n,)
        Rudder angles α_i [rad] of the steady turns.
    form : str or ReducedForm, optional
        Reduced model, a name of :data:`~.REDUCED_FORMS` or the form itself (default "paper",
        eq. (4)).
    bounds : sequence of (float, float), optional
        (low, high) of each coefficient, in the units of the form's coefficients (default: from
        the data, see above).
    n_grid : int, optional
        Grid values per coefficient (>= 2, default 41).
    criterion : str or Criterion, optional
        A name of :data:`~seahelm.identification.reduced.criteria.CRITERIA` (``"squared"``, Σ N_i²,
        the default; ``"absolute"``, Σ|N_i|) or a criterion object.
    chunk : int, optional
        Grid points evaluated at once (memory bound; default 200 000).

    Returns
    -------
    SteadyTurnFit
    """
    t0 = _time.perf_counter()
    f = get_form(form)
    w, al = _check_points(yaw_rate, rudder_angle, f.n_coef, f)
    crit_of = lookup("criterion", CRITERIA, criterion, Criterion)
    if int(n_grid) < 2:
        raise ParameterError(f"`n_grid` must be >= 2, got {n_grid!r}")
    n_grid = int(n_grid)
    if bounds is None:
        nz = w != 0
        b0 = float(np.median(np.abs(al[nz] / w[nz]))) if nz.any() else 1.0
        wm = float(np.max(np.abs(w))) or 1.0
        bounds = [(-3 * b0 / wm, 3 * b0 / wm), (-3 * b0, 3 * b0), (-3 / wm, 3 / wm), (-3.0, 3.0)]
        bounds = bounds[: f.n_coef]
    bounds = [tuple(map(float, bd)) for bd in bounds]
    if len(bounds) != f.n_coef or any(not (lo < hi) for lo, hi in bounds):
        raise ParameterError(
            f"`bounds` must be {f.n_coef} (low, high) pairs with low < high, got {bounds!r}"
        )
    x, y = f.design(w, al)
    _solve_weighted(x, y, np.ones(w.size))  # the same rank checks as least squares
    grids = [np.linspace(lo, hi, n_grid) for lo, hi in bounds]
    # Enumerate the grid in chunks: residuals R = G @ Xᵀ − y for G (chunk, p).
    total = n_grid ** f.n_coef
    best_val, best_idx = np.inf, 0
    idx_all = np.arange(total)
    for start in range(0, total, chunk):
        idx = idx_all[start: start + chunk]
        sub = np.unravel_index(idx, (n_grid,) * f.n_coef)
        g = np.stack([grids[k][sub[k]] for k in range(f.n_coef)], axis=1)
        r = g @ x.T - y
        crit = crit_of(r)
        k = int(np.argmin(crit))
        if crit[k] < best_val:
            best_val, best_idx = float(crit[k]), int(idx[k])
    sub = np.unravel_index(best_idx, (n_grid,) * f.n_coef)
    coef = np.array([grids[k][sub[k]] for k in range(f.n_coef)])
    nan = np.full((f.n_coef, f.n_coef), np.nan)
    xw = x
    norms = np.linalg.norm(xw, axis=0)
    cond = float(np.linalg.cond(xw))
    cond_s = float(np.linalg.cond(xw / np.where(norms > 0, norms, 1.0)))
    return _finish(coef, nan, cond, cond_s, w, al, np.ones(w.size), f, "brute", False, False, t0)


FIT_METHODS: dict[str, Callable[..., SteadyTurnFit]] = {
    "lsq": fit_lsq,
    "robust": fit_robust,
    "brute": fit_brute_force,
}


def fit_steady_turns(yaw_rate: Any, rudder_angle: Any, *, method: str = "lsq",
                     **kwargs: Any) -> SteadyTurnFit:
    """Fit with a method from :data:`FIT_METHODS` by name (unknown names list the valid ones).

    Parameters
    ----------
    yaw_rate : array_like, shape (n,)
        Steady yaw rates ω_i [rad/s].
    rudder_angle : array_like, shape (n,)
        Rudder angles α_i [rad] of the steady turns.
    method : {"lsq", "robust", "brute"}, optional
        Fit method (default "lsq").
    **kwargs
        Passed to the method (:func:`fit_lsq`, :func:`fit_robust`, :func:`fit_brute_force`).

    Returns
    -------
    SteadyTurnFit
    """
    return lookup_name("fit method", FIT_METHODS, method)(yaw_rate, rudder_angle, **kwargs)


def identify_from_time_series(
    time: Any,
    rudder_angle: Any,
    yaw_rate: Any,
    *,
    method: str = "lsq",
    segment_options: Mapping[str, Any] | None = None,
    **fit_options: Any,
) -> tuple[SteadyTurnFit, SteadySegments]:
    """Extract the steady segments of a log and fit the reduced model to them.

    Parameters
    ----------
    time : array_like, shape (steps,)
        Time of the log [s].
    rudder_angle : array_like, shape (steps,)
        Rudder angle α [rad].
    yaw_rate : array_like, shape (steps,)
        Yaw rate ω [rad/s].
    method : {"lsq", "robust", "brute"}, optional
        Fit method of :func:`fit_steady_turns` (default "lsq").
    segment_options : mapping, optional
        Keyword arguments of :func:`~.extract_steady_segments`.
    **fit_options
        Passed to the fit method.

    Returns
    -------
    fit : SteadyTurnFit
        The fitted reduced model.
    segments : SteadySegments
        The steady segments used.
    """
    seg = extract_steady_segments(time, rudder_angle, yaw_rate, **dict(segment_options or {}))
    fit = fit_steady_turns(seg.yaw_rate, seg.rudder_angle, method=method, **fit_options)
    return fit, seg
