"""Sea-wave spectra: Rakhmanin–Firsov (Sushchenko & Lutsko, 2010) and the standard Hs/Tp ones.

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

Rakhmanin–Firsov variants (D_r variance, μ decay rate, λ resonance frequency, a² = μ² + λ²,
Δ(ω) = ω⁴ + 2(μ² − λ²)ω² + a⁴):

* ``"rakhmanin-firsov-1"``: K = D_r e^{−μ|τ|} cos λτ, S₁ = (2D_rμ/π)(ω² + a²)/Δ — eq. (2)-(3).
* ``"rakhmanin-firsov-2"``: K = D_r e^{−μ|τ|}(cos λτ + (μ/λ) sin λ|τ|), S₁ = (4D_rμ/π) a²/Δ — eq. (4).
* ``"rakhmanin-firsov-3"``: K = D_r e^{−μ|τ|}(cos λτ − (μ/λ) sin λ|τ|), S₁ = (4D_rμ/π) ω²/Δ —
  the paper's third variant *corrected* (erratum: as printed, S₁ = 2D_rμω²/Δ integrates to
  (π/2)D_r and the printed correlation is garbled).
* ``"rakhmanin-firsov-3-printed"``: the third spectrum exactly as printed, for reproduction.

Standard spectra, by significant wave height Hs and peak period Tp:
``"pierson-moskowitz"``, ``"jonswap"`` (γ, σ_a, σ_b), ``"bretschneider"`` (alias ``"ittc"``).

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010). Modelling of external disturbances in
stabilisation and heading systems of marine vehicles (in Ukrainian).
Hasselmann, K. et al. (1973). JONSWAP. Dtsch. Hydrogr. Z., Reihe A, 12.
DNV-RP-C205 (2010), Environmental conditions and environmental loads, sec. 3.5.5.
"""

from __future__ import annotations

import abc
import dataclasses
import functools
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike
from scipy import integrate, optimize

from .._validate import as_float_array, check_nonnegative, check_positive
from ..constants import GRAVITY
from ..errors import ParameterError
from .sea_state import sea_state_parameters, wave_variance

__all__ = [
    "WaveSpectrum",
    "RationalSpectrum",
    "RakhmaninFirsov1",
    "RakhmaninFirsov2",
    "RakhmaninFirsov3",
    "RakhmaninFirsov3Printed",
    "DerivativeSpectrum",
    "PiersonMoskowitz",
    "Jonswap",
    "Bretschneider",
    "SPECTRA",
    "get_spectrum",
    "spectrum_from_wave_height",
    "ordinate_rate_spectrum",
    "slope_spectrum",
    "slope_rate_spectrum",
    "slope_acceleration_spectrum",
    "spectral_moment",
    "significant_height_from_h3",
]


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

    edges = [0.0, 0.5 * wp, 0.9 * wp, 1.1 * wp, 2.0 * wp, 10.0 * wp]
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        total += integrate.quad(f, a, b, limit=200, epsabs=0.0, epsrel=1e-11)[0]
    total += integrate.quad(f, edges[-1], math.inf, limit=200, epsabs=0.0, epsrel=1e-11)[0]
    return float(total)


# ---------------------------------------------------------------------------------------------
# Rational spectra (Rakhmanin–Firsov) and their derivatives
# ---------------------------------------------------------------------------------------------


class RationalSpectrum(WaveSpectrum):
    """A spectrum S₁(ω) = |W(jω)|² with a rational, stable, minimum-phase factor W(s).

    :meth:`factor` returns the polynomial coefficients (highest power first) of W(s); the
    factor is normalised so that unit one-sided noise intensity reproduces S₁ (see
    :mod:`seahelm.environment.shaping`).
    """

    @abc.abstractmethod
    def factor(self) -> tuple[np.ndarray, np.ndarray]:
        """Numerator and denominator of W(s), highest power first."""

    def one_sided_from_factor(self, omega: ArrayLike) -> np.ndarray:
        """|W(jω)|² evaluated from :meth:`factor` (used to check the factorisation).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            |W(jω)|², shape of ``omega``.
        """
        w = self._check_omega(omega)
        num, den = self.factor()
        s = 1j * w
        return np.abs(np.polyval(num, s) / np.polyval(den, s)) ** 2


