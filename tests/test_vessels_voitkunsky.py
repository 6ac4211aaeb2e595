"""Voitkunsky steering model (Romanov & Chirkova eq. (1)) as an engine vessel model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT, RUDDER_SERVO, ServoParams
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.identification.reduced.turns import stable_steady_turn, voitkunsky_turns
from seahelm.registry import get_model
from seahelm.simulation.engine import simulate
from seahelm.ships import get_ship
from seahelm.vessels.voitkunsky import (
    MARINER_VOITKUNSKY,
    VOITKUNSKY,
    voitkunsky_from_linear_derivatives,
)

P = MARINER_VOITKUNSKY


def _eq1(x, alpha, d, p):
    """Eq. (1) plus the documented kinematics, written out independently."""
    q21, r21, s21, h2, q31, r31, s31, U = (p.q21, p.r21, p.s21, p.h2, p.q31, p.r31, p.s31,
                                           p.speed)
    _, _, psi, w, b = x
    md, fd, vc = d
    return np.array([
        U * math.cos(psi - b) - vc * math.sin(psi),
        U * math.sin(psi - b) + vc * math.cos(psi),
        w,
        -q31 * b - r31 * w - s31 * alpha + md,
        -q21 * b - r21 * w - h2 * b * abs(b) - s21 * alpha - fd,
    ])


def test_registry_and_catalog():
    assert get_model("voitkunsky") is VOITKUNSKY
    entry = get_ship("mariner-voitkunsky")
    assert entry.model is VOITKUNSKY and entry.params == P
    assert "Chislett" in entry.provenance and "mariner.m" in entry.provenance


def test_rhs_is_eq1_batched():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(7, 5)) * [100, 100, 1, 0.02, 0.2]
    u = rng.normal(size=(7, 1)) * 0.3
    d = rng.normal(size=(7, 3)) * [1e-4, 1e-3, 0.5]
    got = VOITKUNSKY.derivative(0.0, x, u, P, d)
    ref = np.array([_eq1(x[i], u[i, 0], d[i], P) for i in range(7)])
    np.testing.assert_allclose(got, ref, rtol=1e-14, atol=1e-16)
    # no disturbance channel given -> zeros
    got0 = VOITKUNSKY.derivative(0.0, x[0], u[0], P)
    np.testing.assert_allclose(got0, _eq1(x[0], u[0, 0], np.zeros(3), P), rtol=1e-14)


def test_outputs_sign_convention():
    # β > 0 (velocity to port of the heading) -> negative sway speed, course ψ − β
    x = np.array([0.0, 0.0, 0.3, 0.01, 0.1])
    y = VOITKUNSKY.outputs(0.0, x, [0.0], P)
    assert y[4] == pytest.approx(P.speed * math.cos(0.1))
    assert y[5] == pytest.approx(-P.speed * math.sin(0.1))
    dx = VOITKUNSKY.derivative(0.0, x, [0.0], P)
    assert math.atan2(dx[1], dx[0]) == pytest.approx(0.3 - 0.1)


def test_mariner_linear_part_reproduces_nomoto_constants(mariner2):
    # ω/α of the linear part (h2 = 0) in closed form:
    # ω/α = −(s31 s + s31 q21 − q31 s21) / (s² + (r31 + q21) s + r31 q21 − q31 r21)
    p = P
    num = np.array([-p.s31, -(p.s31 * p.q21 - p.q31 * p.s21)])
    den = np.array([1.0, p.r31 + p.q21, p.r31 * p.q21 - p.q31 * p.r21])
    gain = num[1] / den[2]
    poles = np.roots(den)
    t1, t2 = sorted(-1.0 / poles.real, reverse=True)
    t3 = num[0] / num[1]
    assert gain == pytest.approx(mariner2.gain, rel=2e-3)
    assert t1 == pytest.approx(mariner2.t1, rel=2e-3)
    assert t2 == pytest.approx(mariner2.t2, rel=1e-2)
    assert t3 == pytest.approx(mariner2.t3, rel=2e-3)
    # positive rudder turns to starboard with positive drift angle (Russian convention)
    turn = stable_steady_turn(p, math.radians(10))
    assert turn.yaw_rate > 0 and turn.drift_angle > 0


def test_from_derivatives_rudder_sign_and_h2():
    kw = dict(mass=798e-5, inertia=39.2e-5, xg=-0.023, y_vdot=-748e-5, y_rdot=-9.354e-5,
              n_vdot=4.646e-5, n_rdot=-43.8e-5, y_v=-1160e-5, y_r=-499e-5, n_v=-264e-5,
              n_r=-166e-5, y_delta=-278e-5, n_delta=139e-5, y_vvv=-8078e-5, n_vvv=1636e-5,
              speed=7.7175, length=160.93)
    p = voitkunsky_from_linear_derivatives(**kw)
    assert p == P
    flipped = voitkunsky_from_linear_derivatives(**{**kw, "y_delta": 278e-5, "n_delta": -139e-5})
    assert flipped.s31 == pytest.approx(-P.s31) and flipped.s21 == pytest.approx(-P.s21)
    half = voitkunsky_from_linear_derivatives(**kw, beta_range=0.15)
    assert half.h2 == pytest.approx(P.h2 / 2)


@pytest.mark.parametrize(
    "field, value, match",
    [("h2", -0.1, r"`h2` must be in \[0"), ("speed", -1.0, r"`speed`.*\[m/s\]"),
     ("q21", float("nan"), r"`q21` must be finite")],
)
def test_validation(field, value, match):
    with pytest.raises(ParameterError, match=match):
        P.replace(**{field: value})


def test_straight_run_and_steady_turn_in_engine():
    x0 = VOITKUNSKY.initial_state()
    res = simulate(VOITKUNSKY, P, x0, t_final=100.0, dt=0.5, controller=OPEN_LOOP,
                   actuator=DIRECT, reference=[0.0])
    assert res["north"][0, -1] == pytest.approx(P.speed * 100.0, rel=1e-12)
    assert np.max(np.abs(res["heading"][0])) == 0.0
    alpha = math.radians(15)
    res = simulate(VOITKUNSKY, P, x0, t_final=1500.0, dt=0.5, controller=OPEN_LOOP,
                   actuator=DIRECT, reference=[alpha], record_every=10)
    turn = stable_steady_turn(P, alpha)
    assert res["yaw_rate"][0, -1] == pytest.approx(turn.yaw_rate, rel=1e-6)
    assert res["drift_angle"][0, -1] == pytest.approx(turn.drift_angle, rel=1e-6)
    # steady circle: radius U/ω, centre fixed
    n, e, psi = res["north"][0, -200:], res["east"][0, -200:], res["heading"][0, -200:]
    radius = P.speed / turn.yaw_rate
    course = psi - turn.drift_angle
    cn = n - radius * np.sin(course)
    ce = e + radius * np.cos(course)
    assert np.ptp(cn) < 1e-3 * radius and np.ptp(ce) < 1e-3 * radius


def test_constant_disturbance_steady_state_matches_static():
    md, fd = 2e-5, -3e-4
    alpha = math.radians(5)
    res = simulate(VOITKUNSKY, P, VOITKUNSKY.initial_state(), t_final=1500.0, dt=0.5,
                   controller=OPEN_LOOP, actuator=DIRECT, reference=[alpha],
                   disturbance=[md, fd, 0.0, 0.0, 0.0], record_every=100)
    turn = stable_steady_turn(P, alpha, yaw_moment=md, sway_force=fd)
    assert res["yaw_rate"][0, -1] == pytest.approx(turn.yaw_rate, rel=1e-6)
    assert res["drift_angle"][0, -1] == pytest.approx(turn.drift_angle, rel=1e-6)
    plain = stable_steady_turn(P, alpha)
    assert abs(turn.yaw_rate - plain.yaw_rate) > 1e-4  # the channels act


def test_batched_equals_one_by_one():
    params = [P, P.replace(h2=0.0), P.replace(speed=5.0, r31=0.12)]
    x0 = np.zeros((3, 5))
    x0[:, 2] = [0.0, 0.5, -1.0]
    rud = np.array([0.1, -0.2, 0.3])
    kw = dict(t_final=200.0, dt=0.5, controller=OPEN_LOOP, actuator=RUDDER_SERVO,
              actuator_params=ServoParams(), record_every=4)
    batch = simulate(VOITKUNSKY, params, x0, reference=rud[:, None, None], **kw)
    for i in range(3):
        one = simulate(VOITKUNSKY, params[i], x0[i], reference=[rud[i]], **kw)
        for label in ("north", "east", "heading", "yaw_rate", "drift_angle", "rudder_angle"):
            np.testing.assert_array_equal(batch[label][i], one[label][0])


def test_unstable_ship_has_three_equilibria_at_zero_rudder():
    # q21 r31 − r21 q31 < 0: course-unstable; β|β| gives the classical loop (pitchfork)
    p = P.replace(q31=-0.015)
    turns = voitkunsky_turns(p, 0.0)
    assert len(turns) == 3
    assert [t.stable for t in turns] == [True, False, True]
    assert turns[0].yaw_rate == pytest.approx(-turns[2].yaw_rate)
    res = simulate(VOITKUNSKY, p, VOITKUNSKY.initial_state(yaw_rate=1e-4), t_final=3000.0,
                   dt=0.5, controller=OPEN_LOOP, actuator=DIRECT, reference=[0.0],
                   record_every=100)
    assert res["yaw_rate"][0, -1] == pytest.approx(turns[2].yaw_rate, rel=1e-5)


def test_example_scenario_ends_in_the_static_steady_turn():
    from pathlib import Path

    from seahelm.scenario import load_scenario, run_scenario

    path = Path(__file__).resolve().parents[1] / "examples" / "voitkunsky_rudder_steps.toml"
    res = run_scenario(load_scenario(path))
    turn = stable_steady_turn(P, math.radians(15.0))
    assert res["yaw_rate"][0, -1] == pytest.approx(turn.yaw_rate, rel=1e-4)
    assert res["drift_angle"][0, -1] == pytest.approx(turn.drift_angle, rel=1e-4)
