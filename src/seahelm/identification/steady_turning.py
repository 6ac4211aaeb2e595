"""Steady turns of Voitkunsky's model and identification of the reduced steady-turn model.

Romanov & Chirkova reduce the static regime of Voitkunsky's model (eq. (1)-(3), see
:mod:`seahelm.vessels.voitkunsky`) to one equation in the two quantities that are easy to
measure, yaw rate ω and rudder angle α, eq. (4)::

    a ω² + b ω + α (1 + c ω) = 0

and fit a, b, c to n ≥ 3 steady turns (ω_i, α_i). This module provides

* :func:`steady_turns` — every real steady turn for a rudder angle, on both branches of β|β|,
  with the Jacobian eigenvalues and stability;
* :func:`reduced_coefficients` — a, b, c (and the α² coefficient d, see below) in closed form
  from the seven coefficients;
* :func:`fit_lsq` (exact weighted linear least squares with covariance, standard errors and
  condition number), :func:`fit_robust` (soft-L1 loss) and :func:`fit_brute_force` (the
  paper's eq. (5), with a squared criterion) — registry :data:`FIT_METHODS`;
* :func:`extract_steady_segments` — steady turns from a recorded time series;
* :class:`SteadyTurnFit` with prediction both ways (yaw rate for a rudder angle, rudder angle
  for a wanted yaw rate) and their standard errors from the covariance (delta method).

Notes
-----
**Elimination of β.** With normalised coefficients Q = q31/s31, R = r31/s31, q = q21/s21,
r = r21/s21, h = h2/s21, eq. (3) reads Qβ + Rω + α = 0 and qβ + rω + hβ|β| + α = 0. β|β| is
not polynomial, so the elimination is done on one branch, β|β| = σβ² with σ = sign β fixed.
Substituting β = −(Rω + α)/Q and dividing by Q(Q − q) gives, **exactly on that branch**::

    a ω² + b ω + α (1 + c ω) + d α² = 0,         i.e.   d (Rω + α)² + b ω + α = 0,

    a = σ h2 r31² / (q31 D),   b = (q31 r21 − q21 r31) / D,
    c = 2 σ h2 r31 s31 / (q31 D),   d = σ h2 s31² / (q31 D) = c² / (4a),
    D = q31 s21 − q21 s31  (needs q31 ≠ 0, D ≠ 0).

The paper's eq. (4) is this with the α² term dropped: it is exact only for h2 = 0 (where it
degenerates to the linear b ω + α = 0) and otherwise an approximation whose equation error is
d α². The identification can therefore fit either the paper's three-coefficient form
(``form="paper"``) or the exact conic with a free α² coefficient (``form="exact"``, four
coefficients, still linear). Because σ = sign β, one set (a, b, c, d) describes turns of one
sign of β only (for a conventional ship: turns to one side); a, c, d change sign on the other
branch and b does not. The ``*-odd`` forms use that: they replace σ by sign ω,
a ω|ω| + b ω + α (1 + c|ω|) [+ d α² sign ω] = 0, valid on both sides when the steady drift angle
has the sign of the yaw rate (true for the catalog Mariner set); their coefficients are those
of the σ = +1 branch.

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

import dataclasses
import math
import time as _time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from .._validate import check_positive
from ..errors import ParameterError
from ..vessels.voitkunsky import VoitkunskyParams

__all__ = [
    "SteadyTurn",
    "steady_turns",
    "stable_steady_turn",
    "ReducedCoefficients",
    "reduced_coefficients",
    "ReducedForm",
    "REDUCED_FORMS",
    "get_form",
    "SteadyTurnFit",
    "fit_lsq",
    "fit_robust",
    "fit_brute_force",
    "FIT_METHODS",
    "fit_steady_turns",
    "SteadySegments",
    "extract_steady_segments",
    "identify_from_time_series",
]


# --------------------------------------------------------------------------------------------
# Static regime of the full model
# --------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SteadyTurn:
    """One steady turn (equilibrium of eq. (1) at constant rudder angle).

    Attributes
    ----------
    rudder_angle, yaw_rate, drift_angle : float
        α [rad], ω [rad/s], β [rad].
    branch : int
        Sign of β (+1 or −1; 0 for β = 0), the branch of β|β| it lies on.
    eigenvalues : numpy.ndarray
        Eigenvalues [1/s] of the Jacobian of (ω, β) at the equilibrium.
    stable : bool
        All eigenvalues have negative real part.
    """

    rudder_angle: float
    yaw_rate: float
    drift_angle: float
    branch: int
    eigenvalues: np.ndarray
    stable: bool


def _coeffs(params: VoitkunskyParams) -> tuple[float, ...]:
    if not isinstance(params, VoitkunskyParams):
        raise ParameterError(f"expected VoitkunskyParams, got {type(params).__name__}")
    p = params
    return p.q21, p.r21, p.s21, p.h2, p.q31, p.r31, p.s31


def _jacobian(params: VoitkunskyParams, beta: float) -> np.ndarray:
    q21, r21, _, h2, q31, r31, _ = _coeffs(params)
    # d/dβ (β|β|) = 2|β|
    return np.array([[-r31, -q31], [-r21, -q21 - 2.0 * h2 * abs(beta)]])


def steady_turns(
    params: VoitkunskyParams,
    rudder_angle: float,
    *,
    yaw_moment: float = 0.0,
    sway_force: float = 0.0,
) -> list[SteadyTurn]:
    """All real steady turns of eq. (1) for a constant rudder angle, on both branches of β|β|.

    Parameters
    ----------
    params : VoitkunskyParams
    rudder_angle : float
        α [rad].
    yaw_moment, sway_force : float
        Constant disturbances in the model's units ([rad/s²], [rad/s]; see
        :mod:`seahelm.vessels.voitkunsky`).

    Returns
    -------
    list of SteadyTurn
        Sorted by yaw rate. Each β solves, on its branch σ = sign β,
        σ h2 r31 β² + (q21 r31 − r21 q31) β + r31 A2 − r21 A3 = 0 with A3 = s31 α − m_d,
        A2 = s21 α + f_d, and ω = −(q31 β + A3)/r31.

    Raises
    ------
    ParameterError
        Non-finite input, or r31 = 0 and q31 = 0 (no isolated equilibria).
    """
    for name, v, unit in (("rudder_angle", rudder_angle, "rad"), ("yaw_moment", yaw_moment,
                          "rad/s²"), ("sway_force", sway_force, "rad/s")):
        if not math.isfinite(float(v)):
            raise ParameterError(f"`{name}` must be finite [{unit}], got {v!r}")
    q21, r21, s21, h2, q31, r31, s31 = _coeffs(params)
    alpha = float(rudder_angle)
    a3 = s31 * alpha - float(yaw_moment)
    a2 = s21 * alpha + float(sway_force)
    betas: list[float] = []
    omegas: list[float] = []
    if r31 != 0.0:
        p_lin = q21 * r31 - r21 * q31
        const = r31 * a2 - r21 * a3
        for sigma in (1.0, -1.0):
            for beta in _quadratic_roots(sigma * h2 * r31, p_lin, const):
                if sigma * beta >= 0.0:
                    betas.append(beta)
        omegas = [-(q31 * b + a3) / r31 for b in betas]
    elif q31 != 0.0:
        beta = -a3 / q31
        if r21 == 0.0:
            raise ParameterError("r31 = 0 and r21 = 0: the yaw rate is undetermined")
        betas = [beta]
        omegas = [-(q21 * beta + h2 * beta * abs(beta) + a2) / r21]
    else:
        raise ParameterError("r31 = 0 and q31 = 0: the yaw equation has no isolated equilibrium")
    out: dict[tuple[float, float], SteadyTurn] = {}
    for beta, omega in zip(betas, omegas):
        key = (round(beta, 14), round(omega, 14))
        if key in out:
            continue
        ev = np.linalg.eigvals(_jacobian(params, beta))
        out[key] = SteadyTurn(alpha, float(omega), float(beta), int(np.sign(beta)), ev,
                              bool(np.all(ev.real < 0.0)))
    return sorted(out.values(), key=lambda s: s.yaw_rate)


def _quadratic_roots(a: float, b: float, c: float) -> list[float]:
    """Real roots of a x² + b x + c = 0 (numerically stable; linear when a = 0)."""
    if a == 0.0:
        return [] if b == 0.0 else [-c / b]
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return []
    sq = math.sqrt(disc)
    qq = -0.5 * (b + math.copysign(sq, b)) if b != 0.0 else -0.5 * sq
    if qq == 0.0:
        return [0.0]
    return sorted({qq / a, c / qq})


def stable_steady_turn(params: VoitkunskyParams, rudder_angle: float, **disturbances: float
                       ) -> SteadyTurn:
    """The unique stable steady turn for a rudder angle (ParameterError if none or several).

    Parameters
    ----------
    params : VoitkunskyParams
        Ship parameters.
    rudder_angle : float
        Rudder angle δ [rad].
    **disturbances : float
        Constant disturbances, as :func:`steady_turns`.

    Returns
    -------
    SteadyTurn
    """
    turns = [s for s in steady_turns(params, rudder_angle, **disturbances) if s.stable]
    if len(turns) != 1:
        raise ParameterError(
            f"expected one stable steady turn at rudder_angle = {rudder_angle!r} [rad], "
            f"found {len(turns)}"
        )
    return turns[0]


@dataclasses.dataclass(frozen=True)
class ReducedCoefficients:
    """Closed-form coefficients of the reduced steady-turn equation on one branch of β|β|.

    a ω² + b ω + α (1 + c ω) + d α² = 0 holds exactly for the steady turns with sign β = branch;
    the paper's eq. (4) drops d α². Units: a [s²/rad], b [s], c [s/rad], d [1/rad].
    """

    a: float
    b: float
    c: float
    d: float
    branch: int

    def residual(self, yaw_rate: Any, rudder_angle: Any, *, exact: bool = True) -> np.ndarray:
        """Left-hand side of the reduced equation (with the α² term if ``exact``).

        Parameters
        ----------
        yaw_rate : array_like
            Yaw rate ω [rad/s].
        rudder_angle : array_like
            Rudder angle α [rad].
        exact : bool, optional
            Include the d α² term (default True).

        Returns
        -------
        numpy.ndarray
            a ω² + b ω + α(1 + c ω) [+ d α²] [rad].
        """
        w = np.asarray(yaw_rate, dtype=float)
        al = np.asarray(rudder_angle, dtype=float)
        out = self.a * w**2 + self.b * w + al * (1.0 + self.c * w)
        return out + self.d * al**2 if exact else out

    def as_array(self, form: "str | ReducedForm" = "paper") -> np.ndarray:
        """Coefficients in the order of a fitting form ("paper": a, b, c; "exact": a, b, c, d).

        Parameters
        ----------
        form : str or ReducedForm, optional
            Fitting form (default "paper").

        Returns
        -------
        numpy.ndarray, shape (n_coef,)
        """
        f = get_form(form)
        return np.array([self.a, self.b, self.c, self.d][: f.n_coef])


def reduced_coefficients(params: VoitkunskyParams, branch: int = 1) -> ReducedCoefficients:
    """a, b, c (and d) of the reduced equation from the seven coefficients of eq. (1).

    Parameters
    ----------
    params : VoitkunskyParams
    branch : {+1, −1}
        σ = sign β of the steady turns described (β|β| = σβ² there).

    Raises
    ------
    ParameterError
        ``branch`` not ±1, q31 = 0, or q31 s21 − q21 s31 = 0 (β cannot be eliminated, or the
        rudder term vanishes after elimination).

    Notes
    -----
    a = σ h2 r31²/(q31 D), b = (q31 r21 − q21 r31)/D, c = 2σ h2 r31 s31/(q31 D),
    d = σ h2 s31²/(q31 D), D = q31 s21 − q21 s31. Derivation in the module docstring.
    """
    if branch not in (1, -1):
        raise ParameterError(f"`branch` must be +1 or -1 (sign of the drift angle), got {branch!r}")
    q21, r21, s21, h2, q31, r31, s31 = _coeffs(params)
    den = q31 * s21 - q21 * s31
    if q31 == 0.0:
        raise ParameterError("`q31` must be nonzero [1/s²] to eliminate the drift angle, got 0.0")
    if den == 0.0:
        raise ParameterError(
            "q31·s21 − q21·s31 = 0: the rudder angle drops out of the reduced equation"
        )
    sig = float(branch)
    qd = q31 * den
    return ReducedCoefficients(
        a=sig * h2 * r31**2 / qd,
        b=(q31 * r21 - q21 * r31) / den,
        c=2.0 * sig * h2 * r31 * s31 / qd,
        d=sig * h2 * s31**2 / qd,
        branch=int(branch),
    )


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
    if form not in REDUCED_FORMS:
        raise ValueError(f"unknown reduced form '{form}'; valid: {', '.join(REDUCED_FORMS)}")
    return REDUCED_FORMS[form]


# --------------------------------------------------------------------------------------------
# Fit result and prediction
# --------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SteadyTurnFit:
    """Coefficients of the reduced steady-turn model fitted to steady turns.

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


