"""Physical constants and angle helpers (SI units, radians inside)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "GRAVITY",
    "RHO_SEAWATER",
    "RHO_AIR",
    "KNOT",
    "wrap_angle",
    "deg2rad",
    "rad2deg",
]

GRAVITY: float = 9.80665
"""Standard gravity g [m/s²]."""

RHO_SEAWATER: float = 1025.0
"""Sea-water density ρ [kg/m³]."""

RHO_AIR: float = 1.225
"""Air density ρ_a at 15 °C, sea level [kg/m³]."""

KNOT: float = 1852.0 / 3600.0
"""One knot [m/s]."""


def wrap_angle(angle: ArrayLike) -> np.ndarray:
    """Wrap angles [rad] to the half-open interval [-π, π).

    Parameters
    ----------
    angle : float or array_like
        Angle(s) [rad].

    Returns
    -------
    numpy.ndarray
        Wrapped angle(s) [rad].
    """
    a = np.asarray(angle, dtype=float)
    inside = (a >= -np.pi) & (a < np.pi)  # returned exactly, without round-off
    wrapped = np.mod(a + np.pi, 2.0 * np.pi) - np.pi
    # just below −π, a + π rounds so that the mod gives 2π: fold that back to −π
    wrapped = np.where(wrapped >= np.pi, wrapped - 2.0 * np.pi, wrapped)
    return np.where(inside, a, wrapped)


def deg2rad(angle_deg: ArrayLike) -> np.ndarray:
    """Degrees to radians (for the edges: CLI, tables, plots).

    Parameters
    ----------
    angle_deg : float or array_like
        Angle(s) [deg].

    Returns
    -------
    numpy.ndarray
        Angle(s) [rad].
    """
    return np.deg2rad(np.asarray(angle_deg, dtype=float))


def rad2deg(angle_rad: ArrayLike) -> np.ndarray:
    """Radians to degrees (for the edges: CLI, tables, plots).

    Parameters
    ----------
    angle_rad : float or array_like
        Angle(s) [rad].

    Returns
    -------
    numpy.ndarray
        Angle(s) [deg].
    """
    return np.rad2deg(np.asarray(angle_rad, dtype=float))
