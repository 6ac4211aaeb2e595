"""Wind and wave compensation of a course autopilot, after Lvov (2014), eq. (12)-(14), Fig. 1.

The course control system of Lvov (2014), Fig. 1: a course setter (1) computes the course
to steer from the departure and arrival coordinates and the wind and wave drift angles; the
autopilot (2, 3) steers the ship (4) onto it; a wind compensator (5) and a wave compensator (6)
compute the inputs of block (7), which lays the rudder to the compensating angle δ_k so that the
autopilot only works about δ_k. Block (7) also watches for the loss of controllability,
δ_k + δ_b > δ_max = 35°, δ_b being the rudder activity about δ_k.

Pieces (numpy, broadcasting over leading batch axes; radians inside):

* :func:`lateral_resistance_centre` — eq. (13);
* :func:`hull_drift_coefficient`, :func:`drift_angle` — the hull's lateral force at drift
  angle α as used in eq. (12), and the drift angle that balances a lateral force;
* :func:`wind_compensation`, :func:`wave_compensation`, :func:`compensating_rudder_angle`
  — eq. (12) and eq. (14);
* :func:`controllability_monitor` — the loss-of-controllability check on recorded runs;
* :data:`COMPENSATED_PID` — the compiled controller of Fig. 1 (PID + the two compensation
  channels fed forward).

The course setter (block 1) is :mod:`seahelm.control.guidance`
(:func:`~seahelm.control.guidance.initial_great_circle_course`,
:func:`~seahelm.control.guidance.course_to_steer`).

Units and the paper's degree terms
----------------------------------
Eq. (12) as printed::

    δ_k = (1 + 2/λ_p)/(S_p ρ) · [ (0.25 + ℓ_sail/L − q_w/360) · 0.37 sin q_w ρ_a S_a W²/V²
                                 + (0.5 + ℓ_lr/L − α/180) · C_h(α) · ρ S_h ]
    C_h(α) = (0.23 sin α + 1.09 sin² α)/(2.1 δ − 7 T/L)²

q_w and α appear in *degrees* in the arm terms (q_w/360, α/180) and inside sin() as angles;
we take radians everywhere and convert for the two degree terms only. Both bracket terms are
in [kg/m] (a yaw moment divided by V² L), so δ_k is in radians. For wind or drift from port
(q_w, α < 0) the arms use |q_w|, |α| and sin² α becomes sin α |sin α|, so that δ_k is odd in
the angles as a port–starboard symmetric hull requires (the paper treats q_w, α ≥ 0 only).

Eq. (14) as printed differs from (12) in two ways that we treat as misprints:

1. the wind term has lost its W²/V² factor — without it the bracket mixes [kg/m] with the
   wind *coefficient*; we keep W²/V² as in (12), since the paper states that (14) is (12)
   plus the wave moment;
2. the wave moment M_w of eq. (10) [N·m] is added to terms in [kg/m]; we divide it by V² L,
   the same normalisation as the two other terms (rudder moment ≈ S_p ρ V² L δ/(1 + 2/λ_p)).

Its exponent e^(−A0 z/L) is e^(−A0 λ/L) as in eq. (8)-(10) (README note on the paper).
Eq. (13) as printed is already dimensionless: it gives ℓ_lr/L, positive forward of
midships (0 on an even keel), and that is what :func:`lateral_resistance_centre` returns.

Sign convention: as in :mod:`seahelm.environment.wave_forces`, q_w is the bearing the wind and
waves come *from*, positive from starboard, and the paper's force and moment are positive for
q_w > 0 (pushing to port). In seahelm's body axes those loads turn the bow to port for a
forward wind (negative yaw moment), which a *positive* rudder (positive yaw rate) balances — so
the paper's δ_k is the rudder angle in seahelm's convention and the controller adds it as is.

The printed formula on a simulated ship
---------------------------------------
Eq. (12) adds the hull term (drift α) to the wind term with the same sign; on the Mariner
Voitkunsky model the two moments oppose each other and the balancing rudder has the opposite
sign of eq. (12)/(14). The paper's ship data, the weather cases, the closed-loop scenario and
the two ways of computing δ_k (the ship model's steady balance, and eq. (12)/(14) as printed)
are the paper's reproduction, in :mod:`seahelm.studies.lvov2014`.

References
----------
Lvov, V. E. (2014), eq. (12)-(14), Fig. 1. Lvov, V. E. (2008), Sudovozhdenie 15, 109-114
(the wind compensator, eq. (12)-(13)).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, NamedTuple

import numpy as np
from numba import njit
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_on_hull, check_positive
from ..constants import RHO_AIR, RHO_SEAWATER, wrap_angle
from ..errors import ParameterError
from ..parameters import param, signal_indices
from .base import Controller, wrap_pi
from .pid import PIDHeadingParams

__all__ = [
    "DEFAULT_MAX_RUDDER",
    "lateral_resistance_centre",
    "hull_drift_coefficient",
    "drift_angle",
    "wind_compensation",
    "wave_compensation",
    "compensating_rudder_angle",
    "ControllabilityReport",
    "controllability_monitor",
    "CompensatedPIDParams",
    "COMPENSATED_PID",
]

#: δ_max of the loss-of-controllability criterion [rad] (35°, Lvov (2014)).
DEFAULT_MAX_RUDDER: float = math.radians(35.0)


# ------------------------------------------------------------------------------------------
# eq. (13), the hull drift force, the drift angle
# ------------------------------------------------------------------------------------------
def lateral_resistance_centre(draft_fore: ArrayLike, draft_aft: ArrayLike) -> np.ndarray:
    """Centre of lateral resistance ℓ_lr/L forward of midships [-], Lvov (2014) eq. (13).

    ::

        ℓ_lr/L = (1 + 2 T_f/T_a) / (3 (1 + T_f/T_a)) − 0.5                    (13)

    0 on an even keel, negative (aft) when trimmed by the stern. Multiply by L for metres.

    Parameters
    ----------
    draft_fore, draft_aft : array_like
        Drafts at the forward and aft perpendiculars T_f, T_a [m] (> 0).
    """
    tf = as_float_array("draft_fore", draft_fore, "m")
    ta = as_float_array("draft_aft", draft_aft, "m")
    check_positive("draft_fore", tf, "m")
    check_positive("draft_aft", ta, "m")
    k = tf / ta
    return (1.0 + 2.0 * k) / (3.0 * (1.0 + k)) - 0.5


def _signed_sq(s: np.ndarray) -> np.ndarray:
    return s * np.abs(s)


def hull_drift_coefficient(
    drift: ArrayLike, block_coefficient: ArrayLike, draft: ArrayLike, length: ArrayLike
) -> np.ndarray:
    """C_h(α) = (0.23 sin α + 1.09 sin α|sin α|)/(2.1 δ − 7 T/L)² [-] (eq. (12)).

    The hull's lateral force at drift angle α is C_h(α) ρ S_h V² [N].

    Parameters
    ----------
    drift : array_like
        Drift angle α [rad].
    block_coefficient : array_like
        δ [-].
    draft, length : array_like
        Mean draft T and length L [m].
    """
    a = as_float_array("drift", drift, "rad")
    cb = as_float_array("block_coefficient", block_coefficient, "-")
    T = as_float_array("draft", draft, "m")
    L = as_float_array("length", length, "m")
    denom = (2.1 * cb - 7.0 * T / L) ** 2
    if np.any(denom == 0.0):
        raise ParameterError("2.1 δ − 7 T/L must not be 0 (eq. (12) denominator)")
    s = np.sin(a)
    return (0.23 * s + 1.09 * _signed_sq(s)) / denom


def drift_angle(
    lateral_force: ArrayLike,
    *,
    speed: ArrayLike,
    underwater_area: ArrayLike,
    block_coefficient: ArrayLike,
    draft: ArrayLike,
    length: ArrayLike,
    rho: float = RHO_SEAWATER,
) -> np.ndarray:
    """Drift angle α [rad] at which the hull force C_h(α) ρ S_h V² balances ``lateral_force``.

    Solves 1.09 s|s| + 0.23 s = F (2.1 δ − 7T/L)²/(ρ S_h V²) for s = sin α (the root with the
    sign of F). Used for the wind drift angle α of eq. (12) and for the wave drift angle of
    the course setter (block 1 of Fig. 1).

    Parameters
    ----------
    lateral_force : array_like
        Paper-signed lateral load [N] (wind of :func:`~seahelm.environment.wind.wind_lateral_force`,
        waves of eq. (9)).
    speed : array_like
        Ship speed V [m/s] (> 0).
    underwater_area : array_like
        Lateral underwater area S_h [m²].
    block_coefficient, draft, length : array_like
        Block coefficient δ [-], draft T [m], length L [m].
    rho : float
        Water density ρ [kg/m³].

    Returns
    -------
    numpy.ndarray
        Drift angle α [rad].
    """
    f = as_float_array("lateral_force", lateral_force, "N")
    v = as_float_array("speed", speed, "m/s")
    check_positive("speed", v, "m/s")
    s_h = as_float_array("underwater_area", underwater_area, "m²")
    check_positive("underwater_area", s_h, "m²")
    cb = as_float_array("block_coefficient", block_coefficient, "-")
    T = as_float_array("draft", draft, "m")
    L = as_float_array("length", length, "m")
    k = np.abs(f) * (2.1 * cb - 7.0 * T / L) ** 2 / (rho * s_h * v**2)
    s = (-0.23 + np.sqrt(0.23**2 + 4.0 * 1.09 * k)) / (2.0 * 1.09)
    return np.sign(f) * np.arcsin(np.minimum(s, 1.0))


# ------------------------------------------------------------------------------------------
# eq. (12), (14)
# ------------------------------------------------------------------------------------------
def _rudder_factor(rudder_area: Any, rudder_aspect_ratio: Any, rho: float) -> np.ndarray:
    sp = as_float_array("rudder_area", rudder_area, "m²")
    check_positive("rudder_area", sp, "m²")
    lam = as_float_array("rudder_aspect_ratio", rudder_aspect_ratio, "-")
    check_positive("rudder_aspect_ratio", lam, "-")
    return (1.0 + 2.0 / lam) / (sp * rho)


def wind_compensation(
    *,
    wind_speed: ArrayLike,
    wind_angle: ArrayLike,
    drift: ArrayLike,
    speed: ArrayLike,
    length: ArrayLike,
    draft: ArrayLike,
    block_coefficient: ArrayLike,
    rudder_area: ArrayLike,
    rudder_aspect_ratio: ArrayLike,
    windage_area: ArrayLike,
    underwater_area: ArrayLike,
    sail_centre: ArrayLike = 0.0,
    resistance_centre: ArrayLike = 0.0,
    rho: float = RHO_SEAWATER,
    rho_air: float = RHO_AIR,
) -> np.ndarray:
    """Compensating rudder angle for the wind, δ_k of Lvov (2014) eq. (12) [rad].

    ::

        δ_k = (1 + 2/λ_p)/(S_p ρ) [ (0.25 + ℓ_sail/L − |q_w|°/360) 0.37 sin q_w ρ_a S_a W²/V²
                                   + (0.5 + ℓ_lr/L − |α|°/180) C_h(α) ρ S_h ]

    Parameters
    ----------
    wind_speed : array_like
        Apparent wind speed W [m/s].
    wind_angle : array_like
        Apparent-wind bearing q_w [rad], 0 head wind, positive from starboard.
    drift : array_like
        Wind drift angle α [rad] (e.g. :func:`drift_angle` of the wind force).
    speed : array_like
        Ship speed through the water V [m/s] (the paper's V_л, speed by log), > 0.
    length, draft : array_like
        L, mean draft T [m].
    block_coefficient : array_like
        δ [-].
    rudder_area : array_like
        S_p [m²].
    rudder_aspect_ratio : array_like
        λ_p [-].
    windage_area : array_like
        S_a [m²], lateral area above water.
    underwater_area : array_like
        S_h [m²], lateral area under water (≈ L T).
    sail_centre : array_like
        ℓ_sail [m], centre of windage forward of midships.
    resistance_centre : array_like
        ℓ_lr/L [-], from :func:`lateral_resistance_centre` (eq. (13)).
    rho, rho_air : float
        Water and air density [kg/m³].

    Returns
    -------
    numpy.ndarray
        δ_k [rad] (seahelm's rudder convention, see the module docstring).
    """
    w = as_float_array("wind_speed", wind_speed, "m/s")
    check_nonnegative("wind_speed", w, "m/s")
    q = wrap_angle(as_float_array("wind_angle", wind_angle, "rad"))
    a = as_float_array("drift", drift, "rad")
    v = as_float_array("speed", speed, "m/s")
    check_positive("speed", v, "m/s")
    L = as_float_array("length", length, "m")
    check_positive("length", L, "m")
    s_a = as_float_array("windage_area", windage_area, "m²")
    s_h = as_float_array("underwater_area", underwater_area, "m²")
    check_nonnegative("windage_area", s_a, "m²")
    check_positive("underwater_area", s_h, "m²")
    l_sail = as_float_array("sail_centre", sail_centre, "m")
    check_on_hull("sail_centre", l_sail, L)
    l_lr = as_float_array("resistance_centre", resistance_centre, "-")
    factor = _rudder_factor(rudder_area, rudder_aspect_ratio, rho)
    wind = (
        (0.25 + l_sail / L - np.degrees(np.abs(q)) / 360.0)
        * 0.37 * np.sin(q) * rho_air * s_a * w**2 / v**2
    )
    hull = (
        (0.5 + l_lr - np.degrees(np.abs(a)) / 180.0)
        * hull_drift_coefficient(a, block_coefficient, draft, L) * rho * s_h
    )
    return factor * (wind + hull)


def wave_compensation(
    wave_moment: ArrayLike,
    *,
    speed: ArrayLike,
    length: ArrayLike,
    rudder_area: ArrayLike,
    rudder_aspect_ratio: ArrayLike,
    rho: float = RHO_SEAWATER,
) -> np.ndarray:
    """The wave term of eq. (14): (1 + 2/λ_p)/(S_p ρ) · M_w/(V² L) [rad].

    Parameters
    ----------
    wave_moment : array_like
        M_w [N·m] of eq. (10) (paper sign), :func:`seahelm.environment.wave_forces.wave_forces`.
    speed : array_like
        V [m/s] (> 0).
    length : array_like
        L [m].
    rudder_area, rudder_aspect_ratio : array_like
        S_p [m²], λ_p [-].
    rho : float
        ρ [kg/m³].

    Notes
    -----
    The division by V² L is our reading of eq. (14) (module docstring): as printed the wave
    moment [N·m] is added to terms in [kg/m].
    """
    m = as_float_array("wave_moment", wave_moment, "N·m")
    v = as_float_array("speed", speed, "m/s")
    check_positive("speed", v, "m/s")
    L = as_float_array("length", length, "m")
    check_positive("length", L, "m")
    return _rudder_factor(rudder_area, rudder_aspect_ratio, rho) * m / (v**2 * L)


def compensating_rudder_angle(*, wave_moment: ArrayLike = 0.0, **wind: Any) -> np.ndarray:
    """Wind + wave compensating rudder angle δ_k, Lvov (2014) eq. (14) [rad].

    δ_k = :func:`wind_compensation` (eq. (12)) + :func:`wave_compensation` (the M_w term);
    with ``wave_moment = 0`` this is eq. (12). Keyword arguments as :func:`wind_compensation`.

    Parameters
    ----------
    wave_moment : array_like, optional
        Paper-signed wave yaw moment M_w [N·m] of eq. (10) (default 0: wind only).
    **wind
        Keyword arguments of :func:`wind_compensation` (``speed`` [m/s], ``length`` [m],
        ``rudder_area`` [m²], ``rudder_aspect_ratio`` [-], ``rho`` [kg/m³], ...).

    Returns
    -------
    numpy.ndarray
        δ_k [rad].
    """
    dk = wind_compensation(**wind)
    if np.any(np.asarray(wave_moment, dtype=float) != 0.0):
        dk = dk + wave_compensation(
            wave_moment,
            speed=wind["speed"],
            length=wind["length"],
            rudder_area=wind["rudder_area"],
            rudder_aspect_ratio=wind["rudder_aspect_ratio"],
            rho=wind.get("rho", RHO_SEAWATER),
        )
    return dk


# ------------------------------------------------------------------------------------------
# loss-of-controllability monitor (block 7)
# ------------------------------------------------------------------------------------------
class ControllabilityReport(NamedTuple):
    """Result of :func:`controllability_monitor` (arrays over the leading batch axes)."""

    activity: np.ndarray
    """δ_b(t) [rad]: max |δ − δ_k| over the trailing window, shape like ``rudder``."""
    flag: np.ndarray
    """Boolean, |δ_k| + δ_b > δ_max at each sample."""
    lost: np.ndarray
    """Boolean per run: the flag was raised at least once."""
    first_time: np.ndarray
    """Time [s] of the first flag per run (NaN if never)."""


def controllability_monitor(
    rudder: ArrayLike,
    delta_k: ArrayLike,
    *,
    dt: float,
    window: float = 60.0,
    max_angle: float = DEFAULT_MAX_RUDDER,
    t0: float = 0.0,
    start: float | None = None,
) -> ControllabilityReport:
    """Flag the loss of controllability |δ_k| + δ_b > δ_max (Lvov (2014), block 7 of Fig. 1).

    δ_b, the rudder activity about δ_k, is taken as the largest |δ − δ_k| over the trailing
    ``window`` (the paper does not define it further). Works on recorded result arrays.

    Parameters
    ----------
    rudder : array_like, shape (..., n)
        Rudder angle (or command) δ [rad] on a uniform time grid.
    delta_k : array_like, broadcastable to ``rudder``
        Compensating angle δ_k [rad] (a constant or a series).
    dt : float
        Sample interval [s].
    window : float
        Trailing window [s] for δ_b (≥ dt).
    max_angle : float
        δ_max [rad] (35° by default).
    t0 : float
        Time of the first sample [s].
    start : float, optional
        Time [s] from which flags count (e.g. after the rudder has been laid to a new δ_k,
        whose slewing would otherwise count as activity); default ``t0``.

    Returns
    -------
    ControllabilityReport
    """
    d = as_float_array("rudder", rudder, "rad", finite=False)
    dk = np.broadcast_to(as_float_array("delta_k", delta_k, "rad", finite=False), d.shape)
    check_positive("dt", dt, "s")
    check_positive("window", window, "s")
    check_positive("max_angle", max_angle, "rad")
    if d.ndim == 0 or d.shape[-1] == 0:
        raise ParameterError(f"`rudder` must have a time axis, got shape {d.shape}")
    n_win = max(int(round(window / dt)), 1)
    dev = np.abs(d - dk)
    pad = np.concatenate([np.repeat(dev[..., :1], n_win - 1, axis=-1) * 0.0, dev], axis=-1)
    win = np.lib.stride_tricks.sliding_window_view(pad, n_win, axis=-1)
    activity = np.max(win, axis=-1)
    flag = np.abs(dk) + activity > max_angle
    if start is not None:
        flag &= (t0 + np.arange(d.shape[-1]) * dt) >= start
    lost = np.any(flag, axis=-1)
    idx = np.argmax(flag, axis=-1)
    first = np.where(lost, t0 + idx * dt, np.nan)
    return ControllabilityReport(activity, flag, lost, first)


# ------------------------------------------------------------------------------------------
# the compiled controller of Fig. 1
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True, kw_only=True)
class CompensatedPIDParams(PIDHeadingParams):
    """PID heading autopilot (the :class:`~seahelm.control.pid.PIDHeadingParams` gains) with
    the wind and wave compensation channels of Fig. 1."""

    wind_gain: float = param(1.0, unit="", symbol="k_5", low=0.0,
                             doc="weight of the wind compensation channel (block 5); 0 = off")
    wave_gain: float = param(1.0, unit="", symbol="k_6", low=0.0,
                             doc="weight of the wave compensation channel (block 6); 0 = off")
    feedforward_time_constant: float = param(
        0.0, unit="s", symbol="T_k", low=0.0,
        doc="first-order lag on δ_k before it is added (0 = none; lets the ship's drift build up)")


COMPENSATED_MEASUREMENTS: tuple[str, ...] = ("heading", "yaw_rate")
COMPENSATED_REFERENCES: tuple[str, ...] = ("heading", "delta_k_wind", "delta_k_wave")
COMPENSATED_COMMANDS: tuple[str, ...] = ("rudder_command",)
COMPENSATED_STATES: tuple[str, ...] = ("heading_error_integral", "delta_k_filtered")

_M = signal_indices(COMPENSATED_MEASUREMENTS)
_R = signal_indices(COMPENSATED_REFERENCES)
_C = signal_indices(COMPENSATED_COMMANDS)
_S = signal_indices(COMPENSATED_STATES)


@njit(cache=True)
def compensated_pid_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_S.heading_error_integral] = 0.0
    cs[_S.delta_k_filtered] = 0.0


@njit(cache=True)
def compensated_pid_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    kp = p.kp
    ki = p.ki
    kd = p.kd
    umax = p.max_command
    e = wrap_pi(ref[_R.heading] - y[_M.heading])
    dk = 0.0
    if ref.shape[0] > _R.delta_k_wind:
        dk += p.wind_gain * ref[_R.delta_k_wind]
    if ref.shape[0] > _R.delta_k_wave:
        dk += p.wave_gain * ref[_R.delta_k_wave]
    tk = p.feedforward_time_constant
    if tk > 0.0:
        # backward-Euler first-order lag
        dk = cs[_S.delta_k_filtered] + (dk - cs[_S.delta_k_filtered]) * dt / (tk + dt)
    cs[_S.delta_k_filtered] = dk
    integral = cs[_S.heading_error_integral]
    u_unsat = dk + kp * e + ki * integral - kd * y[_M.yaw_rate]
    u = min(max(u_unsat, -umax), umax)
    if u == u_unsat or e * (u_unsat - dk) < 0.0:
        cs[_S.heading_error_integral] = integral + e * dt
    cmd[_C.rudder_command] = u


COMPENSATED_PID = Controller(
    name="compensated-pid",
    description="PID heading autopilot plus the wind and wave compensating rudder angle δ_k "
    "fed forward (Lvov (2014), Fig. 1, eq. (12)-(14))",
    params_type=CompensatedPIDParams,
    state_labels=COMPENSATED_STATES,
    reference_labels=COMPENSATED_REFERENCES,
    reference_units=("rad", "rad", "rad"),
    command_labels=COMPENSATED_COMMANDS,
    command_units=("rad",),
    state_units=("rad·s", "rad"),
    init=compensated_pid_init,
    step=compensated_pid_step,
    measurement_labels=COMPENSATED_MEASUREMENTS,
)
