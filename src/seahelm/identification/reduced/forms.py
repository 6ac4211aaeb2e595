"""Forms of the reduced steady-turn model (Romanov & Chirkova, eq. (4)) and the fit result.

A :class:`ReducedForm` is one linear-in-coefficients form of the reduced equation — the paper's
eq. (4) (``"paper"``), the exact elimination with a free α² coefficient (``"exact"``) and their
odd extensions to both sides (``"paper-odd"``, ``"exact-odd"``), registry
:data:`REDUCED_FORMS` (:mod:`seahelm.identification.reduced.turns` derives them).
:class:`SteadyTurnFit` is what a fit returns (:mod:`seahelm.identification.reduced.fitting`), with
prediction both ways (yaw rate for a rudder angle, rudder angle for a wanted yaw rate) and their
standard errors from the covariance (delta method); as every identification result it is a
:class:`~seahelm.identification.fit_result.FitResult` (standard errors, correlations,
intervals, what the points do not identify) on ``names`` = the form's coefficient names and
``values`` = :attr:`SteadyTurnFit.coef`.

References
----------
Romanov, A. V., Chirkova, M. M. Transforming the mathematical model of ship manoeuvrability to
minimise the time to estimate its coefficients (in Russian), VGAVT. Eq. (4).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from ..._validate import lookup_name
from ..fit_result import FitResult

__all__ = [
    "ReducedForm",
    "REDUCED_FORMS",
    "get_form",
    "SteadyTurnFit",
]


# --------------------------------------------------------------------------------------------
# Reduced model forms (design matrices)
# --------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class ReducedForm:
    """A linear-in-coefficients form of the reduced steady-turn equation.

    F(ω, α; θ) = s·(a ω² + c ω α [+ d α²]) + b ω + α with s = 1, or s = sign ω if ``odd``.
    """

    name: str
    odd: bool
    alpha_squared: bool
    description: str

    @property
    def n_coef(self) -> int:
        return 4 if self.alpha_squared else 3

    @property
    def names(self) -> tuple[str, ...]:
        return ("a", "b", "c", "d")[: self.n_coef]

    def _s(self, w: np.ndarray) -> np.ndarray:
        return np.sign(w) if self.odd else np.ones_like(w)

    def design(self, yaw_rate: np.ndarray, rudder_angle: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
        """Design matrix X (n, n_coef) and target y = −α, so that F = X θ − y.

        Parameters
        ----------
        yaw_rate : array_like, shape (n,)
            Yaw rates ω [rad/s].
        rudder_angle : array_like, shape (n,)
            Rudder angles α [rad].

        Returns
        -------
        X : numpy.ndarray, shape (n, n_coef)
            Design matrix.
        y : numpy.ndarray, shape (n,)
            Target −α [rad].
        """
        w = np.asarray(yaw_rate, dtype=float)
        al = np.asarray(rudder_angle, dtype=float)
        s = self._s(w)
        cols = [s * w * w, w, s * w * al]
        if self.alpha_squared:
            cols.append(s * al * al)
        return np.stack(cols, axis=-1), -al

    def residual(self, coef: np.ndarray, yaw_rate: Any, rudder_angle: Any) -> np.ndarray:
        """Residuals F = X θ − y of the reduced equation for coefficients θ.

        Parameters
        ----------
        coef : array_like, shape (n_coef,)
            Coefficients θ (a, b, c[, d]).
        yaw_rate : array_like, shape (n,)
            Yaw rates ω [rad/s].
        rudder_angle : array_like, shape (n,)
            Rudder angles α [rad].

        Returns
        -------
        numpy.ndarray, shape (n,)
            F [rad].
        """
        x, y = self.design(yaw_rate, rudder_angle)
        return x @ np.asarray(coef, dtype=float) - y

    def partials(self, coef: np.ndarray, w: np.ndarray, al: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
        """∂F/∂ω and ∂F/∂α.

        Parameters
        ----------
        coef : array_like, shape (n_coef,)
            Coefficients θ (a, b, c[, d]).
        w : numpy.ndarray
            Yaw rates ω [rad/s].
        al : numpy.ndarray
            Rudder angles α [rad].

        Returns
        -------
        dF_dw, dF_dal : numpy.ndarray
            ∂F/∂ω [s] and ∂F/∂α [-].
        """
        a, b, c = coef[0], coef[1], coef[2]
        d = coef[3] if self.alpha_squared else 0.0
        s = self._s(w)
        return s * (2 * a * w + c * al) + b, s * (c * w + 2 * d * al) + 1.0


REDUCED_FORMS: dict[str, ReducedForm] = {
    "paper": ReducedForm("paper", False, False, "eq. (4): a ω² + b ω + α(1 + c ω) = 0"),
    "exact": ReducedForm("exact", False, True,
                         "exact elimination on one branch: eq. (4) + d α² = 0"),
    "paper-odd": ReducedForm("paper-odd", True, False,
                             "eq. (4) made odd: a ω|ω| + b ω + α(1 + c|ω|) = 0 (both sides)"),
    "exact-odd": ReducedForm("exact-odd", True, True,
                             "exact form made odd: + d α² sign ω (both sides)"),
}


def get_form(form: "str | ReducedForm") -> ReducedForm:
    """A reduced form by name (or the form itself); unknown names list the valid ones.

    Parameters
    ----------
    form : str or ReducedForm
        Name in :data:`REDUCED_FORMS` ("paper", "exact", "paper-odd", ...) or a form.

    Returns
    -------
    ReducedForm
    """
    if isinstance(form, ReducedForm):
        return form
    return lookup_name("reduced form", REDUCED_FORMS, form)


# --------------------------------------------------------------------------------------------
# Fit result and prediction
# --------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SteadyTurnFit(FitResult):
    """Coefficients of the reduced steady-turn model fitted to steady turns.

    A :class:`~seahelm.identification.fit_result.FitResult` on ``names`` (the form's
    coefficient names) and ``values`` (= ``coef``); its intervals are Student-t with the
    points' degrees of freedom where the covariance is scaled by the residual variance, normal
    where it uses known noise (``absolute_sigma``).

    Attributes
    ----------
    coef : numpy.ndarray
        (a, b, c) or (a, b, c, d) — see :attr:`form`. Units a [s²/rad], b [s], c [s/rad],
        d [1/rad].
    covariance : numpy.ndarray
        Covariance of ``coef`` (NaN where not available: exact fit without known noise, brute
        force).
    stderr : numpy.ndarray
        Standard errors, sqrt of the covariance diagonal.
    residuals : numpy.ndarray
        Equation residuals F(ω_i, α_i) [rad] (unweighted).
    residual_rms : float
        Root mean square of ``residuals`` [rad].
    condition_number : float
        2-norm condition number of the weighted design matrix.
    condition_number_scaled : float
        The same after scaling each column to unit norm (independent of units).
    yaw_rate, rudder_angle, weights : numpy.ndarray
        The points used [rad/s], [rad] and their weights.
    method : str
        "lsq", "robust" or "brute".
    form : ReducedForm
    absolute_sigma : bool
        True if the covariance uses known measurement noise (effective-variance weights);
        False if it is scaled by the residual variance.
    elapsed : float
        Wall time of the fit [s].
    """

    coef: np.ndarray
    covariance: np.ndarray
    stderr: np.ndarray
    residuals: np.ndarray
    residual_rms: float
    condition_number: float
    condition_number_scaled: float
    yaw_rate: np.ndarray
    rudder_angle: np.ndarray
    weights: np.ndarray
    method: str
    form: ReducedForm
    absolute_sigma: bool
    elapsed: float = 0.0

    def __post_init__(self) -> None:
        # the FitResult view: names = the form's coefficient names, values = coef (plain
        # attributes, not fields: the dataclass's fields, repr and equality stay as they were)
        object.__setattr__(self, "names", self.form.names)
        object.__setattr__(self, "values", self.coef)

    @property
    def interval_dof(self) -> int | None:
        """None (normal intervals) for a covariance from known noise, else the points less
        the coefficients (at least 1)."""
        return None if self.absolute_sigma else max(self.points_used - self.form.n_coef, 1)

    @property
    def a(self) -> float:
        return float(self.coef[0])

    @property
    def b(self) -> float:
        return float(self.coef[1])

    @property
    def c(self) -> float:
        return float(self.coef[2])

    @property
    def d(self) -> float:
        return float(self.coef[3]) if self.form.alpha_squared else 0.0

    @property
    def points_used(self) -> int:
        return int(self.yaw_rate.size)

    def _pred_stderr(self, w: np.ndarray, al: np.ndarray, deriv: np.ndarray) -> np.ndarray:
        x, _ = self.form.design(w, al)
        g = -x / deriv[..., None]  # implicit function theorem: dz/dθ = −F_θ / F_z
        return np.sqrt(np.einsum("...i,ij,...j->...", g, self.covariance, g))

    def predict_yaw_rate(self, rudder_angle: Any) -> tuple[np.ndarray, np.ndarray]:
        """Steady yaw rate [rad/s] for rudder angles [rad], and its standard error.

        Solves F(ω, α) = 0 for ω on the branch of steady turns through (0, 0) (the root that
        behaves as −α/b for small α). NaN where the fitted model has no such steady turn (or, for an
        odd form, where the root's sign contradicts the branch).

        Parameters
        ----------
        rudder_angle : float or array_like
            Rudder angles α [rad].

        Returns
        -------
        yaw_rate, stderr : numpy.ndarray or float
            Steady yaw rate ω [rad/s] and its standard error [rad/s], shape of ``rudder_angle``.
        """
        al = np.atleast_1d(np.asarray(rudder_angle, dtype=float))
        a, b, c, d = self.a, self.b, self.c, self.d
        lin = -al / b if b != 0 else np.full_like(al, np.nan)
        s = np.sign(lin) if self.form.odd else np.ones_like(al)
        qa = s * a
        qb = b + s * c * al
        qc = al + s * d * al * al
        w = _branch_root(qa, qb, qc, np.sign(b))
        if self.form.odd:
            w = np.where((np.sign(w) == s) | (w == 0), w, np.nan)
        fw, _ = self.form.partials(self.coef, w, al)
        se = self._pred_stderr(w, al, fw)
        return _squeeze(w, rudder_angle), _squeeze(se, rudder_angle)

    def predict_rudder_angle(self, yaw_rate: Any) -> tuple[np.ndarray, np.ndarray]:
        """Rudder angle [rad] needed for a wanted steady yaw rate [rad/s], and its standard error.

        The paper's "recommendation" use: α = −(a ω² + b ω)/(1 + c ω) (root of the quadratic in
        α for the exact forms, on the branch through (0, 0)).

        Parameters
        ----------
        yaw_rate : float or array_like
            Wanted steady yaw rates ω [rad/s].

        Returns
        -------
        rudder_angle, stderr : numpy.ndarray or float
            Rudder angle α [rad] and its standard error [rad], shape of ``yaw_rate``.
        """
        w = np.atleast_1d(np.asarray(yaw_rate, dtype=float))
        a, b, c, d = self.a, self.b, self.c, self.d
        s = np.sign(w) if self.form.odd else np.ones_like(w)
        al = _branch_root(s * d, 1.0 + s * c * w, s * a * w * w + b * w, 1.0)
        _, fa = self.form.partials(self.coef, w, al)
        se = self._pred_stderr(w, al, fa)
        return _squeeze(al, yaw_rate), _squeeze(se, yaw_rate)

    def to_dict(self) -> dict[str, Any]:
        """Plain summary (JSON-ready with :func:`seahelm.cli._common.print_json`)."""
        out: dict[str, Any] = {n: float(v) for n, v in zip(self.form.names, self.coef)}
        out["stderr"] = {n: float(v) for n, v in zip(self.form.names, self.stderr)}
        out["covariance"] = self.covariance.tolist()
        out["residual_rms"] = self.residual_rms
        out["points_used"] = self.points_used
        out["condition_number"] = self.condition_number
        out["condition_number_scaled"] = self.condition_number_scaled
        out["method"] = self.method
        out["form"] = self.form.name
        out["absolute_sigma"] = self.absolute_sigma
        return out


def _squeeze(value: np.ndarray, like: Any) -> Any:
    return float(value[0]) if np.ndim(like) == 0 else value


def _branch_root(qa: Any, qb: Any, qc: Any, ref: Any) -> np.ndarray:
    """Root of qa x² + qb x + qc = 0 on the branch through x = 0 at qc = 0.

    ``ref`` is the sign of qb where qc = 0 (at the origin of the steady-turn curve); following
    that branch continuously gives x = (−qb + ref·√Δ)/(2 qa), evaluated without cancellation.
    NaN where Δ < 0 (past a fold: no steady turn on this branch).
    """
    qa, qb, qc, ref = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (qa, qb, qc, ref)))
    with np.errstate(invalid="ignore", divide="ignore"):
        disc = qb * qb - 4.0 * qa * qc
        sq = ref * np.sqrt(np.where(disc >= 0.0, disc, np.nan))
        plus = -qb + sq
        minus = -qb - sq
        root = np.where(np.abs(minus) >= np.abs(plus), 2.0 * qc / minus, plus / (2.0 * qa))
        root = np.where(qa == 0.0, -qc / qb, root)
        root = np.where(qc == 0.0, 0.0, root)
    return root


