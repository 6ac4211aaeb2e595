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

No spectrum is callable, so the two cannot be mixed up silently. The base class and the
conventions are :mod:`seahelm.environment.spectrum_base`; the Rakhmanin–Firsov spectra and
their derivatives are :mod:`seahelm.environment.rational_spectra`. This module holds the
standard Hs/Tp spectra and the registry :data:`SPECTRA` of all of them.

Rakhmanin–Firsov variants (D_r variance, μ decay rate, λ resonance frequency, a² = μ² + λ²,
Δ(ω) = ω⁴ + 2(μ² − λ²)ω² + a⁴):

* ``"rakhmanin-firsov-1"``: K = D_r e^{−μ|τ|} cos λτ, S₁ = (2D_rμ/π)(ω² + a²)/Δ — eq. (2)-(3).
* ``"rakhmanin-firsov-2"``: K = D_r e^{−μ|τ|}(cos λτ + (μ/λ) sin λ|τ|), S₁ = (4D_rμ/π) a²/Δ — eq. (4).
* ``"rakhmanin-firsov-3"``: K = D_r e^{−μ|τ|}(cos λτ − (μ/λ) sin λ|τ|), S₁ = (4D_rμ/π) ω²/Δ —
  the paper's third variant *corrected* (erratum: as printed, S₁ = 2D_rμω²/Δ integrates to
  (π/2)D_r and the printed correlation is garbled). The spectrum as printed is the paper's
  reproduction, :class:`seahelm.studies.sushchenko2010.RakhmaninFirsov3Printed`; pass the class
  (or an instance) wherever a spectrum name is taken.

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

import dataclasses
import functools
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .._validate import check_positive, lookup_name
from ..constants import GRAVITY
from ..errors import ParameterError
from .rational_spectra import (
    RakhmaninFirsov1,
    RakhmaninFirsov2,
    RakhmaninFirsov3,
)
from .sea_state import sea_state_parameters
from .spectrum_base import WaveSpectrum, significant_height_from_h3, spectral_moment

__all__ = [
    "PiersonMoskowitz",
    "Jonswap",
    "Bretschneider",
    "SPECTRA",
    "PRINTED_SPECTRA",
    "spectrum_names",
    "get_spectrum",
    "sea_spectrum",
    "sea_spectrum_names",
    "SEA_BOUNDS",
    "spectrum_from_wave_height",
]


# ---------------------------------------------------------------------------------------------
# Standard spectra by Hs / Tp
# ---------------------------------------------------------------------------------------------


def _default_peak_period(h3: float, level: str, table: Any, extrapolate: bool) -> float:
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
        table: Any = "corrected",
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
        table : str or Table2Version, optional
            Version of Table 2 (default "corrected", see
            :func:`~seahelm.environment.sea_state.sea_state_parameters`).
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
        table: Any = "corrected",
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
        table : str or Table2Version, optional
            Version of Table 2 (default "corrected", see
            :func:`~seahelm.environment.sea_state.sea_state_parameters`).
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


#: Registry of spectra by name. Values are classes; build one with :func:`get_spectrum` or
#: :func:`spectrum_from_wave_height`.
SPECTRA: Mapping[str, type[WaveSpectrum]] = MappingProxyType(
    {
        "rakhmanin-firsov-1": RakhmaninFirsov1,
        "rakhmanin-firsov-2": RakhmaninFirsov2,
        "rakhmanin-firsov-3": RakhmaninFirsov3,
        "pierson-moskowitz": PiersonMoskowitz,
        "jonswap": Jonswap,
        "bretschneider": Bretschneider,
        "ittc": Bretschneider,
    }
)


#: Spectra as printed in a paper, by name: reachable wherever a spectrum is named (a scenario
#: file, :func:`get_spectrum`, the CLI) though they live with the paper's reproduction, as
#: ``"module:attribute"`` references resolved on first use (:func:`seahelm.registry.lookup`).
PRINTED_SPECTRA: Mapping[str, str] = MappingProxyType({
    "rakhmanin-firsov-3-printed": "seahelm.studies.sushchenko2010:RakhmaninFirsov3Printed",
})


def spectrum_names() -> tuple[str, ...]:
    """Every spectrum name: those of :data:`SPECTRA`, then the printed ones
    (:data:`PRINTED_SPECTRA`)."""
    return tuple(SPECTRA) + tuple(PRINTED_SPECTRA)


def _spectrum_class(name: str) -> type[WaveSpectrum]:
    if isinstance(name, str) and name in PRINTED_SPECTRA:
        from ..registry import lookup

        return lookup("spectrum", PRINTED_SPECTRA, name, type)
    return lookup_name("spectrum", SPECTRA, name, error=ParameterError, quoted=True,
                       valid=spectrum_names())


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


