"""Wave filtering: a discrete Kalman filter for the low-frequency heading, as an observer stage.

The measured heading ψ_m of a ship in a seaway holds the low-frequency (LF) motion the
autopilot should correct and the wave-frequency (WF) oscillation it cannot and should not
(Fossen 2021, §13.4.3 "Kalman filter with wave filtering"; Balchen et al. 1976). The design
model, continuous in time::

    ψ̇_L = r_L,   ṙ_L = (−r_L + K (δ + b))/T,   ḃ = w_b            Nomoto ship + rudder bias
    ẋ_W = A_W x_W + B_W n,   ψ_W = C_W x_W                          WF yaw (shaping filter)
    ψ_m = ψ_L + ψ_W + v

with the WF yaw the ship's inertial response to an equivalent rudder g_δ α(t) proportional
to the wave slope α = (s/g) W(s) of a sea spectrum, W(s) the ordinate factor of seahelm's
shaping filter (:func:`seahelm.environment.shaping.shaping_filter`): ψ_W ≈ −(K g_δ/(T ω̄²)) α,
realised by :func:`seahelm.environment.wave_yaw.wave_yaw_filter` through
:func:`~seahelm.environment.shaping.from_transfer_functions` (zero at s = 0, so the LF/WF
split is detectable). n has one-sided intensity 1 (q = π), w_b intensity ``bias_intensity``, v variance
σ_v². Sampled at the controller's period Δt exactly (Φ = e^{AΔt}, Γ by the augmented
exponential, Q_d by Van Loan 1978), the steady-state Kalman gain comes from the discrete
algebraic Riccati equation: P⁻ (prior), L = P⁻Cᵀ(CP⁻Cᵀ + σ_v²)⁻¹, P⁺ = (I − LC)P⁻ (posterior,
:attr:`WaveFilterDesign.covariance`).

:func:`wave_filtered` wraps any heading controller: at every sample it corrects the estimate
with the measured heading (innovation wrapped to [−π, π)), hands the controller ψ̂_L and r̂_L
in place of the measured ``heading`` and ``yaw_rate``, steps it, and predicts with the rudder
command it gave. The gains are constants of the generated, compiled stage (one filter for the
whole batch); the controller period must equal the design's Δt (its ``sample_period``: a
problem at another ``controller_dt`` is refused; the command would be NaN). The estimates are recorded as the controller's outputs
``heading_lf_estimate``, ``yaw_rate_lf_estimate``, ``wave_heading_estimate``.

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §13.4 (wave filtering), §10.2.4 (linear wave response models).
Balchen, J. G., Jenssen, N. A., Sælid, S. (1976). Dynamic positioning using Kalman filtering
and optimal control theory. IFAC/IFIP Symposium on Automation in Offshore Oil Field Operation.
Van Loan, C. F. (1978). Computing integrals involving the matrix exponential. IEEE TAC 23(3).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import Any

import numpy as np

from .._codegen import content_digest
from .._validate import check_positive
from ..errors import ParameterError
from .base import Controller

__all__ = ["WaveFilterDesign", "design_wave_filter", "wave_filtered", "WAVE_FILTER_OUTPUTS"]

#: The signals the filtered controller records (after the inner controller's outputs).
WAVE_FILTER_OUTPUTS = ("heading_lf_estimate", "yaw_rate_lf_estimate", "wave_heading_estimate")


@dataclasses.dataclass(frozen=True, eq=False)
class WaveFilterDesign:
    """A steady-state discrete Kalman filter for ψ_L, r_L, the bias and the WF states.

    Attributes
    ----------
    phi, gamma : numpy.ndarray
        x_{k+1} = Φ x_k + Γ δ_k + w_k (Γ shape (n,)).
    process_covariance : numpy.ndarray
        Q_d = Cov(w_k).
    measurement_variance : float
        σ_v² [rad²].
    c : numpy.ndarray, shape (n,)
        ψ_m = c x + v.
    gain : numpy.ndarray, shape (n,)
        Kalman gain L.
    prior_covariance, covariance : numpy.ndarray
        P⁻ and P⁺ (after the measurement update) in steady state.
    dt : float
        Sample period Δt [s].
    state_labels : tuple of str
        ``heading_lf``, ``yaw_rate_lf``, ``rudder_bias``, then the WF filter's states.
    c_wave : numpy.ndarray, shape (n,)
        Reads ψ_W from the state.
    """

    phi: np.ndarray
    gamma: np.ndarray
    process_covariance: np.ndarray
    measurement_variance: float
    c: np.ndarray
    gain: np.ndarray
    prior_covariance: np.ndarray
    covariance: np.ndarray
    dt: float
    state_labels: tuple[str, ...]
    c_wave: np.ndarray

    def simulate(self, n_steps: int, rudder: Any = 0.0, *, runs: int = 1,
                 seed: int | None = None) -> dict[str, np.ndarray]:
        """Run the design model and the filter on it (numpy; batch axis first).

        The true state starts from the filter's prior: x₀ ~ N(0, P⁻), x̂₀⁻ = 0, so the error
        is stationary from the first step on.

        Parameters
        ----------
        n_steps : int
            Samples.
        rudder : float or array_like, shape (n_steps,)
            The rudder δ_k [rad] (known to both).
        runs : int, optional
            Independent runs.
        seed : int, optional
            Seed of ``numpy.random.default_rng``.

        Returns
        -------
        dict
            ``state`` and ``estimate`` (runs, n_steps, n) (the estimate after each update),
            ``measurement`` (runs, n_steps).
        """
        rng = np.random.default_rng(seed)
        n = self.phi.shape[0]
        delta = np.broadcast_to(np.asarray(rudder, float), (n_steps,))
        chol_q = _psd_sqrt(self.process_covariance)
        x = rng.standard_normal((runs, n)) @ _psd_sqrt(self.prior_covariance).T
        xhat = np.zeros((runs, n))
        states = np.empty((runs, n_steps, n))
        estimates = np.empty_like(states)
        ys = np.empty((runs, n_steps))
        sv = math.sqrt(self.measurement_variance)
        for k in range(n_steps):
            y = x @ self.c + sv * rng.standard_normal(runs)
            xhat = xhat + np.outer(y - xhat @ self.c, self.gain)
            states[:, k], estimates[:, k], ys[:, k] = x, xhat, y
            x = x @ self.phi.T + self.gamma * delta[k] + rng.standard_normal((runs, n)) @ chol_q.T
            xhat = xhat @ self.phi.T + self.gamma * delta[k]
        return {"state": states, "estimate": estimates, "measurement": ys}


def _psd_sqrt(m: np.ndarray) -> np.ndarray:
    w, v = np.linalg.eigh(0.5 * (m + m.T))
    return v * np.sqrt(np.clip(w, 0.0, None))


def _van_loan(a: np.ndarray, g_q_gt: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Φ = e^{AΔt}, Q_d = ∫₀^Δt e^{As} GQGᵀ e^{Aᵀs} ds (Van Loan 1978; as
    :func:`seahelm.environment.discretisation.van_loan`, which sits a layer above)."""
    from scipy import linalg

    n = a.shape[0]
    m = np.zeros((2 * n, 2 * n))
    m[:n, :n] = -a
    m[:n, n:] = g_q_gt
    m[n:, n:] = a.T
    e = linalg.expm(m * dt)
    phi = e[n:, n:].T
    qd = phi @ e[:n, n:]
    return phi, 0.5 * (qd + qd.T)