@dataclasses.dataclass(frozen=True, kw_only=True)
class _RakhmaninFirsov(RationalSpectrum):
    """Shared parts of the Rakhmanin–Firsov variants.

    Parameters
    ----------
    variance : float
        D_r, variance of the wave ordinate [m²], > 0.
    decay_rate : float
        μ, decay rate of the correlation function [1/s], > 0.
    resonance_frequency : float
        λ, resonance frequency of the spectrum [rad/s], > 0.
    """

    variance: float  # type: ignore[assignment]  # D_r [m²]
    decay_rate: float  # μ [1/s]
    resonance_frequency: float  # λ [rad/s]

    def __post_init__(self) -> None:
        check_positive("variance", self.variance, "m^2")
        check_positive("decay_rate", self.decay_rate, "1/s")
        check_positive("resonance_frequency", self.resonance_frequency, "rad/s")

    @classmethod
    def from_wave_height(
        cls, h3: float, *, level: str = "mean", table: str = "corrected",
        extrapolate: bool = False, **_: Any
    ) -> "_RakhmaninFirsov":
        """Build from h3% [m] with D_r = 0.143 (h3%/2)² and μ, λ from Table 2.

        See :func:`seahelm.environment.sea_state.sea_state_parameters` for ``level``,
        ``table`` (default: the corrected Table 2) and ``extrapolate`` (beyond 1…10 m).
        """
        p = sea_state_parameters(h3, level=level, table=table, extrapolate=extrapolate)
        return cls(variance=p.variance, decay_rate=p.decay_rate, resonance_frequency=p.resonance_frequency)

    @property
    def _a2(self) -> float:
        return self.decay_rate**2 + self.resonance_frequency**2

    def _denominator(self, w: np.ndarray) -> np.ndarray:
        mu, lam = self.decay_rate, self.resonance_frequency
        return w**4 + 2.0 * (mu**2 - lam**2) * w**2 + self._a2**2

    def _den_poly(self) -> np.ndarray:
        # stable factor of Δ: s² + 2μs + a² (erratum: the paper's a1 = 2λ is wrong)
        return np.array([1.0, 2.0 * self.decay_rate, self._a2])

    @abc.abstractmethod
    def correlation(self, tau: ArrayLike) -> np.ndarray:
        """Correlation function K(τ) [m²]."""


