"""Re-jit a component function so that it and every numba function it calls inline at IR level.

The closed-loop kernel (:mod:`seahelm.simulation.kernel_template`) binds each component
function re-jitted with ``inline="always"``, so numba inlines it into the loop. That alone stops
at the first level: a function the component calls (the catamaran's ``catamaran_drift``
inside ``catamaran_rhs``, the MMG model's hull, propeller and rudder forces) stays an ordinary
dispatcher, compiled apart and *called* at every stage of every step, and LLVM does not inline
it across numba's library boundary. Measured on the catamaran loop: the drift called four times
per RK4 step, not inlined, put the engine at 74–77 % of a hand-fused kernel.

:func:`inline_always` returns a dispatcher over a copy of the function whose globals see
``inline="always"`` copies of every numba function it names, recursively. The originals are
untouched (components keep their own ``cache=True`` dispatchers for direct use).

:func:`python_function` is its plain-Python twin, for the pure-Python closed loop
(``simulate(..., jit=False)``): a copy of the component's Python function whose globals see
Python twins of every numba function it names, so nothing is compiled and a breakpoint in the
component's source is hit. :func:`no_jit` and :func:`record_in_place` stand in for ``njit`` and
:func:`local_record` there.

:func:`local_record` is the other half of what the inlined loop needs to be fast: each run's
parameter record copied onto the stack, so that LLVM can keep the parameters (and what the
components compute from them alone) out of the step loop.
"""

from __future__ import annotations

import collections
import dis
import types
from typing import Any

from numba import njit
from numba.core import cgutils
from numba.core import types as nbtypes
from numba.core.dispatcher import Dispatcher
from numba.core.imputils import impl_ret_borrowed
from numba.extending import intrinsic

from .._codegen import (called_not_inlined, code_fingerprint, content_digest,
                       is_called_not_inlined)
from .inline_copy import install as _install_inline_copy

# numba's inliner copies an IR in (blocks x variables): without this, the crash stop's kernel
# spent most of its compile copying (seahelm.simulation.inline_copy)
_install_inline_copy()

__all__ = ["inline_always", "called_not_inlined", "inlined_size", "local_record",
           "python_function", "no_jit", "record_in_place", "is_numba_function", "py_func_of"]


def is_numba_function(obj: Any) -> bool:
    """Whether ``obj`` is a function of numba's: a dispatcher, or any plain function while
    numba's JIT is disabled (``NUMBA_DISABLE_JIT=1``: ``njit`` then returns the function
    itself, and the components call each other as plain functions).

    Parameters
    ----------
    obj : object

    Returns
    -------
    bool
    """
    if isinstance(obj, Dispatcher):
        return True
    from numba.core import config

    return bool(config.DISABLE_JIT) and isinstance(obj, types.FunctionType)


def py_func_of(func: Any) -> types.FunctionType:
    """The Python function of a numba dispatcher (its ``py_func``), or a plain function itself
    (what ``njit`` returns with numba's JIT disabled).

    Parameters
    ----------
    func : numba dispatcher or function

    Returns
    -------
    function
    """
    return getattr(func, "py_func", func)


def _copy(py: types.FunctionType, glb: dict[str, Any],
          closure: tuple[Any, ...] | None) -> types.FunctionType:
    """``py`` with other globals (and closure cells): the same code object, so a breakpoint
    or a tracer set on the original's lines sees the copy run."""
    clone = types.FunctionType(py.__code__, glb, py.__name__, py.__defaults__, closure)
    clone.__qualname__ = py.__qualname__
    clone.__doc__ = py.__doc__
    clone.__kwdefaults__ = py.__kwdefaults__
    return clone


def _names(code: types.CodeType) -> set[str]:
    names: set[str] = set()
    stack = [code]
    while stack:
        c = stack.pop()
        names.update(c.co_names)
        stack.extend(k for k in c.co_consts if isinstance(k, types.CodeType))
    return names


