"""Sweeps: a scenario's grid, Monte-Carlo draws or manoeuvre samples in chunks, streamed to a
resumable Zarr store, in this process or on a dask.distributed cluster.

::

    from seahelm.sweep import run_sweep, open_sweep

    report = run_sweep("study.toml", "study.zarr")                 # in-process (all cores)
    report = run_sweep("study.toml", "study.zarr", workers=4)      # a local dask cluster
    report = run_sweep("study.toml", "study.zarr", scheduler="tcp://10.0.0.5:8786")
    ds = open_sweep("study.zarr")                                  # dims (kp, kd, time), ...

A sweep interrupted at any point and started again with the same arguments skips the chunks
already in the store and gives the same store as an uninterrupted one (:mod:`.store`). The
draws of a Monte-Carlo batch are made per sample from the seed (:mod:`seahelm.numerics.sampling`),
so the chunk size, the executor and the order chunks complete in change nothing in the
results (:mod:`.chunks`). Dask is imported only when a cluster is asked for
(``pip install 'seahelm[dask]'``). A sweep of first-order wave motions over wave heading ×
speed gives the polar seakeeping diagram with each cell's sampling uncertainty
(:func:`sweep_seakeeping`, :mod:`.seakeeping`).
"""

from __future__ import annotations

from .chunks import SweepSpec, auto_chunk_size, compute_chunk, select_runs
from .run import SweepReport, run_sweep, summary_statistics
from .seakeeping import SweepSeakeeping, sweep_seakeeping
from .store import open_sweep

__all__ = ["run_sweep", "open_sweep", "SweepReport", "SweepSpec", "summary_statistics",
           "compute_chunk", "select_runs", "auto_chunk_size", "sweep_seakeeping",
           "SweepSeakeeping"]
