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
* :func:`initial_great_circle_course`, :func:`course_to_steer` — the course setter;
* :data:`COMPENSATED_PID` — the compiled controller of Fig. 1 (PID + the two compensation
  channels fed forward), and :func:`wind_wave_scenario` which prepares a closed-loop run on the
  Voitkunsky model with wind and wave loads as disturbances.

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

What the printed formula gets wrong on a simulated ship
-------------------------------------------------------
Eq. (12) adds the hull term (drift α) to the wind term with the same sign. Physically the two
moments oppose each other: the wind on a forward bearing turns the bow to leeward, while the
hull's lateral resistance, centred forward (the (0.5 + ℓ_lr/L − α/180) L arm of eq. (12)),
turns it to windward. On the Mariner Voitkunsky model the drift (Munk) moment dominates, and
the balancing rudder has the *opposite* sign of eq. (12)/(14): wind 15 m/s and h3% = 6.75 m
from 60° off the starboard bow need −9.6° in the model, eq. (14) gives +13.3°. Feeding the
printed δ_k forward then makes course keeping worse than PID alone (see
``examples/compensation_table.py``). :func:`wind_wave_scenario` therefore offers
``delta_k_method="model"`` — block 7 computes δ_k as the steady balancing rudder angle of the
ship model for the loads the wind and wave compensators (blocks 5, 6) estimate — next to
``"paper"`` (eq. (12)/(14) as printed).

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
from ..parameters import Params, param, signal_indices
from .base import Controller, wrap_pi
from .guidance import course_to_steer, initial_great_circle_course
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
    "initial_great_circle_course",
    "course_to_steer",
    "CompensatedPIDParams",
    "COMPENSATED_PID",
    "ShipParticulars",
    "MARINER_PARTICULARS",
    "CompensationSummary",
    "compensation_summary",
    "ModelCompensation",
    "model_compensation",
    "WindWaveCase",
    "wind_wave_scenario",
    "heading_metrics",
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
    init=compensated_pid_init,
    step=compensated_pid_step,
    measurement_labels=COMPENSATED_MEASUREMENTS,
)


# ------------------------------------------------------------------------------------------
# ship particulars, one-shot summary (CLI), closed-loop case
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True, kw_only=True)
class ShipParticulars(Params):
    """Hull, rudder and loading data used by eq. (5)-(14) (SI units)."""

    length: float = param(unit="m", symbol="L", low=0.0, low_inclusive=False, doc="length")
    beam: float = param(unit="m", symbol="B", low=0.0, low_inclusive=False, doc="beam")
    draft: float = param(unit="m", symbol="T", low=0.0, low_inclusive=False, doc="mean draft")
    draft_fore: float = param(0.0, unit="m", symbol="T_f", low=0.0,
                              doc="draft forward (0: the mean draft)")
    draft_aft: float = param(0.0, unit="m", symbol="T_a", low=0.0,
                             doc="draft aft (0: the mean draft)")
    block_coefficient: float = param(unit="", symbol="δ", low=0.0, low_inclusive=False,
                                     high=1.0, doc="block coefficient")
    speed: float = param(unit="m/s", symbol="V", low=0.0, low_inclusive=False,
                         doc="speed through the water (by log)")
    rudder_area: float = param(0.0, unit="m²", symbol="S_p", low=0.0,
                               doc="rudder area (0: 1.7 % of L·T)")
    rudder_aspect_ratio: float = param(1.6, unit="", symbol="λ_p", low=0.0, low_inclusive=False,
                                       doc="rudder aspect ratio")
    windage_area: float = param(0.0, unit="m²", symbol="S_a", low=0.0,
                                doc="lateral windage area (0: 0.8·L·T)")
    underwater_area: float = param(0.0, unit="m²", symbol="S_h", low=0.0,
                                   doc="lateral underwater area (0: L·T)")
    sail_centre: float = param(0.0, unit="m", symbol="ℓ_sail",
                               doc="centre of windage forward of midships")
    sway_mass: float = param(0.0, unit="kg", symbol="m − Y_v̇", low=0.0,
                             doc="mass plus added mass in sway (for the model's disturbances)")
    yaw_inertia: float = param(0.0, unit="kg·m²", symbol="I_z − N_ṙ", low=0.0,
                               doc="yaw inertia plus added inertia (for the model's disturbances)")

    def validate(self) -> None:
        check_on_hull("sail_centre", self.sail_centre, self.length)

    @property
    def t_fore(self) -> float:
        return self.draft_fore or self.draft

    @property
    def t_aft(self) -> float:
        return self.draft_aft or self.draft

    @property
    def s_p(self) -> float:
        return self.rudder_area or 0.017 * self.length * self.draft

    @property
    def s_a(self) -> float:
        return self.windage_area or 0.8 * self.length * self.draft

    @property
    def s_h(self) -> float:
        return self.underwater_area or self.length * self.draft


