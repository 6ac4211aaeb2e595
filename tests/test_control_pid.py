"""PID heading autopilot: course change, no steady error, limits, wrapping, gains."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import ServoParams
from seahelm.control.pid import PID_HEADING, PIDHeadingParams, pid_gains_from_nomoto
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.vessels.nomoto import NOMOTO2

GAINS = PIDHeadingParams(kp=4.0, ki=0.0002, kd=110.0)  # the default scenario's gains


def test_twenty_degree_course_change_settles_and_respects_rudder_limits(mariner2):
    servo = ServoParams()
    res = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=600.0, dt=0.1,
                   controller=PID_HEADING, controller_params=GAINS, controller_dt=0.5,
                   reference=[math.radians(20.0)])
    psi = np.degrees(res["heading"][0])
    t = res.time
    outside = np.flatnonzero(np.abs(psi - 20.0) > 0.1)
    assert t[outside[-1]] < 130.0  # within 0.1° after 130 s, and it stays there
    assert np.max(psi) - 20.0 < 0.1
    assert abs(psi[-1] - 20.0) < 0.03  # the integral's slow tail (rejects disturbances below)
    delta = res["rudder_angle"][0]
    assert np.max(np.abs(delta)) <= servo.max_angle + 1e-12
    assert np.max(np.abs(np.diff(delta))) / 0.1 <= servo.max_rate * (1 + 1e-9)


def test_integral_action_removes_steady_error_under_constant_disturbance(mariner2):
    gains = PIDHeadingParams(kp=3.0, ki=0.015, kd=60.0)
    res = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=2400.0, dt=0.1,
                   controller=PID_HEADING, controller_params=gains, controller_dt=0.5,
                   reference=[math.radians(20.0)], disturbance=[math.radians(2.0), 0.0, 0.0, 0.0])
    psi = np.degrees(res["heading"][0])
    assert abs(psi[-1] - 20.0) < 0.01
    # the steady rudder angle cancels the disturbance (2° equivalent rudder): δ = −δ_d
    assert np.degrees(res["rudder_angle"][0, -1]) == pytest.approx(-2.0, abs=0.01)
    # without integral action δ = kp e = −δ_d leaves the error e = ψ* − ψ = −2°/3
    pd = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=2400.0, dt=0.1,
                  controller=PID_HEADING, controller_params=gains.replace(ki=0.0),
                  controller_dt=0.5, reference=[math.radians(20.0)],
                  disturbance=[math.radians(2.0), 0.0, 0.0, 0.0])
    assert np.degrees(pd["heading"][0, -1]) == pytest.approx(20.0 + 2.0 / 3.0, abs=1e-3)


def test_heading_error_is_wrapped(mariner2):
    # from 10° to 350°: the short way is 20° to port (negative rudder, negative yaw rate)
    x0 = np.array([0.0, 0.0, math.radians(10.0), 0.0, 0.0])
    res = simulate(NOMOTO2, mariner2, x0, t_final=900.0, dt=0.1, controller=PID_HEADING,
                   controller_params=GAINS, reference=[math.radians(350.0)])
    assert res["rudder_command"][0, 0] < 0
    final = math.degrees(res["heading"][0, -1]) % 360.0
    assert final == pytest.approx(350.0, abs=0.2)
    assert np.min(np.degrees(res["heading"][0])) > -25.0  # never turned the long way


def test_anti_windup_limits_overshoot_after_saturation(mariner2):
    """A large course change saturates the rudder; conditional integration keeps the
    integral from winding up, so the overshoot stays small."""
    gains = GAINS.replace(ki=0.01)
    res = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=1200.0, dt=0.1,
                   controller=PID_HEADING, controller_params=gains,
                   reference=[math.radians(90.0)])
    psi = np.degrees(res["heading"][0])
    assert np.max(np.abs(res["rudder_command"][0])) == pytest.approx(35.0 * math.pi / 180)
    overshoot = psi.max() - 90.0
    assert overshoot < 8.0
    assert abs(psi[-1] - 90.0) < 0.5


def test_pid_gains_from_nomoto_formulas():
    g = pid_gains_from_nomoto(0.185, 107.3, 0.05, 0.8)
    assert g.kp == pytest.approx(107.3 * 0.05**2 / 0.185)
    assert g.kd == pytest.approx((2 * 0.8 * 0.05 * 107.3 - 1) / 0.185)
    assert g.ki == pytest.approx(g.kp * 0.05 / 10)
    with pytest.raises(ParameterError, match=r"`natural_frequency` must be > 0 \[rad/s\]"):
        pid_gains_from_nomoto(0.185, 107.3, -0.05)


def test_negative_gain_is_rejected():
    with pytest.raises(ParameterError, match=r"`kp` must be in \[0, inf\] \[rad/rad\], got -1.0"):
        PIDHeadingParams(kp=-1.0)
