"""Posteriors of identified Nomoto models and IMO pass probabilities over an ensemble
(issue 30, item 4)."""

from __future__ import annotations


import numpy as np
import pytest

from seahelm.analysis.imo.check import imo_check
from seahelm.analysis.imo.probability import imo_probabilities, wilson_interval
from seahelm.identification.nomoto_fit import fit_nomoto
from seahelm.identification.nomoto_posterior import posterior_samples, posterior_ships
from seahelm.errors import ParameterError

from test_analysis_nomoto_fit import synthetic


def test_wilson_interval_known_values():
    assert wilson_interval(0, 10) == pytest.approx((0.0, 0.2775), abs=1e-4)
    assert wilson_interval(10, 10) == pytest.approx((0.7225, 1.0), abs=1e-4)
    lo, hi = wilson_interval(50, 100)
    assert lo == pytest.approx(0.4038, abs=1e-4) and hi == pytest.approx(0.5962, abs=1e-4)


@pytest.fixture(scope="module")
def fit_and_record():
    rec = synthetic(3)
    return fit_nomoto(rec), rec


def test_laplace_samples_have_the_fit_mean_and_covariance(fit_and_record):
    fit, _ = fit_and_record
    s = posterior_samples(fit, n=20_000, seed=2)
    assert np.all(np.abs(s.mean(0) - fit.values) < 0.03 * fit.standard_errors)
    np.testing.assert_allclose(s.std(0), fit.standard_errors, rtol=0.03)
    assert np.all(s[:, :2] > 0)


def test_mcmc_agrees_with_laplace_for_a_well_identified_model(fit_and_record):
    """First-order model, 0.2° noise: the posterior is nearly Gaussian, so the ensemble
    sampler's spread matches the Laplace standard errors (within 25 %) — with the records'
    initial states sampled too."""
    fit, rec = fit_and_record
    s = posterior_samples(fit, [rec], n=600, method="mcmc", seed=1, walkers=16, burn=150)
    assert s.shape == (600, 3)
    np.testing.assert_allclose(s.std(0), fit.standard_errors, rtol=0.25)
    assert np.all(np.abs(s.mean(0) - fit.values) < 2 * fit.standard_errors)


@pytest.mark.parametrize("kwargs, field", [({"method": "bayes"}, "method"), ({"n": 0}, "n")])
def test_posterior_bad_arguments(fit_and_record, kwargs, field):
    with pytest.raises(ParameterError) as info:
        posterior_samples(fit_and_record[0], **kwargs)
    assert info.value.field == field


def test_ensemble_probabilities_equal_single_checks(fit_and_record):
    """Six Nomoto ships whose gain makes the tactical diameter cross the 5 L limit: the batched
    ensemble's per-criterion pass counts equal the single IMO checks' verdicts."""
    fit, _ = fit_and_record
    samples = np.array([[k, 30.0, 0.0] for k in (0.004, 0.006, 0.008, 0.012, 0.02, 0.04)])
    ships = posterior_ships(fit, samples, name="g", speed=7.0, length=150.0)
    ens = imo_probabilities(ships)
    td = [r for r in ens.rows if r["criterion"] == "tactical diameter"
          and r["side"] == "starboard"][0]
    singles = [imo_check(s) for s in ships]
    single_td = [next(c for c in rep.criteria if c.criterion == "tactical diameter"
                      and c.side == "starboard") for rep in singles]
    assert td["passed"] == sum(c.status == "pass" for c in single_td)
    assert 0 < td["passed"] < 6  # the ensemble straddles the limit
    assert ens.total == 6 and ens.excluded == 0
    every = sum(all(c.status == "pass" for c in rep.criteria
                    if c.status in ("pass", "fail")) for rep in singles)
    assert ens.passed == every


def test_ensemble_needs_one_length(fit_and_record):
    fit, _ = fit_and_record
    a = posterior_ships(fit, np.array([[0.05, 30.0, 0.0]]), name="a", speed=7, length=150)
    b = posterior_ships(fit, np.array([[0.05, 30.0, 0.0]]), name="b", speed=7, length=100)
    with pytest.raises(ParameterError, match="share their length"):
        imo_probabilities(a + b)