def _mariner() -> ShipParticulars:
    rho, L = RHO_SEAWATER, 160.93
    half = 0.5 * rho
    m = 798e-5 * half * L**3
    return ShipParticulars(
        length=L, beam=23.17, draft=8.23,
        block_coefficient=round(m / rho / (L * 23.17 * 8.23), 3),
        speed=7.7175, rudder_area=0.017 * L * 8.23, rudder_aspect_ratio=1.6,
        windage_area=0.8 * L * 8.23, sail_centre=0.0,
        sway_mass=(798e-5 + 748e-5) * half * L**3,
        yaw_inertia=(39.2e-5 + 43.8e-5) * half * L**5,
    )


#: Mariner-class ship (the hull of ``MARINER_VOITKUNSKY``): L, B, T and the masses from
#: Chislett & Strøm-Tejsen (1965) via Fossen's mariner.m (m' = 798e-5, I' = 39.2e-5, added
#: −Y_v̇' = 748e-5, −N_ṙ' = 43.8e-5); δ = ∇/(LBT) = 0.542 from m' — *below* the range of eq.
#: (5)-(7), so eq. (5)-(7) warn for it. Rudder area (1.7 % of L·T), aspect ratio 1.6 and
#: windage area (0.8 L·T, centred amidships) are assumed typical values, not Mariner data.
MARINER_PARTICULARS: ShipParticulars = _mariner()


class CompensationSummary(NamedTuple):
    """Everything the ``seahelm compensate`` command prints (SI units, radians)."""

    cx: float
    cy: float
    cm: float
    wave_length: float
    wave_celerity: float
    surge: float
    sway: float
    yaw: float
    arm: float
    apparent_wind_speed: float
    apparent_wind_angle: float
    wind_force: float
    wind_moment: float
    wind_drift: float
    wave_drift: float
    resistance_centre: float
    delta_k_wind: float
    delta_k_wave: float
    delta_k: float