def inlined_size(func: Dispatcher) -> int:
    """Bytecode instructions of ``func`` and of every numba function it calls (each once).

    What :func:`inline_always` copies into a call site: a measure of the code numba and LLVM
    compile for each inlined call (compile time grows with it), used by the engine to decide
    whether the integrator's stages are written out or looped over
    (:func:`seahelm.simulation.engine.compile_closed_loop`).

    Parameters
    ----------
    func : numba dispatcher
        (or, with numba's JIT disabled, the plain function ``njit`` returned)

    Returns
    -------
    int
    """
    seen: set[int] = set()
    todo = [func]
    total = 0
    while todo:
        f = todo.pop()
        if id(f) in seen:
            continue
        seen.add(id(f))
        py = py_func_of(f)
        codes = [py.__code__]
        while codes:
            c = codes.pop()
            total += sum(1 for _ in dis.get_instructions(c))
            codes.extend(k for k in c.co_consts if isinstance(k, types.CodeType))
        todo.extend(obj for name in _names(py.__code__)
                    if is_numba_function(obj := py.__globals__.get(name))
                    and not is_called_not_inlined(obj))
    return total


def inline_always(func: Dispatcher) -> Dispatcher:
    """``njit(inline="always")`` of ``func`` and, in its copy, of every numba function it calls.

    Parameters
    ----------
    func : numba dispatcher
        A function decorated with ``@njit``.

    Returns
    -------
    numba dispatcher
        A new dispatcher (``inline="always"``); numba functions it names in its globals are
        replaced by their own ``inline_always`` copies. A function that calls itself, directly
        or not, keeps its calls (a recursion cannot be inlined), and so does a function
        marked by :func:`called_not_inlined`.
    """
    return _inline(func, {})


def _inline(func: Dispatcher, memo: dict[int, Any]) -> Dispatcher:
    key = id(func)
    if key in memo:
        # None marks a function whose copy is being built: a recursion, left as a call
        return func if memo[key] is None else memo[key]
    memo[key] = None
    out = njit(inline="always")(_with_copied_callees(func, memo))
    memo[key] = out
    return out


def _with_copied_callees(func: Dispatcher, memo: dict[int, Any]) -> types.FunctionType:
    """A copy of ``func``'s Python function whose globals see the loop's copies of the numba
    functions it names (inlined, or the called copy of one marked :func:`called_not_inlined`)
    and the slim stand-ins of its big index tuples."""
    py = func.py_func
    glb = dict(py.__globals__)
    for name in _names(py.__code__):
        obj = glb.get(name)
        if isinstance(obj, Dispatcher) and obj is not func:
            glb[name] = _called_copy(obj) if is_called_not_inlined(obj) else _inline(obj, memo)
    glb.update(_slim_index_tuples(py.__code__, glb))
    return _copy(py, glb, py.__closure__)


#: The fastmath flags of the compiled loop (the kernel's ``FASTMATH``, written into each
#: generated kernel by :func:`seahelm.simulation.closed_loop.compile_closed_loop`): what an
#: inlined component is compiled with, and so a called one too (:func:`_called_copy`).
LOOP_FASTMATH: tuple[str, ...] = ("arcp", "contract", "afn", "reassoc")

#: The loop's copies of the functions marked :func:`called_not_inlined`, per function.
_CALLED_COPIES: dict[int, tuple[Any, Dispatcher]] = {}


def _called_copy(func: Dispatcher) -> Dispatcher:
    """The loop's own dispatcher of a function marked :func:`called_not_inlined`: a copy
    compiled as the loop compiles what it inlines (the loop's :data:`LOOP_FASTMATH` flags,
    every numba function it calls inlined into it), so that calling it computes what the
    inlined function computed; ``cache=True`` under a name of its own, made of the
    function's name and the fingerprint of its code and its callees'
    (:func:`seahelm._codegen.code_fingerprint`: numba's cache would serve the original's
    code, compiled without those flags, under the function's own name, and keeps a copy
    compiled before a callee in another module was edited)."""
    key = id(func)
    if key in _CALLED_COPIES:
        return _CALLED_COPIES[key][1]
    py = func.py_func
    clone = _with_copied_callees(func, {key: func})  # (a recursion back to it: a call)
    digest = content_digest(code_fingerprint(py))
    clone.__qualname__ = f"{py.__qualname__}__in_loop_{digest}"
    options = {k: v for k, v in func.targetoptions.items() if k == "locals"}
    out = njit(cache=True, fastmath=set(LOOP_FASTMATH), **options)(clone)
    _CALLED_COPIES[key] = (func, out)
    return out