def test_monte_carlo_ships_default_and_given_draws():
    from seahelm.analysis.imo.probability import monte_carlo_ships
    from seahelm.numerics.sampling import get_distribution
    from seahelm.ships import get_ship

    ship = get_ship("kvlcc2-l7")
    a = monte_carlo_ships(ship, 50, seed=4)
    yv = np.array([s.params.Y_v for s in a])
    assert abs(yv.std() / abs(ship.params.Y_v) - 0.10) < 0.04
    assert a[3].params.N_r == monte_carlo_ships(ship, 10, seed=4)[3].params.N_r  # by index
    assert a[0].params.R_0 == ship.params.R_0
    b = monte_carlo_ships(ship, 5, seed=1, draws={"R_0": get_distribution(
        "uniform", low=0.02, high=0.024)})
    assert all(0.02 <= s.params.R_0 <= 0.024 for s in b)
    with pytest.raises(ParameterError, match="`Z_v` is not a parameter"):
        monte_carlo_ships(ship, 5, draws={"Z_v": get_distribution("normal", mean=0, std=1)})
    with pytest.raises(ParameterError, match="sample 0:"):
        monte_carlo_ships(ship, 5, draws={"R_0": get_distribution("normal", mean=-1.0,
                                                                  std=0.01)})


def test_cli_imo_monte_carlo(tmp_path):
    import json

    from typer.testing import CliRunner

    from seahelm.cli.main import app

    runner = CliRunner()
    res = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", "6", "--seed", "2", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["samples"] == 6 and data["total"] + data["excluded"] == 6
    assert len(data["criteria"]) == 13 and 0 <= data["probability"] <= 1  # with stopping
    draws = tmp_path / "d.toml"
    draws.write_text('[draws]\nN_r = {distribution = "normal", mean = -0.049, std = 0.005}\n')
    ok = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", "4", "--draws", str(draws),
                             "--json"])
    assert ok.exit_code == 0, ok.output
    draws.write_text('[draws]\nN_r = {distribution = "normal", mean = -0.049}\n')
    bad = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", "4", "--draws", str(draws)])
    assert bad.exit_code == 2 and "[draws.N_r]" in bad.output and "`std`" in bad.output
    both = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", "4", "--speed", "1.0"])
    assert both.exit_code == 2 and "--monte-carlo" in both.output


def test_members_rerun_for_longer_get_the_values_of_one_long_run(monkeypatch):
    """The first pass runs FIRST_PASS times the reference's durations, the members that miss
    their events run again for LAST_PASS times them: with a first pass too short for any member
    (all rerun) the values equal those of the default passes, which equal the manoeuvres run
    once for the long duration (what every member did before the passes)."""
    from seahelm.analysis.imo import probability as ip
    from seahelm.ships import get_ship

    ship = get_ship("kvlcc2-l7")
    ships = ip.monte_carlo_ships(ship, 4, seed=2)
    default = imo_probabilities(ships, reference=ship)
    runs = []
    real = ip._Passes.run

    def counted(self, key, measure, members, t_event):
        out = real(self, key, measure, members, t_event)
        runs.append(self.rerun)
        return out

    monkeypatch.setattr(ip._Passes, "run", counted)
    monkeypatch.setattr(ip, "FIRST_PASS", 0.3)  # nothing is reached: every member again
    again = imo_probabilities(ships, reference=ship)
    assert runs[-1] == 4 * 5  # 4 members x (35 deg, 10 deg turning, 10/10, 20/20, stopping)
    assert len(default.values) == len(again.values) == 13
    for a, b in zip(default.values, again.values):
        assert np.isfinite(a).all()
        np.testing.assert_allclose(a, b, rtol=1e-9)


def test_the_first_pass_minimises_the_expected_simulated_time():
    """Given the needs of the members seen (in units of the reference's time; inf: beyond the
    second pass), the first pass lasts the f that minimises f + LAST_PASS * P(need > f):
    checked against a brute-force search on a fine grid; below LEARN members it is
    FIRST_PASS."""
    from seahelm.analysis.imo import probability as ip

    rng = np.random.default_rng(7)
    passes = ip._Passes(record_dt=0.3)
    assert passes.first_pass("x") == ip.FIRST_PASS
    needs = np.concatenate([rng.lognormal(0.0, 0.06, 600), [np.inf] * 6])
    passes.needs["x"] = [needs[:300], needs[300:]]
    f = passes.first_pass("x")
    grid = np.linspace(0.5, ip.LAST_PASS, 200001)
    cost = grid + ip.LAST_PASS * np.array([(needs > g).mean() for g in grid[::100]]).repeat(
        100)[:grid.size]
    brute = grid[::100][np.argmin(cost[::100])]
    expected = lambda g: g + ip.LAST_PASS * (needs > g).mean()  # noqa: E731
    assert expected(f) <= expected(brute) + 1e-12
    assert 1.0 < f < 1.3  # (a 6 % spread: a little above the median need)
    passes.needs["y"] = [np.full(ip.LEARN - 1, 1.0)]
    assert passes.first_pass("y") == ip.FIRST_PASS
