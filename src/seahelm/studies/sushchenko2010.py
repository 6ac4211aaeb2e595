"""Sushchenko & Lutsko (2010): sea-wave disturbances — the paper's reproduction.

The reusable parts are components: the sea-state tables (Table 1 and the corrected Table 2) in
:mod:`seahelm.environment.sea_state`, the Rakhmanin–Firsov spectra of eq. (2)-(4) (the third
one corrected) and their derivative spectra of eq. (5) in
:mod:`seahelm.environment.rational_spectra`, the spectrum registry in
:mod:`seahelm.environment.spectra`, the correct shaping filters in
:mod:`seahelm.environment.shaping`, the encounter frequency in
:mod:`seahelm.environment.encounter` and the regular motions in
:mod:`seahelm.environment.motion`. This module holds what only reproducing the paper needs, the
printed variants as objects next to the corrected ones:

* :data:`PRINTED_TABLE2` — Table 2 exactly as printed (λ_mean(4 m) = 0.667,
  μ_min(1 m) = 0.138), registry :data:`TABLE2_VERSIONS` with
  :data:`~seahelm.environment.sea_state.CORRECTED_TABLE2` (``"corrected"``, the default) and
  it (``"printed"``);
* :class:`RakhmaninFirsov3Printed` — the third spectrum as printed (it integrates to
  (π/2)·D_r), registry :data:`SPECTRA` (the component spectra and
  ``"rakhmanin-firsov-3-printed"``), :func:`spectrum_from_wave_height` by name from both;
* :data:`PRINTED_ORDINATE`, :data:`PRINTED_EQ6`, :data:`PRINTED_EQ7` — the shaping filters as
  printed (damping 2λ instead of 2μ; eq. (6) biproper), registry :data:`PRINTED_FILTERS`,
  :func:`paper_filter` builds one;
* :func:`plot_paper_figure` — the paper's six-panel figure with the corrected models and, for
  comparison, a realisation of the printed eq. (7) filter (``seahelm waves figure``).

Errata these variants reproduce (verified by exact integration, Lyapunov equations and Monte
Carlo): the printed third spectrum S₁ = 2D_rμω²/Δ integrates to (π/2)·D_r (corrected:
4D_rμω²/(πΔ)); the factorisation before eq. (6) has a sign slip, so the printed filter has the
poles −λ ± jμ and gives only (μ/λ)·D_r ≈ 0.21·D_r output variance (corrected: damping 2μ);
eq. (6) is biproper (infinite output variance) and (6)-(7) carry an extra √(μ² + λ²);
Table 2 has the two misprints above.

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010). Modelling of external disturbances in
stabilisation and heading systems of marine vehicles (in Ukrainian). Eq. (1)-(7), Tables 1-2
and the figure.
"""

from __future__ import annotations

import abc
import dataclasses
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .._validate import check_positive
from ..constants import GRAVITY
from ..environment import spectra as _spectra
from ..environment.rational_spectra import RakhmaninFirsov3
from ..environment.sea_state import CORRECTED_TABLE2, Table2Version
from ..environment.shaping import StateSpaceFilter, from_transfer_functions
from ..environment.spectrum_base import WaveSpectrum
from ..errors import ParameterError
from ..registry import lookup

__all__ = [
    "PRINTED_TABLE2",
    "TABLE2_VERSIONS",
    "get_table2",
    "RakhmaninFirsov3Printed",
    "SPECTRA",
    "spectrum_from_wave_height",
    "PrintedFilter",
    "PRINTED_ORDINATE",
    "PRINTED_EQ6",
    "PRINTED_EQ7",
    "PRINTED_FILTERS",
    "paper_filter",
    "plot_paper_figure",
]

# ---------------------------------------------------------------------------------------------
# Table 2 as printed
# ---------------------------------------------------------------------------------------------

