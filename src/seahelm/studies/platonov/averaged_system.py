"""The averaged CPP system of Platonov & Platonova, eq. (13), and the check of the averaging
theorem by simulation (eq. (10) against eq. (13) for several ε).

The averaged system is d x̄/dτ = ε [f̄(x̄) + A(x̄) ς] with ς a point of the control set V
(:mod:`seahelm.studies.platonov.control_set`): numpy (:func:`cpp_drift_and_matrix`,
:func:`cpp_averaged_rhs`) and compiled with the engine's plug-in signature
(:func:`rhs_averaged`, :func:`rhs_averaged_printed`).

Erratum: eq. (13) attaches ς2 and ς3 to the wrong terms. :data:`CORRECT_ASSIGNMENT`
(``assignment="correct"``, default: φ̄² term ↔ ς3 = ⟨p² c2⟩, φ̄ e2 term ↔ ς2 = ⟨p c2⟩) versus
:data:`PRINTED_EQ13` (``assignment="printed"``), registry :data:`ASSIGNMENTS`. With the printed
one the averaging error does not shrink as ε → 0 (:func:`cpp_averaging_study`).
"""

from __future__ import annotations

import abc
import dataclasses
import math
import time
from collections.abc import Callable, Mapping, Sequence
from types import MappingProxyType
from typing import Any

import numpy as np
from numba import njit

from ..._validate import as_float_array, check_positive
from ...errors import ParameterError
from ...numerics.periodic import TWO_PI
from ...parameters import signal_indices
from ...registry import lookup
from ...vessels.cpp_ship import (
    CASE_COEFFICIENTS,
    INPUT_LABELS,
    STATE_LABELS,
    CPPShipParams,
    _emergence,
    rhs_waves,
)
from .control_set import cpp_betas, cpp_boundary_map

__all__ = [
    "cpp_drift_and_matrix",
    "cpp_averaged_rhs",
    "SIGMA_LABELS",
    "rhs_averaged",
    "rhs_averaged_printed",
    "Assignment",
    "CorrectAssignment",
    "PrintedEq13",
    "CORRECT_ASSIGNMENT",
    "PRINTED_EQ13",
    "ASSIGNMENTS",
    "get_assignment",
    "AveragingStudy",
    "STUDY_DIRECTION",
    "cpp_averaging_study",
]


def _params(params: CPPShipParams | None) -> CPPShipParams:
    if params is None:
        return CPPShipParams()
    if not isinstance(params, CPPShipParams):
        raise ParameterError(f"`params` must be CPPShipParams, got {type(params).__name__}")
    return params


def cpp_drift_and_matrix(
    x: Any, params: CPPShipParams | None = None, *,
    assignment: str | Assignment = "correct"
) -> tuple[np.ndarray, np.ndarray]:
    """f̄(x) (..., 2) and A(x) (..., 2, 3) of the averaged CPP system, eq. (13), without ε.

    Writes eq. (10) (case 1 coefficients: φ̄ ≥ 0, v̄ ≥ 0, the paper's case) in the form (1):
    f(τ, x) = (e1 k1² v̄² c1(τ) − χ P_e0 c10 v̄², N M_C0 c20 M⁰), φ(τ, u) = (c1 u, c2 u, c2 u²),
    A(x) = [[S1, 0, 0], [0, −N e2 k2² v̄², −N S2]] with
    S_i = a_i ω̄² + b_i k_i v̄ ω̄ + c_i k_i² v̄².
    ``assignment="printed"`` (:data:`PRINTED_EQ13`) swaps the last two columns of the second
    row, as the printed eq. (13) does (erratum).

    Parameters
    ----------
    x : array_like, shape (..., 2)
        States (v̄, ω̄): non-dimensional speed and shaft speed [-].
    params : CPPShipParams, optional
        Ship parameters (default: the paper's set).
    assignment : str or Assignment, optional
        Column assignment of the second row of A(x): a key of :data:`ASSIGNMENTS` or the
        object (default "correct").

    Returns
    -------
    fbar : numpy.ndarray, shape (..., 2)
        Averaged drift f̄(x).
    amat : numpy.ndarray, shape (..., 2, 3)
        Control matrix A(x).
    """
    assignment = get_assignment(assignment)
    p = _params(params)
    x = as_float_array("x", x)
    if x.shape[-1:] != (2,):
        raise ParameterError(f"`x` must end in 2 states (speed, shaft_speed), got shape {x.shape}")
    v, w = x[..., 0], x[..., 1]
    a1, b1, cc1, e1, a2, b2, cc2, e2 = CASE_COEFFICIENTS[0]
    k1, k2 = p.thrust_advance_ratio, p.torque_advance_ratio
    _, beta2, _ = cpp_betas(p.immersion, p.amplitude)
    chi = np.where(v >= 0, 1.0, -1.35) * p.resistance_coefficient
    s1 = a1 * w * w + b1 * k1 * v * w + cc1 * k1 * k1 * v * v
    s2 = a2 * w * w + b2 * k2 * v * w + cc2 * k2 * k2 * v * v
    n = p.inertia_ratio
    fbar = np.stack([
        e1 * k1 * k1 * v * v * beta2 - chi * p.initial_thrust * p.thrust_emergence_initial * v * v,
        np.full(v.shape, n * p.initial_torque * p.torque_emergence_initial * p.engine_torque),
    ], axis=-1)
    zero = np.zeros(v.shape)
    col_e2, col_s2 = assignment.columns(-n * e2 * k2 * k2 * v * v, -n * s2)
    amat = np.stack([np.stack([s1, zero, zero], -1), np.stack([zero, col_e2, col_s2], -1)], -2)
    return fbar, amat


