"""seahelm.gym's rps set-point (issue 52): with a ``-rps`` autopilot the agent sets the heading
set-point and the propeller rps the autopilot holds (no registered controller takes a speed
set-point). A constant action = simulate() with that autopilot, reference and rps, bit for bit;
batched = single; check_env; bad input names its argument. And
seahelm.simulation.stepping_reference.set_controller_param under it."""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402
from seahelm import simulate  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import ShipEnv, ShipVectorEnv  # noqa: E402
from gym_checks import assert_each_sub_env_is_a_single_env  # noqa: E402
from seahelm.simulation.stepping_reference import set_controller_param  # noqa: E402

ACTIONS = ("heading_setpoint", "rps_setpoint")


def _vec(n, **kw):
    return ShipVectorEnv(n, autopilot="pid-heading-rps", actions=ACTIONS, **kw)


def test_a_constant_rps_setpoint_is_simulate_with_that_rps():
    n, seconds = 3, 12.0
    envs = _vec(n, episode_seconds=seconds)
    assert envs.action_labels == ACTIONS and envs.action_units == ("rad", "-")
    n0 = envs.plant.simulator.problem.controller_params.propeller_rps
    np.testing.assert_array_equal(envs.single_action_space.low, np.float32([-np.pi / 4, -0.5]))
    envs.reset(seed=4)
    sim = envs.plant.simulator
    nz = sim.problem.model.n_states
    x0 = np.array([[sim.state(i)[s] for s in sim.state_labels][:nz] for i in range(n)])
    # (float32-exact values: the action space is float32, the check compares float64 sums)
    action = np.array([[0.25, -0.25], [-0.125, 0.25], [0.0, 0.0]])
    rps = n0 * (1.0 + action[:, 1])  # (the rps the autopilot is to hold)
    absolute = envs.task.reference_direction().copy() + action[:, 0]
    stepped = []
    for _ in range(int(seconds)):
        envs.step(action)
        stepped.append([[sim.state(i)[s] for s in sim.state_labels] for i in range(n)])
    stepped = np.array(stepped)
    base = sim.problem.controller_params
    problem = dataclasses.replace(
        sim.problem, x0=x0, record_every=10, reference={"heading": absolute[:, None, None]},
        controller_params=[dataclasses.replace(base, propeller_rps=float(r)) for r in rps])
    whole = simulate(problem)
    np.testing.assert_array_equal(stepped, whole.state[:, 1:].transpose(1, 0, 2))
    # the rps held is the action's, and it changed the speed: slower, faster, the same
    held = whole.command[:, -1, list(whole.command_labels).index("propeller_rps")]
    np.testing.assert_array_equal(held, rps)
    np.testing.assert_allclose(held, [0.75 * n0, 1.25 * n0, n0], rtol=1e-15)
    u = whole.output[:, -1, list(whole.output_labels).index("surge_speed")]
    u0 = whole.output[:, 0, list(whole.output_labels).index("surge_speed")]
    assert u[0] < u0[0] - 0.02 and u[1] > u0[1] + 0.02
    envs.close()


def test_each_sub_environment_equals_a_single_env():
    lo, hi = np.array([-np.pi / 4, -0.5]), np.array([np.pi / 4, 0.5])
    assert_each_sub_env_is_a_single_env(
        lambda: _vec(3, episode_seconds=10.0),
        lambda: ShipEnv(autopilot="pid-heading-rps", actions=ACTIONS, episode_seconds=10.0),
        np.random.default_rng(3).uniform(lo, hi, (8, 3, 2)))


def test_a_restarted_sub_environment_holds_the_autopilot_s_rps_again():
    envs = _vec(2, episode_seconds=2.0)
    envs.reset(seed=2)
    cp = envs.plant.simulator._batch.slices.arrays.get("params", "controller")
    n0 = envs.plant.simulator.problem.controller_params.propeller_rps
    for _ in range(2):
        *_, truncated, _ = envs.step(np.array([[0.0, 0.4], [0.0, -0.4]]))
    assert truncated.all()
    np.testing.assert_allclose(cp["propeller_rps"], [1.4 * n0, 0.6 * n0], rtol=1e-6)
    envs.step(np.zeros((2, 2)))  # (the restart step: the action is ignored)
    np.testing.assert_array_equal(cp["propeller_rps"], [n0, n0])
    envs.close()


def test_check_env_passes():
    env = ShipEnv(autopilot="pid-heading-rps", actions=ACTIONS, episode_seconds=20.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env, skip_render_check=True)
    env.close()


def test_bad_input_names_the_argument():
    with pytest.raises(ParameterError) as info:
        ShipVectorEnv(2, actions=("rudder_command", "rps_setpoint"))
    assert info.value.field == "actions" and "-rps" in str(info.value)
    with pytest.raises(ParameterError) as info:
        ShipVectorEnv(2, autopilot="pid-heading", ship="kvlcc2-l7", actions=ACTIONS)
    assert info.value.field == "autopilot" and "propeller_rps" in str(info.value)
    with pytest.raises(ParameterError) as info:
        _vec(2, action_bounds={"rps_setpoint": (-1.0, 0.5)})
    assert info.value.field == "action_bounds" and "low > -1" in str(info.value)
    envs = _vec(2, episode_seconds=4.0)
    envs.reset(seed=0)
    sim = envs.plant.simulator
    with pytest.raises(ParameterError) as info:
        set_controller_param(sim, "speed", 1.0)
    assert info.value.field == "name" and "propeller_rps" in str(info.value)
    with pytest.raises(ParameterError) as info:
        set_controller_param(sim, "propeller_rps", [5.0, -1.0])
    assert info.value.field == "values" and info.value.run == 1
    with pytest.raises(ParameterError) as info:
        set_controller_param(sim, "propeller_rps", [5.0, 6.0, 7.0])
    assert info.value.field == "values"
    cp = sim._batch.slices.arrays.get("params", "controller")
    assert (cp["propeller_rps"] == sim.problem.controller_params.propeller_rps).all()
    envs.close()
