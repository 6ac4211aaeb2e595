"""Nomoto models: step responses against closed forms, Norrbin steady state, batching."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.vessels.nomoto import NOMOTO1, NOMOTO2, Nomoto1Params, Nomoto2Params

DELTA = math.radians(5.0)


def test_first_order_step_response_equals_closed_form(mariner1):
    p = mariner1
    res = simulate(NOMOTO1, p, np.zeros(4), t_final=600.0, dt=0.5, actuator=DIRECT,
                   reference=[DELTA])
    t = res.time
    k, tc = p.gain, p.time_constant
    r_exact = k * DELTA * (1.0 - np.exp(-t / tc))
    psi_exact = k * DELTA * (t - tc * (1.0 - np.exp(-t / tc)))
    np.testing.assert_allclose(res["yaw_rate"][0], r_exact, atol=1e-10)
    np.testing.assert_allclose(res["heading"][0], psi_exact, atol=1e-8)


def test_second_order_step_response_equals_closed_form(mariner2):
    p = mariner2
    res = simulate(NOMOTO2, p, np.zeros(5), t_final=600.0, dt=0.25, actuator=DIRECT,
                   reference=[DELTA])
    t = res.time
    k, t1, t2, t3 = p.gain, p.t1, p.t2, p.t3
    # step response of K (1 + T3 s) / ((1 + T1 s)(1 + T2 s)) by partial fractions
    r_exact = k * DELTA * (1.0 - (t1 - t3) / (t1 - t2) * np.exp(-t / t1)
                           - (t2 - t3) / (t2 - t1) * np.exp(-t / t2))
    np.testing.assert_allclose(res["yaw_rate"][0], r_exact, atol=1e-9)


def test_norrbin_steady_turn_solves_cubic():
    p = Nomoto1Params(gain=0.2, time_constant=30.0, speed=5.0, norrbin_n3=400.0)
    delta = math.radians(20.0)
    res = simulate(NOMOTO1, p, np.zeros(4), t_final=600.0, dt=0.5, actuator=DIRECT,
                   reference=[delta])
    roots = np.roots([p.norrbin_n3, 0.0, 1.0, -p.gain * delta])
    r_ss = roots[np.abs(roots.imag) < 1e-12].real[0]
    assert res["yaw_rate"][0, -1] == pytest.approx(r_ss, rel=1e-8)
    assert r_ss < p.gain * delta  # the cubic term reduces the steady turning rate


def test_kinematics_follow_heading_and_drift(mariner1):
    x = np.array([0.0, 0.0, math.radians(30.0), 0.0])
    d = np.array([0.0, 0.5])
    dx = NOMOTO1.derivative(0.0, x, [0.0], mariner1, d)
    u, v, psi = mariner1.speed, 0.5, math.radians(30.0)
    np.testing.assert_allclose(dx[:2], [u * math.cos(psi) - v * math.sin(psi),
                                        u * math.sin(psi) + v * math.cos(psi)], rtol=1e-14)


def test_rudder_disturbance_is_an_equivalent_rudder_angle(mariner2):
    x = np.array([0.0, 0.0, 0.1, 0.01, 0.002])
    a = NOMOTO2.derivative(0.0, x, [0.05], mariner2, [0.02, 0.0])
    b = NOMOTO2.derivative(0.0, x, [0.07], mariner2, [0.0, 0.0])
    # δ_d enters the K(δ + δ_d) term but not the K T3 δ̇ feed-through (ṙ differs by a δ)
    a_coef = mariner2.gain * mariner2.t3 / (mariner2.t1 * mariner2.t2)
    assert b[3] - a[3] == pytest.approx(a_coef * 0.02, rel=1e-12)


def test_derivative_is_batched(mariner2):
    rng = np.random.default_rng(1)
    x = rng.normal(size=(3, 4, 5))
    u = rng.normal(size=(3, 4, 1))
    batched = NOMOTO2.derivative(0.0, x, u, mariner2)
    for i in range(3):
        for j in range(4):
            np.testing.assert_array_equal(batched[i, j], NOMOTO2.derivative(0.0, x[i, j], u[i, j],
                                                                            mariner2))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        # K < 0 only with T < 0 (a course-unstable ship, issue 45 item 4); T = 0 never
        ({"gain": -0.1}, r"`gain` must be nonzero and of the sign of time_constant \(50 s\).*"
                         r"got -0.1"),
        ({"time_constant": 0.0}, r"`time_constant` must not be 0 \[s\].*got 0.0"),
        ({"speed": float("nan")}, r"`speed` must be finite \[m/s\], got nan"),
        ({"norrbin_n3": -1.0}, r"`norrbin_n3` must be in \[0, inf\] \[s²\], got -1.0"),
    ],
)
def test_bad_parameters_are_named(kwargs, match):
    base = {"gain": 0.1, "time_constant": 50.0, "speed": 5.0}
    base.update(kwargs)
    with pytest.raises(ParameterError, match=match):
        Nomoto1Params(**base)


def test_second_order_reduces_to_first_order_time_constant(mariner2):
    p1 = mariner2.equivalent_first_order()
    assert p1.time_constant == pytest.approx(118.0 + 7.8 - 18.5)
    with pytest.raises(ParameterError, match="t1"):
        Nomoto2Params(gain=0.1, t1=-1.0, t2=1.0, t3=0.0, speed=1.0)