def cpp_averaged_rhs(
    x: Any,
    sigma: Any,
    params: CPPShipParams | None = None,
    *,
    assignment: str | Assignment = "correct",
) -> np.ndarray:
    """Averaged CPP system, Platonov & Platonova, eq. (13): d x̄/dτ = ε [f̄(x̄) + A(x̄) ς].

    Parameters
    ----------
    x : array_like, shape (..., 2)
        (v̄, ω̄) [1].
    sigma : array_like, shape (..., 3)
        A point ς of V, e.g. :func:`cpp_boundary_map` of a unit z.
    params : CPPShipParams
        ε = 1/A is ``params.epsilon``; τ is the wave phase [rad].
    assignment : str or Assignment
        ``"correct"`` (:data:`CORRECT_ASSIGNMENT`): ς2 multiplies −N e2 (λ0/λ2max)² v̄², ς3
        multiplies −N S2. ``"printed"`` (:data:`PRINTED_EQ13`): the swapped assignment of the
        printed eq. (13) (erratum; does not converge to the original system as ε → 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        d x̄/dτ.
    """
    p = _params(params)
    sigma = as_float_array("sigma", sigma)
    if sigma.shape[-1:] != (3,):
        raise ParameterError(f"`sigma` must end in 3 components, got shape {sigma.shape}")
    fbar, amat = cpp_drift_and_matrix(x, p, assignment=assignment)
    return p.epsilon * (fbar + np.einsum("...ij,...j->...i", amat, sigma))


@njit(cache=True)
def _mean_c1(immersion, amplitude):  # pragma: no cover - compiled
    """⟨c1⟩ in closed form: ⟨min(α, 0.5)⟩ for α = a0 − a1 sin τ, then eq. (11)."""
    a0 = immersion / 2.4
    a1 = amplitude / 2.4
    if a1 == 0.0:
        ab = min(a0, 0.5)
    else:
        s0 = (a0 - 0.5) / a1
        if s0 >= 1.0:
            ab = 0.5
        elif s0 <= -1.0:
            ab = a0
        else:
            th = math.asin(s0)
            ab = (a0 * (math.pi - 2 * th) - 2 * a1 * math.cos(th)
                  + 0.5 * (math.pi + 2 * th)) / TWO_PI
    return 0.4 + 1.2 * ab


_X = signal_indices(STATE_LABELS)
_U = signal_indices(INPUT_LABELS)
#: The components of ς = (⟨c1 φ̄⟩, ⟨c2 φ̄⟩, ⟨c2 φ̄²⟩) ∈ V, the input of the averaged system (and of
#: a direction z in the same space).
SIGMA_LABELS: tuple[str, ...] = ("sigma1", "sigma2", "sigma3")
_SG = signal_indices(SIGMA_LABELS)


