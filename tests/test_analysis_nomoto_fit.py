"""Nomoto identification from manoeuvre records (issue 30): records, equation and output error,
Laplace intervals and their coverage, unidentifiable parameters, the Mariner, the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.identification.nomoto_fit import fit_nomoto, simulate_records
from seahelm.identification.nomoto_fit_result import nomoto_ship
from seahelm.identification.records import read_records, record_from_arrays
from seahelm.cli.main import app
from seahelm.errors import ParameterError

TRUTH = np.array([0.05, 30.0, math.radians(0.5)])  # K [1/s], T [s], δ_0 [rad]


def zigzag_rudder(t: np.ndarray, amplitude_deg: float = 10.0, period: float = 150.0):
    return math.radians(amplitude_deg) * np.sign(np.sin(2 * np.pi * t / period + 0.01))


def synthetic(seed: int | None, *, theta=TRUTH, order: int = 1, amplitude: float = 10.0,
              noise_deg: float = 0.2, dt: float = 0.5, duration: float = 600.0, name="syn"):
    t = np.arange(0.0, duration, dt)
    delta = zigzag_rudder(t, amplitude)
    base = record_from_arrays(name, t, delta, heading=np.zeros_like(t))[0]
    inits = np.zeros((1, 2 if order == 1 else 3))
    psi = simulate_records(order, np.asarray(theta)[None], inits, base, "heading")[0]
    noise = 0.0 if seed is None else np.random.default_rng(seed).normal(
        0.0, math.radians(noise_deg), t.size)
    return record_from_arrays(name, t, delta, heading=psi + noise)[0]


def run(*args: str):
    return CliRunner().invoke(app, list(args), terminal_width=160)


# -- records -------------------------------------------------------------------------------
def write_csv(path, header, rows):
    path.write_text(",".join(header) + "\n" + "\n".join(",".join(map(str, r)) for r in rows)
                    + "\n")
    return path


def test_csv_record_in_degrees_and_gap_split(tmp_path):
    t = np.arange(0.0, 60.0, 1.0)
    t[30:] += 100.0  # a gap of 101 s between samples 29 and 30
    rows = [(ti, 5.0 * math.sin(ti / 5), 2.0 * ti) for ti in t]
    recs = read_records(write_csv(tmp_path / "a.csv", ("time", "rudder_angle", "heading"),
                                  rows))
    assert [r.name[-2:] for r in recs] == ["#1", "#2"] and len(recs[0]) == 30
    assert recs[0].rudder_angle[5] == pytest.approx(math.radians(5.0 * math.sin(1.0)))
    assert recs[0].heading[3] == pytest.approx(math.radians(6.0))


@pytest.mark.parametrize("header, rows, match", [
    (("time", "rudder_angle", "heading"), [(i, (-1) ** i, i if i != 7 else "nan")
                                           for i in range(20)],
     r"column `heading` row 9 is not a finite number"),
    (("time", "rudder_angle", "heading"), [(i if i != 5 else 3, (-1) ** i, i) for i in range(20)],
     r"column `time` row 7 does not increase"),
    (("time", "heading"), [(i, i) for i in range(20)], r"missing column `rudder_angle`"),
    (("time", "rudder_angle"), [(i, i) for i in range(20)], r"`heading` or `yaw_rate`"),
    (("time", "rudder_angle", "heading"), [(i, 2.0, i) for i in range(20)],
     r"no rudder activity"),
    (("time", "rudder_angle", "heading"), [(i, (-1) ** i, i) for i in range(5)],
     r"5 samples; a record needs at least 10"),
])
def test_bad_records_name_file_column_and_row(tmp_path, header, rows, match):
    path = write_csv(tmp_path / "bad.csv", header, rows)
    with pytest.raises(ParameterError, match=match) as info:
        read_records(path)
    assert "bad.csv" in str(info.value)


def test_radians_beyond_90_degrees_are_refused(tmp_path):
    path = write_csv(tmp_path / "r.csv", ("time", "rudder_angle", "heading"),
                     [(i, 10.0 * (-1) ** i, 0.1 * i) for i in range(20)])
    with pytest.raises(ParameterError, match="are they degrees"):
        read_records(path, angles="rad")


def test_seahelm_result_files_are_records(tmp_path):
    res = run("maneuver", "zigzag", "--ship", "mariner-nonlinear", "--rudder", "10", "--side",
              "starboard", "--out", str(tmp_path))
    assert res.exit_code == 0, res.output
    recs = read_records(tmp_path / "zigzag-runs.nc")
    assert len(recs) == 1 and {"surge_speed", "x", "y"} <= set(recs[0].channels)


# -- the fit -------------------------------------------------------------------------------
def test_batched_simulation_equals_single_runs():
    rec = synthetic(None)
    thetas = np.array([TRUTH, TRUTH * [1.1, 0.9, 1.0], TRUTH * [0.8, 1.2, -1.0]])
    inits = np.array([[0.0, 0.0], [0.1, 0.001], [-0.2, 0.0]])
    batch = simulate_records(1, thetas, inits, rec, "heading")
    for i in range(3):
        single = simulate_records(1, thetas[i:i + 1], inits[i:i + 1], rec, "heading")[0]
        np.testing.assert_array_equal(batch[i], single)


def test_noise_free_record_gives_the_truth():
    fit = fit_nomoto(synthetic(None))
    np.testing.assert_allclose(fit.values, TRUTH, rtol=2e-3)
    assert fit.unidentifiable() == {}


def test_laplace_intervals_cover_the_truth_90_to_99_percent():
    """Coverage over 100 seeded noise realisations (white noise σ = 0.2°): the 95 % intervals
    of K and T contain the truth 90–99 % of the time."""
    hits = np.zeros(2)
    n = 100
    for seed in range(n):
        fit = fit_nomoto(synthetic(seed))
        ci = fit.confidence_intervals(0.95)
        hits += (ci[:2, 0] <= TRUTH[:2]) & (TRUTH[:2] <= ci[:2, 1])
    coverage = hits / n
    assert np.all((0.90 <= coverage) & (coverage <= 0.99)), coverage


def test_several_records_are_fitted_together():
    recs = [synthetic(1, amplitude=10.0, name="zz10"), synthetic(2, amplitude=20.0,
                                                                name="zz20")]
    joint = fit_nomoto(recs)
    single = fit_nomoto(recs[0])
    np.testing.assert_allclose(joint.values, TRUTH, rtol=0.02, atol=1e-4)
    assert np.all(joint.standard_errors[:2] < single.standard_errors[:2])
    assert joint.initial_states.shape == (2, 2) and joint.records == ("zz10", "zz20")


def test_second_order_on_first_order_data_reports_what_it_cannot_identify():
    fit = fit_nomoto(synthetic(3), order=2)
    bad = fit.unidentifiable()
    assert set(bad) == {"t2", "t3"}, bad
    assert all("standard error" in why or "correlation" in why for why in bad.values())
    ci = fit.confidence_intervals()
    assert ci[0, 0] <= TRUTH[0] <= ci[0, 1]
    with pytest.raises(ParameterError, match="do not identify T_2"):
        nomoto_ship(fit, name="x", speed=7.0, length=100.0)
    row = {r["name"]: r for r in fit.as_dict()["parameters"]}["t2"]
    assert row["identified"] is False and "value" not in row and row["evidence"]


def test_mariner_10_10_zigzag_against_the_linearised_model(tmp_path):
    """The nonlinear Mariner's own 10/10 zig-zag against MSS's linearised constants (K 0.185
    1/s, T 107 s; T_1 118, T_2 7.8, T_3 18.5 s): the first-order fit gets the initial turning
    ratio K/T within 15 %; K and T alone are much smaller, the zig-zag of a nonlinear ship at
    10° not being the linear model's (stated in the docs); the second order's K within 25 %."""
    run("maneuver", "zigzag", "--ship", "mariner-nonlinear", "--rudder", "10", "--side",
        "starboard", "--out", str(tmp_path))
    recs = read_records(tmp_path / "zigzag-runs.nc")
    first = fit_nomoto(recs, 1)
    k, t = first.values[:2]
    assert k / t == pytest.approx(0.185 / 107.0, rel=0.15)
    second = fit_nomoto(recs, 2)
    assert second.values[0] == pytest.approx(0.185, rel=0.25)
    assert second.unidentifiable() == {}


def test_bootstrap_widens_intervals_when_residuals_are_correlated(tmp_path):
    run("maneuver", "zigzag", "--ship", "mariner-nonlinear", "--rudder", "10", "--side",
        "starboard", "--out", str(tmp_path))
    fit = fit_nomoto(read_records(tmp_path / "zigzag-runs.nc"), bootstrap=12, seed=1)
    assert fit.residual_autocorrelation > 0.9
    width = np.diff(fit.confidence_intervals(), axis=1).ravel()
    boot = np.diff(fit.bootstrap_intervals(), axis=1).ravel()
    assert np.all(boot[:2] > width[:2])


@pytest.mark.parametrize("kwargs, field", [({"order": 3}, "order"), ({"bootstrap": -1},
                                                                     "bootstrap"),
                                           ({"speed": 0.0}, "speed")])
def test_fit_bad_arguments(kwargs, field):
    with pytest.raises(ParameterError) as info:
        fit_nomoto(synthetic(None), **kwargs)
    assert info.value.field == field


# -- CLI -----------------------------------------------------------------------------------
def test_cli_identify_nomoto_writes_a_ship_that_runs(tmp_path):
    rec = synthetic(5)
    path = write_csv(tmp_path / "zz.csv", ("time", "rudder_angle", "heading"),
                     zip(rec.time, np.degrees(rec.rudder_angle), np.degrees(rec.heading)))
    res = run("identify", "nomoto", str(path), "--speed", "7.7", "--length", "160",
              "-o", str(tmp_path / "ship.toml"), "--plot", str(tmp_path / "fit.png"),
              "--json")
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    k = {p["name"]: p for p in data["parameters"]}["gain"]
    assert k["ci_low"] <= 0.05 <= k["ci_high"]
    assert (tmp_path / "fit.png").stat().st_size > 10_000
    from seahelm.ships import read_ship

    ship = read_ship(tmp_path / "ship.toml")
    assert ship.model.name == "nomoto1" and ship.params.gain == pytest.approx(k["value"])
    assert "output-error fit" in ship.source_of("gain")
    imo = run("imo", str(tmp_path / "ship.toml"), "--json")
    assert imo.exit_code == 0, imo.output
    table = run("identify", "nomoto", str(path), "--order", "2")
    assert table.exit_code == 0 and "unidentifiable" in table.output


@pytest.mark.parametrize("args, message", [
    (["missing.csv"], "no such file"),
    (["{csv}", "--order", "3"], "--order"),
    (["{csv}", "--level", "1.5"], "`--level` must be in (0, 1)"),
    (["{csv}", "-o", "{out}"], "`--length` is needed"),
])
def test_cli_identify_nomoto_bad_input(tmp_path, args, message):
    rec = synthetic(None)
    csv = write_csv(tmp_path / "zz.csv", ("time", "rudder_angle", "heading"),
                    zip(rec.time, np.degrees(rec.rudder_angle), np.degrees(rec.heading)))
    args = [a.format(csv=csv, out=tmp_path / "s.toml") for a in args]
    res = run("identify", "nomoto", *args, "--speed", "7")
    assert res.exit_code == 2, res.output
    assert message in res.output


def test_cli_imo_probabilities_given_the_identification(tmp_path):
    rec = synthetic(5)
    path = write_csv(tmp_path / "zz.csv", ("time", "rudder_angle", "heading"),
                     zip(rec.time, np.degrees(rec.rudder_angle), np.degrees(rec.heading)))
    res = run("identify", "nomoto", str(path), "--imo", "8", "--seed", "1", "--speed", "7",
              "--length", "150", "--json")
    assert res.exit_code == 0, res.output
    imo = json.loads(res.stdout)["imo"]
    assert imo["total"] + imo["excluded"] == 8 and 0.0 <= imo["probability"] <= 1.0
    assert {r["criterion"] for r in imo["criteria"]} >= {"advance", "tactical diameter"}
    bad = run("identify", "nomoto", str(path), "--imo", "8")
    assert bad.exit_code == 2 and "`--imo` needs `--speed` and `--length`" in bad.output
