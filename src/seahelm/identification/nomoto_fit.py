"""Nomoto steering models identified from manoeuvre records, with their uncertainty.

First order (Nomoto et al. 1957), with a rudder offset δ_0 (the rudder angle that keeps the
ship straight: propeller asymmetry, wind)::

    T ṙ + r = K (δ + δ_0)

second order::

    T_1 T_2 r̈ + (T_1 + T_2) ṙ + r = K (δ + δ_0) + K T_3 δ̇

(:mod:`seahelm.vessels.nomoto`, where δ_0 is the model's ``rudder_disturbance``).

:func:`fit_nomoto` works in two stages, as identification from trials usually does:

1. **Equation error** (the start): r and ṙ (and r̈) from the record — the logged yaw rate, or
   the heading differentiated by a Savitzky–Golay filter on a uniform resampling — and a linear
   least-squares regression of ṙ on (r, δ, 1) (first order) or of r̈ on (ṙ, r, δ, δ̇, 1)
   (second order). Fast and biased by the noise of the derivatives.
2. **Output error** (the estimate): the heading (or, without one, the yaw rate) is simulated
   from the recorded rudder angle with the linear model of :mod:`seahelm.vessels.nomoto`,
   discretised exactly for a rudder linear between samples (:func:`simulate_records`), and
   the parameters — K, T (or T_1, T_2, T_3), δ_0 and each record's initial heading and yaw
   rate (and ṙ for the second order) — minimise the sum of squared heading errors
   (:func:`scipy.optimize.least_squares`, trust-region reflective, the time constants
   bounded positive), with forward-difference Jacobians.
3. **The start of the record** (issue 45): left free, the initial heading absorbs the model's
   misfit as a heading offset — the fitted heading began 2.2° (order 1) and 5.3° (order 2)
   off the Mariner's 20/20 zig-zag. The model's error is zero at t_0, where it starts from
   the ship's state, so the initial heading is known to the *measurement* noise σ_n
   (:func:`_start_state`), not to the residual σ_1 of the fit. The fit is therefore re-run
   from stage 2's optimum with the prior residual (ψ_0 − ψ̂_0) σ_1/σ_n added per record
   (ψ̂_0 the Savitzky–Golay heading at t_0): a MAP estimate that puts the fitted heading on
   the record (within σ_n) and changes the residual σ little (1.46° → 1.48°, order 1). The
   yaw rate and ṙ at t_0 stay free (their estimates from the end of a noisy record are too
   poor to anchor anything). ``anchor=False`` skips this stage.

**Uncertainty** (Laplace approximation at the optimum): covariance σ² (JᵀJ)⁻¹ with σ² the
residual variance (residuals taken as independent — with coloured residuals, e.g. waves, use
the bootstrap), standard errors, Student-t confidence intervals, the correlation matrix and the
condition number of JᵀJ (scaled). A parameter whose standard error exceeds its value, or whose
correlation with another exceeds 0.999, is reported as **unidentifiable** with that evidence,
never as a confident number. ``bootstrap=N`` adds a moving-block residual bootstrap
(Künsch 1989): N records made of the fitted output plus resampled residual blocks, each refitted
from the estimate; the spread of the refits gives percentile intervals.

Several records (a 10/10 and a 20/20 zig-zag, a turning circle of the same ship) are fitted
together: common K, T, δ_0, each record its own initial state. Time must increase; uneven
sampling is fine (the rudder is interpolated linearly to the simulation grid, the simulated
heading linearly back to the record's times).

References
----------
Nomoto, K., Taguchi, T., Honda, K., Hirano, S. (1957). On the steering qualities of ships.
Int. Shipbuilding Progress 4(35), 354–370.
Fossen, T.I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed. Wiley,
§7.1 and ch. 13 (identification of Nomoto models).
Künsch, H.R. (1989). The jackknife and the bootstrap for general stationary observations. Ann.
Statist. 17(3), 1217–1241.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numba import njit

from ..errors import ParameterError
from .records import ManoeuvreRecord

__all__ = ["NomotoFit", "fit_nomoto", "equation_error_start", "simulate_records"]

from .nomoto_fit_result import _NAMES, NomotoFit

# ------------------------------------------------------------------------------------------
# equation error
# ------------------------------------------------------------------------------------------
def _derivatives(record: ManoeuvreRecord, order: int) -> tuple[np.ndarray, ...]:
    """Uniformly resampled t, δ, δ̇, r, ṙ, r̈ of a record (Savitzky–Golay)."""
    from scipy.signal import savgol_filter

    dt = record.median_interval
    t = np.arange(record.time[0], record.time[-1] + 0.5 * dt, dt)
    delta = np.interp(t, record.time, record.rudder_angle)
    window = max(7, int(round(2.0 / dt)) | 1)
    window = min(window, (t.size - 1) | 1 if t.size % 2 == 0 else t.size)
    if window < 5:
        raise ParameterError(f"{record.name}: too short to differentiate ({t.size} samples)",
                             field="time")
    if record.heading is not None:
        psi = np.interp(t, record.time, record.heading)
        r = savgol_filter(psi, window, 3, deriv=1, delta=dt)
        rdot = savgol_filter(psi, window, 3, deriv=2, delta=dt)
        rddot = savgol_filter(psi, window, 4, deriv=3, delta=dt) if order == 2 else None
    else:
        rr = np.interp(t, record.time, record.yaw_rate)
        r = savgol_filter(rr, window, 3)
        rdot = savgol_filter(rr, window, 3, deriv=1, delta=dt)
        rddot = savgol_filter(rr, window, 3, deriv=2, delta=dt) if order == 2 else None
    ddelta = np.gradient(delta, dt)
    return t, delta, ddelta, r, rdot, rddot


def equation_error_start(records: Sequence[ManoeuvreRecord], order: int = 1) -> np.ndarray:
    """Equation-error least-squares estimate of the Nomoto parameters (module docstring).

    Parameters
    ----------
    records : sequence of ManoeuvreRecord
    order : {1, 2}

    Returns
    -------
    ndarray
        (K, T, δ_0) or (K, T_1, T_2, T_3, δ_0).
    """
    rows, rhs = [], []
    for rec in records:
        _, delta, ddelta, r, rdot, rddot = _derivatives(rec, order)
        one = np.ones_like(r)
        if order == 1:
            rows.append(np.column_stack([r, delta, one]))
            rhs.append(rdot)
        else:
            rows.append(np.column_stack([rdot, r, delta, ddelta, one]))
            rhs.append(rddot)
    A, b = np.vstack(rows), np.concatenate(rhs)
    coef, *_ = np.linalg.lstsq(A, b, rcond=None)
    if order == 1:
        a, bd, c = coef
        T = -1.0 / a if a < 0 else 100.0
        K = bd * T
        return np.array([K, T, c / bd if bd else 0.0])
    a1, a0, b0, b1, c = coef
    P = -1.0 / a0 if a0 < 0 else 100.0
    S = max(-a1 * P, 1e-3)
    disc = S * S - 4 * P
    if disc > 0:
        t1, t2 = 0.5 * (S + math.sqrt(disc)), 0.5 * (S - math.sqrt(disc))
    else:
        t1, t2 = 0.9 * S, 0.1 * S
    K = b0 * P
    return np.array([K, t1, max(t2, 1e-2), b1 / b0 if b0 else 0.0, c / b0 if b0 else 0.0])


# ------------------------------------------------------------------------------------------
# output error
# ------------------------------------------------------------------------------------------
def _grid(record: ManoeuvreRecord) -> tuple[float, int]:
    dt = min(record.median_interval, 0.25)
    n = int(math.ceil(record.duration / dt))
    return dt, n


def _state_space(order: int, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A and B (inputs δ, δ_0) of the linear Nomoto model in :mod:`seahelm.vessels.nomoto`'s
    states: (ψ, r) or (ψ, r, ξ) with ξ = ṙ − K T_3/(T_1 T_2) δ."""
    if order == 1:
        k, tc = theta[0], theta[1]
        A = np.array([[0.0, 1.0], [0.0, -1.0 / tc]])
        B = np.array([[0.0, 0.0], [k / tc, k / tc]])
        return A, B
    k, t1, t2, t3 = theta[:4]
    t12 = t1 * t2
    a = k * t3 / t12
    # ṙ = ξ + a δ;  ξ̇ = [K (δ + δ_0) − (T_1 + T_2) ṙ − r] / (T_1 T_2)
    A = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0],
                  [0.0, -1.0 / t12, -(t1 + t2) / t12]])
    B = np.array([[0.0, 0.0], [a, 0.0], [(k - (t1 + t2) * a) / t12, k / t12]])
    return A, B


