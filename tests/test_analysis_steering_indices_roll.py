"""Steering indices of a model with roll (Son & Nomoto's container ship): roll residualised
(quasi-static), the whole block's poles, and ``seahelm linearize`` giving what the library gives
(issue 45, item 3)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.equilibria.linearisation import LinearModel, linearize
from seahelm.analysis.steering.indices import steering_indices
from seahelm.cli.main import app
from seahelm.hydrodynamics.linear_model import nomoto_from_state_space

runner = CliRunner()
STATES = ("sway_speed", "yaw_rate", "roll_rate", "roll_angle")


def _model(A: np.ndarray, b: np.ndarray) -> LinearModel:
    return LinearModel(A=A, B=b[:, None], C=np.zeros((0, 4)), D=np.zeros((0, 1)),
                       state_labels=STATES, state_units=("m/s", "rad/s", "rad/s", "rad"),
                       input_labels=("rudder_angle",), input_units=("rad",), output_labels=(),
                       output_units=(), x0=np.zeros(4), u0=np.zeros(1), y0=np.zeros(0),
                       speed=7.0, length=175.0)


def test_roll_that_does_not_touch_steering_changes_nothing():
    A = np.zeros((4, 4))
    A[:2, :2] = [[-0.02, -2.8], [-0.001, -0.1]]
    A[2:, 2:] = [[-0.02, -0.045], [1.0, 0.0]]
    A[2, :2] = [0.002, -0.3]  # steering drives roll, roll does not drive steering
    b = np.array([-0.057, 0.0028, 0.004, 0.0])
    ind = steering_indices(_model(A, b))
    ref = nomoto_from_state_space(A[:2, :2], b[:2], speed=7.0, yaw_rate_index=1,
                                  require_stable=False)
    assert (ind.nomoto.gain, ind.nomoto.t1, ind.nomoto.t2, ind.nomoto.t3) == pytest.approx(
        (ref.gain, ref.t1, ref.t2, ref.t3), rel=1e-12)
    assert ind.roll_coupling == 0.0
    assert len(ind.poles) == 4 and ind.steering_states == STATES


@pytest.fixture(scope="module")
def container():
    return linearize("son-nomoto-container", actuator=False)


def test_container_indices_keep_the_full_models_steady_gain_and_poles(container):
    ind = steering_indices(container)
    idx = [container.state_labels.index(s) for s in STATES]
    A = container.A[np.ix_(idx, idx)]
    b = container.B[idx, container.input_labels.index("rudder_angle")]
    steady = -np.linalg.solve(A, b)  # the heeled ship's steady turn per radian of rudder
    assert ind.nomoto.gain == pytest.approx(steady[1], rel=1e-10)
    poles = np.linalg.eigvals(A)
    np.testing.assert_allclose(np.sort_complex(ind.poles), np.sort_complex(poles), rtol=1e-12)
    real = np.sort(poles[np.abs(poles.imag) < 1e-12].real)  # the roll mode is the complex pair
    # roll quasi-static: T1, T2 within 5 % of the full model's non-oscillatory poles
    assert -1 / ind.nomoto.t2 == pytest.approx(real[0], rel=0.05)
    assert -1 / ind.nomoto.t1 == pytest.approx(real[1], rel=0.05)
    assert ind.course_stable and ind.nomoto.t1 > 0
    assert 0.05 < ind.roll_coupling < 1.0  # heel matters for this ship


def test_cli_linearize_container_gives_the_library_numbers(container):
    res = runner.invoke(app, ["linearize", "son-nomoto-container", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    ind = steering_indices(container)
    assert data["indices"]["K_per_s"] == pytest.approx(ind.nomoto.gain, rel=1e-12)
    assert data["indices"]["T1_s"] == pytest.approx(ind.nomoto.t1, rel=1e-12)
    assert data["indices"]["roll_coupling"] == pytest.approx(ind.roll_coupling, rel=1e-12)
    assert len(data["indices"]["poles_per_s"]) == 4
    full = linearize("son-nomoto-container")
    np.testing.assert_allclose(np.array(data["linear_model"]["A"]), full.A, rtol=0, atol=0)
    table = runner.invoke(app, ["linearize", "son-nomoto-container", "--matrices"],
                          terminal_width=200)
    assert table.exit_code == 0, table.output
    assert "roll coupling" in table.stdout and "roll_angle" in table.stdout
