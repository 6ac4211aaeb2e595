"""Generated modules: where they live, what they are named after, how they are imported.

The engine writes one module per combination of components (the closed-loop kernel,
:func:`seahelm.simulation.engine.compile_closed_loop`), and so do the guided controllers
(:mod:`seahelm.control.guided`) and the environment's stage
(:mod:`seahelm.simulation.environment_stage`). Each is written to the kernel cache directory,
named after a hash of its text and of the code it calls (:func:`code_fingerprint`), and
imported from there, so numba's ``cache=True`` compiles it once per machine.

A basic under every layer (it imports no seahelm module), so a component that generates code
(the guided controllers) needs no simulation import; :mod:`seahelm.simulation.generated`
re-exports it for the engine.
"""
from __future__ import annotations

import hashlib
import importlib.util
import linecache
import os
import sys
import tempfile
import types
import warnings
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

__all__ = ["kernel_cache_dir", "code_fingerprint", "code_identity", "content_digest",
           "import_generated", "exec_generated", "watch_compiles", "called_not_inlined",
           "is_called_not_inlined"]


def kernel_cache_dir() -> Path:
    """Directory for generated closed-loop kernels (``SEAHELM_CACHE_DIR`` overrides)."""
    env = os.environ.get("SEAHELM_CACHE_DIR")
    if env:
        base = Path(env)
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = (Path(xdg) if xdg else Path.home() / ".cache") / "seahelm" / "kernels"
    try:
        base.mkdir(parents=True, exist_ok=True)
        probe = base / f".probe-{os.getpid()}"
        probe.write_text("")
        probe.unlink()
        return base
    except OSError as exc:
        fallback = Path(tempfile.gettempdir()) / f"seahelm-kernels-{os.getuid()}"
        warnings.warn(f"kernel cache {base} is not a writable directory ({exc.strerror or exc}); "
                      f"using {fallback}", stacklevel=2)
        fallback.mkdir(parents=True, exist_ok=True)
        return fallback


def _constant_identity(value: Any) -> str:
    """A constant of a code object as text that depends on its value alone (a frozenset's
    members sorted: their order follows string hashing, which differs between processes)."""
    if isinstance(value, frozenset):
        return "frozenset{" + ",".join(sorted(_constant_identity(v) for v in value)) + "}"
    if isinstance(value, tuple):
        return "(" + ",".join(_constant_identity(v) for v in value) + ")"
    return f"{type(value).__name__}:{value!r}"


def code_identity(code: types.CodeType) -> bytes:
    """Bytes that identify what ``code`` does, the same in every process.

    Its bytecode, exception table, names, argument counts, flags and constants (code objects
    among them recursively), but not its file or line numbers, which do not change what the
    compiled code does. Not :func:`marshal.dumps`: marshal flags an object it has seen before
    only when its reference count is above one, so the same function marshals to other bytes
    once numba's compiler has held references to its constants. The kernels named after it
    got another name in the process after the one that compiled them, and every
    ``seahelm imo kvlcc2-full`` compiled its crash-stop kernel again (four minutes).

    Parameters
    ----------
    code : types.CodeType

    Returns
    -------
    bytes
    """
    consts = ",".join(code_identity(c).hex() if isinstance(c, types.CodeType)
                      else _constant_identity(c) for c in code.co_consts)
    header = (code.co_name, code.co_argcount, code.co_posonlyargcount, code.co_kwonlyargcount,
              code.co_flags, code.co_names, code.co_varnames, code.co_freevars,
              code.co_cellvars)
    return b"\0".join([repr(header).encode(), code.co_code,
                       getattr(code, "co_exceptiontable", b""), consts.encode()])


