"""The Monte-Carlo samples of a manoeuvre scenario built in one batch: the same ships as
sample by sample, without a validated construction per sample."""

from __future__ import annotations

import numpy as np
import pytest

import seahelm.scenario.runs as scenario_runs
from seahelm.errors import ParameterError
from seahelm.scenario import ManeuverJob, parse_scenario
from seahelm.scenario.errors import ScenarioError
from seahelm.ships import Ship, get_ship

MEANS = get_ship("kvlcc2-l7").params


def _scenario(runs: int, draws: dict[str, tuple[float, float]], seed: int = 4) -> str:
    lines = "\n".join(f'"{k}" = {{ distribution = "normal", mean = {m!r}, std = {s!r} }}'
                      for k, (m, s) in draws.items())
    return ('[vessel]\ncatalog = "kvlcc2-l7"\n[maneuver]\nkind = "turning"\nrudder_deg = 35\n'
            'sides = "starboard"\nt_final = 40\ndt = 0.5\n'
            f"[batch.monte_carlo]\nruns = {runs}\nseed = {seed}\n"
            f"[batch.monte_carlo.draws]\n{lines}\n")


DRAWS = {"vessel.params.Y_v": (MEANS.Y_v, 0.03), "vessel.params.N_r": (MEANS.N_r, 0.005)}
WITH_GEAR = {**DRAWS, "actuator.params.max_rate": (0.04, 0.002)}


def _one_by_one(job: ManeuverJob, monkeypatch, start: int = 0, stop: int | None = None):
    with monkeypatch.context() as m:
        m.setattr(ManeuverJob, "_sample_ships", lambda self, *args: None)
        return job.ships(start, stop)


@pytest.mark.parametrize("draws", [DRAWS, WITH_GEAR], ids=["params", "params+gear"])
def test_batched_samples_equal_the_ships_built_one_by_one(draws, monkeypatch):
    job = parse_scenario(_scenario(60, draws))
    for start, stop in ((0, 60), (17, 41)):
        fast = job.ships(start, stop)
        slow = _one_by_one(job, monkeypatch, start, stop)
        assert len(fast) == len(slow) == stop - start
        for a, b in zip(fast, slow):
            assert a == b and a.name == b.name and a.test_speed == b.test_speed
            assert a.params.to_array().tobytes() == b.params.to_array().tobytes()
            assert a.servo == b.servo and a.steering_gear == b.steering_gear
    assert len({s.servo.max_rate for s in fast}) == (stop - start if "actuator.params.max_rate"
                                                      in draws else 1)


def test_samples_are_not_validated_one_by_one(monkeypatch):
    job = parse_scenario(_scenario(200, WITH_GEAR))
    built = []
    original = Ship.__post_init__
    monkeypatch.setattr(Ship, "__post_init__", lambda self: (built.append(1), original(self)))
    ships = job.ships()
    assert len(ships) == 200 and len(built) <= 2  # (the first sample's, checked in full)


def test_draws_are_made_once_per_sweep(monkeypatch):
    job = parse_scenario(_scenario(50, DRAWS))
    calls = []
    original = scenario_runs.monte_carlo_draws
    monkeypatch.setattr(scenario_runs, "monte_carlo_draws",
                        lambda *a, **k: (calls.append(len(a[1])), original(*a, **k))[1])
    every = job.draws(np.arange(50))
    part = job.draws(np.arange(10, 30))
    assert calls == [50]
    fresh = original(job.monte_carlo, np.arange(10, 30), "<string>")
    for key in every:
        np.testing.assert_array_equal(part[key], fresh[key])
        part[key][:] = 0.0  # (a caller's changes do not reach the memo)
    np.testing.assert_array_equal(job.draws(np.arange(10, 30))["vessel.params.Y_v"],
                                  fresh["vessel.params.Y_v"])


def test_replace_many_equals_from_mapping():
    rng = np.random.default_rng(2)
    columns = {"Y_v": MEANS.Y_v * (1 + 0.1 * rng.standard_normal(30)),
               "x_G": rng.uniform(-0.3, 0.3, 30)}
    got = MEANS.replace_many(columns)
    assert got is not None
    for i, p in enumerate(got):
        want = type(MEANS).from_mapping({k: float(v[i]) for k, v in columns.items()},
                                        base=MEANS)
        assert p == want and hash(p) == hash(want)
        assert p.to_array().tobytes() == want.to_array().tobytes()


@pytest.mark.parametrize("columns", [
    {"Y_v": np.array([-0.3, np.nan])},       # not finite
    {"length": np.array([7.0, -1.0])},       # out of its range
    {"rudder_angle_deg": np.array([1.0])},   # not a field
    {"Y_v": np.array([1, 2])}])              # not floats
def test_replace_many_leaves_what_it_cannot_check_to_from_mapping(columns):
    assert MEANS.replace_many(columns) is None


def test_replace_many_runs_the_cross_field_check():
    with pytest.raises(ParameterError, match=r"`x_G` must lie within"):
        MEANS.replace_many({"x_G": np.array([0.1, 0.6 * MEANS.length])})


def test_a_bad_sample_is_named_as_before():
    text = _scenario(30, {"vessel.params.length": (7.0, 40.0)}, seed=1)
    with pytest.raises(ScenarioError, match=r"\[batch.monte_carlo\] sample \d+: .*length"):
        parse_scenario(text).ships()


def test_a_turning_circle_of_the_samples_is_unchanged(monkeypatch):
    job = parse_scenario(_scenario(12, WITH_GEAR))
    fast = job.run_ships(job.ships()).metrics
    slow = job.run_ships(_one_by_one(job, monkeypatch)).metrics
    assert fast.identical(slow)