def _first_order_hold(A: np.ndarray, B: np.ndarray, dt: float) -> tuple[np.ndarray, ...]:
    """Exact discretisation for inputs linear between the samples (first-order hold):
    x_{k+1} = Φ x_k + (Γ_1 − Γ_2) u_k + Γ_2 u_{k+1}, from the exponential of
    [[A, B, 0], [0, 0, I/dt], [0, 0, 0]] dt (Franklin, Powell & Workman 1998, §6.3.2)."""
    from scipy.linalg import expm

    n, m = B.shape
    M = np.zeros((n + 2 * m, n + 2 * m))
    M[:n, :n], M[:n, n:n + m] = A * dt, B * dt
    M[n:n + m, n + m:] = np.eye(m)
    E = expm(M)
    phi, g1, g2 = E[:n, :n], E[:n, n:n + m], E[:n, n + m:]
    return phi, g1 - g2, g2


@njit(cache=True)
def _recursion(phi, g0, g1, x0, u, out, row):  # pragma: no cover - compiled
    """x_{k+1} = Φ x_k + G_0 u_k + G_1 u_{k+1} for one run; out[k] = x_k[row]."""
    n = x0.shape[0]
    x = x0.copy()
    nxt = np.empty(n)
    out[0] = x[row]
    for k in range(u.shape[0] - 1):
        for i in range(n):
            acc = 0.0
            for j in range(n):
                acc += phi[i, j] * x[j]
            for j in range(u.shape[1]):
                acc += g0[i, j] * u[k, j] + g1[i, j] * u[k + 1, j]
            nxt[i] = acc
        x[:] = nxt
        out[k + 1] = x[row]


