"""Engine, shaft and reversal sequence (seahelm.vessels.engine_shaft)."""

import math

import pytest

from seahelm.errors import ParameterError
from seahelm.vessels.engine_shaft import (
    EngineShaftParams,
    commanded_rps,
    engine_torque,
    reversal_clock_rate,
    shaft_acceleration,
)

ENGINE = dict(shaft_inertia=1e6, rated_rps=1.8, max_power=1e8, astern_rps=-1.2,
              reversal_time=40.0, reversal_delay=30.0, reversal_rps=0.4,
              governor_time_constant=2.0)


@pytest.mark.parametrize("field, value, unit", [
    ("reversal_time", 0.0, "s"), ("reversal_time", -1.0, "s"), ("max_power", 0.0, "W"),
    ("max_power", -3.0, "W"), ("astern_rps", 1.2, "1/s"), ("astern_rps", 0.0, "1/s"),
    ("shaft_inertia", -5.0, "kg·m²"), ("reversal_rps", 2.0, "1/s"),
    ("reversal_delay", -1.0, "s"),
])
def test_validation_names_field_unit_value(field, value, unit):
    with pytest.raises(ParameterError, match=field) as info:
        EngineShaftParams(**{**ENGINE, field: value})
    assert info.value.field == field
    assert unit in str(info.value)


def test_commanded_rps_and_reversal_sequence():
    p = EngineShaftParams(**ENGINE).to_record()
    assert commanded_rps(1.0, p) == 1.8 and commanded_rps(-1.0, p) == -1.2
    assert commanded_rps(-3.0, p) == -1.2  # clipped order
    after = 30.0  # the sequence clock at the end of the reversal delay
    # opposite order within the delay: fuel cut, the shaft windmills (no engine torque)
    assert engine_torque(1.8, -1.0, 5e6, 29.99, p) == 0.0
    assert engine_torque(0.3, -1.0, 5e6, 0.0, p) == 0.0  # (even below the reversal rps)
    assert shaft_acceleration(1.8, -1.0, 5e6, 0.0, p) == pytest.approx(
        -5e6 / (2 * math.pi * 1e6))
    # after it, above the reversal rps: the air brake stops the shaft in t_rev
    brake = engine_torque(1.8, -1.0, 0.0, after, p)
    assert brake == pytest.approx(-2 * math.pi * 1e6 * 1.8 / 40.0)
    assert shaft_acceleration(1.8, -1.0, 0.0, after, p) == pytest.approx(-1.8 / 40.0)
    # below it: the governor drives astern, limited to the MCR torque
    q_mcr = 1e8 / (2 * math.pi * 1.8)
    governor = 2 * math.pi * 1e6 * (-1.2 - 0.3) / 2.0
    assert engine_torque(0.3, -1.0, 0.0, after, p) == pytest.approx(governor)
    assert engine_torque(0.3, -1.0, -2e7, after, p) == pytest.approx(-q_mcr)
    # on the commanded rps the governor holds it (load fed forward), whatever the clock
    assert shaft_acceleration(1.8, 1.0, 5e6, 0.0, p) == 0.0
    assert shaft_acceleration(1.8, 1.0, 5e6, 12.0, p) == 0.0
    # above the rated rps the power limit governs
    assert engine_torque(2.5, 1.0, 1e9, 0.0, p) == pytest.approx(1e8 / (2 * math.pi * 2.5))


def test_sequence_clock_runs_while_reversing_and_returns_to_zero():
    p = EngineShaftParams(**ENGINE).to_record()
    assert reversal_clock_rate(1.8, -1.0, 5.0, p) == 1.0  # order opposes the rotation
    assert reversal_clock_rate(-0.5, 1.0, 5.0, p) == 1.0
    assert reversal_clock_rate(-0.5, -1.0, 5.0, p) == pytest.approx(-5.0 / 2.0)
    assert reversal_clock_rate(1.8, 0.0, 5.0, p) == pytest.approx(-5.0 / 2.0)  # stop order
