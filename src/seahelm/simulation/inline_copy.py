"""numba's IR inliner without its quadratic copy, for seahelm's own functions.

Each ``inline="always"`` call site makes numba copy the callee's IR twice
(``numba.core.inline_closurecall.InlineWorker.inline_ir``: one copy to mutate, one kept
unmutated), block by block, each block with ``copy.deepcopy`` and a memo of its own. A block
refers to the function's scope, and the scope holds every variable of the function: each block's
copy copies the whole scope again, with every variable and its source location, so copying an IR
costs (blocks × variables), and an inlined component is copied again at every level it is
inlined into (component → closed right-hand side → step → loop). On the four-quadrant MMG
model's crash-stop kernel, whose force function inlines the MMG forces, the four-quadrant
propeller twice, the low-speed hull and their helpers, these copies were most of the compile:
numba's ``inline_inlinables`` pass took 102 of the loop's 187 s and 52 of the 74 s of
``init_runs`` (a loaded 2-core machine, 2026-12-01), 79 of its 87 s in ``copy.deepcopy``
under a profiler. (The cost is known upstream: numba issues #8989, #9204, NVIDIA/numba-cuda
#688.)

:func:`install` makes the blocks of one scope, within one ``inline_ir`` call, share one memo:
the scope and each variable are copied once per copy of the IR instead of once per block, and
the copy has the structure of the original (one scope object shared by all its blocks, as
numba builds it). The IR that results is the same, so the compiled code is too: the LLVM IR of
the crash-stop loop is identical text with and without it (``tests/test_inline_copy.py``).
It applies only where the function being compiled into is seahelm's (its module is
``seahelm`` or a generated ``seahelm_*`` module); any other code numba compiles in the process
goes through numba's copy as it is. ``SEAHELM_INLINE_COPY=0`` leaves numba alone.

Two more repeats of the inliner's are skipped there, within one top-level inlining pass
(``InlineInlinables`` of one function being compiled; the memo is dropped when it ends):

- the callee's IR is made once per function, not once per call site. numba runs the whole
  untyped pipeline on the callee at each site (``InlineWorker.inline_function``): bytecode
  analysis, rewrites and, recursively, the inlining of everything the callee calls. The
  closed right-hand side is inlined at each of RK4's four stages, a 6-DOF model's symmetric
  3 × 3 helper at 27 sites. Each site still gets a copy of its own (``inline_ir`` copies the
  callee before it changes it) and a function identity of its own, so its variables are
  named as numba names them.
- the second copy of the callee, which ``inline_ir`` keeps unmutated and returns, and which
  the inlining pass (its only caller here) throws away, is not made (its blocks are the
  inlined ones).
"""
from __future__ import annotations

import copy
import os
import threading
from typing import Any

__all__ = ["install", "installed"]

_state = threading.local()


class _SharedScopeCopy:
    """Stands for the :mod:`copy` module inside ``numba.core.inline_closurecall`` (whose only
    use of it is the block copies of ``inline_ir``): while :func:`_inline_ir` runs for one of
    seahelm's functions, a block is deep-copied with the memo of its scope."""

    def __getattr__(self, name: str) -> Any:
        return getattr(copy, name)

    @staticmethod
    def deepcopy(x: Any, memo: dict[int, Any] | None = None, _nil: Any = ()) -> Any:
        memos = getattr(_state, "memos", None)
        if memo is None and memos is not None:
            from numba.core import ir

            if isinstance(x, ir.Block):
                copies = _state.copies
                if copies is not None and id(x.scope) in copies:
                    # a block of the first copy: inline_ir's second copy, thrown away
                    return x
                # (the scope is kept beside its memo: its id stays its own while in use)
                memo = memos.setdefault(id(x.scope), (x.scope, {}))[1]
                out = copy.deepcopy(x, memo)
                if copies is not None:
                    copies[id(out.scope)] = out.scope
                return out
        return copy.deepcopy(x, memo)


