"""MMG hull derivatives identified from free-running records, with their uncertainty.

The rudder and propeller of the MMG model (Yasukawa & Yoshimura 2015;
:mod:`seahelm.vessels.mmg`) are taken as given — from a base ship (its captive tests, or
``seahelm ship estimate``) — together with the masses and added masses; what is identified are
the hull's resistance and manoeuvring derivatives (R'_0, X'_vv … N'_rrr), from records that log
u, v, r, δ and n (``surge_speed``, ``sway_speed``, ``yaw_rate``, ``rudder_angle``,
``propeller_rps``).

1. **Regression on accelerations.** u̇, v̇, ṙ by Savitzky–Golay differentiation; the total
   forces from the equations of motion (midship origin)::

       X = (m + m_x) u̇ − (m + m_y) v r − x_G m r²
       Y = (m + m_y) v̇ + (m + m_x) u r + x_G m ṙ
       N = (I_zG + x_G² m + J_z) ṙ + x_G m (v̇ + u r)

   minus the base ship's propeller and rudder forces give the hull forces, and X'_H, Y'_H, N'_H
   are linear in the derivatives: three linear least-squares problems. Manoeuvring records
   make them **collinear** (v' and r' move together in a turn): the column-scaled condition
   number and the correlation of the estimates are reported, and the solve is ordinary
   least squares, ridge (Hoerl & Kennard 1970, the ridge parameter by generalised
   cross-validation, Golub, Heath & Wahba 1979) or truncated SVD (singular values below 1e-3
   of the largest dropped).
2. **Output error** (:func:`refine_mmg`): every record is simulated from its recorded rudder
   angle and rps by the compiled engine, and the derivatives minimise the squared errors of
   u, v, r (scaled by U_0 and U_0/L) over all records at once; the Jacobian is one batched
   engine run per record. Laplace covariance as for the Nomoto fit.

Parameters whose standard error exceeds their magnitude, or whose correlation with another
exceeds 0.999, are reported as unidentifiable with that evidence.

References
----------
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
Hoerl, A.E., Kennard, R.W. (1970). Ridge regression. Technometrics 12(1), 55–67.
Golub, G.H., Heath, M., Wahba, G. (1979). Generalized cross-validation as a method for choosing
a good ridge parameter. Technometrics 21(2), 215–223.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numba import njit

from ..errors import ParameterError
from ..vessels.mmg import _forces as _mmg_forces
from .fit_result import FitResult
from .records import ManoeuvreRecord

__all__ = ["HullFit", "regress_hull", "refine_mmg", "identify_mmg", "HULL_TERMS",
           "REQUIRED_CHANNELS"]

#: The hull derivatives of each equation and their regressor (v', r' non-dimensional).
HULL_TERMS: dict[str, tuple[tuple[str, Any], ...]] = {
    "X": (("R_0", lambda v, r: -np.ones_like(v)), ("X_vv", lambda v, r: v * v),
          ("X_vr", lambda v, r: v * r), ("X_rr", lambda v, r: r * r),
          ("X_vvvv", lambda v, r: v ** 4)),
    "Y": (("Y_v", lambda v, r: v), ("Y_r", lambda v, r: r), ("Y_vvv", lambda v, r: v ** 3),
          ("Y_vvr", lambda v, r: v * v * r), ("Y_vrr", lambda v, r: v * r * r),
          ("Y_rrr", lambda v, r: r ** 3)),
    "N": (("N_v", lambda v, r: v), ("N_r", lambda v, r: r), ("N_vvv", lambda v, r: v ** 3),
          ("N_vvr", lambda v, r: v * v * r), ("N_vrr", lambda v, r: v * r * r),
          ("N_rrr", lambda v, r: r ** 3)),
}

#: Channels a record needs besides the rudder angle and the yaw rate.
REQUIRED_CHANNELS = ("surge_speed", "sway_speed", "propeller_rps")

METHODS = ("ols", "ridge", "tsvd")


@dataclasses.dataclass(frozen=True)
class HullFit(FitResult):
    """Identified hull derivatives (MMG names, non-dimensional as in MMGParams).

    Attributes
    ----------
    names : tuple of str
    values, covariance : ndarray
    method : str
        ``ols``, ``ridge``, ``tsvd`` or ``output-error``.
    condition_numbers : dict of str to float
        Column-scaled condition number of each equation's regressors (X, Y, N), or of the
        output-error Jacobian (``OE``).
    records : tuple of str
    residual_std : dict of str to float
        σ of each equation's (or output's) residuals.
    params : Params
        The base ship's parameters with the identified values in.
    fixed : dict of str to str
        Derivatives the records do not identify, kept at the base ship's values, each with the
        evidence (:func:`identify_mmg`).
    check : HullCheck or None
        Signs, plausible ranges and residual whiteness (:mod:`seahelm.identification.mmg_checks`;
        set by :func:`identify_mmg`).
    """

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray
    method: str
    condition_numbers: dict[str, float]
    records: tuple[str, ...]
    residual_std: dict[str, float]
    params: Any
    fixed: dict[str, str] = dataclasses.field(default_factory=dict)
    check: Any = None

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON).

        Returns
        -------
        dict
        """
        rows = self.parameter_rows()
        rows += [{"name": n, "identified": False, "fixed_at_base": True, "evidence": why}
                 for n, why in self.fixed.items()]
        out = {"method": self.method, "records": list(self.records), "parameters": rows,
               "condition_numbers": self.condition_numbers,
               "residual_std": self.residual_std,
               "correlation": np.round(self.correlation, 6).tolist()}
        if self.check is not None:
            out["checks"] = self.check.as_dict()
        return out

    def ship(self, base: Any, *, name: str | None = None) -> Any:
        """``base`` with the identified derivatives, each with its source (the fit, value and
        standard error); the records and the condition numbers in the provenance.

        Parameters
        ----------
        base : Ship
            The ship whose rudder, propeller and masses were taken as given.
        name : str, optional
            The new ship's name (default ``"<base>-identified"``).

        Returns
        -------
        Ship

        Raises
        ------
        ParameterError
            When a derivative is not identified (it cannot go into a ship file as a number).
        """
        bad = self.unidentifiable()
        if bad:
            raise ParameterError(
                "the records do not identify " + "; ".join(f"{k} ({v})" for k, v in bad.items())
                + ": fit fewer derivatives (the others from the base ship) or add records",
                field="names")
        records = ", ".join(self.records)
        sources = dict(base.coefficient_sources)
        for i, n in enumerate(self.names):
            sources[n] = (f"{self.method} fit to {records}: {self.values[i]:.6g} ± "
                          f"{self.standard_errors[i]:.3g} (standard error)")
        for n, why in self.fixed.items():
            sources[n] = (f"not identified by {records} ({why}): kept at '{base.name}''s "
                          f"value. " + base.source_of(n))
        conds = ", ".join(f"{k} {v:.3g}" for k, v in self.condition_numbers.items())
        return base.replace(
            name=name or f"{base.name}-identified",
            params={n: float(v) for n, v in zip(self.names, self.values)},
            coefficient_sources=tuple(sources.items()),
            description=f"{base.description} — hull derivatives identified from "
                        f"{len(self.records)} record(s)",
            provenance=f"hull derivatives identified ({self.method}; condition numbers {conds}) "
                       f"from {records}; rudder, propeller and masses of '{base.name}': "
                       f"{base.provenance}")


