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
