"""The linear sway–yaw model identified from manoeuvre records.

About a straight run at speed U, the linear equations of sway and yaw (Davidson & Schiff 1946;
Fossen 2021, §7.1, eq. (7.11)) M ν̇ + N ν = b_δ δ, ν = (v, r), are in state-space form::

    [v̇, ṙ]ᵀ = A [v, r]ᵀ + b δ + c,      A = −M⁻¹N,  b = M⁻¹ b_δ

with c a constant (a rudder offset, a single-screw bias). Motions identify A, b and c only:
the mass and damping matrices M and N are not separately identifiable from them (any
invertible M' with N' = M' M⁻¹ N gives the same motions), so :func:`fit_linear` gives A, b, c
and what follows from them — the poles and the second-order Nomoto constants of the yaw
response (Fossen 2021, eq. (7.23)–(7.26))::

    r/δ (s) = K (1 + T_3 s) / ((1 + T_1 s)(1 + T_2 s))
    K = −(A⁻¹ b)_r,  T_1, T_2 = −1/λ(A),  T_3 = b_r / (a_rv b_v − a_vv b_r)

**Equation error.** v̇ and ṙ by Savitzky–Golay differentiation (cubic, 2 s windows, on the
records resampled at their median interval — as :func:`seahelm.identification.mmg_fit.regress_hull`),
then two linear least-squares problems with the regressors v, r, δ, 1 over all records; the
covariance σ² (XᵀX)⁻¹ of each row, the column-scaled condition number, and the parameters the
records do not determine reported as unidentifiable with the evidence
(:func:`seahelm.identification.fit_result.unidentifiable`). The model is linear: records of small
rudder angles (a 5/5 zig-zag or less, a small random-rudder run) at a steady speed; in larger
manoeuvres the nonlinear terms and the speed loss enter the residuals (and the estimates).

References
----------
Davidson, K.S.M., Schiff, L.I. (1946). Turning and course-keeping qualities. Trans. SNAME 54.
Fossen, T.I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.,
Wiley, §7.1.
Savitzky, A., Golay, M.J.E. (1964). Smoothing and differentiation of data by simplified least
squares procedures. Anal. Chem. 36(8), 1627–1639.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError
from .fit_result import FitResult
from .records import ManoeuvreRecord

__all__ = ["LinearFit", "fit_linear", "LINEAR_NAMES", "LINEAR_UNITS"]

#: The identified entries: row v̇ then row ṙ, each on v, r, δ, 1.
LINEAR_NAMES = ("a_vv", "a_vr", "b_v", "c_v", "a_rv", "a_rr", "b_r", "c_r")

#: Their units (SI, radians).
LINEAR_UNITS = {"a_vv": "1/s", "a_vr": "m/s", "b_v": "m/s²", "c_v": "m/s²",
                "a_rv": "1/(m·s)", "a_rr": "1/s", "b_r": "1/s²", "c_r": "rad/s²"}


@dataclasses.dataclass(frozen=True)
class LinearFit(FitResult):
    """The identified linear sway–yaw model (module docstring).

    Attributes
    ----------
    names : tuple of str
        :data:`LINEAR_NAMES`.
    values, covariance : ndarray
        The estimates and their covariance (block-diagonal: the two rows are separate fits).
    condition_numbers : dict of str to float
        Column-scaled condition number of each row's regressors (``v``, ``r``).
    residual_std : dict of str to float
        σ of each row's residuals [m/s², rad/s²].
    records : tuple of str
    """

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray
    condition_numbers: dict[str, float]
    residual_std: dict[str, float]
    records: tuple[str, ...]

    def value(self, name: str) -> float:
        """One estimate by name.

        Parameters
        ----------
        name : str
            A name of :data:`LINEAR_NAMES`.

        Returns
        -------
        float
        """
        return float(self.values[self.names.index(name)])

    @property
    def A(self) -> np.ndarray:
        """The system matrix on (v, r)."""
        return np.array([[self.value("a_vv"), self.value("a_vr")],
                         [self.value("a_rv"), self.value("a_rr")]])

    @property
    def b(self) -> np.ndarray:
        """The rudder's column (b_v, b_r)."""
        return np.array([self.value("b_v"), self.value("b_r")])

    @property
    def poles(self) -> np.ndarray:
        """Eigenvalues of :attr:`A` [1/s] (stable: negative real parts)."""
        return np.linalg.eigvals(self.A)

    def nomoto(self) -> dict[str, float]:
        """K [1/s], T_1, T_2, T_3 [s] of the yaw response r/δ (module docstring).

        Returns
        -------
        dict of str to float
            T_1 ≥ T_2; NaN for T_1, T_2 when the poles are complex (an oscillatory model).
        """
        A, b = self.A, self.b
        K = float(-np.linalg.solve(A, b)[1])
        lam = self.poles
        if np.any(np.abs(lam.imag) > 0):
            t1 = t2 = math.nan
        else:
            t1, t2 = sorted((-1.0 / lam.real).tolist(), reverse=True)
        den = A[1, 0] * b[0] - A[0, 0] * b[1]
        t3 = float(b[1] / den) if den != 0 else math.nan
        return {"gain": K, "t1": t1, "t2": t2, "t3": t3}

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON).

        Returns
        -------
        dict
        """
        return {"records": list(self.records), "parameters": self.parameter_rows(LINEAR_UNITS),
                "condition_numbers": self.condition_numbers, "residual_std": self.residual_std,
                "poles": [complex(p) if p.imag else float(p.real) for p in self.poles],
                "nomoto": self.nomoto()}


def _derivatives(record: ManoeuvreRecord) -> dict[str, np.ndarray]:
    """v, r, δ and v̇, ṙ on the record's median-interval grid (Savitzky–Golay, cubic, 2 s)."""
    from scipy.signal import savgol_filter

    dt = record.median_interval
    t = np.arange(record.time[0], record.time[-1] + 0.5 * dt, dt)
    window = max(7, int(round(2.0 / dt)) | 1)
    if window >= t.size:
        raise ParameterError(f"{record.name}: too short ({t.size} samples) to differentiate",
                             field="time")
    # δ through the same smoothing as v and r: all regressors and targets then see one
    # linear filter, which a linear model's equation passes unchanged
    out = {"delta": savgol_filter(np.interp(t, record.time, record.rudder_angle), window, 3)}
    for key, values in (("v", record.channels["sway_speed"]), ("r", record.yaw_rate)):
        x = np.interp(t, record.time, values)
        out[key] = savgol_filter(x, window, 3)
        out[key + "dot"] = savgol_filter(x, window, 3, deriv=1, delta=dt)
    return out


