"""The standard manoeuvres on constant-speed steering models (Nomoto 1 and 2, Voitkunsky),
against closed forms and an independent ODE solution (issue 29, item 6).

Nomoto 1, T ṙ + r = K δ, at constant speed U with the rudder following its order δ_0 through a
first-order lag τ (a steering gear whose rate limit is not reached), δ(t) = δ_0 (1 − e^{−t/τ}):

    r(t) = K δ_0 [1 − (T e^{−t/T} − τ e^{−t/τ}) / (T − τ)]
    ψ(t) = K δ_0 [t − (T² (1 − e^{−t/T}) − τ² (1 − e^{−t/τ})) / (T − τ)]

(τ → 0: ψ = K δ_0 (t − T (1 − e^{−t/T}))), and the track x_N = ∫ U cos ψ, y_E = ∫ U sin ψ,
here by adaptive quadrature of the closed form, independent of the engine. For K δ_0 T ≪ 1 the
track tends to the circle of radius R = U/(K δ_0) about (U T, R(1 + (rT)²/2)): advance
≈ R + U T, transfer ≈ R (1 + (rT)²/2), tactical diameter ≈ 2R + R (rT)²/2.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from seahelm.actuators.servo import ServoParams
from seahelm.analysis.equilibria.equilibrium import (
    approach_state,
    rudder_for_yaw_rate,
    steady_turn,
    steady_turn_state,
)
from seahelm.analysis.imo.check import imo_check
from seahelm.analysis.maneuvers import maneuver_ship, pull_out, turning_circle, zigzag
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.vessels.nomoto import Nomoto1Params, Nomoto2Params

MARINER_GEAR = get_ship("mariner-nonlinear").servo  # ±40 deg, 5 deg/s, 1 s
#: A fast gear: a pure lag of 0.5 s, its rate limit (10 rad/s) never reached.
LAG_GEAR = ServoParams(max_angle=math.radians(35.0), max_rate=10.0, time_constant=0.5)


def _ship(name: str, servo: ServoParams = LAG_GEAR, **params):
    base = get_ship(name)
    ship = base.replace(params=params) if params else base
    return maneuver_ship(ship, servo=servo)


def _psi(t, K, T, tau, delta):
    return K * delta * (t - (T * T * (1 - math.exp(-t / T))
                             - tau * tau * (1 - math.exp(-t / tau))) / (T - tau))


def _closed_form_turn(K, T, U, tau, delta):
    """(advance, transfer, tactical diameter, time to 90 deg, distance to 10 deg) from the
    closed-form heading by quadrature."""
    def t_at(angle):
        return brentq(lambda t: _psi(t, K, T, tau, delta) - angle, 0.0, 1e5, xtol=1e-12)

    opts = dict(epsabs=1e-10, epsrel=1e-12, limit=500)

    def north(t):
        return quad(lambda s: U * math.cos(_psi(s, K, T, tau, delta)), 0.0, t, **opts)[0]

    def east(t):
        return quad(lambda s: U * math.sin(_psi(s, K, T, tau, delta)), 0.0, t, **opts)[0]

    t90, t180, t10 = t_at(math.pi / 2), t_at(math.pi), t_at(math.radians(10.0))
    return north(t90), east(t90), east(t180), t90, U * t10


@pytest.mark.parametrize("gain, tc, delta_deg", [
    (0.185, 107.3, 35.0),   # the catalog's Mariner Nomoto 1 (K T δ = 12: a slow turn)
    (0.185, 107.3, 10.0),
    (0.02, 15.0, 20.0),     # a quick one (K T δ = 0.1)
])
def test_nomoto1_turning_circle_matches_the_closed_form(gain, tc, delta_deg):
    ship = _ship("mariner-nomoto1", gain=gain, time_constant=tc)
    U, delta = ship.params.speed, math.radians(delta_deg)
    dt = 0.05
    m = turning_circle(ship, delta, sides=1, dt=dt).metrics
    advance, transfer, tactical, t90, dist10 = _closed_form_turn(gain, tc, U, 0.5, delta)
    # events are interpolated linearly between samples: a position error of order U r dt²/8
    tol = U * gain * delta * dt * dt / 4
    assert float(m["advance"]) == pytest.approx(advance, abs=tol)
    assert float(m["transfer"]) == pytest.approx(transfer, abs=tol)
    assert float(m["tactical_diameter"]) == pytest.approx(tactical, abs=tol)
    assert float(m["time_90"]) == pytest.approx(t90, rel=2e-7)
    # the distance travelled at constant speed is U t (a sum of chords: a little shorter)
    assert float(m["distance_10"]) == pytest.approx(dist10, abs=tol)
    # steady turn: radius U/(K δ) once the lags have died out
    t_end = float(m.attrs["t_final"])
    r_end = gain * delta * (1 - (tc * math.exp(-t_end / tc) - 0.5 * math.exp(-t_end / 0.5))
                            / (tc - 0.5))
    assert float(m["steady_yaw_rate"]) == pytest.approx(r_end, rel=1e-9)
    assert float(m["steady_radius"]) == pytest.approx(U / (gain * delta), rel=0.06)
    assert bool(m["complete"]) and str(m["message"].item()) == "ok"
    # constant speed: no speed loss, no drift angle
    assert np.isnan(float(m["speed_loss"])) and np.isnan(float(m["steady_drift_angle"]))
    assert "constant-speed model" in m["speed_loss"].attrs["long_name"]
    assert "constant-speed" in m.attrs["speed"]
    assert float(m["steady_speed"]) == U


def test_small_time_constant_asymptotics():
    """K δ T ≪ 1: advance ≈ R + U T, transfer ≈ R (1 + (rT)²/2), tactical ≈ 2R + R (rT)²/2."""
    gain, tc, delta = 0.01, 5.0, math.radians(20.0)
    ship = _ship("mariner-nomoto1", servo=ServoParams(
        max_angle=math.radians(35.0), max_rate=100.0, time_constant=0.01), gain=gain,
        time_constant=tc)
    U = ship.params.speed
    r = gain * delta
    R, rT = U / r, r * tc
    m = turning_circle(ship, delta, sides=1, dt=0.1).metrics
    assert float(m["advance"]) == pytest.approx(R + U * tc, rel=rT ** 2)
    assert float(m["transfer"]) == pytest.approx(R * (1 + rT ** 2 / 2), rel=rT ** 3)
    assert float(m["tactical_diameter"]) == pytest.approx(2 * R + R * rT ** 2 / 2, rel=rT ** 3)


def _first_overshoot(params, servo, delta, trigger, order):
    K = params.gain

    def rhs(t, x, command):
        r, d = x[1], x[2]
        d_dot = min(max((command - d) / servo.time_constant, -servo.max_rate), servo.max_rate)
        if order == 1:
            return [r, (K * d - r) / params.time_constant, d_dot]
        t12, a = params.t1 * params.t2, K * params.t3 / (params.t1 * params.t2)
        r_dot = x[3] + a * d
        return [r, r_dot, d_dot, (K * d - (params.t1 + params.t2) * r_dot - r) / t12]

    def cross(t, x, command):
        return x[0] - trigger
    cross.terminal = True

    def turn_back(t, x, command):
        return x[1]
    turn_back.terminal = True
    turn_back.direction = -1
    x0 = np.zeros(3 if order == 1 else 4)
    opts = dict(rtol=1e-11, atol=1e-13, max_step=0.5, dense_output=True)
    a = solve_ivp(rhs, (0.0, 1e4), x0, args=(delta,), events=cross, **opts)
    b = solve_ivp(rhs, (a.t[-1], 1e4), a.y[:, -1], args=(-delta,), events=turn_back, **opts)
    return float(b.y_events[0][0][0] - trigger), float(b.y[1, 0])


@pytest.mark.parametrize("name, pair_deg", [("mariner-nomoto1", 10.0), ("mariner-nomoto1", 20.0),
                                            ("mariner-nomoto2", 10.0), ("mariner-nomoto2", 20.0)])
def test_zigzag_first_overshoot_matches_solve_ivp(name, pair_deg):
    ship = _ship(name, servo=MARINER_GEAR)
    pair = math.radians(pair_deg)
    dt = 0.02
    m = zigzag(ship, pair, pair, sides=1, dt=dt).metrics
    order = 1 if name.endswith("1") else 2
    expected, r_execute = _first_overshoot(ship.params, MARINER_GEAR, pair, pair, order)
    # the controller reverses at the sample nearest the crossing: within r Δt/2
    assert float(m["overshoot"].sel(n=1)) == pytest.approx(
        expected, abs=abs(r_execute) * dt / 2 + 1e-6)
    assert bool(m["complete"])


def test_batched_equals_single():
    ship = _ship("mariner-nomoto2", servo=MARINER_GEAR)
    rudders = np.radians([5.0, 15.0, 35.0])
    batch = turning_circle(ship, rudders, sides=(1, -1)).metrics
    t_final, dt = float(batch.attrs["t_final"]), float(batch.attrs["dt"])
    for k, d in enumerate(rudders):
        for side in (1, -1):
            one = turning_circle(ship, float(d), sides=side, t_final=t_final, dt=dt).metrics
            row = batch.isel(rudder=k).sel(side=side)
            for name in ("advance", "transfer", "tactical_diameter", "time_90",
                         "distance_10", "steady_yaw_rate"):
                assert float(row[name]) == float(one[name]), name
    zz = zigzag(ship, np.radians([10.0, 20.0]), np.radians([10.0, 20.0]), sides=1).metrics
    for k, d in enumerate((10.0, 20.0)):
        one = zigzag(ship, math.radians(d), math.radians(d), sides=1,
                     t_final=float(zz.attrs["t_final"])).metrics
        np.testing.assert_array_equal(zz["overshoot"].isel(pair=k).values,
                                      one["overshoot"].values)


def test_equilibria_of_constant_speed_models():
    p1 = get_ship("mariner-nomoto1").params
    a = approach_state(p1, trim=True)
    assert np.all(a.state == 0.0) and a.inputs == {"rudder_angle": 0.0}
    turn = steady_turn(p1, math.radians(10.0))
    assert turn.yaw_rate == pytest.approx(p1.gain * math.radians(10.0), rel=1e-12)
    assert turn.radius == pytest.approx(p1.speed / turn.yaw_rate, rel=1e-12)
    assert turn.speed == p1.speed
    # Norrbin's term: r + n3 r³ = K δ
    pn = p1.replace(norrbin_n3=2000.0)
    r = steady_turn(pn, math.radians(20.0)).yaw_rate
    assert r + 2000.0 * r ** 3 == pytest.approx(p1.gain * math.radians(20.0), rel=1e-10)
    spiral = rudder_for_yaw_rate(pn, np.array([-0.01, 0.0, 0.02]))
    np.testing.assert_allclose(spiral.rudder * p1.gain,
                               spiral.yaw_rate + 2000.0 * spiral.yaw_rate ** 3, rtol=1e-10)
    p2 = get_ship("mariner-nomoto2").params
    s = steady_turn_state(p2, math.radians(15.0))
    assert s.state[3] == pytest.approx(p2.gain * math.radians(15.0), rel=1e-12)
    assert s.state[4] == pytest.approx(-p2.gain * p2.t3 / (p2.t1 * p2.t2) * math.radians(15.0),
                                       rel=1e-12)  # ξ = ṙ − a δ with ṙ = 0
    with pytest.raises(ParameterError, match="has no propeller_rps input") as err:
        steady_turn(p1, 0.1, rps=5.0)
    assert err.value.field == "rps"


def test_another_speed_is_refused_naming_the_option():
    ship = _ship("mariner-nomoto1")
    with pytest.raises(ParameterError, match=r"`speed` must be the constant speed U = 7.7175 "
                       r"\[m/s\] of model 'nomoto1'.*got 5.0") as err:
        turning_circle(ship, 0.3, speed=5.0)
    assert (err.value.field, err.value.unit, err.value.value) == ("speed", "m/s", 5.0)
    # its own speed, given explicitly, is fine
    m = turning_circle(ship, 0.3, sides=1, speed=ship.params.speed).metrics
    assert bool(m["complete"])


def test_pull_out_and_the_imo_check_run():
    lagged = _ship("mariner-nomoto1")
    po = pull_out(lagged, math.radians(20.0), sides=1).metrics
    # a stable linear model returns to a straight course: r = r_0 (T e^{-t/T} - τ e^{-t/τ})/(T - τ)
    T, tau = lagged.params.time_constant, 0.5
    half = brentq(lambda t: (T * math.exp(-t / T) - tau * math.exp(-t / tau)) / (T - tau) - 0.5,
                  0.0, 10 * T)
    assert float(po["initial_yaw_rate"]) == pytest.approx(
        lagged.params.gain * math.radians(20.0), rel=1e-12)
    assert float(po["half_time"]) == pytest.approx(half, rel=1e-4)
    assert abs(float(po["residual_yaw_rate"])) < 1e-3 * float(po["initial_yaw_rate"])
    ship = _ship("mariner-nomoto1", servo=MARINER_GEAR)
    report = imo_check(ship)
    evaluated = {(c.ability, c.criterion) for c in report.criteria if c.status != "not evaluated"}
    assert ("turning", "advance") in evaluated and ("10/10 zig-zag", "first overshoot") in evaluated
    assert all(math.isfinite(c.value) for c in report.criteria if c.status != "not evaluated")
    assert any("constant-speed model 'nomoto1'" in n and "no speed loss" in n
               for n in report.notes)
    tc = turning_circle(ship, math.radians(35.0), sides=1).metrics
    adv = next(c for c in report.criteria if c.criterion == "advance" and c.side == "starboard")
    assert adv.value == pytest.approx(float(tc["advance"]) / ship.length, rel=1e-6)


def test_voitkunsky_keeps_its_drift_angle():
    ship = _ship("mariner-voitkunsky", servo=MARINER_GEAR)
    m = turning_circle(ship, math.radians(20.0), sides=1).metrics
    assert float(m["steady_drift_angle"]) > 0.0 and np.isnan(float(m["speed_loss"]))
    assert isinstance(ship.params, type(get_ship("mariner-voitkunsky").params))


def test_params_types():  # the catalog's constant-speed ships are the ones described above
    assert isinstance(get_ship("mariner-nomoto1").params, Nomoto1Params)
    assert isinstance(get_ship("mariner-nomoto2").params, Nomoto2Params)
