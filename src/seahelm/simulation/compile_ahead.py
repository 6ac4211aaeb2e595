"""Compile a kernel in a second process while this one works on.

A command that needs several kernels (the IMO check: the turning circle's, the zig-zags'
and the crash stop's) compiles them one after another on its first use on a machine, on
one core: numba holds one compiler lock per process. :class:`CompileAhead` runs a call that
needs another kernel (the crash stop) in a second process, which compiles that kernel into
the on-disk cache while this process compiles its own; this process then loads it. It
starts only when this process compiles something (a cold cache) and there is a second core:
a warm run starts nothing.

The second process's results are thrown away; it only fills the cache, so the numbers are
this process's own (the cache serves the same machine code whoever compiled it).
``SEAHELM_COMPILE_AHEAD=0`` turns it off.
"""
from __future__ import annotations

import multiprocessing
import os
from collections.abc import Callable
from typing import Any

__all__ = ["CompileAhead"]


def _available_cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _call(fn: Callable[..., Any], args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    import signal
    import warnings

    # Ctrl-C reaches the whole process group: the first process ends this one (terminate,
    # SIGTERM's default action) instead of a traceback from here
    signal.signal(signal.SIGINT, signal.SIG_IGN)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # this process's own call warns where it matters
        fn(*args, **kwargs)


class CompileAhead:
    """Run ``fn(*args, **kwargs)`` in a second process once this one starts compiling.

    Use as a context manager around the work of this process that comes first; call
    :meth:`wait` before the call that needs the kernel ``fn`` compiles (leaving the block
    without :meth:`wait`, by an exception, ends the second process).

    Parameters
    ----------
    fn : callable
        A module-level function (it is pickled to the second process), with picklable
        arguments.

    Attributes
    ----------
    started : bool
        Whether a second process was started (this process compiled something).
    """

    def __init__(self, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> None:
        self._call = (fn, args, kwargs)
        self._process: Any = None
        self.started = False
        self._stop_watching: Callable[[], None] = lambda: None

    def _start(self) -> None:
        if self._process is not None:
            return
        try:
            context = multiprocessing.get_context("spawn")
            process = context.Process(target=_call, args=self._call, daemon=True,
                                      name="seahelm-compile-ahead")
            process.start()
        except Exception:  # noqa: BLE001 - an optimisation: this process compiles it itself
            return
        self._process = process
        self.started = True

    def __enter__(self) -> CompileAhead:
        if os.environ.get("SEAHELM_COMPILE_AHEAD", "1") != "0" and _available_cores() > 1:
            from .._codegen import watch_compiles

            # (log="": the command's own listener logs the compilations, once)
            self._stop_watching = watch_compiles(on_first=self._start, log="")
        return self

    def wait(self, timeout: float = 900.0) -> None:
        """Wait for the second process (if it started) to finish filling the cache.

        Parameters
        ----------
        timeout : float, optional
            Seconds to wait at most [s] (default 900); a second process still running then is
            ended, and this process compiles the kernel itself.
        """
        self._stop_watching()
        if self._process is not None:
            self._process.join(timeout)
            if self._process.is_alive():  # pragma: no cover - a hung compile
                self._process.terminate()
            self._process = None

    def __exit__(self, *exc: Any) -> None:
        self._stop_watching()
        if self._process is not None:
            self._process.terminate()
            self._process.join(5.0)
            self._process = None