#: Discretisations by (order, dt, parameters): a Jacobian's initial-state columns and δ_0's
#: share the nominal model's.
_HOLDS: dict[tuple[int, float, bytes], tuple[np.ndarray, ...]] = {}


def simulate_records(order: int, thetas: np.ndarray, inits: np.ndarray,
                     record: ManoeuvreRecord, output: str) -> np.ndarray:
    """The model output at the record's times for a batch of parameter sets.

    The linear Nomoto model of :mod:`seahelm.vessels.nomoto` (Norrbin's n3 = 0) is linear in
    its states and the rudder, and the rudder is the straight line between the samples
    (:mod:`seahelm.actuators.hold`), so the exact first-order-hold discretisation on the grid
    of :func:`_grid` replaces time-stepping: equal to the compiled engine's RK4 run to its
    truncation error (tested), and about a hundred times faster (issue 45: an order-2 fit of
    a 10-minute record took 103 s).

    Parameters
    ----------
    order : {1, 2}
    thetas : ndarray, shape (runs, parameters)
        (K, T, δ_0) or (K, T_1, T_2, T_3, δ_0) per run.
    inits : ndarray, shape (runs, 2 or 3)
        Initial ψ, r (and ṙ) per run.
    record : ManoeuvreRecord
    output : {"heading", "yaw_rate"}

    Returns
    -------
    ndarray, shape (runs, samples)
        NaN for a run whose parameters are not admissible or whose output is not finite.
    """
    dt, n = _grid(record)
    t = record.time[0] + dt * np.arange(n + 1)
    delta = np.interp(t, record.time, record.rudder_angle)
    row = 0 if output == "heading" else 1
    out = np.full((thetas.shape[0], record.time.size), np.nan)
    y = np.empty(n + 1)
    for i, (theta, init) in enumerate(zip(np.asarray(thetas, dtype=float),
                                          np.asarray(inits, dtype=float))):
        if not (np.all(np.isfinite(theta)) and np.all(theta[1:order + 1] > 0)):
            continue
        key = (order, dt, theta[:-1].tobytes())  # δ_0 is an input, not in Φ, Γ
        if key not in _HOLDS:
            if len(_HOLDS) > 64:
                _HOLDS.clear()
            _HOLDS[key] = _first_order_hold(*_state_space(order, theta), dt)
        phi, g0, g1 = _HOLDS[key]
        x0 = np.array(init[:order + 1], dtype=float)
        if order == 2:  # ξ = ṙ − K T_3/(T_1 T_2) δ(0)
            x0[2] = init[2] - theta[0] * theta[3] / (theta[1] * theta[2]) * delta[0]
        u = np.column_stack([delta, np.full_like(delta, theta[-1])])
        _recursion(phi, g0, g1, x0, u, y, row)
        if np.all(np.isfinite(y)):
            out[i] = np.interp(record.time, t, y)
    return out


