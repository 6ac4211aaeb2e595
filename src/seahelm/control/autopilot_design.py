"""Heading-autopilot design: PID by pole placement from Nomoto K, T; LQ-integral from a model.

PID by pole placement (Fossen 2021, Algorithm 15.1)
    For the first-order Nomoto ship T ṙ + r = K δ under δ = K_p e + K_i ∫e − K_d r
    (e = ψ* − ψ) the closed loop has the characteristic polynomial
    T s³ + (1 + K K_d) s² + K K_p s + K K_i. Fossen's Algorithm 15.1 places the PD pair at
    the natural frequency ω_n and damping ζ (K_p = T ω_n²/K, K_d = (2ζω_n T − 1)/K, his
    mass–damper–spring with m = T/K, d = 1/K, k = 0) and adds K_i = K_p ω_n/10, which moves the
    poles a little. Here the three poles are placed *exactly* at the roots of
    (s² + 2ζω_n s + ω_n²)(s + 1/T_i), T_i the integral time (default 10/ω_n, Fossen's
    choice)::

        K_d = (T (2ζω_n + 1/T_i) − 1)/K,  K_p = T (ω_n² + 2ζω_n/T_i)/K,  K_i = T ω_n²/(T_i K)

    (T_i → ∞ gives Algorithm 15.1's PD gains). A bandwidth ω_b is turned into ω_n by Fossen's
    (2021) eq. (15.64): ω_n = ω_b / √(1 − 2ζ² + √(4ζ⁴ − 4ζ² + 2)).

Rudder-rate bound
    A heading loop of bandwidth ω_b asks the rudder for sinusoids up to ω_b; one of the full
    amplitude δ_max needs the rate ω_b δ_max. Above ω_b = δ̇_max/δ_max the steering gear can
    follow only smaller rudder angles (and rate saturation destabilises the loop: the
    describing-function phase lag of a rate limiter, van Amerongen 1982), so such a request is
    refused (:func:`max_bandwidth`).

Robustness
    The gain and phase margins of the loop broken at the rudder, L(s) = C(s) G_ψ(s), with G_ψ
    the heading response of the model the design is checked against (by default the Nomoto
    ship with the steering gear's first-order lag), are compared with
    :data:`MIN_GAIN_MARGIN` (2, 6 dB) and :data:`MIN_PHASE_MARGIN` (30°), the usual minimums
    (Åström & Murray 2021, §10.3); below them the design warns
    (:class:`AutopilotDesignWarning`) with the margins.

LQ-integral (Fossen 2021, §15.3.3)
    The steering block of a linearised ship (sway and yaw rate, or yaw rate alone) is
    augmented with the heading error ψ̃ = ψ − ψ* and its integral; the gains minimise
    ∫ (xᵀQx + ρ δ²) dt (continuous algebraic Riccati equation, scipy). The weights default to
    Bryson's rule: 1/(allowed value)².

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, Algorithm 15.1, eq. (15.64), §15.3.
van Amerongen, J. (1982). Adaptive steering of ships. PhD thesis, Delft.
Åström, K. J., Murray, R. M. (2021). Feedback Systems, 2nd ed. Princeton, §10.3.
Bryson, A. E., Ho, Y.-C. (1975). Applied Optimal Control, §5.4.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .._validate import check_finite, check_positive
from ..errors import ParameterError
from .lq_heading import LQHeadingParams
from .pid import PIDHeadingParams

__all__ = ["AutopilotDesignWarning", "MIN_GAIN_MARGIN", "MIN_PHASE_MARGIN", "PIDDesign",
           "LQDesign", "natural_frequency_from_bandwidth", "max_bandwidth", "pid_pole_placement",
           "nomoto_pid_poles", "loop_margins", "heading_loop_poles", "lq_heading",
           "state_space_response"]

#: Smallest acceptable gain margin [-] (6 dB) and phase margin [rad] (30°).
MIN_GAIN_MARGIN = 2.0
MIN_PHASE_MARGIN = math.radians(30.0)


class AutopilotDesignWarning(UserWarning):
    """A design is not robustly stable: its gain or phase margin is below the minimum."""


@dataclasses.dataclass(frozen=True)
class PIDDesign:
    """A pole-placement PID heading autopilot (module docstring).

    Attributes
    ----------
    params : PIDHeadingParams
        K_p [-], K_i [1/s], K_d [s], δ_max [rad]: the ``pid-heading`` controller's parameters.
    natural_frequency, damping, integral_time : float
        ω_n [rad/s], ζ [-], T_i [s] (inf: no integral action).
    bandwidth : float
        ω_b [rad/s].
    poles : numpy.ndarray
        The designed closed-loop poles with the Nomoto model [1/s].
    gain_margin, phase_margin, crossover : float
        Margins [-], [rad] and the gain-crossover frequency [rad/s] of the checked loop.
    """

    params: PIDHeadingParams
    natural_frequency: float
    damping: float
    integral_time: float
    bandwidth: float
    poles: np.ndarray
    gain_margin: float
    phase_margin: float
    crossover: float


@dataclasses.dataclass(frozen=True)
class LQDesign:
    """An LQ-integral heading autopilot.

    Attributes
    ----------
    params : LQHeadingParams
        The ``lq-heading`` controller's parameters.
    gain : numpy.ndarray
        The state-feedback row on (∫ψ̃, ψ̃, steering states...).
    states : tuple of str
        Names of the augmented states.
    poles : numpy.ndarray
        Closed-loop poles of the augmented model [1/s].
    gain_margin, phase_margin, crossover : float
        As :class:`PIDDesign` (the loop broken at the rudder, the design model).
    """

    params: LQHeadingParams
    gain: np.ndarray
    states: tuple[str, ...]
    poles: np.ndarray
    gain_margin: float
    phase_margin: float
    crossover: float


def natural_frequency_from_bandwidth(bandwidth: float, damping: float) -> float:
    """ω_n of a second-order loop of bandwidth ω_b and damping ζ (Fossen 2021, eq. (15.64)).

    Parameters
    ----------
    bandwidth : float
        ω_b [rad/s].
    damping : float
        ζ [-].

    Returns
    -------
    float
        ω_n [rad/s].
    """
    z2 = damping * damping
    return bandwidth / math.sqrt(1.0 - 2.0 * z2 + math.sqrt(4.0 * z2 * z2 - 4.0 * z2 + 2.0))


def max_bandwidth(max_rate: float, max_angle: float) -> float:
    """The largest heading-loop bandwidth the steering gear can serve: δ̇_max/δ_max [rad/s].

    Parameters
    ----------
    max_rate : float
        Rudder rate limit δ̇_max [rad/s].
    max_angle : float
        Rudder angle limit δ_max [rad].

    Returns
    -------
    float
    """
    check_positive("max_rate", max_rate, "rad/s")
    check_positive("max_angle", max_angle, "rad")
    return max_rate / max_angle


def nomoto_pid_poles(gain: float, time_constant: float, params: Any) -> np.ndarray:
    """Closed-loop poles of T ṙ + r = K δ under the PID of ``params`` (kp, ki, kd).

    Parameters
    ----------
    gain, time_constant : float
        K [1/s], T [s].
    params : PIDHeadingParams
        The gains.

    Returns
    -------
    numpy.ndarray
        Roots of T s³ + (1 + K K_d) s² + K K_p s + K K_i [1/s].
    """
    K, T = gain, time_constant
    return np.roots([T, 1.0 + K * params.kd, K * params.kp, K * params.ki])


def state_space_response(A: Any, b: Any, c: Any, omega: Any) -> np.ndarray:
    """c (jωI − A)⁻¹ b at each ω: the frequency response of a single-input, single-output
    linear model.

    Parameters
    ----------
    A : array_like, shape (n, n)
    b : array_like, shape (n,)
    c : array_like, shape (n,)
    omega : array_like
        Frequencies [rad/s].

    Returns
    -------
    numpy.ndarray (complex)
    """
    A = np.asarray(A, dtype=float)
    b = np.asarray(b, dtype=float)
    c = np.asarray(c, dtype=float)
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    eye = np.eye(A.shape[0])
    return np.array([c @ np.linalg.solve(1j * x * eye - A, b) for x in w])


def loop_margins(loop: Callable[[np.ndarray], np.ndarray], *, low: float = 1e-5,
                 high: float = 1e2, points: int = 6000) -> tuple[float, float, float]:
    """Gain margin, phase margin and gain crossover of a loop transfer function L(jω).

    Parameters
    ----------
    loop : callable
        ω [rad/s] (array) → L(jω) (complex array).
    low, high : float, optional
        Frequency range searched [rad/s].
    points : int, optional
        Grid points (log-spaced); crossings are refined by interpolation in log ω.

    Returns
    -------
    gain_margin : float
        1/|L| where the phase crosses −180° with |L| < 1: by how much the gain may grow
        (inf if it never does). A crossing with |L| > 1 (an open-loop unstable ship, whose loop
        needs a least gain) is a lower gain margin and is not counted.
    phase_margin : float
        π + ∠L at the first |L| = 1 crossing [rad] (inf without one).
    crossover : float
        That frequency [rad/s] (nan without one).
    """
    w = np.logspace(math.log10(low), math.log10(high), points)
    L = np.asarray(loop(w))
    lw = np.log(w)

    def crossings(values: np.ndarray) -> list[float]:
        sign = np.sign(values)
        found = [float(w[i]) for i in np.nonzero(sign == 0)[0]]  # on a grid point
        idx = np.nonzero(sign[:-1] * sign[1:] < 0)[0]
        found += [float(np.exp(lw[i] - values[i] * (lw[i + 1] - lw[i])
                               / (values[i + 1] - values[i]))) for i in idx]
        return sorted(found)

    gm = math.inf  # where the phase is −180° (mod 360°): Im L = 0 with Re L < 0
    for wp in crossings(L.imag):
        value = loop(np.array([wp]))[0]
        if value.real < 0 and abs(value) < 1.0:  # |L| > 1 there: a lower gain margin
            gm = min(gm, 1.0 / abs(value))
    cross = crossings(np.log(np.abs(L)))
    if not cross:
        return gm, math.inf, math.nan
    wc = cross[0]
    pm = (math.pi + float(np.angle(loop(np.array([wc]))[0]))) % (2.0 * math.pi)
    return gm, (pm - 2.0 * math.pi if pm > math.pi else pm), wc


def _warn_margins(gm: float, pm: float, what: str) -> None:
    if gm < MIN_GAIN_MARGIN or pm < MIN_PHASE_MARGIN:
        warnings.warn(
            f"{what} is not robustly stable: gain margin {gm:.3g} "
            f"({20 * math.log10(gm) if gm > 0 else -math.inf:.3g} dB; minimum "
            f"{MIN_GAIN_MARGIN:g}, 6 dB), phase margin {math.degrees(pm):.3g} deg (minimum "
            f"{math.degrees(MIN_PHASE_MARGIN):g} deg)", AutopilotDesignWarning, stacklevel=3)


def pid_pole_placement(gain: float, time_constant: float, *, bandwidth: float | None = None,
                       natural_frequency: float | None = None, damping: float = 0.8,
                       integral_time: float | None = None,
                       max_command: float = math.radians(35.0),
                       max_rate: float | None = None, servo_time_constant: float = 0.0,
                       heading_response: Callable[[np.ndarray], np.ndarray] | None = None
                       ) -> PIDDesign:
    """PID heading gains placing the Nomoto loop's poles exactly (module docstring).

    Parameters
    ----------
    gain, time_constant : float
        Nomoto K [1/s] and T [s] (both negative for a course-unstable ship).
    bandwidth : float, optional
        Closed-loop bandwidth ω_b [rad/s] (give it or ``natural_frequency``).
    natural_frequency : float, optional
        ω_n [rad/s] directly.
    damping : float, optional
        ζ [-] (default 0.8).
    integral_time : float, optional
        T_i [s] of the third pole −1/T_i (default 10/ω_n; ``inf`` for a PD).
    max_command : float, optional
        δ_max [rad] (default 35°).
    max_rate : float, optional
        Rudder rate limit δ̇_max [rad/s]: a bandwidth above δ̇_max/δ_max is refused.
    servo_time_constant : float, optional
        Steering-gear lag T_δ [s] included in the margins (default 0).
    heading_response : callable, optional
        ω → ψ/δ_c(jω) of the model to check the margins against (default the Nomoto ship with
        the servo lag).

    Returns
    -------
    PIDDesign

    Raises
    ------
    ParameterError
        For a non-positive ω_b, ζ or T_i, K = 0 or K and T of opposite signs (the pair is not
        a Nomoto ship), a bandwidth above the rudder-rate bound (field ``bandwidth``), or a
        design that needs a negative derivative gain.

    Warns
    -----
    AutopilotDesignWarning
        When the margins are below :data:`MIN_GAIN_MARGIN` / :data:`MIN_PHASE_MARGIN`.
    """
    check_finite("gain", gain, "1/s")
    check_finite("time_constant", time_constant, "s")
    if gain == 0.0 or time_constant == 0.0 or (gain > 0) != (time_constant > 0):
        raise ParameterError(
            f"K = {gain!r} [1/s], T = {time_constant!r} [s]: the rudder does not steer this "
            "model (K = 0) or K and T differ in sign (uncontrollable for the pole placement)",
            field="gain", unit="1/s", value=gain)
    check_positive("damping", damping, "-")
    check_positive("max_command", max_command, "rad")
    if (bandwidth is None) == (natural_frequency is None):
        raise ParameterError("give one of `bandwidth` and `natural_frequency`",
                             field="bandwidth")
    if bandwidth is not None:
        check_positive("bandwidth", bandwidth, "rad/s")
        wn = natural_frequency_from_bandwidth(bandwidth, damping)
    else:
        check_positive("natural_frequency", natural_frequency, "rad/s")
        wn = float(natural_frequency)  # type: ignore[arg-type]
        z2 = damping * damping
        bandwidth = wn * math.sqrt(1 - 2 * z2 + math.sqrt(4 * z2 * z2 - 4 * z2 + 2))
    if max_rate is not None:
        limit = max_bandwidth(max_rate, max_command)
        if bandwidth > limit:
            raise ParameterError(
                f"must be <= {limit:.4g} [rad/s], got {bandwidth:.4g}: the steering gear's "
                f"rate limit {math.degrees(max_rate):.3g} deg/s over the rudder limit "
                f"{math.degrees(max_command):.3g} deg serves no faster full-rudder sinusoid",
                field="bandwidth", unit="rad/s", value=bandwidth)
    Ti = 10.0 / wn if integral_time is None else float(integral_time)
    if math.isfinite(Ti):
        check_positive("integral_time", Ti, "s")
    K, T = float(gain), float(time_constant)
    inv_ti = 0.0 if math.isinf(Ti) else 1.0 / Ti
    kd = (T * (2.0 * damping * wn + inv_ti) - 1.0) / K
    kp = T * (wn * wn + 2.0 * damping * wn * inv_ti) / K
    ki = T * wn * wn * inv_ti / K
    if kd < 0:
        raise ParameterError(
            f"gives a negative derivative gain K_d = {kd:.4g} [s]: ω_n = {wn:.4g} rad/s is "
            f"below what the ship's own damping gives (2ζω_n + 1/T_i < 1/T = {1 / T:.4g} 1/s); "
            "ask for a larger bandwidth", field="bandwidth", unit="rad/s", value=bandwidth)
    params = PIDHeadingParams(kp=kp, ki=ki, kd=kd, max_command=max_command)
    poles = nomoto_pid_poles(K, T, params)
    if heading_response is None:
        def heading_response(w: np.ndarray) -> np.ndarray:
            s = 1j * w
            return K / (s * (T * s + 1.0) * (servo_time_constant * s + 1.0))
    gm, pm, wc = loop_margins(lambda w: (kp + ki / (1j * w) + kd * 1j * w)
                              * heading_response(w))
    _warn_margins(gm, pm, f"the PID design (bandwidth {bandwidth:.4g} rad/s)")
    return PIDDesign(params=params, natural_frequency=wn, damping=float(damping),
                     integral_time=Ti, bandwidth=float(bandwidth), poles=poles,
                     gain_margin=gm, phase_margin=pm, crossover=wc)


def heading_loop_poles(A: Any, b: Any, c_heading: Any, c_yaw_rate: Any, *, k_heading: float,
                       k_yaw_rate: float, k_integral: float, c_sway: Any = None,
                       k_sway: float = 0.0) -> np.ndarray:
    """Closed-loop poles of a linear model under δ = −k_i ∫ψ − k_ψ ψ − k_r r − k_v v.

    The PID (k_ψ = K_p, k_r = K_d, k_i = K_i) and the LQ-integral law both have this form
    about ψ* = 0; ``A``, ``b`` may be the ship with its steering gear (input the command).

    Parameters
    ----------
    A : array_like, shape (n, n)
    b : array_like, shape (n,)
    c_heading, c_yaw_rate, c_sway : array_like, shape (n,)
        Rows reading ψ, r and v from the state.
    k_heading, k_yaw_rate, k_integral, k_sway : float
        The gains.

    Returns
    -------
    numpy.ndarray
        The n + 1 poles [1/s].
    """
    A = np.asarray(A, dtype=float)
    b = np.asarray(b, dtype=float)
    n = A.shape[0]
    k = k_heading * np.asarray(c_heading, float) + k_yaw_rate * np.asarray(c_yaw_rate, float)
    if c_sway is not None:
        k = k + k_sway * np.asarray(c_sway, float)
    Acl = np.zeros((n + 1, n + 1))
    Acl[:n, :n] = A - np.outer(b, k)
    Acl[:n, n] = -b * k_integral
    Acl[n, :n] = c_heading
    return np.linalg.eigvals(Acl)


def lq_heading(A: Any, b: Any, states: Sequence[str], *, max_heading_error: float = 0.1,
               max_integral: float | None = None, max_yaw_rate: float | None = None,
               max_rudder: float = math.radians(35.0), max_command: float | None = None
               ) -> LQDesign:
    """LQ-integral heading gains for a linear steering block (module docstring).

    Parameters
    ----------
    A : array_like, shape (n, n)
        The steering block (states ``states``: ``yaw_rate`` and optionally ``sway_speed``)
        [1/s].
    b : array_like, shape (n,)
        Its rudder column.
    states : sequence of str
        Names of the block's states.
    max_heading_error : float, optional
        Bryson weight: allowed heading error [rad] (default 0.1).
    max_integral : float, optional
        Allowed ∫ψ̃ dt [rad·s] (default 100 × ``max_heading_error`` s).
    max_yaw_rate : float, optional
        Allowed yaw rate [rad/s] (default: not weighted).
    max_rudder : float, optional
        Allowed rudder angle [rad] (ρ = 1/δ²; default 35°).
    max_command : float, optional
        The controller's saturation (default ``max_rudder``).

    Returns
    -------
    LQDesign

    Raises
    ------
    ParameterError
        If the augmented pair (A, b) is not stabilisable (e.g. the rudder does not act on the
        yaw rate), or a state name is not ``yaw_rate``/``sway_speed``.
    """
    from scipy.linalg import solve_continuous_are

    A = np.atleast_2d(np.asarray(A, dtype=float))
    b = np.atleast_1d(np.asarray(b, dtype=float))
    states = tuple(states)
    unknown = [s for s in states if s not in ("yaw_rate", "sway_speed")]
    if unknown or "yaw_rate" not in states:
        raise ParameterError(f"must be yaw_rate and optionally sway_speed, got {states}",
                             field="states")
    check_positive("max_heading_error", max_heading_error, "rad")
    check_positive("max_rudder", max_rudder, "rad")
    n = len(states)
    ir = states.index("yaw_rate")
    # augmented state (∫ψ̃, ψ̃, block)
    Aa = np.zeros((n + 2, n + 2))
    Aa[0, 1] = 1.0
    Aa[1, 2 + ir] = 1.0
    Aa[2:, 2:] = A
    ba = np.concatenate([[0.0, 0.0], b])
    ctrb = np.column_stack([np.linalg.matrix_power(Aa, k) @ ba for k in range(n + 2)])
    sv = np.linalg.svd(ctrb / np.maximum(np.abs(ctrb).max(axis=0), 1e-300), compute_uv=False)
    if not sv[-1] > 1e-12 * sv[0]:
        raise ParameterError(
            "the rudder does not control this model (the augmented pair (A, b) is "
            f"uncontrollable: controllability singular values {sv[0]:.3g} ... {sv[-1]:.3g})",
            field="model")
    q = np.zeros(n + 2)
    q[0] = 1.0 / (max_integral if max_integral is not None else 100.0 * max_heading_error) ** 2
    q[1] = 1.0 / max_heading_error ** 2
    if max_yaw_rate is not None:
        check_positive("max_yaw_rate", max_yaw_rate, "rad/s")
        q[2 + ir] = 1.0 / max_yaw_rate ** 2
    R = np.array([[1.0 / max_rudder ** 2]])
    try:
        P = solve_continuous_are(Aa, ba[:, None], np.diag(q), R)
    except np.linalg.LinAlgError as exc:
        raise ParameterError(f"has no stabilising LQ solution ({exc})", field="model") from None
    k = (ba @ P) / R[0, 0]
    poles = np.linalg.eigvals(Aa - np.outer(ba, k))
    values = {"k_integral": k[0], "k_heading": k[1], "k_yaw_rate": k[2 + ir]}
    if "sway_speed" in states:
        values["k_sway"] = k[2 + states.index("sway_speed")]
    params = LQHeadingParams(**{key: float(v) for key, v in values.items()},
                             max_command=max_command or max_rudder)
    # margins: loop broken at the rudder, L = k (sI − Aa)⁻¹ ba
    gm, pm, wc = loop_margins(lambda w: state_space_response(Aa, ba, k, w))
    _warn_margins(gm, pm, "the LQ design")
    return LQDesign(params=params, gain=k, states=("heading_error_integral", "heading_error")
                    + states, poles=poles, gain_margin=gm, phase_margin=pm, crossover=wc)
