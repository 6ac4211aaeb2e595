"""``SEAHELM_COMPILE_LOG`` naming a path that cannot be appended to (issue 43 campaign): the
command went on to fail with 'error: Is a directory: logdir' or '[Errno 2] No such file or
directory: ...' at its first compilation, naming neither the variable nor why."""

from __future__ import annotations

import warnings

import numba
import pytest

from seahelm._codegen import watch_compiles


def _compile_something(k: int) -> None:
    @numba.njit(cache=False)
    def f(x):
        return x + k

    f(1.0)


@pytest.mark.parametrize("where", ["a directory", "a missing folder"])
def test_a_log_that_cannot_be_written_is_said_once_and_the_work_goes_on(tmp_path, monkeypatch,
                                                                        where):
    log = tmp_path if where == "a directory" else tmp_path / "nope" / "log.txt"
    monkeypatch.setenv("SEAHELM_COMPILE_LOG", str(log))
    stop = watch_compiles()
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            _compile_something(1)
            _compile_something(2)
    finally:
        stop()
    said = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
    reason = "Is a directory" if where == "a directory" else "No such file or directory"
    assert said == [f"SEAHELM_COMPILE_LOG = {str(log)!r} cannot be appended to ({reason}); "
                    "compilations are not logged"], said


def test_a_writable_log_gets_a_line_per_compilation(tmp_path, monkeypatch):
    log = tmp_path / "log.txt"
    monkeypatch.setenv("SEAHELM_COMPILE_LOG", str(log))
    stop = watch_compiles()
    try:
        _compile_something(3)
    finally:
        stop()
    assert "_compile_something.<locals>.f" in log.read_text()
