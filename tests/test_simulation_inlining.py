"""inline_always: a component and every numba function it calls inline into the kernel."""

from __future__ import annotations

from numba import njit

from seahelm.simulation.inlining import inline_always


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
