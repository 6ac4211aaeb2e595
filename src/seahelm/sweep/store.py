"""The store of a sweep: a Zarr group written through xarray, one region per chunk.

Layout of the store directory::

    zarr.json, <variables>/         the results over the flat ``run`` (and ``time``); each
                                    Zarr chunk along ``run`` is one sweep chunk, so a chunk's
                                    region is whole Zarr chunks and no two chunks share a file
    sweep-chunks/000012             completion marker of chunk 12, written (atomically) only
                                    after the chunk's region is written
    sweep-chunks/init               written once the store's arrays and coordinates exist

The root attributes hold the scenario text, its SHA-256, the chunking, the batch's layout,
the engine's metadata (model, integrator, seed, seahelm version) and, when every chunk is
written, the summary statistics (``sweep_summary``, JSON). A sweep started again on the
same store skips the chunks with a marker; a chunk written without its marker (the process
died in between) is written again, with the same bytes.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import tempfile
import time
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError
from ..results import atomic_write
from .chunks import SweepSpec

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["MARKERS", "check_store", "create_store", "is_initialised", "completed_chunks",
           "write_chunk",
           "mark_complete", "open_sweep", "store_attrs", "scenario_digest", "chunk_digests",
           "damaged_chunks", "CorruptStoreError"]

#: Directory (inside the store) of the completion markers.
MARKERS = "sweep-chunks"


def scenario_digest(text: str) -> str:
    """SHA-256 of a scenario's text (the store's ``sweep_scenario_sha256``).

    Parameters
    ----------
    text : str
        The scenario's text.

    Returns
    -------
    str
        Hexadecimal digest.
    """
    return hashlib.sha256(text.encode()).hexdigest()


def _zarr() -> Any:
    import zarr

    return zarr


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Zarr warns that the markers directory is not part of the hierarchy: it is not meant to
    be. (``catch_warnings`` is not thread-safe: a chunk written in the sweep's writer thread
    while the command's own ``catch_warnings`` ends in the main thread -- a Ctrl-C -- can
    lose this filter; the CLI also drops the warning where it shows warnings,
    :func:`is_markers_warning`.)"""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=f".*{MARKERS}.*not recognized")
        yield


def is_markers_warning(text: str) -> bool:
    """Whether ``text`` is zarr's warning that the markers directory is not part of the
    hierarchy (see :func:`_quiet`)."""
    return MARKERS in text and "not recognized" in text


def store_attrs(path: str | Path) -> dict[str, Any] | None:
    """The root attributes of a sweep store, or None if ``path`` holds no sweep store.

    Parameters
    ----------
    path : str or Path
        The store directory.

    Returns
    -------
    dict or None
    """
    path = Path(path)
    if not (path / "zarr.json").is_file():
        return None
    try:
        meta = json.loads((path / "zarr.json").read_text())
    except (OSError, ValueError):
        return None
    attrs = meta.get("attributes", {})
    return attrs if "sweep_scenario_sha256" in attrs else None


