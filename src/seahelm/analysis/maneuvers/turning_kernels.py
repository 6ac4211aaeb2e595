"""Compiled passes of the turning circle's metrics (:mod:`~seahelm.analysis.maneuvers.turning_circle`).

Each replaces a sequence of small numpy operations over a few samples per run, whose Python
calls were most of the cost of one circle's metrics (issue 46 item 6: one circle end to end
>= 10x shipmmg), by one call that does the same element operations in the same order: the
same numbers bit for bit (``tests/test_maneuver_metrics_call_cost.py``,
``tests/test_maneuver_metrics_fast_paths.py``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__: list[str] = []

_QUARTER = 0.5 * math.pi


@njit(cache=True, nogil=True)
def _event_nodes(north: np.ndarray, east: np.ndarray, times: np.ndarray, dist: np.ndarray,
                 k: np.ndarray, j0: np.ndarray, weights: np.ndarray, c0: np.ndarray,
                 s0: np.ndarray, buf: np.ndarray) -> int:  # pragma: no cover - compiled
    """The four signals of :func:`_event_values` at the four nodes of every event into
    ``buf`` (levels, runs, nodes, signals), each element by the operations of the array form
    (dn c0 + de s0, |−dn s0 + de c0|, the time, the distance along the track; ``c0``, ``s0``
    the cosine and sine of each run's first heading, formed by numpy): 0 (``buf`` not
    filled) if an event has no cubic (not reached, or a NaN first weight), else 2 if every
    weight is finite, 1 if not."""
    every = True
    for a in range(k.shape[0]):
        for r in range(k.shape[1]):
            if k[a, r] < 0 or not np.isfinite(weights[a, r, 0]):
                return 0
            for m in range(4):
                if not np.isfinite(weights[a, r, m]):
                    every = False
    for a in range(k.shape[0]):
        for r in range(k.shape[1]):
            n0, e0 = north[r, 0], east[r, 0]
            for m in range(4):
                j = j0[a, r] + m
                dn = north[r, j] - n0
                de = east[r, j] - e0
                buf[a, r, m, 0] = dn * c0[r] + de * s0[r]
                buf[a, r, m, 1] = abs(-dn * s0[r] + de * c0[r])
                buf[a, r, m, 2] = times[r, j]
                buf[a, r, m, 3] = dist[r, j]
    return 2 if every else 1


@njit(cache=True, nogil=True)
def _steady_ends(change: np.ndarray, r: np.ndarray, speed: np.ndarray, radius: np.ndarray,
                 steady: np.ndarray) -> None:  # pragma: no cover - compiled
    """Each run's steady turning radius U/|r| at its last sample (inf where r = 0, NaN where
    r is NaN) into ``radius``, and into ``steady`` whether |r| changed by at most 1 % since
    the last sample at least 90° of heading change before the end (``change`` (runs, samples),
    the heading change; no such sample, or a non-finite r: False): the array form's
    ``np.where(r != 0, U / |r|, inf)`` and ``|r − r_back| <= 0.01 |r|`` per run."""
    last = change.shape[1] - 1
    for i in range(change.shape[0]):
        sr, su = r[i, last], speed[i, last]
        radius[i] = su / abs(sr) if sr != 0.0 else np.inf
        level = change[i, last] - _QUARTER
        back = -1
        for j in range(last, -1, -1):  # (the last sample at or below the level)
            if change[i, j] <= level:
                back = j
                break
        steady[i] = (back >= 0 and np.isfinite(sr)
                     and abs(sr - r[i, back]) <= 0.01 * abs(sr))
