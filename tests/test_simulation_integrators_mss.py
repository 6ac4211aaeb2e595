"""seahelm's ``rk4`` and ``euler`` steps against MSS's ``rk4.m`` and ``euler2.m`` (Fossen, Marine
Systems Simulator, LIBRARY/numericalMethods), typed here from those files: one step of a
nonlinear right-hand side (Nomoto's first-order ship with Norrbin's term, and a rudder input
as the extra argument, as MSS passes ``varargin``). Quoted on ``docs/guide/coming-from.rst``.
The compiled engine steps with the same tableaus (``tests/test_simulation_integrators.py``).
"""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.simulation.integrators import rk_step

K, T, N3 = 0.185, 107.3, 30.0  # [1/s], [s], [s²]


def f(t, x, delta):
    """ψ̇ = r, T ṙ + r + n₃ r³ = K δ (autonomous; ``t`` unused as in MSS's calls)."""
    r = x[..., 1]
    return np.stack([r, (K * delta - r - N3 * r**3) / T], axis=-1)


def mss_rk4(fun, h, x, *varargin):  # rk4.m
    k1 = fun(0.0, x, *varargin)
    k2 = fun(0.0, x + 0.5 * h * k1, *varargin)
    k3 = fun(0.0, x + 0.5 * h * k2, *varargin)
    k4 = fun(0.0, x + h * k3, *varargin)
    return x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def mss_euler2(xdot, x, h):  # euler2.m
    return x + h * xdot


@pytest.mark.parametrize("h", [0.05, 0.5, 5.0])
@pytest.mark.parametrize("x0", [(0.0, 0.0), (0.3, 0.02), (-1.0, -0.05)])
def test_one_step_equals_mss(h, x0):
    x = np.asarray(x0, dtype=float)
    delta = 0.17
    np.testing.assert_allclose(rk_step("rk4", f, 0.0, x, h, delta), mss_rk4(f, h, x, delta),
                               rtol=1e-14, atol=1e-16)
    np.testing.assert_allclose(rk_step("euler", f, 0.0, x, h, delta),
                               mss_euler2(f(0.0, x, delta), x, h), rtol=1e-14, atol=1e-16)


def test_many_steps_stay_equal():
    x_s = x_m = np.array([0.0, 0.0])
    for k in range(600):  # MSS's loop: x = rk4(@f, h, x, delta), 60 s at h = 0.1 s
        delta = 0.17 if k < 300 else -0.17
        x_s = rk_step("rk4", f, 0.1 * k, x_s, 0.1, delta)
        x_m = mss_rk4(f, 0.1, x_m, delta)
    np.testing.assert_allclose(x_s, x_m, rtol=1e-12, atol=1e-15)
