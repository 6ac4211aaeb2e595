"""One default for the position sensors (issue 50): ``PositionSensors()`` in Python and an
empty ``[sensors]`` in a scenario are the same sensors, and they add nothing (no noise, no
wave motion), so the defaults give the run without the stage bit for bit."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from seahelm.control.dp_pid import DP_PID, dp_pid_params
from seahelm.scenario import parse_scenario
from seahelm.scenario.schema import SensorsSection
from seahelm.simulation.engine import simulate
from seahelm.simulation.sensor_stage import PositionSensors

from test_dp_observer import SHIP, sea_problem

EXAMPLE = Path(__file__).parents[1] / "examples" / "supply_dp_setpoint.toml"


def test_the_python_and_scenario_defaults_agree_field_by_field():
    py = {f.name: f.default for f in dataclasses.fields(PositionSensors)}
    toml = {name: f.default for name, f in SensorsSection.model_fields.items()}
    assert py["wave_motion"] is False and toml["wave_motion"] is False
    for name in ("noise_north", "noise_east", "wave_motion", "seed"):
        assert py[name] == toml[name], name
    assert py["noise_heading"] == math.radians(toml["noise_heading_deg"]) == 0.0


def test_an_empty_sensors_section_is_the_default_sensors():
    problem = parse_scenario(EXAMPLE.read_text() + "[sensors]\n")
    assert problem.sensors == PositionSensors()
    assert problem.sensors.wave_motion is False


def test_the_default_sensors_give_the_run_without_the_stage_bit_for_bit():
    """The first-order motions in the loop, the default sensors: the controller sees the true
    position (the sea is not added unless asked), as without the stage. The run without is
    without the first-order motions too (they only add outputs when nobody sees them;
    tests/test_sensor_stage.py compares the same pair), both in the sea of
    examples/supply_dp_observer_waves.toml with its mean wave loads: the loop with the stage is
    test_dp_observer's raw dp-pid, the one without that of tests/test_sensor_stage.py's pair."""
    with_stage = simulate(sea_problem(DP_PID, dp_pid_params(SHIP), t_final=20.0,
                                      sensors=PositionSensors()))
    without = simulate(sea_problem(DP_PID, dp_pid_params(SHIP), t_final=20.0,
                                   sensors=PositionSensors()).replace(sensors=None,
                                                                      first_order=None))
    assert np.array_equal(with_stage.state, without.state)
    assert np.array_equal(with_stage.command, without.command)
    for meas, true in (("measured_north", "north"), ("measured_east", "east"),
                       ("measured_heading", "heading")):
        assert np.array_equal(with_stage[meas], with_stage[true])
