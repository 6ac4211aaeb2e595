"""``seahelm inspect`` (alias ``summary``): metadata, per-run status, summary table and
Monte-Carlo statistics of a result file; a file that is not a seahelm result exits 2."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from conftest import REPORT_BATCH_SCENARIO, one_error
from seahelm.cli.main import app
from seahelm.results import load_result

runner = CliRunner()

#: A 2-point grid × 5 Monte-Carlo samples on the demo's component combination (its compiled
#: kernel is shared with the other CLI tests); kp = 4 leaves the yaw-rate bounds in every
#: sample (diverged, "state out of bounds"), kp = 1 never does.
SCENARIO = REPORT_BATCH_SCENARIO  # (tests/conftest.py: the report tests run it too)


@pytest.fixture(scope="module")
def batch_file(tmp_path_factory):
    """The scenario run once: its result file and the JSON `seahelm run` printed."""
    where = tmp_path_factory.mktemp("inspect")
    scenario = where / "s.toml"
    scenario.write_text(SCENARIO)
    res = runner.invoke(app, ["run", str(scenario), "--json", "--out", str(where / "o"),
                              "--no-plot"])
    assert res.exit_code == 3, res.output  # written, but 5 of the 10 runs diverged
    return where / "o" / "result.nc", json.loads(res.stdout)


def test_diverged_runs_exit_3_after_writing_everything(tmp_path):
    """Exit code 3 (README): the files and the summary are complete, and it says how many."""
    scenario = tmp_path / "s.toml"
    scenario.write_text(SCENARIO)
    res = runner.invoke(app, ["run", str(scenario), "--out", str(tmp_path / "o")],
                        env={"COLUMNS": "160"})
    assert res.exit_code == 3, res.output
    assert "10 run(s), 5 ok, 5 diverged" in res.stdout
    assert {p.name for p in (tmp_path / "o").iterdir()} == {"result.nc", "overview.png"}
    ok_only = tmp_path / "ok.toml"  # kp = 1 alone never diverges: exit 0
    ok_only.write_text(SCENARIO.replace('"controller.params.kp" = [1.0, 4.0]',
                                        '"controller.params.kp" = [1.0]'))
    assert runner.invoke(app, ["run", str(ok_only)]).exit_code == 0


def test_json_has_metadata_status_and_the_summary_run_printed(batch_file):
    path, ran = batch_file
    res = runner.invoke(app, ["inspect", str(path), "--json"])
    assert res.exit_code == 0, res.output
    got = json.loads(res.stdout)
    assert got["metadata"]["title"] == "report test batch"
    assert got["metadata"]["seed"] == 3 and got["metadata"]["model"] == "nomoto2"
    assert "[batch.monte_carlo]" in got["metadata"]["scenario_text"]
    assert got["dims"] == {"kp": 2, "sample": 5} == ran["dims"]
    assert (got["n_runs"], got["n_ok"], got["n_diverged"]) == (10, 5, 5)
    assert got["batch"]["axes"] == [{"name": "kp", "key": "controller.params.kp",
                                     "values": [1.0, 4.0], "units": "rad/rad"}]
    assert got["batch"]["drawn"][0]["name"] == "vessel.params.gain"
    assert got["batch"]["drawn"][0]["distribution"] == "normal"
    # the summary is the one `seahelm run` printed, computed again from the file
    assert got["runs"] == ran["runs"]
    assert got["statistics"] == ran["statistics"]


def test_diverged_runs_have_time_and_reason(batch_file):
    path, _ = batch_file
    got = json.loads(runner.invoke(app, ["inspect", str(path), "--json"]).stdout)
    ds = load_result(path)
    assert [d["run"] for d in got["diverged"]] == [5, 6, 7, 8, 9]
    for d in got["diverged"]:
        assert d["kp"] == 4.0 and d["reason"] == "state out of bounds"
        assert d["time_s"] == pytest.approx(float(ds["failure_time"].sel(kp=4.0)[d["sample"]]))
        assert 0.0 < d["time_s"] < 120.0
    human = runner.invoke(app, ["inspect", str(path)]).stdout
    assert "status: 10 run(s), 5 ok, 5 diverged" in human
    assert "diverged runs" in human and "state out of bounds" in human


def test_monte_carlo_statistics_per_grid_point(batch_file):
    path, ran = batch_file
    ds = load_result(path)
    stats = {entry["point"]["kp"]: entry for entry in ran["statistics"]}
    assert set(stats) == {1.0, 4.0}
    gains = ds["vessel.params.gain"].sel(kp=1.0).values
    drawn = stats[1.0]["drawn"]["vessel.params.gain"]
    assert drawn["n"] == 5
    assert drawn["mean"] == pytest.approx(gains.mean())
    assert drawn["std"] == pytest.approx(gains.std(ddof=1))
    assert drawn["q50"] == pytest.approx(np.median(gains))
    heading = np.degrees(ds["heading"].sel(kp=1.0).values[:, -1])
    metric = stats[1.0]["metrics"]["heading_deg"]
    assert metric["mean"] == pytest.approx(heading.mean())
    assert metric["q05"] == pytest.approx(np.quantile(heading, 0.05))
    assert metric["q95"] == pytest.approx(np.quantile(heading, 0.95))
    # every sample of kp = 4 diverged: no metric over ok runs, the draws still counted
    assert stats[4.0]["n_ok"] == 0 and stats[4.0]["drawn"]["vessel.params.gain"]["n"] == 5
    assert stats[4.0]["metrics"]["heading_deg"]["n"] == 0


def test_human_output_shows_the_batch_and_the_statistics(batch_file):
    path, _ = batch_file
    res = runner.invoke(app, ["summary", str(path)], env={"COLUMNS": "160"})
    assert res.exit_code == 0, res.output
    out = res.stdout
    assert "controller.params.kp = 1, 4 [rad/rad]" in out
    assert "vessel.params.gain (normal) [1/s]" in out
    assert "Monte-Carlo statistics at kp=1" in out
    for column in ("mean", "std", "q05", "q50", "q95"):
        assert column in out
    assert "diverged at" in out  # the per-run table's status of a diverged run


def test_run_prints_drawn_values_and_statistics(tmp_path, monkeypatch):
    from seahelm.cli._common import console

    # rich fixes the console's width from $COLUMNS when the CLI is first imported in this
    # process (by whichever test came first): the table at 160 columns, whatever that was
    monkeypatch.setattr(console, "_width", 160)
    scenario = tmp_path / "s.toml"
    scenario.write_text(SCENARIO.replace('[batch.grid]\n"controller.params.kp" = [1.0, 4.0]\n',
                                         ""))
    res = runner.invoke(app, ["run", str(scenario)], env={"COLUMNS": "160"})
    assert res.exit_code == 3, res.output  # (kp = 3: every sample diverges)
    gains = json.loads(runner.invoke(app, ["run", str(scenario), "--json"]).stdout)["runs"]
    first = next(line for line in res.stdout.splitlines() if line.startswith("│   0 │"))
    assert f"{gains[0]['vessel.params.gain']:.5g}" in first  # the draw: a column of the table
    assert "Monte-Carlo statistics: drawn values over all 5 samples" in res.stdout


def test_a_single_run(tmp_path):
    res = runner.invoke(app, ["demo", "--out", str(tmp_path), "--json"])
    assert res.exit_code == 0, res.output
    ran = json.loads(res.stdout)
    got = json.loads(runner.invoke(app, ["inspect", str(tmp_path / "result.nc"),
                                         "--json"]).stdout)
    assert got["runs"] == ran["runs"] and got["diverged"] == []
    assert "statistics" not in got
    human = runner.invoke(app, ["inspect", str(tmp_path / "result.nc")]).stdout
    assert "none (nothing random in the runs)" in human
    assert "settling time [s]" in human and "Mariner: 20 degree course change" in human


def test_refuses_what_is_not_a_result(tmp_path):
    import xarray as xr

    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(foreign, engine="h5netcdf")
    assert one_error(["inspect", str(foreign)]) == (
        f"error: {foreign}: not a seahelm result file: neither a simulation result (result.nc "
        "of `seahelm run --out`, a manoeuvre's *-runs.nc), a manoeuvre's *-metrics.nc, an "
        "imo-probabilities.nc nor a replay.nc")
    text = tmp_path / "notes.nc"
    text.write_text("not netcdf\n")
    assert "not a NetCDF-4/HDF5 file written by seahelm" in one_error(["inspect", str(text)])
    assert one_error(["summary", str(tmp_path / "none.nc")]) == \
        f"error: `RESULT`: no such file: {tmp_path / 'none.nc'}"
    assert one_error(["inspect", str(tmp_path)]) == \
        f"error: `RESULT`: {tmp_path} is a directory, not a file"


def test_a_manoeuvre_metrics_file(tmp_path):
    # the shape `seahelm maneuver --out` writes (metrics over the batch dims, `complete`,
    # attrs["maneuver"]), built here so that no manoeuvre kernel is compiled for this test
    import xarray as xr

    ds = xr.Dataset(
        {"advance": ("side", [21.559, 21.638], {"units": "m"}),
         "speed_loss": ("side", [0.61342, 0.5], {"units": "1"}),
         "steady_drift_angle": ("side", [math.pi / 6, -0.1], {"units": "rad"}),
         "complete": ("side", [True, True]),
         "message": ("side", np.array(["ok", "ok"], dtype=object))},
        coords={"side": [1, -1]}, attrs={"maneuver": "turning-circle", "dt": 0.05})
    path = tmp_path / "turning-circle-metrics.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    got = json.loads(runner.invoke(app, ["inspect", str(path), "--json"]).stdout)
    assert got["metadata"]["maneuver"] == "turning-circle" and got["n_runs"] == 2
    assert [r["advance"] for r in got["runs"]] == [21.559, 21.638]
    human = runner.invoke(app, ["inspect", str(path)]).stdout
    assert "turning-circle metrics, 2 run(s)" in human
    assert "advance [m]" in human and "21.638" in human
    # the display rule of the CLI and the report: angles in degrees, fractions in per cent
    # (inspect showed speed_loss [1] and the drift angle in rad); --json as stored
    lines = {line.split("│")[1].strip(): line for line in human.splitlines()
             if line.startswith("│")}
    assert "61.342" in lines["speed loss [%]"]
    assert "30 " in lines["steady drift angle [deg]"]
    assert got["runs"][0]["speed_loss"] == 0.61342
