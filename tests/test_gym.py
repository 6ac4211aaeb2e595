"""seahelm.gym: gymnasium's checker passes, the environments are registered, the vector
environment is native and autoresets by gymnasium's next-step rule, seeds reproduce, actions are
clipped (NaN refused), the rewards are the documented terms, the trajectories are simulate()'s,
and bad input names its argument."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import seahelm.gym  # noqa: E402,F401  (registers the environments)
from gymnasium.utils.env_checker import check_env  # noqa: E402
from gymnasium.vector import AutoresetMode, VectorEnv  # noqa: E402
from seahelm import Problem, simulate  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import ShipEnv, ShipVectorEnv  # noqa: E402
from gym_checks import assert_each_sub_env_is_a_single_env  # noqa: E402

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
WEATHER = dict(wind_speed=3.0, wind_direction=math.radians(45.0), wave_height=0.066,
               wave_length=2.6, wave_direction=math.radians(45.0))


@pytest.mark.parametrize("task", ["HeadingKeeping", "PathFollowing"])
def test_check_env_passes_without_a_warning(task):
    env = ShipEnv(task=task, ship="kvlcc2-l7", episode_seconds=20.0, **WEATHER)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # (gymnasium's checker warns of what it doubts)
        check_env(env, skip_render_check=True)
    env.close()


def test_make_and_make_vec_are_registered():
    env = gymnasium.make("seahelm/HeadingKeeping-v0", ship="kvlcc2-l7", episode_seconds=10.0)
    assert isinstance(env.unwrapped, ShipEnv)
    assert env.unwrapped.action_labels == ("rudder_command",)
    assert env.unwrapped.action_units == ("rad",)
    env.close()
    envs = gymnasium.make_vec("seahelm/PathFollowing-v0", num_envs=5, ship="kvlcc2-l7")
    assert isinstance(envs, ShipVectorEnv)  # native: not a Sync/AsyncVectorEnv of 5 envs
    assert isinstance(envs, VectorEnv)
    assert envs.metadata["autoreset_mode"] is AutoresetMode.NEXT_STEP
    assert envs.observation_space.shape == (5, len(envs.observation_labels))
    assert envs.single_observation_space.shape == (len(envs.observation_labels),)
    assert envs.action_space.shape == (5, 1)
    obs, info = envs.reset(seed=0)
    assert envs.observation_space.contains(obs) and info == {}
    envs.close()


def test_bad_names_are_refused_by_name():
    with pytest.raises(gymnasium.error.NameNotFound):
        gymnasium.make("seahelm/Docking-v0")
    with pytest.raises(ParameterError, match="ship.*unknown catalog ship 'no-such-ship'"):
        gymnasium.make("seahelm/HeadingKeeping-v0", ship="no-such-ship")
    with pytest.raises(ParameterError, match="unknown task 'Docking'; tasks: HeadingKeeping"):
        ShipVectorEnv(2, task="Docking")
    with pytest.raises(ParameterError, match="unknown reward term 'speed'.*heading"):
        ShipVectorEnv(2, reward={"speed": 1.0})
    with pytest.raises(ParameterError, match="unknown keyword 'route' of task HeadingKeeping"):
        ShipVectorEnv(2, route=[[0, 0], [1, 0]])
    with pytest.raises(ParameterError, match=r"wind_speed.*>= 0 \[m/s\], got -1.0"):
        ShipVectorEnv(2, wind_speed=-1.0)
    with pytest.raises(ParameterError, match="unknown command 'thruster'"):
        ShipVectorEnv(2, actions=("rudder_command", "thruster"))
    with pytest.raises(ParameterError, match="num_envs.*>= 1, got 0"):
        ShipVectorEnv(0)
    with pytest.raises(ParameterError, match="route.*waypoints 1 and 2 coincide"):
        ShipVectorEnv(2, task="PathFollowing", route=[[0, 0], [5, 0], [5, 0]])


def test_a_seed_reproduces_the_episodes():
    def run(seed):
        envs = ShipVectorEnv(3, episode_seconds=10.0, **WEATHER)
        obs, _ = envs.reset(seed=seed)
        seen = [obs]
        rng = np.random.default_rng(7)
        for _ in range(4):
            obs, reward, *_ = envs.step(rng.uniform(-0.3, 0.3, (3, 1)))
            seen += [obs, reward]
        envs.close()
        return seen

    a, b, c = run(11), run(11), run(12)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    assert not np.array_equal(a[0], c[0])


def test_the_trajectory_is_simulate_s_with_the_same_commands():
    envs = ShipVectorEnv(2, episode_seconds=8.0, **WEATHER)
    envs.reset(seed=3)
    sim = envs.plant.simulator
    x0 = np.array([[sim.state(i)[s] for s in sim.state_labels] for i in range(2)])
    rudder = np.array([[0.2], [-0.1]])
    for _ in range(8):
        obs, *_ = envs.step(rudder)
    p = envs.plant
    n0 = p.command_start[p.command_labels.index("propeller_rps")]
    from seahelm.gym.plant import _weather

    problem = Problem(ship=p.ship, x0=x0[:, :-1], actuator_x0=x0[0, -1:], t_final=8.0, dt=0.1,
                      controller_dt=1.0, reference=[[[0.2, n0]], [[-0.1, n0]]],
                      **_weather(p.ship, WEATHER))
    whole = simulate(problem)
    heading = whole.output[:, -1, list(whole.output_labels).index("heading")]
    target = envs.task.target
    np.testing.assert_allclose(obs[:, 0], ((heading - target + np.pi) % (2 * np.pi) - np.pi),
                               rtol=0, atol=1e-6)  # (float32 observations)
    envs.close()


def test_the_reward_is_the_documented_sum_of_terms():
    w = {"heading": 1.0, "yaw_rate": 0.5, "rudder": 0.25, "rudder_rate": 2.0, "failure": 50.0}
    envs = ShipVectorEnv(4, reward=w, episode_seconds=10.0)
    envs.reset(seed=5)
    p = envs.plant
    envs.step(np.full((4, 1), 0.1))
    obs, reward, terminated, *_ = envs.step(np.full((4, 1), -0.2))
    psi, r = obs[:, 0].astype(float), obs[:, 1].astype(float)
    expected = (np.exp(-(psi / math.radians(10.0)) ** 2)
                - 0.5 * (r * p.length / p.speed) ** 2
                - 0.25 * (-0.2 / p.max_rudder) ** 2
                - 2.0 * (-0.3 / p.max_rudder) ** 2)
    assert not terminated.any()
    np.testing.assert_allclose(reward, expected, rtol=1e-5)
    envs.close()


def test_next_step_autoreset_after_truncation():
    envs = ShipVectorEnv(3, episode_seconds=3.0)
    envs.reset(seed=1)
    for k in range(3):
        obs, reward, terminated, truncated, _ = envs.step(np.full((3, 1), 0.3))
        assert truncated.all() == (k == 2) and not terminated.any()
    # the next step ignores the action, starts new episodes: reward 0, both flags False
    obs, reward, terminated, truncated, _ = envs.step(np.full((3, 1), 0.5))
    assert (reward == 0).all() and not terminated.any() and not truncated.any()
    # (the episodes' clocks: the simulator's runs keep theirs, the model time-invariant)
    assert (envs.elapsed == 0).all()
    np.testing.assert_array_equal(obs[:, 1], 0.0)  # yaw rate of the straight approach
    np.testing.assert_array_equal(obs[:, 4], envs.plant.command_start[0])  # rudder: trim
    obs, reward, terminated, truncated, _ = envs.step(np.full((3, 1), 0.5))
    assert (envs.elapsed == 1.0).all() and (reward != 0).all()
    envs.close()


def test_a_failed_episode_restarts_alone_the_others_go_on():
    envs = ShipVectorEnv(2, episode_seconds=30.0, max_heading_error=math.radians(40.0))
    envs.reset(seed=2)
    sim = envs.plant.simulator
    hard = np.array([[0.6], [0.0]])  # run 0 hard over: off its heading; run 1 steady
    for k in range(30):
        obs, reward, terminated, truncated, _ = envs.step(hard)
        if terminated[0]:
            break
    assert terminated[0] and not terminated[1] and not truncated.any()
    assert reward[0] < -40  # the failure term (-50)
    t_fail = envs.elapsed.copy()
    state1 = sim.state(1)
    obs, reward, terminated, truncated, _ = envs.step(hard)
    assert envs.elapsed[0] == 0.0 and envs.elapsed[1] == t_fail[1] + 1.0 and reward[0] == 0.0
    assert sim.state(1) != state1  # (run 1 went on)
    obs, *_ = envs.step(hard)
    assert envs.elapsed[0] == 1.0 and envs.elapsed[1] == t_fail[1] + 2.0
    # the simulator's runs are kept at one step (one call of the loop a step)
    assert sim.time[0] == sim.time[1]
    envs.close()


def test_actions_out_of_the_box_are_clipped_nan_refused():
    def first_step(action, n=2):
        envs = ShipVectorEnv(n, episode_seconds=5.0)
        envs.reset(seed=4)
        out = envs.step(action)
        return envs, out

    envs, (at_bound, *_) = first_step(np.full((2, 1), envs_max := 0.6108652381980153))
    _, (beyond, *_) = first_step(np.full((2, 1), 10.0))
    np.testing.assert_array_equal(beyond, at_bound)
    assert envs.single_action_space.high[0] == np.float32(envs_max)  # ±35° of the gear
    time_before = envs.plant.simulator.time.copy()
    with pytest.raises(ParameterError, match=r"action 'rudder_command' of sub-environment 1 "
                                             r"is nan; actions must be finite \[rad\]"):
        envs.step(np.array([[0.1], [np.nan]]))
    np.testing.assert_array_equal(envs.plant.simulator.time, time_before)  # nothing stepped
    with pytest.raises(ParameterError, match=r"actions.*shape \(2, 1\)"):
        envs.step(np.zeros((3, 1)))
    with pytest.raises(ParameterError, match="reset"):
        ShipVectorEnv(1).step(np.zeros((1, 1)))


def test_rudder_and_rps_actions_have_units_and_bounds():
    envs = ShipVectorEnv(2, actions=("rudder_command", "propeller_rps"), episode_seconds=5.0)
    p = envs.plant
    n0 = p.command_start[p.command_labels.index("propeller_rps")]
    assert envs.action_units == ("rad", "1/s")
    np.testing.assert_allclose(envs.single_action_space.high, [p.max_rudder, 1.5 * n0],
                               rtol=1e-6)
    np.testing.assert_allclose(envs.single_action_space.low, [-p.max_rudder, 0.0])
    envs.reset(seed=0)
    for _ in range(5):
        obs, *_ = envs.step(np.array([[0.0, 0.5 * n0], [0.0, 1.5 * n0]]))
    assert obs[0, 2] < p.speed < obs[1, 2]  # slower on half the rps, faster on 1.5 n0
    envs.close()


def test_path_following_cross_track_sign_legs_and_the_route_s_end():
    # an eastbound route: a ship south of it is to starboard, positive cross-track error
    envs = ShipVectorEnv(3, task="PathFollowing", route=[[0.0, 0.0], [0.0, 3.0], [1.0, 6.0]],
                         initial_heading_error=0.0, episode_seconds=20.0)
    obs, _ = envs.reset(seed=6)
    sim = envs.plant.simulator
    north = np.array([sim.state(i)["north"] for i in range(3)])
    np.testing.assert_allclose(obs[:, 0], -north, atol=1e-6)
    turn = math.atan2(3.0, 1.0) - math.pi / 2  # then 18.4° to port
    np.testing.assert_allclose(obs[:, 6], turn, atol=1e-6)
    assert (np.abs(north) > 0).all() and (np.abs(north) <= envs.plant.length / 2).all()
    ended = np.zeros(3, dtype=bool)
    for _ in range(20):
        obs, reward, terminated, truncated, _ = envs.step(np.zeros((3, 1)))
        if (envs.task.leg == 1).any():
            assert (obs[envs.task.leg == 1, 6] == 0).all()  # the last leg: no next turn
        ended |= terminated
        if terminated.any():
            # going straight east past the end of the first leg, then the second leg's
            # along-track distance: done without the failure term
            assert (reward[terminated] > -1).all()
            break
    assert ended.any()
    envs.close()


def test_simulator_observe_gives_the_outputs_of_a_state_set():
    envs = ShipVectorEnv(1, episode_seconds=5.0)
    envs.reset(seed=0)
    sim = envs.plant.simulator
    sim.set_state(0, {"heading": 1.25, "yaw_rate": 0.01})
    obs = sim.observe()
    assert obs["heading"][0] == 1.25 and obs["yaw_rate"][0] == 0.01
    from seahelm import Simulator

    with Simulator(sim.problem) as fresh, pytest.raises(ParameterError, match="reset"):
        fresh.observe()
    envs.close()


def test_cross_entropy_example_learns_a_little_in_two_iterations(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLES / "rl_cross_entropy.py"),
                           str(tmp_path), "--iterations", "2", "--population", "10",
                           "--episodes", "2"], capture_output=True, text=True, timeout=600,
                          env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "held-out episodes, mean return: initial policy" in proc.stdout
    assert (tmp_path / "rl_cross_entropy.png").stat().st_size > 10_000


def test_each_sub_environment_equals_a_single_env_from_the_same_start():
    # batched = one by one (house style 11): every sub-environment of the vector environment
    # gives the observations and rewards of a ShipEnv started from its state and target
    assert_each_sub_env_is_a_single_env(
        lambda: ShipVectorEnv(3, episode_seconds=10.0, **WEATHER),
        lambda: ShipEnv(episode_seconds=10.0, **WEATHER),
        np.random.default_rng(3).uniform(-0.4, 0.4, (8, 3, 1)))
