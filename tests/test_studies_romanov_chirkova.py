"""Romanov & Chirkova: the printed criterion of eq. (5) is a named object next to the proper
ones, and the paper's three-turn procedure on a model ship.

Expected values follow from the formulas of the paper and the notes of the seeds guide
(the plain sum of eq. (5) is no criterion; eq. (4) drops d α² with d = c²/4a), never from
values produced by the code under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.identification.reduced.fitting import fit_lsq
from seahelm.identification.reduced.turns import stable_steady_turn
from seahelm.studies import romanov_chirkova as rc
from seahelm.vessels.voitkunsky import MARINER_VOITKUNSKY

A, B, C = -320.0, -5.5, 17.0  # a synthetic reduced model (Mariner-like scale)
W = np.array([0.01, 0.025, 0.04])
ALPHA = -(A * W**2 + B * W) / (1.0 + C * W)  # exact points of eq. (4)


def test_criteria_are_reachable_by_name():
    assert rc.CRITERIA == {"printed": rc.PRINTED_EQ5, "squared": rc.SQUARED,
                           "absolute": rc.ABSOLUTE}
    with pytest.raises(ParameterError, match="unknown eq. \\(5\\) criterion 'nope'.*printed"):
        rc.eq5_criterion(A, B, C, W, ALPHA, "nope")


def test_printed_eq5_is_unbounded_below_and_the_corrected_one_is_not():
    # at the true coefficients every residual vanishes: both criteria are 0
    assert rc.eq5_criterion(A, B, C, W, ALPHA, "squared") == pytest.approx(0.0, abs=1e-20)
    assert rc.eq5_criterion(A, B, C, W, ALPHA, "printed") == pytest.approx(0.0, abs=1e-12)
    # moving b alone by −k lowers the plain sum by k Σ ω_i without bound (ω_i > 0) ...
    k = np.array([1.0, 1e3, 1e6])
    printed = rc.eq5_criterion(A, B - k, C, W, ALPHA, rc.PRINTED_EQ5)
    np.testing.assert_allclose(printed, -k * W.sum(), rtol=1e-9)
    # ... while the squared and absolute sums grow: the true coefficients are their minimum
    assert np.all(rc.eq5_criterion(A, B - k, C, W, ALPHA, rc.SQUARED) > 0)
    np.testing.assert_allclose(rc.eq5_criterion(A, B - k, C, W, ALPHA, "absolute"),
                               k * W.sum(), rtol=1e-9)


def test_three_turn_study_on_the_mariner():
    s = rc.three_turn_study()
    np.testing.assert_allclose(s.rudder_angle, np.radians([5.0, 15.0, 25.0]))
    # eq. (4) through three turns: exactly determined, residuals vanish
    assert s.fit.residual_rms < 1e-12
    # the closed form of the branch satisfies d = c²/4a (the α² term eq. (4) drops) ...
    cf = s.closed_form
    assert cf.branch == 1 and cf.d == pytest.approx(cf.c**2 / (4 * cf.a), rel=1e-12)
    # ... so the three-term fit is not the closed-form (a, b, c): the d α² term is absorbed
    assert abs(s.fit.coef[0] / cf.a - 1) > 0.05
    # but it predicts the held-out 10°, 20°, 30° turns closely (docs: within 0.2 %)
    assert s.max_relative_error < 2e-3
    # the four-coefficient exact form from four turns recovers the closed form
    al = np.radians([5.0, 12.0, 20.0, 28.0])
    w = np.array([stable_steady_turn(MARINER_VOITKUNSKY, a).yaw_rate for a in al])
    ex = fit_lsq(w, al, form="exact")
    np.testing.assert_allclose(ex.coef, [cf.a, cf.b, cf.c, cf.d], rtol=1e-6)


def test_three_turn_study_needs_three_turns_on_one_branch():
    with pytest.raises(ParameterError, match="three angles"):
        rc.three_turn_study(rudder_angles=(0.1, 0.2))
    with pytest.raises(ParameterError, match="one sign"):
        rc.three_turn_study(rudder_angles=(math.radians(-10.0), 0.1, 0.2))


def test_brute_force_search_takes_the_criteria_as_objects():
    from seahelm.identification.reduced.criteria import CRITERIA, SQUARED
    from seahelm.identification.reduced.fitting import fit_brute_force

    assert rc.SQUARED is SQUARED and set(CRITERIA) == {"squared", "absolute"}
    bounds = [(-400.0, -200.0), (-8.0, -3.0), (9.0, 25.0)]  # the truth on the grid
    # on a grid through the true (a, b, c) the proper criteria find them ...
    for crit in ("squared", rc.ABSOLUTE):
        fit = fit_brute_force(W, ALPHA, bounds=bounds, n_grid=41, criterion=crit)
        np.testing.assert_allclose(fit.coef, [A, B, C], rtol=1e-9)
    # ... the printed plain sum, linear in (a, b, c), runs to a corner of the box: each
    # coefficient to the bound where its term Σ ω_i², Σ ω_i, Σ α_i ω_i lowers the sum
    fit = fit_brute_force(W, ALPHA, bounds=bounds, n_grid=41, criterion=rc.PRINTED_EQ5)
    slopes = [np.sum(W**2), np.sum(W), np.sum(ALPHA * W)]
    corner = [lo if s > 0 else hi for (lo, hi), s in zip(bounds, slopes)]
    np.testing.assert_allclose(fit.coef, corner, rtol=1e-12)
    with pytest.raises(ValueError, match="unknown criterion 'printed'; valid: absolute, squared"):
        fit_brute_force(W, ALPHA, criterion="printed")  # (the printed one is the study's)
