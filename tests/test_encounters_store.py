"""Encounter studies in a resumable Zarr store (issue 51): each chunk written as it finishes;
an interrupted study -- interrupted in the process, or the process killed -- resumes from the
chunks written and equals an uninterrupted run bit for bit; the output policy (a file, a
directory that is not a store, another study) is kept."""

from __future__ import annotations

import dataclasses
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import seahelm.encounters.chunked as chunked
from seahelm.cli.main import app
from seahelm.encounters import AIS, Encounter
from seahelm.encounters.monte_carlo import monte_carlo_vessels
from seahelm.errors import ParameterError
from seahelm.sweep.encounter_store import MARKERS, check_study_store, open_study, run_study

runner = CliRunner()
SRC = Path(__file__).resolve().parents[1] / "src"


def _encounter(**kw):
    vessels, _ = monte_carlo_vessels(7, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                     seed=3, detection_range=(3000.0, 3500.0),
                                     tcpa=(100.0, 300.0), overtaking=0.3,
                                     overtaking_range=(1200.0, 1600.0))
    return Encounter(vessels, t_final=240.0, avoidance="velocity-obstacles", record_every=5,
                     **kw)


def _same(a, b):
    for group in ("tracks", "pair", "verdicts"):
        for name, arr in getattr(a, group).items():
            other = getattr(b, group)[name]
            assert arr.dtype == other.dtype and np.array_equal(arr, other, equal_nan=True), name
    for name in ("status", "min_range", "t_min_range", "min_domain_distance", "situation",
                 "collision", "near_miss", "time", "lengths"):
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name
    assert a.names == b.names and a.summary() == b.summary()


@pytest.fixture(scope="module")
def whole():
    return _encounter().run()


def _markers(store: Path, name: str = "vo") -> list[str]:
    return sorted(p.name for p in (store / name / MARKERS).iterdir() if p.name != "init")


def test_a_study_in_a_store_equals_the_run(tmp_path, whole):
    res = run_study(_encounter(), tmp_path / "s.zarr", "vo", chunk_size=3)
    _same(res, whole)
    assert _markers(tmp_path / "s.zarr") == ["000000", "000001", "000002"]
    _same(open_study(tmp_path / "s.zarr", "vo"), whole)


