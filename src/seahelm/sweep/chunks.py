"""A sweep's runs in chunks: the plan every process rebuilds from the scenario text, and one
chunk's results.

A sweep is described by a :class:`SweepSpec` -- the scenario text, the chunk size and what to
store -- small enough to send to a worker. Each process (the coordinator, a dask worker on this
or another machine) prepares the scenario's runs from the text once (:func:`prepared`, cached
per process) and computes chunks by index (:func:`compute_chunk`). A chunk's runs are a slice of
the flat runs (C order over the batch dimensions): every per-run input -- parameter rows,
initial states, Monte-Carlo draws, seeds of random signals -- is the slice of the whole batch's
(draws are made per sample from its own generator, :mod:`seahelm.numerics.sampling`), so a
chunk's results do not depend on the chunk size, the order chunks run in or the process that
runs them, and computing a chunk twice gives the same values.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import math
import sys
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ..simulation.problem import Problem

__all__ = ["SweepSpec", "prepared", "select_runs", "compute_chunk", "chunk_bounds",
           "auto_chunk_size", "check_chunk_memory", "MAX_CHUNK_BYTES"]

#: Upper bound of the memory a chunk's results take [bytes] (the automatic chunk size keeps
#: each chunk below it).
MAX_CHUNK_BYTES = 256 * 2**20


@dataclasses.dataclass(frozen=True)
class SweepSpec:
    """What a process needs to compute any chunk of a sweep (picklable, small).

    Parameters
    ----------
    text : str
        The scenario's TOML text.
    source : str
        Its name in messages and metadata (e.g. the file name).
    chunk_size : int
        Runs per chunk (the last chunk may be shorter).
    n_runs : int
        Runs of the whole sweep.
    series : bool
        Store the time series (True) or only the per-run values and metrics (False).
    """

    text: str
    source: str
    chunk_size: int
    n_runs: int
    series: bool = True

    def __post_init__(self) -> None:
        check_chunk_size(self.chunk_size)

    @property
    def n_chunks(self) -> int:
        """Number of chunks."""
        return math.ceil(self.n_runs / self.chunk_size)

    @property
    def fingerprint(self) -> str:
        """SHA-256 of what determines the store's contents (scenario text, chunking, series)."""
        h = hashlib.sha256()
        h.update(self.text.encode())
        h.update(f"\0{self.chunk_size}\0{self.n_runs}\0{int(self.series)}".encode())
        return h.hexdigest()


def check_chunk_size(chunk_size: Any) -> int:
    """``chunk_size`` as a whole number >= 1 [runs], or :class:`ParameterError`."""
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) \
            or chunk_size < 1:
        raise ParameterError(f"`chunk_size` must be a whole number >= 1 [runs], "
                             f"got {chunk_size!r}")
    return int(chunk_size)


def chunk_bounds(spec: SweepSpec, index: int) -> tuple[int, int]:
    """First and one-past-last flat run of chunk ``index``.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    index : int
        Chunk index, 0 <= index < ``spec.n_chunks``.

    Returns
    -------
    (int, int)
    """
    if not 0 <= index < spec.n_chunks:
        raise IndexError(f"chunk {index} outside 0..{spec.n_chunks - 1}")
    start = index * spec.chunk_size
    return start, min(start + spec.chunk_size, spec.n_runs)


