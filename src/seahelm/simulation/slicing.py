"""The batch cut into slices of runs and of steps, run by the compiled loop.

:class:`_Slices` holds the kernel's argument groups (:mod:`seahelm.simulation.kernel_args`)
and runs ``run_slice`` on slices of runs, on a thread pool; :func:`drive` advances the whole
batch between two steps in slices of about :data:`SLICE_SECONDS` of wall time, so a stop
signal or a progress bar gets Python between them.
"""

from __future__ import annotations

import contextlib
import time as _time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from types import ModuleType
from typing import Any

import numba
import numpy as np

from .. import stop_request
from .kernel_args import KernelArrays

__all__ = ["SLICE_SECONDS", "FIRST_SLICE", "FIRST_SLICE_PYTHON", "drive"]

#: Wall time a slice of steps of the compiled loop aims at [s]. Between slices Python runs:
#: a progress callback, and a signal handler (the CLI turns SIGTERM and Ctrl-C into
#: exceptions), so a stop request ends a long run within about this time. A slice costs some
#: 5 µs to start (100 µs on the thread pool): 0.25 s keeps that below 0.05 %.
SLICE_SECONDS = 0.25

#: Steps × runs of the first slice, before the loop's speed is known: 0.15 s of a KVLCC2 MMG
#: ship (:data:`seahelm.resources.TYPICAL_RATE`), one slice for a short run.
FIRST_SLICE = 200_000

#: The same for the pure-Python loop (``jit=False``: some 10³ steps/s).
FIRST_SLICE_PYTHON = 200


#: Scratch buffer sets kept for reuse per (kernel, scratch sizes)
#: (:meth:`_Slices.release`): as many as a batch has slices, four per thread.
SCRATCH_KEPT = 16
_SCRATCH: dict[tuple[Any, ...], list[tuple[tuple[np.ndarray, ...], list[np.ndarray]]]] = {}


def _blocks(views: tuple[np.ndarray, ...]) -> list[np.ndarray]:
    """The arrays whose views a scratch set is (one or two blocks)."""
    out: dict[int, np.ndarray] = {}
    for v in views:
        base = v if v.base is None else v.base
        out.setdefault(id(base), base)
    return list(out.values())


