"""Compensating rudder angle and controllability monitor of Lvov (2014), eq. (12)-(14), Fig. 1
(the components; the paper's closed loop is tests/test_studies_lvov2014.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.control import compensation as cp
from seahelm.errors import ParameterError

RHO = 1025.0
HULL = dict(length=150.0, draft=8.0, block_coefficient=0.7, rudder_area=20.0,
            rudder_aspect_ratio=1.5, windage_area=1200.0, underwater_area=1200.0)


def c_hull(alpha_deg):
    """(0.23 sin α + 1.09 sin²α)/(2.1 δ − 7 T/L)², δ = 0.7, T = 8, L = 150, by hand."""
    s = math.sin(math.radians(alpha_deg))
    return (0.23 * s + 1.09 * s * s) / (2.1 * 0.7 - 7 * 8 / 150) ** 2


def test_lateral_resistance_centre_eq13():
    assert float(cp.lateral_resistance_centre(7.0, 7.0)) == pytest.approx(0.0, abs=1e-15)
    # T_f/T_a = 2/3: (1 + 4/3)/(3·5/3) − 0.5 = 7/15 − 1/2 = −1/30 (trim by the stern: aft)
    assert float(cp.lateral_resistance_centre(6.0, 9.0)) == pytest.approx(-1.0 / 30.0, rel=1e-12)
    assert float(cp.lateral_resistance_centre(9.0, 6.0)) > 0
    with pytest.raises(ParameterError, match=r"`draft_aft` must be > 0 \[m\]"):
        cp.lateral_resistance_centre(6.0, 0.0)


def test_hull_drift_coefficient_and_drift_angle():
    assert float(cp.hull_drift_coefficient(math.radians(5), 0.7, 8.0, 150.0)) == pytest.approx(
        c_hull(5.0), rel=1e-12)
    assert c_hull(5.0) == pytest.approx(0.023552, rel=1e-4)
    assert float(cp.hull_drift_coefficient(-math.radians(5), 0.7, 8.0, 150.0)) == pytest.approx(
        -c_hull(5.0), rel=1e-12)
    force = c_hull(4.0) * RHO * 1200.0 * 8.0**2
    alpha = cp.drift_angle([force, -force, 0.0], speed=8.0, underwater_area=1200.0,
                           block_coefficient=0.7, draft=8.0, length=150.0)
    np.testing.assert_allclose(alpha, np.radians([4.0, -4.0, 0.0]), rtol=1e-10, atol=1e-15)


def test_wind_compensation_eq12_hand_computed():
    l_lr = -1.0 / 30.0
    factor = (1 + 2 / 1.5) / (20.0 * RHO)
    wind = (0.25 + 5 / 150 - 60 / 360) * 0.37 * math.sin(math.radians(60)) * 1.225 * 1200 * 400 / 64
    hull = (0.5 + l_lr - 3 / 180) * c_hull(3.0) * RHO * 1200
    hand = factor * (wind + hull)
    got = cp.wind_compensation(wind_speed=20.0, wind_angle=math.radians(60), drift=math.radians(3),
                               speed=8.0, sail_centre=5.0, resistance_centre=l_lr, **HULL)
    assert float(got) == pytest.approx(hand, rel=1e-12)
    # odd in the angles (mirror image for wind from port)
    mirror = cp.wind_compensation(wind_speed=20.0, wind_angle=-math.radians(60),
                                  drift=-math.radians(3), speed=8.0, sail_centre=5.0,
                                  resistance_centre=l_lr, **HULL)
    assert float(mirror) == pytest.approx(-hand, rel=1e-12)


def test_wave_term_and_eq14():
    # (1 + 2/λ_p)/(S_p ρ) · M_w/(V² L)
    hand = (1 + 2 / 1.5) / (20.0 * RHO) * 1.0e7 / (64.0 * 150.0)
    got = cp.wave_compensation(1.0e7, speed=8.0, length=150.0, rudder_area=20.0,
                               rudder_aspect_ratio=1.5)
    assert float(got) == pytest.approx(hand, rel=1e-12)
    wind_kw = dict(wind_speed=20.0, wind_angle=math.radians(60), drift=math.radians(3),
                   speed=8.0, **HULL)
    total = cp.compensating_rudder_angle(wave_moment=1.0e7, **wind_kw)
    assert float(total) == pytest.approx(float(cp.wind_compensation(**wind_kw)) + hand, rel=1e-12)


def test_monitor_synthetic():
    dt = 0.5
    t = np.arange(0, 600, dt)
    wiggle = np.radians(10.0) * np.sin(2 * np.pi * t / 40.0)
    dk = np.radians([[20.0], [30.0]])
    rep = cp.controllability_monitor(dk + wiggle, dk, dt=dt, window=60.0)
    assert rep.activity.shape == (2, t.size)
    assert np.degrees(rep.activity[:, -1]) == pytest.approx([10.0, 10.0], abs=0.05)
    assert rep.lost.tolist() == [False, True]  # 20 + 10 < 35 < 30 + 10
    assert np.isnan(rep.first_time[0]) and rep.first_time[1] > 0
    late = cp.controllability_monitor(dk + wiggle, dk, dt=dt, window=60.0, start=599.0)
    assert late.first_time[1] >= 599.0
    with pytest.raises(ParameterError, match="time axis"):
        cp.controllability_monitor(0.1, 0.0, dt=0.1)