def code_fingerprint(py: Any, seen: set[int] | None = None) -> bytes:
    """Bytes that change whenever the compiled behaviour of ``py`` could change.

    The bytecode of the function as it is *in memory* (not its file on disk, which may have
    been edited since it was imported), and recursively of every numba function it calls and
    the numeric globals that numba freezes into the code. Naming a kernel after this keeps the
    on-disk numba cache from serving a loop compiled from other code.

    Parameters
    ----------
    py : function
        A plain Python function (a numba dispatcher's ``py_func``).
    seen : set of int, optional
        Ids of functions already included (recursion guard).

    Returns
    -------
    bytes
    """
    seen = set() if seen is None else seen
    if id(py) in seen:
        return b""
    seen.add(id(py))
    parts = [code_identity(py.__code__)]
    stack = [py.__code__]
    names: list[str] = []
    while stack:
        code = stack.pop()
        names.extend(code.co_names)
        stack.extend(c for c in code.co_consts if isinstance(c, types.CodeType))
    for name in sorted(set(names)):
        obj = py.__globals__.get(name)
        inner = getattr(obj, "py_func", None)
        if inner is not None:
            parts.append(name.encode() + code_fingerprint(inner, seen))
        elif isinstance(obj, (bool, int, float, complex, str)):
            parts.append(f"{name}={obj!r}".encode())
        elif isinstance(obj, np.ndarray):
            parts.append(f"{name}:{obj.dtype.str}{obj.shape!r}".encode() + obj.tobytes())
        elif isinstance(obj, tuple) and all(
                isinstance(v, (bool, int, float, str)) for v in obj):  # signal_indices
            parts.append(f"{name}={obj!r}{getattr(type(obj), '_fields', ())!r}".encode())
    return b"\0".join(parts)


def content_digest(*parts: bytes | str) -> str:
    """The 16 hex digits that name generated code (or key a cache of it) by what it is made
    of: the SHA-1 of the parts joined by NUL bytes, a ``str`` part UTF-8 encoded.

    The parts are what the code's behaviour depends on: its source text and the
    :func:`code_fingerprint` of each function it imports, the package version, the numbers of
    a design. A generated module named ``prefix_<digest>`` is therefore a new module, compiled
    afresh, whenever any of them changes, and the same module (numba's on-disk cache serving
    it) otherwise.

    Parameters
    ----------
    *parts : bytes or str

    Returns
    -------
    str
        16 lower-case hexadecimal digits.
    """
    return hashlib.sha1(b"\0".join(p.encode() if isinstance(p, str) else p
                                    for p in parts)).hexdigest()[:16]


def import_generated(name: str, text: str) -> ModuleType:
    """Import generated source as module ``name`` from the kernel cache directory.

    The file is written atomically (only if missing or different), so numba's on-disk cache
    of its ``cache=True`` functions lives beside it; a module already imported is returned.

    Parameters
    ----------
    name : str
        Module name, unique for the text (e.g. ``seahelm_kernel_<hash>``).
    text : str
        Its Python source.

    Returns
    -------
    module
    """
    if name in sys.modules:
        return sys.modules[name]
    path = kernel_cache_dir() / f"{name}.py"
    if not path.exists() or path.read_text() != text:
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def exec_generated(name: str, text: str) -> ModuleType:
    """Run generated source as a module ``name`` in memory (nothing is written to disk).

    For the pure-Python closed loop: the module is registered in ``sys.modules`` (so generated
    code imports from it by name, and a module already there is returned) but leaves no file in
    :func:`kernel_cache_dir` (numba's cache therefore has nowhere to go either). Its
    text is registered with :mod:`linecache` under the file name ``<name>``, so a debugger
    steps through it and a traceback shows its lines.

    Parameters
    ----------
    name : str
        Module name (e.g. ``seahelm_python_loop_<hash>``).
    text : str
        Its Python source.

    Returns
    -------
    module
    """
    if name in sys.modules:
        return sys.modules[name]
    filename = f"<{name}>"
    # (no modification time: linecache.checkcache leaves the entry alone)
    linecache.cache[filename] = (len(text), None, text.splitlines(keepends=True), filename)
    module = ModuleType(name)
    module.__file__ = filename
    sys.modules[name] = module
    exec(compile(text, filename, "exec"), module.__dict__)
    return module


