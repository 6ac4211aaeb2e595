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

from .track import _gauss_speeds, _times_and_tracks

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


@njit(cache=True, nogil=True)
def _first_crossings(change: np.ndarray, levels: np.ndarray, k: np.ndarray,
                     w: np.ndarray) -> None:  # pragma: no cover - compiled
    """:func:`_crossings` into ``k`` and ``w``: one pass along each run per level (a NaN
    sample reaches no level), w = (level − c[k−1]) / (c[k] − c[k−1])."""
    for a in range(levels.size):
        level = levels[a]
        for r in range(change.shape[0]):
            k[a, r] = -1
            w[a, r] = np.nan
            for j in range(change.shape[1]):
                if change[r, j] >= level:
                    k[a, r] = j
                    # j > 0: c[j] >= level > c[j-1], so the difference is > 0
                    w[a, r] = ((level - change[r, j - 1]) / (change[r, j] - change[r, j - 1])
                               if j > 0 else 1.0)
                    break


@njit(cache=True, nogil=True)
def _bracket(times: np.ndarray, change: np.ndarray, k: np.ndarray, w: np.ndarray,
             j0: np.ndarray, s_nodes: np.ndarray, c_nodes: np.ndarray, good: np.ndarray,
             s: np.ndarray) -> None:  # pragma: no cover - compiled
    """The four samples around each crossing (levels, runs) for :func:`_cubic_crossings`:
    the first of them ``j0`` (k − 2 moved inside the record), their times scaled to the
    bracketing interval [t_{k−1}, t_k] → [0, 1] (``s_nodes``) and heading changes
    (``c_nodes``), whether the cubic applies (``good``: k > 0 and four samples) and Newton's
    start ``s`` (the linear estimate, NaN as 0; 0 where not good)."""
    steps = change.shape[1]
    big = np.finfo(np.float64).max
    for a in range(k.shape[0]):
        for r in range(k.shape[1]):
            kk = k[a, r]
            first = min(max(kk - 2, 0), max(steps - 4, 0))
            j0[a, r] = first
            lo = times[r, max(kk - 1, 0)]
            hi = times[r, max(kk, 0)]
            scale = hi - lo if hi > lo else 1.0
            for m in range(4):
                j = min(first + m, steps - 1)
                s_nodes[a, r, m] = (times[r, j] - lo) / scale
                c_nodes[a, r, m] = change[r, j]
            ok = kk > 0 and steps >= 4
            good[a, r] = ok
            x = w[a, r]
            if x != x:  # (np.nan_to_num)
                x = 0.0
            elif x > big:
                x = big
            elif x < -big:
                x = -big
            s[a, r] = x if ok else 0.0


@njit(cache=True, nogil=True)
def _newton(coef: np.ndarray, levels: np.ndarray, s: np.ndarray) -> None:  # pragma: no cover
    """Eight Newton steps on c0 + c1 s + c2 s² + c3 s³ = level for every (level, run), in
    place from ``s`` and kept in [0, 1] (a step where the slope is not > 0 is none; NaN stays
    NaN): the loop of :func:`_cubic_crossings` over all crossings at once, each operation
    as the array form did it (the same numbers), without its array temporaries."""
    for a in range(s.shape[0]):
        target = levels[a]
        for b in range(s.shape[1]):
            c0, c1, c2, c3 = coef[a, b, 0], coef[a, b, 1], coef[a, b, 2], coef[a, b, 3]
            x = s[a, b]
            for _ in range(8):
                value = c0 + x * (c1 + x * (c2 + x * c3))
                slope = c1 + x * (2.0 * c2 + x * 3.0 * c3)
                step = (value - target) / slope if slope > 0 else 0.0
                x = x - step
                if x < 0.0:  # (np.clip: NaN stays NaN)
                    x = 0.0
                elif x > 1.0:
                    x = 1.0
            s[a, b] = x


