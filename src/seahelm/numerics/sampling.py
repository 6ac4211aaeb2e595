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


# SeedSequence's hash (O'Neill's seed_seq_fe, as numpy writes it in numpy/random/bit_generator.pyx)
# and PCG64's seeding (pcg64_set_seed: the two LCG steps of pcg_setseq_128_srandom_r): the
# constants of those algorithms, so that many samples' generator states are computed at once
_POOL = 4
_INIT_A, _MULT_A = np.uint32(0x43B0D7E5), np.uint32(0x931E8875)
_INIT_B, _MULT_B = np.uint32(0x8B51F9DD), np.uint32(0x58F38DED)
_MIX_L, _MIX_R = np.uint32(0xCA01F9DD), np.uint32(0x4973F715)
_PCG_MULT = 0x2360ED051FC65DA44385DF649FCCF645
_MASK128 = (1 << 128) - 1


def _uint32_words(n: int) -> list[int]:
    """A whole number >= 0 as SeedSequence takes it: 32-bit words, least significant first."""
    words = [n & 0xFFFFFFFF]
    n >>= 32
    while n > 0:
        words.append(n & 0xFFFFFFFF)
        n >>= 32
    return words


def _pcg64_states(seed: int, indices: np.ndarray) -> list[tuple[int, int]] | None:
    """The PCG64 (state, inc) of ``default_rng(SeedSequence(seed, spawn_key=(i,)))`` for
    every index ``i``, computed for all of them at once (None if an index needs more than one
    32-bit word: the caller then builds each generator).

    SeedSequence mixes the entropy words into a pool of four by a hash whose constants
    evolve the same way for every input, so the pools of many spawn keys are whole-array
    uint32 operations; PCG64 is then seeded from the four 64-bit words of
    ``generate_state(4, uint64)``. ``tests/test_sampling_fast_seeding.py`` checks the states
    against numpy's for many seeds and indices.
    """
    if indices.size == 0 or indices.min() < 0 or indices.max() >= 2 ** 32:
        return None
    run = _uint32_words(int(seed))
    run += [0] * (_POOL - len(run))  # (padded to the pool when there is a spawn key)
    entropy = [np.full(indices.size, w, dtype=np.uint32) for w in run]
    entropy.append(indices.astype(np.uint32))
    const = [_INIT_A]

    def hashmix(value: np.ndarray) -> np.ndarray:
        value = value ^ const[0]
        const[0] = const[0] * _MULT_A
        value = value * const[0]
        return value ^ (value >> np.uint32(16))

    def mix(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        result = _MIX_L * x - _MIX_R * y
        return result ^ (result >> np.uint32(16))

    with np.errstate(over="ignore"):  # (uint32 arithmetic wraps, as in the C code)
        pool = [hashmix(entropy[i]) for i in range(_POOL)]
        for src in range(_POOL):
            for dst in range(_POOL):
                if src != dst:
                    pool[dst] = mix(pool[dst], hashmix(pool[src]))
        for src in range(_POOL, len(entropy)):
            for dst in range(_POOL):
                pool[dst] = mix(pool[dst], hashmix(entropy[src]))
        words = []
        h = _INIT_B
        for i in range(8):  # generate_state(4, uint64): 8 words, two per uint64
            value = pool[i % _POOL] ^ h
            h = h * _MULT_B
            value = value * h
            words.append(value ^ (value >> np.uint32(16)))
    w64 = [(words[2 * j + 1].astype(np.uint64) << np.uint64(32)) | words[2 * j].astype(np.uint64)
           for j in range(4)]
    out = []
    for s0, s1, i0, i1 in zip(*(a.tolist() for a in w64)):
        initstate, initseq = (s0 << 64) | s1, (i0 << 64) | i1
        inc = ((initseq << 1) | 1) & _MASK128
        state = (((inc + initstate) & _MASK128) * _PCG_MULT + inc) & _MASK128
        out.append((state, inc))
    return out


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
    # one generator whose PCG64 state is set to each sample's (computed for all samples at
    # once): the draws of sample_generator(seed, i), at a tenth of the cost of making it
    states = _pcg64_states(int(seed), idx)
    bits = np.random.PCG64()
    shared = np.random.Generator(bits)
    state = {"bit_generator": "PCG64", "state": {"state": 0, "inc": 1}, "has_uint32": 0,
             "uinteger": 0}
    for n, i in enumerate(idx.tolist()):
        if states is None:
            rng = sample_generator(seed, i)
        else:
            state["state"]["state"], state["state"]["inc"] = states[n]
            bits.state = state
            rng = shared
        for key, dist in marginals.items():
            out[key][n] = dist.sample(rng)
        for block in correlated:
            values = block.sample(rng)
            for key, v in zip(block.keys, values):
                out[key][n] = v
    return out
