"""Linearisation (Richardson central differences) and steering indices: analytic Jacobians, a
linear model's own matrices, the Mariner's published Nomoto constants, python-control export,
the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.equilibria.linearisation import LinearModel, linearize, linearize_at, \
    richardson_jacobian
from seahelm.analysis.steering.indices import steering_indices
from seahelm.actuators.servo import RUDDER_SERVO, ServoParams
from seahelm.errors import ParameterError
from seahelm.vessels.nomoto import NOMOTO1, NOMOTO2, Nomoto1Params, Nomoto2Params

K, T1, T2, T3, U = 0.185, 118.0, 7.8, 18.5, 7.7175
N2 = Nomoto2Params(gain=K, t1=T1, t2=T2, t3=T3, speed=U, length=160.93)


def test_richardson_on_a_smooth_function():
    def f(X):
        x, y = X[:, 0], X[:, 1]
        return np.stack([np.sin(x) * np.exp(y), x ** 3 * y], axis=1)

    x0 = np.array([0.7, -0.3])
    J, err = richardson_jacobian(f, x0, [0.1, 0.1])
    exact = np.array([[math.cos(0.7) * math.exp(-0.3), math.sin(0.7) * math.exp(-0.3)],
                      [3 * 0.49 * -0.3, 0.343]])
    np.testing.assert_allclose(J, exact, rtol=0, atol=1e-12)
    assert np.all(np.abs(J - exact) <= err + 1e-15)  # the estimate bounds the error


@pytest.mark.parametrize("kwargs, match", [({"step": [0.0, 1.0]}, "step"),
                                           ({"step": [1.0, 1.0], "levels": 1}, "levels")])
def test_richardson_validation(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        richardson_jacobian(lambda X: X, np.zeros(2), **kwargs)


def nomoto2_matrices(heading=0.0, rudder=0.0):
    """A, B of NOMOTO2 (north, east, heading, yaw_rate, yaw_aux; rudder) by hand."""
    a = K * T3 / (T1 * T2)
    t12 = T1 * T2
    A = np.zeros((5, 5))
    A[0, 2] = -U * math.sin(heading)
    A[1, 2] = U * math.cos(heading)
    A[2, 3] = 1.0
    A[3, 4] = 1.0
    A[4, 3] = -1.0 / t12
    A[4, 4] = -(T1 + T2) / t12
    B = np.array([[0.0], [0.0], [0.0], [a], [(K - (T1 + T2) * a) / t12]])
    return A, B


@pytest.mark.parametrize("heading", [0.0, 0.4, -2.0])
def test_a_linear_model_returns_its_own_matrices(heading):
    x0 = NOMOTO2.initial_state(heading=heading, north=100.0, east=-50.0)
    lin = linearize_at(NOMOTO2, N2, x0, {"rudder_angle": 0.0})
    A, B = nomoto2_matrices(heading)
    scale = np.abs(A).max()
    np.testing.assert_allclose(lin.A, A, rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(lin.B, B, rtol=0, atol=1e-10 * np.abs(B).max())
    C = np.zeros((7, 5))
    C[:4, :4] = np.eye(4)
    np.testing.assert_allclose(lin.C, C, rtol=0, atol=1e-12)
    np.testing.assert_allclose(lin.D, 0.0, atol=1e-12)
    assert lin.state_labels == NOMOTO2.state_labels and lin.input_units == ("rad",)
    assert np.all(lin.error["A"] < 1e-9 * scale)  # the estimate: rounding of f ~ U over h


def test_the_steering_gear_and_disturbances_join_the_model():
    servo = ServoParams(max_angle=math.radians(35), max_rate=math.radians(5), time_constant=2.5)
    p = Nomoto1Params(gain=0.1, time_constant=40.0, speed=5.0)
    lin = linearize_at(NOMOTO1, p, NOMOTO1.initial_state(), [0.0], actuator=RUDDER_SERVO,
                       actuator_params=servo, disturbances=True)
    assert lin.state_labels == NOMOTO1.state_labels + ("rudder_angle",)
    assert lin.input_labels == ("rudder_command",) + NOMOTO1.disturbance_labels
    i_r, i_d = lin.state_labels.index("yaw_rate"), lin.state_labels.index("rudder_angle")
    assert lin.A[i_r, i_r] == pytest.approx(-1 / 40.0, rel=1e-10)
    assert lin.A[i_r, i_d] == pytest.approx(0.1 / 40.0, rel=1e-10)
    assert lin.A[i_d, i_d] == pytest.approx(-1 / 2.5, rel=1e-10)
    assert lin.B[i_d, 0] == pytest.approx(1 / 2.5, rel=1e-10)
    # the equivalent rudder disturbance enters as the rudder does; sway drift moves the ship east
    j = lin.input_labels.index("rudder_disturbance")
    assert lin.B[i_r, j] == pytest.approx(0.1 / 40.0, rel=1e-10)
    assert lin.B[lin.state_labels.index("east"), lin.input_labels.index("sway_velocity")] == \
        pytest.approx(1.0, rel=1e-10)


def test_mariner_gives_the_published_nomoto_constants(mariner_linear):
    """K, T1, T2, T3 within 1 % of 0.185 1/s, 118 s, 7.8 s, 18.5 s (Chislett & Strøm-Tejsen
    1965, as in MSS), at the trimmed straight run at U0 = 7.7175 m/s."""
    si = steering_indices(mariner_linear)
    n = si.nomoto
    assert n.gain == pytest.approx(0.185, rel=0.01)
    assert n.t1 == pytest.approx(118.0, rel=0.01)
    assert n.t2 == pytest.approx(7.8, rel=0.01)
    assert n.t3 == pytest.approx(18.5, rel=0.01)
    assert n.time_constant == pytest.approx(118 + 7.8 - 18.5, rel=0.01)
    assert si.course_stable and si.stability_index < 0 and si.stability_lever > 0
    assert si.surge_coupling < 1e-5
    assert np.max(mariner_linear.error["A"]) < 1e-7


def test_mariner_with_its_steering_gear(mariner_linear):
    lin = linearize("mariner-nonlinear")
    assert lin.input_labels == ("rudder_command",)
    assert lin.state_labels[-1] == "rudder_angle"
    np.testing.assert_allclose(lin.A[:6, :6], mariner_linear.A, rtol=0, atol=1e-9)
    assert lin.A[-1, -1] == pytest.approx(-1.0, rel=1e-9)  # MARINER_SERVO: lag 1 s
    with pytest.raises(ParameterError, match="without its steering gear"):
        steering_indices(lin)


def test_a_course_unstable_ship_has_negative_t1():
    # the KVLCC2's straight run is a kink (issue 45): its beta_R < 0 side is course-unstable
    lin = linearize("kvlcc2-full", actuator=False)
    si = steering_indices(lin.sides[0])
    assert not si.course_stable and si.nomoto.t1 < 0 and si.stability_index > 0


def test_constant_speed_models_return_their_constants():
    si = steering_indices(linearize("mariner-nomoto2", actuator=False))
    n = si.nomoto
    assert (n.gain, n.t1, n.t2, n.t3) == pytest.approx((0.185, 118.0, 7.8, 18.5), rel=1e-10)


def test_export_to_python_control_keeps_the_names(mariner_linear):
    ct = pytest.importorskip("control")
    sys = mariner_linear.to_control()
    assert list(sys.state_labels) == list(mariner_linear.state_labels)
    assert list(sys.input_labels) == ["rudder_angle"]
    assert "yaw_rate" in sys.output_labels
    np.testing.assert_array_equal(sys.A, mariner_linear.A)
    block = mariner_linear.select(states=["sway_speed", "yaw_rate"], outputs=["yaw_rate"])
    assert float(ct.dcgain(block.to_control())) == pytest.approx(0.185, rel=0.01)
    arrays = mariner_linear.to_numpy()
    assert arrays["A"] is not mariner_linear.A
    assert arrays["state_labels"] == mariner_linear.state_labels


def test_select_and_its_validation(mariner_linear):
    sub = mariner_linear.select(states=["yaw_rate", "sway_speed"], outputs=["heading"])
    assert sub.A.shape == (2, 2) and sub.A[0, 0] == mariner_linear.A[2, 2]
    with pytest.raises(ParameterError, match="no state spam"):
        mariner_linear.select(states=["spam"])
    with pytest.raises(ParameterError, match=r"must have shape \(1, 1\)"):
        LinearModel(A=np.zeros((2, 2)), B=np.zeros((1, 1)), C=np.zeros((1, 1)),
                    D=np.zeros((1, 1)), state_labels=("a",), state_units=("-",),
                    input_labels=("u",), input_units=("-",), output_labels=("y",),
                    output_units=("-",), x0=np.zeros(1), u0=np.zeros(1), y0=np.zeros(1))


@pytest.mark.parametrize("kwargs, match", [
    ({"x0": np.zeros(3)}, "must have 5 states"),
    ({"u0": {"propeller_rps": 1.0}}, "no model input propeller_rps"),
    ({"actuator": RUDDER_SERVO}, "actuator_params"),
    ({"step": -1.0}, "step"),
])
def test_linearize_at_validation(kwargs, match):
    args = {"x0": NOMOTO2.initial_state(), "u0": [0.0]} | kwargs
    x0, u0 = args.pop("x0"), args.pop("u0")
    with pytest.raises(ParameterError, match=match):
        linearize_at(NOMOTO2, N2, x0, u0, **args)


def test_linearize_refuses_what_has_no_equilibrium():
    with pytest.raises(ParameterError, match="speed"):
        linearize("kvlcc2-l7", speed=0.0)
    with pytest.raises(ParameterError, match="nominal speed"):
        linearize("mariner-nonlinear", speed=5.0)


# -- CLI ---------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def runner():
    return CliRunner()


def test_cli_linearize_json(runner):
    from seahelm.cli.main import app

    res = runner.invoke(app, ["linearize", "mariner-nonlinear", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    ind = out["indices"]
    assert ind["K_per_s"] == pytest.approx(0.185, rel=0.01)
    assert ind["T1_s"] == pytest.approx(118, rel=0.01)
    assert out["linear_model"]["input_labels"] == ["rudder_command"]
    assert len(out["linear_model"]["A"]) == 7


def test_cli_linearize_table_and_matrices(runner):
    from seahelm.cli.main import app

    res = runner.invoke(app, ["linearize", "mariner-nomoto2", "--matrices"])
    assert res.exit_code == 0, res.output
    assert "Nomoto K" in res.stdout and "course stable" in res.stdout
    assert "B (max. est. error" in res.stdout


@pytest.mark.parametrize("args, match", [
    (["kvlcc2-l7", "--speed", "0"], "--speed"),
    (["mariner-nonlinear", "--speed", "5"], "nominal speed"),
    (["mariner-nonlinear", "--rudder", "95"], "--rudder"),
])
def test_cli_linearize_bad_input_exits_2(runner, args, match):
    from seahelm.cli.main import app

    res = runner.invoke(app, ["linearize", *args])
    assert res.exit_code == 2
    assert match in res.output


def test_forced_response_of_the_export_equals_seahelms_simulation():
    """python-control's forced_response of the exported linear Nomoto-2 ship, sampled with a
    zero-order hold at the controller period (1 s, exact for a held rudder), equals seahelm's
    RK4 simulation (step 0.01 s) of the same model under the same held rudder to 1e-9 [rad] in
    heading and 1e-9 [rad/s] in yaw rate: the comparison is at the engine's discretisation of
    the input (held over each controller period), with an integration step fine enough that
    RK4's error (O(h⁴), ~1e-13 here) is below the tolerance."""
    ct = pytest.importorskip("control")
    from seahelm.actuators.servo import DIRECT
    from seahelm.control.open_loop import OPEN_LOOP
    from seahelm.simulation.engine import simulate

    lin = linearize_at(NOMOTO2, N2, NOMOTO2.initial_state(), [0.0]).select(
        states=["heading", "yaw_rate", "yaw_aux"], outputs=["heading", "yaw_rate"])
    sysd = ct.sample_system(lin.to_control(), 1.0, method="zoh")
    rng = np.random.default_rng(3)
    steps = 300
    rudder = np.radians(rng.uniform(-10, 10, steps + 1))
    res_ct = ct.forced_response(sysd, T=np.arange(steps + 1.0), U=rudder)
    t_grid = np.arange(0.0, steps + 0.005, 0.01)
    held = rudder[np.minimum((t_grid + 1e-9).astype(int), steps)]
    sim = simulate(NOMOTO2, N2, NOMOTO2.initial_state(), t_final=float(steps), dt=0.01,
                   actuator=DIRECT, controller=OPEN_LOOP, controller_dt=1.0,
                   reference={"rudder_angle": held[:, None]})
    every = 100
    np.testing.assert_allclose(sim["heading"][0, ::every], res_ct.outputs[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(sim["yaw_rate"][0, ::every], res_ct.outputs[1], rtol=0,
                               atol=1e-9)