#: Bounds of a sea by Hs [m], Tp [s] and γ [-] (:func:`sea_spectrum`): (low, high, low open).
#: Beyond them the spectra and the RAOs overflow (Hs or Tp of 1e300 and Tp of 1e-300 raised
#: OverflowError); every value inside computes finite response moments (measured at each end).
SEA_BOUNDS: Mapping[str, tuple[float, float, bool]] = MappingProxyType({
    "significant_height": (0.0, 100.0, True),
    "peak_period": (0.1, 1000.0, False),
    "gamma": (1.0, 20.0, False),
})
_SEA_UNITS = {"significant_height": "m", "peak_period": "s", "gamma": "-"}
_SEA_SYMBOLS = {"significant_height": "Hs", "peak_period": "Tp", "gamma": "γ"}


def sea_spectrum_names() -> tuple[str, ...]:
    """The names of :data:`SPECTRA` whose spectrum is given by a significant height Hs (and,
    as it declares, Tp and γ): what :func:`sea_spectrum` builds.

    Returns
    -------
    tuple of str
    """
    return tuple(n for n, cls in SPECTRA.items()
                 if any(f.name == "significant_height" and f.init
                        for f in dataclasses.fields(cls)))


def sea_spectrum(name: str, *, significant_height: float, peak_period: float | None = None,
                 gamma: float | None = None) -> WaveSpectrum:
    """A spectrum of the sea given by Hs, Tp and γ, each parameter taken by the spectra that
    declare it (a field of the spectrum's class): Tp by ``jonswap`` and ``bretschneider``
    (``ittc``), required there; γ by ``jonswap`` (default 3.3); Pierson–Moskowitz by Hs
    alone (its peak follows from it).

    Parameters
    ----------
    name : str
        A key of :data:`SPECTRA` (or of :data:`PRINTED_SPECTRA`).
    significant_height : float
        Hs [m], in (0, 100].
    peak_period : float, optional
        Tp [s], in [0.1, 1000], for the spectra that take it.
    gamma : float, optional
        JONSWAP's peak enhancement γ [-], in [1, 20].

    Returns
    -------
    WaveSpectrum

    Raises
    ------
    ParameterError
        Naming the parameter (``field``): a value outside :data:`SEA_BOUNDS`, a parameter the
        spectrum does not take, a required one missing; an unknown name (listing the valid
        ones).
    """
    cls = _spectrum_class(name)
    takes = {f.name: f for f in dataclasses.fields(cls) if f.init}
    given = {"significant_height": significant_height, "peak_period": peak_period,
             "gamma": gamma}
    for key, value in given.items():
        if value is None:
            field = takes.get(key)
            if field is not None and field.default is dataclasses.MISSING:
                raise ParameterError(f"is required for {name} [{_SEA_UNITS[key]}]", field=key,
                                     unit=_SEA_UNITS[key])
            continue
        if key not in takes:
            raise ParameterError(
                f"is not taken by {name} (of Hs, Tp, γ it takes "
                f"{', '.join(_SEA_SYMBOLS[k] for k in given if k in takes) or 'none'}); drop it "
                "or choose a spectrum that takes it", field=key,
                unit=_SEA_UNITS[key], value=value)
        low, high, low_open = SEA_BOUNDS[key]
        if not (math.isfinite(value) and (value > low if low_open else value >= low)
                and value <= high):
            raise ParameterError(f"must be in {'(' if low_open else '['}{low:g}, {high:g}] "
                                 f"[{_SEA_UNITS[key]}], got {value!r}", field=key,
                                 unit=_SEA_UNITS[key], value=value)
    return cls(**{k: v for k, v in given.items() if v is not None})


def spectrum_from_wave_height(spectrum: str | type[WaveSpectrum] | WaveSpectrum, h3: float,
                              **kwargs: Any) -> WaveSpectrum:
    """A spectrum for a 3 %-exceedance wave height h3% [m].

    Rakhmanin–Firsov variants take D_r = 0.143 (h3%/2)² and μ, λ from Table 2 (keywords
    ``level``, ``table``); Hs/Tp spectra take Hs = 4√D_r (same m0) and, where needed,
    Tp = 2π/λ unless ``peak_period`` is given. An object is returned unchanged.

    Parameters
    ----------
    spectrum : str, WaveSpectrum class or WaveSpectrum
        Registry name of the spectrum (e.g. "rakhmanin-firsov-2", "jonswap"), a spectrum class
        with a ``from_wave_height`` constructor (e.g. the paper's printed third spectrum,
        :class:`seahelm.studies.sushchenko2010.RakhmaninFirsov3Printed`) or a spectrum.
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
    if isinstance(spectrum, type) and issubclass(spectrum, WaveSpectrum):
        cls = spectrum
    else:
        cls = _spectrum_class(spectrum)  # type: ignore[arg-type]
    return cls.from_wave_height(h3, **kwargs)  # type: ignore[attr-defined]