def check_store(path: str | Path, text: str, *, chunk_size: int | None, overwrite: bool,
                series: bool = True) -> int | None:
    """Check, before any work, that the sweep of ``text`` may write to ``path``.

    Parameters
    ----------
    path : str or Path
        The store directory.
    text : str
        The scenario's text.
    chunk_size : int or None
        The chunk size asked for (None: any).
    overwrite : bool
        Whether a store of another scenario or chunk size may be replaced.
    series : bool, optional
        Whether the sweep stores the time series (default True); a store written the other
        way is refused unless ``overwrite``.

    Returns
    -------
    int or None
        The chunk size of an existing store of the same scenario (None for a new store), which
        a sweep without an explicit chunk size resumes with.

    Raises
    ------
    ParameterError
        If ``path`` is a file; a directory that holds something other than a sweep store (never
        deleted, even with ``overwrite``); a sweep store of another scenario or chunk size
        (unless ``overwrite``).
    """
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ParameterError(f"`store`: {path} is a file, not a sweep store (a directory)")
    if path.is_file() or (path.parent.exists() and not path.parent.is_dir()):
        raise ParameterError(f"`store`: {path.parent} is a file, not a directory")
    if not path.exists() or not any(path.iterdir()):
        return None
    attrs = store_attrs(path)
    if attrs is None:
        raise ParameterError(f"`store`: {path} exists and is not a sweep store; give a new "
                             "path (it is not deleted, even with --overwrite)")
    if overwrite:
        return None
    if attrs["sweep_scenario_sha256"] != scenario_digest(text):
        raise ParameterError(
            f"`store`: {path} holds the sweep of another scenario "
            f"({attrs.get('scenario_source', '?')!s}, '{attrs.get('title', '')}'); give a new "
            "path or --overwrite to replace it")
    stored = int(attrs["sweep_chunk_size"])
    if chunk_size is not None and chunk_size != stored:
        raise ParameterError(
            f"`store`: {path} holds this scenario's sweep in chunks of {stored} runs, not "
            f"{chunk_size}; resume with --chunk-size {stored} (or without it) or --overwrite")
    if int(attrs.get("sweep_series", 1)) != int(series):
        held = "with" if int(attrs.get("sweep_series", 1)) else "without"
        raise ParameterError(
            f"`store`: {path} holds this scenario's sweep {held} the time series; resume "
            f"{'without' if held == 'with' else 'with'} --no-series or give --overwrite")
    return stored


def _initialised(path: Path, spec: SweepSpec) -> bool:
    attrs = store_attrs(path)
    return (attrs is not None and attrs.get("sweep_fingerprint") == spec.fingerprint
            and (path / MARKERS / "init").is_file())


def is_initialised(path: str | Path, spec: SweepSpec) -> bool:
    """Whether ``path`` holds the complete initialisation of this sweep (:func:`create_store`
    would leave it as it is; its completed chunks count).

    Parameters
    ----------
    path : str or Path
        The store directory.
    spec : SweepSpec
        The sweep.

    Returns
    -------
    bool
    """
    return _initialised(Path(path), spec)


def create_store(path: str | Path, spec: SweepSpec, template: "xr.Dataset",
                 layout_vars: dict[str, Any], attrs: dict[str, Any], *,
                 coords: tuple[str, ...] = ()) -> None:
    """Create the store's arrays (empty along ``run`` but for the batch's coordinates), unless
    a complete initialisation of the same sweep is there already.

    Parameters
    ----------
    path : str or Path
        Store directory (replaced if it holds a partial or other sweep).
    spec : SweepSpec
        The sweep.
    template : xarray.Dataset
        One run's results as a chunk gives them (variables over ``run``, coordinate ``run``).
    layout_vars : dict
        ``{name: ("run", values, attrs)}`` over all runs (:func:`.chunks.layout_variables`).
    attrs : dict
        Root attributes (scenario, engine metadata).
    coords : tuple of str
        Names in ``layout_vars`` that are coordinates (the grid's; draws are variables).
    """
    path = Path(path)
    if _initialised(path, spec):
        return
    # built next to the target and renamed onto it: an interruption never leaves half a store
    path.parent.mkdir(parents=True, exist_ok=True)
    final, path = path, Path(tempfile.mkdtemp(dir=path.parent, prefix=f".{path.name}.",
                                              suffix=".tmp"))
    try:
        _build(path, spec, template, layout_vars, attrs, coords)
        if final.exists():
            shutil.rmtree(final)
        os.replace(path, final)
    except BaseException:
        _remove_partial(path)
        raise