#: Table 2 exactly as printed: h3% [m], then
#: :data:`~seahelm.environment.sea_state.TABLE2_COLUMNS`. Two misprints: λ_mean(4 m) = 0.667
#: (every column follows h^(-1/2) and μ_mean/λ_mean is 0.213-0.214 elsewhere: ≈ 0.867) and
#: μ_min(1 m) = 0.138 (μ_min/λ_min is 0.150 elsewhere: ≈ 0.188).
PRINTED_TABLE2 = Table2Version(
    "printed",
    np.array(
        [
            [1, 0.56, 0.374, 0.138, 2.24, 1.745, 1.25, 0.215],
            [2, 0.394, 0.265, 0.136, 1.573, 1.239, 0.905, 0.214],
            [3, 0.316, 0.214, 0.111, 1.266, 1.003, 0.74, 0.213],
            [4, 0.274, 0.185, 0.096, 1.094, 0.667, 0.64, 0.213],
            [5, 0.246, 0.166, 0.086, 0.982, 0.777, 0.572, 0.213],
            [6, 0.224, 0.151, 0.078, 0.898, 0.709, 0.52, 0.213],
            [7, 0.207, 0.14, 0.072, 0.828, 0.654, 0.48, 0.214],
            [8, 0.194, 0.131, 0.068, 0.774, 0.612, 0.45, 0.214],
            [9, 0.184, 0.123, 0.063, 0.734, 0.578, 0.422, 0.213],
            [10, 0.177, 0.119, 0.061, 0.706, 0.555, 0.404, 0.214],
        ]
    ),
    "as printed in Sushchenko & Lutsko (2010)",
)

#: Table 2 by name: ``"corrected"`` (the default everywhere) and ``"printed"``.
TABLE2_VERSIONS: Mapping[str, Table2Version] = MappingProxyType(
    {"corrected": CORRECTED_TABLE2, "printed": PRINTED_TABLE2})


def get_table2(table: str | Table2Version) -> Table2Version:
    """A version of Table 2 by name (``"corrected"``, ``"printed"``) or the version itself.

    Parameters
    ----------
    table : str or Table2Version
        A key of :data:`TABLE2_VERSIONS` or a version object.

    Returns
    -------
    Table2Version

    Raises
    ------
    ParameterError
        For an unknown name (the message lists the valid ones).
    """
    return lookup("Table 2 version", TABLE2_VERSIONS, table, Table2Version, error=ParameterError)


