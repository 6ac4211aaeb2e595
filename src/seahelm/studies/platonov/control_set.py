"""The admissible control set V of the CPP ship in waves, Platonov & Platonova eq. (14)-(16).

φ(τ, u) = (c1 u, c2 u, c2 u²) with the emergence factors c1(τ), c2(τ) of
:mod:`seahelm.vessels.cpp_ship` (eq. (10)-(12)); ς(z) of eq. (14), the maximiser of
eq. (15)-(16), the means β of eq. (24). The flat approximation Y of eq. (24) and V against Y are
:mod:`seahelm.studies.platonov.flat_set`.

Errata and where they are handled (the printed readings stay reachable by name):

* eq. (15)-(16): the interior maximiser is **clipped to U = [-1, 1]** (the paper omits it, and
  unclipped ς(z) is unbounded): :data:`CLIPPED_MAXIMISER` (``variant="clipped"``, default)
  versus :data:`PRINTED_EQ15` (``variant="printed"``), registry :data:`MAXIMISERS`;
* eq. (19), (21) and the ratio "z1/z2" are misprinted; ς(z) is derived from eq. (14)
  directly.

Period means use Gauss–Legendre quadrature on the pieces between the known kinks; the kinks of
the maximiser (sign switches and clipping onsets) are found in closed form too, so every piece
is analytic and the quadrature converges exponentially.
"""

from __future__ import annotations

import abc
import functools
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import numpy as np

from ..._validate import as_float_array, check_range
from .averaging import PolynomialControlSet, chunk_slices
from ...errors import ParameterError
from ...numerics.periodic import TWO_PI, nodes_on_breaks, period_mean
from ...registry import lookup
from ...vessels.cpp_ship import emergence_factors, emergence_kinks

__all__ = [
    "MaximiserVariant",
    "ClippedMaximiser",
    "PrintedEq15",
    "CLIPPED_MAXIMISER",
    "PRINTED_EQ15",
    "MAXIMISERS",
    "get_maximiser",
    "cpp_control_set",
    "cpp_maximiser",
    "cpp_boundary_map",
    "cpp_support_function",
    "cpp_betas",
]


def _check_waves(immersion: float, amplitude: float) -> None:
    check_range("immersion", immersion, 0.0, math.inf, "R")
    check_range("amplitude", amplitude, 0.0, math.inf, "R")
    if 0.5 + (immersion - amplitude) / 2.4 <= 0.0:
        raise ParameterError(
            "the torque emergence factor c2(τ) = 0.5 + α(τ) reaches 0 "
            "(Platonov & Platonova, eq. (11)): need immersion − amplitude > −1.2 [R], got "
            f"immersion={immersion!r}, amplitude={amplitude!r}"
        )


# ---------------------------------------------------------------------------------------
# the maximiser of eq. (15)-(16): corrected and printed, as objects
# ---------------------------------------------------------------------------------------
class MaximiserVariant(abc.ABC):
    """A reading of the maximiser p(τ, z) of eq. (15)-(16) (a :data:`MAXIMISERS` entry)."""

    #: Registry name.
    name: str = ""

    @abc.abstractmethod
    def select(self, g: np.ndarray, concave: np.ndarray, interior: np.ndarray) -> np.ndarray:
        """p from g = c1 z1 + c2 z2, the mask c2 z3 < 0 and the interior stationary point.

        Parameters
        ----------
        g : numpy.ndarray
            c1 z1 + c2 z2.
        concave : numpy.ndarray of bool
            c2 z3 < 0 (H concave in u).
        interior : numpy.ndarray
            −g/(2 c2 z3) where ``concave`` (0 elsewhere).

        Returns
        -------
        numpy.ndarray
            p(τ, z).
        """


