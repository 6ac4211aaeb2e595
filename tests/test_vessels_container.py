"""Son & Nomoto (1982) container ship, 4-DOF with roll: an independent transcription of MSS's
``container.m`` (non-dimensional form, coefficients typed from the table) integrated with scipy
``solve_ivp`` against seahelm's compiled model and manoeuvre library, at MSS's conditions
(shaft at 80 rpm, rudder limited to 10 deg at 5 deg/s): turning circle and 10/10 zig-zag; the
heel metrics, the steady-turn equilibrium with heel, the sign convention, loads, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from seahelm.analysis.equilibria.equilibrium import (
    steady_turn,
    steady_turn_state,
    straight_run_speed,
)
from seahelm.analysis.maneuvers import turning_circle, zigzag
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.analysis.maneuvers import maneuver_ship
from seahelm.vessels.container import CONTAINER, CONTAINER_MSS_SERVO, CONTAINER_SHIP, ContainerParams

G = 9.80665  # seahelm's g (container.m: 9.81; see the model's docstring)
RPS = 80.0 / 60.0
SHIP = "son-nomoto-container"


def mss_ship():
    """The catalog ship with container.m's steering gear (10 deg, 5 deg/s)."""
    return maneuver_ship(SHIP, servo=CONTAINER_MSS_SERVO)
DEG = math.pi / 180.0


def mss_container(x, delta_c, n_rps):
    """ẋ of container.m for x = [u v r x y psi p phi delta], the shaft at a constant n [1/s].

    Typed from MSS's container.m (non-dimensional; rudder ±10 deg, 5 deg/s)."""
    L = 175.0
    U = math.sqrt(x[0] ** 2 + x[1] ** 2)
    u, v, r = x[0] / U, x[1] / U, x[2] * L / U
    p, phi, psi, delta = x[6] * L / U, x[7], x[5], x[8]
    m, mx, my = 0.00792, 0.000238, 0.007049
    Ix, alphay, lx, ly, Iz, Jx, Jz = 0.0000176, 0.05, 0.0313, 0.0313, 0.000456, 0.0000034, 0.000419
    nabla, Delta, D, GM, t = 21222.0, 1.8219, 6.533, 0.3 / L, 0.175
    AR = 33.0376
    W = 1025 * G * nabla / (1025 * L ** 2 * U ** 2 / 2)
    kk, epsilon, xR, wp, tau, xp = 0.631, 0.921, -0.5, 0.184, 1.09, -0.526
    ga, cRr, cRrrr, cRrrv, cRX, aH, zR, xH = 0.088, -0.156, -0.275, 1.96, 0.71, 0.237, 0.033, -0.48
    dmax, ddmax = 10 * DEG, 5 * DEG
    dc = max(-dmax, min(dmax, delta_c))
    delta_dot = max(-ddmax, min(ddmax, dc - delta))
    n = n_rps
    vR = ga * v + cRr * r + cRrrr * r ** 3 + cRrrv * r ** 2 * v
    uP = u * ((1 - wp) + tau * ((v + xp * r) ** 2))
    J = uP * U / (n * D)
    KT = 0.527 - 0.455 * J
    uR = uP * epsilon * math.sqrt(1 + 8 * kk * KT / (math.pi * J ** 2))
    alphaR = delta + math.atan(vR / uR)
    FN = -((6.13 * Delta) / (Delta + 2.25)) * (AR / L ** 2) * (uR ** 2 + vR ** 2) \
        * math.sin(alphaR)
    T = 2 * D ** 4 / (U ** 2 * L ** 2) * KT * n * abs(n)
    X = (-0.0004226 * u ** 2 + (1 - t) * T - 0.00311 * v * r - 0.00386 * v ** 2
         + 0.00020 * r ** 2 - 0.00020 * phi ** 2 + cRX * FN * math.sin(delta) + (m + my) * v * r)
    Y = (-0.0116 * v + 0.00242 * r - 0.000063 * phi - 0.109 * v ** 3 + 0.00177 * r ** 3
         + 0.0214 * v ** 2 * r - 0.0405 * v * r ** 2 + 0.04605 * v ** 2 * phi
         + 0.00304 * v * phi ** 2 + 0.009325 * r ** 2 * phi - 0.001368 * r * phi ** 2
         + (1 + aH) * FN * math.cos(delta) - (m + mx) * u * r)
    K = (0.0003026 * v - 0.000063 * r - 0.0000075 * p - 0.000021 * phi + 0.002843 * v ** 3
         - 0.0000462 * r ** 3 - 0.000588 * v ** 2 * r + 0.0010565 * v * r ** 2
         - 0.0012012 * v ** 2 * phi - 0.0000793 * v * phi ** 2 - 0.000243 * r ** 2 * phi
         + 0.00003569 * r * phi ** 2 - (1 + aH) * zR * FN * math.cos(delta) + mx * lx * u * r
         - W * GM * phi)
    N = (-0.0038545 * v - 0.00222 * r + 0.000213 * p - 0.0001424 * phi + 0.001492 * v ** 3
         - 0.00229 * r ** 3 - 0.0424 * v ** 2 * r + 0.00156 * v * r ** 2
         - 0.019058 * v ** 2 * phi - 0.0053766 * v * phi ** 2 - 0.0038592 * r ** 2 * phi
         + 0.0024195 * r * phi ** 2 + (xR + aH * xH) * FN * math.cos(delta))
    m11, m22, m32, m42, m33, m44 = m + mx, m + my, -my * ly, my * alphay, Ix + Jx, Iz + Jz
    det = m22 * m33 * m44 - m32 ** 2 * m44 - m42 ** 2 * m33
    return np.array([
        X * (U ** 2 / L) / m11,
        -((-m33 * m44 * Y + m32 * m44 * K + m42 * m33 * N) / det) * (U ** 2 / L),
        ((-m42 * m33 * Y + m32 * m42 * K + N * m22 * m33 - N * m32 ** 2) / det) * (U ** 2 / L ** 2),
        (math.cos(psi) * u - math.sin(psi) * math.cos(phi) * v) * U,
        (math.sin(psi) * u + math.cos(psi) * math.cos(phi) * v) * U,
        math.cos(phi) * r * (U / L),
        ((-m32 * m44 * Y + K * m22 * m44 - K * m42 ** 2 + m32 * m42 * N) / det) * (U ** 2 / L ** 2),
        p * (U / L),
        delta_dot])