def _is_ours(func_ir: Any) -> bool:
    module = getattr(getattr(func_ir, "func_id", None), "modname", None) or ""
    return module == "seahelm" or module.startswith(("seahelm.", "seahelm_"))


_installed = False
_lock = threading.Lock()


def installed() -> bool:
    """Whether :func:`install` has patched numba's inliner in this process.

    Returns
    -------
    bool
    """
    return _installed


def install() -> bool:
    """Patch numba's ``InlineWorker.inline_ir`` (module docstring); idempotent.

    Returns
    -------
    bool
        Whether the patch is in place (False with ``SEAHELM_INLINE_COPY=0``, or when numba's
        inliner is not shaped as expected: then numba is left as it is).
    """
    global _installed
    with _lock:
        if _installed:
            return True
        if os.environ.get("SEAHELM_INLINE_COPY", "1") == "0":
            return False
        try:
            from numba.core import bytecode, untyped_passes
            from numba.core import inline_closurecall as icc
        except ImportError:  # pragma: no cover - numba without the module
            return False
        worker = getattr(icc, "InlineWorker", None)
        original = getattr(worker, "inline_ir", None)
        if (original is None or getattr(icc, "copy", None) is not copy
                or not hasattr(worker, "inline_function")
                or not hasattr(untyped_passes, "InlineInlinables")):
            return False  # pragma: no cover - another numba: leave it alone

        def inline_ir(self: Any, caller_ir: Any, *args: Any, **kwargs: Any) -> Any:
            if not _is_ours(caller_ir):
                return original(self, caller_ir, *args, **kwargs)
            saved = getattr(_state, "memos", None), getattr(_state, "copies", None)
            _state.memos = {}
            # (only for the inlining pass's calls: it discards the unmutated copy)
            _state.copies = {} if getattr(_state, "discard_original", False) else None
            _state.discard_original = False
            try:
                return original(self, caller_ir, *args, **kwargs)
            finally:
                _state.memos, _state.copies = saved

        inline_ir.__wrapped__ = original  # type: ignore[attr-defined]
        original_function = worker.inline_function
        original_pass = untyped_passes.InlineInlinables.run_pass

        def inline_function(self: Any, caller_ir: Any, block: Any, i: int, function: Any,
                            arg_typs: Any = None) -> Any:
            callees = getattr(_state, "callees", None)
            if callees is None or arg_typs is not None or not _is_ours(caller_ir):
                return original_function(self, caller_ir, block, i, function, arg_typs)
            entry = callees.get(function)
            if entry is None or entry[0] is not self.flags:
                # the first site: the IR as numba makes it (inline_ir copies it before it
                # changes it)
                callee_ir = self.run_untyped_passes(function)
                callees[function] = (self.flags, callee_ir)  # (holds the function: its key
                #                                                stays its own)
            else:
                self.flags.enable_ssa = False  # (what run_untyped_passes leaves)
                # a shallow copy with an identity of its own: inline_ir names the variables
                # it inlines after it (only the numbers in the names differ from numba's)
                callee_ir = copy.copy(entry[1])
                callee_ir.func_id = bytecode.FunctionIdentity.from_function(function)
            _state.discard_original = True
            return self.inline_ir(caller_ir, block, i, callee_ir,
                                  function.__code__.co_freevars)

        def run_pass(self: Any, state: Any) -> Any:
            if getattr(_state, "callees", None) is not None or not _is_ours(state.func_ir):
                return original_pass(self, state)
            _state.callees = {}
            try:
                return original_pass(self, state)
            finally:
                _state.callees = None

        inline_function.__wrapped__ = original_function  # type: ignore[attr-defined]
        run_pass.__wrapped__ = original_pass  # type: ignore[attr-defined]
        icc.copy = _SharedScopeCopy()
        worker.inline_ir = inline_ir
        worker.inline_function = inline_function
        untyped_passes.InlineInlinables.run_pass = run_pass
        _installed = True
        return True
