"""Shaping filters: spectral factors as state-space models, exact discretisation, sampling.

A shaping filter turns white noise n(t) into a stationary process with a prescribed spectrum
(Sushchenko & Lutsko (2010), "Wiener factorisation" S(s) = W(s)W(−s)). Here W(s) is the
*stable, minimum-phase* factor, realised as a state-space model

    ẋ = A x + B n(t),    y = C x + D n(t).

White-noise convention (stated once, used everywhere in this module)
--------------------------------------------------------------------
The input n(t) has **one-sided intensity 1**: E[n(t) n(t')] = π δ(t − t'), i.e. a two-sided
spectral density 1/2 in the ω-convention K(τ) = ∫ S(ω) e^{iωτ} dω. Then the one-sided output
spectrum (eq. (1) convention) is exactly S₁(ω) = |W(jω)|². The intensity is stored as
:attr:`StateSpaceFilter.noise_intensity` = π. If you drive (A, B, C, D) with unit-intensity
Wiener increments (E[dw²] = dt), multiply B and D by √π.

The paper's factors (6)-(7) are wrong (erratum: the middle term of the denominator in jω has
the opposite sign, so the damping is 2μ, not 2λ; (6) is biproper and (6)-(7) carry an extra
√(μ² + λ²)). The correct factors are built by :func:`shaping_filter`; the printed ones are the
paper's reproduction, :data:`seahelm.studies.sushchenko2010.PRINTED_FILTERS`.

Sampling is exact: the filter is discretised by Van Loan's matrix exponential and started
from its stationary covariance, so samples reproduce the continuous autocovariance at the
sample instants for any Δt (:mod:`seahelm.environment.discretisation`).

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010), eq. (6)-(7) and the factorisation before them.
Van Loan, C. F. (1978). Computing integrals involving the matrix exponential. IEEE TAC 23(3).
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import math
import os
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy import linalg

from .._optional import optional_import
from .._validate import as_float_array, check_positive, lookup_name
from ..constants import GRAVITY
from ..errors import ParameterError
from .discretisation import (
    DiscreteFilter,
    FilterSamples,
    _innovations,
    _propagate,
    _propagate_2x1,
    _psd_factor,
    van_loan,
)
from .rational_spectra import RationalSpectrum
from .spectra import get_spectrum
from .spectrum_base import WaveSpectrum

__all__ = [
    "NOISE_INTENSITY",
    "QUANTITIES",
    "StateSpaceFilter",
    "from_transfer_functions",
    "shaping_filter",
]

#: One-sided intensity 1 of the input white noise: E[n(t)n(t')] = π δ(t − t').
NOISE_INTENSITY: float = math.pi

#: Output quantities of a shaping filter: name → (k, divide by g, unit). The output is
#: sᵏ W(s) (÷ g for slope quantities): ordinate ζ, its rate, the slope α = ζ̇/g of eq. (5),
#: the slope rate α̇ and the slope acceleration α̈.
QUANTITIES: Mapping[str, tuple[int, bool, str]] = MappingProxyType(
    {
        "ordinate": (0, False, "m"),
        "ordinate_rate": (1, False, "m/s"),
        "slope": (1, True, "rad"),
        "slope_rate": (2, True, "rad/s"),
        "slope_acceleration": (3, True, "rad/s^2"),
    }
)


def _trim(p: ArrayLike) -> np.ndarray:
    p = np.atleast_1d(np.asarray(p, dtype=float))
    nz = np.flatnonzero(p != 0.0)
    return p[nz[0] :] if nz.size else np.zeros(1)


@dataclasses.dataclass(frozen=True, eq=False)
class StateSpaceFilter:
    """A shaping filter ẋ = A x + B n, y = C x + D n driven by white noise n(t).

    The input n(t) has one-sided intensity 1, E[n(t)n(t')] = π δ(t − t') (module docstring);
    then each output's one-sided spectrum is |H_i(jω)|².

    Attributes
    ----------
    A : numpy.ndarray, shape (n, n)
    B : numpy.ndarray, shape (n, 1)
    C : numpy.ndarray, shape (p, n)
    D : numpy.ndarray, shape (p, 1)
    labels : tuple of str
        Output names, length p.
    units : tuple of str
        Output units, length p.
    noise_intensity : float
        q in E[n(t)n(t')] = q δ(t − t'); π by default.
    name : str
        Description (spectrum and parameters).
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    labels: tuple[str, ...]
    units: tuple[str, ...]
    noise_intensity: float = NOISE_INTENSITY
    name: str = ""

    def __post_init__(self) -> None:
        n = self.A.shape[0]
        if self.A.shape != (n, n) or self.B.shape != (n, 1) or self.C.shape[1] != n:
            raise ParameterError("inconsistent state-space dimensions")
        if self.D.shape != (self.C.shape[0], 1) or len(self.labels) != self.C.shape[0]:
            raise ParameterError("inconsistent output dimensions")
        check_positive("noise_intensity", self.noise_intensity)

    @property
    def n_states(self) -> int:
        return int(self.A.shape[0])

    @property
    def is_stable(self) -> bool:
        """True if every eigenvalue of A has a negative real part."""
        return bool(np.all(np.linalg.eigvals(self.A).real < 0))

    def frequency_response(self, omega: ArrayLike) -> np.ndarray:
        """H(jω) = C (jωI − A)⁻¹ B + D, shape (p, len(omega)).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s].

        Returns
        -------
        numpy.ndarray of complex, shape (p, len(omega))
        """
        w = np.atleast_1d(as_float_array("omega", omega, "rad/s"))
        n = self.n_states
        eye = np.eye(n)
        out = np.empty((self.C.shape[0], w.size), complex)
        for i, wi in enumerate(w):
            out[:, i] = (self.C @ np.linalg.solve(1j * wi * eye - self.A, self.B))[:, 0] + self.D[:, 0]
        return out

    def output_spectrum(self, omega: ArrayLike) -> np.ndarray:
        """One-sided output spectra (q/π)|H(jω)|², shape (p, len(omega)) (= |H|² for q = π).

        Parameters
        ----------
        omega : array_like
            Frequencies ω [rad/s].

        Returns
        -------
        numpy.ndarray, shape (p, len(omega))
            S₁ of each output [unit²·s/rad].
        """
        return np.abs(self.frequency_response(omega)) ** 2 * (self.noise_intensity / math.pi)

    def stationary_covariance(self) -> np.ndarray:
        """P solving A P + P Aᵀ + B q Bᵀ = 0 (requires a stable A)."""
        if not self.is_stable:
            raise ParameterError("the filter is not stable; no stationary covariance")
        q = self.B @ self.B.T * self.noise_intensity
        p = linalg.solve_continuous_lyapunov(self.A, -q)
        return 0.5 * (p + p.T)

    def output_variance(self) -> np.ndarray:
        """Stationary variance of each output: diag(C P Cᵀ), ``inf`` where D ≠ 0."""
        p = self.stationary_covariance()
        var = np.einsum("ij,jk,ik->i", self.C, p, self.C)
        return np.where(self.D[:, 0] != 0.0, np.inf, var)

    def output_covariance(self, lag: ArrayLike) -> np.ndarray:
        """Autocovariance K_i(τ) = C_i e^{Aτ} P C_iᵀ of each output, shape (p, len(lag)).

        Parameters
        ----------
        lag : array_like
            Time lags τ [s] (the sign is ignored).

        Returns
        -------
        numpy.ndarray, shape (p, len(lag))
            K_i(τ) [unit²].
        """
        tau = np.abs(np.atleast_1d(as_float_array("lag", lag, "s")))
        p = self.stationary_covariance()
        out = np.empty((self.C.shape[0], tau.size))
        for j, t in enumerate(tau):
            out[:, j] = np.einsum("ij,jk,ik->i", self.C, linalg.expm(self.A * t) @ p, self.C)
        return out

    def to_control(self) -> Any:
        """The filter as a ``control.StateSpace`` (needs the optional extra ``control``).

        The python-control model has the same (A, B, C, D); drive it with white noise of
        intensity :attr:`noise_intensity` (π), see the module docstring.
        """
        ct = optional_import("control", extra="control", purpose="exporting shaping filters")
        return ct.ss(self.A, self.B, self.C, self.D, outputs=list(self.labels), inputs=["noise"])

    def discretize(self, dt: float) -> DiscreteFilter:
        """Exact discretisation at step ``dt`` [s] (matrix exponential + Van Loan covariance).

        Parameters
        ----------
        dt : float
            Sample period [s] (> 0).

        Returns
        -------
        DiscreteFilter

        Raises
        ------
        ParameterError
            If ``dt`` is not finite and > 0, or an output has white-noise feedthrough
            (D ≠ 0: infinite variance — add a roll-off, see :func:`shaping_filter`).
        """
        dt = float(as_float_array("dt", dt, "s"))
        check_positive("dt", dt, "s")
        bad = [lab for lab, d in zip(self.labels, self.D[:, 0]) if d != 0.0]
        if bad:
            raise ParameterError(
                f"output(s) {', '.join(bad)} have white-noise feedthrough (infinite variance) "
                "and cannot be sampled; pass rolloff=ω_c [rad/s] to shaping_filter"
            )
        p = self.stationary_covariance()
        phi, qd = van_loan(self.A, self.B @ self.B.T * self.noise_intensity, dt)
        lfac, p0 = _psd_factor(qd), _psd_factor(p)
        c = np.ascontiguousarray(self.C)
        form, gx, gy, x0 = "state", lfac, np.zeros((c.shape[0], self.n_states)), p0
        if c.shape[0] < self.n_states:
            inno = _innovations(phi, qd, c, p)
            if inno is not None:
                form, (gx, gy, x0) = "innovations", inno
        return DiscreteFilter(
            dt=dt,
            transition=phi,
            noise_covariance=qd,
            noise_factor=lfac,
            output=c,
            stationary_covariance=p,
            stationary_factor=p0,
            form=form,
            state_noise_gain=np.ascontiguousarray(gx),
            output_noise_gain=np.ascontiguousarray(gy),
            initial_factor=np.ascontiguousarray(x0),
        )

    def sample(
        self,
        *,
        n_steps: int | None = None,
        duration: float | None = None,
        dt: float,
        seed: Any = None,
        runs: int = 1,
        workers: int | None = None,
        chunk: int = 1 << 15,
    ) -> FilterSamples:
        """Batched, seeded stationary realisations of every output, sampled exactly.

        Parameters
        ----------
        n_steps : int, optional
            Number of samples per run (t = 0, Δt, …). Give this or ``duration``.
        duration : float, optional
            Length [s]; n_steps = floor(duration/Δt) + 1.
        dt : float
            Sample interval Δt [s], > 0. The statistics are exact for any Δt.
        seed : int, SeedSequence, Generator, sequence of these, or None
            Run i uses the i-th child of ``SeedSequence(seed).spawn(runs)`` (or
            ``Generator.spawn(runs)``). A sequence of ``runs`` seeds/generators gives each run
            its own stream directly, so ``sample(seed=s, runs=R)`` run i equals
            ``sample(seed=[SeedSequence(s).spawn(R)[i]], runs=1)``.
        runs : int
            Number of independent realisations (≥ 1).
        workers : int, optional
            Threads (default: number of CPUs, at most ``runs``).
        chunk : int
            Steps generated per noise block (memory bound).

        Returns
        -------
        FilterSamples
            ``values`` of shape (runs, n_steps, n_outputs).

        Raises
        ------
        ParameterError
            For a bad ``dt``, ``duration``, ``n_steps`` or ``runs``.
        """
        disc = self.discretize(dt)
        if (n_steps is None) == (duration is None):
            raise ParameterError("give exactly one of `n_steps` and `duration`")
        if duration is not None:
            duration = float(as_float_array("duration", duration, "s"))
            check_positive("duration", duration, "s")
            n_steps = int(math.floor(duration / disc.dt + 1e-9)) + 1
        if isinstance(n_steps, bool) or not isinstance(n_steps, (int, np.integer)) or n_steps < 1:
            raise ParameterError(f"`n_steps` must be an integer >= 1, got {n_steps!r}")
        if isinstance(runs, bool) or not isinstance(runs, (int, np.integer)) or runs < 1:
            raise ParameterError(f"`runs` must be an integer >= 1, got {runs!r}")
        n_steps, runs = int(n_steps), int(runs)
        if isinstance(seed, (list, tuple)):
            if len(seed) != runs:
                raise ParameterError(f"`seed` has {len(seed)} per-run seeds for runs={runs}")
            gens = [s if isinstance(s, np.random.Generator) else np.random.default_rng(s) for s in seed]
            seed_repr: Any = "per-run"
        elif isinstance(seed, np.random.Generator):
            gens = seed.spawn(runs)
            seed_repr = "generator"
        else:
            ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
            gens = [np.random.default_rng(c) for c in ss.spawn(runs)]
            seed_repr = ss.entropy
        out = np.empty((runs, n_steps, self.C.shape[0]))
        n = self.n_states
        chunk = max(1, int(chunk))

        gx, gy, x0f = disc.state_noise_gain, disc.output_noise_gain, disc.initial_factor
        assert gx is not None and gy is not None and x0f is not None
        m = gx.shape[1]
        kernel = _propagate_2x1 if gx.shape == (2, 1) and gy.shape == (1, 1) else _propagate

        def one(i: int) -> None:
            rng = gens[i]
            x = x0f @ rng.standard_normal(n)
            buf = np.empty((min(chunk, n_steps), m))
            for start in range(0, n_steps, chunk):
                stop = min(start + chunk, n_steps)
                z = buf[: stop - start]
                rng.standard_normal(out=z)
                kernel(x, disc.transition, gx, disc.output, gy, z, out[i, start:stop])

        workers = min(runs, workers or os.cpu_count() or 1)
        if workers <= 1:
            for i in range(runs):
                one(i)
        else:
            with concurrent.futures.ThreadPoolExecutor(workers) as pool:
                list(pool.map(one, range(runs)))
        return FilterSamples(
            time=np.arange(n_steps) * disc.dt,
            values=out,
            labels=self.labels,
            units=self.units,
            dt=disc.dt,
            seed=seed_repr,
            variance_expected=np.einsum(
                "ij,jk,ik->i", self.C, disc.stationary_covariance, self.C
            ),
            attrs={"filter": self.name, "noise_intensity": self.noise_intensity, "form": disc.form},
        )


def from_transfer_functions(
    numerators: Sequence[ArrayLike],
    denominator: ArrayLike,
    *,
    labels: Sequence[str],
    units: Sequence[str] | None = None,
    noise_intensity: float = NOISE_INTENSITY,
    name: str = "",
) -> StateSpaceFilter:
    """Controllable-canonical realisation of outputs N_i(s)/d(s) sharing one denominator.

    Parameters
    ----------
    numerators : sequence of array_like
        Polynomial coefficients of each N_i(s), highest power first; deg N_i ≤ deg d.
    denominator : array_like
        d(s), highest power first, degree ≥ 1.
    labels, units : sequence of str
        One per output.
    noise_intensity : float
        q of the input noise (π: one-sided intensity 1).
    name : str, optional
        Name of the filter (default "").

    Returns
    -------
    StateSpaceFilter

    Raises
    ------
    ParameterError
        If an output is improper (deg N_i > deg d).
    """
    den = _trim(denominator)
    n = den.size - 1
    if n < 1:
        raise ParameterError("`denominator` must have degree >= 1")
    lead = den[0]
    den = den / lead
    a = np.zeros((n, n))
    a[:-1, 1:] = np.eye(n - 1)
    a[-1, :] = -den[::-1][:-1]
    b = np.zeros((n, 1))
    b[-1, 0] = 1.0
    c = np.zeros((len(numerators), n))
    d = np.zeros((len(numerators), 1))
    for i, num in enumerate(numerators):
        num = _trim(num) / lead
        if num.size > n + 1:
            raise ParameterError(
                f"output {labels[i]!r} is improper (numerator degree {num.size - 1} > "
                f"denominator degree {n}); pass rolloff=ω_c [rad/s] to band-limit it"
            )
        full = np.concatenate([np.zeros(n + 1 - num.size), num])
        d[i, 0] = full[0]
        rem = full - full[0] * den
        c[i, :] = rem[1:][::-1]
    units = tuple(units) if units is not None else ("",) * len(numerators)
    return StateSpaceFilter(a, b, c, d, tuple(labels), units, float(noise_intensity), name)


def shaping_filter(
    spectrum: str | WaveSpectrum,
    outputs: Sequence[str] = ("ordinate",),
    *,
    rolloff: float | None = None,
    rolloff_order: int | None = None,
    gravity: float = GRAVITY,
    **params: Any,
) -> StateSpaceFilter:
    """State-space shaping filter of a rational spectrum, with several outputs.

    Each output is sᵏ W(s) (÷ g for the slope quantities, see :data:`QUANTITIES`), W(s) the
    stable minimum-phase factor of the spectrum (:meth:`RationalSpectrum.factor`), realised on
    one shared state, driven by white noise of one-sided intensity 1 (E[n(t)n(t')] = π δ).
    For the Rakhmanin–Firsov variants with a = √(μ² + λ²) (erratum to the paper's eq. (6)-(7)):

    * variant 1: W(s) = √(2D_rμ/π)(s + a)/(s² + 2μs + a²);
    * variant 2: W(s) = 2√(D_rμ/π) a/(s² + 2μs + a²);
    * variant 3: W(s) = 2√(D_rμ/π) s/(s² + 2μs + a²);
    * slope consistent with eq. (5): (s/g) W_2(s), variance (μ² + λ²)D_r/g².

    Parameters
    ----------
    spectrum : str or RationalSpectrum
        A rational spectrum object, or a registry name with constructor ``params``.
    outputs : sequence of str
        Keys of :data:`QUANTITIES`, e.g. ("ordinate", "slope", "slope_rate").
    rolloff : float, optional
        ω_c [rad/s]: multiply every output by (ω_c/(s + ω_c))^r to band-limit quantities
        whose variance is infinite (e.g. the slope rate of variant 2) so they can be sampled.
    rolloff_order : int, optional
        r; default: the least order that makes every output strictly proper.
    gravity : float
        g [m/s²].

    Returns
    -------
    StateSpaceFilter

    Raises
    ------
    ParameterError
        For an unknown output, a non-rational spectrum, an improper output without a
        roll-off, or bad ``rolloff``.
    """
    spec = get_spectrum(spectrum, **params)
    if not isinstance(spec, RationalSpectrum):
        raise ParameterError(
            f"spectrum {spec.name!r} has no finite-order rational factor; "
            "use a Rakhmanin–Firsov variant for shaping filters"
        )
    check_positive("gravity", gravity, "m/s^2")
    num, den = spec.factor()
    num, den = _trim(num), _trim(den)
    quantities = []
    for o in outputs:
        quantities.append(lookup_name("output", QUANTITIES, o, error=ParameterError,
                                      quoted=True))
    nums = []
    for k, per_g, _unit in quantities:
        nums.append(np.concatenate([num / (gravity if per_g else 1.0), np.zeros(k)]))
    label = spec.name
    if rolloff is not None:
        check_positive("rolloff", rolloff, "rad/s")
        need = max(p.size for p in nums) - (den.size - 1)
        r = max(need, 0) if rolloff_order is None else rolloff_order
        if isinstance(r, bool) or not isinstance(r, (int, np.integer)) or r < 0:
            raise ParameterError(f"`rolloff_order` must be an integer >= 0, got {rolloff_order!r}")
        for _ in range(int(r)):
            den = np.polymul(den, [1.0, rolloff])
        nums = [p * rolloff ** int(r) for p in nums]
        label += f" × (ω_c/(s+ω_c))^{int(r)}, ω_c={rolloff:g}"
    return from_transfer_functions(
        nums, den, labels=tuple(outputs), units=tuple(q[2] for q in quantities), name=label
    )
