"""Where a sweep's chunks run: in this process (the default) or on a dask.distributed cluster.

An executor computes chunks (:func:`.chunks.compute_chunk`) and hands each chunk's results to
a callback in the coordinating process, which writes them to the store: the store is written
by one process only, so workers on other machines need no access to it. Dask is the scheduler
(a local cluster started here, or an existing one); a worker that dies has its chunks computed
again elsewhere, and a chunk's results arrive once per chunk whatever happened.
"""

from __future__ import annotations

import logging
import math
import os
import threading
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from .._dask import local_cluster
from .._optional import optional_import
from .._validate import check_positive
from ..errors import ParameterError
from .chunks import SweepSpec, compute_chunk

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["InProcess", "DaskCluster", "executor"]

OnDone = Callable[[int, "xr.Dataset"], None]


class InProcess:
    """Chunks one after the other in this process, each on the compiled parallel engine (all
    cores).

    With ``overlap`` (:func:`seahelm.sweep.run.run_sweep` sets it where two chunks' results
    fit in memory), chunk k's results are handed to ``on_done`` (the store's write: Zarr
    encoding and compression) on one writer thread while chunk k + 1 is computed, so the
    write takes the core the single-threaded parts of a chunk (approaches, metrics) leave
    idle. The chunks are written in order, one at a time, the same bytes; an exception of
    ``on_done`` is raised before the next chunk is handed on.
    """

    workers = 1
    overlap = False

    def __enter__(self) -> "InProcess":
        return self

    def __exit__(self, *exc: Any) -> None:
        return None

    def run(self, spec: SweepSpec, chunks: Iterable[int], on_done: OnDone) -> None:
        """Compute the chunks and hand each one's results to ``on_done`` in this process.

        Parameters
        ----------
        spec : SweepSpec
            The sweep.
        chunks : iterable of int
            Chunk indices to compute.
        on_done : callable(int, xarray.Dataset)
            Called with each chunk's index and results, once per chunk, as they complete.
        """
        todo = list(chunks)
        if not self.overlap or len(todo) < 2:
            for index in todo:
                on_done(index, compute_chunk(spec, index))
            return
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(1, thread_name_prefix="seahelm-sweep-write") as writer:
            pending = None
            for index in todo:
                ds = compute_chunk(spec, index)
                if pending is not None:
                    pending.result()  # (the previous write's exception, if any, here)
                pending = writer.submit(on_done, index, ds)
                del ds
            pending.result()


