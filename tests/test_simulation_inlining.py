"""inline_always: a component and every numba function it calls inline into the kernel."""

from __future__ import annotations

from numba import njit

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
