"""Equilibria: self-propulsion rps, steady turns, straight approach (MMG and Mariner)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.equilibria.equilibrium import (
    EquilibriumError,
    approach_state,
    self_propulsion_rps,
    steady_turn,
)
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR, MARINER_SERVO
from seahelm.vessels.mmg import KVLCC2_FULL, KVLCC2_L7, KVLCC2_L7_SERVO, MMG

U0_L7 = 1.179
SYMMETRIC = KVLCC2_L7.replace(gamma_R_minus=0.5, gamma_R_plus=0.5, C_2_minus=1.3, C_2_plus=1.3)


def rps_by_hand(p, U):
    """Straight run: (1 − t_P) ρ n² D⁴ K_T(J) = ½ρLdU² R'_0 with J = U(1 − w_P0)/(nD), a
    quadratic in n."""
    T = 0.5 * p.rho * p.length * p.draft * U**2 * p.R_0 / (1 - p.t_P)
    D, uP = p.propeller_diameter, U * (1 - p.w_P0)
    a = p.rho * p.k_0 * D**4
    b = p.rho * p.k_1 * D**3 * uP
    c = p.rho * p.k_2 * D**2 * uP**2 - T
    return (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)


@pytest.fixture(scope="module")
def rps_l7():
    return self_propulsion_rps(KVLCC2_L7, U0_L7)


def test_self_propulsion_rps_matches_the_quadratic(rps_l7):
    assert rps_l7 == pytest.approx(rps_by_hand(KVLCC2_L7, U0_L7), rel=1e-12)
    assert isinstance(rps_l7, float)
    speeds = np.array([[5.0, 15.5 * 1852 / 3600]])
    n = self_propulsion_rps(KVLCC2_FULL, speeds)
    assert n.shape == (1, 2)
    np.testing.assert_allclose(n[0], [rps_by_hand(KVLCC2_FULL, s) for s in speeds[0]],
                               rtol=1e-12)
    # the derivative really has zero surge acceleration there
    dx = MMG.derivative(0.0, [U0_L7, 0, 0, 0, 0, 0], [0.0, rps_l7], KVLCC2_L7)
    assert abs(dx[0]) < 1e-12


@pytest.mark.parametrize(
    "kwargs, error, match",
    [
        (dict(speed=-1.0), ParameterError, r"`speed` must be > 0 \[m/s\], got -1.0"),
        (dict(speed=[1.0, 0.0]), ParameterError, r"`speed` must be > 0 \[m/s\]"),
        (dict(speed=1.179, max_rps=5.0), EquilibriumError,
         r"no propeller rps in \(0, 5\] \[1/s\] gives zero surge force at `speed` = 1.179"),
        (dict(speed=1.179, max_rps=0.0), ParameterError, r"`max_rps` must be > 0 \[1/s\]"),
    ],
)
def test_self_propulsion_errors(kwargs, error, match):
    with pytest.raises(error, match=match):
        self_propulsion_rps(KVLCC2_L7, **kwargs)


def test_self_propulsion_needs_a_propeller():
    with pytest.raises(ParameterError, match=r"model 'mariner' has no input 'propeller_rps'"):
        self_propulsion_rps(MARINER_NONLINEAR, 7.7)


def test_self_propulsion_without_a_root():
    # a propeller whose thrust never grows with rps (k_0 < 0)
    bad = KVLCC2_L7.replace(k_0=-0.1)
    with pytest.raises(EquilibriumError, match=r"no propeller rps"):
        self_propulsion_rps(bad, 1.0, max_rps=100.0)


# ------------------------------------------------------------------------------------------
# steady turns
# ------------------------------------------------------------------------------------------
def residual(model, params, turn, rudder, rps=None):
    if model is MMG:
        x, u = [turn.surge_speed, turn.sway_speed, turn.yaw_rate, 0, 0, 0], [rudder, rps]
    else:
        x, u = [turn.surge_speed - 7.7175, turn.sway_speed, turn.yaw_rate, 0, 0, 0], [rudder]
    return model.derivative(0.0, x, u, params)[:3]


@pytest.mark.parametrize("rudder_deg", [35.0, -35.0, 10.0, -10.0, -1.0, 2.0])
def test_steady_turn_is_an_equilibrium(rps_l7, rudder_deg):
    d = math.radians(rudder_deg)
    turn = steady_turn(KVLCC2_L7, d, rps_l7)
    assert np.max(np.abs(residual(MMG, KVLCC2_L7, turn, d, rps_l7))) < 1e-10
    assert math.copysign(1.0, turn.yaw_rate) == math.copysign(1.0, d)
    assert turn.speed == pytest.approx(math.hypot(turn.surge_speed, turn.sway_speed))
    assert turn.drift_angle == pytest.approx(math.atan2(-turn.sway_speed, turn.surge_speed))
    assert turn.radius == pytest.approx(turn.speed / abs(turn.yaw_rate))


def test_steady_turn_arrays_and_mirror_of_the_symmetric_variant(rps_l7):
    d = np.radians([20.0, -20.0])
    turn = steady_turn(SYMMETRIC, d, rps_l7)
    assert turn.yaw_rate.shape == (2,)
    assert turn.surge_speed[1] == pytest.approx(turn.surge_speed[0], rel=1e-10)
    assert turn.sway_speed[1] == pytest.approx(-turn.sway_speed[0], rel=1e-10)
    assert turn.yaw_rate[1] == pytest.approx(-turn.yaw_rate[0], rel=1e-10)
    standard = steady_turn(KVLCC2_L7, d, rps_l7)
    assert abs(standard.yaw_rate[1] + standard.yaw_rate[0]) > 0.01 * standard.yaw_rate[0]


def test_steady_turn_is_where_the_35_deg_turning_circle_ends(rps_l7):
    res = simulate(MMG, KVLCC2_L7, np.array([U0_L7, 0, 0, 0, 0, 0]), t_final=300.0, dt=0.05,
                   actuator=RUDDER_SERVO, actuator_params=KVLCC2_L7_SERVO, controller=OPEN_LOOP,
                   reference={"rudder_command": math.radians(35.0), "propeller_rps": rps_l7})
    turn = steady_turn(KVLCC2_L7, math.radians(35.0), rps_l7)
    end = res.state[0, -1, :3]
    np.testing.assert_allclose(end, [turn.surge_speed, turn.sway_speed, turn.yaw_rate],
                               rtol=1e-6)


def test_mariner_zero_rudder_turn_is_where_the_simulation_settles():
    res = simulate(MARINER, MARINER_NONLINEAR, np.zeros(6), t_final=3000.0, dt=0.1,
                   actuator=RUDDER_SERVO, actuator_params=MARINER_SERVO, controller=OPEN_LOOP,
                   reference={"rudder_command": 0.0})
    turn = steady_turn(MARINER_NONLINEAR, 0.0)
    assert turn.yaw_rate > 0  # the Y_0/N_0 bias turns it to starboard
    np.testing.assert_allclose(res["yaw_rate"][0, -1], turn.yaw_rate, rtol=1e-5)
    np.testing.assert_allclose(res["surge_speed"][0, -1], turn.surge_speed, rtol=1e-6)
    both = steady_turn(MARINER_NONLINEAR, np.radians([35.0, -35.0]), max_rudder=math.radians(40))
    assert both.yaw_rate[0] > 1.01 * -both.yaw_rate[1] > 0
    for turn_, d in zip(zip(*both), np.radians([35.0, -35.0])):
        t = type(turn)(*turn_)
        assert np.max(np.abs(residual(MARINER, MARINER_NONLINEAR, t, d))) < 1e-12


@pytest.mark.parametrize(
    "args, kwargs, match",
    [
        ((math.radians(36.0), 10.0), {}, r"`rudder` must be in \[-0.610865, 0.610865\] \[rad\], "
                                         r"got 0.628318"),
        ((0.5, 10.0), dict(max_rudder=0.4), r"`rudder` must be in \[-0.4, 0.4\] \[rad\]"),
        ((0.1, 0.0), {}, r"`rps` must be > 0 \[1/s\], got 0.0"),
        ((0.1, -3.0), {}, r"`rps` must be > 0 \[1/s\], got -3.0"),
        ((0.1,), {}, r"`rps` \[1/s\] is required for model 'mmg'"),
        ((0.1, 10.0), dict(model=MARINER), r"model 'mariner' takes MarinerParams, got MMGParams"),
    ],
)
def test_steady_turn_validation(args, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        steady_turn(KVLCC2_L7, *args, **kwargs)


def test_steady_turn_mariner_takes_no_rps():
    with pytest.raises(ParameterError, match=r"`rps`: model 'mariner' has no propeller_rps"):
        steady_turn(MARINER_NONLINEAR, 0.1, 2.0)


# ------------------------------------------------------------------------------------------
# straight approach
# ------------------------------------------------------------------------------------------
def test_approach_state_mmg(rps_l7):
    a = approach_state(KVLCC2_L7, heading=0.5)
    np.testing.assert_array_equal(a.state, [U0_L7, 0, 0, 0, 0, 0.5])
    assert a.inputs == {"rudder_angle": 0.0, "propeller_rps": rps_l7}
    b = approach_state(KVLCC2_L7, 1.0, trim=True)
    assert b.state[0] == pytest.approx(1.0) and b.inputs["rudder_angle"] == pytest.approx(0.0)
    assert b.inputs["propeller_rps"] == pytest.approx(rps_by_hand(KVLCC2_L7, 1.0), rel=1e-12)


def test_approach_state_mariner_trim():
    a = approach_state(MARINER_NONLINEAR)
    np.testing.assert_array_equal(a.state, np.zeros(6))
    assert a.inputs == {"rudder_angle": 0.0}
    t = approach_state(MARINER_NONLINEAR, trim=True)
    assert t.state[2] == 0.0 and t.inputs["rudder_angle"] < 0  # port rudder against the bias
    dx = MARINER.derivative(0.0, t.state, [t.inputs["rudder_angle"]], MARINER_NONLINEAR)
    assert np.max(np.abs(dx[:3])) < 1e-12


@pytest.mark.parametrize(
    "params, kwargs, match",
    [
        (KVLCC2_L7, dict(speed=-0.5), r"`speed` must be > 0 \[m/s\], got -0.5"),
        (MARINER_NONLINEAR, dict(speed=5.0),
         r"`speed` must be the nominal speed U_0 = 7.7175 \[m/s\] .* got 5.0"),
        (KVLCC2_L7, dict(heading=float("nan")), r"`heading` must be finite \[rad\]"),
    ],
)
def test_approach_state_validation(params, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        approach_state(params, **kwargs)


def test_unknown_parameter_type():
    from seahelm.actuators.servo import ServoParams

    with pytest.raises(ParameterError, match=r"no default model for ServoParams; pass `model=`"):
        steady_turn(ServoParams(), 0.1)