def _mss_speed(n_rps):
    return brentq(lambda u0: mss_container([u0, 0, 0, 0, 0, 0, 0, 0, 0], 0.0, n_rps)[0],
                  1.0, 20.0, xtol=1e-13)


def _ref_run(x0, command, t_end, events=None):
    return solve_ivp(lambda t, x: mss_container(x, command, RPS), (0.0, t_end), x0,
                     method="DOP853", rtol=1e-10, atol=1e-10, dense_output=True,
                     events=events, max_step=0.5)


@pytest.fixture(scope="module")
def turn():
    return turning_circle(mss_ship(), rudder=10 * DEG, rps=RPS, sides=1, dt=0.05)


def test_straight_run_speed_matches_the_transcription():
    u0 = _mss_speed(RPS)
    assert straight_run_speed(CONTAINER_SHIP, RPS, model=CONTAINER) == pytest.approx(u0, rel=1e-9)
    # MSS's exRRD examples start at 7.3 m/s with the shaft at 70 rpm
    assert _mss_speed(70 / 60) == pytest.approx(7.33, abs=0.01)


@pytest.mark.parametrize("state, rudder", [((8.0, 0.3, 0.004, 0.002, 0.05), 0.1),
                                           ((6.5, -0.8, -0.009, -0.01, -0.08), -0.17),
                                           ((8.3, 0.0, 0.0, 0.0, 0.0), 0.0)])
def test_derivative_equals_the_transcription(state, rudder):
    u, v, r, p, phi = state
    x_mss = [u, v, r, 0, 0, 0.3, p, phi, rudder]
    ref = mss_container(x_mss, rudder, RPS)
    x = CONTAINER.initial_state(surge_speed=u, sway_speed=v, yaw_rate=r, roll_rate=p,
                                roll_angle=phi, heading=0.3)
    dx = CONTAINER.derivative(0.0, x, [rudder, RPS], CONTAINER_SHIP)
    order = [0, 1, 2, 3, 4, 5, 6, 7]  # u v r x y psi p phi in both
    np.testing.assert_allclose(dx[order], ref[:8], rtol=1e-11, atol=1e-15)


def test_turning_circle_against_the_transcription(turn):
    m = turn.metrics
    u0 = _mss_speed(RPS)
    sol = _ref_run([u0, 0, 0, 0, 0, 0, 0, 0, 0], 10 * DEG, float(turn.runs.time[-1]))
    t = np.linspace(0.0, sol.t[-1], 200001)
    x = sol.sol(t)
    psi, north, east, phi = x[5], x[3], x[4], x[7]
    adv = np.interp(math.pi / 2, psi, north)
    tac = np.interp(math.pi, psi, east)
    assert float(m.advance) == pytest.approx(adv, rel=1e-5)
    assert float(m.tactical_diameter) == pytest.approx(tac, rel=1e-5)
    assert float(m.time_90) == pytest.approx(np.interp(math.pi / 2, psi, t), rel=1e-5)
    k = np.argmax(np.abs(phi))
    assert float(m.max_heel_angle) == pytest.approx(phi[k], rel=1e-4)
    assert float(m.steady_heel_angle) == pytest.approx(phi[-1], rel=1e-5)
    # starboard turn: a small inward heel first, then outwards to port
    assert phi[k] < 0 < phi.max() and float(m.steady_yaw_rate) > 0
    # the values reported in the docs: advance 983 m, tactical diameter 1435 m, heel -6.7/-5.0 deg
    assert float(m.advance) == pytest.approx(983.1, abs=1.0)
    assert math.degrees(float(m.max_heel_angle)) == pytest.approx(-6.72, abs=0.02)
    assert math.degrees(float(m.steady_heel_angle)) == pytest.approx(-5.04, abs=0.02)