# ---------------------------------------------------------------------------------------------
# The third spectrum as printed
# ---------------------------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True, kw_only=True)
class RakhmaninFirsov3Printed(RakhmaninFirsov3):
    """The third Rakhmanin–Firsov spectrum exactly as printed (for reproducing the paper).

    S₁(ω) = 2D_rμω²/(ω⁴ + 2(μ² − λ²)ω² + (μ² + λ²)²), which integrates to (π/2)D_r, not D_r
    (Sushchenko & Lutsko (2010), spectrum after eq. (4); erratum). :attr:`variance` is the
    nominal D_r parameter; the true variance is :attr:`actual_variance` = (π/2)D_r.
    The correlation returned is that of the corrected shape times π/2 (the printed one is
    garbled and not a valid correlation function). The corrected spectrum is
    :class:`~seahelm.environment.rational_spectra.RakhmaninFirsov3`.

    Parameters
    ----------
    variance : float
        D_r, nominal variance of the wave ordinate [m²], > 0 (e.g. 0.143 (h3%/2)²).
    decay_rate : float
        μ, decay rate of the correlation function [1/s], > 0 (Table 2).
    resonance_frequency : float
        λ, resonance frequency of the spectrum [rad/s], > 0 (Table 2).

    Raises
    ------
    ParameterError
        If a parameter is not finite and > 0 (the message names it).
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


def _with_printed(names: Mapping[str, type[WaveSpectrum]]) -> dict[str, type[WaveSpectrum]]:
    out: dict[str, type[WaveSpectrum]] = {}
    for name, cls in names.items():
        out[name] = cls
        if name == "rakhmanin-firsov-3":
            out[RakhmaninFirsov3Printed.name] = RakhmaninFirsov3Printed
    return out


#: The spectra of :data:`seahelm.environment.spectra.SPECTRA` and, after the corrected third
#: spectrum, the printed one (``"rakhmanin-firsov-3-printed"``).
SPECTRA: Mapping[str, type[WaveSpectrum]] = MappingProxyType(_with_printed(_spectra.SPECTRA))


def spectrum_from_wave_height(spectrum: str | type[WaveSpectrum] | WaveSpectrum, h3: float, *,
                              table: str | Table2Version = "corrected",
                              **kwargs: Any) -> WaveSpectrum:
    """:func:`seahelm.environment.spectra.spectrum_from_wave_height` with the paper's variants.

    Parameters
    ----------
    spectrum : str, WaveSpectrum class or WaveSpectrum
        A name of :data:`SPECTRA` (with ``"rakhmanin-firsov-3-printed"``), a class or a
        spectrum (returned unchanged).
    h3 : float
        Wave height of 3 % exceedance h3% [m].
    table : str or Table2Version, optional
        A name of :data:`TABLE2_VERSIONS` (``"corrected"``, default, or ``"printed"``) or a
        version.
    **kwargs
        Passed on (``level``, ``extrapolate``, ``peak_period``, ...).

    Returns
    -------
    WaveSpectrum

    Raises
    ------
    ParameterError
        For an unknown spectrum or table name (the message lists the valid ones).
    """
    if isinstance(spectrum, str):
        spectrum = lookup("spectrum", SPECTRA, spectrum, type, error=ParameterError)
    return _spectra.spectrum_from_wave_height(spectrum, h3, table=get_table2(table), **kwargs)


# ---------------------------------------------------------------------------------------------
# The shaping filters as printed
# ---------------------------------------------------------------------------------------------


class PrintedFilter(abc.ABC):
    """One of the paper's shaping filters exactly as printed (wrong; for reproduction only).

    All three have the printed denominator s² + 2λs + a², a = √(μ² + λ²) (erratum: the damping
    is 2μ; see :func:`seahelm.environment.shaping.shaping_filter` for the correct factors).
    """

    #: Registry name.
    name: ClassVar[str]
    #: Unit of the filter's output.
    unit: ClassVar[str]

    @abc.abstractmethod
    def numerator(self, variance: float, decay_rate: float, resonance_frequency: float,
                  gravity: float) -> np.ndarray:
        """Numerator of W(s) as printed, highest power first.

        Parameters
        ----------
        variance, decay_rate, resonance_frequency : float
            D_r [m²], μ [1/s], λ [rad/s].
        gravity : float
            g [m/s²].

        Returns
        -------
        numpy.ndarray
            Numerator coefficients.
        """

    def transfer_function(self, variance: float, decay_rate: float, resonance_frequency: float,
                          gravity: float = GRAVITY) -> tuple[np.ndarray, np.ndarray]:
        """Numerator and denominator of the printed W(s), highest power first.

        Parameters
        ----------
        variance, decay_rate, resonance_frequency : float
            D_r [m²], μ [1/s], λ [rad/s].
        gravity : float, optional
            g [m/s²].

        Returns
        -------
        tuple of numpy.ndarray
            (numerator, denominator).
        """
        a2 = decay_rate**2 + resonance_frequency**2
        den = np.array([1.0, 2.0 * resonance_frequency, a2])
        return self.numerator(variance, decay_rate, resonance_frequency, gravity), den

    def __repr__(self) -> str:
        return f"<printed filter {self.name!r}>"


class _PrintedOrdinate(PrintedFilter):
    name = "ordinate-printed"
    unit = "m"

    def numerator(self, variance: float, decay_rate: float, resonance_frequency: float,
                  gravity: float) -> np.ndarray:
        k = math.sqrt(2.0 * variance * decay_rate / math.pi)
        return np.array([k, k * math.hypot(decay_rate, resonance_frequency)])


class _PrintedEq6(PrintedFilter):
    name = "eq6"
    unit = "rad"

    def numerator(self, variance: float, decay_rate: float, resonance_frequency: float,
                  gravity: float) -> np.ndarray:
        a = math.hypot(decay_rate, resonance_frequency)
        k = math.sqrt(2.0 * variance * decay_rate * a * a / math.pi) / gravity
        return np.array([k, k * a, 0.0])


class _PrintedEq7(PrintedFilter):
    name = "eq7"
    unit = "rad"

    def numerator(self, variance: float, decay_rate: float, resonance_frequency: float,
                  gravity: float) -> np.ndarray:
        a = math.hypot(decay_rate, resonance_frequency)
        k = 2.0 * math.sqrt(variance * decay_rate * a * a / math.pi) / gravity
        return np.array([k * a, 0.0])


#: The ordinate filter of the factorisation before eq. (6) as printed (poles −λ ± jμ: output
#: variance (μ/λ)·D_r ≈ 0.21·D_r instead of D_r).
PRINTED_ORDINATE: PrintedFilter = _PrintedOrdinate()
#: The slope filter eq. (6) as printed (biproper: infinite output variance).
PRINTED_EQ6: PrintedFilter = _PrintedEq6()
#: The slope filter eq. (7) as printed (an extra √(μ² + λ²) and the wrong damping).
PRINTED_EQ7: PrintedFilter = _PrintedEq7()

#: The paper's filters as printed by name: ``"ordinate-printed"``, ``"eq6"``, ``"eq7"``.
PRINTED_FILTERS: Mapping[str, PrintedFilter] = MappingProxyType(
    {f.name: f for f in (PRINTED_ORDINATE, PRINTED_EQ6, PRINTED_EQ7)})


def paper_filter(
    name: str | PrintedFilter,
    *,
    variance: float,
    decay_rate: float,
    resonance_frequency: float,
    gravity: float = GRAVITY,
) -> StateSpaceFilter:
    """A filter of the paper exactly as printed (wrong; for reproducing the paper's figure).

    Parameters
    ----------
    name : {"ordinate-printed", "eq6", "eq7"} or PrintedFilter
        A key of :data:`PRINTED_FILTERS` or the filter object.
    variance : float
        D_r [m²], > 0.
    decay_rate : float
        μ [1/s], > 0.
    resonance_frequency : float
        λ [rad/s], > 0.
    gravity : float
        g [m/s²].

    Returns
    -------
    StateSpaceFilter

    Raises
    ------
    ParameterError
        For an unknown name (listing the valid ones) or bad parameters.
    """
    printed = lookup("paper filter", PRINTED_FILTERS, name, PrintedFilter, error=ParameterError)
    check_positive("variance", variance, "m^2")
    check_positive("decay_rate", decay_rate, "1/s")
    check_positive("resonance_frequency", resonance_frequency, "rad/s")
    check_positive("gravity", gravity, "m/s^2")
    num, den = printed.transfer_function(variance, decay_rate, resonance_frequency, gravity)
    return from_transfer_functions(
        [num], den, labels=(printed.name,), units=(printed.unit,),
        name=f"Sushchenko & Lutsko (2010) {printed.name} (as printed)")


# ---------------------------------------------------------------------------------------------
# The paper's figure
# ---------------------------------------------------------------------------------------------


def plot_paper_figure(*, fig: Any = None, seed: int = 0, duration: float = 200.0,
                      dt: float = 0.1) -> Any:
    """The six panels of Sushchenko & Lutsko (2010)'s figure, with the corrected models.

    a, b: ordinate spectra of variants 1 (eq. (3)) and 2 (eq. (4)) for sea states 3, 6, 9;
    c, d: slope spectra (eq. (5)) of both for sea states 3, 6; e: slope realisation from the
    corrected filter (s/g)W₂(s); f: from the paper's printed eq. (7) filter
    (:data:`PRINTED_EQ7`), for comparison.

    Parameters
    ----------
    fig : matplotlib Figure, optional
        Figure to draw into (default: a new one).
    seed : int, optional
        Seed of the realisations (default 0).
    duration : float, optional
        Length of the realisations [s] (default 200).
    dt : float, optional
        Sample period [s] (default 0.1).

    Returns
    -------
    matplotlib Figure
    """
    import matplotlib.pyplot as plt

    from ..environment.shaping import shaping_filter
    from ..plotting.waves import grade_wave_height, plot_realisations, plot_sea_state_spectra

    fig = fig if fig is not None else plt.figure(figsize=(11, 11))
    axs = fig.subplots(3, 2)
    for j, model in enumerate(("rakhmanin-firsov-1", "rakhmanin-firsov-2")):
        plot_sea_state_spectra(model, (3, 6, 9), ax=axs[0, j])
        plot_sea_state_spectra(model, (3, 6), quantity="slope", ax=axs[1, j])
    spec = _spectra.spectrum_from_wave_height("rakhmanin-firsov-2", grade_wave_height(6))
    good = shaping_filter(spec, ("slope",)).sample(duration=duration, dt=dt, seed=seed)
    printed = paper_filter(
        PRINTED_EQ7,
        variance=spec.variance,  # type: ignore[attr-defined]
        decay_rate=spec.decay_rate,  # type: ignore[attr-defined]
        resonance_frequency=spec.resonance_frequency,  # type: ignore[attr-defined]
    ).sample(duration=duration, dt=dt, seed=seed)
    plot_realisations(good, ax=axs[2, 0]).set_title("slope, corrected filter (s/g)·W₂")
    plot_realisations(printed, ax=axs[2, 1]).set_title("slope, eq. (7) as printed")
    fig.tight_layout()
    return fig
