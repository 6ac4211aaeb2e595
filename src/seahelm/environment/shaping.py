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
√(μ² + λ²)). The correct factors are built by :func:`shaping_filter`; the printed ones are in
:data:`PAPER_FILTERS` for reproduction.

Exact discretisation: Φ = e^{AΔt} and Q_d = ∫₀^Δt e^{As} B q Bᵀ e^{Aᵀs} ds by Van Loan's
matrix exponential, so x_{k+1} = Φ x_k + w_k, w_k ~ N(0, Q_d) reproduces the continuous
autocovariance at the sample instants for any Δt; the initial state is drawn from the
stationary covariance (Lyapunov equation), so samples are stationary from t = 0. When fewer
outputs than states are sampled, the generator uses the steady-state innovations form of the
same sampled process (discrete Riccati equation): one normal per output and step instead of
one per state, with identical Gaussian statistics (autocovariance tested at Δt = 0.05 s and 1 s).

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
from collections.abc import Callable, Mapping, Sequence
from types import MappingProxyType
from typing import Any

import numpy as np
from numba import njit
from numpy.typing import ArrayLike
from scipy import linalg

from .._optional import optional_import
from .._validate import as_float_array, check_positive
from ..constants import GRAVITY
from ..errors import ParameterError
from .rational_spectra import RationalSpectrum
from .spectra import get_spectrum
from .spectrum_base import WaveSpectrum