def _measured(record: ManoeuvreRecord, output: str) -> np.ndarray:
    return record.heading if output == "heading" else record.yaw_rate


#: The most bootstrap refits :func:`fit_nomoto` makes. Percentile intervals need about 1000 to
#: 2000 (Efron & Tibshirani 1993, ch. 19: beyond, their Monte-Carlo error is far below their
#: sampling error); each refit is a whole output-error fit (0.4-0.8 s for a 600-sample record on
#: a 2-core machine), so 10 000 refits are one to two hours and 10^6 a week.
MAX_BOOTSTRAP = 10_000


def fit_nomoto(records: ManoeuvreRecord | Sequence[ManoeuvreRecord], order: int = 1, *,
               bootstrap: int = 0, seed: int | None = None, speed: float | None = None,
               anchor: bool = True) -> NomotoFit:
    """Identify a first- or second-order Nomoto model from records (module docstring).

    Parameters
    ----------
    records : ManoeuvreRecord or sequence of them
        Records of the same ship at the same speed (:func:`~seahelm.identification.records.
        read_records`).
    order : {1, 2}
        Nomoto's first or second order.
    bootstrap : int, optional
        Moving-block bootstrap refits (0: none).
    seed : int, optional
        Seed of the bootstrap.
    speed : float, optional
        The ship's speed U [m/s] in the records, kept with the fit (for a ship file).
    anchor : bool, optional
        Anchor each record's initial heading to the record's start (default True; module
        docstring). False leaves the initial states free, as before issue 45.

    Returns
    -------
    NomotoFit

    Raises
    ------
    ParameterError
        A bad order, no records, a non-positive speed, a bootstrap < 0.
    """
    from scipy.optimize import least_squares

    if order not in (1, 2):
        raise ParameterError(f"must be 1 or 2, got {order!r}", field="order", value=order)
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    if not recs:
        raise ParameterError("no records to fit", field="records")
    if (isinstance(bootstrap, bool) or not isinstance(bootstrap, int)
            or not 0 <= bootstrap <= MAX_BOOTSTRAP):
        raise ParameterError(
            f"must be a whole number in [0, {MAX_BOOTSTRAP}] (percentile intervals need about "
            "1000-2000 refits, Efron & Tibshirani 1993, ch. 19; each refit is a whole "
            f"output-error fit of the records), got {bootstrap!r}", field="bootstrap",
            value=bootstrap)
    if speed is not None and not (math.isfinite(speed) and speed > 0):
        raise ParameterError(f"must be > 0 [m/s], got {speed!r}", field="speed", unit="m/s",
                             value=speed)
    output = "heading" if all(r.heading is not None for r in recs) else "yaw_rate"
    start = equation_error_start(recs, order)
    n_theta = start.size
    if order == 2:
        # the third derivative of a noisy heading makes a poor start: start from the first-order
        # output-error fit instead, T_1 = T, T_2 = T_3 = T/10 (so T_1 + T_2 − T_3 = T)
        first = fit_nomoto(recs, 1, anchor=False)
        k, tc, offset = first.values
        guess = np.array([k, tc, 0.1 * tc, 0.1 * tc, offset])
    else:
        guess = start
    n_init = 2 if order == 1 else 3
    starts = [_start_state(rec, order) for rec in recs]
    inits = np.ravel([st[0] for st in starts])
    spread = np.ravel([st[1] for st in starts])
    x0 = np.concatenate([_sane(guess, order), inits])
    measured = [_measured(rec, output) for rec in recs]
    # 1. the initial states free; 2. anchored to the record's start (module docstring): prior
    # residuals (x_init − x̂_init) σ_1/s, σ_1 the output residual σ of the first pass
    free, jac, residuals = _output_error(order, recs, measured, output, x0, n_theta, n_init,
                                         least_squares)
    values = free
    pooled = np.concatenate(residuals)
    sigma_1 = max(float(np.sqrt(np.mean(pooled ** 2))), 1e-12)
    if anchor:
        values, jac, residuals = _output_error(order, recs, measured, output, free, n_theta,
                                               n_init, least_squares, (inits, sigma_1 / spread))
    n = sum(m.size for m in measured)
    dof = n - values.size
    rss = float(sum(np.sum(e * e) for e in residuals))
    sigma2 = rss / max(dof, 1)
    cov_all, cond = _laplace(jac, sigma2)
    boot = None
    if bootstrap:
        boot = _bootstrap(order, recs, output, values, residuals, n_theta, n_init, bootstrap,
                          seed, least_squares)
    return NomotoFit(
        order=order, names=_NAMES[order], values=values[:n_theta],
        covariance=cov_all[:n_theta, :n_theta], dof=dof, residual_std=math.sqrt(sigma2),
        output=output, records=tuple(r.name for r in recs),
        initial_states=values[n_theta:].reshape(len(recs), n_init), equation_error=start,
        condition_number=cond, residuals=tuple(residuals), bootstrap=boot, speed=speed)


