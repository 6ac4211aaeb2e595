"""Seeded random draws for Monte-Carlo studies: marginal distributions and correlated normals.

Every sample has its own generator: sample ``i`` of a study seeded with ``seed`` draws from
``np.random.default_rng(SeedSequence(seed, spawn_key=(i,)))`` -- the ``i``-th child of
``SeedSequence(seed).spawn(n)`` -- so a sample's values depend on the seed and its index only,
never on how the samples are split into chunks or which process draws them. Within a sample the
marginal draws are made first, in the order they are given, then the correlated blocks.

Distributions come from a registry (:data:`DISTRIBUTIONS`): ``normal`` (mean, std),
``uniform`` (low, high), ``lognormal`` (mean and std of the underlying normal),
``truncnormal`` (a normal of mean and std cut to [low, high], drawn by inverting its CDF).
A :class:`CorrelatedNormal` draws a vector from a mean and a covariance matrix through its
Cholesky factor, x = μ + L z with L Lᵀ = Σ and z standard normal.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import Any, Protocol

import numpy as np

from ..errors import ParameterError

__all__ = ["Distribution", "Normal", "Uniform", "LogNormal", "TruncatedNormal",
           "CorrelatedNormal", "DISTRIBUTIONS", "get_distribution", "sample_generator",
           "draw_samples"]


class Distribution(Protocol):
    """A scalar distribution: one value per call from the sample's generator."""

    name: str

    def sample(self, rng: np.random.Generator) -> float:
        """One value drawn with ``rng``.

        Parameters
        ----------
        rng : numpy.random.Generator
            The sample's generator.

        Returns
        -------
        float
        """
        ...


