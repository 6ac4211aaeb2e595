"""Steady turns from a recorded time series (the points the reduced-model fits take).

:func:`extract_steady_segments` finds the stretches of a log where the rudder angle and the yaw
rate are steady and returns one point (ω_i, α_i) per stretch, :class:`SteadySegments`; the fits
are in :mod:`seahelm.identification.reduced.fitting`.

References
----------
Romanov, A. V., Chirkova, M. M. Transforming the mathematical model of ship manoeuvrability to
minimise the time to estimate its coefficients (in Russian), VGAVT.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..._validate import as_finite_series, check_positive
from ...errors import ParameterError

__all__ = [
    "SteadySegments",
    "extract_steady_segments",
]


# --------------------------------------------------------------------------------------------
# Steady segments of a time series
# --------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SteadySegments:
    """Steady turns found in a time series, one entry per segment.

    Attributes
    ----------
    start_time, end_time : numpy.ndarray
        Bounds [s] of the settled part of each constant-rudder segment.
    rudder_angle, yaw_rate : numpy.ndarray
        Means over the settled part [rad], [rad/s].
    yaw_rate_std : numpy.ndarray
        Sample standard deviation of the yaw rate over the settled part [rad/s].
    n_samples : numpy.ndarray
        Samples in each settled part.
    """

    start_time: np.ndarray
    end_time: np.ndarray
    rudder_angle: np.ndarray
    yaw_rate: np.ndarray
    yaw_rate_std: np.ndarray
    n_samples: np.ndarray

    def __len__(self) -> int:
        return int(self.yaw_rate.size)


def extract_steady_segments(
    time: Any,
    rudder_angle: Any,
    yaw_rate: Any,
    *,
    rudder_tolerance: float = math.radians(0.2),
    yaw_rate_tolerance: float = 3e-5,
    min_duration: float = 60.0,
    smoothing: float = 20.0,
) -> SteadySegments:
    """Windows where the rudder is constant and the yaw rate has settled.

    Parameters
    ----------
    time : array_like
        Sample times [s], strictly increasing.
    rudder_angle, yaw_rate : array_like
        α [rad] and ω [rad/s] at those times.
    rudder_tolerance : float
        A constant-rudder segment ends at the first sample whose rudder angle differs from the
        segment's first one by more than this [rad].
    yaw_rate_tolerance : float
        Settled means: from the start of the settled part to the end of the segment the yaw rate
        stays inside a band of half-width ``yaw_rate_tolerance`` [rad/s] (max − min ≤ 2·tol).
        The settled part is the longest such tail of the segment.
    min_duration : float
        Minimum duration [s] of the settled part; shorter ones are discarded.
    smoothing : float
        Length [s] of a centred moving average applied (within each segment) to the yaw rate
        before the band test, so that sensor noise does not hide a settled turn; the reported
        means use the raw samples. 0 = no smoothing.

    The defaults suit a large ship (settling over minutes) with a yaw-rate sensor noise of
    a few 1e-5 rad/s; scale them with the ship and the sensor.

    Returns
    -------
    SteadySegments

    Raises
    ------
    ParameterError
        Unequal lengths, fewer than 2 samples, non-finite values, time not increasing,
        non-positive thresholds.
    """
    t = as_finite_series("time", time, "s")
    al = as_finite_series("rudder_angle", rudder_angle, "rad")
    w = as_finite_series("yaw_rate", yaw_rate, "rad/s")
    if not (t.size == al.size == w.size):
        raise ParameterError(
            f"`time`, `rudder_angle`, `yaw_rate` must have equal length, got "
            f"{t.size}, {al.size}, {w.size}"
        )
    if t.size < 2:
        raise ParameterError(f"the time series needs at least 2 samples, got {t.size}")
    if np.any(np.diff(t) <= 0):
        raise ParameterError("`time` must be strictly increasing [s]")
    check_positive("rudder_tolerance", rudder_tolerance, "rad")
    check_positive("yaw_rate_tolerance", yaw_rate_tolerance, "rad/s")
    check_positive("min_duration", min_duration, "s")
    if not (math.isfinite(smoothing) and smoothing >= 0):
        raise ParameterError(f"`smoothing` must be >= 0 [s], got {smoothing!r}")
    half = int(round(0.5 * smoothing / float(np.median(np.diff(t)))))
    # constant-rudder segments
    bounds = []
    start = 0
    for k in range(1, t.size):
        if abs(al[k] - al[start]) > rudder_tolerance:
            bounds.append((start, k))
            start = k
    bounds.append((start, t.size))
    rows = []
    for i0, i1 in bounds:
        seg = _moving_average(w[i0:i1], half)
        # suffix band: running max/min from the end
        smax = np.maximum.accumulate(seg[::-1])[::-1]
        smin = np.minimum.accumulate(seg[::-1])[::-1]
        ok = np.flatnonzero(smax - smin <= 2.0 * yaw_rate_tolerance)
        if ok.size == 0:
            continue
        j0 = i0 + int(ok[0])
        if t[i1 - 1] - t[j0] < min_duration:
            continue
        part = slice(j0, i1)
        n = i1 - j0
        rows.append((t[j0], t[i1 - 1], float(np.mean(al[part])), float(np.mean(w[part])),
                     float(np.std(w[part], ddof=1)) if n > 1 else 0.0, n))
    cols = list(zip(*rows)) if rows else [()] * 6
    return SteadySegments(
        start_time=np.asarray(cols[0], dtype=float),
        end_time=np.asarray(cols[1], dtype=float),
        rudder_angle=np.asarray(cols[2], dtype=float),
        yaw_rate=np.asarray(cols[3], dtype=float),
        yaw_rate_std=np.asarray(cols[4], dtype=float),
        n_samples=np.asarray(cols[5], dtype=int),
    )


def _moving_average(x: np.ndarray, half: int) -> np.ndarray:
    """Centred moving average over 2·half + 1 samples, window shrunk at the ends."""
    if half <= 0 or x.size < 2:
        return x
    c = np.concatenate(([0.0], np.cumsum(x)))
    idx = np.arange(x.size)
    lo = np.maximum(idx - half, 0)
    hi = np.minimum(idx + half + 1, x.size)
    return (c[hi] - c[lo]) / (hi - lo)