def _sane(theta: np.ndarray, order: int) -> np.ndarray:
    """An equation-error start inside the bounds (positive time constants, T_1 ≥ T_2)."""
    th = np.array(theta, dtype=float)
    th[1:order + 1] = np.clip(np.abs(th[1:order + 1]), 0.05, 1e5)
    if order == 2 and th[2] > th[1]:
        th[1], th[2] = th[2], th[1]
    if not np.isfinite(th[0]) or th[0] <= 0:
        th[0] = 0.01
    th[-1] = float(np.clip(th[-1], -0.5, 0.5)) if np.isfinite(th[-1]) else 0.0
    if order == 2:
        th[3] = float(np.clip(th[3], 0.0, 1e5)) if np.isfinite(th[3]) else 0.0
    return th


def _unpack(x: np.ndarray, n_theta: int, n_init: int, k: int) -> tuple[np.ndarray, np.ndarray]:
    return x[:n_theta], x[n_theta + k * n_init:n_theta + (k + 1) * n_init]


def _start_state(record: ManoeuvreRecord, order: int) -> tuple[np.ndarray, np.ndarray]:
    """The record's initial state (ψ, r, and ṙ for order 2) and its measurement spread.

    ψ(t_0), r(t_0), ṙ(t_0) from the Savitzky–Golay fit of the start (:func:`_derivatives`);
    the spread from the measurement noise σ_n (1.4826 × the median absolute deviation of the
    heading, or yaw rate, about its Savitzky–Golay smoothing): σ_n for the measured signal,
    floored at 10⁻⁶ so that a noise-free record still has a finite weight (the heading, or the
    yaw rate of a record without one); infinite (no anchor, a start value only) for the states
    not measured but differentiated (r, ṙ of a heading record) and for a heading not recorded.
    """
    from scipy.signal import savgol_filter

    t, _, _, r, rdot, _ = _derivatives(record, order)
    dt = t[1] - t[0] if t.size > 1 else 1.0
    window = max(7, int(round(2.0 / dt)) | 1)
    window = min(window, (t.size - 1) | 1 if t.size % 2 == 0 else t.size)
    signal = (np.interp(t, record.time, record.heading) if record.heading is not None
              else np.interp(t, record.time, record.yaw_rate))
    smooth = savgol_filter(signal, window, 3)
    noise = 1.4826 * float(np.median(np.abs(signal - smooth)))
    if record.heading is not None:
        psi0, spread = float(smooth[0]), [noise, math.inf]
    else:  # no heading: the heading is not observed, its start is the record's zero
        psi0, spread = 0.0, [math.inf, noise]
    state = [psi0, float(r[0])]
    if order == 2:
        state.append(float(rdot[0]))
        spread.append(math.inf)
    return np.array(state), np.maximum(np.array(spread), 1e-6)