@dataclasses.dataclass(frozen=True, kw_only=True)
class RakhmaninFirsov1(_RakhmaninFirsov):
    """Rakhmanin–Firsov variant 1: K = D_r e^{−μ|τ|} cos λτ.

    S₁(ω) = (2D_rμ/π)(ω² + μ² + λ²)/(ω⁴ + 2(μ² − λ²)ω² + (μ² + λ²)²)
    (Sushchenko & Lutsko (2010), eq. (2)-(3)); S₁ ~ ω^(−2), so the slope variance diverges.
    Factor: W(s) = √(2D_rμ/π)(s + a)/(s² + 2μs + a²), a = √(μ² + λ²) — the factorisation
    after eq. (5) corrected (erratum: the printed damping 2λ must be 2μ).
    """

    name: ClassVar[str] = "rakhmanin-firsov-1"
    high_frequency_order: ClassVar[float] = 2.0
    low_frequency_order: ClassVar[float] = 0.0

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided spectral density S₁(ω) [m²·s/rad], Sushchenko & Lutsko (2010), eq. (3).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega``.
        """
        w = self._check_omega(omega)
        c = 2.0 * self.variance * self.decay_rate / math.pi
        return c * (w**2 + self._a2) / self._denominator(w)

    def correlation(self, tau: ArrayLike) -> np.ndarray:
        """Correlation function K(τ) = D_r e^{−μ|τ|} cos λτ [m²].

        Parameters
        ----------
        tau : array_like
            Time lags τ [s].

        Returns
        -------
        numpy.ndarray
            K(τ), shape of ``tau``.
        """
        t = np.abs(as_float_array("tau", tau, "s"))
        return self.variance * np.exp(-self.decay_rate * t) * np.cos(self.resonance_frequency * t)

    def factor(self) -> tuple[np.ndarray, np.ndarray]:
        k = math.sqrt(2.0 * self.variance * self.decay_rate / math.pi)
        return np.array([k, k * math.sqrt(self._a2)]), self._den_poly()


@dataclasses.dataclass(frozen=True, kw_only=True)
class RakhmaninFirsov2(_RakhmaninFirsov):
    """Rakhmanin–Firsov variant 2: K = D_r e^{−μ|τ|}(cos λτ + (μ/λ) sin λ|τ|).

    S₁(ω) = (4D_rμ/π)(μ² + λ²)/(ω⁴ + 2(μ² − λ²)ω² + (μ² + λ²)²)
    (Sushchenko & Lutsko (2010), eq. (4)); S₁ ~ ω^(−4), the only variant whose slope model of
    eq. (5) has finite variance (μ² + λ²)D_r/g².
    Factor: W(s) = 2√(D_rμ/π) a/(s² + 2μs + a²), a = √(μ² + λ²) (erratum to eq. (7)).
    """

    name: ClassVar[str] = "rakhmanin-firsov-2"
    high_frequency_order: ClassVar[float] = 4.0
    low_frequency_order: ClassVar[float] = 0.0

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided spectral density S₁(ω) [m²·s/rad] of variant 2 (see the class docstring).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega``.
        """
        w = self._check_omega(omega)
        c = 4.0 * self.variance * self.decay_rate / math.pi
        return c * self._a2 / self._denominator(w)

    def correlation(self, tau: ArrayLike) -> np.ndarray:
        """Correlation function K(τ) = D_r e^{−μ|τ|} (cos λτ + (μ/λ) sin λ|τ|) [m²].

        Parameters
        ----------
        tau : array_like
            Time lags τ [s].

        Returns
        -------
        numpy.ndarray
            K(τ), shape of ``tau``.
        """
        t = np.abs(as_float_array("tau", tau, "s"))
        mu, lam = self.decay_rate, self.resonance_frequency
        return self.variance * np.exp(-mu * t) * (np.cos(lam * t) + (mu / lam) * np.sin(lam * t))

    def factor(self) -> tuple[np.ndarray, np.ndarray]:
        k = 2.0 * math.sqrt(self.variance * self.decay_rate / math.pi)
        return np.array([k * math.sqrt(self._a2)]), self._den_poly()

    @property
    def peak_frequency(self) -> float:  # type: ignore[override]
        """√(λ² − μ²) [rad/s] if λ > μ, else 0 (minimum of the denominator)."""
        d = self.resonance_frequency**2 - self.decay_rate**2
        return math.sqrt(d) if d > 0 else 0.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class RakhmaninFirsov3(_RakhmaninFirsov):
    """Rakhmanin–Firsov variant 3, corrected: K = D_r e^{−μ|τ|}(cos λτ − (μ/λ) sin λ|τ|).

    S₁(ω) = (4D_rμ/π) ω²/(ω⁴ + 2(μ² − λ²)ω² + (μ² + λ²)²). Erratum: the paper prints the
    factor 2D_rμ (no 1/π; it then integrates to (π/2)D_r) and a garbled correlation; this
    variant integrates to D_r. It is the spectrum of the derivative of a variant-2 process,
    scaled by 1/a². Factor: W(s) = 2√(D_rμ/π) s/(s² + 2μs + a²).
    The printed form is :class:`RakhmaninFirsov3Printed`.
    """

    name: ClassVar[str] = "rakhmanin-firsov-3"
    high_frequency_order: ClassVar[float] = 2.0
    low_frequency_order: ClassVar[float] = 2.0

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided spectral density S₁(ω) [m²·s/rad] of variant 3 (see the class docstring).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega``.
        """
        w = self._check_omega(omega)
        c = 4.0 * self.variance * self.decay_rate / math.pi
        return c * w**2 / self._denominator(w)

    def correlation(self, tau: ArrayLike) -> np.ndarray:
        """Correlation function K(τ) = D_r e^{−μ|τ|} (cos λτ − (μ/λ) sin λ|τ|) [m²].

        Parameters
        ----------
        tau : array_like
            Time lags τ [s].

        Returns
        -------
        numpy.ndarray
            K(τ), shape of ``tau``.
        """
        t = np.abs(as_float_array("tau", tau, "s"))
        mu, lam = self.decay_rate, self.resonance_frequency
        return self.variance * np.exp(-mu * t) * (np.cos(lam * t) - (mu / lam) * np.sin(lam * t))

    def factor(self) -> tuple[np.ndarray, np.ndarray]:
        k = 2.0 * math.sqrt(self.variance * self.decay_rate / math.pi)
        return np.array([k, 0.0]), self._den_poly()

    @property
    def peak_frequency(self) -> float:  # type: ignore[override]
        """a = √(μ² + λ²) [rad/s] (maximum of ω²/Δ(ω))."""
        return math.sqrt(self._a2)


@dataclasses.dataclass(frozen=True, kw_only=True)
class RakhmaninFirsov3Printed(RakhmaninFirsov3):
    """The third Rakhmanin–Firsov spectrum exactly as printed (for reproducing the paper).

    S₁(ω) = 2D_rμω²/(ω⁴ + 2(μ² − λ²)ω² + (μ² + λ²)²), which integrates to (π/2)D_r, not D_r
    (Sushchenko & Lutsko (2010), spectrum after eq. (4); erratum). :attr:`variance` is the
    nominal D_r parameter; the true variance is :attr:`actual_variance` = (π/2)D_r.
    The correlation returned is that of the corrected shape times π/2 (the printed one is
    garbled and not a valid correlation function).
    """

    name: ClassVar[str] = "rakhmanin-firsov-3-printed"

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided spectral density as printed: π/2 times :meth:`RakhmaninFirsov3.one_sided`.

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω) [m²·s/rad], shape of ``omega``.
        """
        return super().one_sided(omega) * (math.pi / 2.0)

    def correlation(self, tau: ArrayLike) -> np.ndarray:
        """Correlation function as printed: π/2 times :meth:`RakhmaninFirsov3.correlation`.

        Parameters
        ----------
        tau : array_like
            Time lags τ [s].

        Returns
        -------
        numpy.ndarray
            K(τ) [m²], shape of ``tau``.
        """
        return super().correlation(tau) * (math.pi / 2.0)

    def factor(self) -> tuple[np.ndarray, np.ndarray]:
        num, den = super().factor()
        return num * math.sqrt(math.pi / 2.0), den

    @property
    def actual_variance(self) -> float:
        """(π/2) D_r [m²], the integral of the printed spectrum."""
        return 0.5 * math.pi * self.variance


