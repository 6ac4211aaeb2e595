"""Encounter frequency/spectrum, regular roll and pitch, mount-point kinematics, moment."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from seahelm.constants import GRAVITY
from seahelm.environment import encounter as enc
from seahelm.environment import motion as mo
from seahelm.environment import rational_spectra as rs
from seahelm.errors import ParameterError

D, MU, LAM = 0.32175, 0.214, 1.003
BASE = rs.RakhmaninFirsov2(variance=D, decay_rate=MU, resonance_frequency=LAM)


def test_encounter_frequency_formula():
    w = np.array([0.0, 0.5, 1.0, 2.0])
    v, eps = 6.0, 0.4
    np.testing.assert_allclose(
        enc.encounter_frequency(w, v, eps), w - w**2 * v * math.cos(eps) / GRAVITY, rtol=1e-15
    )
    # beam seas: apparent = true frequency; zero speed: same
    np.testing.assert_allclose(enc.apparent_frequency(w, 6.0, math.pi / 2), w, atol=1e-15)
    np.testing.assert_allclose(enc.apparent_frequency(w, 0.0, 0.0), w)
    # following seas beyond g/(v cos ε): the ship overtakes the waves, ω_e < 0
    assert enc.encounter_frequency(3.0, 10.0, 0.0) < 0
    assert enc.apparent_frequency(3.0, 10.0, 0.0) == pytest.approx(9 * 10 / GRAVITY - 3)


def test_singular_frequency():
    assert enc.singular_frequency(5.0, 0.3) == pytest.approx(GRAVITY / (2 * 5.0 * math.cos(0.3)))
    assert math.isinf(enc.singular_frequency(5.0, math.pi))
    assert math.isinf(enc.singular_frequency(5.0, math.pi / 2))
    assert math.isinf(enc.singular_frequency(0.0, 0.0))
    w_star = enc.singular_frequency(5.0, 0.3)
    h = 1e-6  # dω_e/dω = 0 there
    d = (enc.encounter_frequency(w_star + h, 5.0, 0.3) - enc.encounter_frequency(w_star - h, 5.0, 0.3)) / (2 * h)
    assert abs(d) < 1e-8


@pytest.mark.parametrize("v,eps", [(5.0, 0.0), (5.0, 1.0), (8.0, math.pi), (5.0, 2.2), (5.0, math.pi / 2), (0.0, 0.0)])
def test_encounter_spectrum_preserves_variance(v, eps):
    s = enc.EncounterSpectrum(BASE, v, eps)
    ws = s.singular_apparent_frequency
    f = lambda y: float(s.one_sided(y))  # noqa: E731
    pts = [0.0, ws, 10 * max(LAM, 1.0)] if math.isfinite(ws) else [0.0, LAM, 10.0]
    total = sum(integrate.quad(f, a, b, limit=500, epsabs=0, epsrel=1e-10)[0] for a, b in zip(pts, pts[1:]))
    total += integrate.quad(f, pts[-1], np.inf, limit=500)[0]
    assert total == pytest.approx(D, rel=1e-6)


def test_encounter_spectrum_head_seas_closed_form():
    v, eps = 7.0, math.pi
    s = enc.EncounterSpectrum(BASE, v, eps)
    u = v / GRAVITY  # ω_e = ω + u ω²  →  ω = (−1 + √(1 + 4uω_e))/(2u)
    for we in (0.3, 1.0, 2.5):
        w = (-1 + math.sqrt(1 + 4 * u * we)) / (2 * u)
        expected = float(BASE.one_sided(w)) / (1 + 2 * w * u)
        assert float(s.one_sided(we)) == pytest.approx(expected, rel=1e-12)


def test_encounter_spectrum_following_seas_branches_and_singularity():
    v, eps = 6.0, 0.0
    s = enc.EncounterSpectrum(BASE, v, eps)
    c = v / GRAVITY
    ws = 1 / (4 * c)
    assert s.singular_apparent_frequency == pytest.approx(ws)
    roots = s.wave_frequencies(0.5 * ws)
    assert roots.size == 3
    np.testing.assert_allclose(np.abs(roots - c * roots**2), 0.5 * ws, rtol=1e-12)
    assert s.wave_frequencies(2 * ws).size == 1
    assert math.isinf(float(s.one_sided(ws)))
    # inverse-square-root growth next to the singularity
    a, b = float(s.one_sided(ws * (1 - 1e-4))), float(s.one_sided(ws * (1 - 1e-6)))
    assert b / a == pytest.approx(10.0, rel=0.05)


def test_encounter_bad_inputs():
    with pytest.raises(ParameterError, match="`speed` must be >= 0"):
        enc.encounter_frequency(1.0, -1.0, 0.0)
    with pytest.raises(ParameterError, match="`heading` must be finite"):
        enc.encounter_frequency(1.0, 1.0, float("nan"))
    with pytest.raises(ParameterError, match="`omega` must be >= 0"):
        enc.encounter_frequency(-1.0, 1.0, 0.0)
    with pytest.raises(ParameterError, match="`speed`"):
        enc.EncounterSpectrum(BASE, float("nan"), 0.0)


# ---- motion ---------------------------------------------------------------------------------


def test_harmonic_motion_and_derivatives():
    t = np.linspace(0, 20, 20001)
    m = mo.harmonic_motion(t, 0.1, 0.7, 0.3)
    np.testing.assert_allclose(m.angle, 0.1 * np.sin(0.7 * t + 0.3), rtol=1e-14)
    np.testing.assert_allclose(m.rate[1:-1], np.gradient(m.angle, t)[1:-1], atol=1e-7)
    np.testing.assert_allclose(m.acceleration[1:-1], np.gradient(m.rate, t)[1:-1], atol=1e-7)


def test_harmonic_motion_batched():
    t = np.linspace(0, 10, 11)
    amp = np.array([0.05, 0.1, 0.2])
    m = mo.harmonic_motion(t, amp[:, None], np.array([0.5, 0.6, 0.7])[:, None])
    assert m.angle.shape == (3, 11)
    for i in range(3):
        one = mo.harmonic_motion(t, amp[i], [0.5, 0.6, 0.7][i])
        np.testing.assert_array_equal(m.rate[i], one.rate)


def test_mount_point_kinematics():
    t = np.linspace(0, 30, 301)
    theta, w, arm, speed = 0.15, 0.6, 12.0, 5.0
    v, a, total = mo.mount_point_kinematics(t, theta, w, arm, ship_speed=speed)
    np.testing.assert_allclose(v, theta * w * arm * np.cos(w * t), rtol=1e-14)
    np.testing.assert_allclose(a, -theta * w**2 * arm * np.sin(w * t), rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(total, speed + v)
    np.testing.assert_allclose(mo.mount_point_velocity(np.array([0.1, -0.2]), 3.0), [0.3, -0.6])


def test_disturbance_moment():
    w = np.array([-0.5, 0.0, 0.2])
    np.testing.assert_array_equal(mo.disturbance_moment(w, 10.0, 3.0), [7.0, 10.0, 13.0])


@pytest.mark.parametrize(
    "call,match",
    [
        (lambda: mo.harmonic_motion(1.0, -0.1, 1.0), "`amplitude` must be >= 0"),
        (lambda: mo.harmonic_motion(1.0, 0.1, float("nan")), "`frequency` must be finite"),
        (lambda: mo.mount_point_kinematics(1.0, 0.1, 1.0, -2.0), "`lever_arm` must be >= 0"),
        (lambda: mo.disturbance_moment(0.1, 1.0, -1.0), "`friction_moment` must be >= 0"),
        (lambda: mo.disturbance_moment(float("nan"), 1.0, 1.0), "`angular_rate` must be finite"),
    ],
)
def test_motion_bad_inputs(call, match):
    with pytest.raises(ParameterError, match=match):
        call()