def _check_records(records: Sequence[ManoeuvreRecord]) -> None:
    for rec in records:
        missing = [c for c in REQUIRED_CHANNELS if c not in rec.channels]
        if rec.yaw_rate is None:
            missing.insert(0, "yaw_rate")
        if missing:
            raise ParameterError(f"{rec.name}: missing column(s) {', '.join(missing)}: the MMG "
                                 "identification needs u, v, r, δ and n", field=missing[0])


def _smooth(record: ManoeuvreRecord) -> dict[str, np.ndarray]:
    """Uniformly resampled u, v, r, δ, n and the derivatives of u, v, r."""
    from scipy.signal import savgol_filter

    dt = record.median_interval
    t = np.arange(record.time[0], record.time[-1] + 0.5 * dt, dt)
    window = max(7, int(round(2.0 / dt)) | 1)
    if window >= t.size:
        raise ParameterError(f"{record.name}: too short ({t.size} samples) to differentiate",
                             field="time")
    out = {"t": t}
    for key, values in (("u", record.channels["surge_speed"]),
                        ("v", record.channels["sway_speed"]), ("r", record.yaw_rate)):
        x = np.interp(t, record.time, values)
        out[key] = savgol_filter(x, window, 3)
        out[key + "dot"] = savgol_filter(x, window, 3, deriv=1, delta=dt)
    out["delta"] = np.interp(t, record.time, record.rudder_angle)
    out["n"] = np.interp(t, record.time, record.channels["propeller_rps"])
    return out


