"""Short-term statistics of a Gaussian response from its spectral moments m0, m2, m4.

A linear response to a stationary Gaussian sea is a zero-mean Gaussian process x(t) with
spectral moments m_n = ∫ ω_eⁿ S_R(ω_e) dω_e (:mod:`.frequency_domain` computes them).
Its short-term statistics follow from them alone:

* RMS σ = √m0; **significant amplitude** 2√m0 (the mean of the highest third of the
  amplitudes of a narrow-band process, Rayleigh); **significant height** (double amplitude,
  crest to trough) 4√m0. The convention in seahelm: "significant amplitude" is 2√m0,
  "significant height" 4√m0 (as H_s = 4√m0 of the waves).
* Mean zero up-crossing period T_z = 2π√(m0/m2), mean period between maxima
  T_c = 2π√(m2/m4), spectral bandwidth ε = √(1 − m2²/(m0 m4)) (Cartwright & Longuet-Higgins
  1956).
* Up-crossing rate of a level x (Rice 1944–45): ν_x = (1/T_z) exp(−x²/(2m0)).
* **Probability of exceeding x at least once in a time T**, the up-crossings of a high level
  being a Poisson process (Ochi 1998; Lloyd 1989): P = 1 − exp(−(T/T_z) exp(−x²/(2m0))).
  ``both_sides=True`` counts crossings of +x and of −x (``|x(t)| > x``: a roll angle to
  either side), which doubles the rate. The same expression is the probability that the largest of
  N = T/T_z Rayleigh-distributed amplitudes exceeds x, 1 − (1 − e^{−x²/2m0})^N, in the limit
  of small e^{−x²/2m0} (the Poisson limit).
* **Most probable maximum** of N amplitudes (narrow band, Rayleigh; Ochi 1998, Price & Bishop
  1974): x̂_N = √(2 m0 ln N), the mode of the largest amplitude's distribution for large N.

References
----------
Rice, S. O. (1944, 1945). Mathematical analysis of random noise. Bell System Technical
Journal 23, 282–332; 24, 46–156.
Cartwright, D. E., Longuet-Higgins, M. S. (1956). The statistical distribution of the maxima
of a random function. Proc. R. Soc. London A 237, 212–232.
Price, W. G., Bishop, R. E. D. (1974). Probabilistic Theory of Ship Dynamics. Chapman & Hall.
Lloyd, A. R. J. M. (1989). Seakeeping: Ship Behaviour in Rough Weather. Ellis Horwood.
Ochi, M. K. (1998). Ocean Waves: The Stochastic Approach. Cambridge University Press.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..._validate import as_float_array, check_nonnegative, check_positive
from ...errors import ParameterError

__all__ = [
    "significant_amplitude",
    "significant_height",
    "zero_crossing_period",
    "crest_period",
    "spectral_bandwidth",
    "upcrossing_rate",
    "exceedance_probability",
    "most_probable_maximum",
]


def _moment(name: str, value: ArrayLike, unit: str) -> np.ndarray:
    m = as_float_array(name, value, unit)
    check_nonnegative(name, m, unit)
    return m


def significant_amplitude(m0: ArrayLike) -> np.ndarray:
    """Significant amplitude 2√m0 (module docstring) [unit of the response].

    Parameters
    ----------
    m0 : array_like
        Zeroth spectral moment (the variance) [unit²], >= 0.

    Returns
    -------
    numpy.ndarray
    """
    return 2.0 * np.sqrt(_moment("m0", m0, "unit^2"))


def significant_height(m0: ArrayLike) -> np.ndarray:
    """Significant height (double amplitude) 4√m0 [unit of the response].

    Parameters
    ----------
    m0 : array_like
        Zeroth spectral moment [unit²], >= 0.

    Returns
    -------
    numpy.ndarray
    """
    return 4.0 * np.sqrt(_moment("m0", m0, "unit^2"))


def zero_crossing_period(m0: ArrayLike, m2: ArrayLike) -> np.ndarray:
    """Mean zero up-crossing period T_z = 2π√(m0/m2) [s]; NaN where m0 = 0 (no response).

    Parameters
    ----------
    m0 : array_like
        Zeroth spectral moment [unit²], >= 0.
    m2 : array_like
        Second moment [unit²/s²], >= 0.

    Returns
    -------
    numpy.ndarray
    """
    a, b = _moment("m0", m0, "unit^2"), _moment("m2", m2, "unit^2/s^2")
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a > 0, 2.0 * math.pi * np.sqrt(a / b), np.nan)


def crest_period(m2: ArrayLike, m4: ArrayLike) -> np.ndarray:
    """Mean period between maxima T_c = 2π√(m2/m4) [s]; NaN where m2 = 0.

    Parameters
    ----------
    m2 : array_like
        Second moment [unit²/s²], >= 0.
    m4 : array_like
        Fourth moment [unit²/s⁴], >= 0.

    Returns
    -------
    numpy.ndarray
    """
    a, b = _moment("m2", m2, "unit^2/s^2"), _moment("m4", m4, "unit^2/s^4")
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a > 0, 2.0 * math.pi * np.sqrt(a / b), np.nan)


def spectral_bandwidth(m0: ArrayLike, m2: ArrayLike, m4: ArrayLike) -> np.ndarray:
    """ε = √(1 − m2²/(m0 m4)) [-] (Cartwright & Longuet-Higgins 1956); NaN where m0 m4 = 0.

    Parameters
    ----------
    m0, m2, m4 : array_like
        Spectral moments of order 0, 2, 4, >= 0.

    Returns
    -------
    numpy.ndarray
        0 for a narrow-band process, 1 for a wide-band one.
    """
    a = _moment("m0", m0, "unit^2")
    b = _moment("m2", m2, "unit^2/s^2")
    c = _moment("m4", m4, "unit^2/s^4")
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(a * c > 0, 1.0 - b * b / (a * c), np.nan)
    return np.sqrt(np.clip(r, 0.0, 1.0))


def upcrossing_rate(level: ArrayLike, m0: ArrayLike, m2: ArrayLike) -> np.ndarray:
    """Mean rate of up-crossings of ``level``, ν_x = √(m2/m0)/(2π) exp(−x²/(2m0)) [1/s].

    Rice (1944–45). 0 where m0 = 0.

    Parameters
    ----------
    level : array_like
        The level x [unit of the response], > 0.
    m0 : array_like
        Zeroth spectral moment [unit²], >= 0.
    m2 : array_like
        Second moment [unit²/s²], >= 0.

    Returns
    -------
    numpy.ndarray
        Broadcast over the inputs.
    """
    x = as_float_array("level", level, "unit")
    check_positive("level", x, "unit of the response")
    a, b = _moment("m0", m0, "unit^2"), _moment("m2", m2, "unit^2/s^2")
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        rate = np.sqrt(b / a) / (2.0 * math.pi) * np.exp(-x * x / (2.0 * a))
    return np.where(a > 0, rate, 0.0)


def exceedance_probability(level: ArrayLike, duration: ArrayLike, m0: ArrayLike,
                           m2: ArrayLike, *, both_sides: bool = False) -> np.ndarray:
    """P(the response exceeds ``level`` at least once in ``duration``) [-].

    P = 1 − exp(−ν T), ν = (1/T_z) exp(−x²/(2m0)) the up-crossing rate of x, the crossings
    of a high level taken as a Poisson process (module docstring; Ochi 1998, Lloyd 1989).

    Parameters
    ----------
    level : array_like
        Threshold x [unit of the response, e.g. rad for roll], > 0.
    duration : array_like
        Exposure time T [s], > 0.
    m0 : array_like
        Zeroth spectral moment [unit²], >= 0.
    m2 : array_like
        Second moment [unit²/s²], >= 0.
    both_sides : bool, optional
        Count crossings of −x too (``|x(t)| > x``; the rate doubles). Default False: +x only.

    Returns
    -------
    numpy.ndarray
        Broadcast over the inputs; 0 where m0 = 0.

    Raises
    ------
    ParameterError
        If ``level`` or ``duration`` is not > 0, or a moment is negative or NaN.
    """
    t = as_float_array("duration", duration, "s")
    check_positive("duration", t, "s")
    rate = upcrossing_rate(level, m0, m2) * (2.0 if both_sides else 1.0)
    return -np.expm1(-rate * t)


def most_probable_maximum(m0: ArrayLike, n_cycles: ArrayLike) -> np.ndarray:
    """Most probable largest of N Rayleigh amplitudes x̂_N = √(2 m0 ln N) [unit].

    Narrow-band asymptote (Ochi 1998; Price & Bishop 1974); N = T/T_z for a time T.

    Parameters
    ----------
    m0 : array_like
        Zeroth spectral moment [unit²], >= 0.
    n_cycles : array_like
        Number of amplitudes (cycles) N [-], > 1.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    ParameterError
        If N <= 1 (ln N <= 0: no maximum to speak of) or m0 < 0.
    """
    a = _moment("m0", m0, "unit^2")
    n = as_float_array("n_cycles", n_cycles, "-")
    if not np.all(n > 1):
        raise ParameterError(f"must be > 1 [-], got {n_cycles!r}", field="n_cycles",
                             unit="-", value=n_cycles)
    return np.sqrt(2.0 * a * np.log(n))