@dataclasses.dataclass(frozen=True)
class DerivativeSpectrum(RationalSpectrum):
    """Spectrum of scale·dᵏζ/dtᵏ for a base spectrum of ζ: S₁ = scale² ω^(2k) S₁,base.

    Used for the ordinate rate (k = 1, scale 1), the wave slope of eq. (5)
    (k = 1, scale 1/g) and its rate and acceleration (k = 2, 3, scale 1/g), as in
    Sushchenko & Lutsko (2010): S_α = ω²S_r/g² (eq. (5)), S_α̇ = ω²S_α, S_α̈ = ω⁴S_α.

    Parameters
    ----------
    base : WaveSpectrum
    order : int
        k ≥ 0, number of time derivatives.
    scale : float
        Constant factor (1/g for the slope), > 0.
    label : str
        Name of the quantity, e.g. "slope".
    """

    base: WaveSpectrum
    order: int
    scale: float = 1.0
    label: str = "derivative"

    def __post_init__(self) -> None:
        if isinstance(self.order, bool) or not isinstance(self.order, (int, np.integer)) or self.order < 0:
            raise ParameterError(f"`order` must be an integer >= 0, got {self.order!r}")
        check_positive("scale", self.scale)

    @property
    def name(self) -> str:  # type: ignore[override]
        return f"{self.base.name}:{self.label}"

    @property
    def high_frequency_order(self) -> float:  # type: ignore[override]
        return self.base.high_frequency_order - 2 * self.order

    @property
    def low_frequency_order(self) -> float:  # type: ignore[override]
        return self.base.low_frequency_order + 2 * self.order

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided spectral density scale² ω^(2·order) S₁,base(ω).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            Spectral density [unit²·s/rad], shape of ``omega``.
        """
        w = self._check_omega(omega)
        return self.scale**2 * w ** (2 * self.order) * self.base.one_sided(w)

    @property
    def variance(self) -> float:  # type: ignore[override]
        """∫₀^∞ S₁ dω (``inf`` when the derivative process has infinite variance)."""
        return self.moment(0)

    def moment(self, n: int) -> float:
        """m_n of this spectrum = scale² m_(n+2k) of the base.

        Parameters
        ----------
        n : int
            Order of the spectral moment (>= 0).

        Returns
        -------
        float
            m_n = ∫ ωⁿ S₁(ω) dω.
        """
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
            raise ParameterError(f"`n` must be an integer >= 0, got {n!r}")
        return self.scale**2 * self.base.moment(n + 2 * self.order)

    @property
    def peak_frequency(self) -> float:  # type: ignore[override]
        return WaveSpectrum.peak_frequency.func(self)  # type: ignore[attr-defined]

    def factor(self) -> tuple[np.ndarray, np.ndarray]:
        """W(s)·scale·sᵏ (may be biproper or improper: see the shaping module)."""
        if not isinstance(self.base, RationalSpectrum):
            raise ParameterError(f"spectrum {self.base.name!r} has no rational factor")
        num, den = self.base.factor()
        num = np.concatenate([np.asarray(num, float) * self.scale, np.zeros(self.order)])
        return num, den


def ordinate_rate_spectrum(spectrum: WaveSpectrum) -> DerivativeSpectrum:
    """Spectrum of dζ/dt: ω² S₁(ω). Its variance is what the paper calls D_α = (μ² + λ²)D_r.

    Parameters
    ----------
    spectrum : WaveSpectrum
        Wave-ordinate spectrum S₁(ω).

    Returns
    -------
    DerivativeSpectrum
    """
    return DerivativeSpectrum(spectrum, 1, 1.0, "ordinate_rate")


def slope_spectrum(spectrum: WaveSpectrum, *, gravity: float = GRAVITY) -> DerivativeSpectrum:
    """Wave-slope spectrum S_α(ω) = ω² S_r(ω)/g² (Sushchenko & Lutsko (2010), eq. (5)).

    Parameters
    ----------
    spectrum : WaveSpectrum
        Wave-ordinate spectrum S_r(ω).
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    DerivativeSpectrum

    Notes
    -----
    This is the paper's slope model (the deep-water slope spectrum is ω⁴S/g²). Its variance is
    finite only for :class:`RakhmaninFirsov2`: (μ² + λ²)D_r/g² — the paper's
    D_α = (μ² + λ²)D_r lacks the 1/g² of eq. (5) (erratum).
    """
    check_positive("gravity", gravity, "m/s^2")
    return DerivativeSpectrum(spectrum, 1, 1.0 / gravity, "slope")


def slope_rate_spectrum(spectrum: WaveSpectrum, *, gravity: float = GRAVITY) -> DerivativeSpectrum:
    """Angular-rate spectrum S_α̇ = ω² S_α (Sushchenko & Lutsko (2010), after eq. (7)).

    Parameters
    ----------
    spectrum : WaveSpectrum
        Wave-ordinate spectrum S_r(ω).
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    DerivativeSpectrum
    """
    check_positive("gravity", gravity, "m/s^2")
    return DerivativeSpectrum(spectrum, 2, 1.0 / gravity, "slope_rate")


def slope_acceleration_spectrum(
    spectrum: WaveSpectrum, *, gravity: float = GRAVITY
) -> DerivativeSpectrum:
    """Angular-acceleration spectrum S_α̈ = ω⁴ S_α (infinite variance for all R–F variants).

    Parameters
    ----------
    spectrum : WaveSpectrum
        Wave-ordinate spectrum S_r(ω).
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    DerivativeSpectrum
    """
    check_positive("gravity", gravity, "m/s^2")
    return DerivativeSpectrum(spectrum, 3, 1.0 / gravity, "slope_acceleration")


# ---------------------------------------------------------------------------------------------
# Standard spectra by Hs / Tp
# ---------------------------------------------------------------------------------------------


def _default_peak_period(h3: float, level: str, table: str, extrapolate: bool) -> float:
    p = sea_state_parameters(h3, level=level, table=table, extrapolate=extrapolate)
    return 2.0 * math.pi / p.resonance_frequency


@dataclasses.dataclass(frozen=True, kw_only=True)
class Bretschneider(WaveSpectrum):
    """Bretschneider / ITTC two-parameter spectrum by Hs and Tp.

    S₁(ω) = (5/16) Hs² ω_p⁴ ω^(−5) exp(−(5/4)(ω_p/ω)⁴), ω_p = 2π/Tp; m0 = Hs²/16 exactly.

    Parameters
    ----------
    significant_height : float
        Hs [m], > 0.
    peak_period : float
        Tp [s], > 0.
    """

    name: ClassVar[str] = "bretschneider"
    high_frequency_order: ClassVar[float] = 5.0
    low_frequency_order: ClassVar[float] = math.inf

    significant_height: float
    peak_period: float

    def __post_init__(self) -> None:
        check_positive("significant_height", self.significant_height, "m")
        check_positive("peak_period", self.peak_period, "s")

    @classmethod
    def from_wave_height(
        cls,
        h3: float,
        *,
        peak_period: float | None = None,
        level: str = "mean",
        table: str = "corrected",
        extrapolate: bool = False,
        **_: Any,
    ) -> "Bretschneider":
        """Hs = 4√D_r from h3%; Tp given, or 2π/λ with λ from Table 2 (``level``, ``table``).

        Parameters
        ----------
        h3 : float
            Wave height of 3 % exceedance h3% [m].
        peak_period : float, optional
            Peak period Tp [s] (default 2π/λ from Table 2).
        level : {"max", "mean", "min"}, optional
            Which Table 2 column gives λ (default "mean").
        table : {"corrected", "printed"}, optional
            Version of Table 2 (default "corrected").
        extrapolate : bool, optional
            Extend Table 2 beyond 1…10 m with the h^(-1/2) law (default False: refuse).
        **_
            Ignored (accepted for a uniform interface).

        Returns
        -------
        Bretschneider
        """
        tp = (_default_peak_period(h3, level, table, extrapolate) if peak_period is None
              else peak_period)
        return cls(significant_height=significant_height_from_h3(h3), peak_period=tp)

    @property
    def peak_frequency(self) -> float:  # type: ignore[override]
        """ω_p = 2π/Tp [rad/s]."""
        return 2.0 * math.pi / self.peak_period

    def _pm_shape(self, w: np.ndarray) -> np.ndarray:
        wp = self.peak_frequency
        out = np.zeros_like(w)
        pos = w > 0
        x = wp / w[pos]
        out[pos] = (5.0 / 16.0) * self.significant_height**2 * x**4 / w[pos] * np.exp(-1.25 * x**4)
        return out

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided Bretschneider (two-parameter) density from Hs and Tp [m²·s/rad].

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega``.
        """
        return self._pm_shape(self._check_omega(omega))

    @property
    def variance(self) -> float:  # type: ignore[override]
        """m0 = Hs²/16 [m²]."""
        return self.significant_height**2 / 16.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class PiersonMoskowitz(WaveSpectrum):
    """Pierson–Moskowitz spectrum by Hs (fully developed sea).

    S₁(ω) = α g² ω^(−5) exp(−β ω^(−4)), β = 4αg²/Hs², so that m0 = αg²/(4β) = Hs²/16 exactly
    (ITTC rounds β to 3.11/Hs² with g = 9.81 m/s²). ω_p = (4β/5)^(1/4) ≈ 0.40 √(g/Hs).

    Parameters
    ----------
    significant_height : float
        Hs [m], > 0.
    alpha : float
        Phillips constant α, > 0 (default 0.0081).
    gravity : float
        g [m/s²].
    """

    name: ClassVar[str] = "pierson-moskowitz"
    high_frequency_order: ClassVar[float] = 5.0
    low_frequency_order: ClassVar[float] = math.inf

    significant_height: float
    alpha: float = 0.0081
    gravity: float = GRAVITY

    def __post_init__(self) -> None:
        check_positive("significant_height", self.significant_height, "m")
        check_positive("alpha", self.alpha)
        check_positive("gravity", self.gravity, "m/s^2")

    @classmethod
    def from_wave_height(cls, h3: float, **_: Any) -> "PiersonMoskowitz":
        """Hs = 4√D_r from h3% (the peak period follows from Hs).

        Parameters
        ----------
        h3 : float
            Wave height of 3 % exceedance h3% [m].
        **_
            Ignored (accepted for a uniform interface).

        Returns
        -------
        PiersonMoskowitz
        """
        return cls(significant_height=significant_height_from_h3(h3))

    @property
    def _beta(self) -> float:
        return 4.0 * self.alpha * self.gravity**2 / self.significant_height**2

    @property
    def peak_frequency(self) -> float:  # type: ignore[override]
        """ω_p = (4β/5)^(1/4) [rad/s]."""
        return (0.8 * self._beta) ** 0.25

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided Pierson–Moskowitz density α g² ω⁻⁵ exp(−β ω⁻⁴) [m²·s/rad].

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega`` (0 at ω = 0).
        """
        w = self._check_omega(omega)
        out = np.zeros_like(w)
        pos = w > 0
        out[pos] = self.alpha * self.gravity**2 / w[pos] ** 5 * np.exp(-self._beta / w[pos] ** 4)
        return out

    @property
    def variance(self) -> float:  # type: ignore[override]
        """m0 = Hs²/16 [m²]."""
        return self.significant_height**2 / 16.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class Jonswap(Bretschneider):
    """JONSWAP spectrum by Hs, Tp, γ, σ_a, σ_b.

    S₁(ω) = C(γ) S_B(ω) γ^r, r = exp(−(ω − ω_p)²/(2σ²ω_p²)), σ = σ_a for ω ≤ ω_p, σ_b above,
    S_B the Bretschneider spectrum of :class:`Bretschneider`.

    Parameters
    ----------
    significant_height : float
        Hs [m], > 0.
    peak_period : float
        Tp [s], > 0.
    gamma : float
        Peak-enhancement factor γ ≥ 1 (default 3.3).
    sigma_a, sigma_b : float
        Peak widths below/above ω_p, > 0 (defaults 0.07, 0.09).
    exact_normalization : bool
        False (default): C(γ) = 1 − 0.287 ln γ (DNV-RP-C205), so m0 = Hs²/16 only to within
        about 1–3 % for 1 ≤ γ ≤ 7. True: C(γ) computed by quadrature so that m0 = Hs²/16.
    """

    name: ClassVar[str] = "jonswap"

    gamma: float = 3.3
    sigma_a: float = 0.07
    sigma_b: float = 0.09
    exact_normalization: bool = False

    def __post_init__(self) -> None:
        super().__post_init__()
        check_positive("gamma", self.gamma)
        if self.gamma < 1.0:
            raise ParameterError(f"`gamma` must be >= 1, got {float(self.gamma)!r}")
        check_positive("sigma_a", self.sigma_a)
        check_positive("sigma_b", self.sigma_b)

    @classmethod
    def from_wave_height(
        cls,
        h3: float,
        *,
        peak_period: float | None = None,
        level: str = "mean",
        table: str = "corrected",
        extrapolate: bool = False,
        **kwargs: Any,
    ) -> "Jonswap":
        """Hs = 4√D_r from h3%; Tp given or 2π/λ (Table 2); other keywords passed on.

        Parameters
        ----------
        h3 : float
            Wave height of 3 % exceedance h3% [m].
        peak_period : float, optional
            Peak period Tp [s] (default 2π/λ from Table 2).
        level : {"max", "mean", "min"}, optional
            Which Table 2 column gives λ (default "mean").
        table : {"corrected", "printed"}, optional
            Version of Table 2 (default "corrected").
        extrapolate : bool, optional
            Extend Table 2 beyond 1…10 m with the h^(-1/2) law (default False: refuse).
        **kwargs
            Other fields of :class:`Jonswap` (``gamma``, ``sigma_a``, ``sigma_b``,
            ``exact_normalization``).

        Returns
        -------
        Jonswap
        """
        tp = (_default_peak_period(h3, level, table, extrapolate) if peak_period is None
              else peak_period)
        return cls(significant_height=significant_height_from_h3(h3), peak_period=tp, **kwargs)

    def _enhancement(self, w: np.ndarray) -> np.ndarray:
        wp = self.peak_frequency
        sigma = np.where(w <= wp, self.sigma_a, self.sigma_b)
        return self.gamma ** np.exp(-((w - wp) ** 2) / (2.0 * sigma**2 * wp**2))

    @functools.cached_property
    def normalization(self) -> float:
        """C(γ): 1 − 0.287 ln γ, or exact by quadrature if ``exact_normalization``."""
        if not self.exact_normalization:
            return 1.0 - 0.287 * math.log(self.gamma)
        raw = dataclasses.replace(self, exact_normalization=False)
        m0 = spectral_moment(raw, 0) / raw.normalization
        return self.variance / m0

    def one_sided(self, omega: ArrayLike) -> np.ndarray:
        """One-sided JONSWAP density C(γ) S_B(ω) γ^r [m²·s/rad].

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S₁(ω), shape of ``omega``.
        """
        w = self._check_omega(omega)
        return self.normalization * self._pm_shape(w) * self._enhancement(w)

    @property
    def variance(self) -> float:  # type: ignore[override]
        """Nominal m0 = Hs²/16 [m²] (exact only with ``exact_normalization``)."""
        return self.significant_height**2 / 16.0


_RF_PARAMETERS = """
    Parameters
    ----------
    variance : float
        D_r, variance of the wave ordinate [m²], > 0 (e.g. 0.143 (h3%/2)²).
    decay_rate : float
        μ, decay rate of the correlation function [1/s], > 0 (Table 2).
    resonance_frequency : float
        λ, resonance frequency of the spectrum [rad/s], > 0 (Table 2).

    Raises
    ------
    ParameterError
        If a parameter is not finite and > 0 (the message names it).
