"""``pid_pole_placement`` against PythonVehicleSimulator's ``control.PIDpolePlacement`` (Fossen,
PVS lib/control.py), whose gains for a mass-damper-spring plant m ẍ + d ẋ + k x = u are typed
here: K_p = m ω_n² − k, K_d = 2 ζ ω_n m − d, K_i = (ω_n/10) K_p. For Nomoto's ship
(T/K) ψ̈ + (1/K) ψ̇ = δ: m = T/K, d = 1/K, k = 0. Quoted on ``docs/guide/coming-from.rst``.

Without integral action the two are the same design. With it, PVS keeps the PD gains and adds
K_i = ω_n K_p/10, which moves the poles off (s² + 2ζω_n s + ω_n²); seahelm places all three
exactly at (s² + 2ζω_n s + ω_n²)(s + 1/T_i) with T_i = 10/ω_n — the same K_i, larger K_p, K_d.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.control.autopilot_design import pid_pole_placement

K, T = 0.185, 107.3  # the Mariner's Nomoto model [1/s], [s]
M, D, STIFF = T / K, 1.0 / K, 0.0


def pvs_gains(wn, zeta):
    kp = M * wn**2 - STIFF
    kd = M * 2.0 * zeta * wn - D
    return kp, kd, (wn / 10.0) * kp


CASES = [(0.05, 0.8), (0.1, 1.0), (0.03, 0.6)]


@pytest.mark.parametrize("wn, zeta", CASES)
def test_without_integral_action_the_gains_equal_pvs(wn, zeta):
    p = pid_pole_placement(K, T, natural_frequency=wn, damping=zeta,
                           integral_time=math.inf).params
    kp, kd, _ = pvs_gains(wn, zeta)
    assert (p.kp, p.kd, p.ki) == pytest.approx((kp, kd, 0.0), rel=1e-12, abs=0.0)


@pytest.mark.parametrize("wn, zeta", CASES)
def test_with_integral_action_the_same_ki_and_exact_poles(wn, zeta):
    p = pid_pole_placement(K, T, natural_frequency=wn, damping=zeta).params
    kp, kd, ki = pvs_gains(wn, zeta)
    assert p.ki == pytest.approx(ki, rel=1e-12)
    assert p.kp > kp and p.kd > kd  # the exact placement needs more

    def poles(gp, gd, gi):  # m s³ + (d + K_d) s² + K_p s + K_i = 0
        return np.sort_complex(np.roots([M, D + gd, gp, gi]))

    want = np.sort_complex(np.roots(np.polymul([1.0, 2 * zeta * wn, wn**2], [1.0, wn / 10])))
    np.testing.assert_allclose(poles(p.kp, p.kd, p.ki), want, atol=1e-9 * wn)
    assert np.max(np.abs(poles(kp, kd, ki) - want)) > 1e-3 * wn  # PVS's are off
