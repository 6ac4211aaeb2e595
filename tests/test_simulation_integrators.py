"""Fixed-step integrators: convergence orders against closed-form solutions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm

from seahelm.actuators.servo import DIRECT
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.simulation.integrators import INTEGRATORS, ORDERS, integrate, solve_reference
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

# a damped oscillator with a closed-form solution x(t) = expm(A t) x0, batched over 3 states
A = np.array([[0.0, 1.0], [-4.0, -0.4]])
X0 = np.array([[1.0, 0.0], [0.0, 1.0], [0.5, -0.5]])


def _linear(t, x):
    return x @ A.T


def _error(method: str, h: float) -> float:
    t = np.arange(0.0, 5.0 + h / 2, h)
    xs = integrate(_linear, X0, t, method=method)
    exact = X0 @ expm(A * t[-1]).T
    return float(np.max(np.abs(xs[-1] - exact)))


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_numpy_integrators_converge_at_their_order(method):
    ratio = _error(method, 0.02) / _error(method, 0.01)
    assert ratio == pytest.approx(2 ** ORDERS[method], rel=0.1)


def test_solve_reference_matches_closed_form():
    t = np.linspace(0.0, 5.0, 11)
    xs = solve_reference(lambda tt, x: A @ x, X0[0], t)
    exact = np.array([expm(A * tt) @ X0[0] for tt in t])
    np.testing.assert_allclose(xs, exact, atol=1e-9)


def test_integrate_rejects_bad_grid():
    with pytest.raises(ParameterError, match="time step"):
        integrate(_linear, X0, [0.0, 1.0, 0.5])
    with pytest.raises(ValueError, match="unknown integrator 'rk5'; valid: euler, heun, rk4"):
        integrate(_linear, X0, [0.0, 1.0], method="rk5")


# --- the compiled closed-loop kernel integrates with the same orders --------------------------
K, T, DELTA = 0.185, 107.3, math.radians(10.0)
P1 = Nomoto1Params(gain=K, time_constant=T, speed=7.7)


def _heading_exact(t):
    """ψ(t) of T ṙ + r = K δ from rest: K δ (t − T (1 − e^{−t/T}))."""
    return K * DELTA * (t - T * (1.0 - np.exp(-t / T)))


def _kernel_error(method: str, dt: float) -> float:
    res = simulate(NOMOTO1, P1, np.zeros(4), t_final=200.0, dt=dt, actuator=DIRECT,
                   reference=[DELTA], integrator=method)
    return abs(res["heading"][0, -1] - _heading_exact(200.0))


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_kernel_integrators_converge_at_their_order(method):
    # large steps so that round-off does not mask the truncation error of RK4
    e1, e2 = _kernel_error(method, 20.0), _kernel_error(method, 10.0)
    assert e1 / e2 == pytest.approx(2 ** ORDERS[method], rel=0.15)