class _Slices:
    """The batch cut into slices of runs, run by the kernel's ``run_slice`` on a thread pool.

    The compiled loop releases the GIL, so threads run slices in parallel; there are up to four
    slices per thread (a slice of runs that stop early does not leave a thread idle) and never
    more threads than runs (a single run stays in the calling thread). ``numba.set_num_threads``
    and ``NUMBA_NUM_THREADS`` set the number of threads, as for any numba parallel code.

    Every slice has its own scratch buffers (the kernel allocates nothing), the stages' from
    ``stage_scratch()`` (a tuple of each stage's buffers). ``threads`` caps
    the threads (the pure-Python loop runs in the calling thread: ``threads=1``). With
    ``keep_pool`` the thread pool lives as long as this object (:meth:`close`): a stepped
    batch calls the loop once per controller interval, and a pool costs some 100 µs to start.
    """

    def __init__(self, kernel: ModuleType, arrays: KernelArrays,
                 scratch_sizes: tuple[int, ...], threads: int | None = None,
                 stage_scratch: Callable[[], tuple[Any, ...]] = tuple,
                 keep_pool: bool = False) -> None:
        self.kernel = kernel
        n_runs = arrays.n_runs
        # numba types a read-only array apart from a writable one: a kernel called with both
        # (a broadcast view of one run, say) would compile twice, each 15-80 s
        self.arrays = arrays.writable()
        # (one run: one thread, without asking numba, whose answer costs a few µs per call)
        self.threads = 1 if n_runs <= 1 else max(1, min(
            numba.get_num_threads() if threads is None else threads, n_runs))
        n_slices = 1 if self.threads == 1 else min(n_runs, 4 * self.threads)
        if n_slices == 1:
            self.bounds = [(0, n_runs)]
        else:
            cuts = np.linspace(0, n_runs, n_slices + 1).round().astype(np.int64).tolist()
            self.bounds = [(cuts[s], cuts[s + 1]) for s in range(n_slices)]
        # (the buffers of a finished batch of the same kernel and sizes, zeroed, or fresh:
        # making the two dozen views costs some 20 µs, a tenth of a short run; the stages'
        # buffers, sized by the problem, are made fresh)
        self._scratch_key = (kernel, tuple(scratch_sizes))
        free = _SCRATCH.get(self._scratch_key, [])
        self.scratch, self._blocks = [], []
        for _ in range(n_slices):
            try:
                sc, blocks = free.pop()
            except IndexError:
                sc = kernel.scratch(*scratch_sizes)
                blocks = _blocks(sc)
            else:
                for block in blocks:
                    block.fill(0)
            self.scratch.append(sc)
            self._blocks.append(blocks)
        self.stage_scratch = [stage_scratch() for _ in range(n_slices)]
        self._keep_pool = keep_pool
        # nothing observed (the kernel's ``out`` of the whole-horizon loop): empty, (0, outputs)
        self._no_out = np.zeros((0, arrays.record[1].shape[2]))
        self._pool: ThreadPoolExecutor | None = None

    def warm_up(self, n_steps: int, dt: float, ctrl_every: int, rec_every: int) -> None:
        """Compile or load the kernel for these argument types: a zero-step call (once
        compiled, a call costs about 4 µs of argument checks; asking whether these types were
        seen before, from the arrays' flags, cost five times that)."""
        self.run(0, 0, n_steps, dt, ctrl_every, rec_every)

    def init_runs(self, spans: list[tuple[int, int]] | None = None) -> None:
        """The controllers' init at t = 0, for every run, or for the runs of ``spans``
        (contiguous [i0, i1) ranges, in the calling thread: runs restarted)."""
        a = self.arrays
        if spans is None:
            todo = zip(self.bounds, self.scratch, self.stage_scratch)
        else:
            todo = ((span, self.scratch[0], self.stage_scratch[0]) for span in spans)
        for (i0, i1), sc, ssc in todo:
            self.kernel.init_runs(i0, i1, a.state, a.params, a.signals, a.outcome, a.record,
                                  a.stages, sc, ssc, self._no_out)

    def observe(self, k: int, dt: float, out: np.ndarray) -> None:
        """Every run's outputs at its state of step ``k`` into ``out`` (runs, outputs): the
        slices on the kept thread pool (``observe_runs`` releases the GIL as ``run_slice``
        does), else one after another in the calling thread."""
        a = self.arrays
        observe_runs = self.kernel.observe_runs

        def one(s: int) -> None:
            i0, i1 = self.bounds[s]
            observe_runs(i0, i1, k, dt, a.state, a.params, a.signals, a.stages,
                         self.scratch[s], self.stage_scratch[s], out)

        if self._keep_pool and self.threads > 1:
            self._shared(one)
            return
        for s in range(len(self.bounds)):
            one(s)

    def observe_spans(self, spans: list[tuple[int, int]], k: int, n_steps: int, dt: float,
                      ctrl_every: int, rec_every: int, out: np.ndarray) -> None:
        """The outputs of the runs of ``spans`` (contiguous [i0, i1) ranges) at their state of
        step ``k`` into their rows of ``out`` (runs, outputs): a zero-step call of the loop a
        span (the code of :meth:`run`'s observation), in the calling thread (a few runs
        restarted: one short call a span); the other rows are left as they are."""
        a = self.arrays
        sc, ssc = self.scratch[0], self.stage_scratch[0]
        for i0, i1 in spans:
            self.kernel.run_slice(i0, i1, k, k, n_steps, dt, ctrl_every, rec_every, 1,
                                  a.state, a.params, a.signals, a.outcome, a.record, a.stages,
                                  sc, ssc, out)

    def _shared(self, one: Callable[[int], None]) -> None:
        """``one(s)`` of every slice ``s``, shared by the calling thread and ``threads - 1``
        threads of the kept pool, each taking the next slice not yet taken (a stepped batch
        calls this once per interval: one task a thread to hand over, not one a slice, each
        costing some 10 µs; and the calling thread works instead of waiting). An exception of
        any slice is raised here once every thread has stopped."""
        if self._pool is None:
            self._pool = ThreadPoolExecutor(self.threads - 1, thread_name_prefix="seahelm")
        todo = iter(range(len(self.bounds)))  # (its next() is atomic under the GIL)

        def work() -> None:
            for s in todo:
                one(s)

        helpers = [self._pool.submit(work) for _ in range(self.threads - 1)]
        try:
            work()
        finally:
            for f in helpers:  # (the arrays are not handed back while a slice runs)
                f.exception()
        for f in helpers:
            f.result()  # (re-raises a helper's exception)

    def run(self, k_start: int, k_stop: int, n_steps: int, dt: float, ctrl_every: int,
            rec_every: int, external: int = 0, out: np.ndarray | None = None) -> None:
        """Advance every run from step ``k_start`` to ``k_stop`` (``external``: the commands
        held in the state group are applied, the controller is not stepped; ``out`` (runs,
        outputs): each run still going gets its outputs at ``k_stop`` there)."""
        a = self.arrays
        run_slice = self.kernel.run_slice
        out = self._no_out if out is None else out
        if self.threads == 1 and len(self.bounds) == 1:
            # (one slice in the calling thread, a single run's: the call, no closure around it)
            i0, i1 = self.bounds[0]
            run_slice(i0, i1, k_start, k_stop, n_steps, dt, ctrl_every, rec_every, external,
                      a.state, a.params, a.signals, a.outcome, a.record, a.stages,
                      self.scratch[0], self.stage_scratch[0], out)
            return

        def one(s: int) -> None:
            i0, i1 = self.bounds[s]
            run_slice(i0, i1, k_start, k_stop, n_steps, dt, ctrl_every, rec_every, external,
                      a.state, a.params, a.signals, a.outcome, a.record, a.stages,
                      self.scratch[s], self.stage_scratch[s], out)

        n_slices = len(self.bounds)
        # (a zero-step call: serial unless it observes on the kept pool -- warm_up's is not)
        if self.threads == 1 or (k_stop == k_start and not (self._keep_pool
                                                            and out.shape[0] > 0)):
            for s in range(n_slices):
                one(s)
            return
        if self._keep_pool:
            self._shared(one)
            return
        with ThreadPoolExecutor(self.threads, thread_name_prefix="seahelm") as pool:
            # list() re-raises an exception of any slice here
            list(pool.map(one, range(n_slices)))

    def release(self) -> None:
        """Hand this batch's scratch buffers to the next batch of the same kernel and sizes
        (the batch is not run again; at most :data:`SCRATCH_KEPT` sets are kept per key)."""
        free = _SCRATCH.setdefault(self._scratch_key, [])
        while self.scratch and len(free) < SCRATCH_KEPT:
            free.append((self.scratch.pop(), self._blocks.pop()))
        self.scratch, self._blocks = [], []

    def close(self) -> None:
        """End the kept thread pool (if any)."""
        if self._pool is not None:
            self._pool.shutdown(wait=False)
            self._pool = None


