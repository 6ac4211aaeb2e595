"""Wageningen B-series polynomials (Oosterveld & van Oossanen 1975): published values, physics,
the quadratic fit for the MMG model, batches and every validation branch."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError, ValidityRangeWarning, strict_validity
from seahelm.hydrodynamics import propeller_series as ps
from seahelm.vessels.mmg import KVLCC2_FULL


def test_table_sizes():
    assert len(ps.KT_TERMS) == 39 and len(ps.KQ_TERMS) == 47
    assert len({t[1:] for t in ps.KT_TERMS}) == 39  # no exponent set twice
    assert len({t[1:] for t in ps.KQ_TERMS}) == 47


def test_the_disputed_kq_coefficient_has_the_sign_taken():
    # the one sign difference between the two transcriptions (module docstring)
    (c,) = [t[0] for t in ps.KQ_TERMS if t[1:] == (1, 0, 2, 1)]
    assert c == -0.00383637


# Kuiper, G. (1992), The Wageningen propeller series, MARIN Publication 92-001: K_T read off the
# open-water charts by hand, as tabulated in GijsB/propy, test/test_wageningen_b.py
# (test_kt_kuiper, tolerance 4e-3 there; chart reading is good to about ±0.004).
KUIPER_CHARTS = [
    (3, 0.35, 0.6, [0.2, 0.4, 0.6], [0.175, 0.115, 0.042]),
    (3, 0.65, 1.0, [0.2, 0.4, 0.6, 0.8, 1.0], [0.375, 0.296, 0.21, 0.118, 0.025]),
    (3, 0.65, 1.4, [0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4],
     [0.56, 0.486, 0.4, 0.31, 0.214, 0.12, 0.032]),
    (5, 0.60, 0.8, [0.2, 0.4, 0.6, 0.8], [0.298, 0.224, 0.135, 0.036]),
    (5, 0.60, 1.0, [0.2, 0.4, 0.6, 0.8, 1.0], [0.39, 0.324, 0.24, 0.142, 0.04]),
    (5, 0.90, 1.2, [0.2, 0.4, 0.6, 0.8, 1.0, 1.2], [0.526, 0.444, 0.348, 0.242, 0.136, 0.026]),
]


@pytest.mark.parametrize("blades,area,pitch,J,kt", KUIPER_CHARTS)
def test_kuiper_chart_readings(blades, area, pitch, J, kt):
    np.testing.assert_allclose(ps.thrust_coefficient(J, pitch, area, blades), kt, atol=4e-3)


def test_kuiper_worked_example_b4_55():
    # Kuiper (1992) ch. 9.3 (as quoted in GijsB/propy, test/test_wageningen_b.py,
    # test_optimization_max_diameter): B4-55, P/D 1.0, J 0.699: K_T 0.181, K_Q 0.0310, η 0.651
    assert float(ps.thrust_coefficient(0.699, 1.0, 0.55, 4)) == pytest.approx(0.181, abs=6e-4)
    assert float(ps.torque_coefficient(0.699, 1.0, 0.55, 4)) == pytest.approx(0.0310, abs=6e-5)
    assert float(ps.open_water_efficiency(0.699, 1.0, 0.55, 4)) == pytest.approx(0.651,
                                                                                 abs=6e-4)


@pytest.mark.parametrize("blades,area,pitch", [(3, 0.5, 0.6), (4, 0.7, 1.0), (5, 0.75, 1.2),
                                               (4, 0.431, 0.721), (7, 1.0, 1.4)])
def test_thrust_decreases_with_J_and_efficiency_is_below_one(blades, area, pitch):
    j0 = ps.zero_thrust_advance_ratio(pitch, area, blades)
    J = np.linspace(0.0, j0, 60)[:-1]
    kt = ps.thrust_coefficient(J, pitch, area, blades)
    assert np.all(np.diff(kt) < 0)
    assert np.all(kt > 0) and abs(float(ps.thrust_coefficient(j0, pitch, area, blades))) < 1e-9
    eta = ps.open_water_efficiency(J[1:], pitch, area, blades)
    assert np.all((eta > 0) & (eta < 1))
    assert np.all(ps.torque_coefficient(J, pitch, area, blades) > 0)


@pytest.mark.parametrize("J", [0.0, 0.2, 0.4, 0.6])
def test_thrust_increases_with_pitch(J):
    pitch = np.linspace(0.6, 1.4, 9)
    kt = ps.thrust_coefficient(J, pitch, 0.7, 4)
    assert np.all(np.diff(kt) > 0)


def test_reynolds_correction_vanishes_at_the_series_reynolds_number_and_helps_above():
    J = np.linspace(0.0, 0.7, 8)
    base_t = ps.thrust_coefficient(J, 1.0, 0.7, 4)
    base_q = ps.torque_coefficient(J, 1.0, 0.7, 4)
    near = 2.0e6 * (1 + 1e-9)
    np.testing.assert_allclose(ps.thrust_coefficient(J, 1.0, 0.7, 4, reynolds=near), base_t,
                               atol=4e-4)
    np.testing.assert_allclose(ps.torque_coefficient(J, 1.0, 0.7, 4, reynolds=near), base_q,
                               atol=3e-5)
    # a ship-scale Rn: less friction, so less torque and a higher efficiency
    eta = ps.open_water_efficiency(J[1:], 1.0, 0.7, 4)
    eta_ship = ps.open_water_efficiency(J[1:], 1.0, 0.7, 4, reynolds=1e8)
    assert np.all(ps.torque_coefficient(J, 1.0, 0.7, 4, reynolds=1e8) < base_q)
    assert np.all(eta_ship > eta)
    # Rn = 2e6 exactly: no correction
    np.testing.assert_array_equal(ps.thrust_coefficient(J, 1.0, 0.7, 4, reynolds=2e6), base_t)


def test_batch_equals_single():
    J = np.array([[0.1, 0.3, 0.5], [0.2, 0.4, 0.6]])
    pitch = np.array([[0.8], [1.1]])
    area = np.array([0.5, 0.7, 0.9])
    blades = 4
    batch = ps.torque_coefficient(J, pitch, area, blades, reynolds=1e7)
    assert batch.shape == (2, 3)
    for i in range(2):
        for k in range(3):
            single = ps.torque_coefficient(float(J[i, k]), float(pitch[i, 0]), float(area[k]),
                                           blades, reynolds=1e7)
            assert single.shape == ()
            assert float(single) == batch[i, k]
    blades_batch = ps.thrust_coefficient(0.4, 1.0, 0.7, np.array([3, 4, 5]))
    assert [float(ps.thrust_coefficient(0.4, 1.0, 0.7, z)) for z in (3, 4, 5)] == list(
        blades_batch)


@pytest.mark.parametrize("blades,area,pitch", [(4, 0.7, 1.0), (3, 0.5, 0.6), (5, 1.0, 1.4)])
def test_quadratic_fit_within_its_stated_error(blades, area, pitch):
    fit = ps.fit_thrust_polynomial(pitch, area, blades)
    J = np.linspace(fit.J_min, fit.J_max, 1001)
    err = np.abs(fit(J) - ps.thrust_coefficient(J, pitch, area, blades))
    assert err.max() <= fit.max_error * 1.05 + 1e-12
    assert fit.max_error < 0.025 * fit.k_0 and fit.rms_error <= fit.max_error
    assert fit.J_min == 0.0
    assert fit.J_max == pytest.approx(ps.zero_thrust_advance_ratio(pitch, area, blades))
    assert fit.k_0 == pytest.approx(float(ps.thrust_coefficient(0.0, pitch, area, blades)),
                                    abs=fit.max_error)


def test_fit_over_a_given_range_is_cut_at_zero_thrust():
    j0 = ps.zero_thrust_advance_ratio(1.0, 0.7, 4)
    fit = ps.fit_thrust_polynomial(1.0, 0.7, 4, J_range=(0.2, 5.0))
    assert (fit.J_min, fit.J_max) == (0.2, pytest.approx(j0))
    narrow = ps.fit_thrust_polynomial(1.0, 0.7, 4, J_range=(0.3, 0.6))
    assert narrow.J_max == 0.6 and narrow.max_error < fit.max_error


def test_kvlcc2_propeller_against_seahelm_mmg_polynomial():
    # KVLCC2: Z = 4, P/D 0.721, A_E/A_0 0.431 (values of the brief; D_P 9.86 m in
    # /work/shared/reference/kvlcc2_mmg.md). Its propeller is not a B-series one, so the fit is
    # compared, not asserted equal: the B-series K_T(0) is within 0.3 % of the MMG k_0, but its
    # slope is flatter (k_1 −0.236 against −0.275): K_T is 9 % higher at J = 0.4 and zero
    # thrust comes at J 0.816 against 0.768.
    fit = ps.fit_thrust_polynomial(0.721, 0.431, 4)
    p = KVLCC2_FULL
    assert (p.k_0, p.k_1, p.k_2) == (0.2931, -0.2753, -0.1385)
    assert fit.k_0 == pytest.approx(p.k_0, abs=0.002)
    assert fit.k_1 == pytest.approx(-0.2360, abs=5e-4) and fit.k_2 == pytest.approx(-0.1536,
                                                                                    abs=5e-4)
    mmg = p.k_0 + p.k_1 * 0.4 + p.k_2 * 0.16
    ratio = float(ps.thrust_coefficient(0.4, 0.721, 0.431, 4)) / mmg
    assert ratio == pytest.approx(1.086, abs=0.005)
    mmg_zero = (-p.k_1 - math.sqrt(p.k_1**2 - 4 * p.k_2 * p.k_0)) / (2 * p.k_2)
    assert mmg_zero == pytest.approx(0.768, abs=1e-3)
    assert ps.zero_thrust_advance_ratio(0.721, 0.431, 4) == pytest.approx(0.816, abs=1e-3)


# ------------------------------------------------------------------------------------------
# validation: non-physical input raises, outside the series warns


@pytest.mark.parametrize("kwargs,field", [
    (dict(J=-0.1), "J"),
    (dict(J=float("nan")), "J"),
    (dict(pitch_ratio=0.0), "pitch_ratio"),
    (dict(pitch_ratio=-1.0), "pitch_ratio"),
    (dict(area_ratio=-0.5), "area_ratio"),
    (dict(area_ratio=float("inf")), "area_ratio"),
    (dict(blades=1), "blades"),
    (dict(blades=3.5), "blades"),
    (dict(reynolds=0.0), "reynolds"),
    (dict(reynolds=float("nan")), "reynolds"),
])
def test_non_physical_input_raises(kwargs, field):
    args = dict(J=0.5, pitch_ratio=1.0, area_ratio=0.7, blades=4) | kwargs
    with pytest.raises(ParameterError, match=rf"`{field}` must be") as info:
        ps.thrust_coefficient(**args)
    assert info.value.field == field


def test_blades_error_names_unit_and_value():
    with pytest.raises(ParameterError, match=r"`blades` must be an integer number of blades "
                                             r">= 2 \[-\], got 3\.5"):
        ps.torque_coefficient(0.5, 1.0, 0.7, 3.5)


@pytest.mark.parametrize("kwargs,text", [
    (dict(blades=8), r"`blades` = 8 outside the series' range 2 <= blades <= 7"),
    (dict(area_ratio=0.25), r"`area_ratio` = 0\.25 outside the series' range 0\.3 <= "),
    (dict(area_ratio=1.2), r"`area_ratio` = 1\.2 outside"),
    (dict(pitch_ratio=0.4), r"`pitch_ratio` = 0\.4 outside the series' range 0\.5 <= "
                            r"pitch_ratio <= 1\.4"),
    (dict(pitch_ratio=1.6), r"`pitch_ratio` = 1\.6 outside"),
    (dict(J=1.5), r"`J` = 1\.5 beyond zero thrust \(K_T < 0\)"),
    (dict(reynolds=5e5), r"`reynolds` = 5e\+05 below the series' Rn = 2e6"),
])
def test_outside_the_series_warns_naming_formula_parameter_and_range(kwargs, text):
    args = dict(J=0.5, pitch_ratio=1.0, area_ratio=0.7, blades=4) | kwargs
    with pytest.warns(ValidityRangeWarning, match=r"Wageningen B-series \(Oosterveld & van "
                                                  r"Oossanen 1975\)") as record:
        ps.thrust_coefficient(**args)
    assert any(__import__("re").search(text, str(w.message)) for w in record)


def test_strict_mode_raises_instead():
    with strict_validity(), pytest.raises(ParameterError, match=r"`blades` = 8 outside"):
        ps.thrust_coefficient(0.5, 1.0, 0.7, 8)
    with pytest.raises(ParameterError, match=r"`pitch_ratio` = 1\.6 outside"):
        ps.open_water_efficiency(0.5, 1.6, 0.7, 4, strict=True)


def test_fit_validation():
    with pytest.raises(ParameterError, match=r"`pitch_ratio` must be one number"):
        ps.fit_thrust_polynomial([0.8, 1.0], 0.7, 4)
    with pytest.raises(ParameterError, match=r"`J_range` must be \(J_min, J_max\) with 0 <= "):
        ps.fit_thrust_polynomial(1.0, 0.7, 4, J_range=(0.5, 0.2))
    with pytest.raises(ParameterError, match=r"`J_range` starts at or beyond zero thrust"):
        ps.fit_thrust_polynomial(1.0, 0.7, 4, J_range=(1.5, 2.0))
    with pytest.raises(ParameterError, match=r"`points` must be >= 3"):
        ps.fit_thrust_polynomial(1.0, 0.7, 4, points=2)
    with pytest.warns(ValidityRangeWarning, match=r"`pitch_ratio` = 1\.5 outside"):
        ps.fit_thrust_polynomial(1.5, 0.7, 4)
