"""Mean wave forces and yaw moment on a ship hull, after Lvov (2014), eq. (1)-(11).

Two ways of estimating the wave disturbance of a course-keeping ship are given in the paper:

* Voitkunsky's simple lateral force (Lvov (2014), eq. (1)-(4), citing Lukomsky & Chugunov,
  1988): :func:`voitkunsky_lateral_force` and :func:`voitkunsky_lateral_force_from_wind`;
* the empirical coefficients of Yurkansky (2005), eq. (5)-(7)
  (:func:`wave_force_coefficients`), and with them the surge force, sway force and yaw moment
  of eq. (8)-(10) (:func:`wave_forces`) and the arm of the wave force, eq. (11)
  (:func:`wave_force_arm`).

Angle convention (radians inside)
---------------------------------
``wave_angle`` is the paper's q_w, the *relative bearing the waves come from*, measured from
the bow, positive when the waves come from starboard: q_w = 0 head seas, ±π/2 beam seas,
±π following seas. This is the reading under which eq. (14) may use one q_w for both the wind
(the apparent-wind bearing of eq. (12), 0 = head wind) and the waves (a developed sea runs
with the wind), and under which eq. (8) gives an added resistance in head seas
(X_w = −0.9 C_x^w … < 0 at q_w = 0). Forces are the paper's, signed as printed:

* ``X_w`` [N] along the ship's x axis, positive forward (negative = added resistance);
* ``Y_w`` [N] and ``M_w`` [N·m] carry the sign of sin q_w and sin 2q_w: positive for waves
  from starboard, i.e. the paper's lateral axis points to *leeward* for q_w > 0. In seahelm's
  body axes (y to starboard, yaw moment positive turning the bow to starboard) the sway force
  and yaw moment are −Y_w and −M_w (:func:`wave_disturbance_body`).

All functions broadcast over numpy arrays (batch axes lead) and return arrays (0-d for scalar
input).

References
----------
Lvov, V. E. (2014). The effect of wave action on the course control system (in Russian).
Sudovozhdenie (ONMA). Eq. (1)-(11).
Yurkansky, A. V. (2005). Ship controllability in wind and waves (PhD thesis, in Russian),
St Petersburg — the source of eq. (5)-(10).
Lukomsky, Yu. A., Chugunov, V. S. (1988). Control systems of marine moving objects — the
source of Voitkunsky's eq. (1).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_positive
from ..constants import GRAVITY, RHO_SEAWATER, wrap_angle
from ..errors import ParameterError, warn_validity

__all__ = [
    "VALIDITY_RANGES",
    "A0_DEFAULT",
    "A1_RANGE",
    "WaveForceCoefficients",
    "WaveForces",
    "check_hull_validity",
    "wave_force_coefficients",
    "wave_attenuation",
    "wave_forces",
    "wave_force_arm",
    "wave_disturbance_body",
    "voitkunsky_lateral_force",
    "voitkunsky_lateral_force_from_wind",
    "disturbing_force_coefficient",
]

#: Published validity ranges of eq. (5)-(7) (open intervals), Lvov (2014) after eq. (7).
VALIDITY_RANGES: dict[str, tuple[float, float]] = {
    "L/T": (10.0, 23.0),
    "B/T": (1.0, 3.7),
    "L/B": (5.0, 12.0),
    "block coefficient δ": (0.6, 0.8),
}

#: Empirical coefficient A0 of eq. (8)-(10) (recommended value, Lvov (2014)).
A0_DEFAULT: float = 3.3
#: Published range of the speed coefficient A1 of eq. (8)-(10).
A1_RANGE: tuple[float, float] = (1.0, 8.5)


class WaveForceCoefficients(NamedTuple):
    """Dimensionless wave-force coefficients of Lvov (2014), eq. (5)-(7)."""

    cx: np.ndarray
    """C_x^w [-], surge (eq. (5))."""
    cy: np.ndarray
    """C_y^w [-], sway (eq. (6))."""
    cm: np.ndarray
    """C_m^w [-], yaw (eq. (7))."""


class WaveForces(NamedTuple):
    """Mean wave forces and moment of Lvov (2014), eq. (8)-(10) (signs: module docstring)."""

    surge: np.ndarray
    """X_w [N], positive forward."""
    sway: np.ndarray
    """Y_w [N], sign of sin q_w."""
    yaw: np.ndarray
    """M_w [N·m], sign of sin 2q_w."""


def _outside(value: np.ndarray, low: float, high: float) -> np.ndarray:
    return ~((value > low) & (value < high))


def check_hull_validity(
    length: ArrayLike,
    beam: ArrayLike,
    draft: ArrayLike,
    block_coefficient: ArrayLike,
    *,
    strict: bool | None = None,
) -> None:
    """Warn if the hull is outside the data eq. (5)-(7) were fitted to.

    Checks 10 < L/T < 23, 1 < B/T < 3.7, 5 < L/B < 12, 0.6 < δ < 0.8 (Lvov (2014), after
    eq. (7)); every ratio outside its range is named with its value and the published range.

    Parameters
    ----------
    length, beam, draft : array_like
        L, B, T [m] (positive).
    block_coefficient : array_like
        δ [-] (in (0, 1]).
    strict : bool, optional
        Raise instead of warning; ``None`` follows :class:`seahelm.errors.strict_validity`.

    Warns
    -----
    ValidityRangeWarning
        One warning listing every ratio outside its range.

    Raises
    ------
    ParameterError
        In strict mode, instead of the warning; always for non-positive dimensions.
    """
    L = as_float_array("length", length, "m")
    B = as_float_array("beam", beam, "m")
    T = as_float_array("draft", draft, "m")
    cb = as_float_array("block_coefficient", block_coefficient, "-")
    check_positive("length", L, "m")
    check_positive("beam", B, "m")
    check_positive("draft", T, "m")
    check_positive("block_coefficient", cb, "-")
    if np.any(cb > 1.0):
        raise ParameterError(f"`block_coefficient` must be <= 1 [-], got {cb.max()!r}")
    ratios = {
        "L/T": L / T,
        "B/T": B / T,
        "L/B": L / B,
        "block coefficient δ": cb,
    }
    problems = []
    for name, value in ratios.items():
        low, high = VALIDITY_RANGES[name]
        bad = _outside(np.asarray(value), low, high)
        if np.any(bad):
            v = np.asarray(value)[bad].ravel()
            shown = ", ".join(f"{x:.4g}" for x in v[:4]) + (" ..." if v.size > 4 else "")
            problems.append(
                f"{name} = {shown} outside the published range {low:g} < {name} < {high:g}"
            )
    if problems:
        warn_validity(
            "Lvov (2014) eq. (5)-(7) wave-force coefficients used outside their validity range: "
            + "; ".join(problems),
            strict=strict,
            stacklevel=3,
        )


def wave_force_coefficients(
    length: ArrayLike,
    beam: ArrayLike,
    draft: ArrayLike,
    block_coefficient: ArrayLike,
    *,
    strict: bool | None = None,
) -> WaveForceCoefficients:
    """Empirical wave-force coefficients C_x^w, C_y^w, C_m^w, Lvov (2014) eq. (5)-(7).

    ::

        C_x^w = 0.062 B/T − 0.0085 L/T + 0.328 δ            (5)
        C_y^w = 0.0823 L/B + 2.56 T/L + 0.903 δ²             (6)
        C_m^w = 0.15 δ + 0.197 δ² − 0.00373 L/T               (7)

    Parameters
    ----------
    length : array_like
        Waterline length L [m].
    beam : array_like
        Beam B [m].
    draft : array_like
        Mean draft T [m].
    block_coefficient : array_like
        Block coefficient δ [-].
    strict : bool, optional
        Raise :class:`~seahelm.errors.ParameterError` instead of warning when the hull is
        outside the published range (see :func:`check_hull_validity`).

    Returns
    -------
    WaveForceCoefficients
        ``(cx, cy, cm)`` [-], broadcast over the inputs.

    Warns
    -----
    ValidityRangeWarning
        10 < L/T < 23, 1 < B/T < 3.7, 5 < L/B < 12, 0.6 < δ < 0.8 not satisfied.
    """
    check_hull_validity(length, beam, draft, block_coefficient, strict=strict)
    L = np.asarray(length, dtype=float)
    B = np.asarray(beam, dtype=float)
    T = np.asarray(draft, dtype=float)
    cb = np.asarray(block_coefficient, dtype=float)
    cx = 0.062 * B / T - 0.0085 * L / T + 0.328 * cb
    cy = 0.0823 * L / B + 2.56 * T / L + 0.903 * cb**2
    cm = 0.15 * cb + 0.197 * cb**2 - 0.00373 * L / T
    return WaveForceCoefficients(cx, cy, cm)


def wave_attenuation(
    wave_length: ArrayLike,
    length: ArrayLike,
    *,
    speed_along_waves: ArrayLike = 0.0,
    wave_celerity: ArrayLike | None = None,
    a0: float = A0_DEFAULT,
    a1: float = A1_RANGE[0],
    strict: bool | None = None,
) -> np.ndarray:
    """The common factor e^(−A0 λ/L) (1 + A1 V_n/V_w) of eq. (8)-(10) [-].

    Parameters
    ----------
    wave_length : array_like
        Length λ of the regular wave [m].
    length : array_like
        Ship length L [m].
    speed_along_waves : array_like
        V_n [m/s], component of the ship's speed along the direction the waves run.
    wave_celerity : array_like, optional
        V_w [m/s], wave phase speed; default the deep-water celerity √(g λ / 2π).
    a0 : float
        A0 [-] (recommended 3.3).
    a1 : float
        A1 [-], published range [1, 8.5]; outside it a ValidityRangeWarning.
    strict : bool, optional
        Raise :class:`~seahelm.errors.ParameterError` instead of warning outside the range
        (default: the global strict mode).

    Returns
    -------
    numpy.ndarray
        e^(−A0 λ/L) (1 + A1 V_n/V_w) [-].
    """
    lam = as_float_array("wave_length", wave_length, "m")
    check_positive("wave_length", lam, "m")
    L = as_float_array("length", length, "m")
    check_positive("length", L, "m")
    vn = as_float_array("speed_along_waves", speed_along_waves, "m/s")
    if wave_celerity is None:
        vw = np.sqrt(GRAVITY * lam / (2.0 * math.pi))
    else:
        vw = as_float_array("wave_celerity", wave_celerity, "m/s")
        check_positive("wave_celerity", vw, "m/s")
    check_nonnegative("a0", a0, "-")
    if not (A1_RANGE[0] <= a1 <= A1_RANGE[1]):
        warn_validity(
            f"Lvov (2014) eq. (8)-(10): A1 = {a1:g} outside the published range "
            f"{A1_RANGE[0]:g} <= A1 <= {A1_RANGE[1]:g}",
            strict=strict,
            stacklevel=3,
        )
    return np.exp(-a0 * lam / L) * (1.0 + a1 * vn / vw)


def wave_forces(
    wave_angle: ArrayLike,
    wave_height: ArrayLike,
    wave_length: ArrayLike,
    coefficients: WaveForceCoefficients,
    *,
    length: ArrayLike,
    speed_along_waves: ArrayLike = 0.0,
    wave_celerity: ArrayLike | None = None,
    a0: float = A0_DEFAULT,
    a1: float = A1_RANGE[0],
    rho: float = RHO_SEAWATER,
    gravity: float = GRAVITY,
    strict: bool | None = None,
) -> WaveForces:
    """Wave surge force, sway force and yaw moment, Lvov (2014) eq. (8)-(10).

    With F = ρ g L (h3%/2)² e^(−A0 λ/L) (1 + A1 V_n/V_w)::

        X_w = C_x^w (0.1 − cos q_w) F                                  (8)
        Y_w = C_y^w sin q_w F                                          (9)
        M_w = C_m^w sin(2 q_w) / (1 + (π − |q_w|)/π) F L               (10)

    Parameters
    ----------
    wave_angle : array_like
        q_w [rad], relative bearing the waves come from (0 head seas, positive from
        starboard; module docstring). Wrapped to [−π, π) before use.
    wave_height : array_like
        h3% [m], height of 3 % exceedance.
    wave_length : array_like
        λ [m], regular wave length.
    coefficients : WaveForceCoefficients
        C_x^w, C_y^w, C_m^w from :func:`wave_force_coefficients`.
    length : array_like
        Ship length L [m].
    speed_along_waves : array_like
        V_n [m/s]; e.g. −V cos q_w for a ship at speed V (the waves run towards −q_w).
    wave_celerity : array_like, optional
        V_w [m/s]; default deep water √(g λ/2π).
    a0, a1 : float
        A0 (3.3) and A1 ∈ [1, 8.5] [-].
    rho : float
        Water density ρ [kg/m³].
    gravity : float
        g [m/s²].
    strict : bool, optional
        Raise instead of warning for A1 outside its range.

    Returns
    -------
    WaveForces
        ``(surge [N], sway [N], yaw [N·m])``.
    """
    q = as_float_array("wave_angle", wave_angle, "rad")
    q = wrap_angle(q)
    h = as_float_array("wave_height", wave_height, "m")
    check_nonnegative("wave_height", h, "m")
    L = as_float_array("length", length, "m")
    att = wave_attenuation(
        wave_length, L, speed_along_waves=speed_along_waves, wave_celerity=wave_celerity,
        a0=a0, a1=a1, strict=strict,
    )
    f = rho * gravity * L * (h / 2.0) ** 2 * att
    cx, cy, cm = (np.asarray(c, dtype=float) for c in coefficients)
    surge = cx * (0.1 - np.cos(q)) * f
    sway = cy * np.sin(q) * f
    yaw = cm * np.sin(2.0 * q) / (1.0 + (math.pi - np.abs(q)) / math.pi) * f * L
    return WaveForces(surge, sway, yaw)


def wave_force_arm(
    wave_angle: ArrayLike, coefficients: WaveForceCoefficients, *, length: ArrayLike
) -> np.ndarray:
    """Arm of the wave sway force ℓ_w = M_w / Y_w [m], Lvov (2014) eq. (11).

    ::

        ℓ_w = C_m^w / C_y^w · sin(2 q_w) / (2 − |q_w|/π) · L                  (11)

    As printed, eq. (11) is *not* the quotient of eq. (10) by eq. (9) it claims to be: that
    quotient is C_m/C_y · 2 cos q_w /(2 − |q_w|/π) · L (the sin q_w of eq. (9) cancels one
    factor of sin 2q_w = 2 sin q_w cos q_w). We implement eq. (11) as printed (it is the
    published formula); :func:`wave_forces` gives M_w/Y_w exactly when needed.

    Parameters
    ----------
    wave_angle : array_like
        q_w [rad] (wrapped to [−π, π)).
    coefficients : WaveForceCoefficients
        From :func:`wave_force_coefficients` (C_x^w unused).
    length : array_like
        L [m].
    """
    q = as_float_array("wave_angle", wave_angle, "rad")
    q = wrap_angle(q)
    L = as_float_array("length", length, "m")
    _, cy, cm = (np.asarray(c, dtype=float) for c in coefficients)
    return cm / cy * np.sin(2.0 * q) / (2.0 - np.abs(q) / math.pi) * L


def wave_disturbance_body(forces: WaveForces) -> tuple[np.ndarray, np.ndarray]:
    """Sway force [N] and yaw moment [N·m] in seahelm's body axes from eq. (9)-(10).

    seahelm: y to starboard, yaw moment positive turning the bow to starboard. The paper's
    Y_w, M_w are positive for waves from starboard (pushing to port), so both change sign.

    Parameters
    ----------
    forces : WaveForces
        Paper-signed wave loads of eq. (9)-(10) (``sway`` [N], ``yaw`` [N·m]).

    Returns
    -------
    sway : numpy.ndarray
        Sway force [N], seahelm body axes.
    yaw : numpy.ndarray
        Yaw moment [N·m], seahelm body axes.
    """
    return -np.asarray(forces.sway), -np.asarray(forces.yaw)


def voitkunsky_lateral_force(
    length: ArrayLike,
    wave_height: ArrayLike,
    wave_coefficient: ArrayLike,
    *,
    rho: float = RHO_SEAWATER,
) -> np.ndarray:
    """Voitkunsky's lateral wave force R_вн = 0.5 ρ L h3% K_вн, Lvov (2014) eq. (1).

    Units as printed: ρ [kg/m³] · L [m] · h3% [m] gives [kg/m]; the result is a force [N]
    only if K_вн carries [m/s²] (the paper calls it dimensionless and says it depends on the
    ship's dimensions, the wave length and the wave heading). We implement the formula as
    printed and leave K_вн's units to the caller.

    Parameters
    ----------
    length : array_like
        Length between perpendiculars L [m].
    wave_height : array_like
        h3% [m].
    wave_coefficient : array_like
        K_вн (see above).
    rho : float
        Sea-water density ρ [kg/m³].
    """
    L = as_float_array("length", length, "m")
    h = as_float_array("wave_height", wave_height, "m")
    k = as_float_array("wave_coefficient", wave_coefficient, "-")
    check_positive("length", L, "m")
    check_nonnegative("wave_height", h, "m")
    return 0.5 * rho * L * h * k


def disturbing_force_coefficient(
    length: ArrayLike,
    wave_coefficient: ArrayLike,
    *,
    rho: float = RHO_SEAWATER,
    gravity: float = GRAVITY,
) -> np.ndarray:
    """C_b = 4·10⁻⁴ ρ g L K_ey of eq. (4) [N·s²/m² when K_ey is taken dimensionless].

    Note: eq. (4) does not follow from eq. (1) and (3) as the paper says — substituting
    h3% = 0.03 W² in eq. (1) gives 0.015 ρ L K W², not 4·10⁻⁴ ρ g L K W² ≈ 0.0039 ρ L K W²
    (a factor 3.8 apart). Both are implemented as printed.

    Parameters
    ----------
    length : array_like
        Ship length L [m] (> 0).
    wave_coefficient : array_like
        Wave coefficient K_ey [-].
    rho : float, optional
        Water density ρ [kg/m³].
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    numpy.ndarray
        C_b.
    """
    L = as_float_array("length", length, "m")
    check_positive("length", L, "m")
    k = as_float_array("wave_coefficient", wave_coefficient, "-")
    return 4.0e-4 * rho * gravity * L * k


def voitkunsky_lateral_force_from_wind(
    length: ArrayLike,
    wind_speed: ArrayLike,
    wave_coefficient: ArrayLike,
    *,
    rho: float = RHO_SEAWATER,
    gravity: float = GRAVITY,
) -> np.ndarray:
    """R_ey = 4·10⁻⁴ ρ g L K_ey W² = C_b W², Lvov (2014) eq. (4).

    Parameters
    ----------
    length : array_like
        L [m].
    wind_speed : array_like
        True wind speed W [m/s] (developed sea).
    wave_coefficient : array_like
        K_ey [-].
    rho, gravity : float
        ρ [kg/m³], g [m/s²].
    """
    w = as_float_array("wind_speed", wind_speed, "m/s")
    check_nonnegative("wind_speed", w, "m/s")
    return disturbing_force_coefficient(length, wave_coefficient, rho=rho, gravity=gravity) * w**2
