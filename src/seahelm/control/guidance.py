"""Guidance: the course setter of Lvov (2014), Fig. 1, block 1.

The initial great-circle course from departure to arrival, and the heading to steer so that
the course over ground holds against the wind and wave drift angles.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_range

__all__ = ["initial_great_circle_course", "course_to_steer"]


def initial_great_circle_course(
    lat_departure: ArrayLike,
    lon_departure: ArrayLike,
    lat_arrival: ArrayLike,
    lon_arrival: ArrayLike,
) -> np.ndarray:
    """Initial great-circle course [rad] in [0, 2π), clockwise from north.

    tan C = sin Δλ cos φ2 / (cos φ1 sin φ2 − sin φ1 cos φ2 cos Δλ), all angles in radians
    (latitude φ north positive, longitude λ east positive).

    Parameters
    ----------
    lat_departure, lon_departure : array_like
        Latitude φ1 (north positive, in [−π/2, π/2]) and longitude λ1 (east positive) of the
        departure point [rad].
    lat_arrival, lon_arrival : array_like
        Latitude φ2 (in [−π/2, π/2]) and longitude λ2 of the arrival point [rad].

    Returns
    -------
    numpy.ndarray
        Initial course C [rad] in [0, 2π).
    """
    p1 = as_float_array("lat_departure", lat_departure, "rad")
    l1 = as_float_array("lon_departure", lon_departure, "rad")
    p2 = as_float_array("lat_arrival", lat_arrival, "rad")
    l2 = as_float_array("lon_arrival", lon_arrival, "rad")
    for name, v in (("lat_departure", p1), ("lat_arrival", p2)):
        check_range(name, v, -math.pi / 2, math.pi / 2, "rad")
    dl = l2 - l1
    c = np.arctan2(
        np.sin(dl) * np.cos(p2), np.cos(p1) * np.sin(p2) - np.sin(p1) * np.cos(p2) * np.cos(dl)
    )
    return np.mod(c, 2.0 * math.pi)


def course_to_steer(
    course: ArrayLike, wind_drift: ArrayLike = 0.0, wave_drift: ArrayLike = 0.0
) -> np.ndarray:
    """Heading to steer [rad] so that the course over ground is ``course`` (block 1, Fig. 1).

    With the drift angle β positive when the ship's velocity lies to *port* of its heading
    (the paper's and :mod:`seahelm.vessels.voitkunsky`'s convention; a wind or sea from
    starboard gives β > 0), the course over ground is ψ − β, so ψ = C + α_wind + α_waves,
    wrapped to [0, 2π).

    Parameters
    ----------
    course : array_like
        Wanted course over ground C [rad].
    wind_drift : array_like, optional
        Wind drift angle α_wind [rad] (default 0).
    wave_drift : array_like, optional
        Wave drift angle α_waves [rad] (default 0).

    Returns
    -------
    numpy.ndarray
        Heading to steer ψ [rad] in [0, 2π).
    """
    c = as_float_array("course", course, "rad")
    return np.mod(c + np.asarray(wind_drift, float) + np.asarray(wave_drift, float), 2.0 * math.pi)
