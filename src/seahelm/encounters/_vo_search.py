"""The candidate search of :class:`~seahelm.encounters.avoidance.VelocityObstacles`, compiled:
one pass over (encounter, avoiding vessel, candidate heading, other vessel).

For each candidate velocity ``v_c`` and each other vessel heard from, the closest point of
approach of the relative motion (:func:`~seahelm.encounters.geometry.cpa_tcpa`: ``w = v_t -
v_c``, ``TCPA = -(r·w)/|w|²``, ``DCPA = |r + w·TCPA|``), whether ``v_c`` is inside that
vessel's velocity obstacle (Kuwata et al. 2014: ``0 < TCPA < horizon`` and ``DCPA < radius``,
or inside the radius already and closing), whether it passes on the wrong side
(``r × (v_c - v_t) < 0``), and the side rule's bar; then per (encounter, vessel) the cheapest
admissible candidate, or when none is, the one with the largest least DCPA.

The arithmetic is that of the numpy expressions it replaces, operation for operation (no
fused multiply-adds: numba compiles without ``fastmath``; ``math.hypot`` is the C library's
``hypot``, as ``numpy.hypot``), so the picks are the same, bit for bit
(``tests/test_encounters_vo_search.py``); every transcendental function (the candidates'
velocities, the wrapped heading errors) is still computed by numpy, outside.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["vo_pick"]


@njit(cache=True)
def _tcpa(r0, r1, w0, w1):  # pragma: no cover - compiled
    """TCPA of :func:`~seahelm.encounters.geometry.cpa_tcpa` (0 without relative motion),
    and the relative velocity it was computed for."""
    ww = w0 * w0 + w1 * w1
    rw = r0 * w0 + r1 * w1
    return ((-rw) / ww if ww > 0.0 else 0.0), w0, w1


@njit(cache=True)
def _least_dcpa(e, a, c, v_cn, v_ce, po0, po1, p_t, v_t, counted):  # pragma: no cover
    """The least DCPA of candidate ``c`` over the counted pairs (inf without one; NaN if
    one is NaN, as ``np.min``)."""
    least = math.inf
    for j in range(p_t.shape[1]):
        if counted[e, a, j]:
            r0, r1 = p_t[e, j, 0] - po0, p_t[e, j, 1] - po1
            tcpa, w0, w1 = _tcpa(r0, r1, v_t[e, j, 0] - v_cn[e, a, c],
                                 v_t[e, j, 1] - v_ce[e, a, c])
            dcpa = math.hypot(r0 + w0 * tcpa, r1 + w1 * tcpa)
            if math.isnan(dcpa) or dcpa < least:  # (NaN < x is False)
                least = dcpa
    return least


@njit(cache=True)
def vo_pick(v_cn, v_ce, p_o, p_t, v_t, rr, radius, horizon, live, counted, give_way, side, far,
            off):  # pragma: no cover - compiled
    """The candidate each avoiding vessel takes (index into ``off``).

    Parameters
    ----------
    v_cn, v_ce : ndarray (e, a, c)
        Candidate velocities, north and east [m/s].
    p_o : ndarray (e, a, 2)
        The avoiding vessels' true positions [m].
    p_t, v_t : ndarray (e, j, 2)
        Every vessel's reported position [m] and velocity [m/s].
    rr : ndarray (e, a, j)
        Range to each vessel [m].
    radius : ndarray (e, a)
        Safety radius [m] (with hysteresis while off the route).
    horizon : float
        Time horizon of the obstacles [s].
    live : ndarray of bool (e, a, j)
        The pairs that count at all (another vessel, heard from): ``counted`` and
        ``give_way`` must be False elsewhere (their closest points are not computed).
    counted, give_way : ndarray of bool (e, a, j)
        Pairs whose obstacle excludes candidates; pairs whose wrong side excludes them.
    side : ndarray of int8 (e, a, j)
        The side rule: 2 starboard only, ±1 the sign ``r × w`` must keep, 0 free.
    far : ndarray of bool (e, a, c)
        Candidates out of reach (already relaxed where none is within reach).
    off : ndarray (c,)
        The candidates' offsets from the route's heading [rad].

    Returns
    -------
    ndarray of int64 (e, a)
    """
    ne, na, nc = v_cn.shape[0], v_cn.shape[1], v_cn.shape[2]
    nj = p_t.shape[1]
    pick = np.empty((ne, na), dtype=np.int64)
    bad = np.empty(nc, dtype=np.bool_)
    barred = np.empty(nc, dtype=np.bool_)
    cost0 = np.empty(nc)
    for c in range(nc):
        cost0[c] = abs(off[c]) + 1e-6 * (1.0 if off[c] < 0 else 0.0)
    for e in range(ne):
        for a in range(na):
            rad = radius[e, a]
            po0, po1 = p_o[e, a, 0], p_o[e, a, 1]
            for c in range(nc):
                # (a candidate out of reach is excluded whatever else it is, and its
                # largest least DCPA is -inf: nothing else about it is needed)
                bad[c] = barred[c] = False
                if far[e, a, c]:
                    continue
                vc0, vc1 = v_cn[e, a, c], v_ce[e, a, c]
                for j in range(nj):
                    r0 = p_t[e, j, 0] - po0
                    r1 = p_t[e, j, 1] - po1
                    # r x (v_c - v_t)
                    cross = r0 * (vc1 - v_t[e, j, 1]) - r1 * (vc0 - v_t[e, j, 0])
                    s = side[e, a, j]
                    if (s == 2 and off[c] < 0) or ((s == 1 or s == -1) and cross * s < 0):
                        barred[c] = True
                    # (counted and give_way are False where the pair is not live)
                    if bad[c] or not live[e, a, j]:
                        continue
                    if cross < 0 and give_way[e, a, j]:
                        bad[c] = True
                    elif counted[e, a, j]:  # in the obstacle (the DCPA only if it decides)
                        tcpa, w0, w1 = _tcpa(r0, r1, v_t[e, j, 0] - vc0, v_t[e, j, 1] - vc1)
                        if tcpa > 0 and (rr[e, a, j] < rad or (
                                tcpa < horizon
                                and math.hypot(r0 + w0 * tcpa, r1 + w1 * tcpa) < rad)):
                            bad[c] = True
            every = True
            for c in range(nc):
                if not (barred[c] or far[e, a, c]):
                    every = False
                    break
            best, k = math.inf, 0
            for c in range(nc):
                if every:
                    barred[c] = False
                if not (bad[c] or far[e, a, c] or barred[c]) and cost0[c] < best:
                    best, k = cost0[c], c
            if best == math.inf:  # stuck: the largest least DCPA (np.argmax: a NaN wins)
                top, k = -math.inf, 0
                for c in range(nc):
                    v = -math.inf
                    if not (far[e, a, c] or barred[c]):
                        v = _least_dcpa(e, a, c, v_cn, v_ce, po0, po1, p_t, v_t, counted)
                    if math.isnan(v):
                        k = c
                        break
                    if v > top:
                        top, k = v, c
            pick[e, a] = k
    return pick