__all__ = [
    "single_run_stream",
    "NOISE_INTENSITY",
    "QUANTITIES",
    "PAPER_FILTERS",
    "StateSpaceFilter",
    "DiscreteFilter",
    "FilterSamples",
    "from_transfer_functions",
    "shaping_filter",
    "paper_filter",
    "van_loan",
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
class DiscreteFilter:
    """Exact zero-order-free discretisation of a :class:`StateSpaceFilter` at step ``dt``.

    x_{k+1} = Φ x_k + w_k, w_k ~ N(0, Q_d); y_k = C x_k; x_0 ~ N(0, P) with P stationary.

    Attributes
    ----------
    dt : float
        Sample interval Δt [s].
    transition : numpy.ndarray
        Φ = e^{AΔt}, shape (n, n).
    noise_covariance : numpy.ndarray
        Q_d (Van Loan), shape (n, n).
    noise_factor : numpy.ndarray
        L with L Lᵀ = Q_d.
    output : numpy.ndarray
        C, shape (p, n).
    stationary_covariance : numpy.ndarray
        P solving A P + P Aᵀ + B q Bᵀ = 0; also Φ P Φᵀ + Q_d = P.
    stationary_factor : numpy.ndarray
        P₀ with P₀ P₀ᵀ = P.
    form : str
        How :meth:`StateSpaceFilter.sample` generates: ``"state"`` (x_{k+1} = Φx_k + L z_k,
        n normals per step) or ``"innovations"`` (fewer outputs than states: the steady-state
        innovations model x̂_{k+1} = Φx̂_k + K e_k, y_k = C x̂_k + e_k, with K and
        Var e = C P̄ Cᵀ from the discrete Riccati equation — p normals per step and the same
        Gaussian distribution of the sampled outputs).
    state_noise_gain, output_noise_gain : numpy.ndarray
        G_x (n, m) and G_y (p, m): x_{k+1} = Φ x_k + G_x z_k, y_k = C x_k + G_y z_k, z_k ~ N(0, I_m).
    initial_factor : numpy.ndarray
        F with x_0 = F z, z ~ N(0, I_n) (stationary start).
    """

    dt: float
    transition: np.ndarray
    noise_covariance: np.ndarray
    noise_factor: np.ndarray
    output: np.ndarray
    stationary_covariance: np.ndarray
    stationary_factor: np.ndarray
    form: str = "state"
    state_noise_gain: np.ndarray | None = None
    output_noise_gain: np.ndarray | None = None
    initial_factor: np.ndarray | None = None


def _psd_factor(m: np.ndarray) -> np.ndarray:
    m = 0.5 * (m + m.T)
    try:
        return np.linalg.cholesky(m)
    except np.linalg.LinAlgError:
        w, v = np.linalg.eigh(m)
        return v * np.sqrt(np.clip(w, 0.0, None))


def van_loan(a: ArrayLike, g_q_gt: ArrayLike, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Φ = e^{AΔt} and Q_d = ∫₀^Δt e^{As} G Q Gᵀ e^{Aᵀs} ds by Van Loan's method.

    Parameters
    ----------
    a : array_like, shape (n, n)
    g_q_gt : array_like, shape (n, n)
        Continuous noise covariance intensity G Q Gᵀ.
    dt : float
        Δt [s], > 0.
    """
    check_positive("dt", dt, "s")
    a = np.asarray(a, float)
    n = a.shape[0]
    m = np.zeros((2 * n, 2 * n))
    m[:n, :n] = -a
    m[:n, n:] = np.asarray(g_q_gt, float)
    m[n:, n:] = a.T
    e = linalg.expm(m * dt)
    phi = e[n:, n:].T
    qd = phi @ e[:n, n:]
    return phi, 0.5 * (qd + qd.T)


def _innovations(phi: np.ndarray, qd: np.ndarray, c: np.ndarray, p_inf: np.ndarray):
    """Steady-state innovations model of the sampled outputs, or None if it is ill-posed."""
    p = c.shape[0]
    try:
        pbar = linalg.solve_discrete_are(phi.T, c.T, qd, np.zeros((p, p)))
    except (ValueError, np.linalg.LinAlgError):
        return None
    pbar = 0.5 * (pbar + pbar.T)
    re = c @ pbar @ c.T
    sigma = p_inf - pbar
    if not (np.all(np.isfinite(pbar)) and np.all(np.linalg.eigvalsh(re) > 0)):
        return None
    if np.min(np.linalg.eigvalsh(0.5 * (sigma + sigma.T))) < -1e-10 * np.max(np.abs(p_inf)):
        return None
    gain = phi @ pbar @ c.T @ np.linalg.inv(re)
    resid = phi @ pbar @ phi.T + qd - gain @ re @ gain.T - pbar
    if np.max(np.abs(resid)) > 1e-9 * max(np.max(np.abs(p_inf)), 1e-300):
        return None
    r_fac = np.linalg.cholesky(0.5 * (re + re.T))
    return gain @ r_fac, r_fac, _psd_factor(sigma)


@njit(cache=True, nogil=True)
def _propagate(x: np.ndarray, phi: np.ndarray, gx: np.ndarray, c: np.ndarray, gy: np.ndarray,
               noise: np.ndarray, out: np.ndarray) -> None:  # pragma: no cover - compiled
    """y_k = C x_k + G_y z_k; x_{k+1} = Φ x_k + G_x z_k over one chunk (x updated in place)."""
    n = x.shape[0]
    p = c.shape[0]
    m = gx.shape[1]
    nsteps = out.shape[0]
    xn = np.empty(n)
    for k in range(nsteps):
        for i in range(p):
            acc = 0.0
            for j in range(m):
                acc += gy[i, j] * noise[k, j]
            for j in range(n):
                acc += c[i, j] * x[j]
            out[k, i] = acc
        for i in range(n):
            acc = 0.0
            for j in range(m):
                acc += gx[i, j] * noise[k, j]
            for j in range(n):
                acc += phi[i, j] * x[j]
            xn[i] = acc
        for i in range(n):
            x[i] = xn[i]


@njit(cache=True, nogil=True)
def _propagate_2x1(x: np.ndarray, phi: np.ndarray, gx: np.ndarray, c: np.ndarray, gy: np.ndarray,
                   noise: np.ndarray, out: np.ndarray) -> None:  # pragma: no cover - compiled
    """:func:`_propagate` unrolled for two states, one output and one noise (the common case)."""
    p00, p01, p10, p11 = phi[0, 0], phi[0, 1], phi[1, 0], phi[1, 1]
    g0, g1, c0, c1, h = gx[0, 0], gx[1, 0], c[0, 0], c[0, 1], gy[0, 0]
    x0, x1 = x[0], x[1]
    for k in range(out.shape[0]):
        z = noise[k, 0]
        out[k, 0] = c0 * x0 + c1 * x1 + h * z
        x0, x1 = p00 * x0 + p01 * x1 + g0 * z, p10 * x0 + p11 * x1 + g1 * z
    x[0] = x0
    x[1] = x1


@dataclasses.dataclass(frozen=True, eq=False)
class FilterSamples:
    """Sampled outputs of a shaping filter.

    Attributes
    ----------
    time : numpy.ndarray
        Sample times [s], shape (n_steps,).
    values : numpy.ndarray
        Outputs, shape (runs, n_steps, n_outputs) — batch axis first.
    labels : tuple of str
        Output names.
    units : tuple of str
        Output units.
    dt : float
        Δt [s].
    seed : object
        The seed (entropy) the run seeds were spawned from.
    variance_expected : numpy.ndarray
        Stationary variance of each output, shape (n_outputs,).
    attrs : dict
        Extra metadata (spectrum, parameters, noise intensity).
    """

    time: np.ndarray
    values: np.ndarray
    labels: tuple[str, ...]
    units: tuple[str, ...]
    dt: float
    seed: Any
    variance_expected: np.ndarray
    attrs: dict[str, Any] = dataclasses.field(default_factory=dict)

    def __getitem__(self, label: str) -> np.ndarray:
        """Output ``label`` as an array of shape (runs, n_steps)."""
        try:
            return self.values[..., self.labels.index(label)]
        except ValueError:
            raise KeyError(f"unknown output {label!r}; valid: {', '.join(self.labels)}") from None

    def to_xarray(self) -> Any:
        """An ``xarray.Dataset`` with dims (run, time), one variable per output, metadata in attrs."""
        import xarray as xr

        data = {
            lab: (("run", "time"), self.values[..., i], {"units": unit})
            for i, (lab, unit) in enumerate(zip(self.labels, self.units))
        }
        attrs: dict[str, Any] = {
            "dt": self.dt,
            "seed": str(self.seed),
            "variance_expected": np.asarray(self.variance_expected, float),
            "white_noise_convention": "E[n(t)n(t')] = pi delta(t - t') (one-sided intensity 1)",
            "discretisation": "exact (matrix exponential, Van Loan covariance)",
            "reference": "Sushchenko & Lutsko (2010)",
        }
        for k, v in self.attrs.items():
            attrs[k] = v if isinstance(v, (int, float, str, np.ndarray)) else str(v)
        return xr.Dataset(
            data,
            coords={"run": np.arange(self.values.shape[0]), "time": ("time", self.time, {"units": "s"})},
            attrs=attrs,
        )


def single_run_stream(seed: Any) -> Any:
    """The stream a single-run :meth:`StateSpaceFilter.sample` takes from ``seed`` (its first
    spawned child), so that ``sample(seed=[single_run_stream(s) for s in seeds], runs=R)``
    row i equals ``sample(seed=seeds[i])``. A SeedSequence given is not advanced; a Generator
    is, as a single-run draw would advance it.

    Parameters
    ----------
    seed : int, SeedSequence or Generator
        What a single-run draw would be given.

    Returns
    -------
    SeedSequence or Generator
        The stream it would draw from.
    """
    if isinstance(seed, np.random.Generator):
        return seed.spawn(1)[0]
    if isinstance(seed, np.random.SeedSequence):
        seed = np.random.SeedSequence(seed.entropy, spawn_key=seed.spawn_key,
                                      pool_size=seed.pool_size,
                                      n_children_spawned=seed.n_children_spawned)
    else:
        seed = np.random.SeedSequence(seed)
    return seed.spawn(1)[0]


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
        if o not in QUANTITIES:
            valid = ", ".join(repr(k) for k in QUANTITIES)
            raise ParameterError(f"unknown output {o!r}; valid: {valid}")
        quantities.append(QUANTITIES[o])
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


# ---------------------------------------------------------------------------------------------
# The paper's printed filters (for reproduction only)
# ---------------------------------------------------------------------------------------------


def _printed_ordinate(d: float, mu: float, lam: float, g: float) -> tuple[np.ndarray, np.ndarray, str]:
    a = math.hypot(mu, lam)
    k = math.sqrt(2.0 * d * mu / math.pi)
    return np.array([k, k * a]), np.array([1.0, 2.0 * lam, a * a]), "m"


def _printed_eq6(d: float, mu: float, lam: float, g: float) -> tuple[np.ndarray, np.ndarray, str]:
    a = math.hypot(mu, lam)
    k = math.sqrt(2.0 * d * mu * a * a / math.pi) / g
    return np.array([k, k * a, 0.0]), np.array([1.0, 2.0 * lam, a * a]), "rad"


def _printed_eq7(d: float, mu: float, lam: float, g: float) -> tuple[np.ndarray, np.ndarray, str]:
    a = math.hypot(mu, lam)
    k = 2.0 * math.sqrt(d * mu * a * a / math.pi) / g
    return np.array([k * a, 0.0]), np.array([1.0, 2.0 * lam, a * a]), "rad"


#: The paper's filters exactly as printed (Sushchenko & Lutsko (2010)): ``"ordinate-printed"``
#: (the factorisation result before eq. (6), poles −λ ± jμ: output variance (μ/λ)D_r ≈ 0.21 D_r),
#: ``"eq6"`` (biproper: infinite output variance) and ``"eq7"``.
PAPER_FILTERS: Mapping[str, Callable[[float, float, float, float], tuple[np.ndarray, np.ndarray, str]]] = (
    MappingProxyType(
        {"ordinate-printed": _printed_ordinate, "eq6": _printed_eq6, "eq7": _printed_eq7}
    )
)


def paper_filter(
    name: str,
    *,
    variance: float,
    decay_rate: float,
    resonance_frequency: float,
    gravity: float = GRAVITY,
) -> StateSpaceFilter:
    """A filter of the paper exactly as printed (wrong; for reproducing the paper's figure).

    Parameters
    ----------
    name : {"ordinate-printed", "eq6", "eq7"}
    variance : float
        D_r [m²], > 0.
    decay_rate : float
        μ [1/s], > 0.
    resonance_frequency : float
        λ [rad/s], > 0.
    gravity : float
        g [m/s²].

    Raises
    ------
    ParameterError
        For an unknown name (listing the valid ones) or bad parameters.
    """
    if name not in PAPER_FILTERS:
        valid = ", ".join(repr(k) for k in PAPER_FILTERS)
        raise ParameterError(f"unknown paper filter {name!r}; valid: {valid}")
    check_positive("variance", variance, "m^2")
    check_positive("decay_rate", decay_rate, "1/s")
    check_positive("resonance_frequency", resonance_frequency, "rad/s")
    check_positive("gravity", gravity, "m/s^2")
    num, den, unit = PAPER_FILTERS[name](variance, decay_rate, resonance_frequency, gravity)
    return from_transfer_functions(
        [num], den, labels=(name,), units=(unit,), name=f"Sushchenko & Lutsko (2010) {name} (as printed)"
    )
