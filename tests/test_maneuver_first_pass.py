"""The turning circle's fused first compiled pass is its three passes, bit for bit.

:func:`seahelm.analysis.maneuvers.turning_circle._first_pass` runs the crossings, their brackets
and the steady ends of the turns in one compiled call (issue 46: each call from Python costs its
dispatch); it must give what the three separate calls give, NaN runs and unreached levels too.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")
tk = importlib.import_module("seahelm.analysis.maneuvers.turning_kernels")


@pytest.mark.parametrize("runs, steps", [(1, 60), (5, 40), (3, 3)])
def test_the_first_pass_equals_the_three_passes(runs, steps):
    rng = np.random.default_rng(runs * 100 + steps)
    t = np.cumsum(rng.uniform(0.2, 1.0, steps))
    times = np.ascontiguousarray(np.broadcast_to(t, (runs, steps)))
    change = np.cumsum(rng.uniform(0.0, 0.2, (runs, steps)), axis=1)
    change[0, :2] = 0.0
    if runs > 1:
        change[1] = np.nan  # (a run not run)
    r = rng.normal(0.01, 0.003, (runs, steps))
    speed = rng.uniform(0.5, 1.2, (runs, steps))
    levels = tc._LEVELS
    k0, w0 = tc._crossings(change, levels)
    j0a, wa = tc._cubic_crossings(times, change, levels, k0, w0)
    radius0, steady0 = np.empty(runs), np.empty(runs, dtype=np.bool_)
    tk._steady_ends(change, r, speed, radius0, steady0)

    k = np.empty((levels.size, runs), dtype=np.int64)
    w = np.empty(k.shape)
    j0, s_nodes, c_nodes, good, s = tc._bracket_arrays(k.shape)
    radius, steady = np.empty(runs), np.empty(runs, dtype=np.bool_)
    tc._first_pass(change, levels, times, r, speed, k, w, j0, s_nodes, c_nodes, good, s,
                   radius, steady)
    j0b, wb = tc._cubic_weights(levels, j0, s_nodes, c_nodes, good, s)
    assert np.array_equal(k, k0) and np.array_equal(w, w0, equal_nan=True)
    assert np.array_equal(j0b, j0a) and np.array_equal(wb, wa, equal_nan=True)
    assert np.array_equal(radius, radius0, equal_nan=True) and np.array_equal(steady, steady0)
