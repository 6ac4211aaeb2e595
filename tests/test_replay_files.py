"""``seahelm replay``'s step and its file read back (issue 43, open items of the campaign).

* ``replay --dt 100`` of a record sampled every 0.05 s diverged and the error blamed ``--ship``
  ("the replay with ship kvlcc2-l7 failed: diverged: ..."): it now names ``--dt``, the
  divergence and the default step.
* ``inspect`` and ``report`` refused seahelm's own ``replay.nc`` ("not a seahelm result file"):
  they now show its settings, the measured and simulated metrics and (the report) the tracks.

The record is the synthetic FRT-DS-ESSO-header turn of ``tests/test_replay.py``.
"""

from __future__ import annotations

import json

import pytest

from conftest import one_error
from test_replay import SHIP, _simulated_turn, _write, run_cli


@pytest.fixture(scope="module")
def turn_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("rec") / "turn.csv"
    return _write(path, *_simulated_turn())


@pytest.fixture(scope="module")
def replay_out(tmp_path_factory, turn_csv):
    """``replay --out`` of the turn: the directory, and the command's own JSON."""
    out = tmp_path_factory.mktemp("out") / "rep"
    res = run_cli(["replay", str(turn_csv), "--ship", SHIP, "--out", str(out), "--json"])
    assert res.exit_code == 0, res.stderr
    return out, json.loads(res.stdout)["replays"][0]


def test_a_step_that_diverges_names_the_step_not_the_ship(turn_csv):
    line = one_error(["replay", str(turn_csv), "--ship", SHIP, "--dt", "100"])
    assert line.startswith(f"error: `--dt` = 100 s: the replay of {turn_csv} with ship "
                           f"{SHIP} diverged"), line
    assert "coarser than the default 0.05 s" in line and "`--ship`" not in line, line


def test_a_default_step_that_diverges_still_names_the_ship(turn_csv, monkeypatch):
    # the ship (not the step, which was not given) is what the divergence is said of
    import seahelm.analysis.replay.simulate as rp

    real = rp._simulate

    def diverged(simulate, problem, *args):
        res = real(simulate, problem, *args)
        res.status[...] = 1
        return res

    monkeypatch.setattr(rp, "_simulate", diverged)
    line = one_error(["replay", str(turn_csv), "--ship", SHIP])
    assert line.startswith(f"error: `--ship` {turn_csv}: the replay with ship {SHIP} failed"), \
        line


def test_inspect_shows_a_replay_file(replay_out):
    out, printed = replay_out
    res = run_cli(["inspect", str(out / "replay.nc"), "--json"])
    assert res.exit_code == 0, res.stderr
    got = json.loads(res.stdout)
    assert got["metadata"]["ship"] == SHIP and got["metadata"]["kind"] == "turning"
    assert got["tracks"] == ["measured", "simulated"] and got["time_samples"] == 3001
    for key, value in printed["metrics"].items():  # what `seahelm replay` printed, read back
        assert got["metrics"][key]["measured"] == pytest.approx(value["measured"], rel=1e-12)
        assert got["metrics"][key]["simulated"] == pytest.approx(value["simulated"], rel=1e-12)
    assert set(got["metrics"]) == set(printed["metrics"]) == {
        "advance", "transfer", "tactical_diameter", "steady_diameter", "speed_loss"}
    text = run_cli(["inspect", str(out / "replay.nc")])
    assert text.exit_code == 0 and "tactical diameter [m]" in text.stdout
    assert "RMS position error, whole record [L]" in text.stdout


def test_report_of_a_replay_file(replay_out, tmp_path):
    out, printed = replay_out
    page = tmp_path / "replay.html"
    res = run_cli(["report", str(out / "replay.nc"), "-o", str(page), "--json"])
    assert res.exit_code == 0, res.stderr
    summary = json.loads(res.stdout)
    assert "replay" in summary["sections"] and summary["n_runs"] == 1
    html = page.read_text()
    assert "Replay of a measured record" in html and "tactical diameter [m]" in html
    assert f"{printed['metrics']['advance']['measured']:.5g}" in html


def test_a_replay_file_is_reported_alone(replay_out, tmp_path):
    out, _ = replay_out
    res = run_cli(["demo", "--out", str(tmp_path / "demo")])
    assert res.exit_code == 0, res.stderr
    line = one_error(["report", str(out / "replay.nc"), str(tmp_path / "demo" / "result.nc"),
                      "-o", str(tmp_path / "both.html")])
    assert "a replay.nc or an encounters.nc is reported alone" in line, line


def test_a_replay_file_written_before_the_format_attribute_is_read(replay_out, tmp_path):
    import xarray as xr

    out, _ = replay_out
    with xr.open_dataset(out / "replay.nc") as ds:
        old = ds.load()
    del old.attrs["format"]
    old.to_netcdf(tmp_path / "old-replay.nc")
    res = run_cli(["inspect", str(tmp_path / "old-replay.nc"), "--json"])
    assert res.exit_code == 0, res.stderr
    assert json.loads(res.stdout)["metrics"]["advance"]["unit"] == "m"


@pytest.mark.parametrize("damage, message", [
    (lambda ds: ds.assign_attrs(measured_advance="abc"),
     "attribute `measured_advance` must be a number, got 'abc'"),
    (lambda ds: ds.isel(time=slice(0, 0)), "the replay holds no time samples"),
])
def test_a_damaged_replay_file_is_named(replay_out, tmp_path, damage, message):
    # was: "error: could not convert string to float: 'abc'" (no file), and for a file without
    # samples 'failed: IndexError: index -1 is out of bounds' with exit 1 from report
    import xarray as xr

    out, _ = replay_out
    with xr.open_dataset(out / "replay.nc") as ds:
        bad = damage(ds.load())
    path = tmp_path / "damaged.nc"
    bad.to_netcdf(path)
    for args in (["inspect", str(path)], ["report", str(path), "-o", str(tmp_path / "r.html")]):
        assert one_error(args) == f"error: {path}: {message}", args


def test_a_metric_not_reached_shows_a_dash(replay_out, tmp_path):
    import xarray as xr

    out, _ = replay_out
    with xr.open_dataset(out / "replay.nc") as ds:
        bad = ds.load().assign_attrs(simulated_transfer=float("nan"))
    path = tmp_path / "nan.nc"
    bad.to_netcdf(path)
    res = run_cli(["inspect", str(path)])
    assert res.exit_code == 0
    row = next(line for line in res.stdout.splitlines() if "transfer [m]" in line)
    assert row.split("│")[3].strip() == "-" and "nan" not in row, row
