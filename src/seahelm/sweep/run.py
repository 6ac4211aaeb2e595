"""Run a sweep: a scenario's runs in chunks, streamed to a resumable store."""

from __future__ import annotations

import contextlib
import dataclasses
import json
import math
import os
import shutil
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from ..analysis.statistics import metric_statistics, quantile_name
from ..errors import ParameterError
from ..units import metric_unit
from .chunks import SweepSpec, auto_chunk_size, check_chunk_memory, check_chunk_size, prepared
from .executors import InProcess, executor
from .imo import is_imo_store, store_probabilities
from .store import (
    check_store,
    completed_chunks,
    create_store,
    is_initialised,
    mark_complete,
    open_sweep,
    store_attrs,
    write_chunk,
)

__all__ = ["SweepReport", "run_sweep", "summary_statistics", "store_metric_units",
           "fill_summary_units", "QUANTILES"]

#: Quantiles of the summary statistics.
QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)


@dataclasses.dataclass(frozen=True)
class SweepReport:
    """What :func:`run_sweep` did.

    Attributes
    ----------
    store : Path
        The store directory.
    n_runs, n_chunks, chunk_size : int
        Runs, chunks and runs per chunk.
    computed, skipped : int
        Chunks computed now, and found complete in the store (a resumed sweep).
    wall_time_s : float
        Time of this call [s].
    summary : dict
        The summary statistics (:func:`summary_statistics`), as stored.
    """

    store: Path
    n_runs: int
    n_chunks: int
    chunk_size: int
    computed: int
    skipped: int
    wall_time_s: float
    summary: dict[str, Any]


