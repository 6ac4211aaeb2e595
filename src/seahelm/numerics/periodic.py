"""Means over one period by piecewise Gauss–Legendre quadrature, split at known kinks.

Generic numerics at the bottom of the package: :mod:`seahelm.vessels.cpp_ship` (the balanced
emergence coefficients) and :mod:`seahelm.studies.platonov` (the averaged system of
Platonov & Platonova) both use it, and neither needs the other for it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["TWO_PI", "period_mean", "period_breaks", "nodes_on_breaks"]

TWO_PI = 2.0 * math.pi


def nodes_on_breaks(breaks: np.ndarray, nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and period-mean weights on the pieces between sorted ``breaks``.

    Parameters
    ----------
    breaks : numpy.ndarray, shape (..., K)
        Sorted break points [rad], starting at 0 and ending at 2π.
    nodes : int
        Gauss–Legendre nodes per piece.

    Returns
    -------
    t, w : numpy.ndarray, shape (..., (K - 1) * nodes)
        Nodes [rad] and weights; ``w`` sums to 1 (the 1/(2π) of the mean is included).
    """
    x, w = np.polynomial.legendre.leggauss(int(nodes))
    a = breaks[..., :-1, None]
    b = breaks[..., 1:, None]
    half = 0.5 * (b - a)
    t = 0.5 * (a + b) + half * x
    ww = half * w / TWO_PI
    shape = breaks.shape[:-1] + (-1,)
    return t.reshape(shape), ww.reshape(shape)


def period_breaks(kinks: Any, pieces: int) -> np.ndarray:
    """Break points of [0, 2π]: 0, the ``kinks`` (mod 2π) and 2π, each piece cut in ``pieces``.

    Parameters
    ----------
    kinks : sequence of float
        Points [rad] where the integrand is not smooth (any real values; taken mod 2π).
    pieces : int
        Equal subdivisions of every piece between kinks.

    Returns
    -------
    numpy.ndarray
        Sorted break points from 0 to 2π.
    """
    k = np.asarray(kinks, dtype=float).ravel()
    if k.size and (np.any(~np.isfinite(k))):
        raise ParameterError(f"`kinks` must be finite [rad], got {k}")
    k = np.mod(k, TWO_PI)
    pts = np.unique(np.concatenate([[0.0, TWO_PI], k]))
    fine = [np.linspace(a, b, pieces + 1)[:-1] for a, b in zip(pts[:-1], pts[1:])]
    return np.concatenate(fine + [[TWO_PI]])


def period_mean(
    func: Callable[[np.ndarray], Any],
    *,
    kinks: Any = (),
    nodes: int = 32,
    pieces: int = 1,
) -> np.ndarray:
    """Mean over one period, ⟨g⟩ = (1/2π) ∫₀^{2π} g(t) dt, by piecewise Gauss–Legendre.

    Parameters
    ----------
    func : callable
        ``func(t)`` with ``t`` a 1-D array of times [rad]; returns an array whose **last**
        axis runs over ``t``.
    kinks : sequence of float
        Known points in [0, 2π) [rad] where ``func`` is not smooth; the period is split there so
        each piece is smooth and the quadrature converges fast (exponentially for analytic
        pieces, e.g. the emergence factors c1, c2 of Platonov & Platonova, eq. (11)).
    nodes : int
        Gauss–Legendre nodes per piece.
    pieces : int
        Equal subdivisions of every piece between kinks.

    Returns
    -------
    numpy.ndarray
        ``func``'s output with the last axis averaged out.
    """
    if int(nodes) < 1 or int(pieces) < 1:
        raise ParameterError(f"`nodes` and `pieces` must be >= 1, got {nodes!r}, {pieces!r}")
    t, w = nodes_on_breaks(period_breaks(kinks, int(pieces)), int(nodes))
    return np.asarray(func(t)) @ w