#: Fields of a named tuple of indices above which an inlined copy reads it through a
#: stand-in (:func:`_slim_index_tuples`); smaller ones cost the compile nothing measurable,
#: and are not looked for (looking costs some 0.1 ms per function at every kernel import).
SLIM_TUPLES_ABOVE = 64


def _slim_index_tuples(code: types.CodeType, glb: dict[str, Any]) -> dict[str, Any]:
    """Smaller stand-ins for the big named tuples of integers (:func:`seahelm.parameters.
    signal_indices`) that ``code`` reads fields of: each holds only the fields read, with
    their values.

    numba freezes a global named tuple into the code as a constant, but it builds the whole
    tuple, one ``insertvalue`` per field, wherever a field is read: the DP controllers' state
    indices (5,153 fields, most of them the allocation's workspace) made 36,000 of the 41,000
    LLVM instructions of the DP loop's ``init_runs`` and 20 MB of its ``run_slice``'s IR, and
    LLVM's ``EarlyCSE`` pass spent most of the loop's compile on them. A stand-in with the
    fields read gives each read the same integer, so the compiled code computes the same.
    A tuple that ``code`` uses otherwise than by reading a field (``len``, indexing, passing
    it on) is left as it is, and so is one of at most :data:`SLIM_TUPLES_ABOVE` fields.
    """
    big = {name for name in _names(code)
           if _is_index_tuple(glb.get(name)) and len(glb[name]) > SLIM_TUPLES_ABOVE}
    if not big:
        return {}
    key = (code, tuple(sorted((name, id(glb[name])) for name in big)))
    if key not in _SLIMMED:  # (reading a big function's bytecode takes some 30 ms)
        _SLIMMED[key] = (tuple(glb[name] for name in sorted(big)), _slimmed(code, glb, big))
    return dict(_SLIMMED[key][1])


#: The stand-ins made, per code object and the tuples it reads (a process that builds several
#: loops of one component reads its bytecode once). Each entry holds the tuples themselves
#: too: while an entry lives no other object can take a tuple's ``id``, so a key never names
#: a tuple other than the one its stand-ins were made from.
_SLIMMED: dict[tuple[Any, ...], tuple[tuple[Any, ...], dict[str, Any]]] = {}


def _slimmed(code: types.CodeType, glb: dict[str, Any], big: set[str]) -> dict[str, Any]:
    reads: dict[str, set[str]] = {}
    whole: set[str] = set()
    codes = [code]
    while codes:
        c = codes.pop()
        codes.extend(k for k in c.co_consts if isinstance(k, types.CodeType))
        ins = list(dis.get_instructions(c))
        for j, i in enumerate(ins):
            if i.opname not in ("LOAD_GLOBAL", "LOAD_NAME", "LOAD_DEREF") or i.argval not in big:
                continue
            nxt = ins[j + 1] if j + 1 < len(ins) else None
            if (i.opname == "LOAD_GLOBAL" and nxt is not None and nxt.opname == "LOAD_ATTR"
                    and nxt.argval in glb[i.argval]._fields):
                reads.setdefault(i.argval, set()).add(nxt.argval)
            else:
                whole.add(i.argval)
    out: dict[str, Any] = {}
    for name, fields in reads.items():
        if name in whole:
            continue
        obj = glb[name]
        kept = tuple(f for f in obj._fields if f in fields)
        out[name] = collections.namedtuple(type(obj).__name__, kept)(
            *(getattr(obj, f) for f in kept))
    return out


def _is_index_tuple(obj: Any) -> bool:
    """A named tuple of plain integers (what :func:`seahelm.parameters.signal_indices`
    returns)."""
    return (isinstance(obj, tuple) and hasattr(type(obj), "_fields")
            and all(type(v) is int for v in obj))


