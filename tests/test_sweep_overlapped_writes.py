"""A sweep in this process writes chunk k while it computes chunk k + 1: the same store.

:class:`seahelm.sweep.executors.InProcess` with ``overlap`` hands each chunk's results to the
store's writer on one thread of its own (issue 46 item 6: the Monte-Carlo end to end); the
chunks are written in order, one at a time, and the store equals the one written chunk after
chunk. An exception of the writer (here a progress callback's) stops the sweep with the
chunks before it written, as it did.
"""

from __future__ import annotations

import threading
from pathlib import Path

import pytest

from seahelm.sweep import executors, open_sweep, run, run_sweep
from seahelm.sweep.store import MARKERS

SCENARIO = """
title = "overlapped writes"
[vessel]
model = "nomoto2"
catalog = "mariner-nomoto2"
[actuator]
model = "rudder-servo"
[controller]
model = "pid-heading"
dt = 0.5
[controller.reference]
heading_deg = 20.0
[simulation]
t_final = 30.0
dt = 0.1
record_every = 10
[batch.monte_carlo]
runs = 10
seed = 3
[batch.monte_carlo.draws]
"vessel.params.gain" = { distribution = "normal", mean = 0.185, std = 0.02 }
"""


def _store(tmp_path: Path, name: str, overlap: bool, monkeypatch, progress=None) -> Path:
    monkeypatch.setattr(run, "_two_chunks_fit", lambda *a: overlap)
    scenario = tmp_path / "study.toml"
    scenario.write_text(SCENARIO)
    store = tmp_path / name
    run_sweep(scenario, store, chunk_size=3, progress=progress)
    return store


def test_overlapped_writes_give_the_store_written_chunk_after_chunk(tmp_path, monkeypatch):
    threads = []
    real = executors.InProcess.run

    def spy(self, spec, chunks, on_done):
        def noted(index, ds):
            threads.append((index, threading.current_thread() is threading.main_thread()))
            on_done(index, ds)
        return real(self, spec, chunks, noted)

    monkeypatch.setattr(executors.InProcess, "run", spy)
    overlapped = _store(tmp_path, "a.zarr", True, monkeypatch)
    assert [i for i, _ in threads] == [0, 1, 2, 3]  # in order, 4 chunks of 3 runs
    assert not any(main for _, main in threads)  # on the writer thread
    threads.clear()
    sequential = _store(tmp_path, "b.zarr", False, monkeypatch)
    assert all(main for _, main in threads)
    a, b = open_sweep(overlapped, flat=True).load(), open_sweep(sequential, flat=True).load()
    for ds in (a, b):
        ds.attrs.pop("scenario_source", None)
    assert a.identical(b)


def test_a_writer_exception_stops_the_sweep_with_the_chunks_before_it(tmp_path, monkeypatch):
    def stop_after_two(done: int, total: int) -> None:
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        _store(tmp_path, "c.zarr", True, monkeypatch, progress=stop_after_two)
    assert len(list((tmp_path / "c.zarr" / MARKERS).glob("0*"))) == 2
