"""One fit-result base (issue 47, item 1): the reduced steady-turn fit and the Nomoto, MMG
hull and linear fits share :class:`~seahelm.identification.fit_result.FitResult` (standard
errors, correlations, intervals, what is not identified), each keeping its attributes."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy import stats

from seahelm.identification.fit_result import FitResult
from seahelm.identification.linear_fit import LinearFit
from seahelm.identification.mmg_fit import HullFit
from seahelm.identification.nomoto_fit_result import NomotoFit
from seahelm.identification.reduced.fitting import fit_steady_turns
from seahelm.identification.reduced.forms import SteadyTurnFit

#: SteadyTurnFit's fields before the shared base: kept, in order
STEADY_TURN_FIELDS = ["coef", "covariance", "stderr", "residuals", "residual_rms",
                      "condition_number", "condition_number_scaled", "yaw_rate",
                      "rudder_angle", "weights", "method", "form", "absolute_sigma", "elapsed"]


def _turns(noise: float = 2e-5, n: int = 12) -> tuple[np.ndarray, np.ndarray]:
    # points of a ω² + b ω + α (1 + c ω) = 0 with a = 40, b = 12, c = -80 (paper form), and
    # noise on the rudder angle
    rng = np.random.default_rng(7)
    w = np.linspace(0.001, 0.012, n)  # turns to one side (the paper form)
    a, b, c = 40.0, 12.0, -80.0
    al = -(a * w * w + b * w) / (1.0 + c * w)
    return w, al + noise * rng.standard_normal(n)


@pytest.mark.parametrize("cls", [SteadyTurnFit, NomotoFit, HullFit, LinearFit])
def test_every_fit_result_is_a_fit_result_with_the_same_intervals(cls):
    assert issubclass(cls, FitResult)
    assert cls.confidence_intervals is FitResult.confidence_intervals
    assert cls.standard_errors is FitResult.standard_errors


def test_steady_turn_fit_keeps_its_fields():
    assert [f.name for f in dataclasses.fields(SteadyTurnFit)] == STEADY_TURN_FIELDS


def test_steady_turn_fit_as_a_fit_result():
    w, al = _turns()
    fit = fit_steady_turns(w, al)
    assert fit.names == ("a", "b", "c") and fit.values is fit.coef
    np.testing.assert_array_equal(fit.standard_errors, fit.stderr)
    # a covariance scaled by the residual variance: Student-t with n - 3 degrees of freedom
    assert not fit.absolute_sigma and fit.interval_dof == w.size - 3
    half = stats.t.ppf(0.975, w.size - 3) * np.sqrt(np.diag(fit.covariance))
    np.testing.assert_allclose(fit.confidence_intervals(),
                               np.column_stack([fit.coef - half, fit.coef + half]),
                               rtol=1e-14)
    lo, hi = fit.confidence_intervals().T
    assert np.all(lo < fit.coef) and np.all(fit.coef < hi)
    assert fit.unidentifiable() == {}
    assert [r["name"] for r in fit.parameter_rows()] == ["a", "b", "c"]


def test_steady_turn_fit_with_known_noise_has_normal_intervals():
    w, al = _turns()
    fit = fit_steady_turns(w, al, sigma_rudder_angle=2e-5)
    assert fit.absolute_sigma and fit.interval_dof is None
    half = 1.959963984540054 * np.sqrt(np.diag(fit.covariance))
    np.testing.assert_allclose(fit.confidence_intervals(),
                               np.column_stack([fit.coef - half, fit.coef + half]), rtol=1e-14)


def test_nomoto_intervals_are_the_student_t_ones_as_before():
    # the formula NomotoFit had: t_{0.5 + level/2}(max(dof, 1)) times the standard errors
    cov = np.array([[4e-6, 1e-6, 0.0], [1e-6, 9.0, 0.0], [0.0, 0.0, 1e-8]])
    values = np.array([0.05, 30.0, 0.001])
    for dof, level in ((0, 0.95), (7, 0.9), (500, 0.99)):
        fit = NomotoFit(order=1, names=("gain", "time_constant", "rudder_offset"),
                        values=values, covariance=cov, dof=dof, residual_std=0.01,
                        output="heading", records=("r",), initial_states=np.zeros((1, 2)),
                        equation_error=values, condition_number=1.0, residuals=())
        half = stats.t.ppf(0.5 + level / 2, max(dof, 1)) * np.sqrt(np.diag(cov))
        expected = np.column_stack([values - half, values + half])
        assert np.array_equal(fit.confidence_intervals(level), expected)


def test_a_level_outside_0_1_is_refused():
    w, al = _turns()
    with pytest.raises(ValueError, match=r"must be in \(0, 1\), got 1.5"):
        fit_steady_turns(w, al).confidence_intervals(1.5)


def test_the_old_name_of_the_base():
    import seahelm.identification.fit_result as module

    with pytest.warns(DeprecationWarning, match="FitResult"):
        assert module.CovarianceSummary is FitResult
    assert math.isfinite(module.UNIDENTIFIABLE_RELATIVE_SE)
