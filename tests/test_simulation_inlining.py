"""inline_always: a component and every numba function it calls inline into the kernel."""

from __future__ import annotations

import numpy as np
from numba import njit

from seahelm._codegen import called_not_inlined
from seahelm.simulation.inlining import inline_always, local_record


@njit
def _leaf(x):
    return 2.0 * x


@njit
def _middle(x):
    return _leaf(x) + 1.0


@njit
def _top(x):
    return _middle(x) - 0.5


@njit
def _factorial(n):
    return 1.0 if n <= 0 else n * _factorial(n - 1)


def test_helpers_are_inlined_at_every_level_and_the_originals_are_untouched():
    top = inline_always(_top)
    assert top.targetoptions["inline"] == "always"
    middle = top.py_func.__globals__["_middle"]
    assert middle is not _middle and middle.targetoptions["inline"] == "always"
    assert middle.py_func.__globals__["_leaf"].targetoptions["inline"] == "always"
    assert _top.py_func.__globals__["_middle"] is _middle  # the module is not modified

    @njit
    def caller(x):
        return top(x)

    assert caller(3.0) == 6.5
    ir = "".join(caller.inspect_llvm().values())
    # a call that was not inlined shows as a declaration of the callee's mangled name
    assert "_middle" not in ir and "_leaf" not in ir

    @njit
    def caller_plain(x):
        return _top(x)

    assert caller_plain(3.0) == 6.5
    assert "_top" in "".join(caller_plain.inspect_llvm().values())  # the contrast: a call


def test_a_recursive_function_keeps_its_call():
    fact = inline_always(_factorial)

    @njit
    def caller(n):
        return fact(n)

    assert caller(5) == 120.0


# --- local_record: a run's parameter record copied onto the stack ---------------------------
def _records():
    import numpy as np

    dtype = np.dtype([("gain", "f8"), ("steps", "i8"), ("lag", "f8")], align=True)
    recs = np.zeros(3, dtype=dtype)
    recs["gain"] = [1.5, -2.0, 3.25]
    recs["steps"] = [7, 8, 9]
    recs["lag"] = [0.1, 0.2, 0.3]
    return recs


@njit
def _sum_fields_in_a_loop(recs, out):
    for i in range(recs.shape[0]):
        p = local_record(recs[i])
        acc = 0.0
        for k in range(p.steps):
            out[k % out.shape[0]] = p.gain  # a store the copy cannot alias
            acc += p.gain * p.lag + out[0]
        recs[i].lag = acc  # the array itself is still written through the original


def test_local_record_reads_the_same_fields_and_is_a_copy():
    import numpy as np

    recs = _records()
    expected = recs.copy()
    for i in range(3):
        g, n, lag = float(recs["gain"][i]), int(recs["steps"][i]), float(recs["lag"][i])
        expected["lag"][i] = n * (g * lag + g)
    out = np.zeros(4)
    _sum_fields_in_a_loop(recs, out)
    np.testing.assert_allclose(recs["lag"], expected["lag"], rtol=1e-15)

    @njit
    def write_copy(recs):
        p = local_record(recs[0])
        p.gain = 99.0
        return p.gain

    assert write_copy(recs) == 99.0 and recs["gain"][0] == 1.5  # the array is untouched

    @njit
    def passes_arrays_through(a):
        return local_record(a[1])[0]

    assert passes_arrays_through(np.arange(6.0).reshape(3, 2)) == 2.0


# --- a function called from the loop, not copied into it (called_not_inlined) -----------------
@njit
def _dot(a, b):
    s = 0.0  # (the loop's reassociation and contraction change the rounding of this sum)
    for i in range(a.size):
        s += a[i] * b[i]
    return s


@called_not_inlined
@njit
def _rare(a, b):
    return _dot(a, b) + 1.0


@njit
def _rare_unmarked(a, b):  # (the same function, inlined as any other)
    return _dot(a, b) + 1.0


@njit
def _component(a, b):
    return 0.5 * _rare(a, b)


@njit
def _component_inlined(a, b):
    return 0.5 * _rare_unmarked(a, b)


def test_a_marked_function_is_called_compiled_as_the_loop_compiles_it():
    from seahelm._codegen import is_called_not_inlined
    from seahelm.simulation.inlining import LOOP_FASTMATH

    assert is_called_not_inlined(_rare) and not is_called_not_inlined(_rare_unmarked)
    comp = inline_always(_component)
    called = comp.py_func.__globals__["_rare"]
    assert called is not _rare and "inline" not in called.targetoptions  # (a call)
    assert called.targetoptions["fastmath"] == set(LOOP_FASTMATH)
    assert type(called._cache).__name__ == "FunctionCache"  # (cache=True: once per machine)
    assert called.py_func.__qualname__.startswith("_rare__in_loop_")
    assert called.py_func.__globals__["_dot"].targetoptions["inline"] == "always"
    assert inline_always(_component).py_func.__globals__["_rare"] is called  # (one copy)
    inlined = inline_always(_component_inlined)

    def loop(component):
        @njit(fastmath=set(LOOP_FASTMATH))
        def run(a, b):
            return component(a, b)
        return run

    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(2, 40, 1001))
    run_called, run_inlined = loop(comp), loop(inlined)
    as_called = np.array([run_called(x, y) for x, y in zip(a, b)])
    as_inlined = np.array([run_inlined(x, y) for x, y in zip(a, b)])
    assert np.array_equal(as_called, as_inlined)  # the same bits as when it was inlined
    plain = np.array([0.5 * _rare(x, y) for x, y in zip(a, b)])  # (the original's own flags)
    assert not np.array_equal(plain, as_inlined)  # (the flags matter: the test can fail)
    ir = "".join(run_called.inspect_llvm().values())
    assert "_rare__in_loop_" in ir and "_rare__in_loop_" not in "".join(  # a call of the copy
        run_inlined.inspect_llvm().values())


def test_the_copy_is_named_after_its_code_and_its_callees():
    import types

    from seahelm.simulation import inlining

    @njit
    def other_dot(a, b):
        return _dot(a, b) - 0.0

    py = _rare.py_func
    twin = called_not_inlined(njit(types.FunctionType(
        py.__code__, {**py.__globals__, "_dot": other_dot}, py.__name__)))
    names = {inlining._called_copy(f).py_func.__qualname__ for f in (_rare, twin)}
    assert len(names) == 2  # (a callee edited in another module: another cache entry)


def test_the_dp_loop_calls_its_allocation_and_the_kernel_has_the_loops_flags():
    from seahelm.actuators.servo import DIRECT
    from seahelm.control.dp_pid import allocate_step, dp_pid_step
    from seahelm.control.open_loop import OPEN_LOOP
    from seahelm.simulation.engine import compile_closed_loop
    from seahelm.simulation.inlining import LOOP_FASTMATH
    from seahelm.vessels.nomoto import NOMOTO1

    step = inline_always(dp_pid_step)
    control = step.py_func.__globals__["dp_control"]
    called = control.py_func.__globals__["allocate_step"]
    assert called is not allocate_step and called.py_func.__code__ is allocate_step.py_func.__code__
    assert "inline" not in called.targetoptions
    kernel = compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, "euler")  # (imported, not compiled)
    assert kernel.FASTMATH == set(LOOP_FASTMATH)
