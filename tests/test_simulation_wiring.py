"""Engine v2: components wired by signal name (composition), several inputs and disturbances."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from wiring_components import (
    P_TWIN,
    TWIN,
    TWO_CHANNEL,
    GainParams,
    PParams,
    TwinParams,
)

from seahelm.actuators.servo import DIRECT, RUDDER_SERVO
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.simulation.composition import compose
from seahelm.simulation.engine import simulate


def first_order(x0, rate, forcing, t):
    """x' = −rate·x + forcing, constant forcing: the closed form."""
    return forcing / rate + (x0 - forcing / rate) * np.exp(-rate * t)


def test_two_inputs_and_two_disturbances_by_name_through_a_two_channel_actuator():
    # open-loop P controller (gains 0 would give zero commands): use the references as
    # set-points with unit gain on a model whose outputs start at zero, ZOH every step
    p = TwinParams(a=0.5, b=2.0, c=0.25, e=3.0)
    g = GainParams(rudder_gain=0.5, rps_gain=2.0)
    res = simulate(TWIN, p, [0.0, 0.0], t_final=30.0, dt=0.01, actuator=TWO_CHANNEL,
                   actuator_params=g, controller=P_TWIN,
                   controller_params=PParams(k_speed=0.0, k_turn=0.0),
                   reference={"speed": 1.0, "turn": 0.2},
                   disturbance={"moment_z": -0.1, "force_x": 0.3})
    t = res.time
    np.testing.assert_allclose(res["speed"][0], first_order(0.0, 0.5, 0.3, t), atol=1e-9)
    np.testing.assert_allclose(res["turn"][0], first_order(0.0, 0.25, -0.1, t), atol=1e-9)
    assert res.output_labels == ("turn", "speed", "thrust")


def test_commands_reach_the_right_inputs_whatever_the_declaration_order():
    """Controller commands (rps, rudder), actuator channels (rudder, rps) and model inputs
    (rps, rudder) are declared in different orders; a positional wiring would swap them."""
    p = TwinParams(a=0.5, b=2.0, c=0.25, e=3.0)
    g = GainParams(rudder_gain=0.5, rps_gain=2.0)
    k_speed, k_turn, r_speed, r_turn = 0.4, 0.1, 1.0, 0.2
    res = simulate(TWIN, p, [0.0, 0.0], t_final=60.0, dt=0.005, actuator=TWO_CHANNEL,
                   actuator_params=g, controller=P_TWIN,
                   controller_params=PParams(k_speed=k_speed, k_turn=k_turn),
                   reference={"speed": r_speed, "turn": r_turn}, controller_dt=0.005)
    # continuous-time limit of the loops: x' = −a x + b·g_rps·k (r − x)  → steady state
    ks, kt = p.b * g.rps_gain * k_speed, p.e * g.rudder_gain * k_turn
    speed_ss = ks * r_speed / (p.a + ks)
    turn_ss = kt * r_turn / (p.c + kt)
    np.testing.assert_allclose(res["speed"][0, -1], speed_ss, rtol=1e-6)
    np.testing.assert_allclose(res["turn"][0, -1], turn_ss, rtol=1e-6)
    np.testing.assert_allclose(res["thrust"][0, -1], p.b * g.rps_gain * k_speed
                               * (r_speed - speed_ss), rtol=1e-3)


def test_pass_through_actuator_and_controller_take_the_input_names():
    wiring = compose(TWIN, DIRECT, OPEN_LOOP)
    assert wiring.references == ("propeller_rps", "rudder_angle")
    assert wiring.reference_units == ("1/s", "rad")
    p = TwinParams()
    res = simulate(TWIN, p, [1.0, 0.0], t_final=10.0, dt=0.01, actuator=DIRECT,
                   controller=OPEN_LOOP, reference={"rudder_angle": 0.1, "propeller_rps": 0.25})
    np.testing.assert_allclose(res["speed"][0], first_order(1.0, p.a, p.b * 0.25, res.time),
                               atol=1e-9)
    np.testing.assert_allclose(res["turn"][0], first_order(0.0, p.c, p.e * 0.1, res.time),
                               atol=1e-9)


def test_an_input_may_be_fed_directly_beside_an_actuator():
    """The rudder servo feeds rudder_angle; the open-loop controller feeds propeller_rps
    directly (no shaft dynamics) — a turning-circle set-up for a 3-DOF ship."""
    wiring = compose(TWIN, RUDDER_SERVO, OPEN_LOOP)
    assert wiring.commands == ("rudder_command", "propeller_rps")
    assert wiring.input_from == (("command", 1), ("actuator", 0))
    res = simulate(TWIN, TwinParams(), [0.0, 0.0], t_final=5.0, dt=0.01,
                   actuator=RUDDER_SERVO, controller=OPEN_LOOP,
                   reference={"rudder_command": math.radians(10), "propeller_rps": 0.5})
    assert res["rudder_angle"][0, -1] > 0.0  # the servo moved towards 10°
    np.testing.assert_allclose(res["thrust"][0, -1], 2.0 * 0.5)


