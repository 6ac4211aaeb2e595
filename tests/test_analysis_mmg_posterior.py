"""The posterior of identified MMG hull derivatives (issue 30, item 4): the Laplace covariance
against a finite-difference Hessian, the posterior mean against the truth, MCMC against
Laplace, posterior ships, bad input, and ``seahelm identify mmg --imo``."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from seahelm.analysis.maneuvers import turning_circle, zigzag
from seahelm.identification.mmg_fit import HullFit, _scaled_outputs, _simulate, refine_mmg
from seahelm.identification.mmg_posterior import admissible, mmg_posterior, posterior_ships
from seahelm.identification.records import record_from_arrays
from seahelm.errors import ParameterError

NAMES = ("Y_v", "Y_r", "N_v", "N_r")
NOISE = 0.005  # of U0 on u, v; of U0/L on r


@pytest.fixture(scope="module")
def template(kvlcc2_l7):
    """A 20/20 zig-zag's rudder and rps; u, v, r simulated by the output-error model itself
    (so that the likelihood is exact and the posterior can be checked against the truth)."""
    ds = zigzag(kvlcc2_l7, math.radians(20.0), math.radians(20.0), sides=1, record_dt=0.2).runs
    t = ds["time"].values
    rec = record_from_arrays("zz20", t, ds["rudder_angle"].values, ds["heading"].values,
                             ds["yaw_rate"].values, surge_speed=ds["surge_speed"].values,
                             sway_speed=ds["sway_speed"].values,
                             propeller_rps=ds["propeller_rps"].values)[0]
    return rec, _simulate([kvlcc2_l7.params], rec)[0]


def noisy(template, seed):
    rec, clean = template
    U0, L = 1.179, 7.0
    rng = np.random.default_rng(seed)
    e = [np.r_[0.0, rng.normal(0.0, NOISE * s, rec.time.size - 1)] for s in (U0, U0, U0 / L)]
    return record_from_arrays(f"zz20-{seed}", rec.time, rec.rudder_angle, rec.heading,
                              clean[2] + e[2], surge_speed=clean[0] + e[0],
                              sway_speed=clean[1] + e[1],
                              propeller_rps=rec.channels["propeller_rps"])[0]


@pytest.fixture(scope="module")
def fit_and_record(kvlcc2_l7, template):
    rec = noisy(template, 1)
    return refine_mmg(kvlcc2_l7, [rec], names=NAMES), rec


def test_laplace_covariance_is_the_inverse_finite_difference_hessian(fit_and_record):
    """The Hessian of the cost ½ Σ r²/σ² by central second differences of the simulated
    records (not the fit's Jacobian); its inverse is the Laplace covariance within 10 %."""
    fit, rec = fit_and_record
    scales, measured = _scaled_outputs([rec], fit.params.length)
    target = measured[0] / scales[:, None]
    x0, h = fit.values, 0.5 * fit.standard_errors
    p = x0.size
    points = [x0]
    for i in range(p):
        for j in range(p):
            for si, sj in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                points.append(x0 + si * h[i] * np.eye(p)[i] + sj * h[j] * np.eye(p)[j])
    sets = [fit.params.replace(**dict(zip(NAMES, map(float, x)))) for x in points]
    y = _simulate(sets, rec) / scales[None, :, None]
    sse = np.sum((target[None] - y) ** 2, axis=(1, 2))
    sigma2 = sse[0] / (target.size - p)
    cost = 0.5 * sse[1:].reshape(p, p, 4) / sigma2
    H = (cost[..., 0] - cost[..., 1] - cost[..., 2] + cost[..., 3]) / (4 * np.outer(h, h))
    cov = np.linalg.inv(H)
    se = np.sqrt(np.diag(cov))
    np.testing.assert_allclose(fit.standard_errors, se, rtol=0.1)
    np.testing.assert_allclose(fit.correlation, cov / np.outer(se, se), atol=0.03)


@pytest.mark.parametrize("seed", [2, 3, 4])
def test_posterior_covers_the_truth(kvlcc2_l7, template, seed):
    """Records with noise of three seeds: the truth lies within the posterior's 99.9 % region
    (Mahalanobis distance of the Laplace posterior), and the mean of the Laplace samples is
    the estimate."""
    fit = refine_mmg(kvlcc2_l7, [noisy(template, seed)], names=NAMES)
    truth = np.array([getattr(kvlcc2_l7.params, n) for n in NAMES])
    d = fit.values - truth
    assert d @ np.linalg.solve(fit.covariance, d) < 18.47  # chi² (4 dof), 0.999
    post = mmg_posterior(fit, n=4000, seed=seed)
    assert np.all(np.abs(post.samples.mean(axis=0) - fit.values) < 0.1 * fit.standard_errors)


def test_mcmc_agrees_with_laplace_on_a_well_identified_fit(fit_and_record):
    pytest.importorskip("emcee")
    fit, rec = fit_and_record
    post = mmg_posterior(fit, [rec], n=1200, method="mcmc", seed=5, walkers=12, burn=150,
                         thin=2)
    assert post.samples.shape == (1200, 4) and post.steps == 150 + 100 * 2
    assert 0.2 < post.acceptance_fraction < 0.9
    assert post.autocorr_time.shape == (4,) and np.all(post.autocorr_time > 0)
    se = fit.standard_errors
    assert np.all(np.abs(post.samples.mean(axis=0) - fit.values) < 0.3 * se)
    np.testing.assert_allclose(post.samples.std(axis=0), se, rtol=0.25)
    corr = np.corrcoef(post.samples.T)
    np.testing.assert_allclose(corr, fit.correlation, atol=0.1)
    data = post.as_dict()
    assert data["method"] == "mcmc" and set(data["autocorr_time"]) == set(NAMES)


def test_posterior_ships_run_a_turning_circle(kvlcc2_l7, fit_and_record):
    fit, _ = fit_and_record
    post = mmg_posterior(fit, n=2, seed=0)
    ships = posterior_ships(fit, post, kvlcc2_l7)
    assert [s.name for s in ships] == ["posterior #0", "posterior #1"]
    assert ships[1].params.N_r == post.samples[1, 3]
    assert ships[0].params.X_vv == kvlcc2_l7.params.X_vv  # not sampled: the fit's value
    tc = turning_circle(ships[0], math.radians(35.0), sides=1).metrics
    truth = turning_circle(kvlcc2_l7, math.radians(35.0), sides=1).metrics
    assert float(tc["tactical_diameter"]) == pytest.approx(float(truth["tactical_diameter"]),
                                                           rel=0.05)


def test_prior_support():
    ok = admissible(("R_0", "Y_v", "N_r", "X_vv"),
                    np.array([[0.02, -0.3, -0.05, 1.0], [-0.02, -0.3, -0.05, 1.0],
                              [0.02, 0.3, -0.05, 1.0], [0.02, -0.3, np.nan, 1.0]]))
    assert ok.tolist() == [True, False, False, False]


@pytest.mark.parametrize("kwargs, field", [
    ({"method": "foo"}, "method"), ({"n": 0}, "n"), ({"thin": 0}, "thin"),
    ({"method": "mcmc"}, "records"), ({"method": "mcmc", "walkers": 7}, "walkers"),
])
def test_bad_arguments(fit_and_record, kwargs, field):
    fit, rec = fit_and_record
    if kwargs.get("method") == "mcmc":
        pytest.importorskip("emcee")
    if "walkers" in kwargs:
        kwargs = dict(kwargs, records=[rec])
    with pytest.raises(ParameterError) as info:
        mmg_posterior(fit, **kwargs)
    assert info.value.field == field


def test_unidentified_and_singular_directions_are_refused(kvlcc2_l7):
    base = HullFit(names=("Y_v", "Y_r", "N_v"), values=np.array([-0.3, 0.08, -0.13]),
                   covariance=np.diag([1e-6, 1.0, 1e-6]), method="output-error",
                   condition_numbers={}, records=("a",), residual_std={}, params=kvlcc2_l7.params)
    with pytest.raises(ParameterError, match="do not identify Y_r"):
        mmg_posterior(base)
    # three parameters, no pair correlated beyond 0.999, but Y_v + Y_r + N_v singular
    v = np.array([[1.0, -0.5, -0.5], [0.0, 1.0, -1.0]])
    cov = 1e-6 * v.T @ v + 1e-22 * np.eye(3)
    singular = dataclasses.replace(base, covariance=cov)
    with pytest.raises(ParameterError, match="singular along"):
        mmg_posterior(singular)


def test_cli_identify_mmg_imo_probabilities_given_the_identification(tmp_path, kvlcc2_l7):
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    path = tmp_path / "zz20.nc"
    zigzag(kvlcc2_l7, math.radians(20.0), math.radians(20.0), sides=1,
           record_dt=0.2).runs.to_netcdf(path, engine="h5netcdf")
    runner = CliRunner()
    args = ["identify", "mmg", str(path), "--ship", "kvlcc2-l7", "--regression-only"]
    res = runner.invoke(app, [*args, "--imo", "3", "--seed", "1", "--json"])
    assert res.exit_code == 0, res.output
    imo = json.loads(res.stdout)["imo"]
    assert imo["total"] + imo["excluded"] == 3 and imo["posterior"] == "laplace"
    for row in imo["criteria"]:
        assert 0.0 <= row["ci_low"] <= row["probability"] <= row["ci_high"] <= 1.0
    assert {r["criterion"] for r in imo["criteria"]} >= {"advance", "tactical diameter"}
    assert imo["posterior_samples"]["samples"] == 3
    text = runner.invoke(app, [*args, "--imo", "2", "--seed", "1"])
    assert text.exit_code == 0, text.output
    assert "P(pass)" in text.output and "Wilson" in text.output
    for bad, option in ((["--imo", "-1"], "--imo"), (["--posterior", "foo"], "--posterior"),
                        (["--level", "1.5"], "--level")):
        res = runner.invoke(app, [*args, "--imo", "2", *bad])
        assert res.exit_code == 2 and option in res.output, res.output
