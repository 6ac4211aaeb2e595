"""The distance travelled along a recorded track: chords, or the arc of its cubic spline.

:func:`track_distance` measures the distance along a track from the first sample. With the
sample times it integrates the speed along the not-a-knot cubic spline through the positions
(de Boor 1978, ch. IV: the spline's first derivatives s_i solve a tridiagonal system) by
three-point Gauss–Legendre quadrature in each interval: an error of order h⁴ in the recording
interval h. The spline is the one ``scipy.interpolate.CubicSpline(t, y, bc_type="not-a-knot")``
builds, computed here directly — the same bands and right-hand side, the same LAPACK
tridiagonal solve (``?gtsv``, which ``scipy.linalg.solve_banded`` calls), the same Hermite
coefficients and derivative evaluation, in the same floating-point order — so the distances
equal scipy's bit for bit, without constructing two interpolants per call (their input
validation and axis handling were most of the cost of a turning circle's metrics).
``tests/test_maneuver_track.py`` compares with ``CubicSpline`` on several tracks.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from numba import njit

__all__ = ["track_distance", "distance_until"]


@functools.cache
def _gauss3() -> tuple[np.ndarray, np.ndarray]:
    """Nodes on [-1, 1] and weights of three-point Gauss–Legendre quadrature."""
    nodes, weights = np.polynomial.legendre.leggauss(3)
    nodes.setflags(write=False)
    weights.setflags(write=False)
    return nodes, weights


@njit(cache=True, nogil=True)
def _factor(t: np.ndarray, lower: np.ndarray, diag: np.ndarray, upper: np.ndarray,
            fact: np.ndarray, swap: np.ndarray) -> int:  # pragma: no cover - compiled
    """The bands of the not-a-knot spline's tridiagonal system at knots ``t`` (steps >= 4)
    and their elimination with partial pivoting, in place: 0, or the 1-based row of a zero
    pivot.

    The matrix of the knot derivatives in ``scipy.interpolate.CubicSpline`` (its first and
    last rows the not-a-knot conditions), each band formed as there, eliminated as LAPACK's
    ``dgtsv`` does it (Anderson et al. 1999, the reference implementation that
    ``scipy.linalg.solve_banded`` calls): rows i and i + 1 interchanged where
    |diag[i]| < |lower[i]|; ``fact`` and ``swap`` record each step for the right-hand sides
    (:func:`_solve`), ``lower`` ends as the second superdiagonal. The matrix depends on the
    times only, so one elimination serves every run and coordinate.
    """
    n = t.size
    for i in range(n - 2):
        lower[i] = t[i + 2] - t[i + 1]
        upper[i + 1] = t[i + 1] - t[i]
        diag[i + 1] = 2 * ((t[i + 1] - t[i]) + (t[i + 2] - t[i + 1]))
    lower[n - 2] = t[n - 1] - t[n - 3]
    upper[0] = t[2] - t[0]
    diag[0] = t[2] - t[1]
    diag[n - 1] = t[n - 2] - t[n - 3]
    for i in range(n - 1):
        if abs(diag[i]) >= abs(lower[i]):
            if diag[i] == 0.0:
                return i + 1
            fact[i] = lower[i] / diag[i]
            swap[i] = False
            diag[i + 1] = diag[i + 1] - fact[i] * upper[i]
            if i < n - 2:
                lower[i] = 0.0
        else:
            fact[i] = diag[i] / lower[i]
            swap[i] = True
            diag[i] = lower[i]
            temp = diag[i + 1]
            diag[i + 1] = upper[i] - fact[i] * temp
            if i < n - 2:
                lower[i] = upper[i + 1]
                upper[i + 1] = -fact[i] * lower[i]
            upper[i] = temp
    if diag[n - 1] == 0.0:
        return n
    return 0


@njit(cache=True, nogil=True)
def _solve(t: np.ndarray, slope: np.ndarray, lower: np.ndarray, diag: np.ndarray,
           upper: np.ndarray, fact: np.ndarray, swap: np.ndarray,
           b: np.ndarray) -> None:  # pragma: no cover - compiled
    """The knot derivatives of the not-a-knot spline whose interval slopes (Δy/Δt) are
    ``slope``, into ``b``: the right-hand side of ``CubicSpline``'s system, each term formed
    as there, through the elimination :func:`_factor` recorded, and ``dgtsv``'s back
    solve."""
    n = t.size
    for i in range(1, n - 1):
        b[i] = 3 * ((t[i + 1] - t[i]) * slope[i - 1] + (t[i] - t[i - 1]) * slope[i])
    d = t[2] - t[0]
    h0, h1 = t[1] - t[0], t[2] - t[1]
    b[0] = ((h0 + 2 * d) * h1 * slope[0] + h0 ** 2 * slope[1]) / d
    d = t[n - 1] - t[n - 3]
    ha, hb = t[n - 2] - t[n - 3], t[n - 1] - t[n - 2]
    b[n - 1] = (hb ** 2 * slope[n - 3] + (2 * d + hb) * ha * slope[n - 2]) / d
    for i in range(n - 1):
        if swap[i]:
            temp = b[i]
            b[i] = b[i + 1]
            b[i + 1] = temp - fact[i] * b[i + 1]
        else:
            b[i + 1] = b[i + 1] - fact[i] * b[i]
    b[n - 1] = b[n - 1] / diag[n - 1]
    b[n - 2] = (b[n - 2] - upper[n - 2] * b[n - 1]) / diag[n - 2]
    for i in range(n - 3, -1, -1):
        b[i] = (b[i] - upper[i] * b[i + 1] - lower[i] * b[i + 2]) / diag[i]


@njit(cache=True, nogil=True)
def _gauss_speeds(t: np.ndarray, north: np.ndarray, east: np.ndarray, nodes: np.ndarray,
                  until: np.ndarray, out: np.ndarray) -> int:  # pragma: no cover - compiled
    """The speed |(dN/dt, dE/dt)| along the splines through each run's track (rows of
    ``north``, ``east``) at the Gauss points ``nodes`` of its first ``until[run]`` intervals,
    into ``out`` (intervals, nodes, runs; 0 in the later intervals; ``out`` may hold fewer
    intervals than the track, the first ones). The Hermite coefficients and the derivative c2 + 2 c1 x + 3 c0 x²
    are formed as ``CubicHermiteSpline`` and ``PPoly`` form them, term by term, at x from the
    interval's start. 0, or the 1-based row of a zero pivot."""
    n = t.size
    runs = north.shape[0]
    width = min(n - 1, out.shape[0])  # (the intervals asked for)
    lower, diag, upper = np.empty(n - 1), np.empty(n), np.empty(n - 1)
    fact, swap = np.empty(n - 1), np.empty(n - 1, dtype=np.bool_)
    info = _factor(t, lower, diag, upper, fact, swap)
    if info != 0:
        return info
    h = np.empty(n - 1)
    x = np.empty((n - 1, nodes.size))
    for i in range(n - 1):
        h[i] = t[i + 1] - t[i]
        for q in range(nodes.size):
            x[i, q] = (t[i] + 0.5 * h[i] * (nodes[q] + 1.0)) - t[i]
    block = 16  # runs at a time: ``out`` is written along runs, a cache line at a time
    mn, me = np.empty((block, n - 1)), np.empty((block, n - 1))
    sn, se = np.empty((block, n)), np.empty((block, n))
    for j0 in range(0, runs, block):
        size = min(block, runs - j0)
        for jj in range(size):
            for i in range(n - 1):
                mn[jj, i] = (north[j0 + jj, i + 1] - north[j0 + jj, i]) / h[i]
                me[jj, i] = (east[j0 + jj, i + 1] - east[j0 + jj, i]) / h[i]
            _solve(t, mn[jj], lower, diag, upper, fact, swap, sn[jj])
            _solve(t, me[jj], lower, diag, upper, fact, swap, se[jj])
        for i in range(width):
            for jj in range(size):
                tt_n = (sn[jj, i] + sn[jj, i + 1] - 2 * mn[jj, i]) / h[i]
                c0_n = tt_n / h[i]
                c1_n = (mn[jj, i] - sn[jj, i]) / h[i] - tt_n
                tt_e = (se[jj, i] + se[jj, i + 1] - 2 * me[jj, i]) / h[i]
                c0_e = tt_e / h[i]
                c1_e = (me[jj, i] - se[jj, i]) / h[i] - tt_e
                if i >= until[j0 + jj]:
                    for q in range(nodes.size):
                        out[i, q, j0 + jj] = 0.0
                    continue
                for q in range(nodes.size):
                    xq = x[i, q]
                    rate_n = sn[jj, i] + c1_n * xq * 2.0 + c0_n * (xq * xq) * 3.0
                    rate_e = se[jj, i] + c1_e * xq * 2.0 + c0_e * (xq * xq) * 3.0
                    out[i, q, j0 + jj] = math.hypot(rate_n, rate_e)
    return 0