_X, _Y, _N = 0, 1, 2  # columns of _propeller_rudder's output: surge force, sway force, moment


@njit(cache=True)
def _propeller_rudder(u, v, r, delta, n, p, out):  # pragma: no cover - compiled
    """X_P + X_R, Y_R, N_R [N, N·m] of the MMG model for each sample (its own _forces)."""
    for i in range(u.size):
        (_X_H, _Y_H, _N_H, X_P, X_R, Y_R, N_R, _T, _F_N, _w_P, _u_R, _v_R, _U,
         _beta) = _mmg_forces(u[i], v[i], r[i], delta[i], n[i], p)
        out[i, _X] = X_P + X_R
        out[i, _Y] = Y_R
        out[i, _N] = N_R


def _hull_forces(p: Any, s: dict[str, np.ndarray]) -> tuple[np.ndarray, ...]:
    """X'_H, Y'_H, N'_H per sample and v', r' (module docstring)."""
    from ..constants import GRAVITY

    L, rho = p.length, p.rho
    m = rho * p.displacement
    scale = 0.5 * rho * L * L * p.draft
    mx, my, jz = p.m_x * scale, p.m_y * scale, p.J_z * scale * L * L
    izg = m * (p.gyration_radius * L) ** 2
    xg = p.x_G
    u, v, r = s["u"], s["v"], s["r"]
    X = (m + mx) * s["udot"] - (m + my) * v * r - xg * m * r * r
    Y = (m + my) * s["vdot"] + (m + mx) * u * r + xg * m * s["rdot"]
    N = (izg + xg * xg * m + jz) * s["rdot"] + xg * m * (s["vdot"] + u * r)
    comps = np.empty((u.size, 3))
    _propeller_rudder(u, v, r, s["delta"], s["n"], p.to_record(), comps)
    X_H = X - comps[:, 0]
    Y_H = Y - comps[:, 1]
    N_H = N - comps[:, 2]
    speed = np.sqrt(u * u + v * v)
    q = 0.5 * rho * L * p.draft * speed * speed
    floor = np.maximum(speed, p.min_froude_number * math.sqrt(GRAVITY * L))
    return X_H / q, Y_H / q, N_H / (q * L), v / floor, r * L / floor