def _remove_partial(path: Path, timeout: float = 10.0) -> None:
    """Remove the store being built at ``path`` after a failed write.

    zarr writes a store's chunks concurrently (tasks on its IO event loop, each a thread):
    when one fails (a full disk) the error comes back while the others still run, and each
    recreates its directory as it writes, so a tree removed at once came back (a
    ``.s.zarr.*.tmp`` left on a full disk, seen in a fresh-clone suite). So the writes still
    in flight are waited for (``timeout`` seconds at most), then the tree is removed."""
    import asyncio

    from zarr.core import sync as zarr_sync

    loop = (getattr(zarr_sync, "loop", None) or [None])[0]  # (zarr 3's IO loop, if started)
    if loop is not None and loop.is_running():

        async def others_done() -> None:
            me = asyncio.current_task()
            pending = [t for t in asyncio.all_tasks() if t is not me]
            if pending:
                await asyncio.wait(pending, timeout=timeout)

        with contextlib.suppress(Exception):
            asyncio.run_coroutine_threadsafe(others_done(), loop).result(timeout + 1.0)
    for _ in range(3):  # (and again if a write no loop task awaited was still finishing)
        shutil.rmtree(path, ignore_errors=True)
        if not path.exists():
            return
        time.sleep(0.05)


def _build(path: Path, spec: SweepSpec, template: "xr.Dataset", layout_vars: dict[str, Any],
           attrs: dict[str, Any], coords: tuple[str, ...]) -> None:
    import xarray as xr

    n = spec.n_runs
    first = template.isel(run=slice(0, 1))
    for name, (dim, values, vattrs) in layout_vars.items():
        var = xr.Variable(dim, np.asarray(values)[:1], vattrs)
        first = first.assign_coords({name: var}) if name in coords else first.assign({name: var})
    first.attrs = {**attrs, "sweep_scenario_sha256": scenario_digest(spec.text),
                   "sweep_fingerprint": spec.fingerprint, "sweep_chunk_size": spec.chunk_size,
                   "sweep_n_runs": n, "sweep_n_chunks": spec.n_chunks,
                   "sweep_series": int(spec.series)}
    encoding = {}
    for name, var in first.variables.items():
        if "run" in var.dims:
            encoding[name] = {"chunks": tuple(spec.chunk_size if d == "run" else first.sizes[d]
                                              for d in var.dims)}
    first.to_zarr(path, mode="w", encoding=encoding, consolidated=False, zarr_format=3)
    group = _zarr().open_group(path, mode="r+", zarr_format=3)
    for name, arr in group.arrays():
        dims = tuple(arr.metadata.dimension_names or ())
        if "run" in dims:
            shape = tuple(n if d == "run" else s for d, s in zip(dims, arr.shape))
            arr.resize(shape)
    full = xr.Dataset(coords={"run": np.arange(n)})
    for name, (dim, values, vattrs) in layout_vars.items():
        var = xr.Variable(dim, np.asarray(values), vattrs)
        full = full.assign_coords({name: var}) if name in coords else full.assign({name: var})
    group["run"][:] = np.arange(n)
    for name in layout_vars:
        group[name][:] = np.asarray(full[name].values)
    (path / MARKERS).mkdir(exist_ok=True)
    atomic_write(path / MARKERS / "init", lambda tmp: Path(tmp).write_text(spec.fingerprint))


def _marker(path: Path, index: int) -> Path:
    return path / MARKERS / f"{index:06d}"


def completed_chunks(path: str | Path, spec: SweepSpec) -> set[int]:
    """Indices of the chunks whose region is written (a marker exists).

    Parameters
    ----------
    path : str or Path
        The store directory.
    spec : SweepSpec
        The sweep (a store of another sweep has no completed chunk).

    Returns
    -------
    set of int
    """
    path = Path(path)
    if not _initialised(path, spec):
        return set()
    marked = {i for i in range(spec.n_chunks) if _marker(path, i).is_file()}
    damaged = damaged_chunks(path, sorted(marked))
    if damaged:  # computed again by the resume (the same bytes), with a word to the user
        warnings.warn(f"{path}: {len(damaged)} chunk(s) damaged since they were written, "
                      "computed again: " + "; ".join(f"chunk {i} ({why})"
                                                      for i, why in sorted(damaged.items())),
                      stacklevel=2)
        for i in damaged:
            _marker(path, i).unlink(missing_ok=True)
    return marked - set(damaged)


