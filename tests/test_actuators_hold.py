"""The first-order hold that replays a record's inputs (seahelm.actuators.hold): the model sees
the straight lines between the samples, checked against the closed-form response of a
first-order Nomoto model to a piecewise-linear rudder."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.hold import hold_actuator, hold_reference
from seahelm.errors import ParameterError
from seahelm.registry import get_model
from seahelm.simulation.engine import simulate
from seahelm.vessels.nomoto import Nomoto1Params

K, T = 0.08, 20.0  # Nomoto gain [1/s] and time constant [s]
DT = 1.0  # the step and the sampling interval [s]: coarse, so a half-step lag shows


def piecewise_linear_response(t: np.ndarray, delta: np.ndarray) -> np.ndarray:
    """r(t_k) of T ṙ + r = K δ, r(0) = 0, for δ the straight lines between (t_k, δ_k): on a
    segment δ = δ_k + s τ the solution is r = K (δ_k − s T + s τ) + (r_k − K (δ_k − s T))
    e^(−τ/T) (variation of constants)."""
    r = np.zeros_like(t)
    for k in range(t.size - 1):
        h = t[k + 1] - t[k]
        s = (delta[k + 1] - delta[k]) / h
        a = K * (delta[k] - s * T)
        r[k + 1] = a + K * s * h + (r[k] - a) * math.exp(-h / T)
    return r


def rudder_samples(t: np.ndarray) -> np.ndarray:
    """A rudder swinging at 2.3 deg/s between ±20 deg and resting there (a zig-zag's shape)."""
    tri = 2.0 * np.abs((t / 40.0) % 2.0 - 1.0) - 1.0  # triangle wave, period 80 s, ±1
    return np.radians(np.clip(40.0 * tri, -20.0, 20.0))


def run(actuator, t, delta, **kw):
    model = get_model("nomoto1")
    x0 = np.zeros(model.n_states)
    res = simulate(model, params=Nomoto1Params(gain=K, time_constant=T, speed=1.0), x0=x0,
                   t_final=float(t[-1]), dt=DT, actuator=actuator, **kw)
    return np.asarray(res["yaw_rate"])[0]


def test_the_model_sees_the_straight_lines_between_the_samples():
    t = DT * np.arange(241)
    delta = rudder_samples(t)
    exact = piecewise_linear_response(t, delta)
    hold = hold_actuator(("rudder_angle",), ("rad",))
    d0, rates = hold_reference(delta[:, None], DT)
    got = run(hold, t, delta, actuator_x0=d0, reference=rates[None])
    scale = np.max(np.abs(exact))
    # RK4 at h/T = 0.05 on a linear ODE with a linear input: local error (h/T)^5 / 120 =
    # 2.6e-9, at most 240 of them: 6e-7 (measured 9e-8)
    np.testing.assert_allclose(got, exact, rtol=0, atol=6e-7 * scale)
    # the same samples held at each sample (the direct actuator): the rudder half a step late
    held = run("direct", t, delta, reference=delta[None, :, None])
    lag = np.max(np.abs(held - exact)) / scale
    assert lag > 1e-2  # (measured 0.049)


def test_one_actuator_per_set_of_inputs_and_bad_samples():
    a = hold_actuator(("rudder_angle", "propeller_rps"), ("rad", "1/s"))
    assert a is hold_actuator(("rudder_angle", "propeller_rps"), ("rad", "1/s"))
    assert a.command_labels == ("rudder_angle_rate", "propeller_rps_rate")
    assert a.command_units == ("rad/s", "1/s²") and a.output_labels == a.state_labels
    x0, ref = hold_reference(np.array([[0.0, 1.0], [0.5, 1.0], [0.5, 2.0]]), 0.5)
    np.testing.assert_array_equal(x0, [0.0, 1.0])
    np.testing.assert_array_equal(ref, [[1.0, 0.0], [0.0, 2.0], [0.0, 2.0]])
    with pytest.raises(ParameterError, match="one unit per label"):
        hold_actuator(("rudder_angle",), ())
    with pytest.raises(ParameterError, match=r"must be > 0 \[s\], got -1"):
        hold_reference(np.zeros((3, 1)), -1.0)
    with pytest.raises(ParameterError, match="shape") as info:
        hold_reference(np.zeros(3), 0.1)
    assert info.value.field == "samples"
