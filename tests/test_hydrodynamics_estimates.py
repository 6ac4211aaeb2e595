"""Hull derivatives, added masses, rudder/propeller interaction, Clarke's linear model and the
shallow-water corrections estimated from main particulars (seahelm.hydrodynamics)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from seahelm.errors import ParameterError, ValidityRangeWarning, strict_validity
from seahelm.hydrodynamics.hull import HullParticulars, check_ranges
from seahelm.hydrodynamics.hull_derivatives import (
    added_masses,
    hull_derivatives,
    linear_hull_derivatives,
)
from seahelm.hydrodynamics.linear_model import clarke_derivatives, nomoto_constants
from seahelm.hydrodynamics.rudder_propeller import (
    interaction_coefficients,
    rudder_area_dnv,
    rudder_lift_slope,
    wake_fraction_taylor,
)
from seahelm.hydrodynamics.shallow_water import (
    CORRECTED,
    shallow_water_coefficients,
    shallow_water_factors,
)
from seahelm.vessels.mmg import KVLCC2_FULL

KVLCC2 = HullParticulars(length=320.0, beam=58.0, draft=20.8, block_coefficient=0.8098,
                         displacement=312_600.0, x_G=11.2)


def test_added_masses_reproduce_the_kvlcc2_captive_values():
    """Motora's regressions against Yasukawa & Yoshimura's (2015) captive m'_x, m'_y, J'_z:
    within 6 % (a wrong transcription of any term is off by far more)."""
    est = added_masses(KVLCC2)
    for name in ("m_x", "m_y", "J_z"):
        captive = getattr(KVLCC2_FULL, name)
        assert est[name].value == pytest.approx(captive, rel=0.06), name
        assert "Motora" in est[name].source


def test_linear_derivatives_kvlcc2_close_to_captive_and_by_hand():
    """Kijima's linear derivatives: by hand for the KVLCC2 (k = 0.13, C_b B/L = 0.14678), and
    N'_v, N'_r within 10 % of the captive tests (Y'_v is the regression's known weak term)."""
    lin = linear_hull_derivatives(KVLCC2, m_x=0.022)
    k = 2 * 20.8 / 320
    cbl = 0.8098 * 58 / 320
    assert lin["Y_v"].value == pytest.approx(-(math.pi / 2 * k + 1.4 * cbl), rel=1e-12)
    assert lin["N_v"].value == pytest.approx(-0.13, rel=1e-12)
    assert lin["N_r"].value == pytest.approx(-0.54 * 0.13 + 0.13 ** 2, rel=1e-12)
    assert lin["N_v"].value == pytest.approx(KVLCC2_FULL.N_v, rel=0.10)
    assert lin["N_r"].value == pytest.approx(KVLCC2_FULL.N_r, rel=0.10)
    assert lin["Y_r"].value == pytest.approx(KVLCC2_FULL.Y_r, rel=0.20)


def test_kijima_y_r_equals_yoshimura_form_at_even_keel():
    """(m' + m'_x) − 1.5 C_b B/L = m'_x + 0.5 C_b B/L when ∇ = C_b L B d (m' = 2 C_b B/L)."""
    hull = HullParticulars(length=120, beam=18, draft=7, block_coefficient=0.7)
    lin = linear_hull_derivatives(hull, m_x=0.01)
    assert lin["Y_r"].value == pytest.approx(0.01 + 0.5 * 0.7 * 18 / 120, rel=1e-12)


def test_trim_by_the_stern_stiffens_the_hull():
    """Kijima's trim terms: τ > 0 raises |Y'_v| and |N'_r|, lowers |N'_v| (more stable)."""
    even = linear_hull_derivatives(KVLCC2, m_x=0.022)
    trimmed = linear_hull_derivatives(
        HullParticulars(length=320, beam=58, draft=20.8, block_coefficient=0.8098,
                        trim=2.08), m_x=0.022)
    assert trimmed["Y_v"].value == pytest.approx(even["Y_v"].value * 1.067, rel=1e-12)
    assert abs(trimmed["N_v"].value) < abs(even["N_v"].value)
    assert abs(trimmed["N_r"].value) > abs(even["N_r"].value)


def test_every_mmg_hull_field_is_estimated_with_a_source():
    est = hull_derivatives(KVLCC2)
    hull_fields = {"X_vv", "X_vr", "X_rr", "X_vvvv", "Y_v", "Y_r", "Y_vvv", "Y_vvr", "Y_vrr",
                   "Y_rrr", "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr", "m_x", "m_y",
                   "J_z"}
    assert set(est) == hull_fields
    assert all(c.source and math.isfinite(c.value) for c in est.values())


def test_fujii_lift_slope_analytic_points():
    assert rudder_lift_slope(1.5, 1.0).value == pytest.approx(6.13 * 2.25 / 4.5)  # Λ = 2.25
    assert rudder_lift_slope(15.8, 112.5).value == pytest.approx(3.0438, abs=1e-4)
    with pytest.raises(ParameterError, match="rudder_area"):
        rudder_lift_slope(1.0, 0.0)
    with pytest.warns(ValidityRangeWarning, match="Fujii.*aspect ratio"):
        rudder_lift_slope(5.0, 1.0)  # Λ = 25


def test_dnv_rudder_area_and_taylor_wake_by_hand():
    hull = HullParticulars(length=100, beam=15, draft=5, block_coefficient=0.7)
    assert rudder_area_dnv(hull).value == pytest.approx(5.0 * (1 + 25 * 0.15 ** 2))
    assert wake_fraction_taylor(hull).value == pytest.approx(0.30)
    kvlcc2 = interaction_coefficients(KVLCC2)
    assert kvlcc2["t_R"].value == pytest.approx(1 - (0.28 * 0.8098 + 0.55))
    assert kvlcc2["gamma_R_minus"].value == kvlcc2["gamma_R_plus"].value


@pytest.mark.parametrize("field, value, match", [
    ("beam", 400.0, "beam.*less than the length"),
    ("block_coefficient", 1.2, r"block_coefficient.*\(0.3, 1\)"),
    ("block_coefficient", 0.2, r"\(0.3, 1\)"),
    ("draft", -1.0, "draft.*> 0"),
    ("trim", 30.0, "trim.*smaller"),
    ("x_G", 200.0, "x_G.*L/2"),
    ("displacement", 100.0, "disagree by more than 10"),
    ("length", float("nan"), "finite"),
])
def test_unphysical_particulars_are_errors_naming_the_field(field, value, match):
    kwargs = dict(length=320.0, beam=58.0, draft=20.8, block_coefficient=0.81)
    kwargs[field] = value
    with pytest.raises(ParameterError, match=match) as info:
        HullParticulars(**kwargs)
    assert info.value.field == field


def test_outside_the_data_warns_naming_formula_parameter_and_range_and_strict_raises():
    slender = HullParticulars(length=200, beam=20, draft=6, block_coefficient=0.45)  # L/B 10
    with pytest.warns(ValidityRangeWarning, match=r"Kijima.*L/B = 10 outside 4..8"):
        linear_hull_derivatives(slender, m_x=0.01)
    with strict_validity(), pytest.raises(ParameterError, match="C_b = 0.45 outside"):
        hull_derivatives(slender)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hull_derivatives(KVLCC2)  # inside every range: silent
        check_ranges("x", {"a": (1.0, 0.0, 2.0)})


# -- Clarke et al. (1983) and Nomoto ------------------------------------------------------
def test_clarke_derivatives_by_hand():
    hull = HullParticulars(length=100, beam=15, draft=5, block_coefficient=0.6)
    c = clarke_derivatives(hull)
    t = -math.pi * 0.05 ** 2
    assert c["Y_v"].value == pytest.approx(t * (1 + 0.4 * 0.6 * 3))
    assert c["N_r"].value == pytest.approx(t * (0.25 + 0.039 * 3 - 0.56 * 0.15))
    assert c["Y_vdot"].value == pytest.approx(t * (1 + 0.16 * 0.6 * 3 - 5.1 * 0.15 ** 2))
    assert c["N_rdot"].value == pytest.approx(t * (1 / 12 + 0.017 * 0.6 * 3 - 0.33 * 0.15))


def test_nomoto_constants_of_a_decoupled_system():
    """Sway and yaw uncoupled: r/δ = b/(m₂ s + n₂₂), so K' = b/n₂₂, one T is m₂/n₂₂ and the
    sway pole cancels against the zero (T_3 = the sway time constant)."""
    m1, m2, n11, n22, b = 0.3, 0.02, 0.4, 0.05, 0.01
    nc = nomoto_constants(np.diag([m1, m2]), np.diag([n11, n22]), np.array([0.0, b]),
                          length=100.0, speed=5.0)
    scale = 100.0 / 5.0
    assert nc.gain == pytest.approx(b / n22 / scale)
    assert sorted([nc.t1, nc.t2]) == pytest.approx(sorted([m1 / n11 * scale, m2 / n22 * scale]))
    assert nc.t3 == pytest.approx(m1 / n11 * scale)
    assert nc.time_constant == pytest.approx(m2 / n22 * scale)


def test_nomoto_refuses_an_unstable_model():
    with pytest.raises(ParameterError, match="two real negative poles"):
        nomoto_constants(np.eye(2), -np.eye(2), np.array([0.0, 1.0]), length=1.0, speed=1.0)


# -- shallow water -------------------------------------------------------------------------
def test_deep_water_changes_nothing_and_large_depth_tends_to_it():
    deep = KVLCC2_FULL.as_dict()
    assert shallow_water_coefficients(deep, KVLCC2, math.inf) == deep
    far = shallow_water_factors(KVLCC2, 1e4 * 20.8)
    for name in CORRECTED:  # the default keeps the deep-water wake and thrust deduction
        assert far[name] == pytest.approx(1.0, abs=2e-3), name
    far = shallow_water_factors(KVLCC2, 1e4 * 20.8, propulsion="taimuri")
    for name in CORRECTED:
        if name == "t_P":  # the regression's own limit, 1 + 0.004 (29.495 − 14.089 x + ...)
            x = 0.8098 * 320 / 58
            assert far[name] == pytest.approx(1 + 0.004 * (29.495 - 14.089 * x + 1.6486 * x * x),
                                              abs=1e-4)
        else:
            assert far[name] == pytest.approx(1.0, abs=2e-3), name


def test_shallow_water_raises_sway_damping_and_added_mass_as_depth_falls():
    ratios = [4.0, 2.0, 1.5, 1.2]
    yv = [shallow_water_factors(KVLCC2, r * 20.8)["Y_v"] for r in ratios]
    my = [shallow_water_factors(KVLCC2, r * 20.8)["m_y"] for r in ratios]
    assert np.all(np.diff(yv) > 0) and np.all(np.diff(my) > 0)
    assert yv[-1] > 3.0  # Y'_v more than triples at h/T = 1.2 (Kijima's factor 4.2)


def test_depth_at_or_below_the_draft_is_an_error_and_below_1_2_warns():
    with pytest.raises(ParameterError, match="greater than the draft") as info:
        shallow_water_factors(KVLCC2, 20.8)
    assert info.value.field == "water_depth"
    with pytest.warns(ValidityRangeWarning, match=r"h/d = 1.1 outside 1.2"):
        shallow_water_factors(KVLCC2, 1.1 * 20.8)
    with strict_validity(), pytest.raises(ParameterError, match="h/d"):
        shallow_water_factors(KVLCC2, 1.1 * 20.8)


def test_thrust_deduction_is_corrected_on_one_minus_t():
    f = shallow_water_factors(KVLCC2, 1.5 * 20.8, propulsion="taimuri")
    out = shallow_water_coefficients({"t_P": 0.22, "w_P0": 0.4}, KVLCC2, 1.5 * 20.8,
                                     propulsion="taimuri")
    assert out["t_P"] == pytest.approx(1 - f["t_P"] * 0.78)
    assert out["w_P0"] == pytest.approx(0.4 * f["w_P0"])


def test_linear_sets_differ_only_in_the_four_linear_derivatives():
    a = shallow_water_factors(KVLCC2, 2 * 20.8)
    k = shallow_water_factors(KVLCC2, 2 * 20.8, linear="kijima")
    differ = {n for n in CORRECTED if a[n] != k[n]}
    assert differ == {"Y_v", "Y_r", "N_r", "N_vvr", "N_vrr"}  # N'_v: Ankudinov's f_nv in both
    t = 0.5
    assert k["Y_v"] == pytest.approx(1 / (1 - t) ** (0.4 * 0.8098 * 58 / 20.8) - t)
    assert a["Y_v"] == pytest.approx(1.5 * a["X_rr"] - 0.5)  # f_yv = 1.5 f_nr − 0.5
    with pytest.raises(ValueError, match="valid: ankudinov, kijima"):
        shallow_water_factors(KVLCC2, 2 * 20.8, linear="nope")