# --------------------------------------------------------------------------------------------
# Fitting
# --------------------------------------------------------------------------------------------
def _check_points(yaw_rate: Any, rudder_angle: Any, n_coef: int) -> tuple[np.ndarray, np.ndarray]:
    arrs = []
    for name, v, unit in (("yaw_rate", yaw_rate, "rad/s"), ("rudder_angle", rudder_angle, "rad")):
        arrs.append(_series(name, v, unit, what="point(s)"))
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
        Equation form, see :data:`REDUCED_FORMS` ("paper" = eq. (4)).
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
    w, al = _check_points(yaw_rate, rudder_angle, f.n_coef)
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
        Reduced model, a name of :data:`REDUCED_FORMS` or the form itself (default "paper",
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
    w, al = _check_points(yaw_rate, rudder_angle, f.n_coef)
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
    criterion: str = "squared",
    chunk: int = 200_000,
) -> SteadyTurnFit:
    """The paper's brute-force search, eq. (5), with a proper criterion — a baseline.

    Every point of a regular grid of ``n_grid`` values per coefficient inside ``bounds`` is
    evaluated and the one minimising Σ N_i² (``criterion="squared"``) or Σ|N_i|
    ("absolute") is returned. (The paper's plain Σ N_i has no minimum.) The accuracy is
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
        Reduced model, a name of :data:`REDUCED_FORMS` or the form itself (default "paper",
        eq. (4)).
    bounds : sequence of (float, float), optional
        (low, high) of each coefficient, in the units of the form's coefficients (default: from
        the data, see above).
    n_grid : int, optional
        Grid values per coefficient (>= 2, default 41).
    criterion : {"squared", "absolute"}, optional
        Σ N_i² or Σ|N_i| (default "squared").
    chunk : int, optional
        Grid points evaluated at once (memory bound; default 200 000).

    Returns
    -------
    SteadyTurnFit
    """
    t0 = _time.perf_counter()
    f = get_form(form)
    w, al = _check_points(yaw_rate, rudder_angle, f.n_coef)
    if criterion not in ("squared", "absolute"):
        raise ValueError(f"unknown criterion '{criterion}'; valid: squared, absolute")
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
        crit = np.sum(r * r, axis=1) if criterion == "squared" else np.sum(np.abs(r), axis=1)
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
    if method not in FIT_METHODS:
        raise ValueError(f"unknown fit method '{method}'; valid: {', '.join(FIT_METHODS)}")
    return FIT_METHODS[method](yaw_rate, rudder_angle, **kwargs)


