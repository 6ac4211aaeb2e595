"""The compiled candidate search of the velocity obstacles (``encounters._vo_search``) against
the numpy expressions it replaced, bit for bit, on random pairs: every branch (a candidate
inside an obstacle, on the wrong side, barred by the side rule, out of reach; every candidate
excluded: the largest least DCPA; NaN reports and velocities)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.encounters._vo_search import vo_pick
from seahelm.encounters.geometry import cpa_tcpa, velocity


def _numpy_pick(v_c, p_o, p_t, v_t, radius, horizon, counted, give_way, side, far, off):
    """The search as numpy over (e, a, c, j): the expressions of ``VelocityObstacles._choose``
    before it was compiled (seahelm 0.x, issue 51)."""
    v_c = v_c[:, :, :, None, :]  # (e, a, c, 1, 2)
    p_o, p_t, v_t = p_o[:, :, None, None], p_t[:, None, None], v_t[:, None, None]
    rad = radius[:, :, None, None]
    with np.errstate(invalid="ignore"):
        dcpa, tcpa = cpa_tcpa(p_o, v_c, p_t, v_t)  # (e, a, c, j)
        r = p_t - p_o
        in_vo = ((tcpa > 0) & (tcpa < horizon) & (dcpa < rad)) | (
            (np.hypot(r[..., 0], r[..., 1]) < rad) & (tcpa > 0))
        w = v_c - v_t
        wrong_side = (r[..., 0] * w[..., 1] - r[..., 1] * w[..., 0]) < 0
        cross = r[..., 0] * w[..., 1] - r[..., 1] * w[..., 0]
    cnt = counted[:, :, None, :]
    bad = ((in_vo & cnt) | (wrong_side & give_way[:, :, None, :])).any(-1)
    s_c = side[:, :, None, :]
    barred = (((s_c == 2) & (off < 0)[None, None, :, None])
              | ((np.abs(s_c) == 1) & (cross * s_c < 0))).any(-1)
    barred &= ~(barred | far).all(-1, keepdims=True)
    cost = np.abs(off) + 1e-6 * (off < 0)
    cost = np.where(bad | far | barred, np.inf, cost[None, None, :])
    pick = np.argmin(cost, axis=-1)
    stuck = ~np.isfinite(cost.min(-1))
    clear = np.where(far | barred, -np.inf, np.where(cnt, dcpa, np.inf).min(-1))
    return np.where(stuck, np.argmax(clear, axis=-1), pick), stuck


def _case(seed: int, ne: int, na: int, nj: int, twice: bool = False):
    rng = np.random.default_rng(seed)
    off = np.radians(np.arange(-60.0, 91.0, 5.0))
    if twice:  # (candidates given twice: ties go to the first)
        off = np.concatenate([off, off])
    nc = off.size
    p_o = rng.uniform(-3000, 3000, (ne, na, 2))
    p_t = rng.uniform(-3000, 3000, (ne, nj, 2))
    p_t[: ne // 10, 0] = p_o[: ne // 10, 0] + rng.uniform(-500, 500, (ne // 10, 2))  # inside
    v_t = velocity(rng.uniform(-math.pi, math.pi, (ne, nj)), rng.uniform(0, 8, (ne, nj)))
    v_t[ne // 10: ne // 5, 0] = 0.0  # a target at rest
    heading = rng.uniform(-math.pi, math.pi, (ne, na, 1)) + off
    v_c = velocity(heading, rng.uniform(0, 8, (ne, na, 1)))
    v_c[-3:, :, :5] = np.nan  # (a diverged run)
    p_t[-6:-3, 0] = np.nan    # (not heard from)
    radius = np.where(rng.random((ne, na)) < 0.5, 1852.0, 1852.0 * 1.2)
    live = rng.random((ne, na, nj)) < 0.9
    live[-6:-3, :, 0] = False
    counted = live & (rng.random((ne, na, nj)) < 0.8)
    give_way = live & (rng.random((ne, na, nj)) < 0.5)
    side = np.where(live, rng.choice(np.array([0, 0, 1, -1, 2], dtype=np.int8),
                                     (ne, na, nj)), 0).astype(np.int8)
    far = rng.random((ne, na, nc)) < 0.4
    far[: ne // 8] = True  # none reachable: all are
    far &= ~far.all(-1, keepdims=True)
    far[ne // 8: ne // 4] = True  # (out of reach everywhere: stuck)
    # stuck, every candidate inside the obstacle of vessel 1 (100 m off, closing at 10 m/s),
    # and vessel 0's closest points NaN: np.min and np.argmax let a NaN win
    k = slice(ne // 4, ne // 4 + 6)
    p_t[k, 1] = p_o[k, 0] + [100.0, 0.0]
    v_t[k, 1] = [-10.0, 0.0]
    p_t[k, 0] = np.nan
    live[k, 0, :2] = counted[k, 0, :2] = True
    side[k] = 0
    far[k] = False
    far[ne // 4: ne // 4 + 3, 0, :3] = True  # (a NaN after -inf)
    return v_c, p_o, p_t, v_t, radius, counted, give_way, side, far, off, live


@pytest.mark.parametrize("seed, na, nj, twice", [(0, 1, 2, False), (1, 2, 3, False),
                                                 (2, 1, 4, False), (3, 1, 2, True)])
def test_compiled_search_equals_the_numpy_expressions(seed, na, nj, twice):
    v_c, p_o, p_t, v_t, radius, counted, give_way, side, far, off, live = _case(
        seed, 400, na, nj, twice)
    want, stuck = _numpy_pick(v_c, p_o, p_t, v_t, radius, 1200.0, counted, give_way, side,
                              far, off)
    r = p_t[:, None] - p_o[:, :, None]
    with np.errstate(invalid="ignore"):
        rr = np.hypot(r[..., 0], r[..., 1])
    got = vo_pick(v_c[..., 0].copy(), v_c[..., 1].copy(), p_o, p_t, v_t, rr, radius, 1200.0,
                  live, counted, give_way, side, far, off)
    assert got.dtype == np.int64 and got.shape == want.shape
    np.testing.assert_array_equal(got, want)
    # the branches were exercised: a free pick, a route pick, stuck rows, a non-zero pick
    assert stuck.any() and (~stuck).any()
    i0 = int(np.flatnonzero(off == 0)[0])
    assert (want == i0).any() and (want != i0).any()