"""
for _cls in (RakhmaninFirsov1, RakhmaninFirsov2, RakhmaninFirsov3, RakhmaninFirsov3Printed):
    _cls.__doc__ = (_cls.__doc__ or "").rstrip() + "\n" + _RF_PARAMETERS

#: Registry of spectra by name. Values are classes; build one with :func:`get_spectrum` or
#: :func:`spectrum_from_wave_height`.
SPECTRA: Mapping[str, type[WaveSpectrum]] = MappingProxyType(
    {
        "rakhmanin-firsov-1": RakhmaninFirsov1,
        "rakhmanin-firsov-2": RakhmaninFirsov2,
        "rakhmanin-firsov-3": RakhmaninFirsov3,
        "rakhmanin-firsov-3-printed": RakhmaninFirsov3Printed,
        "pierson-moskowitz": PiersonMoskowitz,
        "jonswap": Jonswap,
        "bretschneider": Bretschneider,
        "ittc": Bretschneider,
    }
)


def _spectrum_class(name: str) -> type[WaveSpectrum]:
    try:
        return SPECTRA[name]
    except (KeyError, TypeError):
        valid = ", ".join(repr(k) for k in SPECTRA)
        raise ParameterError(f"unknown spectrum {name!r}; valid: {valid}") from None


def get_spectrum(spectrum: str | WaveSpectrum, **params: Any) -> WaveSpectrum:
    """A spectrum from a registry name and its parameters, or an existing spectrum object.

    Parameters
    ----------
    spectrum : str or WaveSpectrum
        A key of :data:`SPECTRA` or a :class:`WaveSpectrum` (returned unchanged; ``params``
        must then be empty).
    **params
        Constructor keywords (e.g. ``variance=…, decay_rate=…, resonance_frequency=…``).

    Raises
    ------
    ParameterError
        (a ``ValueError``) for an unknown name, listing the valid names, or bad parameters.
    """
    if isinstance(spectrum, WaveSpectrum):
        if params:
            raise ParameterError("parameters cannot be given together with a spectrum object")
        return spectrum
    return _spectrum_class(spectrum)(**params)


def spectrum_from_wave_height(spectrum: str | WaveSpectrum, h3: float, **kwargs: Any) -> WaveSpectrum:
    """A spectrum for a 3 %-exceedance wave height h3% [m].

    Rakhmanin–Firsov variants take D_r = 0.143 (h3%/2)² and μ, λ from Table 2 (keywords
    ``level``, ``table``); Hs/Tp spectra take Hs = 4√D_r (same m0) and, where needed,
    Tp = 2π/λ unless ``peak_period`` is given. An object is returned unchanged.

    Parameters
    ----------
    spectrum : str or WaveSpectrum
        Registry name of the spectrum (e.g. "rakhmanin-firsov-2", "jonswap") or a spectrum.
    h3 : float
        Wave height of 3 % exceedance h3% [m].
    **kwargs
        Passed to the class's ``from_wave_height`` (e.g. ``level``, ``table``, ``peak_period``).

    Returns
    -------
    WaveSpectrum
    """
    if isinstance(spectrum, WaveSpectrum):
        return spectrum
    cls = _spectrum_class(spectrum)
    return cls.from_wave_height(h3, **kwargs)  # type: ignore[attr-defined]
