"""The base of every sea-wave spectrum: conventions, spectral moments, Hs from h3%.

Conventions
-----------
Frequencies ω are circular [rad/s]. Every spectrum has two explicitly named methods:

``one_sided(omega)``
    S₁(ω) on ω ≥ 0 with K(τ) = ∫₀^∞ S₁(ω) cos ωτ dω, so the variance is ∫₀^∞ S₁ dω.
    This is the convention of Sushchenko & Lutsko (2010), eq. (1), and of the Hs/Tp spectra.
``two_sided(omega)``
    S(ω) = S₁(|ω|)/2 on −∞ < ω < ∞ with K(τ) = ∫ S(ω) e^{iωτ} dω (the Wiener–Khinchin pair
    before eq. (1)); the variance is ∫_{−∞}^{∞} S dω.

No spectrum is callable, so the two cannot be mixed up silently.

Concrete spectra: :mod:`seahelm.environment.rational_spectra` (Rakhmanin–Firsov and their
derivatives), :mod:`seahelm.environment.spectra` (the standard Hs/Tp spectra and the registry
:data:`~seahelm.environment.spectra.SPECTRA` of all of them).

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010). Modelling of external disturbances in
stabilisation and heading systems of marine vehicles (in Ukrainian).
Hasselmann, K. et al. (1973). JONSWAP. Dtsch. Hydrogr. Z., Reihe A, 12.
DNV-RP-C205 (2010), Environmental conditions and environmental loads, sec. 3.5.5.
"""

from __future__ import annotations

import abc
import functools
import math
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative
from ..errors import ParameterError
from .sea_state import wave_variance

__all__ = ["WaveSpectrum", "spectral_moment", "significant_height_from_h3"]


def significant_height_from_h3(h3: float) -> float:
    """Significant wave height Hs = 4√D_r [m] with D_r = 0.143 (h3%/2)².

    With this choice every spectrum built from the same h3% has the same variance m0 = D_r.

    Parameters
    ----------
    h3 : float
        Wave height of 3 % exceedance h3% [m].

    Returns
    -------
    float
        Hs [m].
    """
    return 4.0 * math.sqrt(float(wave_variance(h3)))


class WaveSpectrum(abc.ABC):
    """Base class of wave spectra (see the module docstring for the conventions).

    Subclasses implement :meth:`one_sided` and set :attr:`high_frequency_order` p, the power
    in S₁ ~ ω^(−p) as ω → ∞, and :attr:`low_frequency_order` q in S₁ ~ ω^q as ω → 0
    (``inf`` for spectra that vanish faster than any power); they decide which moments exist.
    """

    name: ClassVar[str] = "spectrum"
    high_frequency_order: ClassVar[float] = math.inf
    low_frequency_order: ClassVar[float] = 0.0

    @abc.abstractmethod
    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided spectral density S₁(ω) [unit²·s/rad] for ω ≥ 0 (eq. (1) convention).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega``.
        """

    def two_sided(self, omega: ArrayLike) -> np.ndarray:
        """Two-sided spectral density S(ω) = S₁(|ω|)/2 for −∞ < ω < ∞.

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s].

        Returns
        -------
        numpy.ndarray
            S(ω), shape of ``omega``.
        """
        w = as_float_array("omega", omega, "rad/s")
        return 0.5 * self.one_sided(np.abs(w))

    # Every subclass provides ``variance`` (m0 = ∫₀^∞ S₁ dω), as a field or a property.

    def moment(self, n: int) -> float:
        """Spectral moment m_n = ∫₀^∞ ωⁿ S₁(ω) dω (``inf`` if it diverges).

        Parameters
        ----------
        n : int
            Order, ≥ 0.
        """
        return spectral_moment(self, n)

    @functools.cached_property
    def peak_frequency(self) -> float:
        """Frequency of the maximum of S₁ [rad/s] (numerical unless overridden)."""
        grid = np.geomspace(1e-3, 1e2, 4001)
        vals = self.one_sided(grid)
        i = int(np.argmax(vals))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        from scipy import optimize  # (here: importing the spectra costs no scipy)

        res = optimize.minimize_scalar(
            lambda w: -float(self.one_sided(np.array([w]))[0]),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-10},
        )
        return float(res.x)

    def _check_omega(self, omega: ArrayLike) -> np.ndarray:
        w = as_float_array("omega", omega, "rad/s")
        check_nonnegative("omega", w, "rad/s")
        return w


def spectral_moment(spectrum: WaveSpectrum, n: int) -> float:
    """Spectral moment m_n = ∫₀^∞ ωⁿ S₁(ω) dω of a one-sided spectrum.

    Parameters
    ----------
    spectrum : WaveSpectrum
    n : int
        Order, ≥ 0.

    Returns
    -------
    float
        m_n, or ``inf`` when the integral diverges (decided from the spectrum's asymptotic
        orders, e.g. m2 of Rakhmanin–Firsov variant 1, m4 of Pierson–Moskowitz).

    Raises
    ------
    ParameterError
        If ``n`` is negative or not an integer.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ParameterError(f"`n` must be an integer >= 0, got {n!r}")
    if n - spectrum.high_frequency_order >= -1 or n + spectrum.low_frequency_order <= -1:
        return math.inf
    wp = max(spectrum.peak_frequency, 1e-6)

    def f(w: float) -> float:
        return w**n * float(spectrum.one_sided(np.array([w]))[0])

    from scipy import integrate  # (here: importing the spectra costs no scipy)

    edges = [0.0, 0.5 * wp, 0.9 * wp, 1.1 * wp, 2.0 * wp, 10.0 * wp]
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        total += integrate.quad(f, a, b, limit=200, epsabs=0.0, epsrel=1e-11)[0]
    total += integrate.quad(f, edges[-1], math.inf, limit=200, epsabs=0.0, epsrel=1e-11)[0]
    return float(total)