def track_distance(north: Any, east: Any, time: Any = None) -> np.ndarray:
    """Distance travelled along a recorded track [m].

    Without ``time``: the cumulative sum of the chords between samples (it falls short of the
    arc by ~ L κ² h² U²/24 for a recording interval h at curvature κ). With ``time`` (and at
    least four samples): the arc length of the cubic spline through the positions
    (not-a-knot, as ``scipy.interpolate.CubicSpline``), by three-point Gauss–Legendre
    quadrature of the speed along it in each interval — an error of order h⁴. A run with a
    non-finite position gets the chord sum.

    Parameters
    ----------
    north, east : array_like, shape (steps,) or (runs, steps)
        Positions [m].
    time : array_like, shape (steps,), optional
        Sample times [s], strictly increasing.

    Returns
    -------
    numpy.ndarray, shape (runs, steps)
        Distance from the first sample [m].

    Raises
    ------
    ValueError
        If ``time`` is not a finite, strictly increasing 1-D array of the track's length.
    """
    return distance_until(north, east, time)


def distance_until(north: Any, east: Any, time: Any = None, until: Any = None) -> np.ndarray:
    """:func:`track_distance` where only the first ``until[run]`` samples of each run are
    wanted (default: all): the same values there (the quadrature of the later intervals, whose
    speeds are not evaluated, is 0, so the distances beyond are not the track's). A metric read
    early in a long record (the initial turning's distance at 10°) costs a fraction.

    Parameters
    ----------
    north, east : array_like
        Positions [m], shape (runs, samples) or (samples,); a run with a NaN is not run.
    time : array_like, optional
        Sample times [s], strictly increasing, shape (samples,); without it, the chords.
    until : array_like of int, optional
        Per run, the number of intervals whose distance is wanted (default: all).

    Returns
    -------
    numpy.ndarray
        Distance along the track [m] at each sample, shape (runs, samples).
    """
    n = np.atleast_2d(np.asarray(north, dtype=float))
    e = np.atleast_2d(np.asarray(east, dtype=float))
    fast = _every_run_by_spline(n, e, time, until)
    if fast is not None:
        return fast
    rows = np.isfinite(n).all(axis=1) & np.isfinite(e).all(axis=1)  # (a run not run: NaN)
    spline = time is not None and n.shape[1] >= 4 and bool(rows.any())
    pieces = (np.hypot(np.diff(n, axis=1), np.diff(e, axis=1)) if not spline or not rows.all()
              else None)  # (the chords of the runs without a spline)
    if spline:
        t = np.asarray(time, dtype=float)
        h = np.diff(t) if t.ndim == 1 else None
        if (h is None or t.size != n.shape[1] or not np.isfinite(t).all()
                or not (h > 0).all()):
            raise ValueError(f"`time` [s] must be finite, strictly increasing and of shape "
                             f"({n.shape[1]},) as the positions, got shape {t.shape}")
        every = bool(rows.all())
        nodes, weights = _gauss3()
        north_rows = n if every else n[rows]
        intervals = np.full(n.shape[0], n.shape[1] - 1, dtype=np.int64) if until is None \
            else np.asarray(until, dtype=np.int64)
        wanted = np.ascontiguousarray(intervals if every else intervals[rows])
        # only the intervals some run asks for are evaluated and summed: the later ones'
        # pieces are 0 (as the kernel writes beyond ``until``; 0.5 h (0 @ w) is +0.0)
        width = (t.size - 1 if until is None or not wanted.size
                 else int(min(t.size - 1, max(int(wanted.max()), 0))))
        speed = np.empty((width, nodes.size, north_rows.shape[0]))
        if _gauss_speeds(t, np.ascontiguousarray(north_rows),
                         np.ascontiguousarray(e if every else e[rows]), nodes, wanted, speed):
            raise np.linalg.LinAlgError("singular matrix")  # pragma: no cover - h > 0
        # (the quadrature sum over this memory layout, (intervals, 3, runs) seen as
        # (runs, intervals, 3), as before: numpy's matmul sums in an order of its layout's
        # and size's; each run's and interval's sum of three is the same for fewer intervals)
        arc = 0.5 * h[:width] * (speed.transpose(2, 0, 1) @ weights)
        if width < t.size - 1:
            arc = np.concatenate([arc, np.zeros((arc.shape[0], t.size - 1 - width))], axis=1)
        if every:
            pieces = arc
        else:
            pieces[rows] = arc
    return np.concatenate([np.zeros((n.shape[0], 1)), np.cumsum(pieces, axis=1)], axis=1)


