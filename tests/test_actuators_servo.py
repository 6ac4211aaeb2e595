"""Actuators: rudder servo, rudder + propeller shaft, direct pass-through (component level)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import (
    DIRECT,
    RUDDER_PROPELLER,
    RUDDER_SERVO,
    DirectParams,
    RudderPropellerParams,
    ServoParams,
)
from seahelm.errors import ParameterError
from seahelm.registry import get_actuator

RP = RudderPropellerParams(max_angle=math.radians(35.0), max_rate=math.radians(2.33),
                           time_constant=1.0, propeller_time_constant=8.0, max_rps=2.0,
                           max_rps_rate=0.05)


def _rhs(actuator, params, xa, ca):
    dxa = np.empty(len(xa))
    actuator.rhs(0.0, np.asarray(xa, float), np.asarray(ca, float), params.to_record(), dxa)
    return dxa


def _out(actuator, params, xa, ca, n):
    ya = np.empty(n)
    actuator.output(np.asarray(xa, float), np.asarray(ca, float), params.to_record(), ya)
    return ya


def test_declared_signals_and_registry():
    assert get_actuator("rudder-servo") is RUDDER_SERVO
    assert get_actuator("rudder-propeller") is RUDDER_PROPELLER
    assert get_actuator("direct") is DIRECT
    assert RUDDER_SERVO.command_labels == ("rudder_command",)
    assert RUDDER_SERVO.output_labels == ("rudder_angle",)
    assert RUDDER_PROPELLER.state_labels == ("rudder_angle", "propeller_rps")
    assert RUDDER_PROPELLER.command_labels == ("rudder_command", "propeller_rps_command")
    assert RUDDER_PROPELLER.output_labels == ("rudder_angle", "propeller_rps")
    assert RUDDER_PROPELLER.output_units == ("rad", "1/s")
    assert DIRECT.passthrough and DIRECT.n_commands == 0 and DIRECT.n_outputs == 0
    # the rudder limits are the servo's fields, by name
    assert set(ServoParams.field_names()) < set(RudderPropellerParams.field_names())
    assert isinstance(RP, ServoParams)


@pytest.mark.parametrize("rudder, cmd", [(0.0, 0.01), (0.1, -1.0), (-0.2, 0.9), (0.3, 0.3)])
def test_rudder_channel_is_the_rudder_servo(rudder, cmd):
    servo = ServoParams(**{n: getattr(RP, n) for n in ServoParams.field_names()})
    want = _rhs(RUDDER_SERVO, servo, [rudder], [cmd])[0]
    assert _rhs(RUDDER_PROPELLER, RP, [rudder, 1.0], [cmd, 1.0])[0] == want


def test_propeller_shaft_lag_with_rps_and_rate_limits():
    # small step: first-order lag (n_c − n)/T_n
    assert _rhs(RUDDER_PROPELLER, RP, [0.0, 1.0], [0.0, 1.2])[1] == pytest.approx(0.2 / 8.0)
    # large step: the acceleration is clipped to ±max_rps_rate
    assert _rhs(RUDDER_PROPELLER, RP, [0.0, 1.0], [0.0, 1.9])[1] == 0.05
    assert _rhs(RUDDER_PROPELLER, RP, [0.0, 1.0], [0.0, -1.9])[1] == -0.05
    # the command is saturated to ±max_rps (ahead and astern)
    slow = RP.replace(max_rps_rate=100.0)
    assert _rhs(RUDDER_PROPELLER, slow, [0.0, 1.9], [0.0, 5.0])[1] == pytest.approx(0.1 / 8.0)
    assert _rhs(RUDDER_PROPELLER, slow, [0.0, -1.9], [0.0, -5.0])[1] == pytest.approx(-0.1 / 8.0)
    assert _rhs(RUDDER_PROPELLER, slow, [0.0, 2.0], [0.0, 5.0])[1] == 0.0


def test_outputs_are_the_states():
    np.testing.assert_array_equal(_out(RUDDER_PROPELLER, RP, [0.1, 1.5], [0.3, 2.0], 2),
                                  [0.1, 1.5])
    np.testing.assert_array_equal(_out(RUDDER_SERVO, ServoParams(), [0.2], [0.0], 1), [0.2])


def test_direct_copies_command_channel_j_to_output_j():
    ya = _out(DIRECT, DirectParams(), np.empty(0), [0.3, -2.0], 2)
    np.testing.assert_array_equal(ya, [0.3, -2.0])


def test_propeller_parameters_are_required_and_validated():
    with pytest.raises(TypeError, match="propeller_time_constant"):
        RudderPropellerParams(max_rps=2.0, max_rps_rate=0.05)  # type: ignore[call-arg]
    with pytest.raises(ParameterError, match=r"`max_rps` must be in \(0, inf\] \[1/s\]"):
        RP.replace(max_rps=0.0)
    with pytest.raises(ParameterError, match=r"`max_rps_rate`.*\[1/s²\]"):
        RP.replace(max_rps_rate=-1.0)
    with pytest.raises(ParameterError, match=r"`propeller_time_constant`.*\[s\]"):
        RP.replace(propeller_time_constant=0.0)


# --- the closed-form step (``advance``) -----------------------------------------------------
def _advance(actuator, params, xa, ca, h):
    out = np.empty(len(xa))
    actuator.advance(float(h), np.asarray(xa, float), np.asarray(ca, float), params.to_record(),
                     out)
    return out


def _integrated(actuator, params, xa, ca, h, steps=20000):
    """The servo ODE integrated with RK4 at h/steps (the rate is continuous in the state)."""
    x = np.asarray(xa, float)
    dt = h / steps
    for _ in range(steps):
        k1 = _rhs(actuator, params, x, ca)
        k2 = _rhs(actuator, params, x + 0.5 * dt * k1, ca)
        k3 = _rhs(actuator, params, x + 0.5 * dt * k2, ca)
        k4 = _rhs(actuator, params, x + dt * k3, ca)
        x = x + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


# rudder from, command, time: inside the lag band (|e| <= rate * T = 2.33 deg), a ramp that
# ends inside the interval, a ramp that does not, the command beyond the angle limit, going
# to port, at rest on the target, zero time
ADVANCE_CASES = [(0.0, math.radians(1.0), 3.0), (0.0, math.radians(20.0), 12.0),
                 (0.0, math.radians(20.0), 4.0), (math.radians(-10.0), 1.5, 30.0),
                 (math.radians(30.0), math.radians(-25.0), 10.0), (0.2, 0.2, 5.0),
                 (0.1, -0.3, 0.0)]


@pytest.mark.parametrize("rudder, cmd, h", ADVANCE_CASES)
def test_closed_form_step_is_the_integrated_servo(rudder, cmd, h):
    servo = ServoParams(max_angle=math.radians(35.0), max_rate=math.radians(2.33),
                        time_constant=1.0)
    got = _advance(RUDDER_SERVO, servo, [rudder], [cmd], h)
    want = _integrated(RUDDER_SERVO, servo, [rudder], [cmd], h, steps=max(1, int(2000 * h)))
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-10)
    # both channels of the rudder + propeller servo, the shaft accelerating at its limit
    got = _advance(RUDDER_PROPELLER, RP, [rudder, 0.5], [cmd, 1.8], h)
    want = _integrated(RUDDER_PROPELLER, RP, [rudder, 0.5], [cmd, 1.8], h,
                       steps=max(1, int(2000 * h)))
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-10)


def test_closed_form_step_ramp_then_lag_by_hand():
    # 20 deg from rest at 2.33 deg/s, T = 1 s: the ramp ends 2.33 deg short of the target at
    # t1 = (20 - 2.33)/2.33 s, then the error decays as 2.33 deg * exp(-(t - t1)/T)
    servo = ServoParams(max_angle=math.radians(35.0), max_rate=math.radians(2.33),
                        time_constant=1.0)
    t1 = (20.0 - 2.33) / 2.33
    for t in (0.5 * t1, t1, t1 + 0.7, t1 + 5.0):
        want = 2.33 * t if t <= t1 else 20.0 - 2.33 * math.exp(-(t - t1))
        got = math.degrees(_advance(RUDDER_SERVO, servo, [0.0], [math.radians(20.0)], t)[0])
        assert got == pytest.approx(want, abs=1e-12)


def test_closed_form_step_composes_over_time():
    # the exact solution of an autonomous ODE: advancing by a then by b is advancing by a + b
    for rudder, cmd, h in ADVANCE_CASES:
        for part in (0.1, 0.37, 0.5, 0.9):
            x1 = _advance(RUDDER_PROPELLER, RP, [rudder, 0.5], [cmd, 1.8], part * h)
            x2 = _advance(RUDDER_PROPELLER, RP, x1, [cmd, 1.8], (1.0 - part) * h)
            whole = _advance(RUDDER_PROPELLER, RP, [rudder, 0.5], [cmd, 1.8], h)
            np.testing.assert_allclose(x2, whole, rtol=0, atol=1e-14)


def test_closed_form_step_with_a_rate_never_reached_is_the_plain_lag():
    servo = ServoParams(max_angle=1.0, max_rate=1e6, time_constant=2.0)
    got = _advance(RUDDER_SERVO, servo, [0.1], [5.0], 3.0)[0]  # target saturated to 1.0
    assert got == pytest.approx(1.0 - 0.9 * math.exp(-1.5), abs=1e-15)


def test_only_the_servos_have_a_closed_form_step():
    assert RUDDER_SERVO.advance is not None and RUDDER_PROPELLER.advance is not None
    assert DIRECT.advance is None
