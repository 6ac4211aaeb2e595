"""CompileAhead: the second process starts only when this one compiles, and is waited for."""
from __future__ import annotations

from pathlib import Path

import numba
import pytest

from seahelm.simulation.compile_ahead import CompileAhead


def _touch(path: str) -> None:
    Path(path).write_text("filled")


def test_starts_when_this_process_compiles(tmp_path: Path,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("seahelm.simulation.compile_ahead._available_cores", lambda: 2)
    marker = tmp_path / "marker"
    with CompileAhead(_touch, str(marker)) as ahead:
        numba.njit(lambda x: x * 3)(2)  # a compilation in this process
        ahead.wait()
    assert ahead.started
    assert marker.read_text() == "filled"


def test_nothing_starts_without_a_compilation(tmp_path: Path,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("seahelm.simulation.compile_ahead._available_cores", lambda: 2)
    marker = tmp_path / "marker"
    with CompileAhead(_touch, str(marker)) as ahead:
        ahead.wait()
    assert not ahead.started and not marker.exists()


def test_off_on_one_core_and_by_the_environment(tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    marker = tmp_path / "marker"
    monkeypatch.setattr("seahelm.simulation.compile_ahead._available_cores", lambda: 1)
    with CompileAhead(_touch, str(marker)) as ahead:
        numba.njit(lambda x: x * 5)(2)
        ahead.wait()
    assert not ahead.started
    monkeypatch.setattr("seahelm.simulation.compile_ahead._available_cores", lambda: 2)
    monkeypatch.setenv("SEAHELM_COMPILE_AHEAD", "0")
    with CompileAhead(_touch, str(marker)) as ahead:
        numba.njit(lambda x: x * 7)(2)
        ahead.wait()
    assert not ahead.started and not marker.exists()


def test_an_exception_ends_the_second_process(tmp_path: Path,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("seahelm.simulation.compile_ahead._available_cores", lambda: 2)
    with pytest.raises(RuntimeError, match="boom"):
        with CompileAhead(_touch, str(tmp_path / "m")) as ahead:
            numba.njit(lambda x: x * 11)(2)
            process = ahead._process
            raise RuntimeError("boom")
    assert process is not None
    process.join(10)
    assert not process.is_alive()


def test_the_compile_log_gets_each_compilation_once(tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """CompileAhead's own listener does not log: with the command's, every compilation was
    listed twice."""
    from seahelm._codegen import watch_compiles

    log = tmp_path / "log.txt"
    monkeypatch.setenv("SEAHELM_COMPILE_LOG", str(log))
    monkeypatch.setattr("seahelm.simulation.compile_ahead._available_cores", lambda: 2)
    stop = watch_compiles()
    try:
        with CompileAhead(_touch, str(tmp_path / "m")) as ahead:
            numba.njit(lambda x: x * 13)(2)
            ahead.wait()
    finally:
        stop()
    assert len(log.read_text().splitlines()) == 1