@njit(cache=True, nogil=True)
def _first_pass(change: np.ndarray, levels: np.ndarray, times: np.ndarray, r: np.ndarray,
                speed: np.ndarray, k: np.ndarray, w: np.ndarray, j0: np.ndarray,
                s_nodes: np.ndarray, c_nodes: np.ndarray, good: np.ndarray, s: np.ndarray,
                radius: np.ndarray, steady: np.ndarray) -> None:  # pragma: no cover - compiled
    """:func:`_first_crossings`, :func:`_bracket` and :func:`_steady_ends` in one call (the
    same functions, so the same numbers: each compiled call from Python costs its dispatch,
    a good part of a single circle's metrics)."""
    _first_crossings(change, levels, k, w)
    _bracket(times, change, k, w, j0, s_nodes, c_nodes, good, s)
    _steady_ends(change, r, speed, radius, steady)


@njit(cache=True, nogil=True)
def _front(psi: np.ndarray, levels: np.ndarray, t: np.ndarray, times: np.ndarray,
           r: np.ndarray, speed: np.ndarray, north: np.ndarray, east: np.ndarray,
           nodes: np.ndarray, event: int, change: np.ndarray, k: np.ndarray, w: np.ndarray,
           j0: np.ndarray, s_nodes: np.ndarray, c_nodes: np.ndarray, good: np.ndarray,
           s: np.ndarray, radius: np.ndarray, steady: np.ndarray, h: np.ndarray,
           rates: np.ndarray) -> tuple[int, bool]:  # pragma: no cover - compiled
    """A turning circle's metrics up to the cubic weights' solves, in one compiled call.

    The heading change ``change`` = |ψ − ψ₀| of each run (the array form's
    ``np.abs(psi - psi[:, :1])``, element by element), then :func:`_first_pass` (crossings,
    brackets, steady ends), then the speeds along the track's spline of
    :func:`~seahelm.analysis.maneuvers.track.distance_until`'s fast path up to the last node of
    level ``event`` (j0 + 3 intervals: its ``_times_and_tracks`` check and ``_gauss_speeds``,
    the same functions, into ``rates[:width]`` and the steps into ``h``).

    Returns (width, every_good): the intervals whose speeds were evaluated (−1: the track or
    times do not pass the fast path's check, or fewer than four samples; the general form is
    then taken) and whether every crossing has its cubic (``good.all()``).
    """
    for i in range(psi.shape[0]):
        first = psi[i, 0]
        for j in range(psi.shape[1]):
            change[i, j] = abs(psi[i, j] - first)
    _first_pass(change, levels, times, r, speed, k, w, j0, s_nodes, c_nodes, good, s, radius,
                steady)
    every_good = True
    for a in range(good.shape[0]):
        for b in range(good.shape[1]):
            if not good[a, b]:
                every_good = False
    runs, samples = north.shape[0], north.shape[1]
    if samples < 4 or t.size != samples or _times_and_tracks(t, north, east, h):
        return -1, every_good
    until = np.empty(runs, dtype=np.int64)
    most = 0
    for i in range(runs):
        until[i] = j0[event, i] + 3
        most = max(most, until[i])
    width = min(samples - 1, most)
    if _gauss_speeds(t, north, east, nodes, until, rates[:width]):
        return -1, every_good  # (a zero pivot: never, h > 0; the general form raises)
    return width, every_good


@njit(cache=True, nogil=True)
def _completion(time_at: np.ndarray, status: np.ndarray,
                complete: np.ndarray) -> int:  # pragma: no cover - compiled
    """Whether each run is complete into ``complete``: every event's time (``time_at``,
    (levels, runs)) reached (not NaN) and the run's status 0 (its message "ok"): the array
    form's ``~isnan(t_10) & ~isnan(t_90) & ~isnan(t_180) & (messages == "ok")``. Returns how
    many runs are not complete."""
    missing = 0
    for i in range(status.size):
        ok = status[i] == 0
        for a in range(time_at.shape[0]):
            if time_at[a, i] != time_at[a, i]:
                ok = False
        complete[i] = ok
        missing += not ok
    return missing
