"""The Problem: one typed request, validated once, run by simulate(problem)."""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT, RUDDER_SERVO
from seahelm.analysis.equilibria.equilibrium import approach_state, self_propulsion_rps
from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.errors import ParameterError
from seahelm.ships import get_ship, write_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.vessels.mmg import MMG
from seahelm.vessels.nomoto import NOMOTO2

L7 = get_ship("kvlcc2-l7")
RPS = self_propulsion_rps(L7.params, 1.179)
START = approach_state(L7.params, 1.179).state
REF = {"rudder_command": math.radians(35.0), "propeller_rps": RPS}


def test_a_ship_problem_is_the_keyword_run_bit_for_bit(tmp_path):
    problem = Problem(ship="kvlcc2-l7", x0=START, t_final=20.0, dt=0.05, reference=REF)
    assert problem.model is MMG and problem.actuator is RUDDER_SERVO
    assert problem.actuator_params == L7.steering_gear.params
    assert (problem.n_steps, problem.controller_every) == (400, 1)
    by_problem = simulate(problem)
    by_keywords = simulate(MMG, L7.params, START, t_final=20.0, dt=0.05, actuator=RUDDER_SERVO,
                           actuator_params=L7.servo, reference=REF)
    np.testing.assert_array_equal(by_problem.state, by_keywords.state)
    np.testing.assert_array_equal(by_problem.output, by_keywords.output)
    # a ship file is the same ship
    path = write_ship(L7, tmp_path / "l7.toml")
    by_file = simulate(Problem(ship=path, x0=START, t_final=20.0, dt=0.05, reference=REF))
    np.testing.assert_array_equal(by_file.state, by_problem.state)


def test_exact_actuator_is_an_option_of_the_problem():
    problem = Problem(ship="kvlcc2-l7", x0=START, t_final=5.0, dt=0.05, reference=REF,
                      exact_actuator=False)
    assert simulate(problem).metadata["actuator_step"] == "integrated"
    assert simulate(problem.replace(exact_actuator=None)).metadata["actuator_step"] == \
        "closed-form"


@pytest.mark.parametrize(("changes", "field", "match"), [
    ({"dt": -0.1}, "dt", r"`dt` must be > 0 \[s\], got -0.1"),
    ({"t_final": 20.03}, "t_final", r"`t_final` must be a positive whole multiple of `dt`"),
    ({"controller_dt": 0.07}, "controller_dt", "whole multiple"),
    ({"controller_dt": 40.0}, "controller_dt", "exceeds `t_final`"),
    ({"record_every": 0}, "record_every", "whole number >= 1"),
    ({"record_every": 1000}, "record_every", "exceeds the number of steps"),
    ({"integrator": "rk5"}, "integrator", "unknown integrator 'rk5'"),
    ({"bounds": {"speed": (0, 1)}}, "bounds.speed", "is an unknown state; states: surge_speed"),
    ({"exact_actuator": "no"}, "exact_actuator", "must be True, False or None, got 'no'"),
    ({"actuator": DIRECT, "actuator_params": None, "exact_actuator": True}, "exact_actuator",
     "the actuator 'direct' has no closed-form step"),
    ({"jit": "fast"}, "jit", "must be True, False or None"),
    ({"environment_params": [1.0]}, "environment_params", "given without an `environment`"),
    ({"model": NOMOTO2}, "model", "'nomoto2' is not the model of ship 'kvlcc2-l7' \\('mmg'\\)"),
    ({"controller": "lqr"}, "controller", "unknown controller 'lqr'"),
    ({"controller": PID_HEADING}, "controller", "model 'mmg', actuator 'rudder-servo', "
                                                "controller 'pid-heading': model input "
                                                "'propeller_rps' is not fed"),
    ({"ship": "kvlcc9"}, "ship", "unknown catalog ship 'kvlcc9'"),
    # (with a ship, no x0 is its straight approach: tests/test_simulation_ship_start.py)
    ({"ship": None, "model": MMG, "params": L7.params, "x0": None}, "x0",
     "is required: the initial state"),
])
def test_bad_requests_name_their_field(changes, field, match):
    problem = Problem(ship="kvlcc2-l7", x0=START, t_final=20.0, dt=0.05, reference=REF)
    with pytest.raises(ParameterError, match=match) as err:
        problem.replace(**changes)
    assert err.value.field == field


def test_a_problem_needs_a_model_or_a_ship_and_its_parameters():
    with pytest.raises(ParameterError, match="`model` is required") as err:
        Problem(x0=np.zeros(5), t_final=1.0, dt=0.1)
    assert err.value.field == "model"
    with pytest.raises(ParameterError, match="`params` is required") as err:
        Problem(model=NOMOTO2, x0=np.zeros(5), t_final=1.0, dt=0.1)
    with pytest.raises(ParameterError, match="`t_final` is required"):
        simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros(5), dt=0.1)


def test_a_problem_is_frozen_picklable_and_run_once_validated():
    problem = Problem(model="nomoto2", params=get_ship("mariner-nomoto2").params,
                      x0=np.zeros(5), t_final=10.0, dt=0.1, controller="pid-heading",
                      controller_params=PIDHeadingParams(kp=1.0),
                      reference={"heading": 0.1}, bounds={"heading": (-1.0, 1.0)},
                      metadata={"title": "t"})
    with pytest.raises(dataclasses.FrozenInstanceError):
        problem.dt = 0.2
    with pytest.raises(TypeError):
        problem.bounds["heading"] = (0.0, 1.0)
    again = pickle.loads(pickle.dumps(problem))
    assert again.model.name == "nomoto2" and dict(again.bounds) == dict(problem.bounds)
    np.testing.assert_array_equal(simulate(again).state, simulate(problem).state)
    with pytest.raises(ParameterError, match="give a Problem or keyword arguments, not both"):
        simulate(problem, t_final=5.0)


SCENARIO = """
title = "t"
[vessel]
ship = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 20.0
dt = 0.1
{extra}
"""


def test_a_scenario_sets_exact_actuator():
    from seahelm.scenario import parse_scenario, run_scenario
    from seahelm.scenario.errors import ScenarioError

    off = parse_scenario(SCENARIO.format(extra="exact_actuator = false"))
    assert off.exact_actuator is False
    assert run_scenario(off).metadata["actuator_step"] == "integrated"
    assert run_scenario(parse_scenario(SCENARIO.format(extra=""))).metadata[
        "actuator_step"] == "closed-form"
    with pytest.raises(ScenarioError, match=r"\[simulation.exact_actuator\]"):
        parse_scenario(SCENARIO.format(extra='exact_actuator = "no"'))