def _output_error(order, recs, measured, output, x0, n_theta, n_init, least_squares,
                  anchor=None):
    """Least squares on the simulated output (and, with ``anchor`` = (x̂_init, weights), the
    weighted deviations of the initial states from the record's start); the Jacobian is one
    batched simulation per record (forward differences)."""
    lower = np.full(x0.size, -np.inf)
    upper = np.full(x0.size, np.inf)
    lower[0] = 1e-9  # K > 0: a positive rudder angle turns to starboard (the models' range)
    lower[1:order + 1] = 1e-3  # time constants > 0
    if order == 2:
        lower[3] = 0.0  # T_3 >= 0 (the model's range)
    cache: dict[bytes, list[np.ndarray]] = {}

    def outputs(x: np.ndarray) -> list[np.ndarray]:
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = [simulate_records(order, x[None, :n_theta],
                                           _unpack(x, n_theta, n_init, k)[1][None], rec,
                                           output)[0] for k, rec in enumerate(recs)]
        return cache[key]

    def fun(x: np.ndarray) -> np.ndarray:
        res = [m - y for m, y in zip(measured, outputs(x))]
        if anchor is not None:
            res.append(anchor[1] * (x[n_theta:] - anchor[0]))
        out = np.concatenate(res)
        return np.where(np.isfinite(out), out, 1e3)

    def jac(x: np.ndarray) -> np.ndarray:
        base = outputs(x)
        steps = 1e-6 * np.maximum(np.abs(x), 1e-3)
        cols = []
        for k, rec in enumerate(recs):
            theta, init = _unpack(x, n_theta, n_init, k)
            # the nominal set and one perturbation per parameter this record depends on
            own = list(range(n_theta)) + [n_theta + k * n_init + j for j in range(n_init)]
            thetas = np.repeat(theta[None], len(own), axis=0)
            inits = np.repeat(init[None], len(own), axis=0)
            for row, j in enumerate(own):
                if j < n_theta:
                    thetas[row, j] += steps[j]
                else:
                    inits[row, j - n_theta - k * n_init] += steps[j]
            y = simulate_records(order, thetas, inits, rec, output)
            block = np.zeros((rec.time.size, x.size))
            for row, j in enumerate(own):
                block[:, j] = -(y[row] - base[k]) / steps[j]
            cols.append(block)
        if anchor is not None:
            prior = np.zeros((anchor[0].size, x.size))
            prior[:, n_theta:] = np.diag(anchor[1])
            cols.append(prior)
        J = np.vstack(cols)
        return np.where(np.isfinite(J), J, 0.0)

    sol = least_squares(fun, x0, jac=jac, bounds=(lower, upper), x_scale="jac",
                        method="trf", xtol=1e-10, ftol=1e-12, gtol=1e-10, max_nfev=200)
    residuals = [m - y for m, y in zip(measured, outputs(sol.x))]
    return sol.x, jac(sol.x), residuals


def _laplace(J: np.ndarray, sigma2: float) -> tuple[np.ndarray, float]:
    """σ² (JᵀJ)⁻¹ by SVD of the column-scaled J, and the condition number of JᵀJ."""
    norms = np.linalg.norm(J, axis=0)
    norms[norms == 0] = 1.0
    U, s, Vt = np.linalg.svd(J / norms, full_matrices=False)
    cond = float((s[0] / s[-1]) ** 2) if s[-1] > 0 else math.inf
    with np.errstate(divide="ignore"):
        inv = np.where(s > s[0] * 1e-12, 1.0 / (s * s), np.inf)
    cov_scaled = (Vt.T * inv) @ Vt
    cov = cov_scaled / np.outer(norms, norms) * sigma2
    return cov, cond


def _bootstrap(order, recs, output, values, residuals, n_theta, n_init, n_boot, seed,
               least_squares):
    """Moving-block residual bootstrap: refits from the estimate (module docstring)."""
    rng = np.random.default_rng(seed)
    fitted = [_measured(rec, output) - e for rec, e in zip(recs, residuals)]
    out = []
    for _ in range(n_boot):
        measured = []
        for f, e in zip(fitted, residuals):
            block = max(1, int(round(e.size ** (1.0 / 3.0))) * 2)
            starts = rng.integers(0, max(e.size - block, 1), size=e.size // block + 1)
            resampled = np.concatenate([e[s:s + block] for s in starts])[:e.size]
            measured.append(f + resampled)
        x, _, _ = _output_error(order, recs, measured, output, values.copy(), n_theta,
                                n_init, least_squares)
        out.append(x[:n_theta])
    return np.array(out)

