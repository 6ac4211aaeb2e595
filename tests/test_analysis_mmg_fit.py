"""MMG hull derivatives identified from free-running records (issue 30): regression on
accelerations, output error, prediction of a manoeuvre not used in the fit, the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.maneuvers import turning_circle, zigzag
from seahelm.identification.mmg_fit import HullFit, identify_mmg, refine_mmg, regress_hull
from seahelm.identification.records import record_from_arrays
from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.ships import get_ship

U0 = 1.179  # KVLCC2 L7 test speed [m/s]


def records_of(result, name, noise=0.0, seed=0):
    """The runs of a manoeuvre result as records (optionally with white measurement noise of
    ``noise`` U0 on u, v and ``noise`` U0/L on r)."""
    ds = result.runs
    rng = np.random.default_rng(seed)
    t = ds["time"].values
    out = []
    runs = [ds] if "side" not in ds.dims else [ds.isel(side=i) for i in range(ds.sizes["side"])]
    for k, run in enumerate(runs):
        def noisy(v, s):
            x = run[v].values
            return x + (rng.normal(0.0, s, x.size) if noise else 0.0)
        out += record_from_arrays(
            f"{name}[{k}]", t, run["rudder_angle"].values, run["heading"].values,
            noisy("yaw_rate", noise * U0 / 7.0), surge_speed=noisy("surge_speed", noise * U0),
            sway_speed=noisy("sway_speed", noise * U0),
            propeller_rps=run["propeller_rps"].values)
    return out


@pytest.fixture(scope="module")
def manoeuvres(kvlcc2_l7):
    zz10 = zigzag(kvlcc2_l7, math.radians(10.0), math.radians(10.0), sides=1, record_dt=0.1)
    zz20 = zigzag(kvlcc2_l7, math.radians(20.0), math.radians(20.0), sides=1, record_dt=0.1)
    tc = turning_circle(kvlcc2_l7, math.radians(35.0), sides=1, record_dt=0.1)
    return zz10, zz20, tc


def test_regression_on_clean_records_recovers_the_linear_derivatives(kvlcc2_l7, manoeuvres):
    recs = [r for res, n in zip(manoeuvres, ("zz10", "zz20", "tc")) for r in records_of(res, n)]
    fit = regress_hull(recs, kvlcc2_l7, method="ols")
    got = dict(zip(fit.names, fit.values))
    for name in ("R_0", "Y_v", "Y_r", "N_v", "N_r", "X_vvvv"):
        assert got[name] == pytest.approx(getattr(kvlcc2_l7.params, name), rel=0.01), name
    assert set(fit.condition_numbers) == {"X", "Y", "N"}
    assert fit.condition_numbers["Y"] > 100  # v' and r' move together in manoeuvres


#: The derivatives a 10/10 and a 20/20 zig-zag and a 35° turn identify sharply (standard
#: errors below 1e-4 of the values on noiseless records).
LINEAR = ("R_0", "Y_v", "Y_r", "N_v", "N_r")


@pytest.mark.parametrize("record_dt, tol", [(0.1, 1e-3), (0.025, 1e-4)])
def test_output_error_recovers_the_truth_from_noiseless_manoeuvre_records(kvlcc2_l7, manoeuvres,
                                                                          record_dt, tol):
    """Records of the ordinary manoeuvre simulation (the steering gear moving the rudder, the
    zig-zag controller reversing it, the step 0.025 s), not of the fit's own simulation:
    output error from the regression's start refines R'_0, Y'_v, Y'_r, N'_v, N'_r back to the
    catalog's values. Holding each rudder sample over the step after it (the fit before the
    first-order hold of seahelm.actuators.hold) was 1.5–2.4 % off in these. What remains is
    the record's: between samples the fit takes the straight line while the steering gear's
    angle bends (rate limit, 0.1 s lag), an O(Δt²) error — measured 2.2e-4 at 10 Hz and
    1.8e-5 at 40 Hz (16 times less for 4 times the rate); the tolerances allow 4–5 times
    that."""
    if record_dt == 0.1:
        runs = manoeuvres
    else:
        runs = (zigzag(kvlcc2_l7, math.radians(10.0), math.radians(10.0), sides=1,
                       record_dt=record_dt),
                zigzag(kvlcc2_l7, math.radians(20.0), math.radians(20.0), sides=1,
                       record_dt=record_dt),
                turning_circle(kvlcc2_l7, math.radians(35.0), sides=1, dt=record_dt))
    recs = [r for res, n in zip(runs, ("zz10", "zz20", "tc")) for r in records_of(res, n)]
    assert recs[0].median_interval == pytest.approx(record_dt)
    fit = refine_mmg(regress_hull(recs, kvlcc2_l7, method="ols"), recs)
    got = dict(zip(fit.names, fit.values))
    for name in LINEAR:
        assert got[name] == pytest.approx(getattr(kvlcc2_l7.params, name), rel=tol), name


def test_identified_model_predicts_a_manoeuvre_not_used_in_the_fit(kvlcc2_l7, manoeuvres):
    """Noisy records (σ 0.5 % of U0 on u, v; 0.5 % U0/L on r) of a 10/10 and a 20/20 zig-zag
    and a 35° starboard turn; regression then output error; the 20° port turning circle and
    the 15/15 zig-zag predicted within 2 % of the true model's. Derivatives the noisy records
    do not identify are kept at the base ship's values (here the truth's) and said so."""
    recs = [r for res, n, s in zip(manoeuvres, ("zz10", "zz20", "tc"), (1, 2, 3))
            for r in records_of(res, n, noise=0.005, seed=s)]
    fit = identify_mmg(recs, kvlcc2_l7)
    identified = fit.ship(kvlcc2_l7)
    for name, why in fit.fixed.items():
        assert "not identified" in identified.source_of(name) and why
    truth = {}
    for label, ship in (("truth", kvlcc2_l7), ("identified", identified)):
        turn = turning_circle(ship, math.radians(20.0), sides=-1).metrics
        zz = zigzag(ship, math.radians(15.0), math.radians(15.0), sides=1).metrics
        truth[label] = np.array([float(turn["advance"]), float(turn["tactical_diameter"]),
                                 float(zz["overshoot"].sel(n=1))])
    np.testing.assert_allclose(truth["identified"], truth["truth"], rtol=0.02)
    assert "output-error fit" in identified.source_of("Y_v")


def test_missing_channels_and_a_non_mmg_base(kvlcc2_l7, manoeuvres):
    rec = records_of(manoeuvres[0], "zz10")[0]
    bare = record_from_arrays("bare", rec.time, rec.rudder_angle, rec.heading, rec.yaw_rate)
    with pytest.raises(ParameterError, match="missing column.*surge_speed") as info:
        regress_hull(bare, kvlcc2_l7)
    assert info.value.field == "surge_speed"
    with pytest.raises(ParameterError, match="MMG ship"):
        regress_hull(rec, get_ship("mariner-nonlinear"))
    with pytest.raises(ParameterError, match="one of ols, ridge, tsvd"):
        regress_hull(rec, kvlcc2_l7, method="lasso")


def test_unidentifiable_derivatives_are_reported_not_written(kvlcc2_l7):
    cov = np.diag([1e-8, 4.0, 1e-6])
    cov[1, 2] = cov[2, 1] = 0.9999 * math.sqrt(4.0 * 1e-6)
    fit = HullFit(names=("Y_v", "Y_vvr", "N_vvr"), values=np.array([-0.3, 0.5, -0.3]),
                  covariance=cov, method="ols", condition_numbers={"Y": 1e6}, records=("a",),
                  residual_std={}, params=kvlcc2_l7.params)
    bad = fit.unidentifiable()
    assert set(bad) == {"Y_vvr", "N_vvr"}
    assert "standard error 2 exceeds the value 0.5" in bad["Y_vvr"]
    assert "correlation 0.9999 with Y_vvr" in bad["N_vvr"]
    with pytest.raises(ParameterError, match="do not identify Y_vvr"):
        fit.ship(kvlcc2_l7)
    row = {r["name"]: r for r in fit.as_dict()["parameters"]}["Y_vvr"]
    assert not row["identified"] and "value" not in row


def test_cli_identify_mmg(tmp_path, manoeuvres):
    paths = []
    for res, name in zip(manoeuvres[:2], ("zz10", "zz20")):
        path = tmp_path / f"{name}.nc"
        res.runs.to_netcdf(path, engine="h5netcdf")
        paths.append(str(path))
    runner = CliRunner()
    res = runner.invoke(app, ["identify", "mmg", *paths, "--ship", "kvlcc2-l7",
                              "--regression-only", "--json", "-o", str(tmp_path / "id.toml")])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["method"] == "ridge" and len(data["records"]) == 2
    from seahelm.ships import read_ship

    assert read_ship(tmp_path / "id.toml").model.name == "mmg"
    bad = runner.invoke(app, ["identify", "mmg", *paths, "--ship", "mariner-nonlinear"])
    assert bad.exit_code == 2 and "needs an MMG ship" in bad.output
