"""The collision-avoidance environment with the target seen through AIS (issue 52):
``EncounterVectorEnv(sensor=AIS(...))`` -- reports every update_interval, received delay later,
with seeded noise (seahelm.encounters.sensing). The view equals the encounters' own AISView of
the true tracks; a rule-based target that avoids on that view is Encounter.run with that
sensor, bit for bit, batched and alone; a restarted episode starts a fresh view; the rewards
stay the truth's; bad input names its argument."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from seahelm.encounters import AIS, Encounter, Vessel  # noqa: E402
from seahelm.encounters.sensing import REPORT_FIELDS, report_noise  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import EncounterEnv, EncounterVectorEnv  # noqa: E402

SHIP = "kvlcc2-l7"
SENSOR = AIS(update_interval=3.0, delay=2.0, position_noise=0.5, course_noise=0.02,
             speed_noise=0.01, heading_noise=0.02, seed=7)
N, SECONDS = 4, 30.0


def _run(sensor, n=N, seed=5, avoidance="rule-based"):
    envs = EncounterVectorEnv(n, ship=SHIP, episode_seconds=SECONDS, sensor=sensor,
                              target_avoidance=avoidance, autoreset_mode="Disabled")
    obs0, _ = envs.reset(seed=seed)
    g = {k: v.copy() for k, v in envs.start_geometry.items()}
    states, views, obs, rewards = [envs.vessel_states], [envs.target_view], [obs0], []
    for _ in range(int(SECONDS)):
        o, r, *_ = envs.step(np.zeros((n, 1)))
        states.append(envs.vessel_states)
        views.append(envs.target_view)
        obs.append(o)
        rewards.append(r)
    envs.close()
    return g, np.stack(states, -1), np.stack(views), np.stack(obs), np.stack(rewards)


@pytest.fixture(scope="module")
def run():
    return _run(SENSOR)


def test_the_view_is_the_encounters_ais_view_of_the_true_tracks(run):
    g, states, views, obs, _ = run
    truth = states[:, :, :5]  # (encounters, vessels, fields, time)
    view = SENSOR.start(N * 2, 1.0, SECONDS, n_vessels=2)
    for k in range(int(SECONDS) + 1):
        expected = view.update(k, truth[..., k].reshape(N * 2, 5)).reshape(N, 2, 5)[:, 1]
        np.testing.assert_array_equal(views[k], expected, err_msg=f"interval {k}")
    # nothing before the first report arrived (the delay), then reports 3 s apart, noisy
    assert np.isnan(views[:2]).all() and np.isfinite(views[2:]).all()
    assert (views[3] == views[2]).all() and (views[5] != views[4]).all()
    sent = (np.arange(2, int(SECONDS) + 1) - 2) // 3 * 3  # (the report each view holds)
    error = views[2:] - np.moveaxis(truth[:, 1], -1, 0)[sent]
    assert 0.1 < np.abs(error[..., 0]).max() < 5 * SENSOR.position_noise
    # the agent's target observations: 0 before the first report, then from the view
    tgt = slice(6, 12)
    assert (obs[:2, :, tgt] == 0).all() and (obs[2:, :, 7] > 0).all()


def test_a_target_avoiding_on_the_view_is_encounter_run_with_that_sensor(run):
    g, states, *_ = run
    own = Vessel(ship=SHIP, north=0.0, east=0.0, course=0.0)
    target = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"],
                    avoid=True)
    result = Encounter([own, target], t_final=SECONDS, avoidance="rule-based", sensor=SENSOR,
                       record_every=1).run()
    for j, name in enumerate(("north", "east", "course", "speed", "heading", "yaw_rate")):
        np.testing.assert_array_equal(states[:, :, j], result.tracks[name], err_msg=name)
    exact = Encounter([own, target], t_final=SECONDS, avoidance="rule-based",
                      record_every=1).run()
    assert not np.array_equal(exact.tracks["heading"], result.tracks["heading"])  # it matters
    # batched = alone: encounter e of the batch is the encounter run alone as number e
    for e in (0, N - 1):
        alone = Encounter([own, dataclasses.replace(target, north=g["north"][e],
                                                    east=g["east"][e], course=g["course"][e])],
                          t_final=SECONDS, avoidance="rule-based", sensor=SENSOR,
                          record_every=1, first_encounter=e).run()
        np.testing.assert_array_equal(states[e, :, 4], alone.tracks["heading"][0])


def test_the_rewards_are_the_true_geometry_s():
    # the target on course (no avoidance): the same tracks with or without the sensor, so the
    # same rewards (the observations differ: the target as reported)
    _, states, _, obs, rewards = _run(SENSOR, avoidance=None)
    _, states_exact, _, obs_exact, rewards_exact = _run(None, avoidance=None)
    np.testing.assert_array_equal(states, states_exact)
    np.testing.assert_array_equal(rewards, rewards_exact)
    assert not np.array_equal(obs[:, :, 6:], obs_exact[:, :, 6:])
    np.testing.assert_array_equal(obs[:, :, :6], obs_exact[:, :, :6])


def test_a_restarted_episode_starts_a_fresh_view_with_fresh_noise():
    envs = EncounterVectorEnv(2, ship=SHIP, episode_seconds=6.0, sensor=SENSOR)
    envs.reset(seed=1)
    for _ in range(6):
        envs.step(np.zeros((2, 1)))
    assert np.isfinite(envs.target_view).all()
    envs.step(np.zeros((2, 1)))  # (both truncated at 6 s: the autoreset step)
    assert (envs.elapsed == 0).all() and np.isnan(envs.target_view).all()
    start = envs.vessel_states[:, 1, :5]  # (the new episodes' first reports: sent now)
    for _ in range(2):
        envs.step(np.zeros((2, 1)))
    # they arrive 2 s later, with the noise of episode numbers 2 and 3 (i + N j)
    ais = envs._ais
    expected = start + report_noise(ais.key, np.array([2, 3]), np.array([1, 1]),
                                    np.array([0, 0])) * ais.sd
    expected[:, 3] = np.abs(expected[:, 3])
    np.testing.assert_array_equal(envs.target_view, expected)
    envs.close()


def test_the_noise_of_a_report_is_the_same_per_run_or_per_interval():
    # (EpisodeAIS draws a batch whose runs are at different intervals in one call)
    key = 12345
    enc, ves, k = np.array([0, 1, 2, 3]), np.array([1, 0, 1, 1]), np.array([0, 5, 5, 9])
    together = report_noise(key, enc, ves, k)
    for r in range(4):
        np.testing.assert_array_equal(together[r], report_noise(key, enc[r:r + 1],
                                                                ves[r:r + 1], int(k[r]))[0])
    assert together.shape == (4, len(REPORT_FIELDS))


def test_seeded_and_single_env():
    a = _run(SENSOR, n=2, seed=3)[2]
    b = _run(SENSOR, n=2, seed=3)[2]
    c = _run(dataclasses.replace(SENSOR, seed=8), n=2, seed=3)[2]
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a[2:], c[2:])
    env = EncounterEnv(ship=SHIP, episode_seconds=10.0, sensor=SENSOR)
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    for _ in range(3):
        obs, *_ = env.step(np.zeros(1))
    assert env.observation_space.contains(obs) and obs[7] > 0
    env.close()


def test_bad_sensors_are_refused_by_name():
    with pytest.raises(ParameterError) as info:
        EncounterVectorEnv(2, ship=SHIP, sensor="ais")
    assert info.value.field == "sensor"
    with pytest.raises(ParameterError) as info:
        EncounterVectorEnv(2, ship=SHIP, sensor=AIS(delay=1.5))
    assert info.value.field == "sensor.delay"
    with pytest.raises(ParameterError) as info:
        EncounterVectorEnv(2, ship=SHIP, episode_seconds=10.0, sensor=AIS(delay=10.0))
    assert info.value.field == "sensor.delay"