def auto_chunk_size(n_runs: int, bytes_per_run: float, *, workers: int = 1) -> int:
    """The chunk size chosen when none is given.

    About eight chunks per worker (load balance, a progress bar that moves, little lost on an
    interruption), no fewer than 256 runs per chunk where there are that many (the engine's
    threads and the per-chunk overheads -- store write, dispatch -- stay small against the
    simulation) and no more than :data:`MAX_CHUNK_BYTES` of results per chunk.

    Parameters
    ----------
    n_runs : int
        Runs of the sweep.
    bytes_per_run : float
        Memory of one run's results [bytes].
    workers : int, optional
        Processes that compute chunks (default 1).

    Returns
    -------
    int
    """
    target = math.ceil(n_runs / (8 * max(1, workers)))
    size = max(target, min(256, n_runs))
    cap = max(1, int(MAX_CHUNK_BYTES // max(bytes_per_run, 1.0)))
    return max(1, min(size, cap, n_runs))


def check_chunk_memory(chunk_size: int, bytes_per_run: float, *, workers: int = 1) -> None:
    """Refuse, before any run, chunks whose results cannot fit in memory.

    Each of ``workers`` processes on this machine holds one chunk's results at a time, with the
    engine's peak (:data:`~seahelm.simulation.engine.RECORD_PEAK_FACTOR` of them); together they
    may take :data:`~seahelm.simulation.engine.RECORD_MEMORY_SHARE` of the memory this process
    may use (:func:`seahelm.resources.memory_limit`). The sweep's whole study is never held at
    once: a streamed sweep is bounded by its chunk, not by the study.

    Parameters
    ----------
    chunk_size : int
        Runs per chunk.
    bytes_per_run : float
        Memory of one run's results [bytes].
    workers : int, optional
        Processes computing chunks on this machine (default 1).

    Raises
    ------
    ParameterError
        With ``field="chunk_size"``, naming the chunk's size, the peak and the limit.
    """
    from ..resources import memory_limit
    from ..simulation.engine import RECORD_MEMORY_SHARE, RECORD_PEAK_FACTOR

    need = RECORD_PEAK_FACTOR * chunk_size * bytes_per_run * max(1, workers)
    limit = memory_limit()
    if limit is None or need <= RECORD_MEMORY_SHARE * limit.bytes:
        return
    fits = max(1, int(RECORD_MEMORY_SHARE * limit.bytes
                      / (RECORD_PEAK_FACTOR * max(bytes_per_run, 1.0) * max(1, workers))))
    raise ParameterError(
        f"= {chunk_size:,} runs would hold {chunk_size * bytes_per_run / 1e9:.3g} GB of results "
        f"per chunk ({max(1, workers)} at a time, a peak of about {RECORD_PEAK_FACTOR:g}x), "
        f"more than {RECORD_MEMORY_SHARE:.0%} of the {limit.bytes / 1e9:.3g} GB this process "
        f"may use ({limit.source}); give at most {fits:,}", field="chunk_size",
        value=chunk_size)


@functools.lru_cache(maxsize=2)
def prepared(text: str, source: str) -> Any:
    """The scenario's job (a :class:`~seahelm.simulation.problem.Problem` or a
    :class:`~seahelm.scenario.ManeuverJob`), prepared once per process and text."""
    from ..scenario import parse_scenario

    # streamed in chunks: bounded by the chunk (check_chunk_memory), not by the whole study
    return parse_scenario(text, source=source, in_memory=False)


def _rows(value: Any, n: int, start: int, stop: int, ndim: int) -> Any:
    """The rows of a per-run array input, or the input itself when it is shared by all runs."""
    if isinstance(value, np.ndarray) and value.ndim == ndim and value.shape[0] == n and n > 1:
        return value[start:stop]
    return value


def select_runs(batch: "Problem", start: int, stop: int) -> "Problem":
    """The runs ``start:stop`` of a batch (flat run order) as a batch of their own.

    Per-run inputs (parameter rows, initial states, constant reference and disturbance rows,
    environment parameters) are sliced; time-varying signals of a scenario keep their runs'
    realisations (their seeds are drawn by flat run index), and so does every input that
    selects its own runs (``select_runs(start, stop)``: the first-order wave motions in the
    loop and after it, :mod:`seahelm.scenario.first_order`). The result has no layout (one
    ``run`` dimension, numbered from 0).

    Parameters
    ----------
    batch : Problem
        A batch with a layout (e.g. from :func:`seahelm.scenario.prepare_runs`).
    start, stop : int
        Flat run indices, 0 <= start < stop <= runs.

    Returns
    -------
    Problem
    """
    n = batch.n_runs
    if n is None or not 0 <= start < stop <= n:
        raise ParameterError(f"runs {start}:{stop} are not a slice of the batch's {n} runs")
    changes: dict[str, Any] = {"layout": None}
    for name, ndim in (("params", 2), ("x0", 2), ("controller_params", 2),
                       ("actuator_params", 2), ("actuator_x0", 2), ("environment_params", 2)):
        changes[name] = _rows(getattr(batch, name), n, start, stop, ndim)
    for name in ("reference", "disturbance"):
        value = getattr(batch, name)
        if isinstance(value, np.ndarray):
            changes[name] = _rows(value, n, start, stop, 3)
        elif value is not None and hasattr(value, "runs") and hasattr(value, "first_run"):
            if len(value.runs) == n and n > 1:
                changes[name] = dataclasses.replace(value, runs=value.runs[start:stop],
                                                    first_run=value.first_run + start)
        elif value is not None:
            raise ParameterError(f"cannot split the `{name}` input ({type(value).__name__}) "
                                 "into chunks")
    for field in dataclasses.fields(batch):  # per-run inputs that select their own runs
        value = getattr(batch, field.name)
        if field.name not in changes and callable(getattr(value, "select_runs", None)):
            changes[field.name] = value.select_runs(start, stop)
    return batch.replace(**changes)


def _limit_threads() -> None:
    """In a dask worker, let the engine use the worker's threads, not every core (several
    workers share a machine)."""
    if "distributed" not in sys.modules:
        return
    try:
        from distributed import get_worker

        nthreads = int(get_worker().state.nthreads)
    except (ImportError, ValueError, AttributeError):
        return
    import numba

    numba.set_num_threads(max(1, min(nthreads, numba.config.NUMBA_NUM_THREADS)))


def compute_chunk(spec: SweepSpec, index: int) -> "xr.Dataset":
    """Simulate chunk ``index`` of a sweep; its per-run results over a global ``run``.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    index : int
        Chunk index, 0 <= index < ``spec.n_chunks``.

    Returns
    -------
    xarray.Dataset
        Variables over ``run`` (flat run indices ``start..stop-1``), with ``time`` for the time
        series; per-run metrics (``kind = "metric"``); no attributes.
    """
    _limit_threads()
    job = prepared(spec.text, spec.source)
    start, stop = chunk_bounds(spec, index)
    from ..scenario import ManeuverJob

    if isinstance(job, ManeuverJob):
        from .maneuvers import maneuver_chunk

        return maneuver_chunk(job, start, stop)
    return simulation_chunk(job, start, stop, series=spec.series)


#: Metadata of the engine that differ from one call to the next (not stored).
_VOLATILE = ("created", "wall_time_s", "compile_time_s")


def simulation_chunk(batch: "Problem", start: int, stop: int, *, series: bool = True,
                     with_attrs: bool = False) -> Any:
    """Runs ``start:stop`` of a ``[simulation]`` batch as a Dataset over the global ``run``.

    The engine's results of the runs (:meth:`~seahelm.results.SimResult.to_xarray`, flat,
    without the status text, which ``status`` and ``failure_time`` say) and their summary
    metrics (:func:`seahelm.analysis.maneuvers.summarize`, ``kind = "metric"``, each with its
    ``units``: :func:`~seahelm.analysis.maneuvers.summary_units`); with
    ``with_attrs`` also the attributes the result carries that are the same on every call
    (model names, integrator, scenario text, ...), as ``(dataset, attrs)``.
    """
    from ..analysis.maneuvers import summarize, summary_units
    from ..scenario import run_batch

    result = run_batch(select_runs(batch, start, stop))
    ds = result.to_xarray(flat=True)
    ds = ds.drop_vars("status_message")
    if not series:
        ds = ds.drop_vars([v for v in ds.data_vars if "time" in ds[v].dims] + ["time"])
    rows = summarize(result)
    units = summary_units(result, rows[0])
    for name in rows[0]:
        if name in ("run", "status"):
            continue
        ds[name] = ("run", np.array([r[name] for r in rows], dtype=float),
                    {"kind": "metric", "units": units[name]})
    ds = ds.assign_coords(run=np.arange(start, stop))
    attrs = {k: v for k, v in ds.attrs.items() if k not in _VOLATILE}
    attrs["sweep_bytes_per_run"] = result_bytes(result) // max(result.n_runs, 1)
    ds.attrs = {}
    return (ds, attrs) if with_attrs else ds


def result_bytes(result: Any) -> int:
    """Memory of a :class:`~seahelm.results.SimResult`'s recorded arrays [bytes] (what a
    chunk holds while it runs, before anything is stored)."""
    return int(sum(getattr(result, name).nbytes for name in
                   ("state", "output", "command", "reference", "disturbance")))


def layout_variables(layout: Any) -> dict[str, tuple[str, np.ndarray, dict[str, Any]]]:
    """The batch's coordinates and drawn values over the flat ``run``: ``{name: ("run",
    values, attrs)}`` (grid coordinates such as ``kp(run)``, ``sample(run)``, Monte-Carlo
    draws named by their key path)."""
    out: dict[str, tuple[str, np.ndarray, dict[str, Any]]] = {}
    if layout is None or layout.is_flat:
        return out
    n = layout.size
    index = np.unravel_index(np.arange(n), layout.shape)
    for axis, where in zip(layout.axes, index):
        out[axis.name] = ("run", np.asarray(axis.values)[where], dict(axis.attrs))
    for v in layout.values:
        attrs = {"kind": "batch_values", **dict(v.attrs)}
        if v.units:
            attrs["units"] = v.units
        out[v.name] = ("run", np.asarray(v.values), attrs)
    return out
