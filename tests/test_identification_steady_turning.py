"""Steady turns of Voitkunsky's model and identification of the reduced model (Romanov & Chirkova)."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import fsolve

from seahelm.errors import ParameterError
from seahelm.identification.reduced.fitting import (
    fit_brute_force,
    fit_lsq,
    fit_robust,
    fit_steady_turns,
    identify_from_time_series,
)
from seahelm.identification.reduced.forms import REDUCED_FORMS, get_form
from seahelm.identification.reduced.segments import extract_steady_segments
from seahelm.identification.reduced.turns import (
    reduced_coefficients,
    stable_steady_turn,
    voitkunsky_turns,
)
from seahelm.vessels.voitkunsky import MARINER_VOITKUNSKY, VOITKUNSKY

P = MARINER_VOITKUNSKY
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
A, B, C = -320.0, -5.5, 17.0  # a, b, c of a synthetic reduced model (Mariner-like scale)


def _eq4_points(omega, a=A, b=B, c=C):
    omega = np.asarray(omega, dtype=float)
    return omega, -(a * omega**2 + b * omega) / (1.0 + c * omega)


# ------------------------------------------------------------------------------------------
# static regime and closed form
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("deg", [-30.0, -12.0, -1.0, 0.0, 0.5, 7.0, 20.0, 35.0])
def test_steady_turns_are_equilibria_with_correct_stability(deg):
    alpha = math.radians(deg)
    turns = voitkunsky_turns(P, alpha)
    assert len(turns) == 1 and turns[0].stable
    for s in turns:
        x = VOITKUNSKY.initial_state(yaw_rate=s.yaw_rate, drift_angle=s.drift_angle)
        dx = VOITKUNSKY.derivative(0.0, x, [alpha], P)
        assert np.abs(dx[3:]).max() < 1e-15
        # eigenvalues against a finite-difference Jacobian of the model's rhs
        jac = np.empty((2, 2))
        for j, k in enumerate((3, 4)):
            h = 1e-7
            xp, xm = x.copy(), x.copy()
            xp[k] += h
            xm[k] -= h
            jac[:, j] = (VOITKUNSKY.derivative(0.0, xp, [alpha], P)[3:]
                         - VOITKUNSKY.derivative(0.0, xm, [alpha], P)[3:]) / (2 * h)
        ev = np.sort_complex(np.linalg.eigvals(jac))
        np.testing.assert_allclose(ev, np.sort_complex(s.eigenvalues), rtol=1e-5, atol=1e-9)
        assert s.branch == int(np.sign(s.drift_angle))


def test_unstable_ship_branches_at_small_rudder():
    p = P.replace(q31=-0.015)  # course-unstable
    turns = voitkunsky_turns(p, math.radians(0.5))
    assert len(turns) == 3
    assert {t.branch for t in turns} == {-1, 1}
    assert sum(t.stable for t in turns) == 2
    with pytest.raises(ParameterError, match="expected one stable steady turn"):
        stable_steady_turn(p, math.radians(0.5))


@pytest.mark.parametrize("branch", [1, -1])
def test_closed_form_against_numerical_steady_states(branch):
    rc = reduced_coefficients(P, branch=branch)
    assert rc.d == pytest.approx(rc.c**2 / (4 * rc.a), rel=1e-12)

    def f(z, alpha):
        x = VOITKUNSKY.initial_state(yaw_rate=z[0], drift_angle=z[1])
        return VOITKUNSKY.derivative(0.0, x, [alpha], P)[3:] * [1e3, 1e2]

    for deg in (2.0, 5.0, 10.0, 20.0, 30.0, 35.0):
        alpha = branch * math.radians(deg)
        lin = -alpha / rc.b
        z, info, ier, _ = fsolve(f, [lin, 5 * lin], args=(alpha,), full_output=True,
                                 xtol=1e-13)
        assert np.abs(info["fvec"]).max() < 1e-15 and np.sign(z[1]) == branch
        # exact on the branch: eq. (4) + d α²
        assert abs(rc.residual(z[0], alpha)) < 1e-12
        # the paper's eq. (4) misses exactly d α²
        assert rc.residual(z[0], alpha, exact=False) == pytest.approx(-rc.d * alpha**2,
                                                                      abs=1e-12)


def test_closed_form_linear_ship_and_branch_symmetry(mariner1):
    lin = reduced_coefficients(P.replace(h2=0.0))
    assert lin.a == lin.c == lin.d == 0.0
    # b ω + α = 0 -> ω = −α/b = K α
    assert -1.0 / lin.b == pytest.approx(mariner1.gain, rel=2e-3)
    pos, neg = reduced_coefficients(P, 1), reduced_coefficients(P, -1)
    assert (neg.a, neg.b, neg.c, neg.d) == (-pos.a, pos.b, -pos.c, -pos.d)
    with pytest.raises(ParameterError, match="`branch` must be"):
        reduced_coefficients(P, 0)
    with pytest.raises(ParameterError, match="`q31` must be nonzero"):
        reduced_coefficients(P.replace(q31=0.0))


# ------------------------------------------------------------------------------------------
# least squares, robust, brute force
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("omega", [[0.01, 0.025, 0.04], np.linspace(0.004, 0.05, 7)])
def test_exact_points_recover_coefficients(omega):
    w, al = _eq4_points(omega)
    fit = fit_lsq(w, al)
    np.testing.assert_allclose(fit.coef, [A, B, C], rtol=1e-9)
    assert fit.residual_rms < 1e-14
    assert fit.points_used == len(w)
    if len(w) == 3:
        assert np.all(np.isnan(fit.stderr))  # exact fit, no noise level given
    rob = fit_robust(w, al)
    np.testing.assert_allclose(rob.coef, [A, B, C], rtol=1e-9)


def test_exact_form_recovers_closed_form_from_model_steady_turns():
    rc = reduced_coefficients(P)
    turns = [stable_steady_turn(P, math.radians(d)) for d in (4, 12, 22, 33)]
    w = np.array([t.yaw_rate for t in turns])
    al = np.array([t.rudder_angle for t in turns])
    fit = fit_lsq(w, al, form="exact")
    np.testing.assert_allclose(fit.coef, [rc.a, rc.b, rc.c, rc.d], rtol=1e-7)
    # both sides with the odd form
    turns += [stable_steady_turn(P, -math.radians(d)) for d in (6, 18, 30)]
    w = np.array([t.yaw_rate for t in turns])
    al = np.array([t.rudder_angle for t in turns])
    fit = fit_lsq(w, al, form="exact-odd")
    np.testing.assert_allclose(fit.coef, [rc.a, rc.b, rc.c, rc.d], rtol=1e-7)
    # the plain paper form cannot describe both sides (its fit had a residual 1e3 times the
    # odd form's, with exit 0): refused, naming the odd form (issue 43)
    with pytest.raises(ParameterError, match="turns are to both sides .*'paper-odd'"):
        fit_lsq(w, al, form="paper")


def test_noise_unbiased_and_stderr_match_spread():
    """Many seeded repetitions: mean estimate at the truth, reported stderr = spread.

    Noise levels are those of steady-segment means (σ_ω = 2e-5 rad/s, σ_α = 0.02°); the
    estimator's bias is O(σ²) (errors in variables) and small against the spread here.
    """
    w0, a0 = _eq4_points(np.linspace(0.005, 0.045, 8))
    sw, sa = 2e-5, math.radians(0.02)
    n_rep = 400
    rng = np.random.default_rng(20261122)
    est, se, pred, pred_se = [], [], [], []
    for _ in range(n_rep):
        w = w0 + sw * rng.standard_normal(w0.size)
        al = a0 + sa * rng.standard_normal(a0.size)
        fit = fit_lsq(w, al, sigma_yaw_rate=sw, sigma_rudder_angle=sa)
        est.append(fit.coef)
        se.append(fit.stderr)
        p, ps = fit.predict_yaw_rate(math.radians(12.0))
        pred.append(p)
        pred_se.append(ps)
    est, se = np.array(est), np.array(se)
    spread = est.std(axis=0, ddof=1)
    z = (est.mean(axis=0) - [A, B, C]) / (spread / math.sqrt(n_rep))
    assert np.all(np.abs(z) < 3.5), z
    np.testing.assert_allclose(se.mean(axis=0) / spread, 1.0, atol=0.15)
    # delta-method prediction error against the spread of predictions
    assert np.mean(pred_se) / np.std(pred, ddof=1) == pytest.approx(1.0, abs=0.15)
    truth = _branch_truth(math.radians(12.0))
    assert abs(np.mean(pred) - truth) < 3.5 * np.std(pred, ddof=1) / math.sqrt(n_rep)


def _branch_truth(alpha, a=A, b=B, c=C):
    # a ω² + (b + c α) ω + α = 0, root through the origin
    qb = b + c * alpha
    return (-qb + math.copysign(1.0, b) * math.sqrt(qb * qb - 4 * a * alpha)) / (2 * a)


def test_scaled_covariance_without_noise_levels():
    w0, a0 = _eq4_points(np.linspace(0.005, 0.045, 10))
    rng = np.random.default_rng(7)
    sa = math.radians(0.02)
    est, se = [], []
    for _ in range(300):
        fit = fit_lsq(w0, a0 + sa * rng.standard_normal(w0.size))
        assert not fit.absolute_sigma
        est.append(fit.coef)
        se.append(fit.stderr)
    ratio = np.mean(se, axis=0) / np.std(est, axis=0, ddof=1)
    np.testing.assert_allclose(ratio, 1.0, atol=0.2)


def test_weights_and_condition_number():
    w, al = _eq4_points([0.01, 0.02, 0.03, 0.04])
    fit = fit_lsq(w, al, weights=[1, 2, 3, 4])
    np.testing.assert_allclose(fit.coef, [A, B, C], rtol=1e-9)
    x, _ = get_form("paper").design(w, al)
    sw = np.sqrt([1, 2, 3, 4])[:, None]
    assert fit.condition_number == pytest.approx(np.linalg.cond(x * sw))
    xs = x * sw / np.linalg.norm(x * sw, axis=0)
    assert fit.condition_number_scaled == pytest.approx(np.linalg.cond(xs))
    with pytest.raises(ParameterError, match="`weights` must be > 0"):
        fit_lsq(w, al, weights=[1, 0, 1, 1])


def test_robust_resists_an_outlier():
    w, al = _eq4_points(np.linspace(0.005, 0.045, 9))
    rng = np.random.default_rng(3)
    al = al + math.radians(0.01) * rng.standard_normal(al.size)
    al[4] += math.radians(3.0)  # one corrupted rudder reading
    lsq = fit_lsq(w, al)
    rob = fit_robust(w, al)
    err = lambda f: np.max(np.abs(f.coef - [A, B, C]) / np.abs([A, B, C]))  # noqa: E731
    # the corrupted point is also a leverage point (α enters the design row), which limits any
    # M-estimator; still the soft-L1 fit is an order of magnitude closer than least squares
    assert err(rob) < 0.25
    assert err(lsq) > 5 * err(rob)
    assert np.all(np.isfinite(rob.stderr))


def test_brute_force_baseline():
    w, al = _eq4_points(np.linspace(0.005, 0.045, 6))
    bounds = [(-400.0, -240.0), (-6.5, -4.5), (10.0, 24.0)]  # truth on the grid (n = 41)
    fit = fit_brute_force(w, al, bounds=bounds, n_grid=41)
    np.testing.assert_allclose(fit.coef, [A, B, C], rtol=1e-12)
    assert np.all(np.isnan(fit.stderr))
    off = fit_brute_force(w, al, bounds=bounds, n_grid=40, criterion="absolute")
    step = np.array([hi - lo for lo, hi in bounds]) / 39
    assert np.all(np.abs(off.coef - [A, B, C]) <= 3 * step)
    assert fit_steady_turns(w, al, method="brute", bounds=bounds, n_grid=41).method == "brute"
    with pytest.raises(ValueError, match="unknown criterion"):
        fit_brute_force(w, al, criterion="signed")
    with pytest.raises(ParameterError, match="`bounds` must be 3"):
        fit_brute_force(w, al, bounds=bounds[:2])


def test_prediction_both_ways_is_consistent():
    w, al = _eq4_points(np.linspace(0.005, 0.045, 6))
    fit = fit_lsq(w, al)
    alpha = np.radians([1.0, 8.0, 17.0, 26.0, 34.0])
    omega, _ = fit.predict_yaw_rate(alpha)
    np.testing.assert_allclose(omega, [_branch_truth(x) for x in alpha], rtol=1e-9)
    back, _ = fit.predict_rudder_angle(omega)
    np.testing.assert_allclose(back, alpha, rtol=1e-9)
    assert fit.predict_yaw_rate(0.0)[0] == 0.0
    odd = fit_lsq(np.r_[w, -w], np.r_[al, -al], form="paper-odd")
    om, _ = odd.predict_yaw_rate(-alpha)
    np.testing.assert_allclose(om, -omega, rtol=1e-9)
    rud, _ = odd.predict_rudder_angle(-omega)
    np.testing.assert_allclose(rud, -alpha, rtol=1e-9)


# ------------------------------------------------------------------------------------------
# steady segments of a simulated manoeuvre (engine run of the full model)
# ------------------------------------------------------------------------------------------
def _load_example_script():
    spec = importlib.util.spec_from_file_location("make_steady_turn_log",
                                                  EXAMPLES / "make_steady_turn_log.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def manoeuvre():
    mod = _load_example_script()
    return mod, mod.simulate_manoeuvre()


def test_segments_of_simulated_manoeuvre_and_held_out_prediction(manoeuvre):
    mod, (t, rudder, yaw, _) = manoeuvre
    seg = extract_steady_segments(t, rudder, yaw)
    steps = np.radians(mod.RUDDER_STEPS_DEG)
    assert len(seg) == len(steps)
    np.testing.assert_allclose(seg.rudder_angle, steps, rtol=1e-9)
    # each settled window lies inside its rudder step, after the step
    k = np.arange(len(steps))
    assert np.all(seg.start_time > k * mod.HOLD) and np.all(seg.end_time <= (k + 1) * mod.HOLD)
    truth = np.array([stable_steady_turn(P, a).yaw_rate for a in steps])
    # the settled window is the tail inside the ±tolerance band: its mean is within the band
    assert np.all(np.abs(seg.yaw_rate - truth) <= 3e-5)  # default yaw_rate_tolerance
    np.testing.assert_allclose(seg.yaw_rate, truth, rtol=1e-3)
    # identify from the 5°, 15°, 25° turns; predict the held-out 10°, 20°, 30° turns
    train, test = k % 2 == 0, k % 2 == 1
    fit = fit_lsq(seg.yaw_rate[train], seg.rudder_angle[train])
    pred, _ = fit.predict_yaw_rate(seg.rudder_angle[test])
    np.testing.assert_allclose(pred, truth[test], rtol=2e-3)
    back, _ = fit.predict_rudder_angle(truth[test])
    np.testing.assert_allclose(back, steps[test], rtol=5e-3)
    # the exact form (4 coefficients) from 4 turns: held-out error at the segment-mean accuracy
    ex = fit_lsq(seg.yaw_rate[[0, 2, 4, 5]], seg.rudder_angle[[0, 2, 4, 5]], form="exact")
    pe, _ = ex.predict_yaw_rate(seg.rudder_angle[[1, 3]])
    np.testing.assert_allclose(pe, truth[[1, 3]], rtol=1e-3)


def test_example_log_is_written_and_identifiable(tmp_path, manoeuvre):
    mod, _ = manoeuvre
    path = mod.write_log(tmp_path / "log.csv")
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    assert data.shape[1] == 3 and data.shape[0] == 1 + int(6 * mod.HOLD / 2.0)
    shipped = np.loadtxt(EXAMPLES / "steady_turn_log.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(data, shipped, atol=2e-7)
    fit, seg = identify_from_time_series(data[:, 0], np.radians(data[:, 1]),
                                         np.radians(data[:, 2]))
    assert len(seg) == 6
    truth = stable_steady_turn(P, math.radians(12.5)).yaw_rate
    pred, se = fit.predict_yaw_rate(math.radians(12.5))
    assert abs(pred - truth) < max(4 * se, 1e-3 * truth)


# ------------------------------------------------------------------------------------------
# bad input
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "w, al, match",
    [
        ([0.01, 0.02], [0.05, 0.1], "at least 3 distinct steady points"),
        ([0.01, 0.01, 0.02, 0.0], [0.05, 0.05, 0.1, 0.0], "at least 3 distinct"),
        ([0.01, 0.02, 0.03], [0.1, 0.1, 0.1], "degenerate design: all points at the same rudder"),
        ([0.01, np.nan, 0.03], [0.05, 0.1, 0.15], r"`yaw_rate` must be finite"),
        ([0.01, 0.02, 0.03], [0.05, np.inf, 0.15], r"`rudder_angle` must be finite"),
        ([0.01, 0.02, 0.03], [0.05, 0.1], "equal length"),
        ([0.0, 0.0, 0.0], [0.05, 0.1, 0.15], "degenerate design"),
    ],
)
@pytest.mark.parametrize("method", ["lsq", "robust", "brute"])
def test_bad_points(w, al, match, method):
    with pytest.raises(ParameterError, match=match):
        fit_steady_turns(w, al, method=method)


def test_unknown_names():
    w, al = _eq4_points([0.01, 0.02, 0.03])
    with pytest.raises(ValueError, match="unknown fit method 'ols'; valid: lsq, robust, brute"):
        fit_steady_turns(w, al, method="ols")
    with pytest.raises(ValueError, match="unknown reduced form"):
        fit_lsq(w, al, form="cubic")
    assert set(REDUCED_FORMS) == {"paper", "exact", "paper-odd", "exact-odd"}


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(time=[0.0, 1.0, 1.0]), "strictly increasing"),
        (dict(time=[0.0]), "equal length"),
        (dict(yaw_rate=[0.0, np.nan, 0.0]), r"`yaw_rate` must be finite"),
        (dict(rudder_tolerance=0.0), r"`rudder_tolerance` must be > 0"),
        (dict(min_duration=-1.0), r"`min_duration` must be > 0"),
        (dict(smoothing=-1.0), r"`smoothing` must be >= 0"),
    ],
)
def test_bad_time_series(kw, match):
    args = dict(time=[0.0, 1.0, 2.0], rudder_angle=[0.1, 0.1, 0.1], yaw_rate=[0.0, 0.0, 0.0])
    args.update(kw)
    with pytest.raises(ParameterError, match=match):
        extract_steady_segments(**args)