def fit_linear(records: ManoeuvreRecord | Sequence[ManoeuvreRecord]) -> LinearFit:
    """The linear sway–yaw model of the records by equation error (module docstring).

    Parameters
    ----------
    records : ManoeuvreRecord or sequence of them
        With ``sway_speed`` and the yaw rate (and the rudder angle): small-rudder manoeuvres
        at a steady speed.

    Returns
    -------
    LinearFit

    Raises
    ------
    ParameterError
        A record without ``sway_speed`` or yaw rate, or too short to differentiate.
    """
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    if not recs:
        raise ParameterError("no records", field="records")
    for rec in recs:
        missing = [c for c, ok in (("sway_speed", "sway_speed" in rec.channels),
                                   ("yaw_rate", rec.yaw_rate is not None)) if not ok]
        if missing:
            raise ParameterError(f"{rec.name}: missing column(s) {', '.join(missing)}: the "
                                 "linear sway-yaw fit needs v, r and the rudder angle",
                                 field=missing[0])
    data = [_derivatives(rec) for rec in recs]
    cat = {k: np.concatenate([d[k] for d in data]) for k in data[0]}
    X = np.column_stack([cat["v"], cat["r"], cat["delta"], np.ones_like(cat["v"])])
    values, blocks, conds, sig = [], [], {}, {}
    for row, target in (("v", cat["vdot"]), ("r", cat["rdot"])):
        norms = np.linalg.norm(X, axis=0)
        Xs = X / norms
        coef, _, rank, s = np.linalg.lstsq(Xs, target, rcond=None)
        resid = target - Xs @ coef
        dof = max(X.shape[0] - X.shape[1], 1)
        sigma2 = float(resid @ resid) / dof
        cov = np.linalg.pinv(Xs.T @ Xs) * sigma2
        values.append(coef / norms)
        blocks.append(cov / np.outer(norms, norms))
        conds[row] = float(s[0] / s[-1]) if s[-1] > 0 else math.inf
        sig[row] = math.sqrt(sigma2)
    from scipy.linalg import block_diag

    return LinearFit(names=LINEAR_NAMES, values=np.concatenate(values),
                     covariance=block_diag(*blocks), condition_numbers=conds,
                     residual_std=sig, records=tuple(r.name for r in recs))
