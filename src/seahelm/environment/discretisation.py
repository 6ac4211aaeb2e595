"""Exact discretisation and sampling of a linear filter driven by white noise.

Exact discretisation: Φ = e^{AΔt} and Q_d = ∫₀^Δt e^{As} B q Bᵀ e^{Aᵀs} ds by Van Loan's
matrix exponential, so x_{k+1} = Φ x_k + w_k, w_k ~ N(0, Q_d) reproduces the continuous
autocovariance at the sample instants for any Δt; the initial state is drawn from the
stationary covariance (Lyapunov equation), so samples are stationary from t = 0. When fewer
outputs than states are sampled, the generator uses the steady-state innovations form of the
same sampled process (discrete Riccati equation): one normal per output and step instead of
one per state, with identical Gaussian statistics (autocovariance tested at Δt = 0.05 s and 1 s).

The continuous filters are :class:`~seahelm.environment.shaping.StateSpaceFilter`
(:mod:`seahelm.environment.shaping`): :class:`DiscreteFilter` is one discretised at a step,
:class:`FilterSamples` what sampling returns, :func:`van_loan` the matrix-exponential integral.

References
----------
Van Loan, C. F. (1978). Computing integrals involving the matrix exponential. IEEE TAC 23(3).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from numba import njit
from numpy.typing import ArrayLike
from scipy import linalg

from .._validate import check_positive, lookup_name

__all__ = ["DiscreteFilter", "FilterSamples", "van_loan", "single_run_stream"]


@dataclasses.dataclass(frozen=True, eq=False)
class DiscreteFilter:
    """Exact zero-order-free discretisation of a :class:`~.StateSpaceFilter` at step ``dt``.

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
        How :meth:`~.StateSpaceFilter.sample` generates: ``"state"`` (x_{k+1} = Φx_k + L z_k,
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
        index = lookup_name("output", {n: i for i, n in enumerate(self.labels)}, label,
                            error=KeyError)
        return self.values[..., index]

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
    """The stream a single-run :meth:`~.StateSpaceFilter.sample` takes from ``seed`` (its first
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
