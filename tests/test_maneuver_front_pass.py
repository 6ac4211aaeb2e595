"""The turning circle's fused front pass is the passes it replaces, bit for bit.

:func:`seahelm.analysis.maneuvers.turning_kernels._front` forms the heading change, runs the
first pass (crossings, brackets, steady ends) and the track spline's speeds up to the 10°
event in one compiled call (issue 46 item 6: each call from Python and each array check cost
a part of one circle's metrics); with :func:`~seahelm.analysis.maneuvers.track._arc_distances`
it must give what ``np.abs(psi - psi[:, :1])``, ``_first_pass``, ``good.all()`` and
``distance_until`` give, on strided views of a record as the engine's result hands them out,
NaN runs, unreached levels and short records included (where the fast path's check fails it
says so, and the general form is taken).
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")
track = importlib.import_module("seahelm.analysis.maneuvers.track")


def _record(seed: int, runs: int, steps: int):
    """(t, state) of turning runs: state (runs, steps, 5) = north, east, heading, r, U."""
    rng = np.random.default_rng(seed)
    t = np.arange(steps) * 0.5
    rate = rng.uniform(0.02, 0.2, (runs, 1))
    psi = rng.uniform(-3.0, 3.0, (runs, 1)) + np.cumsum(np.broadcast_to(rate, (runs, steps)),
                                                         axis=1) * 0.5
    state = np.empty((runs, steps, 5))
    state[..., 0] = 10.0 * rng.normal(size=(runs, 1)) + np.cumsum(np.cos(psi), axis=1) * 0.5
    state[..., 1] = np.cumsum(np.sin(psi), axis=1) * 0.5
    state[..., 2] = psi
    state[..., 3] = rate + rng.normal(0.0, 1e-4, (runs, steps))
    state[..., 4] = rng.uniform(0.5, 1.2, (runs, steps))
    return t, state


def _separate(t, north, east, psi, r, speed, times):
    """The passes before the fusion, as the metrics called them."""
    levels = tc._LEVELS
    change = np.abs(psi - psi[:, :1])
    k = np.empty((levels.size, psi.shape[0]), dtype=np.int64)
    w = np.empty(k.shape)
    j0, s_nodes, c_nodes, good, s = tc._bracket_arrays(k.shape)
    radius, steady = np.empty(psi.shape[0]), np.empty(psi.shape[0], dtype=np.bool_)
    tc._first_pass(np.ascontiguousarray(change, dtype=float), levels, times, r, speed, k, w,
                   j0, s_nodes, c_nodes, good, s, radius, steady)
    dist = track.distance_until(north, east, t, until=j0[2] + 3)
    return (change, k, w, j0, s_nodes, c_nodes, good, s, radius, steady), bool(good.all()), dist


def _fused(t, north, east, psi, r, speed, times):
    levels = tc._LEVELS
    runs, samples = psi.shape
    k = np.empty((levels.size, runs), dtype=np.int64)
    w = np.empty(k.shape)
    j0, s_nodes, c_nodes, good, s = tc._bracket_arrays(k.shape)
    radius, steady = np.empty(runs), np.empty(runs, dtype=np.bool_)
    change, h, rates = np.empty((runs, samples)), np.empty(samples - 1), np.empty(
        (samples - 1, 3, runs))
    width, every = tc._front(psi, levels, t, times, r, speed, north, east, tc._GAUSS_NODES, 2,
                             change, k, w, j0, s_nodes, c_nodes, good, s, radius, steady, h,
                             rates)
    dist = track._arc_distances(h, rates, width, samples) if width >= 0 else None
    return (change, k, w, j0, s_nodes, c_nodes, good, s, radius, steady), every, dist, width


@pytest.mark.parametrize("seed, runs, steps, variant", [
    (0, 1, 181, ""), (1, 7, 120, ""), (2, 5, 60, "nan run"), (3, 3, 30, "short turn"),
    (4, 2, 6, ""), (5, 4, 80, "uneven times")])
def test_the_front_pass_equals_the_passes_apart(seed, runs, steps, variant):
    t, state = _record(seed, runs, steps)
    if variant == "nan run":
        state[1, 20:] = np.nan  # (a diverged run: the fast path's check fails)
    if variant == "short turn":
        state[:, :, 2] *= 0.05  # (90 and 180 deg never reached: no cubic there)
    if variant == "uneven times":
        t = np.cumsum(np.random.default_rng(seed).uniform(0.2, 0.8, steps))
    north, east, psi, r, speed = (state[..., j] for j in range(5))  # (strided views)
    times = np.ascontiguousarray(np.broadcast_to(t, psi.shape))
    want, want_every, want_dist = _separate(t, north, east, psi, r, speed, times)
    got, every, dist, width = _fused(t, north, east, psi, r, speed, times)
    for a, b in zip(got, want):
        assert a.dtype == b.dtype and np.array_equal(a, b, equal_nan=True)
    assert every is want_every
    if variant == "nan run":
        assert width == -1 and dist is None  # (the general form is taken)
        return
    assert width == min(steps - 1, int((want[3][2] + 3).max()))
    assert np.array_equal(dist, want_dist) and dist.shape == want_dist.shape


def test_the_front_pass_leaves_bad_times_and_short_records_to_the_general_form():
    t, state = _record(9, 2, 3)  # (three samples: no spline)
    north, east, psi, r, speed = (state[..., j] for j in range(5))
    times = np.ascontiguousarray(np.broadcast_to(t, psi.shape))
    assert _fused(t, north, east, psi, r, speed, times)[3] == -1
    t, state = _record(9, 2, 20)
    t[5] = t[4]  # (not strictly increasing)
    north, east, psi, r, speed = (state[..., j] for j in range(5))
    times = np.ascontiguousarray(np.broadcast_to(t, psi.shape))
    assert _fused(t, north, east, psi, r, speed, times)[3] == -1


def test_completion_equals_the_array_form():
    """``_completion`` is ``~isnan`` of every event's time and the message "ok" (status 0),
    for each status code and NaN at each event; it counts the runs not complete."""
    from seahelm.results import STATUS_TEXT

    kernels = importlib.import_module("seahelm.analysis.maneuvers.turning_kernels")
    rng = np.random.default_rng(3)
    runs = 64
    time_at = rng.uniform(1.0, 90.0, (3, runs))
    time_at[rng.random((3, runs)) < 0.2] = np.nan
    status = rng.choice([0, 0, 0, 1, 2, 3], runs).astype(np.int64)
    messages = [STATUS_TEXT[int(code)] for code in status]
    want = (~np.isnan(time_at[2]) & ~np.isnan(time_at[0]) & ~np.isnan(time_at[1])
            & np.array([m == "ok" for m in messages], dtype=bool))
    complete = np.empty(runs, dtype=bool)
    missing = kernels._completion(time_at, status, complete)
    assert np.array_equal(complete, want) and missing == int((~want).sum())
    assert 0 < missing < runs