def python_function(func: Any) -> types.FunctionType:
    """The plain-Python twin of :func:`inline_always`: ``func``'s Python function, calling the
    Python functions of the numba functions it names.

    A copy of ``func.py_func`` (the same code object, so a breakpoint in the component's
    source is hit) whose globals and closure cells see the twins of every numba function they
    hold, recursively: calling it compiles nothing, and no numba cache is written.

    Parameters
    ----------
    func : numba dispatcher or function
        A function decorated with ``@njit`` (with numba's JIT disabled, the plain function).

    Returns
    -------
    function
        A plain Python function; a function that calls itself calls its own twin.
    """
    return _python_twin(func, {})


def _python_twin(func: Any, memo: dict[int, types.FunctionType]) -> types.FunctionType:
    key = id(func)
    if key in memo:
        return memo[key]
    py = py_func_of(func)
    glb = dict(py.__globals__)
    # a component made by a factory holds its helpers in closure cells: new cells for those
    old_cells = py.__closure__ or ()
    cells = tuple(types.CellType() if is_numba_function(_cell_contents(c)) else c
                  for c in old_cells)
    # the copy is registered before its globals and cells are filled in: a recursion finds
    # its twin
    memo[key] = twin = _copy(py, glb, cells if py.__closure__ is not None else None)
    for new, old in zip(cells, old_cells):
        if new is not old:
            new.cell_contents = _python_twin(old.cell_contents, memo)
    for name in _names(py.__code__):
        obj = glb.get(name)
        if obj is not func and is_numba_function(obj):
            glb[name] = _python_twin(obj, memo)
        elif obj is func:
            glb[name] = twin
    return twin


def _cell_contents(cell: types.CellType) -> Any:
    try:
        return cell.cell_contents
    except ValueError:  # an empty cell
        return None


def no_jit(*args: Any, **options: Any) -> Any:
    """A stand-in for ``njit`` that leaves a function as it is (``@no_jit`` or
    ``@no_jit(cache=True, ...)``), for the pure-Python closed loop.

    Parameters
    ----------
    *args
        The function, when used without options.
    **options
        ``njit``'s options (ignored).

    Returns
    -------
    function or decorator
    """
    if len(args) == 1 and callable(args[0]) and not options:
        return args[0]
    return lambda func: func


def record_in_place(rec: Any) -> Any:
    """:func:`local_record` in plain Python: the record itself (read in place; the compiled
    stack copy is only for speed).

    Parameters
    ----------
    rec : numpy.record or any

    Returns
    -------
    The same object.
    """
    return rec


@intrinsic
def local_record(typingctx, rec):  # pragma: no cover - compiled
    """A copy of the record ``rec`` on the stack (any other argument is returned as it is).

    A record read in place (``mp[i]``) points into an argument array, and LLVM cannot prove
    that the loop's stores to the other argument arrays (the scratch buffers) leave it
    unchanged: every field is reloaded, and everything computed from the parameters alone
    recomputed (the catamaran's damping constant and mass reciprocal), at every stage of every
    step. A stack copy that does not escape aliases no argument, so the fields are loaded once
    per run and the parameter algebra is hoisted out of the step loop (measured: the catamaran
    loop went from 75-80 % to 94-99 % of a hand-fused kernel, the Nomoto-2 loop from 1.74e7 to
    2.0e7 vessel-steps/s at batch 10,000).

    Only for reading: the copy lives in the caller's stack frame (allocated once, at the
    function's entry, and overwritten by each call), so writes to it do not reach the array.
    """
    def codegen(context, builder, signature, args):
        if not isinstance(rec, nbtypes.Record):
            return impl_ret_borrowed(context, builder, rec, args[0])
        # the record's bytes (numba passes a record as a pointer to them), 16-byte aligned
        # so that field loads are aligned wherever the array's records were
        slot = cgutils.alloca_once(builder, context.get_data_type(rec))
        slot.align = 16
        builder.store(builder.load(args[0]), slot)
        return slot

    return rec(rec), codegen
