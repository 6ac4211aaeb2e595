"""Directional spreading of a short-crested sea: D(θ) about the mean wave direction.

A short-crested sea has the directional spectrum S(ω, θ) = S(ω) D(θ), θ the direction of
travel of a wave component relative to the mean direction, ∫ D dθ = 1 (frequency-independent
spreading). Two families:

``"cos-n"`` (:class:`CosinePowerSpreading`, the cos² spreading for n = 2, the default)
    D(θ) = Γ(1 + n/2)/(√π Γ(1/2 + n/2)) cosⁿθ for −π/2 ≤ θ ≤ π/2, 0 beyond
    (DNV-RP-C205 (2010), eq. 3.5.8.4; n = 2: D = (2/π) cos²θ, ITTC's short-crested sea).
``"cos-2s"`` (:class:`Cos2sSpreading`)
    D(θ) = Γ(s + 1)/(2√π Γ(s + 1/2)) cos^{2s}(θ/2) for −π ≤ θ ≤ π
    (Longuet-Higgins, Cartwright & Smith 1963; s ≈ 10–25 swell-like, 1–5 wind sea).

Each gives a quadrature rule (:meth:`~CosinePowerSpreading.quadrature`): midpoint directions
over its support with weights D(θ_j) Δθ rescaled to sum to exactly 1, so a spread sea keeps
the variance of the long-crested one whatever the number of directions — what the
frequency-domain statistics integrate (:mod:`seahelm.analysis.seakeeping`); and directions
drawn with density D (:meth:`~CosinePowerSpreading.draw`, the inverse of its cumulative
distribution): what the first-order wave motions give each random wave component
(:mod:`seahelm.environment.first_order`, single summation).

References
----------
Longuet-Higgins, M. S., Cartwright, D. E., Smith, N. D. (1963). Observations of the
directional spectrum of sea waves using the motions of a floating buoy. Ocean Wave Spectra,
Prentice-Hall, 111–136.
DNV-RP-C205 (2010). Environmental conditions and environmental loads, sec. 3.5.8.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, lookup_name
from ..errors import ParameterError

__all__ = ["CosinePowerSpreading", "Cos2sSpreading", "SPREADING", "get_spreading",
           "spreading_with_parameter"]

#: Points of the tabulated cumulative distribution that :meth:`_Spreading.draw` inverts.
_TABLE_POINTS = 4097
#: Most directions of a quadrature (0.036 deg apart over the full circle).
MAX_DIRECTIONS = 10_000
#: Largest cos-2s ``s`` and cos-n ``power``: narrower spreads are long-crested seas for any
#: quadrature, and beyond them cos^{2s} underflows to 0 between the quadrature's directions
#: (measured s = 1e6: every weight 0, the moments NaN). Observed swell reaches s ~ 75
#: (Mitsuyasu et al. 1975).
MAX_S = 1000.0
MAX_POWER = 2.0 * MAX_S


def _check_count(n: Any) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not \
            1 <= n <= MAX_DIRECTIONS:
        raise ParameterError(f"must be an integer in [1, {MAX_DIRECTIONS}] [-], got {n!r}",
                             field="n_directions", unit="-", value=n)
    return int(n)


class _Spreading:
    name: ClassVar[str] = "spreading"
    #: Half-width of the support [rad]: D = 0 for |θ| beyond it.
    half_width: ClassVar[float] = math.pi

    def density(self, theta: ArrayLike) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def quadrature(self, n_directions: int = 36) -> tuple[np.ndarray, np.ndarray]:
        """Directions θ_j [rad] and weights w_j (Σ w_j = 1) of a midpoint rule over the support.

        Parameters
        ----------
        n_directions : int, optional
            Number of directions (default 36), >= 1; one direction is the long-crested sea.

        Returns
        -------
        theta, weights : numpy.ndarray, shape (n_directions,)
        """
        n = _check_count(n_directions)
        if n == 1:
            return np.zeros(1), np.ones(1)
        h = self.half_width
        theta = -h + (np.arange(n) + 0.5) * (2.0 * h / n)
        w = self.density(theta)
        return theta, w / w.sum()

    def draw(self, uniform: ArrayLike) -> np.ndarray:
        """Directions θ [rad] relative to the mean direction with density D, from uniform
        numbers in [0, 1).

        The inverse of the cumulative distribution of D, tabulated on 4,097 points over the
        support (trapezoid rule, linear in between: the distribution within 1e-6 for s, n up
        to 100).

        Parameters
        ----------
        uniform : array_like
            Numbers in [0, 1) (e.g. ``rng.random(n)``).

        Returns
        -------
        numpy.ndarray
            θ, the shape of ``uniform``.
        """
        grid = np.linspace(-self.half_width, self.half_width, _TABLE_POINTS)
        d = self.density(grid)
        cdf = np.concatenate([[0.0], np.cumsum(0.5 * (d[1:] + d[:-1]) * np.diff(grid))])
        cdf /= cdf[-1]
        keep = np.concatenate([[True], np.diff(cdf) > 0])  # strictly increasing to invert
        return np.interp(np.asarray(uniform, dtype=float), cdf[keep], grid[keep])


@dataclasses.dataclass(frozen=True)
class CosinePowerSpreading(_Spreading):
    """D(θ) = Γ(1 + n/2)/(√π Γ(1/2 + n/2)) cosⁿθ on −π/2 ≤ θ ≤ π/2 (DNV-RP-C205, eq. 3.5.8.4).

    Parameters
    ----------
    power : float
        The exponent n [-], in (0, 2000] (default 2: the cos² spreading).
    """

    name: ClassVar[str] = "cos-n"
    half_width: ClassVar[float] = 0.5 * math.pi

    power: float = 2.0

    def __post_init__(self) -> None:
        if isinstance(self.power, bool) or not (isinstance(self.power, (int, float))
                                                and math.isfinite(self.power)
                                                and 0 < self.power <= MAX_POWER):
            raise ParameterError(f"must be in (0, {MAX_POWER:g}] [-], got {self.power!r}",
                                 field="power",
                                 unit="-", value=self.power)

    def density(self, theta: ArrayLike) -> np.ndarray:
        """D(θ) [1/rad], 0 outside −π/2 ≤ θ ≤ π/2.

        Parameters
        ----------
        theta : array_like
            Direction relative to the mean direction θ [rad].

        Returns
        -------
        numpy.ndarray
        """
        t = as_float_array("theta", theta, "rad")
        n = float(self.power)
        c = math.exp(math.lgamma(1 + n / 2) - math.lgamma(0.5 + n / 2)) / math.sqrt(math.pi)
        inside = np.abs(t) <= 0.5 * math.pi
        return np.where(inside, c * np.abs(np.cos(np.where(inside, t, 0.0))) ** n, 0.0)


@dataclasses.dataclass(frozen=True)
class Cos2sSpreading(_Spreading):
    """D(θ) = Γ(s + 1)/(2√π Γ(s + 1/2)) cos^{2s}(θ/2) on −π ≤ θ ≤ π (Longuet-Higgins et al.
    1963).

    Parameters
    ----------
    s : float
        The spreading parameter s [-], in (0, 1000] (default 10).
    """

    name: ClassVar[str] = "cos-2s"
    half_width: ClassVar[float] = math.pi

    s: float = 10.0

    def __post_init__(self) -> None:
        if isinstance(self.s, bool) or not (isinstance(self.s, (int, float))
                                            and math.isfinite(self.s)
                                            and 0 < self.s <= MAX_S):
            raise ParameterError(f"must be in (0, {MAX_S:g}] [-], got {self.s!r}", field="s",
                                 unit="-",
                                 value=self.s)

    def density(self, theta: ArrayLike) -> np.ndarray:
        """D(θ) [1/rad], 0 outside −π ≤ θ ≤ π.

        Parameters
        ----------
        theta : array_like
            Direction relative to the mean direction θ [rad].

        Returns
        -------
        numpy.ndarray
        """
        t = as_float_array("theta", theta, "rad")
        s = float(self.s)
        c = math.exp(math.lgamma(s + 1) - math.lgamma(s + 0.5)) / (2.0 * math.sqrt(math.pi))
        inside = np.abs(t) <= math.pi
        return np.where(inside, c * np.abs(np.cos(0.5 * np.where(inside, t, 0.0))) ** (2 * s),
                        0.0)


#: Spreading functions by name; :func:`get_spreading` builds one.
SPREADING: Mapping[str, type] = MappingProxyType({"cos-n": CosinePowerSpreading,
                                                   "cos2": CosinePowerSpreading,
                                                   "cos-2s": Cos2sSpreading})


def get_spreading(spreading: str | Any, **params: Any) -> Any:
    """A spreading function from a name of :data:`SPREADING` and its parameters, or an object.

    Parameters
    ----------
    spreading : str or spreading object
        ``"cos2"`` (= ``"cos-n"`` with n = 2), ``"cos-n"`` (``power=``), ``"cos-2s"``
        (``s=``), or an object (returned unchanged; ``params`` must then be empty).
    **params
        The class's parameters.

    Returns
    -------
    CosinePowerSpreading or Cos2sSpreading

    Raises
    ------
    ParameterError
        For an unknown name (listing the valid ones) or bad parameters.
    """
    if isinstance(spreading, _Spreading):
        if params:
            raise ParameterError("parameters cannot be given together with a spreading object",
                                 field="spreading")
        return spreading
    cls = lookup_name("spreading", SPREADING, spreading, error=ParameterError, quoted=True,
                      field="spreading", value=spreading)
    return cls(**params)


#: The one parameter of each named spreading, for :func:`spreading_with_parameter`.
_PARAMETER = {"cos-n": "power", "cos-2s": "s"}


def spreading_with_parameter(name: str, parameter: float) -> Any:
    """``"cos-n"`` with its exponent n or ``"cos-2s"`` with its s: one number for either (as
    the scenario's ``spreading`` and ``spreading_parameter`` give them).

    Parameters
    ----------
    name : str
        ``"cos-n"`` or ``"cos-2s"``.
    parameter : float
        n or s [-], > 0.

    Returns
    -------
    CosinePowerSpreading or Cos2sSpreading

    Raises
    ------
    ParameterError
        For another name (listing the valid ones) or a parameter not > 0.
    """
    lookup_name("directional spreading", _PARAMETER, name, error=ParameterError,
                field="spreading", value=name)
    try:
        return get_spreading(name, **{_PARAMETER[name]: parameter})
    except ParameterError as exc:
        raise ParameterError(exc.reason.lstrip(": "), field="spreading_parameter", unit="-",
                             value=parameter) from None
