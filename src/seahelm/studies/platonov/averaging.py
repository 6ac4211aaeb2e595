"""Full averaging of control-affine periodic systems and the averaged control set (generic).

Platonov & Platonova, eq. (1)-(4): for

    ẋ = ε [f(t, x) + A(x) φ(t, u)],   u ∈ U compact,  f, φ 2π-periodic in t,

the fully averaged system is dx̄/dt = ε [f̄(x̄) + A(x̄) ς(z)] with f̄ = ⟨f⟩ (⟨·⟩ the mean over
one period), a new control z on the unit sphere and ς(z) = ⟨φ(t, y(t, z))⟩, where the
Hamiltonian maximiser y(t, z) maximises ⟨φ(t, u), z⟩ over u ∈ U. ς(z) lies on the boundary of
the averaged control set V = {⟨φ(t, u(t))⟩ : u(t) ∈ U}, whose support function is
h_V(z) = ⟨max_{u∈U} ⟨φ(t, u), z⟩⟩ = ⟨ς(z), z⟩.

This module holds what does not depend on the ship: :func:`averaged_drift`, the maximiser of a
polynomial in a scalar control (:func:`maximise_polynomial`), control sets polynomial in u
(:class:`PolynomialControlSet`, :func:`support_function`, :func:`boundary_map`), the unit
directions of eq. (17) (:func:`sphere_grid`) and the Hausdorff distance of convex sets from
their support functions (:func:`hausdorff_from_support`). Period means are
:func:`seahelm.numerics.periodic.period_mean`. The CPP ship of the paper (its control set,
the printed and corrected eq. (13)-(24), the ε study) is the rest of
:mod:`seahelm.studies.platonov`, the only user of this module, which therefore lives beside it
(it was ``seahelm.analysis.averaging``, a deprecated path now; issue 47).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np

from ..._validate import as_float_array, check_range
from ...errors import ParameterError
from ...numerics.periodic import TWO_PI, nodes_on_breaks, period_breaks

__all__ = [
    "averaged_drift",
    "maximise_polynomial",
    "PolynomialControlSet",
    "support_function",
    "boundary_map",
    "sphere_grid",
    "hausdorff_from_support",
    "chunk_slices",
]


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
        pieces per period (default 2), as :func:`~seahelm.numerics.periodic.period_mean`.

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


def chunk_slices(n: int, size: int) -> Iterator[slice]:
    """The slices that cut ``n`` rows into consecutive chunks of at most ``size`` rows.

    Parameters
    ----------
    n : int
        Number of rows.
    size : int
        Rows per chunk (the last may hold fewer).

    Returns
    -------
    iterator of slice
    """
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
    for sl in chunk_slices(zf.shape[0], 1024):
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
