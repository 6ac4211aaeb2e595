"""A new store of an in-process sweep is built while its first chunk is computed (issue 46:
the Monte-Carlo end to end): on a thread of its own, finished before the first chunk is
written; the same store as one built first (``test_sweep_overlapped_writes``); a failed build
stops the sweep with its own error and leaves no store; a resumed store is not built again."""

from __future__ import annotations

import threading
from pathlib import Path

import pytest

from seahelm.sweep import open_sweep, run, run_sweep, store as store_mod
from seahelm.sweep.store import MARKERS

from test_sweep_overlapped_writes import SCENARIO


def _sweep(tmp_path: Path, name: str, monkeypatch, overlap: bool = True) -> Path:
    monkeypatch.setattr(run, "_two_chunks_fit", lambda *a: overlap)
    scenario = tmp_path / "study.toml"
    scenario.write_text(SCENARIO)
    store = tmp_path / name
    run_sweep(scenario, store, chunk_size=3)
    return store


def test_the_store_is_built_on_a_thread_before_the_first_write(tmp_path, monkeypatch):
    events = []
    create, write = store_mod.create_store, store_mod.write_chunk

    def spy_create(path, *a, **k):
        events.append(("create", threading.current_thread() is threading.main_thread()))
        return create(path, *a, **k)

    def spy_write(path, spec, index, ds):
        assert (Path(path) / MARKERS / "init").is_file()  # (the arrays exist)
        events.append(("write", index))
        return write(path, spec, index, ds)

    monkeypatch.setattr(run, "create_store", spy_create)
    monkeypatch.setattr(run, "write_chunk", spy_write)
    store = _sweep(tmp_path, "a.zarr", monkeypatch)
    assert events[0] == ("create", False)  # (not on the main thread)
    assert [e for e in events if e[0] == "write"] == [("write", i) for i in range(4)]
    assert open_sweep(store, flat=True).sizes["run"] == 10
    # resumed: initialised already, nothing built (create_store returns at once, here)
    events.clear()
    _sweep(tmp_path, "a.zarr", monkeypatch)
    assert events == [("create", True)]


def test_a_failed_build_stops_the_sweep_with_its_error(tmp_path, monkeypatch):
    def broken(*a, **k):
        raise OSError("disk full (test)")

    monkeypatch.setattr(run, "create_store", broken)
    with pytest.raises(OSError, match="disk full"):
        _sweep(tmp_path, "b.zarr", monkeypatch)
    assert not (tmp_path / "b.zarr").exists()