def _every_run_by_spline(n: np.ndarray, e: np.ndarray, time: Any,
                         until: Any) -> np.ndarray | None:
    """:func:`distance_until` of the usual case, every run finite and the times valid (one
    compiled pass checks both, :func:`_times_and_tracks`): the same steps and numbers, without
    the array checks and the two concatenations; None otherwise (the general form then checks,
    raises or takes the chords as before)."""
    if time is None or n.ndim != 2 or n.shape != e.shape or n.shape[1] < 4:
        return None
    t = np.asarray(time, dtype=float)
    if t.ndim != 1 or t.size != n.shape[1]:
        return None
    t = np.ascontiguousarray(t)
    h = np.empty(t.size - 1)
    if _times_and_tracks(t, n, e, h):
        return None
    nodes, weights = _gauss3()
    wanted = (np.full(n.shape[0], n.shape[1] - 1, dtype=np.int64) if until is None
              else np.ascontiguousarray(np.asarray(until, dtype=np.int64)))
    width = (t.size - 1 if until is None or not wanted.size
             else int(min(t.size - 1, max(int(wanted.max()), 0))))
    speed = np.empty((width, nodes.size, n.shape[0]))
    if _gauss_speeds(t, np.ascontiguousarray(n), np.ascontiguousarray(e), nodes, wanted, speed):
        return None  # pragma: no cover - h > 0 (the general form raises)
    return _arc_distances(h, speed, width, t.size)