def _solve(A: np.ndarray, b: np.ndarray, method: str) -> tuple[np.ndarray, np.ndarray, float,
                                                                 float]:
    """Coefficients, covariance, residual σ, column-scaled condition number."""
    norms = np.linalg.norm(A, axis=0)
    norms[norms == 0] = 1.0
    As = A / norms
    U, s, Vt = np.linalg.svd(As, full_matrices=False)
    cond = float(s[0] / s[-1]) if s[-1] > 0 else math.inf
    beta = U.T @ b
    n, p = As.shape
    if method == "ols":
        f = np.ones_like(s)
    elif method == "tsvd":
        f = (s > 1e-3 * s[0]).astype(float)
    else:  # ridge, λ by generalised cross-validation over a log grid
        best = (math.inf, 0.0)
        resid0 = float(b @ b - beta @ beta)
        for lam in np.logspace(-10, 0, 61) * s[0] ** 2:
            ff = s * s / (s * s + lam)
            rss = resid0 + float(np.sum(((1 - ff) * beta) ** 2))
            gcv = rss / (n - np.sum(ff)) ** 2
            if gcv < best[0]:
                best = (gcv, lam)
        f = s * s / (s * s + best[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(s > 0, f / s, 0.0)
    coef_s = Vt.T @ (inv * beta)
    resid = b - As @ coef_s
    dof = max(n - float(np.sum(f)), 1.0)
    sigma2 = float(resid @ resid) / dof
    cov_s = (Vt.T * (inv * inv)) @ Vt * sigma2
    return coef_s / norms, cov_s / np.outer(norms, norms), math.sqrt(sigma2), cond


def regress_hull(records: ManoeuvreRecord | Sequence[ManoeuvreRecord], base: Any, *,
                 method: str = "ridge") -> HullFit:
    """Hull derivatives by regression on accelerations (module docstring, step 1).

    Parameters
    ----------
    records : ManoeuvreRecord or sequence of them
        With u, v, r, δ, n (:data:`REQUIRED_CHANNELS`).
    base : Ship or MMGParams
        The ship whose masses, propeller and rudder are taken as given.
    method : {"ols", "ridge", "tsvd"}

    Returns
    -------
    HullFit
    """
    from ..vessels.mmg import MMGParams

    params = getattr(base, "params", base)
    if not isinstance(params, MMGParams):
        raise ParameterError(f"must be an MMG ship, got {type(params).__name__}", field="ship")
    if method not in METHODS:
        raise ParameterError(f"must be one of {', '.join(METHODS)}, got {method!r}",
                             field="method")
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    _check_records(recs)
    data = [_hull_forces(params, _smooth(rec)) for rec in recs]
    xh, yh, nh, v, r = (np.concatenate([d[k] for d in data]) for k in range(5))
    names, values, blocks, conds, sig = [], [], [], {}, {}
    for eq, target in (("X", xh), ("Y", yh), ("N", nh)):
        terms = HULL_TERMS[eq]
        A = np.column_stack([fn(v, r) for _, fn in terms])
        coef, cov, sigma, cond = _solve(A, target, method)
        names += [n for n, _ in terms]
        values.append(coef)
        blocks.append(cov)
        conds[eq], sig[eq] = cond, sigma
    from scipy.linalg import block_diag

    vals = np.concatenate(values)
    fitted = params.replace(**{n: float(x) for n, x in zip(names, vals)})
    return HullFit(names=tuple(names), values=vals, covariance=block_diag(*blocks),
                   method=method, condition_numbers=conds, records=tuple(r.name for r in recs),
                   residual_std=sig, params=fitted)


def _simulate(params_list: list[Any], record: ManoeuvreRecord) -> np.ndarray:
    """u, v, r of a batch of MMG parameter sets driven by the record's δ and n, at its times:
    shape (runs, 3, samples).

    δ and n are the record's (the angle the rudder had, not the order given to the steering
    gear), the straight lines between its samples (:mod:`seahelm.actuators.hold`); the step
    is the record's median sampling interval (at most a fortieth of the record)."""
    from ..actuators.hold import hold_actuator, hold_reference
    from ..registry import get_model
    from ..simulation.engine import simulate

    model = get_model("mmg")
    dt = min(record.median_interval, 0.25 * record.duration / 10)
    n = int(math.ceil(record.duration / dt))
    t = record.time[0] + dt * np.arange(n + 1)
    inputs = ("rudder_angle", "propeller_rps")
    samples = np.stack([np.interp(t, record.time, record.rudder_angle),
                        np.interp(t, record.time, record.channels["propeller_rps"])], axis=-1)
    hold = hold_actuator(inputs, tuple(model.input_units[model.input_labels.index(k)]
                                       for k in inputs))
    u0, ref = hold_reference(samples, dt)
    x0 = np.zeros(model.n_states)
    labels = model.state_labels
    x0[labels.index("surge_speed")] = record.channels["surge_speed"][0]
    x0[labels.index("sway_speed")] = record.channels["sway_speed"][0]
    x0[labels.index("yaw_rate")] = record.yaw_rate[0]
    result = simulate(model, params=params_list, x0=np.repeat(x0[None], len(params_list), 0),
                      t_final=n * dt, dt=dt, actuator=hold, actuator_x0=u0,
                      reference=ref[None])
    out = np.full((len(params_list), 3, record.time.size), np.nan)
    for k, name in enumerate(("surge_speed", "sway_speed", "yaw_rate")):
        y = np.asarray(result[name])
        for i in range(len(params_list)):
            if np.all(np.isfinite(y[i])):
                out[i, k] = np.interp(record.time, t, y[i])
    return out


def _scaled_outputs(recs: Sequence[ManoeuvreRecord],
                    length: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """The output-error scales of u, v, r (U_0, U_0, U_0/L; U_0 the records' mean speed) and
    each record's measured u, v, r, shape (3, samples)."""
    U0 = float(np.mean([np.mean(np.hypot(r.channels["surge_speed"], r.channels["sway_speed"]))
                        for r in recs]))
    scales = np.array([U0, U0, U0 / length])
    measured = [np.stack([r.channels["surge_speed"], r.channels["sway_speed"], r.yaw_rate])
                for r in recs]
    return scales, measured


def refine_mmg(start: HullFit | Any, records: ManoeuvreRecord | Sequence[ManoeuvreRecord], *,
               names: Sequence[str] | None = None) -> HullFit:
    """Hull derivatives by output error over all records at once (module docstring, step 2).

    Parameters
    ----------
    start : HullFit or Ship or MMGParams
        Where to start (a :func:`regress_hull` fit, or a ship's own values).
    records : ManoeuvreRecord or sequence of them
        With u, v, r, δ, n.
    names : sequence of str, optional
        The derivatives to fit (default: every hull term, :data:`HULL_TERMS`); the others stay
        at their start values.

    Returns
    -------
    HullFit
        ``method = "output-error"``, with the Laplace covariance of the fitted names.
    """
    from scipy.optimize import least_squares

    from .nomoto_fit import _laplace

    params = start.params if isinstance(start, HullFit) else getattr(start, "params", start)
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    _check_records(recs)
    every = [n for terms in HULL_TERMS.values() for n, _ in terms]
    names = list(every if names is None else names)
    unknown = [n for n in names if n not in every]
    if unknown:
        raise ParameterError(f"not hull derivatives: {', '.join(unknown)}; valid: "
                             f"{', '.join(every)}", field="names")
    scales, measured = _scaled_outputs(recs, params.length)
    x0 = np.array([getattr(params, n) for n in names], dtype=float)

    def with_values(x: np.ndarray) -> Any:
        return params.replace(**{n: float(v) for n, v in zip(names, x)})

    def fun(x: np.ndarray) -> np.ndarray:
        p = with_values(x)
        res = [((m - _simulate([p], rec)[0]) / scales[:, None]).ravel()
               for m, rec in zip(measured, recs)]
        out = np.concatenate(res)
        return np.where(np.isfinite(out), out, 10.0)

    def jac(x: np.ndarray) -> np.ndarray:
        steps = 1e-6 * np.maximum(np.abs(x), 1e-2)
        sets = [with_values(x)] + [with_values(x + steps[j] * np.eye(x.size)[j])
                                   for j in range(x.size)]
        blocks = []
        for rec in recs:
            y = _simulate(sets, rec) / scales[None, :, None]
            blocks.append(((y[1:] - y[0]).reshape(x.size, -1) / steps[:, None]).T)
        J = -np.vstack(blocks)
        return np.where(np.isfinite(J), J, 0.0)

    sol = least_squares(fun, x0, jac=jac, x_scale="jac", method="trf", xtol=1e-10, ftol=1e-12,
                        gtol=1e-10, max_nfev=100)
    res = fun(sol.x)
    dof = max(res.size - sol.x.size, 1)
    sigma2 = float(res @ res) / dof
    cov, cond = _laplace(jac(sol.x), sigma2)
    return HullFit(names=tuple(names), values=sol.x, covariance=cov, method="output-error",
                   condition_numbers={"OE": cond}, records=tuple(r.name for r in recs),
                   residual_std={"u, v, r (scaled)": math.sqrt(sigma2)},
                   params=with_values(sol.x))


def _with_velocities(records: ManoeuvreRecord | Sequence[ManoeuvreRecord],
                     length: float) -> list[ManoeuvreRecord]:
    """Records without u and v but with x, y and heading get them from the EKF/RTS smoother
    (:func:`~seahelm.identification.velocity_smoother.reconstruct_velocities`, default noise
    levels); the others are returned as they are."""
    from .velocity_smoother import reconstruct_velocities

    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    out = []
    for rec in recs:
        has_uv = "surge_speed" in rec.channels and "sway_speed" in rec.channels
        if not has_uv and {"x", "y"} <= set(rec.channels) and rec.heading is not None:
            rec = reconstruct_velocities(rec, length=length)
        out.append(rec)
    return out


def identify_mmg(records: ManoeuvreRecord | Sequence[ManoeuvreRecord], base: Any, *,
                 method: str = "ridge", output_error: bool = True) -> HullFit:
    """Regression, output error, and the identifiable subset (module docstring).

    Records that log position and heading but not u and v get them from the smoother of
    :mod:`seahelm.identification.velocity_smoother` first. After the output-error fit of every hull
    derivative, the ones the records do not identify
    (:meth:`HullFit.unidentifiable`) are set back to the base ship's values and the others
    fitted again (parameter-subset selection), until every fitted derivative is identified;
    the fit lists the fixed ones in :attr:`HullFit.fixed` with their evidence.

    Parameters
    ----------
    records : ManoeuvreRecord or sequence of them
    base : Ship
        The MMG ship whose masses, propeller and rudder are taken as given, and whose values
        stand in for what the records do not identify.
    method : {"ols", "ridge", "tsvd"}
        The regression.
    output_error : bool
        Refine by output error (default) or stop at the regression.

    Returns
    -------
    HullFit
        With :attr:`HullFit.check` (signs, plausible ranges, residual whiteness:
        :func:`seahelm.identification.mmg_checks.check_hull_fit`).

    Warns
    -----
    SuspectBaseShipWarning
        When an identified derivative is implausible or the residuals are not white, naming
        the base ship's inputs to check (rudder, propeller, masses).
    """
    fit = _identify(records, base, method=method, output_error=output_error)
    return _checked(fit, records, base)


def _checked(fit: HullFit, records: Any, base: Any) -> HullFit:
    """The fit with its checks (and their warning), the residuals of its own simulation."""
    import warnings

    from .mmg_checks import SuspectBaseShipWarning, check_hull_fit

    recs = _with_velocities(records, float(getattr(base, "params", base).length))
    scales, measured = _scaled_outputs(recs, float(fit.params.length))
    residuals = {}
    for rec, m in zip(recs, measured):
        sim = _simulate([fit.params], rec)[0]
        every = max(1, int(round(1.0 / rec.median_interval)))  # about one sample a second
        for k, name in enumerate(("u", "v", "r")):
            residuals[f"{rec.name} {name}"] = ((m[k] - sim[k]) / scales[k])[::every]
    heldout = None
    if len(recs) >= 2 and fit.method == "output-error":  # predict the last record unseen
        train = refine_mmg(fit, recs[:-1], names=list(fit.names))
        sim = _simulate([train.params], recs[-1])[0]
        err = (measured[-1] - sim) / scales[:, None]
        heldout = (recs[-1].name, float(next(iter(train.residual_std.values()))),
                   float(np.sqrt(np.nanmean(err ** 2))))
    check = check_hull_fit(fit, base, residuals, heldout)
    if check.warning:
        warnings.warn(check.warning, SuspectBaseShipWarning, stacklevel=3)
    return dataclasses.replace(fit, check=check)


def _identify(records: Any, base: Any, *, method: str, output_error: bool) -> HullFit:
    records = _with_velocities(records, float(getattr(base, "params", base).length))
    fit = regress_hull(records, base, method=method)
    if output_error:
        fit = refine_mmg(fit, records)
    fixed: dict[str, str] = {}
    # fixing some derivatives can leave others without support (their partners gone, the
    # intervals of the rest wider or narrower): repeat until every fitted one is identified
    while True:
        bad = fit.unidentifiable()
        if not bad:
            return dataclasses.replace(fit, fixed=fixed) if fixed else fit
        fixed.update(bad)
        keep = [n for n in fit.names if n not in bad]
        if not keep:
            raise ParameterError(
                "the records identify none of the hull derivatives (e.g. "
                + "; ".join(f"{k}: {v}" for k, v in list(fixed.items())[:3])
                + "): give records with more manoeuvring (zig-zags and turns to both sides), "
                "or measured velocities", field="records")
        start = fit.params.replace(**{n: float(getattr(base.params, n)) for n in bad})
        if output_error:
            fit = refine_mmg(start, records, names=keep)
        else:
            idx = [fit.names.index(n) for n in keep]
            fit = dataclasses.replace(fit, names=tuple(keep), values=fit.values[idx],
                                      covariance=fit.covariance[np.ix_(idx, idx)], params=start)
