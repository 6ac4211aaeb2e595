"""A sweep store verifies itself: every chunk's marker holds its variables' checksums, so a
chunk file lost or altered after it was written is found (issue 33, part 2)."""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.sweep import open_sweep, run_sweep
from seahelm.sweep.store import CorruptStoreError, damaged_chunks

SCENARIO = """
title = "integrity"
[vessel]
ship = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 20.0
[simulation]
t_final = 30.0
dt = 0.1
record_every = 10
[simulation.bounds]
heading = [-0.1, 0.36]
[batch.grid]
"controller.params.kp" = [0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0]
"""


@pytest.fixture
def store(tmp_path: Path) -> tuple[Path, Path]:
    scenario = tmp_path / "s.toml"
    scenario.write_text(SCENARIO)
    path = tmp_path / "s.zarr"
    run_sweep(scenario, path, chunk_size=2)
    return scenario, path


def _values(path: Path) -> dict[str, np.ndarray]:
    ds = open_sweep(path, flat=True)
    return {name: ds[name].values for name in ("status", "heading", "failure_time")}


def test_a_lost_status_chunk_is_not_read_as_ok(store):
    scenario, path = store
    before = _values(path)
    assert (before["status"] != 0).any() and (before["status"] == 0).any()  # some diverged
    chunk_files = sorted((path / "status" / "c").iterdir())
    assert chunk_files  # (a chunk of only ok runs, all fill value, has no file at all)
    lost = chunk_files[0]
    lost.unlink()  # the diverged runs' status would read as the fill value 0, "ok"
    index = int(lost.name)
    with pytest.raises(CorruptStoreError, match=rf"s.zarr: 1 chunk\(s\) damaged since they "
                                                rf"were written: chunk {index}, runs "
                                                rf"{2 * index}:{2 * index + 2}: variable "
                                                r"`status` does not match its checksum"):
        open_sweep(path)
    res = CliRunner().invoke(app, ["report", str(path), "-o", str(path.parent / "r.html")])
    assert res.exit_code == 2 and "variable `status` does not match" in res.stderr
    # a resume computes the damaged chunk again: the store is whole and as before
    with pytest.warns(UserWarning, match=rf"chunk {index} \(runs"):
        report = run_sweep(scenario, path, chunk_size=2)
    assert report.computed == 1
    after = _values(path)
    for name in before:
        np.testing.assert_array_equal(after[name], before[name])
    assert damaged_chunks(path) == {}


def test_an_altered_compressed_chunk_is_named(store):
    _, path = store
    target = sorted((path / "heading" / "c").rglob("*"))
    target = next(p for p in target if p.is_file())
    data = bytearray(target.read_bytes())
    data[len(data) // 2:len(data) // 2 + 16] = b"\x13" * 16
    target.write_bytes(bytes(data))
    bad = damaged_chunks(path)
    assert len(bad) == 1
    (why,) = bad.values()
    assert "variable `heading`" in why and ("cannot be read" in why or "checksum" in why)


def test_an_intact_store_and_an_older_store_pass(store, tmp_path):
    _, path = store
    assert damaged_chunks(path) == {}
    older = tmp_path / "older.zarr"
    shutil.copytree(path, older)
    for marker in (older / "sweep-chunks").glob("0*"):
        marker.write_text("")  # the markers of an older seahelm: nothing to compare
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert damaged_chunks(older) == {}
        open_sweep(older)


def test_a_stopped_sweep_leaves_no_partial_file(tmp_path, monkeypatch):
    # SIGTERM arrives as SystemExit (seahelm's handler) in the middle of zarr's atomic write,
    # whose clean-up catches Exception only: its *.partial file would stay in the store
    import seahelm.sweep.run as run

    scenario = tmp_path / "s.toml"
    scenario.write_text(SCENARIO)
    path = tmp_path / "s.zarr"
    real = run.write_chunk
    calls = []

    def stopped(store, spec, index, ds):
        calls.append(index)
        if len(calls) == 2:
            (Path(store) / "heading" / "c" / "x.1234.partial").write_bytes(b"half")
            raise SystemExit(143)
        real(store, spec, index, ds)

    monkeypatch.setattr(run, "write_chunk", stopped)
    with pytest.raises(SystemExit):
        run_sweep(scenario, path, chunk_size=2)
    assert not list(path.rglob("*.partial"))
    monkeypatch.setattr(run, "write_chunk", real)
    report = run_sweep(scenario, path, chunk_size=2)  # and it resumes
    assert report.skipped == 1 and damaged_chunks(path) == {}