class DaskCluster:
    """Chunks as tasks of a dask.distributed cluster.

    Parameters
    ----------
    workers : int, optional
        Start a local cluster of this many worker processes (one thread each, loopback only,
        no dashboard), closed at the end.
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:port``) to use instead.
    timeout : float, optional
        Seconds to wait for the scheduler (default 10).
    client : distributed.Client, optional
        A connected client to use instead (left open at the end).
    """

    def __init__(self, *, workers: int | None = None, scheduler: str | None = None,
                 timeout: float = 10.0, client: Any = None) -> None:
        if sum(x is not None for x in (workers, scheduler, client)) != 1:
            raise ParameterError("give `workers` (a local cluster), `scheduler` (an existing "
                                 "one) or `client`, one of them")
        check_positive("timeout", timeout, "s")
        self.n_workers = workers
        self.scheduler = scheduler
        self.timeout = float(timeout)
        self.client: Any = client
        self.cluster: Any = None
        self.own_client = client is None
        self.quiet = _QuietDistributed()

    @property
    def workers(self) -> int:
        if self.client is None:
            return self.n_workers or 1
        return max(1, len(self.client.scheduler_info().get("workers", {})))

    def __enter__(self) -> "DaskCluster":
        distributed = optional_import("distributed", extra="dask",
                                      purpose="sweeps on a dask cluster (--workers/--scheduler)")
        if not self.own_client:
            return self
        if self.scheduler is not None:
            self.client = _connect(distributed, self.scheduler, self.timeout)
        else:
            import signal

            # The workers are started with Ctrl-C ignored (they inherit it): a Ctrl-C at the
            # terminal reaches the whole process group, and workers that took it each logged
            # a traceback (45 lines before the command's one); this process stops them.
            main_thread = threading.current_thread() is threading.main_thread()
            old = signal.signal(signal.SIGINT, signal.SIG_IGN) if main_thread else None
            try:
                # the workers' own logs at ERROR: a worker's warnings (a task cancelled by a
                # Ctrl-C, its shutdown) reached the command's stderr beside its one line
                self.cluster = local_cluster(self.n_workers, purpose="sweeps on a dask "
                                             "cluster (--workers)")
            finally:
                if main_thread:
                    signal.signal(signal.SIGINT, old)
            self.client = distributed.Client(self.cluster, set_as_default=False)
        return self

    def __exit__(self, *exc: Any) -> None:
        stopped = bool(exc) and isinstance(exc[1], (KeyboardInterrupt, SystemExit))
        if stopped:  # (the scheduler's "lost tasks" as the workers stop)
            self.quiet.start()
        if self.client is not None and self.own_client:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()
        if not stopped:  # (on a stop they stay silent: dask's threads log as the process ends)
            self.quiet.stop()

    def run(self, spec: SweepSpec, chunks: Iterable[int], on_done: OnDone) -> None:
        """Compute the chunks and hand each one's results to ``on_done`` in this process.

        Parameters
        ----------
        spec : SweepSpec
            The sweep.
        chunks : iterable of int
            Chunk indices to compute.
        on_done : callable(int, xarray.Dataset)
            Called with each chunk's index and results, once per chunk, as they complete.
        """
        distributed = optional_import("distributed", extra="dask")
        tag = spec.fingerprint[:12]
        futures = {}
        for index in chunks:
            fut = self.client.submit(compute_chunk, spec, index, key=f"seahelm-{tag}-{index}",
                                     pure=False, retries=0)
            futures[fut.key] = (index, fut)
        try:
            for fut, ds in distributed.as_completed([f for _, f in futures.values()],
                                                    loop=self.client.loop, with_results=True):
                index, _ = futures.pop(fut.key)
                on_done(index, ds)
                fut.release()
        except (KeyboardInterrupt, SystemExit):
            self.quiet.start()  # until the cluster is closed (__exit__)
            if self.cluster is None:  # (a cluster of our own stops with its work)
                self.client.cancel([f for _, f in futures.values()])
            futures.clear()
            raise
        finally:
            if futures:
                self.client.cancel([f for _, f in futures.values()])


class _QuietDistributed:
    """dask's loggers silenced from :meth:`start` to :meth:`stop`: on a stop (Ctrl-C, SIGTERM)
    the cluster's warnings about lost or cancelled work, and tornado's about a callback the
    interrupt broke, are not the user's concern -- the store resumes."""

    NAMES = ("distributed", "tornado", "asyncio")

    def __init__(self) -> None:
        self.saved: list[tuple[logging.Logger, int]] | None = None

    def start(self) -> None:
        if self.saved is None:
            # the children too: distributed's logging config sets levels of its own on some
            # (``tornado.application``: ERROR), which a parent's level does not override
            names = set(self.NAMES) | {
                name for name in list(logging.root.manager.loggerDict)
                if any(name.startswith(root + ".") for root in self.NAMES)}
            self.saved = [(lg, lg.level) for lg in map(logging.getLogger, sorted(names))]
            for lg, _ in self.saved:
                lg.setLevel(logging.CRITICAL + 1)

    def stop(self) -> None:
        for lg, level in self.saved or ():
            lg.setLevel(level)
        self.saved = None