def run_sweep(
    scenario: str | Path,
    store: str | Path,
    *,
    text: str | None = None,
    chunk_size: int | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    overwrite: bool = False,
    series: bool = True,
    timeout: float = 10.0,
    client: Any = None,
    progress: Callable[[int, int], None] | None = None,
) -> SweepReport:
    """Run a scenario's batch (grid, Monte-Carlo draws or a manoeuvre's samples) in chunks and
    write the results to a Zarr store, resuming a store of the same sweep.

    With neither ``workers`` nor ``scheduler`` the chunks run in this process on the compiled
    parallel engine; ``workers`` starts a local dask.distributed cluster; ``scheduler`` uses an
    existing one. The results are the same bit for bit in all three cases, and whatever the
    chunk size.

    Parameters
    ----------
    scenario : str or Path
        Scenario TOML file (or its name in messages when ``text`` is given).
    store : str or Path
        Store directory (Zarr). A store of the same scenario is resumed: its completed chunks
        are skipped.
    text : str, optional
        The scenario's text (default: read from ``scenario``).
    chunk_size : int, optional
        Runs per chunk (default: the store's when resuming, else chosen by
        :func:`~seahelm.sweep.chunks.auto_chunk_size`).
    workers : int, optional
        Start a local dask cluster of this many worker processes.
    scheduler : str, optional
        Address of a running dask scheduler, ``tcp://HOST:PORT``.
    overwrite : bool, optional
        Replace a store of another scenario or chunk size (default False: refused).
    series : bool, optional
        Store the time series (default True); False stores per-run values and metrics only.
    timeout : float, optional
        Seconds to wait for ``scheduler`` (default 10).
    client : distributed.Client, optional
        A connected dask client to run the chunks on (e.g. of a cluster started in a notebook;
        left open), instead of ``workers`` or ``scheduler``.
    progress : callable(done_chunks, total_chunks), optional
        Called once chunks already in the store are counted, and after each chunk is written.

    Returns
    -------
    SweepReport

    Raises
    ------
    ParameterError
        Bad input (chunk size, workers, scheduler address or an unreachable scheduler, a store
        path that is a file or another scenario's store), before any run; a
        :class:`~seahelm.scenario.ScenarioError` for the scenario's own errors.
    """
    t0 = time.perf_counter()
    scenario = Path(scenario)
    if text is None:
        if not scenario.is_file():
            raise ParameterError(f"`scenario`: no such file: {scenario}")
        text = scenario.read_text()
    if chunk_size is not None:
        chunk_size = check_chunk_size(chunk_size)
    store = Path(store)
    stored_size = check_store(store, text, chunk_size=chunk_size, overwrite=overwrite,
                              series=series)
    replace = overwrite and store_attrs(store) is not None  # (a sweep store: start afresh)
    source = str(scenario)
    if chunk_size is not None:  # (before the batch is expanded: drawing 1e6 samples takes 30 s)
        _check_chunk_work(text, source, chunk_size)
    pool = executor(workers=workers, scheduler=scheduler, timeout=timeout, client=client)
    job = prepared(text, source)
    with pool, _naming_the_store(store):
        template, layout_vars, coords, attrs, n_runs = _template(job, series)
        bytes_per_run = attrs.get("sweep_bytes_per_run",
                                  template.nbytes / max(template.sizes.get("run", 1), 1))
        if chunk_size is None:
            chunk_size = stored_size or auto_chunk_size(n_runs, bytes_per_run,
                                                         workers=pool.workers)
        local = pool.workers if workers is not None else 1  # (a remote cluster: its own)
        check_chunk_memory(chunk_size, bytes_per_run, workers=local)
        if isinstance(pool, InProcess):  # (a chunk written while the next is computed)
            pool.overlap = _two_chunks_fit(chunk_size, bytes_per_run)
        spec = SweepSpec(text=text, source=source, chunk_size=chunk_size, n_runs=n_runs,
                         series=series)
        attrs["sweep_dims"] = json.dumps(_dims(job))
        if replace:
            shutil.rmtree(store)
        with _store_built(store, spec, template, layout_vars, attrs, coords, pool) as built:
            done = set() if built is not None else completed_chunks(store, spec)
            todo = [i for i in range(spec.n_chunks) if i not in done]
            count = [len(done)]
            if progress is not None:
                progress(count[0], spec.n_chunks)

            def on_done(index: int, ds: Any) -> None:
                if built is not None:
                    built.result()  # (the store's arrays exist before the first write)
                write_chunk(store, spec, index, ds)
                count[0] += 1
                if progress is not None:
                    progress(count[0], spec.n_chunks)

            pool.run(spec, todo, on_done)
    summary = summary_statistics(open_sweep(store, flat=True, verify=False))  # (just checked)
    mark_complete(store, summary)
    return SweepReport(store=store, n_runs=n_runs, n_chunks=spec.n_chunks,
                       chunk_size=chunk_size, computed=len(todo), skipped=len(done),
                       wall_time_s=time.perf_counter() - t0, summary=summary)


@contextlib.contextmanager
def _store_built(store: Path, spec: SweepSpec, template: Any, layout_vars: dict[str, Any],
                 attrs: dict[str, Any], coords: tuple[str, ...], pool: Any) -> Iterator[Any]:
    """Create the store; a new store of an in-process sweep whose chunks are written while
    the next is computed is built on a thread while the first chunk is computed (yields its
    future, which the first write waits for; nothing of it is done yet), else here (yields
    None).

    The store's bytes are the same either way (:func:`~seahelm.sweep.store.create_store` builds
    it next to its place and renames it there); the build's exception is raised at the first
    write or, at the latest, on leaving.
    """
    if not (isinstance(pool, InProcess) and pool.overlap) or is_initialised(store, spec):
        create_store(store, spec, template, layout_vars, attrs, coords=coords)
        yield None
        return
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(1, thread_name_prefix="seahelm-sweep-store") as builder:
        built = builder.submit(create_store, store, spec, template, layout_vars, attrs,
                               coords=coords)
        try:
            yield built
        finally:
            exc = built.exception()  # (waits for the build)
    if exc is not None:
        raise exc


def _two_chunks_fit(chunk_size: int, bytes_per_run: float) -> bool:
    """Whether a chunk's results can be held while the next chunk is computed (the engine's
    peak, :data:`~seahelm.simulation.engine.RECORD_PEAK_FACTOR`, plus one chunk's results)
    within the memory share :func:`~seahelm.sweep.chunks.check_chunk_memory` allows."""
    from ..resources import memory_limit
    from ..simulation.engine import RECORD_MEMORY_SHARE, RECORD_PEAK_FACTOR

    limit = memory_limit()
    need = (RECORD_PEAK_FACTOR + 1) * chunk_size * bytes_per_run
    return limit is None or need <= RECORD_MEMORY_SHARE * limit.bytes


