"""Full averaging of control-affine periodic systems and the admissible control set.

General part (Platonov & Platonova, eq. (1)-(2)): for

    ẋ = ε [f(t, x) + A(x) φ(t, u)],   u ∈ U compact,  f, φ 2π-periodic in t,

the fully averaged system is dx̄/dt = ε [f̄(x̄) + A(x̄) ς(z)] with f̄ = ⟨f⟩ (⟨·⟩ the mean over
one period), a new control z on the unit sphere and ς(z) = ⟨φ(t, y(t, z))⟩, where the
Hamiltonian maximiser y(t, z) maximises ⟨φ(t, u), z⟩ over u ∈ U. ς(z) lies on the boundary of
the averaged control set V = {⟨φ(t, u(t))⟩ : u(t) ∈ U}, whose support function is
h_V(z) = ⟨max_{u∈U} ⟨φ(t, u), z⟩⟩ = ⟨ς(z), z⟩.

CPP part (Platonov & Platonova, eq. (10)-(24)): φ(τ, u) = (c1 u, c2 u, c2 u²) with the
emergence factors c1(τ), c2(τ) of :mod:`seahelm.vessels.cpp_ship`; ς(z) of eq. (14), the
maximiser of eq. (15)-(16), the flat approximation Y of eq. (24), the averaged system eq. (13).

Errata (see the seahelm paper guide) and where they are handled:

* eq. (15)-(16): the interior maximiser is **clipped to U = [-1, 1]** (the paper omits it, and
  unclipped ς(z) is unbounded): :func:`cpp_maximiser` ``variant="clipped"`` (default) versus
  ``variant="printed"``;
* eq. (13): the paper attaches ς2 and ς3 to the wrong terms; :func:`cpp_averaged_rhs`
  ``assignment="correct"`` (default: φ̄² term ↔ ς3 = ⟨p² c2⟩, φ̄ e2 term ↔ ς2 = ⟨p c2⟩)
  versus ``assignment="printed"``;
* eq. (19), (21) and the ratio "z1/z2" are misprinted; ς(z) is derived from eq. (14)
  directly;
* eq. (24) is inconsistent (its segment does not meet the arc's ends): Y is the convex hull of
  the arc (β1 t, β2 t, β3 t²), t ∈ [-1, 1] (``variant="hull"``); the printed set (arc plus
  segment y1 = y2 ∈ [-1, 1], y3 = β3, hulled) is ``variant="printed"``.

The averaged system is also available as compiled right-hand sides with the engine's plug-in
signature, :func:`rhs_averaged` (``u`` = ς ∈ V) and :func:`rhs_averaged_printed`.

Period means use Gauss–Legendre quadrature on the pieces between the known kinks; for the CPP
case the kinks of the maximiser (sign switches and clipping onsets) are found in closed form
too, so every piece is analytic and the quadrature converges exponentially.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Callable, Sequence
from typing import Any, Literal

import numpy as np
from numba import njit

from .._validate import as_float_array, check_positive, check_range
from ..errors import ParameterError
from ..numerics.periodic import TWO_PI, nodes_on_breaks, period_breaks, period_mean
from ..parameters import signal_indices
from ..vessels.cpp_ship import (
    CASE_COEFFICIENTS,
    INPUT_LABELS,
    STATE_LABELS,
    CPPShipParams,
    _emergence,
    emergence_factors,
    emergence_kinks,
    rhs_waves,
)

__all__ = [
    "TWO_PI",
    "period_mean",
    "averaged_drift",
    "maximise_polynomial",
    "PolynomialControlSet",
    "support_function",
    "boundary_map",
    "cpp_control_set",
    "cpp_maximiser",
    "cpp_boundary_map",
    "cpp_support_function",
    "cpp_betas",
    "sphere_grid",
    "flat_support_function",
    "hausdorff_from_support",
    "CPPControlSetResult",
    "cpp_admissible_set",
    "cpp_drift_and_matrix",
    "cpp_averaged_rhs",
    "rhs_averaged",
    "rhs_averaged_printed",
    "AveragingStudy",
    "STUDY_DIRECTION",
    "cpp_averaging_study",
]

MaximiserVariant = Literal["clipped", "printed"]
Assignment = Literal["correct", "printed"]
FlatVariant = Literal["hull", "printed"]

_MAXIMISER_VARIANTS = ("clipped", "printed")
_ASSIGNMENTS = ("correct", "printed")
_FLAT_VARIANTS = ("hull", "printed")


def _check_choice(name: str, value: str, valid: Sequence[str]) -> None:
    if value not in valid:
        raise ParameterError(
            f"`{name}` must be one of {', '.join(map(repr, valid))}, got {value!r}"
        )


def averaged_drift(
    f: Callable[[float, np.ndarray], Any],
    x: Any,
    *,
    kinks: Any = (),
    nodes: int = 32,
    pieces: int = 2,
) -> np.ndarray:
    """Averaged drift f̄(x) = ⟨f(t, x)⟩, Platonov & Platonova, eq. (2).

    Parameters
    ----------
    f : callable
        ``f(t, x)`` for a scalar time ``t`` [rad] and states ``x`` of shape (..., n), returning
        (..., n); 2π-periodic in ``t``.
    x : array_like, shape (..., n)
        States.
    kinks, nodes, pieces : optional
        Kinks of ``f`` in t [rad], Gauss–Legendre nodes per piece (default 32) and equal
        pieces per period (default 2), as :func:`period_mean`.

    Returns
    -------
    numpy.ndarray, shape (..., n)
        f̄(x).
    """
    x = as_float_array("x", x)
    t, w = nodes_on_breaks(period_breaks(kinks, int(pieces)), int(nodes))
    acc = None
    for tj, wj in zip(t, w):
        val = wj * np.asarray(f(float(tj), x), dtype=float)
        acc = val if acc is None else acc + val
    return acc


# ---------------------------------------------------------------------------------------
# maximiser of a polynomial in a scalar u over an interval
# ---------------------------------------------------------------------------------------
def _polyval(coeffs: np.ndarray, u: np.ndarray) -> np.ndarray:
    out = np.zeros(np.broadcast_shapes(coeffs.shape[:-1], u.shape))
    for k in range(coeffs.shape[-1] - 1, -1, -1):
        out = out * u + coeffs[..., k]
    return out


def maximise_polynomial(
    coeffs: Any, low: float = -1.0, high: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """Maximise q(u) = Σ_k q_k u^k over u ∈ [low, high], vectorised over leading axes.

    Candidates are the two ends and the real stationary points inside the interval: in
    closed form for degree ≤ 3, through batched companion-matrix eigenvalues above. The
    maximiser therefore never leaves [low, high] (this is the clipping that Platonov &
    Platonova's eq. (15)-(16) omit). Ties go to the first candidate found (``high`` first).

    Parameters
    ----------
    coeffs : array_like, shape (..., K+1)
        Ascending coefficients q_0 … q_K.
    low, high : float
        The interval U, ``low <= high``.

    Returns
    -------
    argmax, maximum : numpy.ndarray, shape (...)
    """
    q = as_float_array("coeffs", coeffs)
    if q.ndim == 0 or q.shape[-1] < 1:
        raise ParameterError(f"`coeffs` must have a last axis of coefficients, got shape {q.shape}")
    check_range("low", low, -math.inf, high)
    batch = q.shape[:-1]
    deg = q.shape[-1] - 1
    cands = [np.full(batch, float(high)), np.full(batch, float(low))]
    if deg >= 1:
        d = q[..., 1:] * np.arange(1, deg + 1)  # derivative, ascending
        for r in _real_roots(d):
            inside = np.isfinite(r) & (r > low) & (r < high)
            cands.append(np.where(inside, r, float(high)))
    u = np.stack(cands, axis=-1)
    vals = _polyval(q[..., None, :], u)
    i = np.argmax(vals, axis=-1)
    best_u = np.take_along_axis(u, i[..., None], axis=-1)[..., 0]
    best = np.take_along_axis(vals, i[..., None], axis=-1)[..., 0]
    return best_u, best


def _real_roots(d: np.ndarray) -> list[np.ndarray]:
    """Real roots (NaN where absent) of polynomials with ascending coefficients ``d``."""
    n = d.shape[-1] - 1  # degree
    with np.errstate(divide="ignore", invalid="ignore"):
        if n == 0:
            return []
        if n == 1:
            return [np.where(d[..., 1] != 0, -d[..., 0] / d[..., 1], np.nan)]
        if n == 2:
            c, b, a = d[..., 0], d[..., 1], d[..., 2]
            disc = b * b - 4 * a * c
            sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
            # numerically stable pair; a == 0 falls back to the linear root
            qq = -0.5 * (b + np.copysign(sq, b))
            r1 = np.where(a != 0, qq / a, np.where(b != 0, -c / b, np.nan))
            r2 = np.where(a != 0, np.where(qq != 0, c / qq, 0.0), np.nan)
            return [r1, r2]
    # general degree: companion matrices, grouped by effective degree
    out = [np.full(d.shape[:-1], np.nan) for _ in range(n)]
    flat = d.reshape(-1, n + 1)
    outs = [o.reshape(-1) for o in out]
    scale = np.max(np.abs(flat), axis=-1)
    eff = np.full(flat.shape[0], 0)
    for k in range(n, 0, -1):
        mask = (eff == 0) & (np.abs(flat[:, k]) > 1e-300) & (np.abs(flat[:, k]) > 1e-14 * scale)
        eff[mask] = k
    for k in range(1, n + 1):
        rows = np.nonzero(eff == k)[0]
        if rows.size == 0:
            continue
        c = flat[rows, : k + 1] / flat[rows, k : k + 1]
        comp = np.zeros((rows.size, k, k))
        comp[:, 1:, :-1] = np.eye(k - 1)
        comp[:, :, -1] = -c[:, :k]
        ev = np.linalg.eigvals(comp)
        real = np.abs(ev.imag) <= 1e-9 * (1 + np.abs(ev.real))
        for j in range(k):
            outs[j][rows] = np.where(real[:, j], ev[:, j].real, np.nan)
    return [o.reshape(d.shape[:-1]) for o in outs]


# ---------------------------------------------------------------------------------------
# general averaged control set
# ---------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class PolynomialControlSet:
    """Control term φ(t, u) = Σ_k Φ_k(t) u^k with scalar u ∈ [low, high], 2π-periodic in t.

    Attributes
    ----------
    coefficients : callable
        ``coefficients(t)`` for a 1-D array ``t`` [rad] returns Φ of shape (m, K+1, len(t)):
        component, power of u, time.
    low, high : float
        The interval U.
    kinks : tuple of float
        Known non-smooth points of Φ in [0, 2π) [rad].
    """

    coefficients: Callable[[np.ndarray], np.ndarray]
    low: float = -1.0
    high: float = 1.0
    kinks: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        check_range("low", self.low, -math.inf, self.high)


def _chunks(n: int, size: int):
    for i in range(0, n, size):
        yield slice(i, min(n, i + size))


def _generic_eval(
    cs: PolynomialControlSet, z: Any, nodes: int, pieces: int
) -> tuple[np.ndarray, np.ndarray]:
    z = as_float_array("z", z)
    t, w = nodes_on_breaks(period_breaks(cs.kinks, int(pieces)), int(nodes))
    phi = np.asarray(cs.coefficients(t), dtype=float)  # (m, K+1, nt)
    m = phi.shape[0]
    if z.shape[-1:] != (m,):
        raise ParameterError(f"`z` must end in {m} components, got shape {z.shape}")
    zf = z.reshape(-1, m)
    h = np.empty(zf.shape[0])
    sig = np.empty((zf.shape[0], m))
    for sl in _chunks(zf.shape[0], 1024):
        q = np.einsum("bm,mkt->btk", zf[sl], phi)
        u, val = maximise_polynomial(q, cs.low, cs.high)  # (b, nt)
        powers = u[..., None] ** np.arange(phi.shape[1])  # (b, nt, K+1)
        h[sl] = val @ w
        sig[sl] = np.einsum("btk,mkt,t->bm", powers, phi, w)
    return h.reshape(z.shape[:-1]), sig.reshape(z.shape)


def support_function(
    control_set: PolynomialControlSet, z: Any, *, nodes: int = 16, pieces: int = 16
) -> np.ndarray:
    """h_V(z) = ⟨max_{u∈U} ⟨φ(t, u), z⟩⟩, Platonov & Platonova, eq. (2).

    ``z`` has shape (..., m) (need not be unit: h_V is positively homogeneous). The maximiser's
    own kinks are unknown in general, so the composite quadrature converges algebraically;
    use ``pieces`` to refine. See :func:`cpp_support_function` for the exact CPP case.

    Parameters
    ----------
    control_set : PolynomialControlSet
        The control set φ(t, U) (coefficients periodic in t, u in [u_min, u_max]).
    z : array_like, shape (..., m)
        Directions.
    nodes : int, optional
        Gauss–Legendre nodes per piece (default 16).
    pieces : int, optional
        Equal pieces per period for the composite quadrature, besides the known kinks
        (default 16).

    Returns
    -------
    numpy.ndarray, shape (...)
        h_V(z).
    """
    return _generic_eval(control_set, z, nodes, pieces)[0]


def boundary_map(
    control_set: PolynomialControlSet, z: Any, *, nodes: int = 16, pieces: int = 16
) -> np.ndarray:
    """ς(z) = ⟨φ(t, y(t, z))⟩ with the Hamiltonian maximiser y, Platonov & Platonova, eq. (2).

    Returns an array of shape (..., m); ⟨ς(z), z⟩ = h_V(z).

    Parameters
    ----------
    control_set : PolynomialControlSet
        The control set φ(t, U) (coefficients periodic in t, u in [u_min, u_max]).
    z : array_like, shape (..., m)
        Directions.
    nodes : int, optional
        Gauss–Legendre nodes per piece (default 16).
    pieces : int, optional
        Equal pieces per period for the composite quadrature, besides the known kinks
        (default 16).
    """
    return _generic_eval(control_set, z, nodes, pieces)[1]


# ---------------------------------------------------------------------------------------
# CPP case
# ---------------------------------------------------------------------------------------
def _check_waves(immersion: float, amplitude: float) -> None:
    check_range("immersion", immersion, 0.0, math.inf, "R")
    check_range("amplitude", amplitude, 0.0, math.inf, "R")
    if 0.5 + (immersion - amplitude) / 2.4 <= 0.0:
        raise ParameterError(
            "the torque emergence factor c2(τ) = 0.5 + α(τ) reaches 0 "
            "(Platonov & Platonova, eq. (11)): need immersion − amplitude > −1.2 [R], got "
            f"immersion={immersion!r}, amplitude={amplitude!r}"
        )


def cpp_control_set(immersion: float = 1.2, amplitude: float = 0.96) -> PolynomialControlSet:
    """φ(τ, u) = (c1 u, c2 u, c2 u²), u ∈ [-1, 1], Platonov & Platonova, eq. (10), (14).

    ``immersion`` = h0/R and ``amplitude`` = eψ0/R in propeller radii (eq. (12)).

    Parameters
    ----------
    immersion : float, optional
        Propeller shaft immersion h0/R [R] (default 1.2).
    amplitude : float, optional
        Wave amplitude at the propeller eψ0/R [R] (default 0.96).

    Returns
    -------
    PolynomialControlSet
        The set with the emergence kinks of :func:`~seahelm.vessels.cpp_ship.emergence_kinks`.
    """
    _check_waves(immersion, amplitude)

    def coefficients(t: np.ndarray) -> np.ndarray:
        c1, c2 = emergence_factors(t, immersion, amplitude)
        zero = np.zeros_like(c1)
        return np.array([[zero, c1, zero], [zero, c2, zero], [zero, zero, c2]])

    return PolynomialControlSet(coefficients, -1.0, 1.0,
                                tuple(emergence_kinks(immersion, amplitude)))


def cpp_maximiser(
    c1: Any, c2: Any, z: Any, variant: MaximiserVariant = "clipped"
) -> np.ndarray:
    """Maximiser p(τ, z) of H = c1 u z1 + c2 u z2 + c2 u² z3 over u ∈ [-1, 1], eq. (15)-(16).

    Parameters
    ----------
    c1, c2 : array_like
        Emergence factors at the times of interest (broadcast against ``z[..., 0]``).
    z : array_like, shape (..., 3)
    variant : {"clipped", "printed"}
        ``"clipped"`` (correct): for c2 z3 < 0 the interior stationary point
        −(c1 z1 + c2 z2)/(2 c2 z3) clipped to [-1, 1]; otherwise ±1 by the sign of
        c1 z1 + c2 z2 (ties to +1). ``"printed"``: Platonov & Platonova's eq. (15) as printed —
        unclipped (erratum: leaves U for about 40 % of the directions with z3 < 0) and
        ``sign`` giving 0 on ties.
    """
    _check_choice("variant", variant, _MAXIMISER_VARIANTS)
    z = as_float_array("z", z)
    if z.shape[-1:] != (3,):
        raise ParameterError(f"`z` must end in 3 components, got shape {z.shape}")
    c1 = np.asarray(c1, dtype=float)
    c2 = np.asarray(c2, dtype=float)
    z1, z2, z3 = z[..., 0], z[..., 1], z[..., 2]
    g = c1 * z1 + c2 * z2
    concave = c2 * z3 < 0
    with np.errstate(divide="ignore", invalid="ignore"):
        interior = np.where(concave, -g / (2.0 * np.where(concave, c2 * z3, 1.0)), 0.0)
    if variant == "printed":
        return np.where(concave, interior, np.sign(g))
    return np.where(concave, np.clip(interior, -1.0, 1.0), np.where(g >= 0, 1.0, -1.0))


def _alpha_root(w1: np.ndarray, w2: np.ndarray) -> np.ndarray:
    """ᾱ with c1(ᾱ) w1 + c2(ᾱ) w2 = 0 on the branch c1 = 0.4 + 1.2ᾱ, c2 = 0.5 + ᾱ."""
    den = 1.2 * w1 + w2
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den != 0, -(0.4 * w1 + 0.5 * w2) / np.where(den != 0, den, 1.0), np.nan)


def _cpp_breaks(z: np.ndarray, immersion: float, amplitude: float) -> np.ndarray:
    """Sorted breakpoints (..., 10) in [0, 2π]: kinks of c1, c2 and of the maximiser."""
    a0, a1 = immersion / 2.4, amplitude / 2.4
    z1, z2, z3 = z[..., 0], z[..., 1], z[..., 2]
    alphas = [np.full(z1.shape, 0.5), _alpha_root(z1, z2),
              _alpha_root(z1, z2 + 2 * z3), _alpha_root(z1, z2 - 2 * z3)]
    taus = []
    for k, al in enumerate(alphas):
        if a1 > 0:
            s = (a0 - al) / a1
            ok = np.isfinite(s) & (np.abs(s) < 1) & ((al <= 0.5) if k else True)
            asin = np.arcsin(np.where(ok, s, 0.0))
            taus.append(np.where(ok, np.mod(asin, TWO_PI), 0.0))
            taus.append(np.where(ok, np.mod(math.pi - asin, TWO_PI), 0.0))
        else:
            taus.extend([np.zeros(z1.shape)] * 2)
    b = np.stack([np.zeros(z1.shape)] + taus + [np.full(z1.shape, TWO_PI)], axis=-1)
    return np.sort(b, axis=-1)


def cpp_boundary_map(
    z: Any,
    immersion: float = 1.2,
    amplitude: float = 0.96,
    *,
    variant: MaximiserVariant = "clipped",
    nodes: int = 24,
    chunk: int = 2048,
) -> np.ndarray:
    """ς(z) = (⟨p c1⟩, ⟨p c2⟩, ⟨p² c2⟩), Platonov & Platonova, eq. (14), with p of eq. (15)-(16).

    Every period is split at the kinks of c1, c2 (α = 0.5) and at the maximiser's own kinks
    (sign switch of c1 z1 + c2 z2, clipping onsets p = ±1), all found in closed form, so the
    Gauss–Legendre quadrature is exact to rounding for smooth pieces.

    Parameters
    ----------
    z : array_like, shape (..., 3)
        Directions (need not be unit).
    immersion, amplitude : float
        h0/R and eψ0/R [R], eq. (12).
    variant : {"clipped", "printed"}
        Maximiser of :func:`cpp_maximiser`.
    nodes : int
        Gauss–Legendre nodes per piece.
    chunk : int, optional
        Number of directions evaluated at once (memory bound; default 2048).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        With ``variant="clipped"``: |ς1| ≤ β2, |ς2| ≤ β3, 0 ≤ ς3 ≤ β3.
    """
    _check_waves(immersion, amplitude)
    _check_choice("variant", variant, _MAXIMISER_VARIANTS)
    z = as_float_array("z", z)
    if z.shape[-1:] != (3,):
        raise ParameterError(f"`z` must end in 3 components, got shape {z.shape}")
    zf = z.reshape(-1, 3)
    out = np.empty_like(zf)
    for sl in _chunks(zf.shape[0], int(chunk)):
        zc = zf[sl]
        t, w = nodes_on_breaks(_cpp_breaks(zc, immersion, amplitude), int(nodes))
        c1, c2 = emergence_factors(t, immersion, amplitude)
        p = cpp_maximiser(c1, c2, zc[:, None, :], variant)
        out[sl, 0] = np.sum(w * p * c1, axis=-1)
        out[sl, 1] = np.sum(w * p * c2, axis=-1)
        out[sl, 2] = np.sum(w * p * p * c2, axis=-1)
    return out.reshape(z.shape)


def cpp_support_function(
    z: Any, immersion: float = 1.2, amplitude: float = 0.96, *, nodes: int = 24
) -> np.ndarray:
    """h_V(z) = ⟨ς(z), z⟩ for the CPP control set (clipped maximiser), shape (...).

    Parameters
    ----------
    z : array_like, shape (..., 3)
        Directions (need not be unit).
    immersion : float, optional
        Propeller shaft immersion h0/R [R] (default 1.2), eq. (12).
    amplitude : float, optional
        Wave amplitude at the propeller eψ0/R [R] (default 0.96), eq. (12).
    nodes : int, optional
        Gauss–Legendre nodes per piece (default 24).

    Returns
    -------
    numpy.ndarray, shape (...)
        h_V(z).
    """
    z = as_float_array("z", z)
    return np.sum(cpp_boundary_map(z, immersion, amplitude, nodes=nodes) * z, axis=-1)


def cpp_betas(immersion: float = 1.2, amplitude: float = 0.96, *, nodes: int = 48
              ) -> tuple[float, float, float]:
    """(β1, β2, β3) = (⟨c1²/c2⟩, ⟨c1⟩, ⟨c2⟩), Platonov & Platonova, eq. (24).

    For the paper's α(τ) = 0.5 − 0.4 sin τ: 0.82419, 0.8472, 0.8727.

    Parameters
    ----------
    immersion : float, optional
        Propeller shaft immersion h0/R [R] (default 1.2), eq. (12).
    amplitude : float, optional
        Wave amplitude at the propeller eψ0/R [R] (default 0.96), eq. (12).
    nodes : int, optional
        Gauss–Legendre nodes per piece between kinks (default 48).

    Returns
    -------
    tuple of float
        (β1, β2, β3) [-].
    """
    _check_waves(immersion, amplitude)
    return _cpp_betas_cached(float(immersion), float(amplitude), int(nodes))


@functools.lru_cache(maxsize=64)
def _cpp_betas_cached(immersion: float, amplitude: float, nodes: int
                      ) -> tuple[float, float, float]:

    def g(t: np.ndarray) -> np.ndarray:
        c1, c2 = emergence_factors(t, immersion, amplitude)
        return np.stack([c1 * c1 / c2, c1, c2])

    b = period_mean(g, kinks=emergence_kinks(immersion, amplitude), nodes=nodes)
    return float(b[0]), float(b[1]), float(b[2])


def sphere_grid(
    n_azimuth: int = 200, n_elevation: int = 100
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit directions of Platonov & Platonova, eq. (17), on a (n_elevation, n_azimuth) grid.

    z = (cos φ1 cos φ2, sin φ1 cos φ2, sin φ2), φ1 ∈ [0, 2π], φ2 ∈ [−π/2, π/2] (both ends
    included, so surfaces close). Returns ``z`` (n_elevation, n_azimuth, 3), φ1, φ2 [rad].

    Parameters
    ----------
    n_azimuth : int, optional
        Number of azimuth angles φ1 (>= 3, default 200).
    n_elevation : int, optional
        Number of elevation angles φ2 (>= 3, default 100).

    Returns
    -------
    z : numpy.ndarray, shape (n_elevation, n_azimuth, 3)
        Unit directions.
    phi1 : numpy.ndarray, shape (n_azimuth,)
        Azimuths φ1 [rad].
    phi2 : numpy.ndarray, shape (n_elevation,)
        Elevations φ2 [rad].
    """
    if int(n_azimuth) < 3 or int(n_elevation) < 3:
        raise ParameterError(
            f"`n_azimuth` and `n_elevation` must be >= 3, got {n_azimuth!r}, {n_elevation!r}"
        )
    phi1 = np.linspace(0.0, TWO_PI, int(n_azimuth))
    phi2 = np.linspace(-0.5 * math.pi, 0.5 * math.pi, int(n_elevation))
    p1, p2 = np.meshgrid(phi1, phi2)
    z = np.stack([np.cos(p1) * np.cos(p2), np.sin(p1) * np.cos(p2), np.sin(p2)], axis=-1)
    return z, phi1, phi2


def flat_support_function(
    z: Any, betas: Sequence[float], variant: FlatVariant = "hull"
) -> np.ndarray:
    """Support function of the flat approximation Y, Platonov & Platonova, eq. (24).

    ``variant="hull"``: Y = conv{(β1 t, β2 t, β3 t²) : t ∈ [-1, 1]} (correct reading);
    h_Y(z) = max_t (β1 z1 + β2 z2) t + β3 z3 t². ``variant="printed"``: the convex hull of that
    arc and the printed segment {(s, s, β3) : s ∈ [-1, 1]} (erratum: it does not meet the arc's
    ends and sticks out of V); h = max(h_arc, |z1 + z2| + β3 z3).

    Parameters
    ----------
    z : array_like, shape (..., 3)
        Directions (need not be unit).
    betas : sequence of float
        (β1, β2, β3) of :func:`cpp_betas` [-].
    variant : {"hull", "printed"}, optional
        Reading of eq. (24) (default "hull").

    Returns
    -------
    numpy.ndarray, shape (...)
        h_Y(z).
    """
    _check_choice("variant", variant, _FLAT_VARIANTS)
    z = as_float_array("z", z)
    b1, b2, b3 = (float(b) for b in betas)
    q = np.stack([np.zeros(z.shape[:-1]), b1 * z[..., 0] + b2 * z[..., 1], b3 * z[..., 2]], -1)
    h = maximise_polynomial(q)[1]
    if variant == "printed":
        h = np.maximum(h, np.abs(z[..., 0] + z[..., 1]) + b3 * z[..., 2])
    return h


def hausdorff_from_support(h_a: Any, h_b: Any) -> float:
    """Hausdorff distance of two convex compact sets, max over unit directions of |h_A − h_B|.

    ``h_a``, ``h_b`` are the support functions on the same set of unit directions; on a grid
    this is a lower bound that converges as the grid is refined.

    Parameters
    ----------
    h_a, h_b : array_like
        Support functions of sets A and B on the same unit directions.

    Returns
    -------
    float
        max |h_A − h_B|.
    """
    a = as_float_array("h_a", h_a)
    b = as_float_array("h_b", h_b)
    return float(np.max(np.abs(a - b)))


@dataclasses.dataclass(frozen=True)
class CPPControlSetResult:
    """V and Y for the CPP ship (Platonov & Platonova, Figs. 1 and 2, eq. (14)-(24))."""

    immersion: float
    amplitude: float
    betas: tuple[float, float, float]
    phi1: np.ndarray  #: azimuths of the grid [rad]
    phi2: np.ndarray  #: elevations of the grid [rad]
    directions: np.ndarray  #: (n_elevation, n_azimuth, 3) unit z
    boundary: np.ndarray  #: ς(z) on the grid, points of ∂V, (n_elevation, n_azimuth, 3)
    support_V: np.ndarray
    support_Y: np.ndarray
    support_Y_printed: np.ndarray
    hausdorff_V_Y: float
    hausdorff_V_Y_printed: float
    width: float  #: thickness of V across (1, −1, 0)/√2: h_V(n) + h_V(−n)
    elapsed: float  #: wall time [s]

    @property
    def grid_points(self) -> int:
        return int(self.directions.shape[0] * self.directions.shape[1])

    def summary(self) -> dict[str, Any]:
        """Plain-number summary (the CLI's JSON)."""
        b1, b2, b3 = self.betas
        return {
            "immersion": self.immersion,
            "amplitude": self.amplitude,
            "beta1": b1,
            "beta2": b2,
            "beta3": b3,
            "hausdorff_V_Y": self.hausdorff_V_Y,
            "hausdorff_V_Y_printed": self.hausdorff_V_Y_printed,
            "width_V": self.width,
            "grid_points": self.grid_points,
            "elapsed_s": self.elapsed,
        }


def _refine_hausdorff(
    phi1: float, phi2: float, immersion: float, amplitude: float, betas: Sequence[float],
    variant: FlatVariant,
) -> float:
    from scipy.optimize import minimize

    def neg(a: np.ndarray) -> float:
        z = np.array([math.cos(a[0]) * math.cos(a[1]), math.sin(a[0]) * math.cos(a[1]),
                      math.sin(a[1])])
        hv = cpp_support_function(z, immersion, amplitude)
        hy = flat_support_function(z, betas, variant)
        return -abs(float(hv - hy))

    res = minimize(neg, np.array([phi1, phi2]), method="Nelder-Mead",
                   options={"xatol": 1e-7, "fatol": 1e-12, "maxiter": 400})
    return -float(res.fun)


def cpp_admissible_set(
    immersion: float = 1.2,
    amplitude: float = 0.96,
    *,
    n_azimuth: int = 200,
    n_elevation: int = 100,
    refine: bool = True,
) -> CPPControlSetResult:
    """Boundary of V on the grid of eq. (17), the flat set Y and their Hausdorff distances.

    Parameters
    ----------
    immersion, amplitude : float
        h0/R and eψ0/R [R] (Platonov & Platonova, eq. (12)); defaults give α = 0.5 − 0.4 sin τ.
    n_azimuth, n_elevation : int
        Grid of φ1 ∈ [0, 2π] and φ2 ∈ [−π/2, π/2].
    refine : bool
        Polish each Hausdorff distance by a local maximisation over the sphere started at the
        best grid direction (otherwise the grid value, a lower bound).
    """
    start = time.perf_counter()
    _check_waves(immersion, amplitude)
    z, phi1, phi2 = sphere_grid(n_azimuth, n_elevation)
    betas = cpp_betas(immersion, amplitude)
    sigma = cpp_boundary_map(z, immersion, amplitude)
    hv = np.sum(sigma * z, axis=-1)
    hy = flat_support_function(z, betas, "hull")
    hyp = flat_support_function(z, betas, "printed")
    dists = []
    for h in (hy, hyp):
        d = hausdorff_from_support(hv, h)
        if refine:
            i, j = np.unravel_index(np.argmax(np.abs(hv - h)), hv.shape)
            d = max(d, _refine_hausdorff(phi1[j], phi2[i], immersion, amplitude, betas,
                                         "hull" if h is hy else "printed"))
        dists.append(d)
    n = np.array([[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0]]) / math.sqrt(2.0)
    width = float(np.sum(cpp_support_function(n, immersion, amplitude)))
    return CPPControlSetResult(
        immersion=float(immersion), amplitude=float(amplitude), betas=betas, phi1=phi1,
        phi2=phi2, directions=z, boundary=sigma, support_V=hv, support_Y=hy,
        support_Y_printed=hyp, hausdorff_V_Y=dists[0], hausdorff_V_Y_printed=dists[1],
        width=width, elapsed=time.perf_counter() - start,
    )


# ---------------------------------------------------------------------------------------
# CPP averaged system, eq. (13)
# ---------------------------------------------------------------------------------------
def _params(params: CPPShipParams | None) -> CPPShipParams:
    if params is None:
        return CPPShipParams()
    if not isinstance(params, CPPShipParams):
        raise ParameterError(f"`params` must be CPPShipParams, got {type(params).__name__}")
    return params


def cpp_drift_and_matrix(
    x: Any, params: CPPShipParams | None = None, *, assignment: Assignment = "correct"
) -> tuple[np.ndarray, np.ndarray]:
    """f̄(x) (..., 2) and A(x) (..., 2, 3) of the averaged CPP system, eq. (13), without ε.

    Writes eq. (10) (case 1 coefficients: φ̄ ≥ 0, v̄ ≥ 0, the paper's case) in the form (1):
    f(τ, x) = (e1 k1² v̄² c1(τ) − χ P_e0 c10 v̄², N M_C0 c20 M⁰), φ(τ, u) = (c1 u, c2 u, c2 u²),
    A(x) = [[S1, 0, 0], [0, −N e2 k2² v̄², −N S2]] with
    S_i = a_i ω̄² + b_i k_i v̄ ω̄ + c_i k_i² v̄².
    ``assignment="printed"`` swaps the last two columns of the second row, as the printed
    eq. (13) does (erratum).

    Parameters
    ----------
    x : array_like, shape (..., 2)
        States (v̄, ω̄): non-dimensional speed and shaft speed [-].
    params : CPPShipParams, optional
        Ship parameters (default: the paper's set).
    assignment : {"correct", "printed"}, optional
        Column assignment of the second row of A(x) (default "correct").

    Returns
    -------
    fbar : numpy.ndarray, shape (..., 2)
        Averaged drift f̄(x).
    amat : numpy.ndarray, shape (..., 2, 3)
        Control matrix A(x).
    """
    _check_choice("assignment", assignment, _ASSIGNMENTS)
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
    col_e2 = -n * e2 * k2 * k2 * v * v
    col_s2 = -n * s2
    if assignment == "printed":
        col_e2, col_s2 = col_s2, col_e2
    amat = np.stack([np.stack([s1, zero, zero], -1), np.stack([zero, col_e2, col_s2], -1)], -2)
    return fbar, amat


def cpp_averaged_rhs(
    x: Any,
    sigma: Any,
    params: CPPShipParams | None = None,
    *,
    assignment: Assignment = "correct",
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
    assignment : {"correct", "printed"}
        ``"correct"``: ς2 multiplies −N e2 (λ0/λ2max)² v̄², ς3 multiplies −N S2.
        ``"printed"``: the swapped assignment of the printed eq. (13) (erratum; does not
        converge to the original system as ε → 0).
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
    assignment: Assignment = "correct",
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
    assignment : {"correct", "printed"}
        Of eq. (13), see :func:`cpp_averaged_rhs`.
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
    _check_choice("assignment", assignment, _ASSIGNMENTS)
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

        avg = rhs_averaged if assignment == "correct" else rhs_averaged_printed

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
        sigma=sigma, direction=z, horizon=float(horizon), assignment=assignment,
    )