# --------------------------------------------------------------------------------------------
# Steady segments of a time series
# --------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SteadySegments:
    """Steady turns found in a time series, one entry per segment.

    Attributes
    ----------
    start_time, end_time : numpy.ndarray
        Bounds [s] of the settled part of each constant-rudder segment.
    rudder_angle, yaw_rate : numpy.ndarray
        Means over the settled part [rad], [rad/s].
    yaw_rate_std : numpy.ndarray
        Sample standard deviation of the yaw rate over the settled part [rad/s].
    n_samples : numpy.ndarray
        Samples in each settled part.
    """

    start_time: np.ndarray
    end_time: np.ndarray
    rudder_angle: np.ndarray
    yaw_rate: np.ndarray
    yaw_rate_std: np.ndarray
    n_samples: np.ndarray

    def __len__(self) -> int:
        return int(self.yaw_rate.size)


def extract_steady_segments(
    time: Any,
    rudder_angle: Any,
    yaw_rate: Any,
    *,
    rudder_tolerance: float = math.radians(0.2),
    yaw_rate_tolerance: float = 3e-5,
    min_duration: float = 60.0,
    smoothing: float = 20.0,
) -> SteadySegments:
    """Windows where the rudder is constant and the yaw rate has settled.

    Parameters
    ----------
    time : array_like
        Sample times [s], strictly increasing.
    rudder_angle, yaw_rate : array_like
        α [rad] and ω [rad/s] at those times.
    rudder_tolerance : float
        A constant-rudder segment ends at the first sample whose rudder angle differs from the
        segment's first one by more than this [rad].
    yaw_rate_tolerance : float
        Settled means: from the start of the settled part to the end of the segment the yaw rate
        stays inside a band of half-width ``yaw_rate_tolerance`` [rad/s] (max − min ≤ 2·tol).
        The settled part is the longest such tail of the segment.
    min_duration : float
        Minimum duration [s] of the settled part; shorter ones are discarded.
    smoothing : float
        Length [s] of a centred moving average applied (within each segment) to the yaw rate
        before the band test, so that sensor noise does not hide a settled turn; the reported
        means use the raw samples. 0 = no smoothing.

    The defaults suit a large ship (settling over minutes) with a yaw-rate sensor noise of
    a few 1e-5 rad/s; scale them with the ship and the sensor.

    Returns
    -------
    SteadySegments

    Raises
    ------
    ParameterError
        Unequal lengths, fewer than 2 samples, non-finite values, time not increasing,
        non-positive thresholds.
    """
    t = _series("time", time, "s")
    al = _series("rudder_angle", rudder_angle, "rad")
    w = _series("yaw_rate", yaw_rate, "rad/s")
    if not (t.size == al.size == w.size):
        raise ParameterError(
            f"`time`, `rudder_angle`, `yaw_rate` must have equal length, got "
            f"{t.size}, {al.size}, {w.size}"
        )
    if t.size < 2:
        raise ParameterError(f"the time series needs at least 2 samples, got {t.size}")
    if np.any(np.diff(t) <= 0):
        raise ParameterError("`time` must be strictly increasing [s]")
    check_positive("rudder_tolerance", rudder_tolerance, "rad")
    check_positive("yaw_rate_tolerance", yaw_rate_tolerance, "rad/s")
    check_positive("min_duration", min_duration, "s")
    if not (math.isfinite(smoothing) and smoothing >= 0):
        raise ParameterError(f"`smoothing` must be >= 0 [s], got {smoothing!r}")
    half = int(round(0.5 * smoothing / float(np.median(np.diff(t)))))
    # constant-rudder segments
    bounds = []
    start = 0
    for k in range(1, t.size):
        if abs(al[k] - al[start]) > rudder_tolerance:
            bounds.append((start, k))
            start = k
    bounds.append((start, t.size))
    rows = []
    for i0, i1 in bounds:
        seg = _moving_average(w[i0:i1], half)
        # suffix band: running max/min from the end
        smax = np.maximum.accumulate(seg[::-1])[::-1]
        smin = np.minimum.accumulate(seg[::-1])[::-1]
        ok = np.flatnonzero(smax - smin <= 2.0 * yaw_rate_tolerance)
        if ok.size == 0:
            continue
        j0 = i0 + int(ok[0])
        if t[i1 - 1] - t[j0] < min_duration:
            continue
        part = slice(j0, i1)
        n = i1 - j0
        rows.append((t[j0], t[i1 - 1], float(np.mean(al[part])), float(np.mean(w[part])),
                     float(np.std(w[part], ddof=1)) if n > 1 else 0.0, n))
    cols = list(zip(*rows)) if rows else [()] * 6
    return SteadySegments(
        start_time=np.asarray(cols[0], dtype=float),
        end_time=np.asarray(cols[1], dtype=float),
        rudder_angle=np.asarray(cols[2], dtype=float),
        yaw_rate=np.asarray(cols[3], dtype=float),
        yaw_rate_std=np.asarray(cols[4], dtype=float),
        n_samples=np.asarray(cols[5], dtype=int),
    )


def _moving_average(x: np.ndarray, half: int) -> np.ndarray:
    """Centred moving average over 2·half + 1 samples, window shrunk at the ends."""
    if half <= 0 or x.size < 2:
        return x
    c = np.concatenate(([0.0], np.cumsum(x)))
    idx = np.arange(x.size)
    lo = np.maximum(idx - half, 0)
    hi = np.minimum(idx + half + 1, x.size)
    return (c[hi] - c[lo]) / (hi - lo)


def _series(name: str, value: Any, unit: str, *, what: str = "sample(s)") -> np.ndarray:
    """A finite 1-D float array, or ParameterError naming ``name``, ``unit`` and where."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"`{name}` must be numbers [{unit}], got {value!r}") from None
    if a.ndim != 1:
        raise ParameterError(f"`{name}` must be one-dimensional [{unit}], got shape {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        raise ParameterError(
            f"`{name}` must be finite [{unit}], got NaN/inf at {what} "
            f"{np.flatnonzero(bad)[:6].tolist()}"
        )
    return a


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
        Keyword arguments of :func:`extract_steady_segments`.
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
