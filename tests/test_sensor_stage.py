"""The position sensors' stage (seahelm.simulation.sensor_stage): with zero noise and no wave
motion the run is today's bit for bit; a batch equals its runs one by one (a sweep's chunks);
stepping equals the whole horizon; the noise is standard normal, per run, step and channel;
bad settings are refused naming the key."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.control.dp_observer import DP_PID_OBSERVER
from seahelm.control.dp_pid import DP_PID, dp_pid_params
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.simulation.sensor_stage import PositionSensors, sensor_noise
from seahelm.simulation.stages import STAGES
from seahelm.simulation.stepping import Simulator

from test_dp_observer import NOISE, SHIP, dp_problem, observer_params, sea_problem


def _same(a, b):
    for what in ("state", "command", "output"):
        x, y = getattr(a, what), getattr(b, what)
        assert x.shape == y.shape, what
        assert np.array_equal(x, y), what  # bit for bit


def test_the_stage_is_registered_after_the_first_order_motions():
    names = list(STAGES)
    assert names.index("sensors") == names.index("first_order") + 1


def test_zero_noise_and_no_wave_motion_is_todays_run_bit_for_bit():
    """The stage in the loop (the first-order motions too) but off: the states, commands and
    the model's outputs equal those of the run without either, and the measured values are
    the true ones. In the sea of examples/supply_dp_observer_waves.toml, its mean wave loads
    in both runs (the loop with the stage is then the raw dp-pid's of test_dp_observer)."""
    off = sea_problem(DP_PID, dp_pid_params(SHIP), t_final=60.0,
                      sensors=PositionSensors(wave_motion=False))
    with_stage = simulate(off)
    today = simulate(off.replace(first_order=None, sensors=None))
    n = len(today.output_labels)
    assert with_stage.output_labels[:7] == today.output_labels[:7]
    assert np.array_equal(with_stage.state, today.state)
    assert np.array_equal(with_stage.command, today.command)
    model_out = len(SHIP.model.output_labels)
    assert np.array_equal(with_stage.output[..., :model_out], today.output[..., :model_out])
    assert n < len(with_stage.output_labels)
    for meas, true in (("measured_north", "north"), ("measured_east", "east"),
                       ("measured_heading", "heading")):
        assert np.array_equal(with_stage[meas], with_stage[true])
    # and on: the wave motion moves the vessel's thrusters (the test can fail)
    on = simulate(off.replace(sensors=PositionSensors(**NOISE, wave_motion=True)))
    assert not np.array_equal(on.command, today.command)


def test_a_batch_equals_its_runs_one_by_one():
    """Three runs (their own seas and noise) as one batch, and each alone as a sweep's chunk
    of one (the first-order motions and the noise keys of run i, by their select_runs); in
    the sea of examples/supply_dp_observer_waves.toml (test_dp_observer's raw dp-pid loop)."""
    problem = sea_problem(DP_PID, dp_pid_params(SHIP), runs=3, seed=[4, 5, 6], t_final=60.0)
    batch = simulate(problem)
    for i in range(3):
        alone = simulate(problem.replace(  # (as seahelm.sweep.select_runs makes a chunk)
            x0=problem.x0[i:i + 1], first_order=problem.first_order.select_runs(i, i + 1),
            sensors=problem.sensors.select_runs(i, i + 1)))
        for what in ("state", "command", "output"):
            assert np.array_equal(getattr(alone, what)[0], getattr(batch, what)[i]), (i, what)
    noise = batch["measured_heading"] - batch["heading"] - batch["yaw_wave"]
    assert not np.allclose(noise[0], noise[1])  # (each run its own noise)


def test_stepping_equals_the_whole_horizon():
    """The observer's loop stepped one controller interval at a time gives simulate's values
    bit for bit (the noise is a function of the step, not a stream); in the sea of
    examples/supply_dp_observer_waves.toml (its mean wave loads too: that example's kernel)."""
    problem = sea_problem(DP_PID_OBSERVER, observer_params(), runs=2, seed=[4, 5], t_final=30.0)
    whole = simulate(problem)
    with Simulator(problem) as sim:
        sim.reset()
        for _ in range(sim.n_intervals):
            sim.step()
        stepped = sim.result()
    _same(stepped, whole)


def test_the_noise_is_standard_normal_and_independent():
    keys = PositionSensors(seed=7).keys(4)
    n = np.array([[[sensor_noise(key, k, j) for j in range(3)] for k in range(5000)]
                  for key in keys])
    assert abs(n.mean()) < 0.02 and abs(n.std() - 1.0) < 0.02
    assert abs(np.mean(np.abs(n) > 2.0) - 0.0455) < 0.005  # the normal's tails
    flat = n.reshape(4, -1)
    assert np.abs(np.corrcoef(flat)[np.triu_indices(4, 1)]).max() < 0.03  # runs
    assert abs(np.corrcoef(n[0, 1:, 0], n[0, :-1, 0])[0, 1]) < 0.05  # steps
    assert abs(np.corrcoef(n[0, :, 0], n[0, :, 1])[0, 1]) < 0.05  # channels


def test_a_chunk_keeps_its_runs_keys():
    whole = PositionSensors(seed=3)
    np.testing.assert_array_equal(whole.select_runs(2, 4).keys(2), whole.keys(5)[2:4])
    assert not np.array_equal(PositionSensors(seed=4).keys(3), whole.keys(3))


@pytest.mark.parametrize("kw, match", [
    (dict(noise_north=-1.0), r"sensors\.noise_north.*>= 0 \[m\], got -1\.0"),
    (dict(noise_east=math.nan), r"sensors\.noise_east.*\[m\], got nan"),
    (dict(noise_heading="0.1"), r"sensors\.noise_heading.*\[rad\], got '0\.1'"),
    (dict(wave_motion="yes"), r"sensors\.wave_motion.*true or false, got 'yes'"),
    (dict(seed=-2), r"sensors\.seed.*integer >= 0, got -2"),
])
def test_bad_settings_are_refused(kw, match):
    with pytest.raises(ParameterError, match=match):
        PositionSensors(**kw)


def test_a_problem_that_cannot_take_its_sensors_is_refused():
    problem = dp_problem(DP_PID, dp_pid_params(SHIP), t_final=10.0)
    with pytest.raises(ParameterError, match=r"sensors.*wave_motion.*needs first-order "
                                             r"motions in the loop.*got none"):
        problem.replace(first_order=None)
    with pytest.raises(ParameterError, match=r"sensors.*wave_motion.*got DOF heave"):
        dp_problem(DP_PID, dp_pid_params(SHIP), t_final=10.0, wave_dofs=("heave",))
    with pytest.raises(ParameterError, match=r"sensors.*must be a PositionSensors"):
        problem.replace(sensors={"noise_north": 0.1})


@pytest.mark.parametrize("extra, words", [
    ("[sensors]\nwave_motion = true\n", ["sensors", "wave_motion", "first-order motions"]),
    ("[sensors]\nnoise_north = -1.0\n", ["sensors.noise_north", "-1"]),
    ("[sensors]\nnoise_heading = 0.1\n", ["sensors", "noise_heading"]),
])
def test_the_scenario_key_is_checked(extra, words):
    from pathlib import Path

    from seahelm.scenario import parse_scenario

    text = (Path(__file__).parents[1] / "examples" / "supply_dp_setpoint.toml").read_text()
    with pytest.raises((ParameterError, ValueError)) as info:
        parse_scenario(text + extra)
    message = str(info.value)
    assert all(w in message for w in words), message


def test_the_scenario_key_makes_the_sensors():
    from pathlib import Path

    from seahelm.scenario import parse_scenario

    text = (Path(__file__).parents[1] / "examples" / "supply_dp_setpoint.toml").read_text()
    problem = parse_scenario(text + "[sensors]\nnoise_north = 0.1\nnoise_heading_deg = 0.5\n"
                                    "seed = 3\n")
    assert problem.sensors == PositionSensors(noise_north=0.1, noise_heading=math.radians(0.5),
                                              wave_motion=False, seed=3)