def write_chunk(path: str | Path, spec: SweepSpec, index: int, ds: "xr.Dataset") -> None:
    """Write chunk ``index``'s results into its region, then its completion marker.

    Writing a chunk again writes the same bytes (the region is whole Zarr chunks and a chunk's
    results do not depend on where or when it ran).

    Parameters
    ----------
    path : str or Path
        The store directory (created by :func:`create_store`).
    spec : SweepSpec
        The sweep.
    index : int
        Chunk index.
    ds : xarray.Dataset
        The chunk's results (:func:`.chunks.compute_chunk`).
    """
    from .chunks import chunk_bounds

    path = Path(path)
    start, stop = chunk_bounds(spec, index)
    if ds.sizes.get("run") != stop - start or int(ds["run"][0]) != start:
        raise ParameterError(f"chunk {index}: the results are for runs "
                             f"{int(ds['run'][0])}..., not {start}:{stop}")
    shared = [v for v in ds.variables if "run" not in ds[v].dims]  # (time: written once)
    region = ds.drop_vars(shared)
    with _quiet():
        region.to_zarr(path, region={"run": slice(start, stop)}, mode="r+",
                       consolidated=False, zarr_format=3)
    # the marker holds each variable's checksum: a chunk lost or damaged later is found
    marker = json.dumps({"runs": [start, stop], "sha256": chunk_digests(region)},
                        sort_keys=True)
    atomic_write(_marker(path, index), lambda tmp: Path(tmp).write_text(marker))


def _digest(values: Any) -> str:
    arr = np.asarray(values)
    h = hashlib.sha256(f"{arr.shape}".encode())
    if arr.dtype.kind in "OUS":  # text: by value (its storage differs between writers)
        h.update("\0".join(map(str, arr.ravel())).encode())
    else:
        h.update(arr.dtype.str.lstrip("<>=|").encode())
        h.update(np.ascontiguousarray(arr, dtype=arr.dtype.newbyteorder("<")).tobytes())
    return h.hexdigest()


def chunk_digests(ds: "xr.Dataset") -> dict[str, str]:
    """SHA-256 of each variable of a chunk's results (its values as read back).

    Parameters
    ----------
    ds : xarray.Dataset
        A chunk's region (variables over ``run``).

    Returns
    -------
    dict
        Variable name -> hexadecimal digest.
    """
    return {str(name): _digest(ds[name].values) for name in ds.data_vars}


def damaged_chunks(path: str | Path, indices: Any = None) -> dict[int, str]:
    """The written chunks whose data no longer match the checksums of their markers.

    A chunk file deleted (its values read as the array's fill value) or altered (a different
    value, or a compressed chunk that no longer decompresses) is found by reading the chunk's
    region back and comparing each variable with its marker's SHA-256. Markers of stores
    written before markers held checksums are taken as they are.

    Parameters
    ----------
    path : str or Path
        The store directory.
    indices : iterable of int, optional
        The chunks to check (default: every chunk with a marker).

    Returns
    -------
    dict
        Chunk index -> what is wrong (``"runs 64:128: variable `status` does not match its
        checksum"``); empty when all is well.
    """
    import xarray as xr

    path = Path(path)
    attrs = store_attrs(path) or {}
    n_chunks = int(attrs.get("sweep_n_chunks", 0))
    if indices is None:
        indices = [i for i in range(n_chunks) if _marker(path, i).is_file()]
    bad: dict[int, str] = {}
    with _quiet():
        ds = xr.open_zarr(path, consolidated=False, zarr_format=3, chunks=None)
        for index in indices:
            try:
                record = json.loads(_marker(path, index).read_text() or "{}")
            except (OSError, ValueError):
                bad[index] = "its completion marker cannot be read"
                continue
            digests = record.get("sha256")
            if not digests:
                continue  # (a marker of an older seahelm: nothing to compare)
            start, stop = record["runs"]
            where = f"runs {start}:{stop}"
            region = ds.isel(run=slice(start, stop))
            for name, digest in sorted(digests.items()):
                if name not in region:
                    bad[index] = f"{where}: variable `{name}` is missing"
                    break
                try:
                    values = region[name].values
                except Exception as exc:  # noqa: BLE001 - a codec's error on damaged bytes
                    bad[index] = (f"{where}: variable `{name}` cannot be read "
                                  f"({type(exc).__name__}: {' '.join(str(exc).split())[:120]})")
                    break
                if _digest(values) != digest:
                    bad[index] = f"{where}: variable `{name}` does not match its checksum"
                    break
    return bad


