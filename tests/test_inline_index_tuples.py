"""The loop's inlined copies read big named tuples of indices through small stand-ins.

numba builds a global named tuple field by field (one LLVM ``insertvalue`` each) wherever a
field of it is read; the DP controllers' 5,153 state indices made most of their loop's IR and
compile (:func:`seahelm.simulation.inlining._slim_index_tuples`). The copies that the loop
inlines (:func:`~seahelm.simulation.inlining.inline_always`) read the same integers from a
named tuple of the fields they read, so they compute the same.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from seahelm.control import dp_pid
from seahelm.parameters import signal_indices
from seahelm.simulation.inlining import inline_always

BIG = signal_indices([f"s{j}" for j in range(2000)])


@njit
def reads_fields(x):  # pragma: no cover - compiled
    return x[BIG.s3] + 2.0 * x[BIG.s1998]


@njit
def reads_whole(x):  # pragma: no cover - compiled
    return x[BIG.s3] + len(BIG)


def _outer(inner):
    @njit
    def outer(x):  # pragma: no cover - compiled
        return inner(x)
    return outer


def test_an_inlined_copy_reads_its_fields_from_a_stand_in():
    glb = inline_always(reads_fields).py_func.__globals__
    assert glb["BIG"]._fields == ("s3", "s1998")
    assert (glb["BIG"].s3, glb["BIG"].s1998) == (3, 1998)
    assert globals()["BIG"] is BIG and len(BIG) == 2000  # the original is left alone


def test_a_tuple_used_whole_is_left_as_it_is():
    assert inline_always(reads_whole).py_func.__globals__["BIG"] is BIG


def test_the_inlined_code_computes_the_same_and_builds_no_tuple(monkeypatch):
    from numba.core import codegen

    lowered = []  # the LLVM IR numba lowers, before LLVM optimises it
    add = codegen.CPUCodeLibrary.add_ir_module
    monkeypatch.setattr(codegen.CPUCodeLibrary, "add_ir_module",
                        lambda self, m: (lowered.append((self.name, str(m))), add(self, m))[1])
    x = np.arange(2000.0) * 0.37
    outer = _outer(inline_always(reads_fields))
    assert outer(x) == reads_fields(x) == x[3] + 2.0 * x[1998]
    # (before: the 2,000-field tuple built at each of the two reads, 4,000 insertvalues)
    def built(name):
        return sum(ir.count("insertvalue [2000 x i64]") for lib, ir in lowered if lib == name)

    assert {"_outer.<locals>.outer", "reads_fields"} <= {lib for lib, _ in lowered}
    assert built("_outer.<locals>.outer") == 0
    assert built("reads_fields") == 4000  # (the original, compiled as it is)


def _index_tuples(func, name, seen=None):
    """The ``name`` globals seen by an inlined copy and by the copies it calls."""
    from numba.core.dispatcher import Dispatcher

    seen = set() if seen is None else seen
    if id(func) in seen:
        return []
    seen.add(id(func))
    glb = func.py_func.__globals__
    found = [glb[name]] if name in glb and name in func.py_func.__code__.co_names else []
    for obj in list(glb.values()):
        if isinstance(obj, Dispatcher) and obj.targetoptions.get("inline") == "always":
            found += _index_tuples(obj, name, seen)
    return found


def test_the_dp_controllers_read_small_state_indices():
    # (before: signal_indices(STATES), 5,153 fields, slimmed in the loop's copies only; the
    # observer step's own dispatcher compiled in 58-70 s, now 3 s)
    from seahelm.control import dp_observer

    for mod in (dp_pid, dp_observer):
        assert 0 < len(mod._S) < 50
        assert all(getattr(mod._S, f) == dp_pid.STATES.index(f) for f in mod._S._fields)
    for found in (_index_tuples(inline_always(dp_pid.DP_PID.step), "_S"),
                  _index_tuples(inline_always(dp_observer.DP_PID_OBSERVER.step), "_S")):
        assert found and all(0 < len(s) < 50 for s in found)