def _arc_distances(h: np.ndarray, speed: np.ndarray, width: int, samples: int) -> np.ndarray:
    """The distances (runs, ``samples``) from the spline's speeds at the Gauss points of the
    first ``width`` intervals, ``speed[:width]`` (intervals, nodes, runs) of
    :func:`_gauss_speeds`, and the steps ``h``: the quadrature of each interval and their
    cumulative sum, as :func:`distance_until` forms them (the later intervals' pieces are 0:
    their sums stay the last one). A ``speed`` of more intervals is read in its first
    ``width`` (C order: the same memory layout, so numpy's matmul sums as it did)."""
    weights = _gauss3()[1]
    arc = 0.5 * h[:width] * (speed[:width].transpose(2, 0, 1) @ weights)  # (as distance_until)
    out = np.zeros((speed.shape[2], samples))
    np.cumsum(arc, axis=1, out=out[:, 1:width + 1])
    out[:, width + 1:] = out[:, width:width + 1]
    return out


@njit(cache=True, nogil=True)
def _times_and_tracks(t: np.ndarray, north: np.ndarray, east: np.ndarray,
                      h: np.ndarray) -> int:  # pragma: no cover - compiled
    """0 if the times ``t`` are finite and strictly increasing and every position finite
    (``h`` then holds the steps t[i+1] − t[i], as ``np.diff``), else 1."""
    for i in range(t.size):
        if not np.isfinite(t[i]):
            return 1
    for i in range(t.size - 1):
        h[i] = t[i + 1] - t[i]
        if not h[i] > 0:
            return 1
    for r in range(north.shape[0]):
        for j in range(north.shape[1]):
            if not (np.isfinite(north[r, j]) and np.isfinite(east[r, j])):
                return 1
    return 0
