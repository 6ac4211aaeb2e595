"""The IMO check under uncertainty in one command (issue 32, item 3): ``seahelm imo SHIP
--monte-carlo N`` and a ``kind = "imo"`` scenario with ``[batch.monte_carlo]`` (``seahelm run``,
``seahelm sweep``) give the same probabilities; ``imo-probabilities.nc`` and a sweep store keep
every sample's values and the limits, so the probabilities recomputed from them are the ones
shown; samples that do not complete are excluded, counted and their reason recorded; bad input
is one line naming the key, exit 2.

Sizes are small (the IMO check of one KVLCC2 L7 sample costs about 0.3 s).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from conftest import one_error
from seahelm.analysis.imo.probability import probabilities_from_values, wilson_interval
from seahelm.cli.main import app
from seahelm.results import open_result_file
from seahelm.scenario import load_scenario
from seahelm.sweep import open_sweep

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "kvlcc2_imo_monte_carlo.toml"
runner = CliRunner()

DRAWS = {"N_r": '{ distribution = "normal", mean = -0.049, std = 0.0049 }',
         "Y_v": '{ distribution = "normal", mean = -0.315, std = 0.0315 }'}


def scenario(runs: int, seed: int, draws: dict[str, str], extra: str = "") -> str:
    lines = "\n".join(f'"vessel.params.{k}" = {v}' for k, v in draws.items())
    return (f'title = "imo mc"\n[vessel]\nship = "kvlcc2-l7"\n[maneuver]\nkind = "imo"\n{extra}'
            f"[batch.monte_carlo]\nruns = {runs}\nseed = {seed}\n"
            f"[batch.monte_carlo.draws]\n{lines}\n")


def invoke(args: list[str]) -> dict:
    res = runner.invoke(app, args)
    assert res.exit_code == 0, (res.stdout, res.stderr)
    return json.loads(res.stdout)


def check_file(path: Path, payload: dict) -> None:
    """The file's probabilities are the fractions of its counted samples whose values are at
    most the limits (Wilson intervals from those counts), and are what the command printed."""
    ds = open_result_file(path)
    value, limit = ds["value"].values, ds["limit"].values
    complete = ds["complete"].values
    passes = value <= limit
    np.testing.assert_array_equal(ds["passes"].values, passes)
    assert int(ds.attrs["n_counted"]) == complete.sum() == payload["total"]
    assert int(ds.attrs["n_excluded"]) == (~complete).sum() == payload["excluded"]
    for k, row in enumerate(payload["criteria"]):
        n_pass = int(passes[complete, k].sum())
        assert ds["probability"].values[k] == n_pass / complete.sum() == row["probability"]
        assert (ds["ci_low"].values[k], ds["ci_high"].values[k]) == wilson_interval(
            n_pass, int(complete.sum()), float(ds.attrs["confidence_level"]))
        assert ds["limit"].values[k] == row["limit"] and ds["ability"].values[k] == row["ability"]
    every = passes.all(axis=1)
    assert ds.attrs["all_probability"] == every[complete].mean() == payload["probability"]
    again = probabilities_from_values(list(value.T), json.loads(ds.attrs["imo_criteria"]),
                                      complete=complete).as_dict()
    assert again["criteria"] == payload["criteria"]
    assert set(np.flatnonzero(ds["reason"].values != "")) == set(np.flatnonzero(~complete))


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    out = tmp_path_factory.mktemp("example")
    payload = invoke(["run", str(EXAMPLE), "--out", str(out), "--json"])
    return out, payload


def test_the_example_scenario(example):
    """50 samples of the KVLCC2 L7 with 10 % on its linear derivatives: one JSON object with
    every criterion (stopping included), the file with the draws of the scenario."""
    out, payload = example
    assert payload["samples"] == 50 and payload["seed"] == 1
    assert payload["total"] + payload["excluded"] == 50 and len(payload["criteria"]) == 13
    assert 0 < payload["probability"] <= 1 and payload["ci_low"] < payload["ci_high"]
    path = out / "imo-probabilities.nc"
    assert payload["files"] == {"netcdf": str(path),
                                "plot": str(out / "imo-probabilities.png")}
    check_file(path, payload)
    ds = open_result_file(path)
    job = load_scenario(EXAMPLE)
    for key, values in job.draws(np.arange(50)).items():
        np.testing.assert_array_equal(ds[key].values, values)
        assert ds[key].attrs["distribution"] == "normal"
    assert ds.attrs["title"] == job.title and ds.attrs["scenario_text"] == EXAMPLE.read_text()


def test_inspect_and_report_show_the_file(example, tmp_path):
    out, payload = example
    path = out / "imo-probabilities.nc"
    shown = invoke(["inspect", str(path), "--json"])
    for key in ("criteria", "probability", "ci_low", "ci_high", "total", "excluded"):
        assert shown[key] == payload[key], key
    text = runner.invoke(app, ["inspect", str(path)]).stdout
    assert "P(pass)" in text and "excluded" in text and "vessel.params.N_r" in text
    report = invoke(["report", str(path), "-o", str(tmp_path / "r.html"), "--json"])
    assert "imo-probabilities" in report["sections"]
    page = (tmp_path / "r.html").read_text()
    assert "pass probabilities" in page and "Wilson" in page
    # the drawn derivatives: their statistics over the 50 samples and their histograms
    drawn = page[page.index('class="statistics drawn"'):]
    drawn = drawn[:drawn.index("</table>")]
    assert drawn.count("<tr>") == 1 + 4 and "vessel.params.N_r" in drawn
    assert page.count("Plotly.newPlot(") == 2  # the criteria's values, the drawn inputs


def test_the_scenario_equals_the_imo_command(tmp_path):
    """The same draws and seed: the scenario's samples are the command's ships, bit for bit."""
    draws = tmp_path / "draws.toml"
    draws.write_text("[draws]\n" + "\n".join(f"{k} = {v}" for k, v in DRAWS.items()) + "\n")
    scn = tmp_path / "imo.toml"
    scn.write_text(scenario(4, 2, DRAWS))
    cmd = invoke(["imo", "kvlcc2-l7", "--monte-carlo", "4", "--seed", "2", "--draws",
                  str(draws), "--out", str(tmp_path / "a"), "--json"])
    run = invoke(["run", str(scn), "--out", str(tmp_path / "b"), "--json"])
    for key in ("criteria", "probability", "ci_low", "ci_high", "passed", "total", "excluded"):
        assert cmd[key] == run[key], key
    a = open_result_file(tmp_path / "a" / "imo-probabilities.nc")
    b = open_result_file(tmp_path / "b" / "imo-probabilities.nc")
    np.testing.assert_array_equal(a["value"].values, b["value"].values)
    for key in ("vessel.params.N_r", "vessel.params.Y_v"):
        np.testing.assert_array_equal(a[key].values, b[key].values)
    check_file(tmp_path / "a" / "imo-probabilities.nc", cmd)


def test_failed_samples_are_excluded_counted_and_swept_alike(tmp_path):
    """k_0 <= 0 leaves no propeller rps for the straight approach: those samples are not run,
    are excluded with the reason and counted; the sweep of the same scenario in chunks of 2
    (sample 0, alone in the store's template run, has none) stores the same values, and its
    probabilities, from the stored values and limits, are the run's."""
    draws = {"N_r": DRAWS["N_r"],
             "k_0": '{ distribution = "uniform", low = -0.1, high = 0.3 }'}
    scn = tmp_path / "fail.toml"
    scn.write_text(scenario(5, 1, draws))
    job = load_scenario(scn)
    k0 = job.draws(np.arange(5))["vessel.params.k_0"]
    bad = set(np.flatnonzero(k0 <= 0).tolist())
    assert 0 in bad and 0 < len(bad) < 5  # (the seed gives both kinds, sample 0 failing)
    run = invoke(["run", str(scn), "--out", str(tmp_path / "out"), "--json"])
    assert run["excluded"] == len(bad) and run["total"] == 5 - len(bad)
    assert {e["sample"] for e in run["excluded_samples"]} == bad
    assert all(e["reason"].startswith("no straight approach") for e in run["excluded_samples"])
    check_file(tmp_path / "out" / "imo-probabilities.nc", run)
    text = runner.invoke(app, ["run", str(scn)]).stdout
    assert f"{len(bad)} sample(s) excluded" in " ".join(text.split())
    assert "excluded: sample 0: no straight approach" in " ".join(text.split())

    store = tmp_path / "s.zarr"
    swept = invoke(["sweep", str(scn), "--store", str(store), "--chunk-size", "2", "--json"])
    imo = swept["summary"]["imo"]
    for key in ("criteria", "probability", "ci_low", "ci_high", "passed", "total", "excluded"):
        assert imo[key] == run[key], key
    assert swept["summary"]["n_failed"] == len(bad)
    flat = open_sweep(store, flat=True)
    ds = open_result_file(tmp_path / "out" / "imo-probabilities.nc")
    np.testing.assert_array_equal(flat["value"].values, ds["value"].values)
    assert json.loads(flat.attrs["imo_criteria"])[0]["limit"] == 4.5  # (the limits, kept)
    assert list(flat["failure"].values) == [1 if i in bad else 0 for i in range(5)]
    report = invoke(["report", str(store), "-o", str(tmp_path / "s.html"), "--json"])
    assert "imo-probabilities" in report["sections"]
    page = (tmp_path / "s.html").read_text()
    assert "no straight approach" in page


def test_probabilities_from_values():
    criteria = [{"ability": "turning", "criterion": "advance", "side": "port", "limit": 4.5,
                 "unit": "L"},
                {"ability": "stopping", "criterion": "track reach", "side": "-", "limit": 15.0,
                 "unit": "L"}]
    p = probabilities_from_values([[3.0, 5.0, math.nan, 4.5], [10.0, 10.0, 1.0, 16.0]],
                                  criteria)
    assert p.total == 3 and p.excluded == 1 and p.passed == 1
    assert [r["passed"] for r in p.rows] == [2, 2]
    assert p.reasons[2].startswith("no value for turning: advance (port)")
    assert p.rows[0]["probability"] == 2 / 3 and p.rows[0]["median"] == 4.5
    assert (p.rows[0]["ci_low"], p.rows[0]["ci_high"]) == wilson_interval(2, 3)


@pytest.mark.parametrize("value", ["0", "-3", "abc", "1.5"])
def test_bad_sample_counts(value):
    assert "--monte-carlo" in one_error(["imo", "kvlcc2-l7", "--monte-carlo", value])


@pytest.mark.parametrize("draws, extra, named", [
    ({"Z_w": '{ distribution = "normal", mean = 1.0, std = 0.1 }'}, "", "Z_w"),
    ({"displacement": '{ distribution = "normal", mean = -1.0, std = 0.01 }'}, "",
     "displacement"),
    ({"length": '{ distribution = "normal", mean = 7.0, std = 0.1 }'}, "",
     "batch.monte_carlo.vessel.params.length"),
    ({"approach_speed": '{ distribution = "normal", mean = 1.179, std = 0.1 }'}, "",
     "vessel.params.approach_speed"),
    ({"N_r": DRAWS["N_r"]}, "speed = 1.0\n", "maneuver.speed"),
])
def test_bad_scenarios_name_the_key(tmp_path, draws, extra, named):
    scn = tmp_path / "bad.toml"
    scn.write_text(scenario(3, 0, draws, extra))
    for command in (["run", str(scn)], ["sweep", str(scn), "--store", str(tmp_path / "s")]):
        assert named in one_error(command)


@pytest.mark.parametrize("key, value, named", [
    ("Z_w", "{ distribution = \"normal\", mean = 1.0, std = 0.1 }", "Z_w"),
    ("displacement", "{ distribution = \"normal\", mean = -1.0, std = 0.01 }", "displacement"),
    ("length", "{ distribution = \"normal\", mean = 7.0, std = 0.1 }", "length"),
    ("approach_speed", "{ distribution = \"normal\", mean = 1.179, std = 0.1 }",
     "approach_speed"),
])
def test_bad_draws_files_name_the_key(tmp_path, key, value, named):
    draws = tmp_path / "d.toml"
    draws.write_text(f"[draws]\n{key} = {value}\n")
    line = one_error(["imo", "kvlcc2-l7", "--monte-carlo", "3", "--draws", str(draws)])
    assert named in line


def test_sweeps_refuse_what_they_cannot_store(tmp_path):
    for kind, why in (("spiral", "spiral"), ("imo", "[batch.monte_carlo]")):
        scn = tmp_path / f"{kind}.toml"
        scn.write_text(f'[vessel]\nship = "kvlcc2-l7"\n[maneuver]\nkind = "{kind}"\n')
        line = one_error(["sweep", str(scn), "--store", str(tmp_path / f"{kind}.zarr")])
        assert why in line
        assert not (tmp_path / f"{kind}.zarr").exists()