def design_wave_filter(gain: float, time_constant: float, wave: Any, dt: float, *,
                       measurement_std: float = math.radians(0.1),
                       bias_intensity: float = 1e-10) -> WaveFilterDesign:
    """The steady-state Kalman filter of the module docstring.

    Parameters
    ----------
    gain, time_constant : float
        Nomoto K [1/s] and T [s] of the LF model.
    wave : StateSpaceFilter
        The WF yaw model (``A``, ``B``, ``C``, ``noise_intensity``); its first output is ψ_W
        [rad], strictly proper (:func:`seahelm.environment.wave_yaw.wave_yaw_filter`).
    dt : float
        Sample period Δt [s] (the controller's).
    measurement_std : float, optional
        σ_v of the heading sensor [rad] (default 0.1°).
    bias_intensity : float, optional
        Intensity of the rudder-bias random walk [rad²/s].

    Returns
    -------
    WaveFilterDesign

    Raises
    ------
    ParameterError
        For non-positive arguments or a model without a stabilising filter.
    """
    from scipy import linalg

    check_positive("time_constant", time_constant, "s")
    check_positive("dt", dt, "s")
    check_positive("measurement_std", measurement_std, "rad")
    check_positive("bias_intensity", bias_intensity, "rad²/s")
    if gain == 0 or not math.isfinite(gain):
        raise ParameterError(f"must be finite and non-zero [1/s], got {gain!r}", field="gain")
    nw = wave.A.shape[0]
    n = 3 + nw
    A = np.zeros((n, n))
    A[0, 1] = 1.0
    A[1, 1] = -1.0 / time_constant
    A[1, 2] = gain / time_constant
    A[3:, 3:] = wave.A
    b = np.zeros(n)
    b[1] = gain / time_constant
    G = np.zeros((n, 2))
    G[2, 0] = 1.0
    G[3:, 1] = wave.B[:, 0]
    Qc = G @ np.diag([bias_intensity, wave.noise_intensity]) @ G.T
    phi, qd = _van_loan(A, Qc, dt)
    aug = np.zeros((n + 1, n + 1))
    aug[:n, :n] = A
    aug[:n, n] = b
    gamma = linalg.expm(aug * dt)[:n, n]
    c = np.zeros(n)
    c[0] = 1.0
    c[3:] = wave.C[0]
    R = measurement_std ** 2
    try:
        prior = linalg.solve_discrete_are(phi.T, c[:, None], qd, np.array([[R]]))
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ParameterError(f"has no stabilising Kalman filter ({exc})", field="wave") from None
    prior = 0.5 * (prior + prior.T)
    L = prior @ c / (c @ prior @ c + R)
    post = prior - np.outer(L, c @ prior)
    c_wave = np.zeros(n)
    c_wave[3:] = wave.C[0]
    return WaveFilterDesign(
        phi=phi, gamma=gamma, process_covariance=qd, measurement_variance=R, c=c, gain=L,
        prior_covariance=prior, covariance=0.5 * (post + post.T), dt=float(dt),
        state_labels=("heading_lf", "yaw_rate_lf", "rudder_bias")
        + tuple(f"wave_{i}" for i in range(nw)), c_wave=c_wave)


