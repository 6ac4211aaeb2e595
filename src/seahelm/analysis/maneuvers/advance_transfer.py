"""Turning-circle metrics from recorded tracks: advance, transfer, tactical diameter.

Definitions of IMO Resolution MSC.137(76) (Standards for Ship Manoeuvrability, 2002), measured
at the point the track was recorded for (the midship point for the MMG model), from the
position and heading at the moment the rudder is **ordered** (so the rudder's travel time
counts):

advance
    distance travelled along the original course until the heading has changed by 90°;
transfer
    distance perpendicular to the original course at the 90° heading change;
tactical diameter
    distance perpendicular to the original course at the 180° heading change.

Crossings of 90° and 180° are found by linear interpolation of the recorded track between the
two samples that bracket them. This module will grow into the manoeuvre library (zig-zag
overshoots, initial turning, stopping); the functions take arrays with a leading run axis and
return one value per run.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from ..._validate import as_float_array
from ...errors import ParameterError

__all__ = ["TurningMetrics", "turning_metrics", "heading_change_crossing"]


class TurningMetrics(NamedTuple):
    """Turning-circle metrics per run (NaN where the heading change was not reached)."""

    advance: np.ndarray
    """Distance along the original course at 90° heading change [m]."""
    transfer: np.ndarray
    """Distance across the original course at 90° heading change [m] (absolute)."""
    tactical_diameter: np.ndarray
    """Distance across the original course at 180° heading change [m] (absolute)."""
    time_90: np.ndarray
    """Time of the 90° heading change [s]."""
    time_180: np.ndarray
    """Time of the 180° heading change [s]."""


def heading_change_crossing(time: Any, heading: Any, change: float, *,
                            order_time: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """First time the heading has changed by ``change`` since the order, by interpolation.

    The heading must be continuous (not wrapped); the change is counted in the direction of
    the turn, ``|ψ(t) − ψ(t_order)|``.

    Parameters
    ----------
    time : array_like, shape (steps,)
        Recording times [s], increasing.
    heading : array_like, shape (steps,) or (runs, steps)
        Continuous heading [rad].
    change : float
        Heading change [rad], > 0.
    order_time : float, optional
        Time of the rudder order [s] (default: the first recorded time).

    Returns
    -------
    index : numpy.ndarray of int, shape (runs,)
        Index k of the first sample at or beyond the change (−1 if never reached); the
        crossing lies in (k − 1, k].
    fraction : numpy.ndarray, shape (runs,)
        Interpolation weight w of sample k (value = (1 − w)·a[k−1] + w·a[k]); NaN if never
        reached.
    """
    t = as_float_array("time", time, "s")
    psi = np.atleast_2d(as_float_array("heading", heading, "rad", finite=False))
    if t.ndim != 1 or psi.shape[-1] != t.size or t.size < 2:
        raise ParameterError(
            f"`time` must be 1-D with the length of the last axis of `heading`, got "
            f"{t.shape} and {psi.shape}")
    if not change > 0:
        raise ParameterError(f"`change` must be > 0 [rad], got {change!r}")
    k0 = _order_index(t, order_time)
    delta = np.abs(psi - psi[:, k0:k0 + 1])
    index = np.full(psi.shape[0], -1, dtype=np.int64)
    fraction = np.full(psi.shape[0], np.nan)
    for i, row in enumerate(delta):
        hit = np.flatnonzero(row[k0:] >= change)
        if hit.size == 0:
            continue
        k = k0 + int(hit[0])
        index[i] = k
        if k == k0:
            fraction[i] = 1.0
        else:
            fraction[i] = (change - row[k - 1]) / (row[k] - row[k - 1])
    return index, fraction


def turning_metrics(time: Any, north: Any, east: Any, heading: Any, *,
                    order_time: float | None = None) -> TurningMetrics:
    """Advance, transfer and tactical diameter of turning circles (IMO MSC.137(76)).

    Parameters
    ----------
    time : array_like, shape (steps,)
        Recording times [s], increasing.
    north, east : array_like, shape (steps,) or (runs, steps)
        Track of the reference point (midship) [m].
    heading : array_like, shape (steps,) or (runs, steps)
        Continuous (unwrapped) heading [rad].
    order_time : float, optional
        Time of the rudder order [s] (default: the first recorded time); the original course
        and the origin of the distances are taken at the last sample at or before it.

    Returns
    -------
    TurningMetrics
        Arrays of shape (runs,): advance [m] (along the original course, positive ahead),
        transfer and tactical diameter [m] (across it, absolute), and the times of the 90°
        and 180° heading changes [s].
    """
    t = as_float_array("time", time, "s")
    n = np.atleast_2d(as_float_array("north", north, "m", finite=False))
    e = np.atleast_2d(as_float_array("east", east, "m", finite=False))
    psi = np.atleast_2d(as_float_array("heading", heading, "rad", finite=False))
    if not (n.shape == e.shape == psi.shape):
        raise ParameterError(
            f"`north`, `east` and `heading` must have one shape, got {n.shape}, {e.shape}, "
            f"{psi.shape}")
    k0 = _order_index(t, order_time)
    c0, s0 = np.cos(psi[:, k0]), np.sin(psi[:, k0])
    along = (n - n[:, k0:k0 + 1]) * c0[:, None] + (e - e[:, k0:k0 + 1]) * s0[:, None]
    across = -(n - n[:, k0:k0 + 1]) * s0[:, None] + (e - e[:, k0:k0 + 1]) * c0[:, None]
    out = {}
    for label, change in (("90", 0.5 * np.pi), ("180", np.pi)):
        idx, w = heading_change_crossing(t, psi, change, order_time=order_time)
        out[label] = (_at(along, idx, w), _at(np.abs(across), idx, w), _at(t[None, :], idx, w))
    return TurningMetrics(
        advance=out["90"][0], transfer=out["90"][1], tactical_diameter=out["180"][1],
        time_90=out["90"][2], time_180=out["180"][2],
    )


def _order_index(t: np.ndarray, order_time: float | None) -> int:
    if order_time is None:
        return 0
    if not (t[0] <= order_time <= t[-1]):
        raise ParameterError(
            f"`order_time` must lie in the recorded interval [{t[0]:g}, {t[-1]:g}] [s], got "
            f"{order_time!r}")
    return int(np.searchsorted(t, order_time, side="right") - 1)


def _at(values: np.ndarray, index: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """Interpolated value per run between samples index−1 and index (NaN if index < 0)."""
    out = np.full(index.shape, np.nan)
    for i, (k, w) in enumerate(zip(index, weight)):
        if k < 0:
            continue
        row = values[min(i, values.shape[0] - 1)]
        out[i] = row[k] if k == 0 or w == 1.0 else (1.0 - w) * row[k - 1] + w * row[k]
    return out
