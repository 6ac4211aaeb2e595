"""Wind gusts: the turbulent part of the wind speed from a gust spectrum.

The wind speed at height z is the mean U plus a zero-mean Gaussian fluctuation u(t) whose
one-sided spectrum S(f) [m²/s² per Hz] is a gust spectrum (registry :data:`GUST_SPECTRA`):

``"norsok"``
    The Frøya/NORSOK spectrum (NORSOK N-003; ISO 19901-1; also in Fossen 2021, §10.1),
    fitted to measurements over the Norwegian sea::

        S(f) = 320 (U/10)² (z/10)^0.45 / (1 + x^n)^(5/(3n)),
        x = 172 f (z/10)^(2/3) (U/10)^(-0.75),  n = 0.468,

    f in Hz, U the one-hour mean wind speed at 10 m [m/s], z the height [m]. At high
    frequencies S ∝ f^(-5/3) (Kolmogorov's inertial range).

A realisation is drawn by harmonic superposition (:func:`gust_realisation`): components at a
random frequency inside each of ``n_components`` logarithmically spaced bands from 1/3600 Hz
(the spectrum's one-hour averaging period) to min(1 Hz, the grid's Nyquist frequency), with
amplitude √(2 S(f_k) Δf_k) and a random phase; its variance is the spectrum's integral over
that band. Each run of a batch draws its own seeded realisation.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .._validate import as_float_array, check_positive, lookup_name, uniform_time_step
from ..errors import ParameterError

__all__ = ["GustSpectrum", "GUST_SPECTRA", "norsok_spectrum", "gust_realisation"]

#: The band of the harmonic superposition: one hour to one second.
F_MIN, F_MAX = 1.0 / 3600.0, 1.0


def norsok_spectrum(f: Any, mean_speed: float, height: float = 10.0) -> np.ndarray:
    """The NORSOK (Frøya) gust spectrum S(f) [m²/s²/Hz] (module docstring).

    Parameters
    ----------
    f : array_like
        Frequency [Hz] (≥ 0).
    mean_speed : float
        One-hour mean wind speed at 10 m, U [m/s] (> 0).
    height : float, optional
        Height above the sea z [m] (> 0; default 10).

    Returns
    -------
    numpy.ndarray
        S(f), the shape of ``f``.
    """
    f = as_float_array("f", f, "Hz")
    if np.any(f < 0):
        raise ParameterError(f"`f` must be >= 0 [Hz], got {f[f < 0].flat[0]!r}")
    check_positive("mean_speed", mean_speed, "m/s")
    check_positive("height", height, "m")
    n = 0.468
    x = 172.0 * f * (height / 10.0) ** (2.0 / 3.0) * (mean_speed / 10.0) ** -0.75
    return (320.0 * (mean_speed / 10.0) ** 2 * (height / 10.0) ** 0.45
            / (1.0 + x ** n) ** (5.0 / (3.0 * n)))


@dataclasses.dataclass(frozen=True)
class GustSpectrum:
    """A gust spectrum of the registry: ``density(f, mean_speed, height)`` [m²/s²/Hz]."""

    name: str
    description: str
    density: Callable[..., np.ndarray]


#: Gust spectra by name.
GUST_SPECTRA: dict[str, GustSpectrum] = {
    "norsok": GustSpectrum("norsok", "Frøya/NORSOK N-003 gust spectrum (Fossen 2021, §10.1)",
                           norsok_spectrum),
}


def get_gust_spectrum(name: "str | GustSpectrum") -> GustSpectrum:
    """A gust spectrum by name (unknown names list the valid ones)."""
    if isinstance(name, GustSpectrum):
        return name
    return lookup_name("gust spectrum", GUST_SPECTRA, name, error=ParameterError)


def gust_realisation(t: Any, mean_speed: float, seed: Any, *, spectrum: str = "norsok",
                     height: float = 10.0, n_components: int = 200) -> np.ndarray:
    """One seeded realisation of the gust u(t) [m/s] on a uniform grid (module docstring).

    Parameters
    ----------
    t : array_like
        Uniform time grid [s] (2 or more samples).
    mean_speed : float
        One-hour mean wind speed U [m/s] (> 0).
    seed : int, SeedSequence or Generator
        The realisation.
    spectrum : str or GustSpectrum, optional
        A name in :data:`GUST_SPECTRA` (default "norsok").
    height : float, optional
        Height z [m] (default 10).
    n_components : int, optional
        Harmonic components (default 200).

    Returns
    -------
    numpy.ndarray
        u(t), zero mean in expectation, the shape of ``t``.
    """
    spec = get_gust_spectrum(spectrum)
    t, dt = uniform_time_step(t, "a gust")
    if isinstance(n_components, bool) or int(n_components) != n_components or n_components < 1:
        raise ParameterError(f"`n_components` must be an integer >= 1, got {n_components!r}")
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    f_max = min(F_MAX, 0.5 / dt)
    if not f_max > F_MIN:
        raise ParameterError(f"the time step {dt:g} s is too long for gusts "
                             f"(the grid must resolve periods under one hour)")
    edges = np.geomspace(F_MIN, f_max, int(n_components) + 1)
    freq = edges[:-1] + rng.random(int(n_components)) * np.diff(edges)
    amp = np.sqrt(2.0 * spec.density(freq, mean_speed, height) * np.diff(edges))
    phase = rng.uniform(0.0, 2.0 * math.pi, int(n_components))
    out = np.empty_like(t)
    for start in range(0, t.size, 4096):  # (components × samples in blocks: bounded memory)
        block = t[start:start + 4096]
        out[start:start + 4096] = amp @ np.cos(2.0 * math.pi * freq[:, None] * block[None, :]
                                               + phase[:, None])
    return out
