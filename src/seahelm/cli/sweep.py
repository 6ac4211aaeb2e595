"""``seahelm sweep SCENARIO``: a scenario's batch in chunks, streamed to a resumable Zarr store.

Runs in this process by default (the compiled parallel engine, no scheduler); ``--workers N``
starts a local dask.distributed cluster, ``--scheduler tcp://HOST:PORT`` uses a running one
(``dask scheduler`` / ``dask worker``). The same command started again after an interruption
skips the chunks already in the store. Prints the summary statistics (also stored in the
store's attributes). Exit codes: 0 done, 2 bad input (checked before any run: scenario, chunk
size, workers, scheduler, store path), 1 other failure.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from .._validate import check_positive
from ..errors import ParameterError
from ._common import JsonFlag, ProgressBar, _writable_directory, console, \
    exit_if_diverged, handle_errors, input_file, print_json, store_containing
from ._runs import sweep_summary_table

__all__ = ["sweep"]

#: Rows of the statistics table (the JSON output and the store have them all).
MAX_ROWS = 40


@handle_errors
def sweep(
    scenario: Annotated[Path, typer.Argument(help="Scenario TOML file ([batch] grid and/or "
                                                  "Monte-Carlo draws, or a [maneuver]).")],
    store: Annotated[Path | None, typer.Option(
        help="Zarr store directory (default: <scenario name>.zarr here). A store of the same "
             "scenario is resumed.")] = None,
    chunk_size: Annotated[int | None, typer.Option(
        "--chunk-size", help="Runs per chunk (default: chosen from the runs and workers, or "
                             "the store's when resuming).")] = None,
    workers: Annotated[int | None, typer.Option(
        help="Start a local dask cluster of N worker processes (pip install 'seahelm[dask]').")
    ] = None,
    scheduler: Annotated[str | None, typer.Option(
        help="Use a running dask scheduler, tcp://HOST:PORT.")] = None,
    timeout: Annotated[float, typer.Option(
        help="Seconds to wait for --scheduler.")] = 10.0,
    overwrite: Annotated[bool, typer.Option(
        "--overwrite", help="Replace a store of another scenario or chunk size.")] = False,
    series: Annotated[bool, typer.Option(
        help="Store the time series (--no-series: per-run values and metrics only).")] = True,
    json_out: JsonFlag = False,
) -> None:
    """Run a scenario's sweep in chunks into a resumable Zarr store, in-process or on dask."""
    from ..sweep import run_sweep
    from ..sweep.store import check_store

    input_file("SCENARIO", scenario)
    target = store if store is not None else Path(f"{scenario.stem}.zarr")
    if chunk_size is not None and chunk_size < 1:
        raise ParameterError(f"`--chunk-size` must be >= 1 [runs], got {chunk_size}")
    if workers is not None and workers < 1:
        raise ParameterError(f"`--workers` must be >= 1, got {workers}")
    check_positive("--timeout", timeout, "s")
    if workers is not None and scheduler is not None:
        raise ParameterError("give --workers (a local cluster) or --scheduler (a running one), "
                             "not both")
    # the store is never the scenario, nor inside another store (it may be a store itself:
    # resuming writes into it)
    if target.resolve() == scenario.resolve():
        raise ParameterError(f"`--store` {target} is the scenario file: writing the store "
                             "there would destroy it; choose another path")
    outer = store_containing(target.parent)
    if outer is not None:
        raise ParameterError(f"`--store` {target} is inside the store {outer}: writing there "
                             "would corrupt it; choose a path outside it")
    text = scenario.read_text()
    check_store(target, text, chunk_size=chunk_size, overwrite=overwrite, series=series)
    _writable_directory("--store", target.parent)
    bar = ProgressBar("chunks", enabled=not json_out, delay=0.0, counted=True)
    try:
        report = run_sweep(scenario, target, text=text, chunk_size=chunk_size, workers=workers,
                           scheduler=scheduler, overwrite=overwrite, series=series,
                           timeout=timeout, progress=bar)
    finally:
        bar.close()
    payload = {"store": str(report.store), "n_runs": report.n_runs,
               "n_chunks": report.n_chunks, "chunk_size": report.chunk_size,
               "chunks_computed": report.computed, "chunks_skipped": report.skipped,
               "wall_time_s": report.wall_time_s, "summary": report.summary}
    if json_out:
        print_json(json.loads(json.dumps(payload)))
        exit_if_diverged(report.summary.get("n_diverged", 0))
        return
    summary = report.summary
    table, more = sweep_summary_table(
        f"{scenario}: statistics over {summary['n_runs']} run(s)", summary, MAX_ROWS)
    console.print(table)
    if more > 0:
        console.print(f"  ... {more} more row(s) in the store's sweep_summary and --json",
                      highlight=False)
    if "imo" in summary:  # an IMO check's samples: the probabilities, as `seahelm imo` shows
        from .imo import print_imo_probabilities

        print_imo_probabilities(summary["imo"], f"IMO MSC.137(76): {scenario}, "
                                                f"{summary['imo']['samples']} samples")
    counts = ""
    if "n_ok" in summary:
        counts = f", {summary['n_ok']} ok, {summary['n_failed']} failed"
    console.print(f"{report.n_runs} run(s) in {report.n_chunks} chunk(s) of {report.chunk_size}"
                  f"{counts}; {report.computed} chunk(s) computed, {report.skipped} already "
                  f"in the store; {report.wall_time_s:.3g} s", highlight=False, soft_wrap=True)
    console.print(f"  store: {report.store}", highlight=False, soft_wrap=True)
    exit_if_diverged(summary.get("n_diverged", 0))