@pytest.mark.parametrize(
    "change, match",
    [
        (dict(measurement_labels=("speed", "heading")),
         r"measures 'heading'.*model outputs: turn, speed, thrust"),
        (dict(command_labels=("propeller_rps_command", "rudder_command", "flap_command"),
              reference_labels=("speed", "turn")),
         r"command\(s\) flap_command feed nothing"),
        (dict(command_labels=("propeller_rps_command",)),
         r"actuator channel 'rudder_command' gets no command; the controller gives "
         r"propeller_rps_command"),
    ],
)
def test_miswired_controller_is_named(change, match):
    bad = dataclasses.replace(P_TWIN, **change)
    with pytest.raises(ParameterError, match=match):
        compose(TWIN, TWO_CHANNEL, bad)


def test_actuator_output_that_is_no_model_input_is_named():
    from seahelm.vessels.nomoto import NOMOTO1

    with pytest.raises(ParameterError, match=r"actuator output 'propeller_rps' is not an "
                                             r"input of the model \(model inputs: "
                                             r"rudder_angle\)"):
        compose(NOMOTO1, TWO_CHANNEL, P_TWIN)


def test_unfed_model_input_is_named():
    # the servo feeds rudder_angle; nothing feeds propeller_rps
    only_rudder = dataclasses.replace(P_TWIN, command_labels=("rudder_command",))
    with pytest.raises(ParameterError, match=r"model input 'propeller_rps' is not fed.*"
                                             r"actuator outputs: rudder_angle; controller "
                                             r"commands: rudder_command"):
        compose(TWIN, RUDDER_SERVO, only_rudder)


def test_disturbance_and_reference_by_unknown_name():
    with pytest.raises(ParameterError, match=r"unknown channel\(s\) 'wind'.*force_x, moment_z"):
        simulate(TWIN, TwinParams(), [0.0, 0.0], t_final=1.0, dt=0.1, actuator=DIRECT,
                 controller=OPEN_LOOP, disturbance={"wind": 1.0})
    with pytest.raises(ParameterError, match=r"must have 2 channel\(s\) \(force_x, moment_z\)"):
        simulate(TWIN, TwinParams(), [0.0, 0.0], t_final=1.0, dt=0.1, actuator=DIRECT,
                 controller=OPEN_LOOP, disturbance=[1.0, 2.0, 3.0])


def test_disturbance_time_series_by_name_per_run():
    t = np.arange(101) * 0.1
    ramp = np.stack([0.1 * t, 0.2 * t])  # two runs, a ramp each (exact for linear interpolation)
    res = simulate(TWIN, TwinParams(a=0.5, c=0.25), [0.0, 0.0], t_final=10.0, dt=0.1,
                   actuator=DIRECT, controller=OPEN_LOOP,
                   disturbance={"force_x": ramp[:, :, None]})
    # x' = −a x + s t, x(0) = 0 → x = s/a (t − (1 − e^{−a t})/a)
    for i, slope in enumerate((0.1, 0.2)):
        exact = slope / 0.5 * (t - (1 - np.exp(-0.5 * t)) / 0.5)
        np.testing.assert_allclose(res["speed"][i], exact, atol=1e-7)
    np.testing.assert_array_equal(res["turn"], 0.0)


def test_nonfinite_state_is_still_caught_under_fastmath():
    """The kernel is compiled with fastmath flags but without nnan/ninf, so the finiteness
    check is not optimised away: a state that overflows is caught at the step it happens,
    with its time and state, and the other run of the batch goes on.

    x' = −a x + F with F = 1e308, a = 0.5: x(t) = (F/a)(1 − e^{−a t}) passes the largest
    double (1.797e308) at t = −ln(1 − 1.797e308·a/F)/a ≈ 3.0 s."""
    force = np.array([[[1e308, 0.0]], [[1.0, 0.0]]])  # run 0 overflows, run 1 does not
    res = simulate(TWIN, TwinParams(a=0.5), [0.0, 0.0], t_final=10.0, dt=0.01,
                   actuator=DIRECT, controller=OPEN_LOOP, disturbance=force)
    assert res.status.tolist() == [1, 0]
    t_cross = -math.log(1.0 - np.finfo(float).max * 0.5 / 1e308) / 0.5
    assert abs(res.failure_time[0] - t_cross) < 0.02
    assert not np.isfinite(res.failure_state[0, 0])
    before = res.time < res.failure_time[0] - 1e-9
    assert np.isfinite(res["speed"][0][before]).all()
    np.testing.assert_allclose(res["speed"][1, -1], 2.0 * (1 - math.exp(-5.0)), rtol=1e-9)
