"""seahelm.gym keeps the simulator's runs at one step (one call of the compiled loop a step,
issue 52's speed): a sub-environment started again sets every run's clock back to 0
(seahelm.simulation.stepping_reference.restart_clock), and the others go on exactly as alone."""

from __future__ import annotations

import math

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from seahelm import Problem, Simulator  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import ShipEnv, ShipVectorEnv  # noqa: E402
from seahelm.simulation.stepping_reference import restart_clock  # noqa: E402

WEATHER = dict(wind_speed=3.0, wind_direction=math.radians(45.0), wave_height=0.066,
               wave_length=2.6, wave_direction=math.radians(45.0))


def test_restart_clock_keeps_the_runs_going_exactly():
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    problem = Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0,
                                                          speed=5.0),
                      x0=np.zeros((3, 4)), t_final=10.0, dt=0.1, controller="pid-heading",
                      reference={"heading": np.array([0.1, 0.2, 0.3])[:, None, None]})
    with Simulator(problem) as straight, Simulator(problem) as clocked:
        straight.reset()
        clocked.reset()
        a = straight.step(n=60)
        clocked.step(n=20)
        clocked.reset(runs=[1])  # run 1 again from the start: the runs at different steps
        assert clocked.time.tolist() == [2.0, 0.0, 2.0]
        restart_clock(clocked)
        assert clocked.time.tolist() == [0.0, 0.0, 0.0]
        b = clocked.step(n=40)
        np.testing.assert_array_equal(b.values[[0, 2]], a.values[[0, 2]])  # bit for bit
        assert b.values[1, 0] != a.values[1, 0]  # (run 1 started later)


def test_restart_clock_refuses_a_time_series():
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    problem = Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0,
                                                          speed=5.0),
                      x0=np.zeros(4), t_final=1.0, dt=0.1, reference=np.zeros((11, 1)))
    with Simulator(problem) as sim:
        sim.reset()
        with pytest.raises(ParameterError, match="reference.*time series"):
            restart_clock(sim)


@pytest.mark.parametrize("autopilot", [None, "pid-heading-rps"])
def test_a_run_goes_on_exactly_through_another_s_restarts(autopilot):
    # run 0 fails and restarts over and over; run 1 must be the single env of its start
    kw = dict(episode_seconds=40.0, max_heading_error=math.radians(10.0),
              initial_heading_error=0.0, **WEATHER)
    if autopilot:
        kw["autopilot"] = autopilot
    envs = ShipVectorEnv(2, **kw)
    sim = envs.plant.simulator
    obs = envs.reset(seed=8)[0]
    start, target = sim.state(1), float(envs.task.target[1])
    batched, restarts = [], 0
    for _ in range(30):
        # run 0 hard over; run 1 kept on its heading (a PD law on what it observes)
        steer = float(np.clip(-2.0 * obs[1, 0] - 40.0 * obs[1, 1], -0.5, 0.5))
        action = np.array([[0.6], [steer]]) if autopilot is None else np.array([[0.78], [0.0]])
        obs, reward, terminated, *_ = envs.step(action)
        restarts += int(terminated[0])
        assert not terminated[1]
        batched.append((action[1], obs[1].copy(), reward[1]))
        assert sim.time[0] == sim.time[1]  # one step for every run
    assert restarts >= 2
    env = ShipEnv(**kw)
    env.reset(seed=0)
    env.plant.simulator.set_state(0, start)
    env.task.target[0] = target
    for action, obs_b, reward_b in batched:
        obs, reward, *_ = env.step(action)
        np.testing.assert_array_equal(obs, obs_b)
        assert reward == reward_b
    env.close()
    envs.close()


def test_restart_clock_starts_runs_again():
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    problem = Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0,
                                                          speed=5.0),
                      x0=np.zeros((3, 4)), t_final=10.0, dt=0.1, controller="pid-heading",
                      reference={"heading": np.array([0.1, 0.2, 0.3])[:, None, None]})
    with Simulator(problem) as straight, Simulator(problem) as fresh, \
            Simulator(problem) as clocked:
        straight.reset()
        fresh.reset()
        clocked.reset()
        a = straight.step(n=60)
        f = fresh.step(n=40)
        clocked.step(n=20)
        restart_clock(clocked, runs=[1])  # run 1 from the start, runs 0 and 2 kept
        assert clocked.time.tolist() == [0.0, 0.0, 0.0]
        b = clocked.step(n=40)
        np.testing.assert_array_equal(b.values[[0, 2]], a.values[[0, 2]])
        np.testing.assert_array_equal(b.values[1], f.values[1])  # as a fresh run
        with pytest.raises(ParameterError, match="run"):
            restart_clock(clocked, runs=[5])


def test_set_states_writes_many_runs_or_refuses_by_name():
    from seahelm.simulation.stepping_reference import set_states
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    problem = Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0,
                                                          speed=5.0),
                      x0=np.zeros((3, 4)), t_final=1.0, dt=0.1,
                      bounds={"yaw_rate": (-1.0, 1.0)})
    with Simulator(problem) as sim:
        sim.reset()
        set_states(sim, [0, 2], {"heading": [0.5, -0.5], "yaw_rate": 0.01})
        assert [sim.state(i)["heading"] for i in range(3)] == [0.5, 0.0, -0.5]
        assert [sim.state(i)["yaw_rate"] for i in range(3)] == [0.01, 0.0, 0.01]
        with pytest.raises(ParameterError, match="values.*unknown state 'roll'"):
            set_states(sim, [0], {"roll": 0.1})
        with pytest.raises(ParameterError, match=r"values.*\['heading'\].*shape \(2,\)"):
            set_states(sim, [0, 1], {"heading": [0.1, 0.2, 0.3]})
        with pytest.raises(ParameterError, match="values.*'yaw_rate' = 2.0 of run 1.*bounds"):
            set_states(sim, [0, 1], {"yaw_rate": [0.0, 2.0]})
        assert sim.state(1)["yaw_rate"] == 0.0  # (nothing written)
