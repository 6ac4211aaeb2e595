"""The turning circle's metrics formed on the events' samples only equal the whole-record forms.

``_event_values`` forms the distances along and across the original course at the four
samples around each event only, and ``distance_until`` evaluates and sums the track's speed
only over the intervals some run asks for; both must give the numbers of the forms over the
whole record bit for bit (issue 46 item 6: the metrics cost more than the simulation, and
nothing users rely on changes its numbers). The references here are those whole-record forms,
written out.
"""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest

from seahelm.analysis.maneuvers import track_distance
from seahelm.analysis.maneuvers.track import distance_until

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")


def _turns(seed: int, runs: int, steps: int, rate: float):
    """Turning tracks: heading changes growing at random rates, positions along them."""
    rng = np.random.default_rng(seed)
    t = np.arange(steps) * 0.5
    r = rng.uniform(0.5, 1.5, (runs, 1)) * rate
    psi = rng.uniform(-3.0, 3.0, (runs, 1)) + np.cumsum(np.broadcast_to(r, (runs, steps)),
                                                         axis=1) * 0.5
    north = 10.0 * rng.normal(size=(runs, 1)) + np.cumsum(np.cos(psi), axis=1) * 0.5
    east = np.cumsum(np.sin(psi), axis=1) * 0.5
    return t, north, east, psi


def _whole_record(north, east, psi, times, dist, k, w, j0, weights):
    """The events' values as the metrics formed them over the whole record: the distances at
    every sample, the four signals stacked, gathered at the nodes and weighted."""
    dn, de = north - north[:, :1], east - east[:, :1]
    c0, s0 = np.cos(psi[:, :1]), np.sin(psi[:, :1])
    values = np.stack([dn * c0 + de * s0, np.abs(-dn * s0 + de * c0), times, dist])
    if values.shape[2] < 4:  # (no cubic through four samples)
        return tc._at_crossings(values, k, w)
    idx = j0[..., None] + np.arange(4)
    rows = np.arange(values.shape[1])[None, :, None]
    out = np.einsum("slrj,lrj->slr", values[:, rows, idx], np.nan_to_num(weights))
    cubic = (k >= 0) & np.isfinite(weights[..., 0])
    return np.where(cubic, out, tc._at_crossings(values, k, w))


@pytest.mark.parametrize("seed, runs, steps, rate", [
    (0, 1, 181, 0.05),    # one run, every event reached
    (1, 40, 120, 0.05),   # a batch
    (2, 7, 60, 0.02),     # slow turns: 180 deg (and some 90 deg) not reached, linear fallback
    (3, 5, 4, 0.5),       # four samples
    (4, 3, 3, 0.9),       # fewer than four: linear only
])
def test_event_values_equal_the_whole_record_forms_bit_for_bit(seed, runs, steps, rate):
    t, north, east, psi = _turns(seed, runs, steps, rate)
    change = np.abs(psi - psi[:, :1])
    times = np.broadcast_to(t, psi.shape)
    k, w = tc._crossings(change, tc._LEVELS)
    j0, weights = tc._cubic_crossings(np.ascontiguousarray(times), change, tc._LEVELS, k, w)
    dist = track_distance(north, east, t)
    got = tc._event_values(north, east, psi, times, dist, k, w, j0, weights)
    want = _whole_record(north, east, psi, times, dist, k, w, j0, weights)
    np.testing.assert_array_equal(got, want)
    if seed == 2:  # (the case meant to take the fallback does)
        assert (k < 0).any()


@pytest.mark.parametrize("seed, runs, steps", [(5, 1, 181), (6, 30, 90), (7, 4, 12)])
def test_distance_until_sums_only_the_wanted_intervals_bit_for_bit(seed, runs, steps):
    """Up to each run's wanted sample the distances are the whole track's, bit for bit, and
    beyond it they stay at that value (pieces of 0), as when every interval was summed."""
    t, north, east, _ = _turns(seed, runs, steps, 0.05)
    until = np.random.default_rng(seed).integers(0, steps // 2, runs)  # (all early)
    got = distance_until(north, east, t, until=until)
    whole = track_distance(north, east, t)
    assert got.shape == whole.shape
    for r, u in enumerate(until.tolist()):
        np.testing.assert_array_equal(got[r, :u + 1], whole[r, :u + 1])
        np.testing.assert_array_equal(got[r, u:], np.full(steps - u, got[r, u]))


def test_distance_until_nothing_wanted_is_zero():
    t, north, east, _ = _turns(8, 3, 20, 0.05)
    got = distance_until(north, east, t, until=np.zeros(3, dtype=np.int64))
    np.testing.assert_array_equal(got, np.zeros((3, 20)))


def test_messages_of_a_batch_with_runs_that_do_not_finish():
    """The message loop runs over the incomplete runs only: a complete run says ok (or that
    the turn was not yet steady), an incomplete one what was not reached."""
    from seahelm.analysis.maneuvers import turning_circle

    m = turning_circle("kvlcc2-l7", np.radians([5.0, 35.0]), sides=1, t_final=60.0,
                       dt=0.2).metrics
    msg, complete = m["message"].values, m["complete"].values
    assert complete.tolist() == [False, True]
    assert msg[0].startswith("90 deg heading change, 180 deg heading change not reached "
                             "within t_final = 60 s (final heading change ")
    assert msg[1] in ("ok", tc._NOT_STEADY)
    assert math.isnan(float(m["tactical_diameter"][0]))
    assert math.isfinite(float(m["tactical_diameter"][1]))
