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
                # (the scope is kept beside its memo: its id stays its own while in use)
                memo = memos.setdefault(id(x.scope), (x.scope, {}))[1]
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
            from numba.core import inline_closurecall as icc
        except ImportError:  # pragma: no cover - numba without the module
            return False
        worker = getattr(icc, "InlineWorker", None)
        original = getattr(worker, "inline_ir", None)
        if original is None or getattr(icc, "copy", None) is not copy:
            return False  # pragma: no cover - another numba: leave it alone

        def inline_ir(self: Any, caller_ir: Any, *args: Any, **kwargs: Any) -> Any:
            if not _is_ours(caller_ir):
                return original(self, caller_ir, *args, **kwargs)
            saved = getattr(_state, "memos", None)
            _state.memos = {}
            try:
                return original(self, caller_ir, *args, **kwargs)
            finally:
                _state.memos = saved

        inline_ir.__wrapped__ = original  # type: ignore[attr-defined]
        icc.copy = _SharedScopeCopy()
        worker.inline_ir = inline_ir
        _installed = True
        return True