def compensation_summary(
    ship: ShipParticulars,
    *,
    wind_speed: float,
    wind_angle: float,
    wave_height: float,
    wave_angle: float,
    wave_length: float | None = None,
    a0: float = 3.3,
    a1: float = 1.0,
    strict: bool | None = None,
) -> CompensationSummary:
    """Wave coefficients, wave and wind loads, drift angles and δ_k for one ship and sea.

    Parameters
    ----------
    ship : ShipParticulars
    wind_speed : float
        True wind speed [m/s] (sets the wave length by eq. (2) unless ``wave_length`` is given).
    wind_angle : float
        Bearing the true wind comes from, relative to the bow [rad] (positive from starboard);
        the apparent wind follows from the ship's speed.
    wave_height : float
        h3% [m].
    wave_angle : float
        q_w of the waves [rad] (bearing they come from, relative to the bow).
    wave_length : float, optional
        λ [m]; default 1.55 τ² of eq. (2) from the true wind speed (λ = L when there is no
        wind; it only matters when ``wave_height`` > 0).
    a0, a1 : float
        A0, A1 of eq. (8)-(10); V_n = −V cos q_w (ship speed along the wave travel).
    strict : bool, optional
        Validity-range warnings become errors.
    """
    from ..environment import wave_forces as wf
    from ..environment import wind as wd

    L, V = ship.length, ship.speed
    check_nonnegative("wind_speed", wind_speed, "m/s")
    check_nonnegative("wave_height", wave_height, "m")
    coeffs = wf.wave_force_coefficients(
        L, ship.beam, ship.draft, ship.block_coefficient, strict=strict
    )
    if wave_length is None:
        wave_length = float(wd.wave_length_from_wind(wind_speed)) if wind_speed > 0 else L
    check_positive("wave_length", wave_length, "m")
    vw = float(wd.deep_water_celerity(wave_length))
    forces = wf.wave_forces(
        wave_angle, wave_height, wave_length, coeffs, length=L,
        speed_along_waves=-V * math.cos(wave_angle), wave_celerity=vw, a0=a0, a1=a1, strict=strict,
    )
    arm = wf.wave_force_arm(wave_angle, coeffs, length=L)
    app = wd.apparent_wind(wind_speed, wind_angle, V, 0.0)
    y_a = wd.wind_lateral_force(app.speed, app.angle, ship.s_a)
    n_a = wd.wind_yaw_moment(app.speed, app.angle, ship.s_a, length=L, sail_centre=ship.sail_centre)
    common = dict(speed=V, underwater_area=ship.s_h, block_coefficient=ship.block_coefficient,
                  draft=ship.draft, length=L)
    alpha_wind = drift_angle(y_a, **common)
    alpha_wave = drift_angle(forces.sway, **common)
    l_lr = lateral_resistance_centre(ship.t_fore, ship.t_aft)
    dk_wind = wind_compensation(
        wind_speed=app.speed, wind_angle=app.angle, drift=alpha_wind, speed=V, length=L,
        draft=ship.draft, block_coefficient=ship.block_coefficient, rudder_area=ship.s_p,
        rudder_aspect_ratio=ship.rudder_aspect_ratio, windage_area=ship.s_a,
        underwater_area=ship.s_h, sail_centre=ship.sail_centre, resistance_centre=l_lr,
    )
    dk_wave = wave_compensation(forces.yaw, speed=V, length=L, rudder_area=ship.s_p,
                                rudder_aspect_ratio=ship.rudder_aspect_ratio)
    f = float
    return CompensationSummary(
        f(coeffs.cx), f(coeffs.cy), f(coeffs.cm), f(wave_length), vw,
        f(forces.surge), f(forces.sway), f(forces.yaw), f(arm),
        f(app.speed), f(app.angle), f(y_a), f(n_a), f(alpha_wind), f(alpha_wave), f(l_lr),
        f(dk_wind), f(dk_wave), f(dk_wind + dk_wave),
    )