def _finite(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ParameterError(f"`{name}` must be a number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ParameterError(f"`{name}` must be finite, got {value!r}")
    return value


class _Scalar:
    """What every scalar distribution shares: :meth:`sample` draws through ``_draw``."""

    def sample(self, rng: np.random.Generator) -> float:
        """One value drawn with ``rng``.

        Parameters
        ----------
        rng : numpy.random.Generator
            The sample's generator.

        Returns
        -------
        float
        """
        return self._draw(rng)

    def _draw(self, rng: np.random.Generator) -> float:
        raise NotImplementedError


def _check_mean_std(dist: Any) -> None:
    """A finite mean and a finite std >= 0 of a normal or lognormal draw."""
    _finite("mean", dist.mean)
    if not _finite("std", dist.std) >= 0:
        raise ParameterError(f"`std` of a {dist.name} draw must be >= 0, got {dist.std!r}")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Normal(_Scalar):
    """Normal distribution N(mean, std²)."""

    mean: float
    std: float
    name = "normal"

    def __post_init__(self) -> None:
        _check_mean_std(self)

    def _draw(self, rng: np.random.Generator) -> float:
        return float(rng.normal(self.mean, self.std))


@dataclasses.dataclass(frozen=True, kw_only=True)
class Uniform(_Scalar):
    """Uniform distribution on [low, high)."""

    low: float
    high: float
    name = "uniform"

    def __post_init__(self) -> None:
        if not _finite("high", self.high) > _finite("low", self.low):
            raise ParameterError(f"a uniform draw needs `low` < `high`, got {self.low!r}, "
                                 f"{self.high!r}")

    def _draw(self, rng: np.random.Generator) -> float:
        return float(rng.uniform(self.low, self.high))


@dataclasses.dataclass(frozen=True, kw_only=True)
class LogNormal(_Scalar):
    """Log-normal distribution: exp of N(mean, std²) (mean and std of the underlying normal)."""

    mean: float
    std: float
    name = "lognormal"

    def __post_init__(self) -> None:
        _check_mean_std(self)

    def _draw(self, rng: np.random.Generator) -> float:
        return float(rng.lognormal(self.mean, self.std))


@dataclasses.dataclass(frozen=True, kw_only=True)
class TruncatedNormal(_Scalar):
    """N(mean, std²) cut to [low, high] (either bound may be infinite), by CDF inversion.

    One uniform number u per value: x = mean + std Φ⁻¹(Φ(a) + u (Φ(b) − Φ(a))) with
    a = (low − mean)/std, b = (high − mean)/std; a range above the mean is drawn through its
    mirror image, where the CDF values are small and keep their digits.
    """

    mean: float
    std: float
    low: float = -math.inf
    high: float = math.inf
    name = "truncnormal"

    def __post_init__(self) -> None:
        _finite("mean", self.mean)
        if not _finite("std", self.std) > 0:
            raise ParameterError(f"`std` of a truncnormal draw must be > 0, got {self.std!r}")
        low, high = float(self.low), float(self.high)
        if math.isnan(low) or math.isnan(high) or not high > low:
            raise ParameterError(f"a truncnormal draw needs `low` < `high`, got {self.low!r}, "
                                 f"{self.high!r}")

    def _draw(self, rng: np.random.Generator) -> float:
        from scipy.special import ndtr, ndtri

        a = (self.low - self.mean) / self.std
        b = (self.high - self.mean) / self.std
        u = rng.uniform()
        if a > 0:  # the upper tail: invert the mirror image (small CDF values keep their digits)
            lo, hi = ndtr(-b), ndtr(-a)
            z = -float(ndtri(hi - u * (hi - lo)))
        else:
            lo, hi = ndtr(a), ndtr(b)
            z = float(ndtri(lo + u * (hi - lo)))
        x = self.mean + self.std * z
        return min(max(x, self.low), self.high)


#: Scalar distributions by name.
DISTRIBUTIONS: dict[str, type] = {"normal": Normal, "uniform": Uniform, "lognormal": LogNormal,
                                  "truncnormal": TruncatedNormal}


def get_distribution(name: str, **params: float) -> Distribution:
    """A distribution from its name and parameters.

    Parameters
    ----------
    name : str
        A name in :data:`DISTRIBUTIONS`.
    **params : float
        Its parameters (``mean``, ``std``, ``low``, ``high`` as it takes them).

    Returns
    -------
    Distribution

    Raises
    ------
    ParameterError
        For an unknown name (listing the valid ones) or bad parameters.
    """
    if name not in DISTRIBUTIONS:
        raise ParameterError(f"unknown distribution '{name}'; valid: "
                             f"{', '.join(DISTRIBUTIONS)}")
    try:
        return DISTRIBUTIONS[name](**params)
    except TypeError as exc:
        raise ParameterError(f"a {name} draw: {exc}") from None


@dataclasses.dataclass(frozen=True, eq=False)
class CorrelatedNormal:
    """A normal vector N(μ, Σ) over named keys, drawn as μ + L z (L Lᵀ = Σ, Cholesky).

    Parameters
    ----------
    keys : sequence of str
        What each component is (e.g. key paths of a scenario).
    mean : sequence of float
        μ, one per key.
    covariance : array_like, shape (k, k)
        Σ: symmetric and positive definite (units: the keys' units squared).
    """

    keys: tuple[str, ...]
    mean: np.ndarray
    covariance: np.ndarray
    factor: np.ndarray = dataclasses.field(init=False, repr=False)

    def __post_init__(self) -> None:
        keys = tuple(self.keys)
        k = len(keys)
        if k == 0 or len(set(keys)) != k:
            raise ParameterError(f"`keys` of a correlated draw must be distinct and not "
                                 f"empty, got {list(keys)}")
        mean = np.asarray(self.mean, dtype=float)
        cov = np.asarray(self.covariance, dtype=float)
        if mean.shape != (k,):
            raise ParameterError(f"`mean` of a correlated draw needs {k} values (one per key), "
                                 f"got shape {mean.shape}")
        if cov.shape != (k, k):
            raise ParameterError(f"`covariance` of a correlated draw must be {k} x {k} (one row "
                                 f"and column per key), got shape {cov.shape}")
        if not (np.all(np.isfinite(mean)) and np.all(np.isfinite(cov))):
            raise ParameterError("`mean` and `covariance` of a correlated draw must be finite")
        if not np.allclose(cov, cov.T, rtol=1e-12, atol=0.0):
            raise ParameterError("`covariance` of a correlated draw must be symmetric")
        try:
            factor = np.linalg.cholesky(cov)
        except np.linalg.LinAlgError:
            smallest = float(np.linalg.eigvalsh(cov).min())
            raise ParameterError(
                f"`covariance` of a correlated draw must be positive definite; its smallest "
                f"eigenvalue is {smallest:.6g}") from None
        for name, arr in (("mean", mean), ("covariance", cov), ("factor", factor)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "keys", keys)

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        """One vector drawn with ``rng`` (one standard normal number per key).

        Parameters
        ----------
        rng : numpy.random.Generator
            The sample's generator.

        Returns
        -------
        ndarray, shape (k,)
        """
        z = rng.standard_normal(len(self.keys))
        return self.mean + self.factor @ z


def sample_generator(seed: int, index: int) -> np.random.Generator:
    """The generator of sample ``index`` of a study seeded with ``seed``.

    The same as ``default_rng(SeedSequence(seed).spawn(n)[index])`` for any n > index.

    Parameters
    ----------
    seed : int
        The study's seed (>= 0).
    index : int
        The sample's index (>= 0).

    Returns
    -------
    numpy.random.Generator
    """
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(int(index),)))


def draw_samples(
    marginals: Mapping[str, Distribution],
    seed: int,
    indices: Sequence[int] | np.ndarray,
    correlated: Sequence[CorrelatedNormal] = (),
) -> dict[str, np.ndarray]:
    """Draw samples by index: each from its own generator (:func:`sample_generator`).

    Parameters
    ----------
    marginals : mapping of key to Distribution
        Independent scalar draws, made in this order.
    seed : int
        The study's seed (>= 0).
    indices : sequence of int
        Sample indices to draw (any subset gives the same values as drawing all).
    correlated : sequence of CorrelatedNormal, optional
        Correlated blocks, drawn after the marginals.

    Returns
    -------
    dict of key to ndarray, shape (len(indices),)
    """
    if isinstance(seed, bool) or int(seed) != seed or seed < 0:
        raise ParameterError(f"`seed` must be a whole number >= 0, got {seed!r}")
    keys = list(marginals) + [k for block in correlated for k in block.keys]
    if len(set(keys)) != len(keys):
        raise ParameterError(f"a key is drawn twice: {keys}")
    idx = np.asarray(indices, dtype=np.int64)
    out = {k: np.empty(idx.size) for k in keys}
    for n, i in enumerate(idx.tolist()):
        rng = sample_generator(seed, i)
        for key, dist in marginals.items():
            out[key][n] = dist.sample(rng)
        for block in correlated:
            values = block.sample(rng)
            for key, v in zip(block.keys, values):
                out[key][n] = v
    return out
