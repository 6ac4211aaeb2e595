"""Plots of wave spectra and disturbance realisations (like Sushchenko & Lutsko (2010), figure).

The paper's figure itself, which also draws the printed eq. (7) filter, is the study's
:func:`seahelm.studies.sushchenko2010.plot_paper_figure`.

matplotlib is imported inside the functions; every function takes ``ax=`` (or ``fig=``) and
returns what it drew on.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._validate import lookup_name
from ..environment.sea_state import TABLE1, TABLE2, wave_height_range

__all__ = [
    "grade_wave_height",
    "grade_label",
    "spectrum_unit",
    "plot_spectrum",
    "plot_sea_state_spectra",
    "plot_realisations",
]

_LINESTYLES = ("-", "--", ":")


def grade_wave_height(grade: int | str) -> float:
    """Representative h3% [m] of a sea-state grade: the middle of its Table 1 range, clipped to
    the 1…10 m covered by Table 2 (grade IX, open above 11 m, is drawn at 10 m).

    Parameters
    ----------
    grade : int or str
        Sea-state grade (Table 1), e.g. 6 or "VI".

    Returns
    -------
    float
        h3% [m].
    """
    lo, hi = wave_height_range(grade)
    hs = TABLE2["corrected"][:, 0]
    mid = 0.5 * (lo + hi) if np.isfinite(hi) else lo
    return float(np.clip(mid, hs[0], hs[-1]))


_ROMAN = ("I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX")

#: Unit of each wave quantity whose spectrum is plotted (the spectrum's is unit²·s/rad).
_QUANTITY_UNITS = {"ordinate": "m", "ordinate_rate": "m/s", "slope": "rad",
                   "slope_rate": "rad/s", "slope_acceleration": "rad/s²"}


def grade_label(grade: int | str, wave_height: float) -> str:
    """A figure label for a sea-state grade drawn at ``wave_height``, in Table 1's words.

    The grade is written as in Table 1 (Roman numerals); a height outside the grade's Table 1
    range says so (grade IX, open above 11 m, is drawn at Table 2's last row, 10 m:
    ``"sea state IX (h3% ≥ 11 m), drawn at 10 m"``).

    Parameters
    ----------
    grade : int or str
        Sea-state grade, e.g. 6 or "VI".
    wave_height : float
        h3% [m] at which the grade is drawn.

    Returns
    -------
    str
        E.g. ``"sea state VI (h3% = 4.75 m)"``.
    """
    lo, hi = wave_height_range(grade)
    roman = _ROMAN[next(g for g, bounds in TABLE1.items() if bounds == (lo, hi)) - 1]
    if lo <= wave_height < hi:
        return f"sea state {roman} (h3% = {wave_height:g} m)"
    return f"sea state {roman} (h3% ≥ {lo:g} m), drawn at {wave_height:g} m"


def spectrum_unit(spectrum: Any) -> str:
    """The unit of a spectral density S₁(ω): the quantity's unit squared per rad/s.

    The ordinate's spectrum is in m²·s/rad, the slope's (eq. (5)) in rad²·s/rad; a derivative
    spectrum is recognised by its ``label`` (``ordinate_rate``, ``slope``, ...).

    Parameters
    ----------
    spectrum : WaveSpectrum
        A wave spectrum (of the ordinate unless it is a labelled derivative spectrum).

    Returns
    -------
    str
        E.g. ``"m²·s/rad"``.
    """
    from ..environment.rational_spectra import DerivativeSpectrum

    quantity = spectrum.label if isinstance(spectrum, DerivativeSpectrum) else "ordinate"
    unit = _QUANTITY_UNITS.get(quantity)
    if unit is None:
        return "unit²·s/rad"  # a derivative whose quantity is not named here
    return f"({unit})²·s/rad" if "/" in unit else f"{unit}²·s/rad"


def _axes(ax: Any) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.figure().add_subplot()


def plot_spectrum(
    spectrum: Any,
    *,
    ax: Any = None,
    omega: np.ndarray | None = None,
    label: str | None = None,
    **line_kw: Any,
) -> Any:
    """Plot a one-sided spectrum S₁(ω) (eq. (1) convention) against ω [rad/s].

    Parameters
    ----------
    spectrum : WaveSpectrum
        Spectrum with a ``one_sided(omega)`` method.
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).
    omega : array_like, optional
        Frequencies ω [rad/s] (default 0…4 rad/s, 801 points).
    label : str, optional
        Legend label (default: the spectrum's name).
    **line_kw
        Passed to ``ax.plot``.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    w = np.linspace(0.0, 4.0, 801) if omega is None else np.asarray(omega, float)
    ax.plot(w, spectrum.one_sided(w), label=label or getattr(spectrum, "name", None), **line_kw)
    ax.set_xlabel("ω [rad/s]")
    ax.set_ylabel(f"S₁(ω) [{spectrum_unit(spectrum)}] (one-sided)")
    return ax


def plot_sea_state_spectra(
    model: str = "rakhmanin-firsov-1",
    grades: Sequence[int] = (3, 6, 9),
    *,
    quantity: str = "ordinate",
    table: str = "corrected",
    ax: Any = None,
    omega: np.ndarray | None = None,
) -> Any:
    """Spectra of the wave ordinate or slope (eq. (5)) for several sea-state grades.

    Solid, dashed and dotted lines as in the paper's figure (panels a–d).

    Parameters
    ----------
    model : str, optional
        Spectrum name (default "rakhmanin-firsov-1").
    grades : sequence of int, optional
        Sea-state grades (default 3, 6, 9).
    quantity : {"ordinate", "slope"}, optional
        Wave ordinate or slope spectrum (default "ordinate").
    table : str, optional
        Version of Table 2 (default "corrected").
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).
    omega : array_like, optional
        Frequencies ω [rad/s] (default 0…4 rad/s).

    Returns
    -------
    matplotlib Axes
    """
    from ..environment.rational_spectra import slope_spectrum
    from ..environment.spectra import spectrum_from_wave_height

    transforms = {"ordinate": lambda s: s, "slope": slope_spectrum}
    transform = lookup_name("quantity", transforms, quantity, quoted=True)
    ax = _axes(ax)
    for i, g in enumerate(grades):
        h3 = grade_wave_height(g)
        spec = transform(spectrum_from_wave_height(model, h3, table=table))
        plot_spectrum(
            spec, ax=ax, omega=omega, label=grade_label(g, h3),
            linestyle=_LINESTYLES[i % len(_LINESTYLES)], color="k",
        )
    ax.set_title(f"{model}: {quantity}")
    ax.legend(loc="upper right", fontsize="small")
    return ax


def plot_realisations(
    samples: Any, output: str | None = None, *, runs: Sequence[int] = (0,), ax: Any = None
) -> Any:
    """Plot realisations from :meth:`seahelm.environment.shaping.StateSpaceFilter.sample`.

    Parameters
    ----------
    samples : FilterSamples
        Result of :meth:`~seahelm.environment.shaping.StateSpaceFilter.sample`.
    output : str, optional
        Output label to draw (default: the first).
    runs : sequence of int, optional
        Runs to draw (default: run 0).
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    label = output or samples.labels[0]
    data = samples[label]
    unit = samples.units[samples.labels.index(label)]
    for r in runs:
        ax.plot(samples.time, data[r], label=f"run {r}", lw=0.8)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{label} [{unit}]")
    return ax
