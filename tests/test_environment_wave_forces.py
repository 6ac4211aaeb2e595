"""Wave and wind loads of Lvov (2014), eq. (1)-(11): hand-computed points, symmetries, validity."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.environment import wave_forces as wf
from seahelm.environment import wind as wd
from seahelm.errors import ParameterError, ValidityRangeWarning, strict_validity

# A hull inside every published range: L/T = 18.75, B/T = 2.5, L/B = 7.5, δ = 0.7.
L, B, T, CB = 150.0, 20.0, 8.0, 0.7
RHO, G = 1025.0, 9.81

# eq. (5)-(7) by hand:
#   Cx = 0.062·2.5 − 0.0085·18.75 + 0.328·0.7 = 0.155 − 0.159375 + 0.2296
#   Cy = 0.0823·7.5 + 2.56·8/150 + 0.903·0.49 = 0.61725 + 0.1365333… + 0.44247
#   Cm = 0.15·0.7 + 0.197·0.49 − 0.00373·18.75 = 0.105 + 0.09653 − 0.0699375
CX, CY, CM = 0.225225, 1.19625333333, 0.1315925


def coeffs():
    return wf.wave_force_coefficients(L, B, T, CB)


def test_coefficients_hand_computed():
    c = coeffs()
    assert float(c.cx) == pytest.approx(CX, rel=1e-10)
    assert float(c.cy) == pytest.approx(CY, rel=1e-10)
    assert float(c.cm) == pytest.approx(CM, rel=1e-10)


def test_forces_hand_computed():
    # h3% = 4 m, λ = 100 m, q_w = 30°, V_n = 2 m/s, V_w = 12 m/s, A0 = 3.3, A1 = 1
    # F = ρ g L (h/2)² e^(−3.3·100/150) (1 + 2/12) = 1025·9.81·150·4·e^(−2.2)·7/6
    f = 1025.0 * 9.81 * 150.0 * 4.0 * 0.11080315836233387 * (7.0 / 6.0)
    assert f == pytest.approx(779907.4, rel=1e-6)
    x_hand = CX * (0.1 - math.sqrt(3) / 2) * f
    y_hand = CY * 0.5 * f
    m_hand = CM * (math.sqrt(3) / 2) / (1.0 + 5.0 / 6.0) * f * L  # sin 60° / (1 + (π − π/6)/π)
    out = wf.wave_forces(math.radians(30), 4.0, 100.0, coeffs(), length=L, speed_along_waves=2.0,
                         wave_celerity=12.0, a0=3.3, a1=1.0, rho=RHO, gravity=G)
    assert float(out.surge) == pytest.approx(x_hand, rel=1e-6)
    assert float(out.sway) == pytest.approx(y_hand, rel=1e-6)
    assert float(out.yaw) == pytest.approx(m_hand, rel=1e-6)


def test_default_celerity_is_deep_water():
    a = wf.wave_attenuation(100.0, L, speed_along_waves=3.0, a1=2.0)
    vw = math.sqrt(9.80665 * 100.0 / (2 * math.pi))
    assert float(a) == pytest.approx(math.exp(-3.3 * 100 / 150) * (1 + 2.0 * 3.0 / vw), rel=1e-12)


def test_arm_eq11_as_printed():
    # ℓ_w = Cm/Cy · sin(2·45°)/(2 − 0.25) · L
    arm = wf.wave_force_arm(math.radians(45), coeffs(), length=L)
    assert float(arm) == pytest.approx(CM / CY * 1.0 / 1.75 * L, rel=1e-10)


@pytest.mark.parametrize("q_deg", [10.0, 35.0, 60.0, 90.0, 120.0, 170.0])
def test_symmetries(q_deg):
    q = math.radians(q_deg)
    kw = dict(length=L, speed_along_waves=0.0)
    plus = wf.wave_forces(q, 3.0, 120.0, coeffs(), **kw)
    minus = wf.wave_forces(-q, 3.0, 120.0, coeffs(), **kw)
    assert float(minus.surge) == pytest.approx(float(plus.surge), rel=1e-12)  # X_w even
    assert float(minus.sway) == pytest.approx(-float(plus.sway), rel=1e-12)   # Y_w odd
    assert float(minus.yaw) == pytest.approx(-float(plus.yaw), rel=1e-12)     # M_w odd


@pytest.mark.parametrize("q_deg", [0.0, 90.0, -90.0, 180.0])
def test_moment_zero_head_and_beam(q_deg):
    out = wf.wave_forces(math.radians(q_deg), 5.0, 80.0, coeffs(), length=L)
    scale = RHO * 9.81 * L**2 * 2.5**2
    assert abs(float(out.yaw)) < 1e-12 * scale
    assert abs(float(wf.wave_force_arm(math.radians(q_deg), coeffs(), length=L))) < 1e-12 * L


def test_head_seas_resist_and_zero_height():
    head = wf.wave_forces(0.0, 4.0, 100.0, coeffs(), length=L)
    assert float(head.surge) < 0 and float(head.sway) == 0.0
    calm = wf.wave_forces(0.7, 0.0, 100.0, coeffs(), length=L)
    assert all(float(v) == 0.0 for v in calm)


def test_batched_equals_one_by_one():
    q = np.radians([[10.0, 50.0, 100.0], [150.0, -30.0, -120.0]])
    h = np.array([[1.0], [6.0]])
    out = wf.wave_forces(q, h, 90.0, coeffs(), length=L)
    assert out.sway.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            one = wf.wave_forces(q[i, j], h[i, 0], 90.0, coeffs(), length=L)
            for a, b in zip(out, one):
                assert a[i, j] == pytest.approx(float(b), rel=1e-14)
    c = wf.wave_force_coefficients([150.0, 120.0], [20.0, 16.0], [8.0, 7.0], [0.7, 0.65])
    c1 = wf.wave_force_coefficients(120.0, 16.0, 7.0, 0.65)
    assert c.cm[1] == pytest.approx(float(c1.cm))


@pytest.mark.parametrize(
    "hull, match",
    [
        ((200.0, 25.0, 8.0, 0.7), r"L/T = 25 outside the published range 10 < L/T < 23"),
        ((160.0, 30.0, 7.5, 0.7), r"B/T = 4 outside the published range 1 < B/T < 3\.7"),
        ((150.0, 12.0, 8.0, 0.7), r"L/B = 12\.5 outside the published range 5 < L/B < 12"),
        ((150.0, 20.0, 8.0, 0.85), r"block coefficient δ = 0\.85 outside .* 0\.6 < block"),
    ],
)
def test_validity_warnings_and_strict(hull, match):
    with pytest.warns(ValidityRangeWarning, match=match):
        wf.wave_force_coefficients(*hull)
    with pytest.raises(ParameterError, match=match):
        wf.wave_force_coefficients(*hull, strict=True)
    with strict_validity(), pytest.raises(ParameterError, match=match):
        wf.wave_force_coefficients(*hull)


def test_in_range_hull_does_not_warn():
    coeffs()  # filterwarnings = error: a warning would fail this test


def test_a1_range_and_bad_inputs():
    with pytest.warns(ValidityRangeWarning, match=r"A1 = 9 outside .* 1 <= A1 <= 8\.5"):
        wf.wave_attenuation(100.0, L, a1=9.0)
    with pytest.raises(ParameterError, match=r"A1 = 0\.5"):
        wf.wave_attenuation(100.0, L, a1=0.5, strict=True)
    with pytest.raises(ParameterError, match=r"`wave_height` must be >= 0 \[m\]"):
        wf.wave_forces(0.3, -1.0, 100.0, coeffs(), length=L)
    with pytest.raises(ParameterError, match=r"`draft` must be > 0 \[m\]"):
        wf.wave_force_coefficients(150.0, 20.0, 0.0, 0.7)
    with pytest.raises(ParameterError, match=r"`wave_length` must be > 0 \[m\]"):
        wf.wave_forces(0.3, 1.0, 0.0, coeffs(), length=L)


def test_voitkunsky_eq1_and_eq4():
    # eq. (1): 0.5·1025·150·4·0.2 = 61500
    assert float(wf.voitkunsky_lateral_force(150.0, 4.0, 0.2, rho=1025.0)) == pytest.approx(61500.0)
    # eq. (4): 4e-4·1025·9.81·150·0.2·10² = 12066.3
    r = wf.voitkunsky_lateral_force_from_wind(150.0, 10.0, 0.2, rho=1025.0, gravity=9.81)
    assert float(r) == pytest.approx(12066.3, rel=1e-9)
    cb = wf.disturbing_force_coefficient(150.0, 0.2, rho=1025.0, gravity=9.81)
    assert float(cb) * 100.0 == pytest.approx(float(r))


def test_wind_to_sea_eq2_eq3():
    # τ = 0.65·0.8·15 = 7.8 s; λ = 1.55·7.8² = 94.302 m ≈ 0.655·0.8²·15² = 94.32 m; h = 0.03·225
    assert float(wd.wave_period_from_wind(15.0)) == pytest.approx(7.8)
    assert float(wd.wave_length_from_wind(15.0)) == pytest.approx(94.302)
    assert float(wd.wave_length_from_wind(15.0)) == pytest.approx(0.655 * 0.64 * 225.0, rel=1e-3)
    assert float(wd.wave_height_from_wind(15.0)) == pytest.approx(6.75)
    np.testing.assert_allclose(wd.wave_height_from_wind([0.0, 10.0]), [0.0, 3.0])
    with pytest.raises(ParameterError, match=r"`wind_speed` must be >= 0 \[m/s\]"):
        wd.wave_period_from_wind(-1.0)


def test_apparent_wind_and_wind_loads():
    head = wd.apparent_wind(10.0, 0.0, 5.0, 0.0)
    assert float(head.speed) == pytest.approx(15.0) and float(head.angle) == pytest.approx(0.0)
    beam = wd.apparent_wind(10.0, math.pi / 2, 5.0, 0.0)
    assert float(beam.speed) == pytest.approx(math.sqrt(125.0))
    assert float(beam.angle) == pytest.approx(math.atan2(10.0, 5.0))
    # relative to the heading: wind from the north, ship heading east -> from port (−90°)
    port = wd.apparent_wind(10.0, 0.0, 0.0, math.pi / 2)
    assert float(port.angle) == pytest.approx(-math.pi / 2)
    # Y = 0.37 sin 30° · 1.225 · 1000 · 20² ; arm = 0.25 + 10/150 − 30/360
    y = wd.wind_lateral_force(20.0, math.radians(30), 1000.0)
    assert float(y) == pytest.approx(0.37 * 0.5 * 1.225 * 1000 * 400)
    n = wd.wind_yaw_moment(20.0, math.radians(30), 1000.0, length=150.0, sail_centre=10.0)
    assert float(n) == pytest.approx((0.25 + 10 / 150 - 30 / 360) * 150 * float(y))
    n_port = wd.wind_yaw_moment(20.0, -math.radians(30), 1000.0, length=150.0, sail_centre=10.0)
    assert float(n_port) == pytest.approx(-float(n))
