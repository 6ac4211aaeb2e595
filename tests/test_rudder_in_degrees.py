"""A rudder told to turn beyond a right angle is degrees given as radians: refused, by name,
before anything is compiled (``reference`` of a problem, ``commands`` of a step); a command
of ``None`` is named as ``None``, not as the nan numpy would make of it."""

import math

import numpy as np
import pytest

from seahelm import simulate
from seahelm.errors import ParameterError
from seahelm.simulation.inputs import MAX_RUDDER_ANGLE, check_rudder_angles
from seahelm.simulation.stepping_io import check_commands

LABELS = ("rudder_command", "propeller_rps_command")
UNITS = ("rad", "1/s")


def test_a_problem_with_a_rudder_reference_in_degrees_is_refused_naming_it():
    with pytest.raises(ParameterError) as err:
        simulate(ship="kvlcc2-l7", t_final=10.0, dt=0.1,
                 reference={"rudder_command": 35.0, "propeller_rps": 1.6})
    text = str(err.value)
    assert err.value.field == "reference"
    assert "'rudder_command' reaches 35 rad" in text
    assert f"{math.radians(35.0):.6g} rad" in text  # what the user meant, in radians


def test_the_limit_is_a_right_angle_and_only_rudders_in_radians_are_held_to_it():
    check_rudder_angles("reference", np.array([[[MAX_RUDDER_ANGLE, 0.0]]]), LABELS, UNITS)
    check_rudder_angles("reference", np.array([[[-1.0, 0.0]]]), LABELS, UNITS)
    # a heading, an rps or an azimuth angle is not a rudder
    check_rudder_angles("reference", np.array([[[35.0, 35.0]]]), ("heading", "rps"),
                        ("rad", "1/s"))
    check_rudder_angles("reference", np.array([[[0.0, 35.0]]]), LABELS, UNITS)
    with pytest.raises(ParameterError, match="reaches -1.5708 rad"):
        check_rudder_angles("reference", np.array([[[0.0, 0.0], [-MAX_RUDDER_ANGLE - 1e-9,
                                                                  0.0]]]), LABELS, UNITS)
    assert MAX_RUDDER_ANGLE == pytest.approx(math.pi / 2)


@pytest.mark.parametrize("commands", [[35.0, 1.0], {"rudder_command": 35.0},
                                      np.array([[0.1, 1.0], [-35.0, 1.0]])])
def test_a_step_command_in_degrees_is_refused(commands):
    sel = np.arange(2)
    with pytest.raises(ParameterError,
                       match=r"'rudder_command' of run [01] reaches -?35 rad") as err:
        check_commands(commands, sel, np.zeros((2, 2)), LABELS, UNITS)
    assert err.value.field == "commands"


@pytest.mark.parametrize("commands", [[None, 1.0], {"rudder_command": None}, None,
                                      np.array([None, 1.0], dtype=object)])
def test_a_command_of_none_is_named_none_not_nan(commands):
    with pytest.raises(ParameterError) as err:
        check_commands(commands, np.arange(1), np.zeros((1, 2)), LABELS, UNITS)
    assert "None" in str(err.value) and "nan" not in str(err.value)


def test_radians_within_the_limit_pass_unchanged():
    got = check_commands([0.6, 1.5], np.arange(2), np.zeros((2, 2)), LABELS, UNITS)
    np.testing.assert_array_equal(got, [[0.6, 1.5], [0.6, 1.5]])


def test_the_error_names_the_run_and_the_sign_in_a_batch():
    # a per-run reference (runs, 1, channels): run 1 is the one in degrees, to port
    ref = np.array([[[0.1, 1.0]], [[-35.0, 1.0]], [[0.2, 1.0]]])
    with pytest.raises(ParameterError, match=r"'rudder_command' of run 1 reaches -35 rad") as err:
        check_rudder_angles("reference", ref, LABELS, UNITS)
    assert err.value.run == 1 and err.value.value == -35.0
    # a step of selected runs names the simulator's run, not the row
    with pytest.raises(ParameterError, match="of run 7 reaches 35 rad") as err:
        check_commands([[0.1, 1.0], [35.0, 1.0]], np.array([4, 7]), np.zeros((2, 2)),
                       LABELS, UNITS)
    assert err.value.run == 7
    # one run: no run named
    with pytest.raises(ParameterError) as err:
        check_rudder_angles("reference", np.array([[[35.0, 1.0]]]), LABELS, UNITS)
    assert err.value.run is None and "of run" not in str(err.value)