def _array(name: str, values: np.ndarray) -> str:
    flat = ", ".join(repr(float(v)) for v in np.ravel(values))
    return f"{name} = np.array([{flat}]).reshape({values.shape})\n"


def wave_filtered(controller: Controller, design: WaveFilterDesign) -> Controller:
    """``controller`` fed by the wave filter ``design`` (module docstring).

    Parameters
    ----------
    controller : Controller
        A heading controller: it measures ``heading`` (and may measure ``yaw_rate``) and
        commands ``rudder_command``.
    design : WaveFilterDesign

    Returns
    -------
    Controller
        Named ``wave-filter+<controller>``, the controller's parameters, references and
        commands; its outputs then :data:`WAVE_FILTER_OUTPUTS`.

    Raises
    ------
    ParameterError
        If the controller does not measure ``heading`` or command ``rudder_command``.
    """
    return _wave_filtered(controller, _Key(design))


class _Key:
    """A design hashed by its numbers (for the cache of generated controllers)."""

    def __init__(self, design: WaveFilterDesign) -> None:
        self.design = design
        self.digest = content_digest(*(np.ascontiguousarray(a, float).tobytes() for a in (
            design.phi, design.gamma, design.gain, design.c, design.c_wave,
            np.array([design.dt]))))

    def __hash__(self) -> int:
        return hash(self.digest)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Key) and other.digest == self.digest


