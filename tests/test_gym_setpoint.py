"""seahelm.gym's set-point action: the agent gives a heading autopilot (run inside the compiled
loop) its set-point instead of a rudder order. A constant set-point gives simulate()'s
trajectory with that autopilot and reference; check_env passes; every sub-environment equals a
single env; bad input names its argument. And the stepping functions it rests on
(seahelm.simulation.stepping_reference)."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402
from seahelm import Problem, Simulator, simulate  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import ShipEnv, ShipVectorEnv  # noqa: E402
from gym_checks import assert_each_sub_env_is_a_single_env  # noqa: E402
from seahelm.simulation.stepping_reference import held_commands, set_reference  # noqa: E402

WEATHER = dict(wind_speed=3.0, wind_direction=math.radians(45.0), wave_height=0.066,
               wave_length=2.6, wave_direction=math.radians(45.0))


@pytest.mark.parametrize("task", ["HeadingKeeping", "PathFollowing"])
def test_a_constant_setpoint_is_simulate_with_that_autopilot_and_reference(task):
    n, seconds = 3, 12.0
    envs = ShipVectorEnv(n, task=task, autopilot="pid-heading-rps", episode_seconds=seconds,
                         **WEATHER)
    assert envs.action_labels == ("heading_setpoint",) and envs.action_units == ("rad",)
    envs.reset(seed=4)
    sim = envs.plant.simulator
    nz = sim.problem.model.n_states
    x0 = np.array([[sim.state(i)[s] for s in sim.state_labels][:nz] for i in range(n)])
    setpoint = np.array([[0.3], [-0.2], [0.0]])  # relative to the target / the first leg
    absolute = envs.task.reference_direction().copy() + setpoint[:, 0]
    stepped = []
    for _ in range(int(seconds)):
        envs.step(setpoint)
        stepped.append([[sim.state(i)[s] for s in sim.state_labels] for i in range(n)])
    stepped = np.array(stepped)  # (seconds, runs, states)
    # the same problem through simulate(): the autopilot and the set-point held constant
    problem = dataclasses.replace(sim.problem, x0=x0, record_every=10,
                                  reference={"heading": absolute[:, None, None]})
    whole = simulate(problem)
    assert whole.state_labels == sim.state_labels  # (vessel then actuator states)
    states = whole.state[:, 1:]  # t = 1, 2, ...
    np.testing.assert_array_equal(stepped, states.transpose(1, 0, 2))
    # the autopilot steered: the heading went to the set-point (not held at the start's)
    heading = whole.output[:, -1, list(whole.output_labels).index("heading")]
    start_error = np.abs(((x0[:, list(sim.state_labels).index("heading")] - absolute + np.pi)
                          % (2 * np.pi)) - np.pi)
    end_error = np.abs(((heading - absolute + np.pi) % (2 * np.pi)) - np.pi)
    big = start_error > 0.2  # (a small error is not undone in 12 s: the ship turns slowly)
    assert big.any() and (end_error[big] < 0.7 * start_error[big]).all()
    envs.close()


@pytest.mark.parametrize("task", ["HeadingKeeping", "PathFollowing"])
def test_check_env_passes_with_the_setpoint_action(task):
    env = ShipEnv(task=task, autopilot="pid-heading-rps", episode_seconds=20.0, **WEATHER)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env, skip_render_check=True)
    env.close()


def test_make_takes_the_autopilot():
    env = gymnasium.make("seahelm/HeadingKeeping-v0", ship="kvlcc2-l7", episode_seconds=10.0,
                         autopilot="pid-heading-rps")
    assert env.unwrapped.action_labels == ("heading_setpoint",)
    np.testing.assert_allclose(env.action_space.high, [math.pi / 4])  # ±45°
    env.close()


def test_each_sub_environment_equals_a_single_env_with_the_setpoint_action():
    assert_each_sub_env_is_a_single_env(
        lambda: ShipVectorEnv(3, autopilot="pid-heading-rps", episode_seconds=10.0, **WEATHER),
        lambda: ShipEnv(autopilot="pid-heading-rps", episode_seconds=10.0, **WEATHER),
        np.random.default_rng(3).uniform(-0.5, 0.5, (8, 3, 1)))


def test_the_rudder_observed_is_the_autopilot_s_order():
    envs = ShipVectorEnv(2, autopilot="pid-heading-rps", episode_seconds=5.0)
    envs.reset(seed=1)
    obs, *_ = envs.step(np.array([[0.4], [-0.4]]))  # turn to starboard / to port
    rudder = obs[:, envs.observation_labels.index("rudder_command")]
    assert rudder[0] > 0.05 and rudder[1] < -0.05
    held = held_commands(envs.plant.simulator)
    np.testing.assert_array_equal(rudder, held[:, 0].astype(np.float32))
    envs.close()


def test_autoreset_with_the_setpoint_action():
    envs = ShipVectorEnv(2, autopilot="pid-heading-rps", episode_seconds=2.0)
    envs.reset(seed=2)
    for k in range(2):
        _, _, _, truncated, _ = envs.step(np.zeros((2, 1)))
    assert truncated.all()
    obs, reward, terminated, truncated, _ = envs.step(np.full((2, 1), 0.5))
    assert (reward == 0).all() and not terminated.any() and not truncated.any()
    # (the episodes' clocks: the simulator's runs keep theirs, the model time-invariant)
    assert (envs.elapsed == 0).all()
    np.testing.assert_array_equal(obs[:, 4], envs.plant.command_start[0])  # rudder: trim
    envs.step(np.full((2, 1), 0.5))
    assert (envs.elapsed == 1.0).all()
    envs.close()


def test_bad_setpoint_setups_are_refused_by_name():
    with pytest.raises(ParameterError, match="actions.*'heading_setpoint'.*needs an autopilot"):
        ShipVectorEnv(2, actions=("heading_setpoint",))
    with pytest.raises(ParameterError, match=r"actions.*must be \('heading_setpoint',\) or "
                                             r"\('heading_setpoint', 'rps_setpoint'\) with an "
                                             "autopilot"):
        ShipVectorEnv(2, autopilot="pid-heading-rps", actions=("rudder_command",))
    with pytest.raises(ParameterError, match="autopilot.*'no-such-pilot'"):
        ShipVectorEnv(2, autopilot="no-such-pilot")
    with pytest.raises(ParameterError, match="autopilot.*'zigzag-rps' takes no heading set-point"):
        ShipVectorEnv(2, autopilot="zigzag-rps")
    envs = ShipVectorEnv(2, autopilot="pid-heading-rps", episode_seconds=5.0)
    envs.reset(seed=0)
    with pytest.raises(ParameterError, match="action 'heading_setpoint' of sub-environment 0 "
                                             r"is nan; actions must be finite \[rad\]"):
        envs.step(np.array([[np.nan], [0.0]]))
    envs.close()


def test_set_reference_refuses_a_shared_or_broadcast_reference():
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    base = dict(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0),
                x0=np.zeros((2, 4)), t_final=10.0, dt=0.1, controller="pid-heading")
    with Simulator(Problem(**base, reference={"heading": 0.2})) as sim:  # one for every run
        sim.reset()
        with pytest.raises(ParameterError, match=r"reference.*shape \(1, 1, 1\).*one constant "
                                                 "reference per run"):
            set_reference(sim, [0.1])
    own = np.zeros((2, 1, 1))
    with Simulator(Problem(**base, reference=own)) as sim:  # the caller's own array
        sim.reset()
        with pytest.raises(ParameterError, match="reference.*of its own"):
            set_reference(sim, [0.1])
    with Simulator(Problem(**base, reference={"heading": np.zeros((2, 1, 1))})) as sim:
        sim.reset()
        with pytest.raises(ParameterError, match="values.*unknown reference 'course'"):
            set_reference(sim, {"course": 0.1})
        with pytest.raises(ParameterError, match="values.*reference 'heading' of run 1 is inf"):
            set_reference(sim, [[0.1], [np.inf]])
        set_reference(sim, {"heading": 0.5}, runs=1)
        obs = sim.step(n=100)
        assert obs["heading"][0] == 0.0 and obs["heading"][1] > 0.01  # run 1 turns to 0.5


def test_the_docs_setpoint_example_runs():
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "docs" / "guide"
            / "driven-from-outside.rst").read_text()
    section = text[text.index("**Set-point actions.**"):]
    lines = section[section.index(".. code-block:: python"):].splitlines()[2:]
    block = []
    for line in lines:
        if line and not line.startswith("    "):
            break
        block.append(line[4:])
    namespace: dict = {}
    exec("\n".join(block), namespace)  # noqa: S102 - the page's own example
    envs = namespace["envs"]
    assert envs.action_labels == ("heading_setpoint",) and namespace["reward"].shape == (256,)
    envs.close()