def drive(slices: _Slices, n_steps: int, dt: float, ctrl_every: int, record_every: int, *,
          jit: bool, progress: Callable[[int, int], None] | None = None,
          k_start: int = 0, k_stop: int | None = None, external: int = 0) -> float:
    """Advance the batch from step ``k_start`` to ``k_stop`` in slices of about
    :data:`SLICE_SECONDS` each.

    Between slices Python runs, so a stop signal (Ctrl-C, SIGTERM: the CLI raises it as an
    exception, and raises it again here if some C code swallowed it,
    :func:`seahelm.stop_request.check`) ends even a long compiled run within about that
    time, and a progress bar moves smoothly. The loop stops early once every run has stopped.

    Parameters
    ----------
    slices : _Slices
        The batch's kernel and arrays.
    n_steps : int
        Steps of the horizon.
    dt : float
        Integration step [s].
    ctrl_every, record_every : int
        Steps per controller interval and per record.
    jit : bool
        Whether the loop is compiled (the pure-Python loop starts with smaller slices).
    progress : callable(done_steps, total_steps), optional
        Called after every slice.
    k_start, k_stop : int
        The steps to go from and to (default: the whole horizon).
    external : int
        1: the commands held in the state group are applied, the controller is not stepped.

    Returns
    -------
    float
        The wall time [s].
    """
    k_stop = n_steps if k_stop is None else k_stop
    status = slices.arrays.outcome[0]
    n_runs = status.shape[0]
    wall0 = _time.perf_counter()
    k = k_start
    span = k_stop - k_start
    chunk = min(span, max(1, (FIRST_SLICE if jit else FIRST_SLICE_PYTHON) // max(n_runs, 1)))
    while k < k_stop:
        k_next = min(k_stop, k + chunk)
        t0 = _time.perf_counter()
        with quiet(jit):
            slices.run(k, k_next, n_steps, dt, ctrl_every, record_every, external)
        elapsed = _time.perf_counter() - t0
        done, k = k_next - k, k_next
        if progress is not None:
            progress(k, n_steps)
        stop_request.check()  # (a stop signal some C code swallowed: raised again here)
        chunk = int(min(max(done / max(elapsed, 1e-6) * SLICE_SECONDS, 1), n_steps))
        if status.all():
            break
    return _time.perf_counter() - wall0


def quiet(jit: bool) -> Any:
    """The pure-Python loop's numpy scalars warn where the compiled loop silently makes
    inf/NaN (then recorded as the run's divergence, as compiled): silenced."""
    return _NULL_CONTEXT if jit else np.errstate(all="ignore")


_NULL_CONTEXT = contextlib.nullcontext()  # (stateless, so one serves every call)