@njit(cache=True)
def _rhs_averaged_core(x, sig, p, swap, dx):  # pragma: no cover - compiled
    v = x[_X.speed]
    w = x[_X.shaft_speed]
    c = CASE_COEFFICIENTS
    k1 = p.thrust_advance_ratio
    k2 = p.torque_advance_ratio
    s1 = c[0, 0] * w * w + c[0, 1] * k1 * v * w + c[0, 2] * k1 * k1 * v * v
    s2 = c[0, 4] * w * w + c[0, 5] * k2 * v * w + c[0, 6] * k2 * k2 * v * v
    chi1 = p.resistance_coefficient
    chi = chi1 if v >= 0.0 else -1.35 * chi1
    phi0 = p.initial_pitch
    pe0 = phi0 * (c[0, 0] + c[0, 1] * k1 + c[0, 2] * k1 * k1) + c[0, 3] * k1 * k1
    mc0 = phi0 * (phi0 * (c[0, 4] + c[0, 5] * k2 + c[0, 6] * k2 * k2) + c[0, 7] * k2 * k2)
    e2term = c[0, 7] * k2 * k2 * v * v
    if swap:
        quad_part = e2term * sig[_SG.sigma3] + s2 * sig[_SG.sigma2]
    else:
        quad_part = e2term * sig[_SG.sigma2] + s2 * sig[_SG.sigma3]
    inv_a = 1.0 / p.wave_ratio
    dx[_X.speed] = inv_a * (c[0, 3] * k1 * k1 * v * v * _mean_c1(p.immersion, p.amplitude)
                            - chi * pe0 * p.thrust_emergence_initial * v * v
                            + s1 * sig[_SG.sigma1])
    dx[_X.shaft_speed] = inv_a * p.inertia_ratio * (
        mc0 * p.torque_emergence_initial * p.engine_torque - quad_part)


