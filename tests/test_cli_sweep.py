"""``seahelm sweep SCENARIO`` (CliRunner): runs, resumes, prints and stores the statistics;
bad input is one ``error:`` line and exit code 2, found before anything runs."""

from __future__ import annotations

import json
import socket

import pytest
from typer.testing import CliRunner

from conftest import one_error
from seahelm.cli.main import app
from seahelm.sweep import open_sweep
from seahelm.units import metric_label

from test_sweep import N_RUNS, SCENARIO

runner = CliRunner()


@pytest.fixture
def scenario(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(SCENARIO)
    return path


@pytest.fixture
def no_sweep(monkeypatch):
    """Fail the test if the sweep starts (bad input must be refused first)."""
    import seahelm.sweep

    def tripwire(*args, **kwargs):
        raise AssertionError("the sweep ran before its input was checked")

    monkeypatch.setattr(seahelm.sweep, "run_sweep", tripwire)


def test_sweep_runs_then_resumes_with_the_same_command(scenario, tmp_path):
    store = tmp_path / "out" / "study.zarr"
    args = ["sweep", str(scenario), "--store", str(store), "--chunk-size", "4"]
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.stderr
    first = json.loads(res.stdout)
    assert (first["n_runs"], first["n_chunks"], first["chunks_computed"]) == (N_RUNS, 4, 4)
    stored = json.loads(open_sweep(store).attrs["sweep_summary"])
    assert first["summary"] == stored
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.stderr
    assert "0 chunk(s) computed, 4 already in the store" in res.stdout
    text = " ".join(res.stdout.split())
    assert f"statistics over {N_RUNS} run(s)" in text and "mean" in text


def test_the_default_store_is_named_after_the_scenario(scenario, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["sweep", str(scenario), "--no-series", "--json"])
    assert res.exit_code == 0, res.stderr
    assert json.loads(res.stdout)["store"] == "study.zarr"
    ds = open_sweep(tmp_path / "study.zarr")
    assert "time" not in ds.dims and "final_heading_rad" in ds


def test_bad_input_is_refused_before_the_sweep(scenario, tmp_path, no_sweep):
    store = str(tmp_path / "s.zarr")
    base = ["sweep", str(scenario), "--store", store]
    assert one_error([*base, "--chunk-size", "0"]) == \
        "error: `--chunk-size` must be >= 1 [runs], got 0"
    assert one_error([*base, "--workers", "0"]) == "error: `--workers` must be >= 1, got 0"
    assert one_error([*base, "--timeout", "-1"]) == "error: `--timeout` must be > 0 [s], got -1.0"
    assert "not both" in one_error([*base, "--workers", "2", "--scheduler", "tcp://x:1"])
    afile = tmp_path / "afile"
    afile.write_text("x")
    assert one_error(["sweep", str(scenario), "--store", str(afile)]) == \
        f"error: `--store`: {afile} is a file, not a sweep store (a directory)"
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "keep.txt").write_text("x")
    assert "is not a sweep store" in one_error(
        ["sweep", str(scenario), "--store", str(tmp_path / "data"), "--overwrite"])
    assert "no such file" in one_error(["sweep", str(tmp_path / "missing.toml")])
    assert not (tmp_path / "s.zarr").exists()


def test_bad_scenarios_and_another_scenarios_store(scenario, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENARIO.replace('"truncnormal"', '"gamma"'))
    assert "truncnormal" in one_error(["sweep", str(bad), "--store", str(tmp_path / "b.zarr")])
    bad.write_text(SCENARIO.replace("[[25.0, 5.0], [5.0, 16.0]]", "[[1.0, 5.0], [5.0, 1.0]]"))
    assert "positive definite" in one_error(["sweep", str(bad), "--store",
                                             str(tmp_path / "b.zarr")])
    store = tmp_path / "s.zarr"
    res = runner.invoke(app, ["sweep", str(scenario), "--store", str(store), "--json"])
    assert res.exit_code == 0, res.stderr
    other = tmp_path / "other.toml"
    other.write_text(SCENARIO.replace("seed = 5", "seed = 7"))
    line = one_error(["sweep", str(other), "--store", str(store)])
    assert "holds the sweep of another scenario" in line and "--overwrite" in line
    res = runner.invoke(app, ["sweep", str(other), "--store", str(store), "--overwrite",
                              "--json"])
    assert res.exit_code == 0, res.stderr
    assert open_sweep(store).attrs["seed"] == 7


def test_an_unreachable_scheduler(scenario, tmp_path):
    pytest.importorskip("distributed")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    line = one_error(["sweep", str(scenario), "--store", str(tmp_path / "s.zarr"),
                      "--scheduler", f"tcp://127.0.0.1:{port}", "--timeout", "1"])
    assert f"cannot reach the dask scheduler at tcp://127.0.0.1:{port} within 1 s" in line


def test_inspect_shows_a_store_complete_or_not(scenario, tmp_path):
    """`seahelm inspect STORE.zarr` (it said "is a directory"): the store's state and the
    statistics the sweep printed; while incomplete, those of the runs written."""
    store = tmp_path / "study.zarr"
    res = runner.invoke(app, ["sweep", str(scenario), "--store", str(store), "--chunk-size",
                              "4", "--json"])
    assert res.exit_code == 0, res.stderr
    swept = json.loads(res.stdout)["summary"]
    res = runner.invoke(app, ["inspect", str(store), "--json"])
    assert res.exit_code == 0, res.stderr
    shown = json.loads(res.stdout)
    assert shown["state"] == "complete" and shown["summary"] == swept
    assert (shown["n_runs"], shown["n_chunks"], shown["chunk_size"]) == (N_RUNS, 4, 4)
    res = runner.invoke(app, ["inspect", str(store)], env={"COLUMNS": "100"})
    assert res.exit_code == 0, res.stderr
    text = " ".join(res.stdout.split())
    assert "sweep store, complete" in text and f"statistics over {N_RUNS} run(s)" in text
    first = swept["metrics"][0]
    assert metric_label(first["name"], first["units"]) in text  # (final east [m])
    assert first["units"] == "m"
    # a chunk's marker gone: the store is incomplete, its statistics those of the rest
    (store / "sweep-chunks" / "000001").unlink()
    res = runner.invoke(app, ["inspect", str(store), "--json"])
    assert res.exit_code == 0, res.stderr
    shown = json.loads(res.stdout)
    assert shown["state"] == f"incomplete: {N_RUNS - 4} of {N_RUNS} runs written"
    assert shown["summary"]["n_runs"] == N_RUNS - 4


def test_inspect_refuses_a_directory_that_is_no_store(tmp_path):
    assert "is a directory, not a file" in one_error(["inspect", str(tmp_path)])
