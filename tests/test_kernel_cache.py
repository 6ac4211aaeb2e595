"""The on-disk kernel cache: a command repeated compiles nothing.

A generated kernel is named after :func:`seahelm._codegen.code_fingerprint` of the code it
calls. That name must be the same in every process, or a later run looks for a kernel no run
has written and compiles it again (a repeated ``seahelm imo kvlcc2-full`` took four minutes
every time: the fingerprint was ``marshal.dumps`` of the code, which flags shared objects by
their reference count, and numba's compiler holds references to the constants).
"""
from __future__ import annotations

import marshal
import os
import subprocess
import sys
import types
from pathlib import Path

import pytest

from seahelm._codegen import code_fingerprint, code_identity, watch_compiles
from seahelm.vessels import mmg


def _hold_references(code: types.CodeType, keep: list[object]) -> None:
    keep.extend(code.co_consts)
    keep.extend(code.co_names)
    keep.extend(code.co_varnames)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            _hold_references(const, keep)


def test_fingerprint_does_not_depend_on_reference_counts() -> None:
    # a fresh copy of the model's code: its constants are referenced by it alone (as after an
    # import from bytecode), whatever this process compiled before
    original = mmg._forces.py_func
    py = types.FunctionType(marshal.loads(marshal.dumps(original.__code__)),
                            original.__globals__, original.__name__)
    before_marshal = marshal.dumps(py.__code__)
    before = code_fingerprint(py)
    keep: list[object] = []
    _hold_references(py.__code__, keep)
    # the precondition: this is what changed marshal's bytes (a constant shared once more)
    assert marshal.dumps(py.__code__) != before_marshal
    assert code_fingerprint(py) == before
    assert code_fingerprint(py) == code_fingerprint(original)
    del keep


def _f_one(x):  # the same code as _f_two but for one constant
    return x * 1.5 + 2.0


def _f_two(x):
    return x * 1.5 + 2.5


def _f_names(x):
    return x in {"alpha", "beta", "gamma", "delta"}


def test_identity_changes_with_what_the_code_does() -> None:
    assert code_identity(_f_one.__code__) != code_identity(_f_two.__code__)
    twin = types.FunctionType(compile("def _f_one(x):\n    return x * 1.5 + 2.0\n",
                                      "/elsewhere/other.py", "exec").co_consts[0], {})
    # another file, another line: the same behaviour, the same identity
    assert code_identity(twin.__code__) == code_identity(_f_one.__code__)


def test_identity_is_the_same_under_another_string_hash_seed() -> None:
    # a set literal becomes a frozenset constant whose order follows the string hash
    script = ("import sys; sys.path.insert(0, %r); import test_kernel_cache as t; "
              "from seahelm._codegen import code_identity; "
              "print(code_identity(t._f_names.__code__).hex())" % str(Path(__file__).parent))
    digests = set()
    for seed in ("1", "2", "3"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                             text=True, check=True)
        digests.add(out.stdout.strip())
    assert len(digests) == 1


def test_compile_log_names_each_compiled_function(tmp_path: Path) -> None:
    import numba

    log = tmp_path / "compiles.txt"
    stop = watch_compiles(log=log)
    try:
        @numba.njit
        def _fresh(x):
            return x + 1

        _fresh(1)
        _fresh(2)  # the same types: no second compilation
    finally:
        stop()
    _fresh(1.5)  # after stop(): not logged
    lines = log.read_text().splitlines()
    assert len(lines) == 1 and "_fresh" in lines[0]


def _run(args: list[str], env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "seahelm", *args], env=env,
                          capture_output=True, text=True, timeout=600)


def test_a_repeated_command_compiles_nothing(tmp_path: Path) -> None:
    """A zig-zag of the KVLCC2 in a fresh cache, twice: the second run loads every kernel.
    (Before the fix the second run compiled its kernel again, 17 s, under a new name.)"""
    env = {**os.environ, "SEAHELM_CACHE_DIR": str(tmp_path / "kernels"),
           "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "MPLBACKEND": "Agg"}
    env.pop("SEAHELM_COMPILE_LOG", None)
    command = ["maneuver", "zigzag", "--ship", "kvlcc2-l7", "--rudder", "20", "--heading", "20",
               "--json"]
    first_log = tmp_path / "first.txt"
    first = _run(command, {**env, "SEAHELM_COMPILE_LOG": str(first_log)})
    assert first.returncode == 0, first.stderr
    assert first_log.exists() and "seahelm_kernel_" in first_log.read_text()
    files = sorted(p.name for p in (tmp_path / "kernels").rglob("*"))

    second_log = tmp_path / "second.txt"
    second = _run(command, {**env, "SEAHELM_COMPILE_LOG": str(second_log)})
    assert second.returncode == 0, second.stderr
    assert second.stdout == first.stdout
    compiled = second_log.read_text().splitlines() if second_log.exists() else []
    assert [line.split(" ")[0] for line in compiled] == []
    assert sorted(p.name for p in (tmp_path / "kernels").rglob("*")) == files


def test_compiling_status_only_on_a_terminal(tmp_path: Path) -> None:
    """Not a terminal: no status line on stderr (scripts and pipes see the command's output
    alone)."""
    env = {**os.environ, "SEAHELM_CACHE_DIR": str(tmp_path / "kernels"),
           "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    out = _run(["linearize", "mariner-nonlinear", "--json"], env)
    assert out.returncode == 0, out.stderr
    assert "compiling" not in out.stderr


@pytest.mark.skipif(sys.platform == "win32", reason="a pseudo-terminal")
def test_compiling_status_on_a_terminal(tmp_path: Path) -> None:
    import pty

    env = {**os.environ, "SEAHELM_CACHE_DIR": str(tmp_path / "kernels"),
           "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    script = ("import sys, numba; from seahelm.cli.main import _show_compiling; "
              "_show_compiling(); numba.njit(lambda x: x + 1)(1)")
    master, slave = pty.openpty()
    proc = subprocess.run([sys.executable, "-c", script], env=env, stdout=subprocess.DEVNULL,
                          stderr=slave, timeout=120)
    os.close(slave)
    text = os.read(master, 4096).decode()
    os.close(master)
    assert proc.returncode == 0
    assert text.count("compiling") == 1 and "first use" in text


def test_the_actuator_row_loops_are_generated_and_equal_the_generic_loop() -> None:
    """The linearisation's actuator rows run through loops generated per function (cached on
    disk; the loop that took the functions as arguments compiled in every process: 1.4 s of
    every `seahelm linearize`), with the generic loop's numbers."""
    import numpy as np

    from seahelm.actuators.servo import RUDDER_SERVO
    from seahelm.parameters import as_records
    from seahelm.vessels import base

    act = RUDDER_SERVO
    assert base._row_loop(act.rhs, "output") is not None
    assert base._row_loop(act.output, "output_untimed") is not None
    k = 5
    X = np.linspace(-0.3, 0.3, k * act.n_states).reshape(k, act.n_states)
    C = np.linspace(0.5, -0.5, k * act.n_commands).reshape(k, act.n_commands)
    P = as_records(np.repeat(base._param_array(act.params_type(), act.params_type)[None], k, 0),
                   act.params_type)
    dx, y = np.zeros((k, act.n_states)), np.zeros((k, act.n_outputs))
    dx0, y0 = np.zeros_like(dx), np.zeros_like(y)
    base._batched_actuator(act.rhs, act.output, 0.0, X, C, P, dx, y)
    base._generic_actuator(act.rhs, act.output, 0.0, X, C, P, dx0, y0)
    assert np.array_equal(dx, dx0) and np.array_equal(y, y0) and np.abs(dx).max() > 0
