"""Baseline steering laws (introduction of Shushlyapin et al., 2017) and the PID yaw-rate loop."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT
from seahelm.control.baselines import (
    DRIFT_THRUSTER_BASELINE,
    HEADING_RATE_BASELINE,
    PID_YAW_RATE,
    DriftThrusterBaselineParams,
    HeadingRateBaselineParams,
    PIDYawRateParams,
    drift_thruster_baseline_init,
    drift_thruster_baseline_step,
    heading_rate_baseline_step,
)
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.vessels.catamaran import CATAMARAN, paper_params

P = paper_params()
CRUISE = np.r_[P.straight_speed(), np.zeros(6)]


def _run(controller, cparams, ref, *, x0=CRUISE, t_final=300.0, **kw):
    return simulate(CATAMARAN, P, x0, t_final=t_final, dt=0.001, controller=controller,
                    controller_params=cparams, actuator=DIRECT, reference=ref,
                    controller_dt=0.01, record_every=1000, **kw)


def test_heading_law_is_the_printed_formula():
    p = HeadingRateBaselineParams(k1=-0.1, k2=-0.5, k3=0.2)
    z = np.array([4.0, 0.1, 0.01, 0.0, 0.0, 0.3, 0.05])
    assert HEADING_RATE_BASELINE.measurement_labels == ("heading", "yaw_rate")
    y = np.array([0.3, 0.01])  # the measurements: heading, yaw rate
    cmd = np.zeros(1)
    heading_rate_baseline_step(0.0, 0.01, z, y, np.array([0.8]), p.to_record(), np.zeros(1), cmd)
    assert cmd[0] == pytest.approx(-0.1 * (0.3 - 0.8) - 0.5 * 0.01 - 0.2 * 0.05)
    # the heading error is wrapped: K − K* = 3.0 − (−3.0) is −0.283 rad, not 6 rad
    y[0] = 3.0
    heading_rate_baseline_step(0.0, 0.01, z, y, np.array([-3.0]), p.to_record(), np.zeros(1), cmd)
    assert cmd[0] == pytest.approx(-0.1 * (6.0 - 2 * math.pi) - 0.5 * 0.01 - 0.2 * 0.05)


def test_heading_baseline_reaches_the_course():
    res = _run(HEADING_RATE_BASELINE, HeadingRateBaselineParams(), [0.8], t_final=600.0)
    K = res["heading"][0]
    assert res.status[0] == 0
    assert K[-1] == pytest.approx(0.8, abs=1e-4)
    assert K.max() < 0.8 * 1.01  # well damped: < 1 % overshoot
    # too much yaw-rate feedback excites the listing's 14.5 rad/s mode (like T_u·h too small)
    bad = _run(HEADING_RATE_BASELINE, HeadingRateBaselineParams(k2=-2.0), [0.8],
               t_final=100.0, bounds={"yaw_rate": (-1.0, 1.0)})
    assert bad.status[0] != 0


def test_drift_law_integrates_the_printed_equation():
    p = DriftThrusterBaselineParams(k1=100.0, k2=50.0, k3=0.5, force_output=1.0)
    z = np.array([4.0, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0])
    beta = math.atan2(0.2, 4.0)
    cs = np.zeros(2)
    cmd = np.zeros(1)
    assert DRIFT_THRUSTER_BASELINE.measurement_labels == ()  # reads the state z only
    drift_thruster_baseline_init(z, np.zeros(0), np.array([0.0]), p.to_record(), cs)
    dt = 0.1
    drift_thruster_baseline_step(0.0, dt, z, np.zeros(0), np.array([0.0]), p.to_record(), cs, cmd)
    # explicit Euler of dP/dt = k1 β + k2 ∫β − k3 P from P = 0, ∫β = 0
    assert cmd[0] == pytest.approx(dt * 100.0 * beta)
    assert cs[1] == pytest.approx(beta * dt)
    drift_thruster_baseline_step(dt, dt, z, np.zeros(0), np.array([0.0]), p.to_record(), cs, cmd)
    P1 = dt * 100.0 * beta
    assert cmd[0] == pytest.approx(P1 + dt * (100.0 * beta + 50.0 * beta * dt - 0.5 * P1))


def test_drift_baseline_holds_a_wanted_drift_angle():
    res = _run(DRIFT_THRUSTER_BASELINE, DriftThrusterBaselineParams(), [-0.05],
               x0=np.r_[P.straight_speed(), 0.3, np.zeros(5)])
    beta = np.arctan2(res["sway_speed_port"][0], res["surge_speed"][0])
    assert res.status[0] == 0
    assert beta[-1] == pytest.approx(-0.05, abs=1e-5)
    # the side force P = 2 T_v sin δ realised by the thrusters points the other way
    side_force = 2 * P.thrust * math.sin(res["thruster_angle"][0, -1])
    assert side_force > 0 > beta[-1]


def test_pid_yaw_rate_tracks_without_steady_error_and_winds_up_safely():
    refs = np.array([0.00072, 0.04, 0.3]).reshape(3, 1, 1)
    res = _run(PID_YAW_RATE, PIDYawRateParams(), refs)
    assert np.all(res.status == 0)
    w = res["yaw_rate"]
    assert w[0, -1] == pytest.approx(0.00072, rel=1e-4)
    assert w[1, -1] == pytest.approx(0.04, rel=1e-4)
    # unreachable: the thruster angle saturates at max_angle = 89°, anti-windup keeps it finite
    assert math.degrees(res["thruster_angle"][2, -1]) == pytest.approx(89.0, abs=0.1)
    assert np.all(np.isfinite(res.state))


def test_pid_batched_equals_one_by_one():
    refs = np.array([0.00072, 0.04]).reshape(2, 1, 1)
    cps = [PIDYawRateParams(), PIDYawRateParams(kp=1.0, ki=0.8)]
    batch = _run(PID_YAW_RATE, cps, refs, t_final=50.0)
    for i in range(2):
        one = _run(PID_YAW_RATE, cps[i], refs[i, 0], t_final=50.0)
        np.testing.assert_array_equal(batch.state[i], one.state[0])


@pytest.mark.parametrize(
    "cls, field, value, match",
    [
        (PIDYawRateParams, "kp", -1.0, "kp"),
        (PIDYawRateParams, "tracking_time", 0.0, "tracking_time"),
        (PIDYawRateParams, "max_angle", 2.0, "max_angle"),
        (DriftThrusterBaselineParams, "thrust", 0.0, r"thrust.*\[N\]"),
        (DriftThrusterBaselineParams, "force_output", 2.0, "force_output"),
        (HeadingRateBaselineParams, "max_angle", 0.0, "max_angle"),
    ],
)
def test_bad_parameters_raise(cls, field, value, match):
    with pytest.raises(ParameterError, match=match):
        cls(**{field: value})
