"""Noisy AIS views in chunked encounter runs (issue 51): each report's noise is a function of
(seed, encounter index, vessel, interval, field), so a study run in chunks of any size, in
this process or on Dask workers, equals the whole batch bit for bit with noise on."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from seahelm.encounters import AIS, Encounter
from seahelm.encounters.chunked import run_chunked, split_encounter
from seahelm.encounters.monte_carlo import monte_carlo_vessels
from seahelm.encounters.sensing import report_noise, seed_key
from seahelm.errors import ParameterError

NOISE = AIS(position_noise=30.0, course_noise=0.02, speed_noise=0.1, heading_noise=0.02,
            update_interval=2.0, seed=51)


def _encounter(sensor=NOISE, **kw):
    vessels, _ = monte_carlo_vessels(5, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                     seed=3, detection_range=(3000.0, 3500.0),
                                     tcpa=(100.0, 300.0), overtaking=0.3,
                                     overtaking_range=(1200.0, 1600.0))
    return Encounter(vessels, t_final=300.0, avoidance="velocity-obstacles", record_every=5,
                     sensor=sensor, **kw)


def _same(a, b):
    for group in ("tracks", "pair", "verdicts"):
        for name, arr in getattr(a, group).items():
            assert np.array_equal(arr, getattr(b, group)[name], equal_nan=True), name
    for name in ("status", "min_range", "min_domain_distance", "collision", "near_miss"):
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name


@pytest.fixture(scope="module")
def whole():
    return _encounter().run()


def test_report_noise_is_standard_normal_and_a_function_of_its_counters():
    key = seed_key(7)
    z = report_noise(key, np.arange(200_000), np.zeros(200_000, dtype=int), 3)
    assert z.shape == (200_000, 5)
    assert abs(z.mean()) < 0.005 and abs(z.std() - 1.0) < 0.005
    assert abs((np.abs(z) > 1.959963984540054).mean() - 0.05) < 0.002
    assert abs(np.corrcoef(z[:, 0], z[:, 1])[0, 1]) < 0.01
    # the same counters give the same deviates, in any order or batch
    part = report_noise(key, np.array([123, 5]), np.array([0, 0]), 3)
    assert np.array_equal(part, z[[123, 5]])
    # and any other counter, other deviates
    for other in (report_noise(seed_key(8), np.arange(10), np.zeros(10, dtype=int), 3),
                  report_noise(key, np.arange(10), np.ones(10, dtype=int), 3),
                  report_noise(key, np.arange(10), np.zeros(10, dtype=int), 4)):
        assert not np.isin(other, z[:10]).any()


def test_the_noise_acts(whole):
    exact = _encounter(sensor=dataclasses.replace(NOISE, position_noise=0.0, course_noise=0.0,
                                                  speed_noise=0.0, heading_noise=0.0)).run()
    assert not np.array_equal(whole.tracks["desired_heading"], exact.tracks["desired_heading"])


@pytest.mark.parametrize("chunk_size", [1, 2, 3])
def test_noisy_chunks_in_process_equal_the_whole_batch(whole, chunk_size):
    _same(run_chunked(_encounter(), chunk_size=chunk_size), whole)


def test_an_encounter_alone_sees_the_noise_it_sees_in_the_batch(whole):
    """Encounter 3 run by itself with first_encounter=3."""
    enc = _encounter()
    (vessels, settings), = [c for c in split_encounter(enc, 1)][3:4]
    alone = Encounter(vessels, **settings).run()
    assert settings["first_encounter"] == 3
    np.testing.assert_array_equal(alone.tracks["desired_heading"][0],
                                  whole.tracks["desired_heading"][3])


def test_noisy_chunks_on_dask_workers_equal_the_whole_batch(whole):
    pytest.importorskip("distributed")
    _same(run_chunked(_encounter(), chunk_size=2, workers=2), whole)


def test_a_sensor_without_a_seed_gets_one_seed_for_all_its_chunks():
    enc = _encounter(sensor=dataclasses.replace(NOISE, seed=None))
    seeds = {c[1]["sensor"].seed for c in split_encounter(enc, 2)}
    assert len(seeds) == 1 and None not in seeds


@pytest.mark.parametrize("bad", [-1, 1.5, "3"])
def test_bad_first_encounter_is_named(bad):
    with pytest.raises(ParameterError, match="first_encounter"):
        _encounter(first_encounter=bad)