def test_zigzag_against_the_transcription():
    z = zigzag(mss_ship(), rudder=10 * DEG, heading=10 * DEG, rps=RPS, sides=1, dt=0.01)
    u0 = _mss_speed(RPS)
    x0 = np.array([u0, 0, 0, 0, 0, 0, 0, 0, 0.0])
    command, t0, overshoots = 10 * DEG, 0.0, []
    for _ in range(3):
        def switch(t, x, c=command):
            return x[5] - math.copysign(10 * DEG, c)
        switch.terminal = True
        sol = solve_ivp(lambda t, x, c=command: mss_container(x, c, RPS), (t0, t0 + 400.0), x0,
                        method="DOP853", rtol=1e-10, atol=1e-10, events=switch,
                        dense_output=True, max_step=0.5)
        if overshoots or t0 > 0:
            tt = np.linspace(t0, sol.t[-1], 20001)
            psi = sol.sol(tt)[5]
            overshoots.append(np.max(np.abs(psi)) - 10 * DEG)
        t0, x0, command = sol.t[-1], sol.y[:, -1], -command
    # the zig-zag controller switches at the first step past the heading (a delay < dt, an
    # error of first order in dt: 2e-3 at dt = 0.05 s, 2e-4 at 0.01 s, 3e-5 at 0.002 s)
    got = z.metrics.overshoot.values.ravel()[:2]
    np.testing.assert_allclose(got, overshoots[:2], rtol=5e-4)
    assert math.degrees(got[0]) == pytest.approx(3.74, abs=0.01)


def test_steady_turn_balances_the_heel(turn):
    st = steady_turn(get_ship(SHIP), 10 * DEG, RPS)
    x = steady_turn_state(get_ship(SHIP), 10 * DEG, RPS).state
    dx = CONTAINER.derivative(0.0, x, [10 * DEG, RPS], CONTAINER_SHIP)
    np.testing.assert_allclose(dx[[0, 1, 2, 6, 7]], 0.0, atol=1e-10)
    assert x[CONTAINER.state_index("roll_angle")] < 0
    assert st.yaw_rate == pytest.approx(float(turn.metrics.steady_yaw_rate), rel=1e-4)


def test_positive_rudder_turns_to_starboard_and_the_ship_is_symmetric():
    x = CONTAINER.initial_state(surge_speed=8.0)
    d = CONTAINER.derivative(0.0, x, [[0.1, RPS], [-0.1, RPS]], CONTAINER_SHIP)
    assert d[0, 2] > 0 > d[1, 2]
    np.testing.assert_allclose(d[0, [1, 2, 6]], -d[1, [1, 2, 6]], rtol=1e-12)


def test_loads_enter_through_the_mass_matrix():
    p = CONTAINER_SHIP
    x = CONTAINER.initial_state(surge_speed=8.0, sway_speed=0.2, yaw_rate=0.003)
    loads = np.array([1e5, 2e5, 3e6, 4e7, 0.0, 0.0])  # X, Y, K, N, current
    d0 = CONTAINER.derivative(0.0, x, [0.05, RPS], p)
    d1 = CONTAINER.derivative(0.0, x, [0.05, RPS], p, d=loads)
    h, L = 0.5 * p.rho, p.length
    M = p.mass_matrix() * np.array([[h * L ** 3, h * L ** 4, h * L ** 4],
                                    [h * L ** 4, h * L ** 5, h * L ** 5],
                                    [h * L ** 4, h * L ** 5, h * L ** 5]])
    acc = np.linalg.solve(M, loads[[1, 2, 3]])  # (v̇, ṗ, ṙ)
    np.testing.assert_allclose(d1[[1, 6, 2]] - d0[[1, 6, 2]], acc, rtol=1e-9)
    assert d1[0] - d0[0] == pytest.approx(1e5 / ((p.mass + p.m_x) * h * L ** 3), rel=1e-12)


def test_finite_at_rest_and_without_the_propeller():
    x = CONTAINER.initial_state()
    assert np.all(np.isfinite(CONTAINER.derivative(0.0, x, [0.1, 0.0], CONTAINER_SHIP)))
    x = CONTAINER.initial_state(surge_speed=5.0)
    d = CONTAINER.derivative(0.0, x, [0.0, 0.0], CONTAINER_SHIP)
    assert d[0] < 0  # no thrust: the ship slows down


def test_roll_period_and_validation():
    assert CONTAINER_SHIP.roll_period() == pytest.approx(33.0, abs=0.1)
    with pytest.raises(ParameterError, match="mass matrix"):
        ContainerParams(I_x=1e-9, J_x=0.0)
    with pytest.raises(ParameterError, match="metacentric_height"):
        ContainerParams(metacentric_height=-0.3)


def test_batched_run_equals_single_runs():
    both = turning_circle(SHIP, rudder=[5 * DEG, 10 * DEG], rps=RPS, sides=1,
                          t_final=120.0)
    one = turning_circle(SHIP, rudder=5 * DEG, rps=RPS, sides=1, t_final=120.0)
    np.testing.assert_allclose(both.runs.roll_angle.values[0], one.runs.roll_angle.values,
                               rtol=1e-12, atol=1e-15)