def mark_complete(path: str | Path, summary: dict[str, Any]) -> None:
    """Store the summary statistics in the root attributes (``sweep_summary``, JSON).

    Parameters
    ----------
    path : str or Path
        The store directory.
    summary : dict
        :func:`~seahelm.sweep.run.summary_statistics` of the store.
    """
    with _quiet():
        group = _zarr().open_group(Path(path), mode="r+", zarr_format=3)
    group.attrs.update({"sweep_summary": json.dumps(summary, sort_keys=True)})


class CorruptStoreError(ParameterError):
    """A sweep store's chunks do not match the checksums written with them (``field`` is
    ``"store"``; the message names the store, the chunks and the runs)."""

    def _render(self) -> str:
        return self.reason


def open_sweep(path: str | Path, *, flat: bool = False, verify: bool = True
               ) -> "xr.Dataset":
    """Open a sweep store (lazily) as a Dataset.

    Parameters
    ----------
    path : str or Path
        The store directory.
    flat : bool, optional
        Keep the flat ``run`` dimension with the batch coordinates over it (default False:
        the batch's own dimensions, e.g. ``(kp, kd, time)`` or ``(sample, time)``, when every
        chunk is written).
    verify : bool, optional
        Check every written chunk against its checksums first (default True; it reads the
        store once).

    Returns
    -------
    xarray.Dataset
        With ``complete`` (bool over ``run``: the run's chunk is written) when chunks are
        missing; ``attrs["sweep_summary"]`` (JSON) when the sweep is complete.

    Raises
    ------
    ParameterError
        If ``path`` holds no sweep store.
    CorruptStoreError
        If a written chunk no longer matches its checksums (a chunk file lost or altered).
    """
    import xarray as xr

    path = Path(path)
    attrs = store_attrs(path)
    if attrs is None:
        raise ParameterError(f"{path}: not a sweep store (no zarr.json with sweep attributes)")
    damaged = damaged_chunks(path) if verify else {}
    if damaged:
        raise CorruptStoreError(
            f"{path}: {len(damaged)} chunk(s) damaged since they were written: "
            + "; ".join(f"chunk {i}, {why}" for i, why in sorted(damaged.items()))
            + " (`seahelm sweep` on the same scenario and store computes them again)",
            field="store")
    with _quiet():
        ds = xr.open_zarr(path, consolidated=False, zarr_format=3, chunks=None)
    size = int(attrs["sweep_chunk_size"])
    n_chunks = int(attrs["sweep_n_chunks"])
    done = np.array([_marker(path, i).is_file() for i in range(n_chunks)])
    if not done.all():
        ds["complete"] = ("run", np.repeat(done, size)[:ds.sizes["run"]])
        return ds
    dims = json.loads(attrs.get("sweep_dims", "[]"))
    if flat or not dims or [d for d, _ in dims] == ["run"]:
        return ds
    names = [d for d, _ in dims]
    if len(names) == 1:
        shaped = ds.swap_dims(run=names[0]).drop_vars("run")
    else:
        shaped = ds.set_index(run=names).unstack("run")
    return shaped.transpose(*names, ...)