def _check_chunk_work(text: str, source: str, chunk_size: int) -> None:
    """Refuse chunks of more work than the budget (:func:`seahelm.resources.check_work`),
    naming ``chunk_size`` and the largest chunk that fits (a manoeuvre's chunks are checked by
    the engine when they run)."""
    from ..resources import WorkTooLarge, check_work, work_budget
    from ..scenario.loading import validate_scenario
    from ..scenario.runs import scenario_work

    work = scenario_work(validate_scenario(text, source=source))
    if work is None:
        return
    n_runs, steps = work
    runs = min(chunk_size, n_runs)
    fits = int(work_budget() // max(steps, 1.0))
    try:
        check_work(runs, steps, field="chunk_size", advice=(
            f"fewer runs per chunk (`chunk_size` at most {fits:,} at {steps:.3g} steps a run)"
            if fits >= 1 else "a shorter `t_final` or a larger `dt`"))
    except WorkTooLarge as exc:
        raise ParameterError(f"= {chunk_size:,} runs{exc.reason}", field="chunk_size",
                             value=chunk_size) from None


def _dims(job: Any) -> list[tuple[str, int]]:
    from ..scenario import ManeuverJob

    if isinstance(job, ManeuverJob):
        from .maneuvers import maneuver_dims

        return maneuver_dims(job)
    layout = job.layout
    return [] if layout is None else [[d, s] for d, s in zip(layout.dims, layout.shape)]


def _template(job: Any, series: bool) -> tuple[Any, dict[str, Any], tuple[str, ...],
                                                dict[str, Any], int]:
    """One run's results (the store's template), the batch's variables over ``run``, which of
    them are coordinates, the root attributes and the number of runs."""
    from ..scenario import ManeuverJob

    if isinstance(job, ManeuverJob):
        from .maneuvers import maneuver_template

        return maneuver_template(job)
    from .chunks import layout_variables, simulation_chunk

    template, attrs = simulation_chunk(job, 0, 1, series=series, with_attrs=True)
    layout_vars = layout_variables(job.layout)
    layout = job.layout
    coords = tuple(a.name for a in layout.axes) if layout is not None else ()
    return template, layout_vars, coords, attrs, int(job.n_runs or 1)


def summary_statistics(ds: Any) -> dict[str, Any]:
    """Failure counts and, per metric, the count of finite values, mean, standard deviation
    (population, ``ddof=0``), minimum, quantiles (:data:`QUANTILES`) and maximum over the runs
    (:func:`seahelm.analysis.statistics.metric_statistics`).

    Metrics are the per-run variables with ``kind = "metric"`` (and a manoeuvre's metrics),
    for each position along their other dimensions (e.g. ``side``).

    Parameters
    ----------
    ds : xarray.Dataset
        The flat view of a sweep store (:func:`~seahelm.sweep.open_sweep` with ``flat=True``).

    Returns
    -------
    dict
        ``{"n_runs", "n_ok", "n_failed", "metrics": [{"name", "where", "units", "n", "mean",
        "std", "min", "q05", ..., "max"}, ...]}`` (NaN written as None; ``units`` the
        metric's stored unit, :func:`seahelm.units.metric_unit` for a store without it);
        simulation sweeps also ``n_diverged`` (= ``n_failed``: runs whose status is not
        ok), manoeuvre sweeps count incomplete manoeuvres as failed; an IMO check's sweep
        also ``imo``, the probability of passing each criterion and the whole check
        (:func:`~seahelm.sweep.imo.store_probabilities`), and counts its excluded samples as
        failed.
    """
    out: dict[str, Any] = {"n_runs": int(ds.sizes["run"])}
    if "status" in ds:
        status = np.asarray(ds["status"].values)
        out["n_ok"] = int(np.sum(status == 0))
        out["n_failed"] = out["n_diverged"] = int(np.sum(status != 0))
    elif "complete" in ds and ds["complete"].dtype == bool:
        flags = np.asarray(ds["complete"].values)
        while flags.ndim > 1:
            flags = flags.all(axis=-1)
        out["n_ok"] = int(flags.sum())
        out["n_failed"] = int((~flags).sum())
    if is_imo_store(ds):
        out["imo"] = store_probabilities(ds)
        out["n_ok"] = out["imo"]["total"]
        out["n_failed"] = out["imo"]["excluded"]
    qnames = [quantile_name(q) for q in QUANTILES]
    units = store_metric_units(ds)
    rows = []
    for name in sorted(ds.data_vars):  # (a store lists its arrays in no particular order)
        var = ds[name]
        if var.attrs.get("kind") != "metric" or var.dims[:1] != ("run",):
            continue
        values = np.asarray(var.values, dtype=float)
        rest = var.dims[1:]
        for idx in np.ndindex(*values.shape[1:]):
            where = ", ".join(f"{d}={_coord(ds, d, i)}" for d, i in zip(rest, idx))
            s = metric_statistics({name: values[(slice(None), *idx)]}, quantiles=QUANTILES,
                                  ddof=0)[name]
            row: dict[str, Any] = {"name": name, "where": where, "n": s["n"],
                                   "units": units[name]}
            row.update({k: None if math.isnan(s[k]) else s[k]
                        for k in ("mean", "std", "min", "max", *qnames)})
            rows.append(row)
    out["metrics"] = rows
    return out


def store_metric_units(ds: Any) -> dict[str, str]:
    """The stored unit of each metric (``kind = "metric"``) of a sweep store: its ``units``
    attribute, or for a store written before seahelm stored them, the unit its name says
    (:func:`seahelm.units.metric_unit`, with the units of the store's signals).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep store (:func:`~seahelm.sweep.open_sweep`).

    Returns
    -------
    dict of str to str
    """
    signals = {str(n): str(v.attrs["units"]) for n, v in ds.data_vars.items()
               if "units" in v.attrs and v.attrs.get("kind") != "metric"}
    return {str(n): str(v.attrs["units"]) if "units" in v.attrs
            else metric_unit(str(n), signals)
            for n, v in ds.data_vars.items() if v.attrs.get("kind") == "metric"}


def fill_summary_units(summary: dict[str, Any], ds: Any) -> dict[str, Any]:
    """A stored summary (:func:`summary_statistics`) with every metric's unit: a summary
    stored by an older seahelm has blank units, filled here from :func:`store_metric_units`.

    Parameters
    ----------
    summary : dict
        The summary statistics (changed in place).
    ds : xarray.Dataset
        Its sweep store.

    Returns
    -------
    dict
        ``summary``.
    """
    units = store_metric_units(ds)
    for row in summary.get("metrics", ()):
        if not row.get("units"):
            row["units"] = units.get(row["name"], "")
    return summary


def _coord(ds: Any, dim: str, i: int) -> str:
    labels = ds[dim].attrs.get("labels") if dim in ds.coords else None
    if labels:  # (an IMO store's criteria: their names)
        return str(json.loads(labels)[i])
    if dim in ds.coords:
        value = ds[dim].values[i]
        return f"{value:g}" if isinstance(value, (float, np.floating)) else str(value)
    return str(i)


@contextlib.contextmanager
def _naming_the_store(store: Path) -> Iterator[None]:
    """While the store is written: an OS error (a full disk, an I/O error) names the store
    (zarr's own errors name no file), and a stop of any kind (SIGTERM is a ``SystemExit``
    here, which zarr's atomic writes do not clean up after) leaves none of zarr's temporary
    ``*.partial`` files in it."""
    try:
        yield
    except BaseException as exc:
        for partial in store.rglob("*.partial") if store.is_dir() else ():
            with contextlib.suppress(OSError):
                partial.unlink()
        if isinstance(exc, OSError) and exc.filename is None and exc.errno is not None:
            raise OSError(exc.errno, exc.strerror or os.strerror(exc.errno),
                          str(store)) from exc
        raise