# ------------------------------------------------------------------------------------------
# closed loop of Fig. 1 on the Voitkunsky model
# ------------------------------------------------------------------------------------------
def _steady_rudder(
    vp: Any, yaw_moment: np.ndarray, sway_force: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Steady (ω = 0) drift angle β and rudder angle of Voitkunsky's model under constant loads.

    0 = −q31 β − s31 δ + m_d,  0 = −q21 β − h2 β|β| − s21 δ − f_d: eliminating δ gives
    h2 β|β| − a β + c = 0 with a = s21 q31/s31 − q21, c = f_d + s21 m_d/s31, a monotone
    equation in β when a < 0 (a course-stable ship).
    """
    q21, s21, h2, q31, s31 = vp.q21, vp.s21, vp.h2, vp.q31, vp.s31
    a = s21 * q31 / s31 - q21
    c = sway_force + s21 * yaw_moment / s31
    if a >= 0.0:
        raise ParameterError("the Voitkunsky model is not course-stable (a >= 0); no steady state")
    if h2 == 0.0:
        beta = c / a
    else:
        # β ≥ 0 branch: h2 β² + |a| β + c = 0 (c ≤ 0); β < 0 branch mirrored
        disc = np.sqrt(a * a + 4.0 * h2 * np.abs(c))
        beta = -np.sign(c) * (disc - abs(a)) / (2.0 * h2)
    delta = (yaw_moment - q31 * beta) / s31
    return beta, delta


class ModelCompensation(NamedTuple):
    """The compensating rudder angle computed from the ship model (radians).

    ``delta_k_wind`` balances the wind loads alone (channel 5 of Fig. 1), ``delta_k_wave`` is
    the extra angle the wave loads need on top (channel 6), ``delta_k`` their sum (the steady
    rudder angle under both) and ``drift`` the steady drift angle β under both.
    """

    delta_k_wind: float
    delta_k_wave: float
    delta_k: float
    drift: float


def model_compensation(
    summary: CompensationSummary,
    *,
    ship: ShipParticulars | None = None,
    vessel_params: Any = None,
) -> ModelCompensation:
    """δ_k from the ship model: the steady rudder angle that balances the loads of ``summary``.

    The wind force and moment and the wave sway force and yaw moment that
    :func:`compensation_summary` computes (Lvov 2014, eq. (9)-(12); the paper's signs, turned
    into seahelm's body axes) are converted to the Voitkunsky model's normalised disturbances
    (yaw moment / (I_z − N_ṙ), sway force / ((m − Y_v̇) V)) and its steady state with ω = 0 is
    solved for β and δ. This is the δ_k that :func:`wind_wave_scenario` feeds the autopilot by
    default (``delta_k_method="model"``); eq. (12)/(14) as printed have the wrong sign on the
    Mariner (module docstring).

    Parameters
    ----------
    summary : CompensationSummary
        The loads, from :func:`compensation_summary` for ``ship``.
    ship : ShipParticulars, optional
        Its masses convert the loads (default: the Mariner particulars); ``sway_mass`` and
        ``yaw_inertia`` must be > 0.
    vessel_params : VoitkunskyParams, optional
        The ship model (default: the Mariner set, ``MARINER_VOITKUNSKY``).

    Returns
    -------
    ModelCompensation

    Raises
    ------
    ParameterError
        If the ship's masses are not given or the model is not course-stable.
    """
    from ..vessels.voitkunsky import MARINER_VOITKUNSKY

    ship = MARINER_PARTICULARS if ship is None else ship
    vp = MARINER_VOITKUNSKY if vessel_params is None else vessel_params
    if ship.sway_mass <= 0 or ship.yaw_inertia <= 0:
        raise ParameterError("`ship.sway_mass` and `ship.yaw_inertia` must be > 0 [kg, kg·m²]")
    m_scale, f_scale = ship.yaw_inertia, ship.sway_mass * ship.speed
    # seahelm body axes: the negatives of the paper-signed loads
    md_wind, fd_wind = -summary.wind_moment / m_scale, -summary.wind_force / f_scale
    md_wave, fd_wave = -summary.yaw / m_scale, -summary.sway / f_scale
    _, dk_w = _steady_rudder(vp, np.asarray(md_wind), np.asarray(fd_wind))
    beta_t, dk_t = _steady_rudder(vp, np.asarray(md_wind + md_wave),
                                  np.asarray(fd_wind + fd_wave))
    return ModelCompensation(float(dk_w), float(dk_t - dk_w), float(dk_t), float(beta_t))


@dataclasses.dataclass(frozen=True)
class WindWaveCase:
    """One weather case of the course-keeping scenario (SI units, radians).

    Attributes
    ----------
    name : str
    wind_speed : float
        True wind speed W [m/s].
    wind_angle : float
        Bearing the wind comes from, relative to the course to steer [rad].
    wave_height : float
        h3% [m] (0: no waves).
    wave_angle : float
        Bearing the waves come from, relative to the course to steer [rad].
    irregular : bool
        Irregular sea: the wave loads of eq. (8)-(10) with (h3%/2)² replaced by the
        instantaneous ζ(t)² scaled to the same mean, ζ a Rakhmanin–Firsov sea sampled by
        :mod:`seahelm.environment.shaping` (quasi-steady, no encounter-frequency correction).
    onset : float
        Time [s] at which wind and waves set in (a step; the compensators see it at once).
    a1 : float
        A1 of eq. (8)-(10).
    """

    name: str
    wind_speed: float = 0.0
    wind_angle: float = 0.0
    wave_height: float = 0.0
    wave_angle: float = 0.0
    irregular: bool = False
    onset: float = 30.0
    a1: float = 1.0


def wind_wave_scenario(
    case: WindWaveCase,
    *,
    ship: ShipParticulars | None = None,
    vessel_params: Any = None,
    course: float = 0.0,
    t_final: float = 900.0,
    dt: float = 0.1,
    delta_k_method: str = "model",
    seed: int = 0,
    strict: bool | None = None,
) -> dict[str, Any]:
    """Inputs of :func:`seahelm.simulation.engine.simulate` for the closed loop of Fig. 1.

    The Voitkunsky model (default: the Mariner set) is loaded by the wind force and moment
    of eq. (12) and the wave sway force and yaw moment of eq. (9)-(10), converted to the
    model's normalised disturbances (yaw moment / (I_z − N_ṙ), sway force / ((m − Y_v̇) U)),
    evaluated on the course to steer (small heading errors). The course setter gives the
    heading ψ* = C + β (drift from the same steady balance that gives δ_k), and the two
    compensation channels of :data:`COMPENSATED_PID` get

    * ``delta_k_method="model"`` — the rudder angle that balances the wind loads (channel 5)
      and the extra angle for the wave loads (channel 6) in the ship model's steady state;
    * ``delta_k_method="paper"`` — eq. (12) (channel 5) and the wave term of eq. (14)
      (channel 6) as printed (module docstring), with the paper's drift angles.

    Parameters
    ----------
    case : WindWaveCase
        The weather case (wind and wave speeds [m/s], heights [m], angles [rad], onset [s]).
    ship : ShipParticulars, optional
        Hull, rudder and loading data (default: the Mariner particulars).
    vessel_params : VoitkunskyParams, optional
        Parameters of the simulated Voitkunsky model (default: the Mariner set).
    course : float, optional
        Wanted course over ground C [rad] (default 0).
    t_final : float, optional
        Duration [s] (default 900).
    dt : float, optional
        Integration step [s] (default 0.1).
    delta_k_method : {"model", "paper"}, optional
        How the compensating rudder angles are computed (default "model"), see above.
    seed : int, optional
        Seed of the irregular-wave realisation (default 0).
    strict : bool, optional
        Raise instead of warning outside the validity ranges of the empirical formulas
        (default: the global strict mode).

    Returns
    -------
    dict
        ``model, params, x0, t_final, dt, reference, disturbance, actuator, actuator_params,
        controller, controller_dt`` for ``simulate(**...)`` (minus ``controller_params``),
        plus ``info`` (loads, drift, δ_k, the course to steer).
    """
    from ..actuators.servo import RUDDER_SERVO, ServoParams
    from ..vessels.voitkunsky import MARINER_VOITKUNSKY, VOITKUNSKY

    methods = ("model", "paper")
    if delta_k_method not in methods:
        raise ValueError(f"unknown delta_k_method '{delta_k_method}'; valid: {', '.join(methods)}")
    ship = MARINER_PARTICULARS if ship is None else ship
    vp = MARINER_VOITKUNSKY if vessel_params is None else vessel_params
    if ship.sway_mass <= 0 or ship.yaw_inertia <= 0:
        raise ParameterError("`ship.sway_mass` and `ship.yaw_inertia` must be > 0 [kg, kg·m²]")
    V = ship.speed
    n = int(round(t_final / dt))
    t = np.arange(n + 1) * dt
    on = (t >= case.onset).astype(float)

    summ = compensation_summary(
        ship, wind_speed=case.wind_speed, wind_angle=case.wind_angle,
        wave_height=case.wave_height, wave_angle=case.wave_angle, a1=case.a1, strict=strict,
    )
    # seahelm body axes: the negatives of the paper-signed loads
    n_wind, y_wind = -summ.wind_moment, -summ.wind_force
    n_wave, y_wave = -summ.yaw, -summ.sway
    m_scale, f_scale = ship.yaw_inertia, ship.sway_mass * V
    md_wind, fd_wind = n_wind / m_scale, y_wind / f_scale
    md_wave, fd_wave = n_wave / m_scale, y_wave / f_scale

    wave_mod = np.ones_like(t)
    if case.irregular and case.wave_height > 0:
        from ..environment.shaping import shaping_filter
        from ..environment.spectra import spectrum_from_wave_height

        filt = shaping_filter(spectrum_from_wave_height("rakhmanin-firsov-2", case.wave_height),
                              ["ordinate"])
        zeta = filt.sample(n_steps=n + 1, dt=dt, seed=seed, runs=1).values[0, :, 0]
        wave_mod = zeta**2 / float(filt.output_variance()[0])
    dist = np.zeros((n + 1, VOITKUNSKY.n_disturbances))
    dist[:, 0] = on * (md_wind + md_wave * wave_mod)
    dist[:, 1] = on * (fd_wind + fd_wave * wave_mod)

    model = model_compensation(summ, ship=ship, vessel_params=vp)
    dk_t = model.delta_k
    if delta_k_method == "model":
        ch_wind, ch_wave, drift = model.delta_k_wind, model.delta_k_wave, model.drift
    else:
        ch_wind, ch_wave = summ.delta_k_wind, summ.delta_k_wave
        drift = summ.wind_drift + summ.wave_drift
    heading = float(course_to_steer(course, drift))
    ref = np.zeros((n + 1, 3))
    ref[:, 0] = heading
    ref[:, 1] = on * ch_wind
    ref[:, 2] = on * ch_wave
    x0 = np.array([0.0, 0.0, heading, 0.0, 0.0])
    info = dict(summary=summ, heading_to_steer=heading, drift=drift,
                delta_k_wind=ch_wind, delta_k_wave=ch_wave, delta_k=ch_wind + ch_wave,
                steady_rudder=dk_t, steady_drift=model.drift, onset=case.onset)
    return dict(model=VOITKUNSKY, params=vp, x0=x0, t_final=t_final, dt=dt, reference=ref,
                disturbance=dist, actuator=RUDDER_SERVO, actuator_params=ServoParams(),
                controller=COMPENSATED_PID, controller_dt=1.0, info=info)


def heading_metrics(
    heading_error: ArrayLike,
    rudder: ArrayLike,
    *,
    dt: float,
    delta_k: ArrayLike = 0.0,
    start: float = 0.0,
    band: float = math.radians(1.0),
    deadband: float = math.radians(0.05),
) -> dict[str, np.ndarray]:
    """Course-keeping metrics of recorded runs (leading batch axes, time last; radians in).

    Returns ``mean_abs_error`` and ``max_abs_error`` [rad], ``iae`` (∫|e| dt) [rad·s],
    ``reversals_per_min`` (sign changes of the rudder's motion, moves under ``deadband``
    ignored), ``mean_activity`` (mean |δ − δ_k|) [rad] and ``settling_time`` [s] (time after
    ``start`` from which |e| ≤ ``band``; NaN if never), all over t ≥ ``start``.

    Parameters
    ----------
    heading_error : array_like, shape (..., steps)
        Heading error e [rad] (only |e| is used; wrapped to [−π, π) internally).
    rudder : array_like, shape (..., steps)
        Rudder angle δ [rad].
    dt : float
        Sample period of the records [s].
    delta_k : float or array_like, optional
        Compensating rudder angle δ_k [rad], constant or per sample (default 0).
    start : float, optional
        Time from which the metrics are taken [s] (default 0).
    band : float, optional
        Settling band on |e| [rad] (default 1°).
    deadband : float, optional
        Rudder moves smaller than this are not counted as reversals [rad] (default 0.05°).

    Returns
    -------
    dict of str to numpy.ndarray
        The metrics listed above, each of the batch shape.
    """
    e = np.abs(wrap_angle(as_float_array("heading_error", heading_error, "rad", finite=False)))
    d = as_float_array("rudder", rudder, "rad", finite=False)
    k0 = int(round(start / dt))
    e, d = e[..., k0:], d[..., k0:]
    dk = np.asarray(delta_k, dtype=float)
    if dk.ndim and dk.shape[-1] == d.shape[-1] + k0:
        dk = dk[..., k0:]
    duration = (e.shape[-1] - 1) * dt
    out: dict[str, np.ndarray] = {
        "mean_abs_error": e.mean(axis=-1),
        "max_abs_error": e.max(axis=-1),
        "iae": np.trapezoid(e, dx=dt, axis=-1),
        "mean_activity": np.abs(d - dk).mean(axis=-1),
    }
    # rudder reversals with hysteresis
    flat_d = d.reshape(-1, d.shape[-1])
    rev = np.zeros(flat_d.shape[0])
    for i, row in enumerate(flat_d):
        anchor, direction, count = row[0], 0, 0
        for v in row[1:]:
            step = v - anchor
            if abs(step) >= deadband:
                s = 1 if step > 0 else -1
                if direction != 0 and s != direction:
                    count += 1
                direction, anchor = s, v
            elif direction != 0 and (v - anchor) * direction > 0:
                anchor = v
        rev[i] = count
    out["reversals_per_min"] = rev.reshape(d.shape[:-1]) / (duration / 60.0)
    outside = e > band
    any_out = outside.any(axis=-1)
    last = e.shape[-1] - 1 - np.argmax(outside[..., ::-1], axis=-1)
    settle = np.where(any_out, (last + 1) * dt, 0.0)
    out["settling_time"] = np.where(any_out & (last == e.shape[-1] - 1), np.nan, settle)
    return out