def test_an_interrupted_study_resumes_with_the_same_numbers(tmp_path, whole, monkeypatch):
    store = tmp_path / "s.zarr"
    ran: list[int] = []
    real = chunked._run_chunk

    def interrupted(vessels, settings):
        if len(ran) == 2:
            raise KeyboardInterrupt
        ran.append(settings["first_encounter"])
        return real(vessels, settings)

    monkeypatch.setattr(chunked, "_run_chunk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_study(_encounter(), store, "vo", chunk_size=2)
    assert ran == [0, 2] and _markers(store) == ["000000", "000001"]
    with pytest.raises(ParameterError, match="2 of 4 chunks still to run"):
        open_study(store, "vo")
    ran.clear()

    def counted(vessels, settings):
        ran.append(settings["first_encounter"])
        return real(vessels, settings)

    monkeypatch.setattr(chunked, "_run_chunk", counted)
    res = run_study(_encounter(), store, "vo", chunk_size=2)
    assert ran == [4, 6]  # (only the chunks not written)
    _same(res, whole)
    ran.clear()
    _same(run_study(_encounter(), store, "vo", chunk_size=2), whole)  # (all there)
    assert ran == []


def test_a_chunk_damaged_since_is_computed_again(tmp_path, whole):
    store = tmp_path / "s.zarr"
    run_study(_encounter(), store, "vo", chunk_size=3)
    chunk = store / "vo" / "north" / "c" / "1"  # (encounters 3-5 of `north`)
    files = [f for f in chunk.rglob("*") if f.is_file()]
    assert files
    for f in files:
        f.write_bytes(b"garbage")
    with pytest.warns(UserWarning, match="damaged since they were written"):
        res = run_study(_encounter(), store, "vo", chunk_size=3)
    _same(res, whole)


def test_a_noisy_study_without_a_seed_resumes_with_its_seed(tmp_path, monkeypatch):
    store = tmp_path / "s.zarr"
    sensor = AIS(position_noise=30.0, heading_noise=0.02)
    real, calls = chunked._run_chunk, []

    def once(vessels, settings):
        if calls:
            raise KeyboardInterrupt
        calls.append(1)
        return real(vessels, settings)

    monkeypatch.setattr(chunked, "_run_chunk", once)
    with pytest.raises(KeyboardInterrupt):
        run_study(_encounter(sensor=sensor), store, "vo", chunk_size=4)
    monkeypatch.setattr(chunked, "_run_chunk", real)
    res = run_study(_encounter(sensor=sensor), store, "vo", chunk_size=4)
    seed = json.loads((store / "vo" / "zarr.json").read_text())["attributes"][
        "study_sensor_seed"]
    _same(res, _encounter(sensor=dataclasses.replace(sensor, seed=seed)).run())


def test_a_study_on_dask_workers_equals_the_run(tmp_path, whole):
    pytest.importorskip("distributed")
    _same(run_study(_encounter(), tmp_path / "s.zarr", "vo", chunk_size=2, workers=2), whole)


def test_the_store_keeps_the_output_policy(tmp_path):
    enc = _encounter()
    mine = tmp_path / "mine.zarr"
    mine.write_text("a user's file\n")
    with pytest.raises(ParameterError, match="is a file.*--force"):
        check_study_store(mine, {"vo": (enc, 2)})
    assert mine.read_text() == "a user's file\n"
    folder = tmp_path / "folder"
    folder.mkdir()
    (folder / "notes.txt").write_text("mine\n")
    with pytest.raises(ParameterError, match="not deleted, even with --force"):
        check_study_store(folder, {"vo": (enc, 2)}, force=True)
    assert (folder / "notes.txt").read_text() == "mine\n"


# -- the command ---------------------------------------------------------------------------
ARGS = ["encounter", "--monte-carlo", "4", "--t-final", "300", "--detection", "2500",
        "--seed", "4", "--avoidance", "rule-based"]


def _table(stdout: str) -> dict:
    return json.loads(stdout)["methods"]


def test_cli_kill_and_resume(tmp_path):
    """The command killed (SIGKILL) after its first chunk is written; the same command
    again runs only the rest, and prints the table of a run without a store."""
    store = tmp_path / "study.zarr"
    env = {**os.environ, "PYTHONPATH": str(SRC), "MPLBACKEND": "Agg"}
    proc = subprocess.Popen([sys.executable, "-m", "seahelm", *ARGS, "--chunk-size", "1",
                             "--store", str(store), "--json"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    marker = store / "rule-based" / MARKERS / "000000"
    deadline = time.monotonic() + 300.0
    while not marker.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    written = _markers(store, "rule-based")
    assert 1 <= len(written) < 4
    res = runner.invoke(app, [*ARGS, "--store", str(store)])
    assert res.exit_code == 0, res.stderr
    assert (f"study rule-based: {len(written)} of 4 chunk(s) there before, "
            f"{4 - len(written)} run now") in res.stdout
    plain = runner.invoke(app, [*ARGS, "--json"])
    again = runner.invoke(app, [*ARGS, "--store", str(store), "--json"])
    assert _table(again.stdout) == _table(plain.stdout)


def test_cli_compare_writes_one_study_per_method(tmp_path):
    store = tmp_path / "study.zarr"
    args = [*ARGS[:-2], "--compare", "--chunk-size", "2", "--store", str(store), "--json"]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.stderr
    assert sorted(p.name for p in store.iterdir() if p.is_dir()) == [
        "none", "rule-based", "velocity-obstacles"]
    assert json.loads(res.stdout)["store"] == str(store)


@pytest.mark.parametrize("setup, extra, match", [
    (None, ["--chunk-size", "3"], "in chunks of 1 encounters, not 3; resume with "
                                  "--chunk-size 1"),
    (None, ["--seed", "5"], "holds another study 'rule-based'"),
    ("file", [], "is a file, not an encounter study store"),
    ("dir", ["--force"], "is not an encounter study store.*not deleted"),
    ("inside", [], "is inside the store"),
])
def test_cli_store_refusals(tmp_path, setup, extra, match):
    store = tmp_path / "study.zarr"
    if setup is None:
        assert runner.invoke(app, [*ARGS, "--chunk-size", "1", "--store", str(store)]
                             ).exit_code == 0
    elif setup == "file":
        store.write_text("mine\n")
    elif setup == "dir":
        store.mkdir()
        (store / "mine.txt").write_text("mine\n")
    else:
        assert runner.invoke(app, [*ARGS, "--store", str(store)]).exit_code == 0
        store = store / "rule-based" / "inner.zarr"
    res = runner.invoke(app, [*ARGS, *extra, "--store", str(store)])  # (the last --seed)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    assert len(res.stderr.strip().splitlines()) == 1 and "--store" in res.stderr
    import re
    assert re.search(match, res.stderr), res.stderr
    if setup == "file":
        assert store.read_text() == "mine\n"
    if setup == "dir":
        assert (store / "mine.txt").read_text() == "mine\n"


def test_cli_force_replaces_a_file_and_another_study(tmp_path):
    store = tmp_path / "study.zarr"
    store.write_text("mine\n")
    assert runner.invoke(app, [*ARGS, "--store", str(store), "--force"]).exit_code == 0
    assert store.is_dir()
    res = runner.invoke(app, [*ARGS, "--seed", "5", "--store", str(store), "--force"])
    assert res.exit_code == 0, res.stderr
    assert "0 of 4 chunk(s) there before, 4 run now" in res.stdout