@njit(cache=True)
def rhs_averaged(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """Averaged CPP system, eq. (13) with the correct assignment, engine plug-in signature.

    ``u = (ς1, ς2, ς3)`` is a point of V (e.g. ς(z)); ``p`` a :class:`CPPShipParams` record;
    ``t`` (wave phase [rad]) and ``d`` are unused. Case 1 coefficients (φ̄ ≥ 0, v̄ ≥ 0).
    """
    _rhs_averaged_core(x, u, p, False, dx)


@njit(cache=True)
def rhs_averaged_printed(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """As :func:`rhs_averaged` with the printed (swapped) ς2/ς3 assignment of eq. (13)."""
    _rhs_averaged_core(x, u, p, True, dx)

# ---------------------------------------------------------------------------------------
# the ς2/ς3 assignment of eq. (13): corrected and printed, as objects
# ---------------------------------------------------------------------------------------
class Assignment(abc.ABC):
    """Which columns of A(x) ς2 and ς3 multiply in eq. (13) (an :data:`ASSIGNMENTS` entry)."""

    #: Registry name.
    name: str = ""
    #: The compiled averaged right-hand side with this assignment (engine plug-in signature).
    rhs: Callable[..., None]

    @abc.abstractmethod
    def columns(self, col_e2: np.ndarray, col_s2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The second row's (ς2, ς3) columns of A(x) from the two physical terms.

        Parameters
        ----------
        col_e2 : numpy.ndarray
            −N e2 (λ0/λ2max)² v̄² (multiplies φ̄ in eq. (10)).
        col_s2 : numpy.ndarray
            −N S2 (multiplies φ̄² in eq. (10)).

        Returns
        -------
        tuple of numpy.ndarray
            The ς2 and ς3 columns.
        """


class CorrectAssignment(Assignment):
    """ς2 = ⟨p c2⟩ multiplies the φ̄ term, ς3 = ⟨p² c2⟩ the φ̄² term (from eq. (10))."""

    name = "correct"
    rhs = staticmethod(rhs_averaged)

    def columns(self, col_e2: np.ndarray, col_s2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(col_e2, col_s2).

        Parameters
        ----------
        col_e2 : numpy.ndarray
            The φ̄ term.
        col_s2 : numpy.ndarray
            The φ̄² term.

        Returns
        -------
        tuple of numpy.ndarray
            The ς2 and ς3 columns.
        """
        return col_e2, col_s2


class PrintedEq13(Assignment):
    """Eq. (13) as printed: ς2 and ς3 swapped (erratum; the averaging error does not shrink
    as ε → 0)."""

    name = "printed"
    rhs = staticmethod(rhs_averaged_printed)

    def columns(self, col_e2: np.ndarray, col_s2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(col_s2, col_e2).

        Parameters
        ----------
        col_e2 : numpy.ndarray
            The φ̄ term.
        col_s2 : numpy.ndarray
            The φ̄² term.

        Returns
        -------
        tuple of numpy.ndarray
            The ς2 and ς3 columns (swapped).
        """
        return col_s2, col_e2


#: The correct assignment (``"correct"``, the default).
CORRECT_ASSIGNMENT: Assignment = CorrectAssignment()
#: Eq. (13) as printed (``"printed"``).
PRINTED_EQ13: Assignment = PrintedEq13()
#: Readings of eq. (13), by name.
ASSIGNMENTS: Mapping[str, Assignment] = MappingProxyType(
    {v.name: v for v in (CORRECT_ASSIGNMENT, PRINTED_EQ13)})


def get_assignment(assignment: str | Assignment) -> Assignment:
    """A reading of eq. (13) by name (a key of :data:`ASSIGNMENTS`) or the object itself.

    Parameters
    ----------
    assignment : str or Assignment
        ``"correct"``, ``"printed"`` or an :class:`Assignment`.

    Returns
    -------
    Assignment

    Raises
    ------
    ParameterError
        If ``assignment`` is an unknown name (the message lists the valid ones).
    """
    return lookup("`assignment`", ASSIGNMENTS, assignment, Assignment, error=ParameterError)


# ---------------------------------------------------------------------------------------
# simulation check of the averaging theorem
# ---------------------------------------------------------------------------------------
@njit(cache=True)
def _pitch_clipped(c1, c2, z1, z2, z3):  # pragma: no cover - compiled
    g = c1 * z1 + c2 * z2
    if c2 * z3 < 0.0:
        u = -g / (2.0 * c2 * z3)
        return min(1.0, max(-1.0, u))
    return 1.0 if g >= 0.0 else -1.0


@njit(cache=True)
def _original_rhs(t, x, p, z, dx):  # pragma: no cover - compiled
    """Eq. (10) under the clipped maximiser φ̄ = p(t, z); ``p`` a CPPShipParams record."""
    c1, c2 = _emergence(t, p.immersion, p.amplitude)
    u = np.empty(1)
    u[_U.pitch_ratio] = _pitch_clipped(c1, c2, z[_SG.sigma1], z[_SG.sigma2], z[_SG.sigma3])
    rhs_waves(t, x, u, np.empty(0), p, dx)


_EMPTY = np.empty(0)


@dataclasses.dataclass(frozen=True)
class AveragingStudy:
    """Original (eq. (10)) against averaged (eq. (13)) simulations for several ε."""

    epsilons: np.ndarray
    errors: np.ndarray  #: max over t ∈ [0, L/ε] of |x − x̄|_∞
    order: float  #: fitted slope of log(error) against log(ε)
    nfev_original: np.ndarray
    nfev_averaged: np.ndarray
    time_original: np.ndarray  #: wall time [s]
    time_averaged: np.ndarray
    sigma: np.ndarray
    direction: np.ndarray
    horizon: float
    assignment: str

    def summary(self) -> dict[str, Any]:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v)
                for k, v in dataclasses.asdict(self).items()}


#: Default control direction of the study: p(τ, z) ∈ [0.6, 1], clipped on part of each period.
STUDY_DIRECTION = np.array([7.5, -5.3, -1.0]) / math.sqrt(7.5**2 + 5.3**2 + 1.0)


def cpp_averaging_study(
    epsilons: Sequence[float] = (0.2, 0.1, 0.05, 0.02, 0.01),
    *,
    params: CPPShipParams | None = None,
    direction: Any = None,
    horizon: float = 2.0,
    x0: Sequence[float] = (0.8, 0.9),
    assignment: str | Assignment = "correct",
    rtol: float = 1e-9,
    atol: float = 1e-11,
    n_eval: int = 4001,
    method: str = "DOP853",
) -> AveragingStudy:
    """Simulate eq. (10) and eq. (13) under the same control z and measure the gap.

    The original system runs over the wave phase t ∈ [0, L/ε] with φ̄(t) = p(t, z) (clipped
    maximiser); the averaged one uses the constant ς(z). Both are integrated with
    :func:`scipy.integrate.solve_ivp` at the same tolerances. The averaging theorem
    (Platonov & Platonova, Theorem of section 1) gives error ≤ C ε.

    Parameters
    ----------
    epsilons : sequence of float
        Small parameters ε = 1/A, each > 0.
    params : CPPShipParams
        Ship (its ``wave_ratio`` is replaced by 1/ε).
    direction : array_like, shape (3,)
        z (normalised); default :data:`STUDY_DIRECTION`, which keeps φ̄ ∈ [0.6, 1] (case 1).
    horizon : float
        L, in slow time ε t.
    x0 : (v̄0, ω̄0)
        Initial non-dimensional speed and shaft speed [-].
    assignment : str or Assignment
        Of eq. (13), see :func:`cpp_averaged_rhs` (a key of :data:`ASSIGNMENTS` or the object).
    rtol, atol : float, optional
        Relative and absolute tolerances of :func:`scipy.integrate.solve_ivp`
        (default 1e-9, 1e-11).
    n_eval : int, optional
        Number of comparison points on the slow time [0, L] (default 4001).
    method : str, optional
        :func:`scipy.integrate.solve_ivp` method (default "DOP853").

    Returns
    -------
    AveragingStudy
        Errors, fitted order in ε, function evaluations and timings per ε.
    """
    from scipy.integrate import solve_ivp

    eps = as_float_array("epsilons", epsilons).ravel()
    check_positive("epsilons", eps, "1")
    check_positive("horizon", horizon, "1")
    assignment = get_assignment(assignment)
    base = _params(params)
    z = STUDY_DIRECTION if direction is None else as_float_array("direction", direction)
    if z.shape != (3,) or not np.linalg.norm(z) > 0:
        raise ParameterError(f"`direction` must be a nonzero 3-vector, got {z!r}")
    z = z / np.linalg.norm(z)
    x0 = as_float_array("x0", x0)
    sigma = cpp_boundary_map(z, base.immersion, base.amplitude)
    s_eval = np.linspace(0.0, horizon, int(n_eval))

    errors, nfo, nfa, to, ta = [], [], [], [], []
    for e in eps:
        p = base.replace(wave_ratio=1.0 / float(e))
        prec = p.to_record()

        def f_orig(t: float, x: np.ndarray, prec: Any = prec) -> np.ndarray:
            dx = np.empty(2)
            _original_rhs(t, x, prec, z, dx)
            return dx

        avg = assignment.rhs

        def f_avg(t: float, x: np.ndarray, prec: Any = prec) -> np.ndarray:
            dx = np.empty(2)
            avg(t, x, sigma, _EMPTY, prec, dx)
            return dx

        t_end = horizon / float(e)
        f_orig(0.0, x0)  # compile outside the timing
        f_avg(0.0, x0)
        t0 = time.perf_counter()
        so = solve_ivp(f_orig, (0.0, t_end), x0, method=method, rtol=rtol, atol=atol,
                       t_eval=s_eval / float(e))
        t1 = time.perf_counter()
        sa = solve_ivp(f_avg, (0.0, t_end), x0, method=method, rtol=rtol, atol=atol,
                       t_eval=s_eval / float(e))
        t2 = time.perf_counter()
        if not (so.success and sa.success):
            raise ParameterError(
                f"integration failed at epsilon={e!r}: {so.message} / {sa.message}"
            )
        errors.append(float(np.max(np.abs(so.y - sa.y))))
        nfo.append(int(so.nfev))
        nfa.append(int(sa.nfev))
        to.append(t1 - t0)
        ta.append(t2 - t1)
    errs = np.array(errors)
    order = float(np.polyfit(np.log(eps), np.log(errs), 1)[0]) if eps.size > 1 else math.nan
    return AveragingStudy(
        epsilons=eps, errors=errs, order=order, nfev_original=np.array(nfo),
        nfev_averaged=np.array(nfa), time_original=np.array(to), time_averaged=np.array(ta),
        sigma=sigma, direction=z, horizon=float(horizon), assignment=assignment.name,
    )
