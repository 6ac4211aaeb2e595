"""Checks on identified MMG hull derivatives (issue 45, item 5): a base ship with the wrong
rudder area gives confident, implausible derivatives — now flagged, with the suspect inputs
named; the right base ship passes."""

from __future__ import annotations

import json
import math
import types
import warnings

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.maneuvers import turning_circle, zigzag
from seahelm.identification.mmg_checks import (SuspectBaseShipWarning, check_hull_fit, ljung_box)
from seahelm.identification.mmg_fit import identify_mmg
from seahelm.cli.main import app
from seahelm.ships.estimate import Design, estimate_ship
from test_analysis_mmg_fit import records_of

#: the README's estimated cargo ship; the default rudder area (DNV's minimum) is 13.1 m²
CARGO = dict(length=120.0, beam=18.0, draft=7.0, block_coefficient=0.7, speed=6.5)


@pytest.fixture(scope="module")
def cargo():
    truth = estimate_ship(Design(**CARGO, rudder_area=16.0))
    wrong = estimate_ship(Design(**CARGO))
    assert wrong.params.rudder_area == pytest.approx(13.125)
    runs = [zigzag(truth, math.radians(10.0), math.radians(10.0), sides=1, record_dt=0.5),
            zigzag(truth, math.radians(20.0), math.radians(20.0), sides=1, record_dt=0.5),
            turning_circle(truth, math.radians(35.0), sides=1, record_dt=0.5)]
    recs = [r for res, n in zip(runs, ("zz10", "zz20", "tc")) for r in records_of(res, n)]
    return truth, wrong, recs, runs


def test_a_wrong_rudder_area_is_flagged_and_named(cargo):
    truth, wrong, recs, _ = cargo
    with pytest.warns(SuspectBaseShipWarning, match="rudder") as caught:
        fit = identify_mmg(recs, wrong)
    got = dict(zip(fit.names, fit.values))
    # the defect: a confident Y'_vvv of the wrong sign (truth -0.75)
    assert got["Y_vvv"] > 0 > truth.params.Y_vvv
    assert "Y_vvv" in fit.check.implausible and "must be < 0" in fit.check.implausible["Y_vvv"]
    assert any("rudder" in s for s in fit.check.suspects)
    assert "Y_vvv" in str(caught[0].message)
    assert fit.as_dict()["checks"]["implausible"]


def test_the_right_base_ship_passes(cargo):
    truth, _, recs, _ = cargo
    with warnings.catch_warnings():
        warnings.simplefilter("error", SuspectBaseShipWarning)
        fit = identify_mmg(recs, truth)
    assert fit.check.implausible == {} and not fit.check.poor_fit and fit.check.warning == ""
    got = dict(zip(fit.names, fit.values))
    assert got["Y_vvv"] == pytest.approx(truth.params.Y_vvv, rel=0.05)


def test_cli_warns_on_stderr_and_reports_checks_in_json(tmp_path, cargo):
    _, wrong, _, runs = cargo
    paths = []
    for res, name in zip(runs, ("zz10", "zz20", "tc")):
        path = tmp_path / f"{name}.nc"
        res.runs.to_netcdf(path, engine="h5netcdf")
        paths.append(str(path))
    base = tmp_path / "cargo.toml"
    runner = CliRunner()
    made = runner.invoke(app, ["ship", "estimate", "--length", "120", "--beam", "18", "--draft",
                               "7", "--cb", "0.7", "--speed", "6.5", "-o", str(base)])
    assert made.exit_code == 0, made.output
    res = runner.invoke(app, ["identify", "mmg", *paths, "--ship", str(base), "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert "Y_vvv" in data["checks"]["implausible"] and data["checks"]["suspects"]
    assert "warning:" in res.stderr and "rudder" in res.stderr


def test_ljung_box_tells_white_from_coloured():
    rng = np.random.default_rng(4)
    white = rng.normal(size=600)
    coloured = np.zeros(600)
    for k in range(1, 600):
        coloured[k] = 0.9 * coloured[k - 1] + white[k]
    assert ljung_box(white)[1] > 0.01
    q, p, rho = ljung_box(coloured)
    assert p < 1e-10 and rho == pytest.approx(0.9, abs=0.08)


def test_sign_rules_without_particulars():
    fit = types.SimpleNamespace(names=("Y_v", "N_r", "R_0"), values=np.array([0.2, -0.05, 0.01]),
                                standard_errors=np.array([0.01, 0.01, 0.001]))
    base = types.SimpleNamespace(particulars=None)
    check = check_hull_fit(fit, base)
    assert list(check.implausible) == ["Y_v"] and "must be < 0" in check.implausible["Y_v"]
    assert check.suspects and "rudder" in check.suspects[0]


def test_the_kvlcc2_captive_test_derivatives_are_plausible():
    """The bounds must pass a real ship's captive-test values (Yasukawa & Yoshimura 2015)."""
    from seahelm.ships import get_ship

    ship = get_ship("kvlcc2-l7")
    names = ("R_0", "X_vv", "X_vr", "X_rr", "X_vvvv", "Y_v", "Y_r", "Y_vvv", "Y_vvr", "Y_vrr",
             "Y_rrr", "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr")
    fit = types.SimpleNamespace(names=names, standard_errors=np.zeros(len(names)),
                                values=np.array([getattr(ship.params, n) for n in names]))
    assert check_hull_fit(fit, ship).implausible == {}


def test_held_out_prediction_separates_the_wrong_rudder_from_the_right(cargo):
    truth, wrong, recs, _ = cargo
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SuspectBaseShipWarning)
        bad, good = identify_mmg(recs, wrong).check, identify_mmg(recs, truth).check
    assert bad.heldout[0] == good.heldout[0] == recs[-1].name
    assert bad.heldout[2] > 10 * bad.heldout[1] and bad.heldout[2] > 0.02  # 4.5 %, 55x
    assert good.heldout[2] < 0.005  # 0.13 %
    assert bad.poor_fit and not good.poor_fit and "held out" in bad.warning