def _connect(distributed: Any, address: str, timeout: float) -> Any:
    """A client of the dask scheduler at ``address``, or a ParameterError within about
    ``timeout`` seconds.

    dask's own timeout covers the connection, not a peer that accepts it and then says
    nothing a scheduler would (an HTTP server: dask waits for its handshake for ever) or
    something else (its first bytes read as a length of exabytes: MemoryError). The client is
    therefore made in a helper thread that is given ``timeout`` and a little more; a peer that
    has not answered by then, or answered wrongly, is named as not a dask scheduler (the thread,
    stuck on the peer, is left to end with the process).
    """
    import threading

    hint = "start one with `dask scheduler` and give its address (tcp://HOST:PORT)"
    outcome: dict[str, Any] = {}

    def connect() -> None:
        try:
            outcome["client"] = distributed.Client(address, timeout=timeout,
                                                   set_as_default=False)
        except BaseException as exc:  # noqa: BLE001 - handed to the caller below
            outcome["error"] = exc

    # a daemon thread: one stuck on a silent peer does not keep the process from exiting
    thread = threading.Thread(target=connect, name="seahelm-dask-connect", daemon=True)
    thread.start()
    thread.join(timeout + 2.0)
    if thread.is_alive():
        raise ParameterError(
            f"`scheduler`: {address} accepted the connection but did not answer as a dask "
            f"scheduler within {timeout:g} s: it is not a dask scheduler (or is stuck); "
            f"{hint}")
    exc = outcome.get("error")
    if exc is None:
        return outcome["client"]
    if isinstance(exc, (OSError, TimeoutError)):
        raise ParameterError(
            f"`scheduler`: cannot reach the dask scheduler at {address} within {timeout:g} s "
            f"({type(exc).__name__}: {exc}); {hint}") from None
    if isinstance(exc, (ValueError, MemoryError, EOFError, TypeError, KeyError)):
        raise ParameterError(
            f"`scheduler`: {address} is not a dask scheduler: its answer is not dask's "
            f"protocol ({type(exc).__name__}); {hint}") from None
    raise exc


def executor(*, workers: int | None = None, scheduler: str | None = None,
             timeout: float = 10.0, client: Any = None) -> InProcess | DaskCluster:
    """The executor for the options: in-process (none), a local cluster (``workers``), an
    existing one (``scheduler``) or a connected dask ``client``.

    Parameters
    ----------
    workers : int, optional
        Worker processes of a local dask cluster.
    scheduler : str, optional
        Address of a running dask scheduler (``tcp://HOST:PORT``).
    timeout : float, optional
        Seconds to wait for ``scheduler`` (default 10).
    client : distributed.Client, optional
        A connected dask client.

    Returns
    -------
    InProcess or DaskCluster
        A context manager; :meth:`run` inside it computes chunks.

    Raises
    ------
    ParameterError
        For more than one of the options, or a bad value.
    """
    if client is not None:
        if workers is not None or scheduler is not None:
            raise ParameterError("give `client` alone (not with `workers` or `scheduler`)")
        return DaskCluster(client=client)
    if workers is not None:
        if isinstance(workers, bool) or int(workers) != workers or workers < 1:
            raise ParameterError(f"`workers` must be a whole number >= 1, got {workers!r}")
        cores = os.cpu_count() or 1
        if workers > cores:  # (each worker is a process running the engine on its threads)
            raise ParameterError(
                f"`workers` = {workers} is more than this machine's {cores} core(s): a local "
                "cluster of more processes than cores only adds their memory and start-up; "
                f"give at most {cores}, or `scheduler` for a larger cluster",
                field="workers", value=workers)
        if scheduler is not None:
            raise ParameterError("give `workers` (a local cluster) or `scheduler` (an existing "
                                 "one), not both")
    if scheduler is not None:
        if not isinstance(scheduler, str) or "://" not in scheduler:
            raise ParameterError(f"`scheduler` must be an address such as "
                                 f"tcp://HOST:PORT, got {scheduler!r}")
        if not (isinstance(timeout, (int, float)) and math.isfinite(timeout) and timeout > 0):
            raise ParameterError(f"`timeout` must be > 0 [s], got {timeout!r}")
    if workers is None and scheduler is None:
        return InProcess()
    return DaskCluster(workers=workers, scheduler=scheduler, timeout=timeout)
