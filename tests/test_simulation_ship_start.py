"""A Problem built from a ship without ``x0`` starts on its trimmed straight approach.

Before: ``Problem(ship="kvlcc2-l7", t_final=..., dt=...)`` raised "`x0` is required"; the CLI's
manoeuvres start from the ship's straight approach, and so does a Problem now. A straight run
is checked by what it must do (keep its speed, not turn), against the one-run scipy solver
(:func:`seahelm.analysis.equilibria.equilibrium.approach_state`), not the batched one the default uses.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem


@pytest.mark.parametrize("name", ["kvlcc2-l7", "mariner-nonlinear", "son-nomoto-container"])
def test_a_ship_alone_goes_straight_at_its_test_speed(name):
    ship = get_ship(name)
    problem = Problem(ship=name, t_final=60.0, dt=0.1)
    scipy = approach_state(ship, ship.approach_speed, trim=True)
    np.testing.assert_allclose(problem.x0, scipy.state, rtol=1e-7, atol=1e-9)
    # the steering gear starts at the trim angle, the open loop holds the approach's inputs
    assert problem.actuator_x0[0] == pytest.approx(scipy.inputs["rudder_angle"], abs=1e-9)
    assert problem.reference["rudder_command"] == pytest.approx(scipy.inputs["rudder_angle"],
                                                                abs=1e-9)
    if "propeller_rps" in scipy.inputs:
        assert problem.reference["propeller_rps"] == pytest.approx(
            scipy.inputs["propeller_rps"], rel=1e-7)
    result = simulate(problem)
    for label in ("surge_speed", "yaw_rate"):  # an equilibrium: it keeps its speed, no turn
        np.testing.assert_allclose(result[label][0], result[label][0, 0], rtol=1e-6, atol=1e-9)
    assert np.max(np.abs(result["heading"][0])) < 1e-6  # and its heading


def test_given_inputs_are_kept():
    ref = {"rudder_command": math.radians(35.0), "propeller_rps": 10.0}
    problem = Problem(ship="kvlcc2-l7", t_final=10.0, dt=0.1, reference=ref,
                      actuator_x0=[0.1])
    assert problem.reference is ref and problem.actuator_x0 == [0.1]
    assert problem.x0[0] == pytest.approx(get_ship("kvlcc2-l7").approach_speed)


def test_one_approach_per_parameter_set():
    ship = get_ship("kvlcc2-l7")
    slower = ship.params.replace(approach_speed=0.8)  # (U_0 is the ship's test speed)
    problem = Problem(ship=ship, params=[ship.params, slower], t_final=10.0, dt=0.1)
    assert problem.x0.shape == (2, 6) and problem.reference["propeller_rps"].shape == (2, 1, 1)


@pytest.mark.parametrize("name", ["otter", "supply", "shushlyapin2017-dp"])
def test_a_craft_without_a_test_speed_is_told_how_to_give_x0(name):
    with pytest.raises(ParameterError, match=f"ship '{name}' has no test speed.*give the "
                                             "initial state") as err:
        Problem(ship=name, t_final=10.0, dt=0.1)
    assert err.value.field == "x0"


def test_a_craft_without_a_rudder_input_defaults_to_no_servo():
    # before: "actuator output 'rudder_angle' is not an input of the model" for the Otter's x0
    otter = get_ship("otter")
    x0 = np.zeros(otter.model.n_states)
    assert Problem(ship=otter, x0=x0, t_final=1.0, dt=0.05).actuator is DIRECT
