"""Sweeps on real dask.distributed clusters (loopback only, every test bounded in time).

A sweep on a local cluster of 2 worker processes equals the in-process sweep bit for bit; a
worker killed (SIGKILL, by pid) while it computes a chunk loses no run and duplicates none; an
unreachable scheduler is a clear error within its timeout. The workers load the kernels the
coordinator compiled from the on-disk cache (they inherit SEAHELM_CACHE_DIR / NUMBA_CACHE_DIR).
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("distributed")

from seahelm.errors import ParameterError  # noqa: E402
from seahelm.sweep import open_sweep, run_sweep  # noqa: E402
from seahelm.sweep.store import MARKERS  # noqa: E402

from test_sweep import N_RUNS, SCENARIO  # noqa: E402

#: Each run integrates 1500 s at 10 ms (~0.1 s of CPU): a chunk of one run is still being
#: computed when the worker is killed.
# chunks long enough (a run each, ~0.2 s) for a worker to be caught computing one
SLOW = SCENARIO.replace("t_final = 60.0", "t_final = 20000.0").replace(
    "dt = 0.1\n", "dt = 0.01\n").replace("record_every = 10", "record_every = 1000")


@contextlib.contextmanager
def deadline(seconds: float):
    """Fail (instead of hanging) if the block takes longer than ``seconds``."""
    def expired(signum, frame):
        raise TimeoutError(f"the test took longer than {seconds} s")

    previous = signal.signal(signal.SIGALRM, expired)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _load(store: Path):
    ds = open_sweep(store, flat=True).load()
    ds.attrs.pop("scenario_source")
    return ds


@pytest.fixture(scope="module")
def cluster():
    """A local cluster of 2 worker processes started as ``run_sweep(workers=2)`` starts it."""
    from seahelm.sweep.executors import executor

    pool = executor(workers=2)
    with deadline(120):
        pool.__enter__()
    yield pool.cluster, pool.client
    with deadline(60):
        pool.__exit__(None, None, None)


@pytest.fixture(scope="module")
def in_process(tmp_path_factory):
    base = tmp_path_factory.mktemp("here")
    (base / "study.toml").write_text(SCENARIO)
    with deadline(120):
        run_sweep(base / "study.toml", base / "here.zarr", chunk_size=3)
    return base / "study.toml", _load(base / "here.zarr")


def test_two_local_workers_equal_the_in_process_sweep(cluster, in_process, tmp_path):
    cl, client = cluster
    path, here = in_process
    assert len(client.scheduler_info()["workers"]) == 2
    # the workers inherit the kernel cache (they load what this process compiled)
    seen = client.run(lambda: os.environ.get("SEAHELM_CACHE_DIR"))
    assert set(seen.values()) == {os.environ.get("SEAHELM_CACHE_DIR")}
    with deadline(120):
        there = run_sweep(path, tmp_path / "there.zarr", chunk_size=3, client=client)
    assert (there.n_chunks, there.computed) == (5, 5)
    ds = _load(tmp_path / "there.zarr")
    assert ds.identical(here)
    assert np.array_equal(ds["run"].values, np.arange(N_RUNS))


def test_a_running_scheduler_by_its_address(cluster, in_process, tmp_path):
    cl, client = cluster
    path, here = in_process
    with deadline(120):
        run_sweep(path, tmp_path / "there.zarr", chunk_size=3, scheduler=cl.scheduler_address)
    assert _load(tmp_path / "there.zarr").identical(here)


def test_a_worker_killed_mid_sweep_loses_and_duplicates_nothing(cluster, tmp_path):
    cl, client = cluster
    path = tmp_path / "slow.toml"
    path.write_text(SLOW)
    killed: list[int] = []
    written: list[int] = []

    def kill_once(done: int, total: int) -> None:
        written.append(done)
        if killed or done < 1:
            return
        pids = client.run(os.getpid)
        busy: list[str] = []
        for _ in range(100):  # the scheduler may take a moment to hand out the next chunk
            busy = [addr for addr, keys in client.processing().items() if keys]
            if busy:
                break
            time.sleep(0.05)
        assert busy, "no worker is computing a chunk: the sweep is too short to test a kill"
        pid = pids[busy[0]]
        os.kill(pid, signal.SIGKILL)
        killed.append(pid)

    with deadline(300):
        report = run_sweep(path, tmp_path / "killed.zarr", chunk_size=1, client=client,
                           progress=kill_once)
        run_sweep(path, tmp_path / "here.zarr", chunk_size=1)  # the reference
    assert killed
    assert (report.n_chunks, report.computed, report.skipped) == (N_RUNS, N_RUNS, 0)
    assert written == list(range(N_RUNS + 1))  # each chunk written once
    markers = sorted(p.name for p in (tmp_path / "killed.zarr" / MARKERS).glob("0*"))
    assert markers == [f"{i:06d}" for i in range(N_RUNS)]
    a, b = _load(tmp_path / "killed.zarr"), _load(tmp_path / "here.zarr")
    assert np.array_equal(a["run"].values, np.arange(N_RUNS))
    assert np.all(np.isfinite(a["heading"].values))
    assert a.identical(b)


def test_an_unreachable_scheduler_is_a_clear_error_within_the_timeout(tmp_path):
    with socket.socket() as s:  # a loopback port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    path = tmp_path / "study.toml"
    path.write_text(SCENARIO)
    start = time.perf_counter()
    with deadline(60), pytest.raises(ParameterError, match=(
            rf"cannot reach the dask scheduler at tcp://127.0.0.1:{port} within 2 s")):
        run_sweep(path, tmp_path / "s.zarr", scheduler=f"tcp://127.0.0.1:{port}", timeout=2.0)
    assert time.perf_counter() - start < 30
    assert not (tmp_path / "s.zarr").exists()
