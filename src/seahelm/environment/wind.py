"""Wind, the sea it raises, and the wind force and moment on the hull, after Lvov (2014).

Wind-to-sea relations of a developed sea (Lvov (2014), eq. (2)-(3))::

    τ = 0.65 K_E W            wave period [s] from the true wind speed W [m/s]
    λ = 1.55 τ² = 0.655 K_E² W²  wave length [m]
    h3% = 0.03 W²              height of 3 % exceedance [m]

with K_E the growth coefficient (0.8 for a developed sea). The numeric coefficients carry
units: 0.65 [s²/m], 1.55 [m/s²] (≈ g/2π, deep-water dispersion), 0.03 [s²/m].

Wind force and moment as the paper uses them inside eq. (12) (Lvov 2008, 2014)::

    Y_a = 0.37 sin q_w ρ_a S_n W²                                  lateral force [N]
    N_a = (0.25 + ℓ_sail/L − |q_w|°/360) · L · Y_a                  yaw moment [N·m]

with q_w the apparent-wind bearing (0 = head wind, positive from starboard), W the apparent
wind speed, S_n the lateral windage area and ℓ_sail the distance of the centre of windage
forward of midships. The arm runs from 0.25 L forward (head wind) through ℓ_sail (beam wind)
to 0.25 L aft (stern wind); the degree term q_w/360 is computed from q_w in degrees and the
mirror image is used for wind from port (|q_w|), so the moment is odd in q_w. Signs are the
paper's: positive for wind from starboard (seahelm's body-axis sway force and yaw moment are
the negatives, :func:`wind_disturbance_body`).

References
----------
Lvov, V. E. (2014), eq. (2), (3), (12). Lvov, V. E. (2008). A method of improving the
compensating properties of a ship's course control system (in Russian). Sudovozhdenie 15.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_on_hull, check_positive
from ..constants import GRAVITY, RHO_AIR, wrap_angle

__all__ = [
    "DEVELOPED_SEA_GROWTH",
    "wave_period_from_wind",
    "wave_length_from_wind",
    "wave_height_from_wind",
    "deep_water_celerity",
    "ApparentWind",
    "apparent_wind",
    "wind_lateral_force",
    "wind_moment_arm",
    "wind_yaw_moment",
    "wind_disturbance_body",
]

#: Growth coefficient K_E of a developed sea (Lvov (2014), after eq. (2)).
DEVELOPED_SEA_GROWTH: float = 0.8


def wave_period_from_wind(
    wind_speed: ArrayLike, growth: ArrayLike = DEVELOPED_SEA_GROWTH
) -> np.ndarray:
    """Wave period τ = 0.65 K_E W [s], Lvov (2014) eq. (2).

    Parameters
    ----------
    wind_speed : array_like
        True wind speed W [m/s].
    growth : array_like
        Growth coefficient K_E [-] (0.8 developed sea).
    """
    w = as_float_array("wind_speed", wind_speed, "m/s")
    check_nonnegative("wind_speed", w, "m/s")
    k = as_float_array("growth", growth, "-")
    check_positive("growth", k, "-")
    return 0.65 * k * w


def wave_length_from_wind(
    wind_speed: ArrayLike, growth: ArrayLike = DEVELOPED_SEA_GROWTH
) -> np.ndarray:
    """Wave length λ = 1.55 τ² [m] (= 0.655 K_E² W²), Lvov (2014) eq. (2).

    Parameters
    ----------
    wind_speed : array_like
        True wind speed W [m/s].
    growth : array_like, optional
        Growth coefficient K_E [-] (default 0.8, developed sea).

    Returns
    -------
    numpy.ndarray
        λ [m].
    """
    tau = wave_period_from_wind(wind_speed, growth)
    return 1.55 * tau**2


def wave_height_from_wind(wind_speed: ArrayLike) -> np.ndarray:
    """Height of 3 % exceedance h3% = 0.03 W² [m], Lvov (2014) eq. (3).

    Parameters
    ----------
    wind_speed : array_like
        True wind speed W [m/s].
    """
    w = as_float_array("wind_speed", wind_speed, "m/s")
    check_nonnegative("wind_speed", w, "m/s")
    return 0.03 * w**2


def deep_water_celerity(wave_length: ArrayLike, *, gravity: float = GRAVITY) -> np.ndarray:
    """Deep-water phase speed V_w = √(g λ / 2π) [m/s] of a wave of length λ [m].

    Parameters
    ----------
    wave_length : array_like
        Wave length λ [m] (> 0).
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    numpy.ndarray
        V_w [m/s].
    """
    lam = as_float_array("wave_length", wave_length, "m")
    check_positive("wave_length", lam, "m")
    return np.sqrt(gravity * lam / (2.0 * math.pi))


class ApparentWind(NamedTuple):
    """Apparent (relative) wind seen from a moving ship."""

    speed: np.ndarray
    """Apparent wind speed W [m/s]."""
    angle: np.ndarray
    """Apparent-wind bearing q_w [rad] from the bow, 0 head wind, positive from starboard."""


def apparent_wind(
    true_speed: ArrayLike,
    true_direction: ArrayLike,
    ship_speed: ArrayLike,
    heading: ArrayLike,
) -> ApparentWind:
    """Apparent wind speed and bearing from the true wind and the ship's velocity.

    Parameters
    ----------
    true_speed : array_like
        True wind speed [m/s].
    true_direction : array_like
        Direction the true wind blows *from* [rad], clockwise from north.
    ship_speed : array_like
        Ship speed over ground [m/s] (along the heading; drift neglected).
    heading : array_like
        Heading ψ [rad], clockwise from north.

    Returns
    -------
    ApparentWind
        ``(speed [m/s], angle [rad])``; the angle is wrapped to [−π, π).
    """
    w = as_float_array("true_speed", true_speed, "m/s")
    check_nonnegative("true_speed", w, "m/s")
    th = as_float_array("true_direction", true_direction, "rad")
    v = as_float_array("ship_speed", ship_speed, "m/s")
    psi = as_float_array("heading", heading, "rad")
    # "from" vector of the apparent wind = true "from" vector + ship velocity
    n = w * np.cos(th) + v * np.cos(psi)
    e = w * np.sin(th) + v * np.sin(psi)
    speed = np.hypot(n, e)
    angle = wrap_angle(np.arctan2(e, n) - psi)
    return ApparentWind(speed, angle)


def wind_lateral_force(
    wind_speed: ArrayLike,
    wind_angle: ArrayLike,
    lateral_area: ArrayLike,
    *,
    rho_air: float = RHO_AIR,
) -> np.ndarray:
    """Wind lateral force Y_a = 0.37 sin q_w ρ_a S_n W² [N] (the wind term of eq. (12)).

    Parameters
    ----------
    wind_speed : array_like
        Apparent wind speed W [m/s].
    wind_angle : array_like
        Apparent-wind bearing q_w [rad] (0 head wind, positive from starboard).
    lateral_area : array_like
        Lateral windage area S_n [m²] (above-water hull and superstructure).
    rho_air : float
        Air density ρ_a [kg/m³].
    """
    w = as_float_array("wind_speed", wind_speed, "m/s")
    q = as_float_array("wind_angle", wind_angle, "rad")
    s = as_float_array("lateral_area", lateral_area, "m²")
    check_nonnegative("lateral_area", s, "m²")
    return 0.37 * np.sin(q) * rho_air * s * w**2


def wind_moment_arm(wind_angle: ArrayLike, sail_centre: ArrayLike, length: ArrayLike) -> np.ndarray:
    """Relative arm of the wind force 0.25 + ℓ_sail/L − |q_w|°/360 [-] (eq. (12)).

    Multiply by L for the arm in metres (positive forward of midships).

    Parameters
    ----------
    wind_angle : array_like
        q_w [rad]; the degree term uses |q_w| converted to degrees.
    sail_centre : array_like
        ℓ_sail [m], centre of windage forward of midships.
    length : array_like
        L [m].
    """
    q = wrap_angle(as_float_array("wind_angle", wind_angle, "rad"))
    L = as_float_array("length", length, "m")
    check_positive("length", L, "m")
    ls = as_float_array("sail_centre", sail_centre, "m")
    check_on_hull("sail_centre", ls, L)
    return 0.25 + ls / L - np.degrees(np.abs(q)) / 360.0


def wind_yaw_moment(
    wind_speed: ArrayLike,
    wind_angle: ArrayLike,
    lateral_area: ArrayLike,
    *,
    length: ArrayLike,
    sail_centre: ArrayLike = 0.0,
    rho_air: float = RHO_AIR,
) -> np.ndarray:
    """Wind yaw moment N_a = (0.25 + ℓ_sail/L − |q_w|°/360) L Y_a [N·m] (eq. (12)).

    Parameters as :func:`wind_lateral_force` and :func:`wind_moment_arm`.

    Parameters
    ----------
    wind_speed : array_like
        Apparent wind speed W [m/s].
    wind_angle : array_like
        Apparent-wind bearing q_w [rad] (0 head wind, positive from starboard).
    lateral_area : array_like
        Lateral windage area S_n [m²].
    length : array_like
        Ship length L [m].
    sail_centre : array_like, optional
        ℓ_sail [m], centre of windage forward of midships (default 0).
    rho_air : float, optional
        Air density ρ_a [kg/m³].

    Returns
    -------
    numpy.ndarray
        N_a [N·m] (paper-signed).
    """
    y = wind_lateral_force(wind_speed, wind_angle, lateral_area, rho_air=rho_air)
    L = as_float_array("length", length, "m")
    return wind_moment_arm(wind_angle, sail_centre, L) * L * y


def wind_disturbance_body(force: ArrayLike, moment: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Paper-signed wind force/moment → seahelm body axes (y starboard, yaw bow-to-starboard).

    Parameters
    ----------
    force : array_like
        Paper-signed wind lateral force Y_a [N].
    moment : array_like
        Paper-signed wind yaw moment N_a [N·m].

    Returns
    -------
    force, moment : numpy.ndarray
        Sway force [N] and yaw moment [N·m] in seahelm body axes.
    """
    return -np.asarray(force, dtype=float), -np.asarray(moment, dtype=float)