class ClippedMaximiser(MaximiserVariant):
    """Correct: for c2 z3 < 0 the interior stationary point −(c1 z1 + c2 z2)/(2 c2 z3) clipped
    to [-1, 1]; otherwise ±1 by the sign of c1 z1 + c2 z2 (ties to +1)."""

    name = "clipped"

    def select(self, g: np.ndarray, concave: np.ndarray, interior: np.ndarray) -> np.ndarray:
        """p clipped to U = [-1, 1].

        Parameters
        ----------
        g : numpy.ndarray
            c1 z1 + c2 z2.
        concave : numpy.ndarray of bool
            c2 z3 < 0.
        interior : numpy.ndarray
            The interior stationary point where ``concave``.

        Returns
        -------
        numpy.ndarray
            p(τ, z) ∈ [-1, 1].
        """
        return np.where(concave, np.clip(interior, -1.0, 1.0), np.where(g >= 0, 1.0, -1.0))


class PrintedEq15(MaximiserVariant):
    """Platonov & Platonova's eq. (15) as printed: unclipped (erratum: leaves U for about 40 %
    of the directions with z3 < 0) and ``sign`` giving 0 on ties."""

    name = "printed"

    def select(self, g: np.ndarray, concave: np.ndarray, interior: np.ndarray) -> np.ndarray:
        """p as printed (not clipped).

        Parameters
        ----------
        g : numpy.ndarray
            c1 z1 + c2 z2.
        concave : numpy.ndarray of bool
            c2 z3 < 0.
        interior : numpy.ndarray
            The interior stationary point where ``concave``.

        Returns
        -------
        numpy.ndarray
            p(τ, z), unbounded for z3 → 0⁻.
        """
        return np.where(concave, interior, np.sign(g))


#: The clipped maximiser (``"clipped"``, the default).
CLIPPED_MAXIMISER: MaximiserVariant = ClippedMaximiser()
#: Eq. (15) as printed (``"printed"``).
PRINTED_EQ15: MaximiserVariant = PrintedEq15()
#: Readings of eq. (15)-(16), by name.
MAXIMISERS: Mapping[str, MaximiserVariant] = MappingProxyType(
    {v.name: v for v in (CLIPPED_MAXIMISER, PRINTED_EQ15)})


def get_maximiser(variant: str | MaximiserVariant) -> MaximiserVariant:
    """A reading of eq. (15)-(16) by name (a key of :data:`MAXIMISERS`) or the object itself.

    Parameters
    ----------
    variant : str or MaximiserVariant
        ``"clipped"``, ``"printed"`` or a :class:`MaximiserVariant`.

    Returns
    -------
    MaximiserVariant

    Raises
    ------
    ParameterError
        If ``variant`` is an unknown name (the message lists the valid ones).
    """
    return lookup("`variant`", MAXIMISERS, variant, MaximiserVariant, error=ParameterError)


# ---------------------------------------------------------------------------------------
# the control set V of eq. (14)
# ---------------------------------------------------------------------------------------
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
    c1: Any, c2: Any, z: Any, variant: str | MaximiserVariant = "clipped"
) -> np.ndarray:
    """Maximiser p(τ, z) of H = c1 u z1 + c2 u z2 + c2 u² z3 over u ∈ [-1, 1], eq. (15)-(16).

    Parameters
    ----------
    c1, c2 : array_like
        Emergence factors at the times of interest (broadcast against ``z[..., 0]``).
    z : array_like, shape (..., 3)
    variant : str or MaximiserVariant
        A key of :data:`MAXIMISERS` or the object: ``"clipped"`` (:data:`CLIPPED_MAXIMISER`,
        correct, default) or ``"printed"`` (:data:`PRINTED_EQ15`).

    Returns
    -------
    numpy.ndarray
        p(τ, z), shape of the broadcast of ``c1``, ``c2`` and ``z[..., 0]``.
    """
    maximiser = get_maximiser(variant)
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
    return maximiser.select(g, concave, interior)


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
    variant: str | MaximiserVariant = "clipped",
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
    variant : str or MaximiserVariant
        Maximiser of :func:`cpp_maximiser` (a key of :data:`MAXIMISERS` or the object).
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
    variant = get_maximiser(variant)
    z = as_float_array("z", z)
    if z.shape[-1:] != (3,):
        raise ParameterError(f"`z` must end in 3 components, got shape {z.shape}")
    zf = z.reshape(-1, 3)
    out = np.empty_like(zf)
    for sl in chunk_slices(zf.shape[0], int(chunk)):
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
