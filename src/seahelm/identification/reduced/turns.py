"""Steady turns of Voitkunsky's model and the reduced steady-turn coefficients, in closed form.

Romanov & Chirkova reduce the static regime of Voitkunsky's model (eq. (1)-(3), see
:mod:`seahelm.vessels.voitkunsky`) to one equation in the two quantities that are easy to
measure, yaw rate ω and rudder angle α, eq. (4)::

    a ω² + b ω + α (1 + c ω) = 0

This module gives the exact steady turns of the full model and the reduced coefficients:

* :func:`voitkunsky_turns` — every real steady turn for a rudder angle, on both branches of β|β|,
  with the Jacobian eigenvalues and stability; :func:`stable_steady_turn` — the stable one;
* :func:`reduced_coefficients` — a, b, c (and the α² coefficient d, see below) in closed form
  from the seven coefficients.

The reduced forms are in :mod:`seahelm.identification.reduced.forms`, the fits in
:mod:`seahelm.identification.reduced.fitting`, the steady segments of a log in
:mod:`seahelm.identification.reduced.segments`.

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

References
----------
Romanov, A. V., Chirkova, M. M. Transforming the mathematical model of ship manoeuvrability to
minimise the time to estimate its coefficients (in Russian), VGAVT. Eq. (1)-(5).
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ...errors import ParameterError, deprecated_names
from ...vessels.voitkunsky import VoitkunskyParams
from .forms import get_form

if TYPE_CHECKING:
    from .forms import ReducedForm

__all__ = [
    "SteadyTurn",
    "voitkunsky_turns",
    "stable_steady_turn",
    "ReducedCoefficients",
    "reduced_coefficients",
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


def voitkunsky_turns(
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
        Constant disturbances, as :func:`voitkunsky_turns`.

    Returns
    -------
    SteadyTurn
    """
    turns = [s for s in voitkunsky_turns(params, rudder_angle, **disturbances) if s.stable]
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




#: Old names (issue 47: ``steady_turns`` was also
#: :func:`seahelm.analysis.equilibria.batch_steady_turn.
#: steady_turns`, the batched equilibria of any model).
__getattr__ = deprecated_names(__name__, {"steady_turns": (
    __name__, "voitkunsky_turns", "seahelm.identification.reduced.turns.voitkunsky_turns")})
