"""Four-quadrant Wageningen B4-70 propeller (Roddy, Hess & Faller 2006)."""

import math

import numpy as np
import pytest

from seahelm.hydrodynamics import propeller_series as ps
from seahelm.hydrodynamics.four_quadrant import (
    B4_70_PD10,
    advance_angle,
    ct_cq,
    four_quadrant_kt_kq,
    fourier_coefficients,
    thrust_coefficient_4q,
    torque_coefficient_4q,
)

#: An unlabelled 21-term table (NTNU-MCS/MarPowSim, thrusterInit.m; C_T* directly), most
#: probably van Lammeren et al.'s (1969) B4-70 P/D 1.0 fit: compared, not used.
MARPOWSIM_AT = [2.5350e-02, 1.7820e-01, 1.4674e-02, 2.8054e-02, -1.6328e-02, -5.3041e-02]
MARPOWSIM_BT1 = -7.4777e-01

#: kylemarl/UMFullStop B470data.csv (the P/D 1.4 table, 3 significant figures), rows k = 0..2:
#: the same library's B4_70_14 entry (4 to 5 figures) reads 1.8891, 0, 28.033, -65.683, 1.886,
#: -0.23066 for A_T, B_T.
UMFULLSTOP_PD14 = [(1.89, 0.0), (28.0, -65.7), (1.89, -0.231)]
SHIPSIM_PD14 = [(1.8891, 0.0), (28.033, -65.683), (1.886, -0.23066)]


def test_table_shape_and_scaling():
    assert B4_70_PD10.shape == (31, 4)
    c = fourier_coefficients()
    assert c[1, 0] == pytest.approx(0.17802)
    assert c[1, 3] == pytest.approx(-0.11038)
    with pytest.raises(ValueError, match="shape"):
        fourier_coefficients(np.zeros((3, 3)))


@pytest.mark.parametrize("J", [0.0, 0.2, 0.4, 0.6, 0.8, 1.0])
def test_first_quadrant_matches_the_b_series_polynomials(J):
    """Same propeller (Z 4, A_E/A_0 0.70, P/D 1.0): |ΔK_T| < 0.0116, |ΔK_Q| < 0.0037."""
    kt, kq = four_quadrant_kt_kq(J)
    assert abs(kt - ps.thrust_coefficient(J, 1.0, 0.70, 4)) < 0.0116
    assert abs(kq - ps.torque_coefficient(J, 1.0, 0.70, 4)) < 0.0037


def test_first_quadrant_differences_are_the_stated_maxima_on_a_fine_grid():
    """The module docstring's statement: max |ΔK_T| = 0.01150 (J = 1.0), max |ΔK_Q| = 0.00362
    (J = 0.30) over J = 0, 0.0001, ..., 1.0 (issue 45, item 7: 0.003 was claimed)."""
    J = np.linspace(0.0, 1.0, 10001)
    kt, kq = four_quadrant_kt_kq(J)
    dkt = np.abs(kt - ps.thrust_coefficient(J, 1.0, 0.70, 4))
    dkq = np.abs(kq - ps.torque_coefficient(J, 1.0, 0.70, 4))
    assert dkt.max() == pytest.approx(0.01150, abs=5e-6) and J[dkt.argmax()] == 1.0
    assert dkq.max() == pytest.approx(0.00362, abs=5e-6)
    assert J[dkq.argmax()] == pytest.approx(0.30, abs=0.005)
    assert dkt.max() < 0.0116 and dkq.max() < 0.0037


def test_bollard_and_quadrant_signs():
    assert thrust_coefficient_4q(0.0) == pytest.approx(0.2369, abs=1e-4)
    assert torque_coefficient_4q(0.0) > 0.0
    assert thrust_coefficient_4q(math.pi) < 0.0  # astern bollard: thrust astern
    ratio = thrust_coefficient_4q(math.pi) / thrust_coefficient_4q(0.0)
    assert -0.8 < ratio < -0.7
    assert thrust_coefficient_4q(math.pi / 2) < 0.0  # a stopped propeller is a drag
    assert torque_coefficient_4q(math.pi / 2) < 0.0  # and windmills ahead
    # periodic in beta
    assert thrust_coefficient_4q(-math.pi / 2) == pytest.approx(
        thrust_coefficient_4q(1.5 * math.pi))


def test_compiled_series_equals_numpy():
    c = fourier_coefficients()
    # (every quadrant, and near the angles where a recurrence in k could lose accuracy)
    for b in np.concatenate([np.linspace(-math.pi, math.pi, 13),
                             np.random.default_rng(4).uniform(-math.pi, math.pi, 200),
                             [1e-9, -1e-9, math.pi - 1e-9, 0.5 * math.pi + 1e-12]]):
        ct, cq = ct_cq(b, c)
        assert ct == pytest.approx(thrust_coefficient_4q(b), abs=1e-14)
        assert cq == pytest.approx(torque_coefficient_4q(b), abs=1e-14)


@pytest.mark.parametrize("n_terms", [1, 2, 3, 4, 5, 6, 7, 8, 30])
def test_compiled_series_of_any_length(n_terms):
    # the four rotation chains and the K mod 4 terms after them, against the sums written out
    c = fourier_coefficients()[:n_terms]
    k = np.arange(n_terms)
    for b in np.random.default_rng(n_terms).uniform(-math.pi, math.pi, 50):
        ct, cq = ct_cq(b, c)
        assert ct == pytest.approx(np.cos(k * b) @ c[:, 0] + np.sin(k * b) @ c[:, 1], abs=1e-14)
        assert cq == pytest.approx(np.cos(k * b) @ c[:, 2] + np.sin(k * b) @ c[:, 3], abs=1e-14)


def test_advance_angle_quadrants():
    assert advance_angle(1.0, 1.0, 1.0) == pytest.approx(math.atan2(1.0, 0.7 * math.pi))
    assert advance_angle(1.0, -1.0, 1.0) > math.pi / 2
    assert advance_angle(-1.0, -1.0, 1.0) < -math.pi / 2
    assert advance_angle(0.0, 0.0, 1.0) == 0.0


def test_other_transcriptions():
    """MarPowSim's 20-harmonic fit is close, not equal; UMFullStop's P/D 1.4 rounds ShipSIM's."""
    c = fourier_coefficients()
    diff = np.abs(np.array(MARPOWSIM_AT) - c[:6, 0])
    assert diff.max() < 0.0015 and diff.max() > 0.0
    assert abs(MARPOWSIM_BT1 - c[1, 1]) < 0.001
    for (a, b), (a_ref, b_ref) in zip(UMFULLSTOP_PD14, SHIPSIM_PD14):
        assert float(f"{a_ref:.3g}") == a and float(f"{b_ref:.3g}") == b


def test_negative_advance_ratio_rejected():
    with pytest.raises(ValueError, match="J"):
        four_quadrant_kt_kq(-0.1)