def watch_compiles(on_first: Any = None,
                   log: str | os.PathLike[str] | None = None) -> Any:
    """Listen to numba's compilations in this process (not its loads from the on-disk cache).

    Parameters
    ----------
    on_first : callable, optional
        Called once, with no arguments, when the first compilation starts (the command line
        shows a "compiling … (first use)" status with it).
    log : path, optional
        A file that gets one line per compiled function (``module.name (argument types)``)
        when its compilation ends; ``SEAHELM_COMPILE_LOG`` names it when not given (``""``:
        none, whatever the environment says). A repeated command must leave it empty: the test
        of the kernel cache reads it. A log that cannot be appended to (a directory, a missing
        folder) is said once in a ``UserWarning`` and the command goes on.

    Returns
    -------
    callable
        Stops listening (nothing to stop when neither is set).
    """
    from numba.core import event

    source = "log" if log is not None else "SEAHELM_COMPILE_LOG"
    log = os.environ.get("SEAHELM_COMPILE_LOG") or None if log is None else (log or None)
    if on_first is None and log is None:
        return lambda: None

    class _Listener(event.Listener):  # type: ignore[misc]
        started = False

        def on_start(self, ev: Any) -> None:
            if not self.started and on_first is not None:
                self.started = True
                on_first()

        failed = False

        def on_end(self, ev: Any) -> None:
            if log is None or self.failed:
                return
            data = ev.data or {}
            py = getattr(data.get("dispatcher"), "py_func", None)
            name = f"{getattr(py, '__module__', '?')}.{getattr(py, '__qualname__', '?')}"
            try:
                with open(log, "a", encoding="utf-8") as fh:
                    fh.write(f"{name} {data.get('args', '')}\n")
            except OSError as exc:  # (a log must not stop the command: said once)
                import warnings

                self.failed = True
                warnings.warn(f"{source} = {os.fspath(log)!r} cannot be appended to "
                              f"({exc.strerror or exc}); compilations are not logged",
                              UserWarning, stacklevel=2)

    listener = _Listener()
    event.register("numba:compile", listener)

    registered = [True]

    def stop() -> None:  # once: a second unregister raises
        if registered.pop() if registered else False:
            event.unregister("numba:compile", listener)

    return stop


#: The numba functions :func:`seahelm.simulation.inlining.inline_always` leaves as calls (by
#: ``id``; each entry holds its dispatcher, so that no other object takes the ``id``).
_CALLED: dict[int, Any] = {}


def called_not_inlined(func: Any) -> Any:
    """Mark a numba function that :func:`seahelm.simulation.inlining.inline_always` keeps as
    a call where a component calls it (its own ``cache=True`` dispatcher, compiled once per
    machine and linked into each loop), instead of copying it into the loop.

    For a large function that runs rarely: the DP controllers' constrained allocation (an
    active-set QP, :func:`seahelm.control.dp_pid.allocate_step`) runs once per controller
    interval, and inlined into the loop it was half of every DP kernel's compile for no
    speed (a call per QP solve): the supply vessel's dp-pid loop with the sensor stage
    compiled in 21.6 s with it inlined, 11.8 s with it called (its own compile, 4.9 s, once
    per machine; measured 2026-12-03, 2 cores). The loop's copy is compiled with the loop's
    flags, so the numbers are the same bit for bit
    (:func:`seahelm.simulation.inlining._called_copy`). What the components call at every stage of the step stays
    inlined (the reason for ``inline_always``).

    Parameters
    ----------
    func : numba dispatcher

    Returns
    -------
    numba dispatcher
        ``func`` itself (usable as a decorator above ``@njit``).
    """
    if not hasattr(func, "py_func"):
        return func  # (numba's JIT disabled: a plain function, nothing is inlined)
    _CALLED[id(func)] = func
    return func


def is_called_not_inlined(func: Any) -> bool:
    """Whether :func:`called_not_inlined` marked ``func``.

    Parameters
    ----------
    func : object
        A numba dispatcher (anything else is not marked).

    Returns
    -------
    bool
    """
    return id(func) in _CALLED and _CALLED[id(func)] is func
