"""A seeded reset of the collision environment with an AIS sensor gives the same episodes
again, noise included: reset(seed=s) twice on one environment, the same observations (the
reports' noise is numbered by episode; a seeded reset numbers the episodes from 0 again, as
when the environment was made). Vector and single environment alike."""

from __future__ import annotations

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from seahelm.encounters import AIS  # noqa: E402
from seahelm.gym import EncounterEnv, EncounterVectorEnv  # noqa: E402

SHIP = "kvlcc2-l7"
SENSOR = AIS(update_interval=3.0, delay=2.0, position_noise=0.5, course_noise=0.02,
             speed_noise=0.01, heading_noise=0.02, seed=7)


def _episode(env, seed, action):
    obs = [env.reset(seed=seed)[0]]
    for _ in range(8):
        obs.append(env.step(action)[0])
    return np.stack(obs)


def test_a_seeded_reset_repeats_the_vector_env_s_episodes_noise_included():
    envs = EncounterVectorEnv(2, ship=SHIP, episode_seconds=10.0, sensor=SENSOR,
                              autoreset_mode="Disabled", target_avoidance="rule-based")
    first = _episode(envs, 3, np.zeros((2, 1)))
    other = _episode(envs, 4, np.zeros((2, 1)))
    again = _episode(envs, 3, np.zeros((2, 1)))
    envs.close()
    np.testing.assert_array_equal(again, first)
    assert not np.array_equal(other, first)


def test_a_seeded_reset_repeats_the_single_env_s_episode_noise_included():
    env = EncounterEnv(ship=SHIP, episode_seconds=10.0, sensor=SENSOR)
    first = _episode(env, 0, np.zeros(1))
    again = _episode(env, 0, np.zeros(1))
    env.close()
    np.testing.assert_array_equal(again, first)
