"""Rational sea-wave spectra: Rakhmanin–Firsov (Sushchenko & Lutsko, 2010) and their
derivative spectra, each with its spectral factor W(s) for the shaping filters of
:mod:`seahelm.environment.shaping`.

Conventions as in :mod:`seahelm.environment.spectrum_base`.

Rakhmanin–Firsov variants (D_r variance, μ decay rate, λ resonance frequency, a² = μ² + λ²,
Δ(ω) = ω⁴ + 2(μ² − λ²)ω² + a⁴):

* ``"rakhmanin-firsov-1"``: K = D_r e^{−μ|τ|} cos λτ, S₁ = (2D_rμ/π)(ω² + a²)/Δ — eq. (2)-(3).
* ``"rakhmanin-firsov-2"``: K = D_r e^{−μ|τ|}(cos λτ + (μ/λ) sin λ|τ|), S₁ = (4D_rμ/π) a²/Δ — eq. (4).
* ``"rakhmanin-firsov-3"``: K = D_r e^{−μ|τ|}(cos λτ − (μ/λ) sin λ|τ|), S₁ = (4D_rμ/π) ω²/Δ —
  the paper's third variant *corrected* (erratum: as printed, S₁ = 2D_rμω²/Δ integrates to
  (π/2)D_r and the printed correlation is garbled). The spectrum as printed is the paper's
  reproduction, :class:`seahelm.studies.sushchenko2010.RakhmaninFirsov3Printed`.

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010). Modelling of external disturbances in
stabilisation and heading systems of marine vehicles (in Ukrainian).
"""

from __future__ import annotations

import abc
import dataclasses
import math
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_positive
from ..constants import GRAVITY
from ..errors import ParameterError
from .sea_state import sea_state_parameters
from .spectrum_base import WaveSpectrum

__all__ = [
    "RationalSpectrum",
    "RakhmaninFirsov1",
    "RakhmaninFirsov2",
    "RakhmaninFirsov3",
    "DerivativeSpectrum",
    "ordinate_rate_spectrum",
    "slope_spectrum",
    "slope_rate_spectrum",
    "slope_acceleration_spectrum",
]


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
        cls, h3: float, *, level: str = "mean", table: Any = "corrected",
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
    The printed form is :class:`seahelm.studies.sushchenko2010.RakhmaninFirsov3Printed`.
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
for _cls in (RakhmaninFirsov1, RakhmaninFirsov2, RakhmaninFirsov3):
    _cls.__doc__ = (_cls.__doc__ or "").rstrip() + "\n" + _RF_PARAMETERS