@functools.lru_cache(maxsize=64)
def _wave_filtered(controller: Controller, key: _Key) -> Controller:
    from .._codegen import code_fingerprint, import_generated

    design = key.design
    meas = controller.measurement_labels
    if "heading" not in meas or "rudder_command" not in controller.command_labels:
        raise ParameterError(
            f"the wave filter feeds a heading controller (measuring `heading`, commanding "
            f"`rudder_command`); controller '{controller.name}' measures "
            f"{', '.join(meas) or 'nothing'} and commands {', '.join(controller.command_labels)}",
            field="controller")
    py_init, py_step = controller.init.py_func, controller.step.py_func
    n, ny = design.phi.shape[0], len(meas)
    nc, no = len(controller.command_labels), len(controller.output_labels)
    source = (
        f'"""Generated by seahelm.control.wave_filter: wave filter + {controller.name}."""\n'
        "import numpy as np\nfrom numba import njit\n\n"
        "from seahelm.control.base import wrap_pi\n"
        f"from {py_init.__module__} import {py_init.__name__} as inner_init\n"
        f"from {py_step.__module__} import {py_step.__name__} as inner_step\n\n"
        + _array("PHI", design.phi) + _array("GAMMA", design.gamma)
        + _array("GAIN", design.gain) + _array("CROW", design.c) + _array("CWAVE", design.c_wave)
        + f"NX = {n}\nNY = {ny}\nDT = {design.dt!r}\nI_HEAD = {meas.index('heading')}\n"
        f"I_RATE = {meas.index('yaw_rate') if 'yaw_rate' in meas else -1}\n"
        f"I_CMD = {controller.command_labels.index('rudder_command')}\n"
        f"I_OUT = {nc + no}\nS0 = 2 * NX + NY\n\n\n"
        "@njit(cache=True)\n"
        "def wf_init(z, y, ref, p, cs):  # pragma: no cover - compiled\n"
        "    for i in range(S0):\n"
        "        cs[i] = 0.0\n"
        "    cs[0] = y[I_HEAD]\n"
        "    inner_init(z, y, ref, p, cs[S0:])\n\n\n"
        "@njit(cache=True)\n"
        "def wf_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled\n"
        "    pred = 0.0\n"
        "    for i in range(NX):\n"
        "        pred += CROW[i] * cs[i]\n"
        "    innov = wrap_pi(y[I_HEAD] - pred)\n"
        "    for i in range(NX):\n"
        "        cs[i] += GAIN[i] * innov\n"
        "    yb = cs[NX:NX + NY]\n"
        "    for i in range(NY):\n"
        "        yb[i] = y[i]\n"
        "    yb[I_HEAD] = cs[0]\n"
        "    if I_RATE >= 0:\n"
        "        yb[I_RATE] = cs[1]\n"
        "    inner_step(t, dt, z, yb, ref, p, cs[S0:], cmd)\n"
        "    wave = 0.0\n"
        "    for i in range(NX):\n"
        "        wave += CWAVE[i] * cs[i]\n"
        "    cmd[I_OUT] = cs[0]\n"
        "    cmd[I_OUT + 1] = cs[1]\n"
        "    cmd[I_OUT + 2] = wave\n"
        "    if abs(dt - DT) > 1e-9 * DT:\n"
        "        cmd[I_CMD] = np.nan  # sampled at another period than designed for\n"
        "    delta = cmd[I_CMD]\n"
        "    tmp = cs[NX + NY:2 * NX + NY]\n"
        "    for i in range(NX):\n"
        "        acc = GAMMA[i] * delta\n"
        "        for j in range(NX):\n"
        "            acc += PHI[i, j] * cs[j]\n"
        "        tmp[i] = acc\n"
        "    for i in range(NX):\n"
        "        cs[i] = tmp[i]\n")
    digest = content_digest(source, code_fingerprint(py_init), code_fingerprint(py_step))
    module = import_generated(f"seahelm_wave_filter_{digest}", source)
    return Controller(
        name=f"wave-filter+{controller.name}",
        description=f"{controller.description}, fed by a wave-filtering Kalman filter "
                    f"(Δt = {design.dt:g} s)",
        params_type=controller.params_type,
        state_labels=tuple(f"filter_{s}" for s in design.state_labels)
        + tuple(f"filter_measurement_{m}" for m in meas)
        + tuple(f"filter_scratch_{i}" for i in range(n)) + controller.state_labels,
        reference_labels=controller.reference_labels,
        reference_units=controller.reference_units,
        command_labels=controller.command_labels,
        init=module.wf_init,
        step=module.wf_step,
        measurement_labels=meas,
        output_labels=controller.output_labels + WAVE_FILTER_OUTPUTS,
        output_units=controller.output_units + ("rad", "rad/s", "rad"),
        sample_period=design.dt,
    )
