"""The output side of the ``seahelm`` command: where its files go, checked before any work.

Every file a command writes goes by the library's one output policy
(:func:`seahelm.output_files.check_output`): :func:`output_file` and :func:`output_dir` add
what the command line knows (the option's name, the path as typed -- a trailing slash --, the
command's ``--force`` and its name, the stores it must not write into), before any work.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import typer

from ..errors import ParameterError
from ..output_files import check_output, kind_for_suffix

#: The name of a result's HTML report: ``seahelm run --report`` and ``seahelm demo`` write it
#: beside ``result.nc``, ``seahelm report RESULT`` beside RESULT (the same page had two names:
#: ``report.html`` from ``run``, ``result.html`` from ``report``).
REPORT_NAME = "report.html"

#: Output directories the running command created (removed again, if still empty, when it
#: stops without finishing: an interrupted or failed run leaves no empty --out directory).
_created_dirs: list[Path] = []

#: The running command line's words as typed (an option's path loses a trailing slash when
#: it becomes a Path: ``-o kv.toml/`` must not be taken for the file ``kv.toml``).
_raw_args: list[str] = []

#: The running command's ``--force`` (:data:`ForceFlag`; set by :func:`handle_errors` from
#: the command's ``force`` argument), the default of :func:`output_file` and
#: :func:`output_dir`.
_force_state = {"on": False}


def output_dir(option: str, path: Path, names: tuple[str, ...] = (), *,
               reads: Iterable[Path] = (), force: bool | None = None) -> Path:
    """Check, before any work, that ``path`` is (or can be made) a writable directory and that
    each file to be written there (``names``) may be written (:func:`output_file`'s rule: not a
    directory, a file the command reads or a place inside a store; an existing file only if it
    is this command's own output of an earlier run, or with ``force``); returns ``path``.

    Raises
    ------
    ParameterError
        Naming the option and the path: an existing file, a parent that is a file, a directory
        that cannot be created or written, a target that is a directory, an input of the
        command, a place inside a sweep store (:func:`protect_inputs`), an existing file of
        another kind or not seahelm's without ``force``
        (:func:`seahelm.output_files.check_output`).
    """
    if path.exists() and not path.is_dir():
        raise ParameterError(f"`{option}` must be a directory, but {path} is a file")
    force = _force_state["on"] if force is None else force
    reads = tuple(reads)
    protect_inputs(option, path, reads)
    for name in names:
        protect_inputs(option, path / name, reads)
    for name in names:
        if (path / name).is_dir():
            raise ParameterError(f"`{option}`: {path / name} is a directory; it would be "
                                 "overwritten by a file")
        kind = kind_for_suffix(name)
        # a figure at the command's own name drawn by matplotlib is its earlier output (the
        # figures of seahelm before the output policy carry no seahelm metadata)
        old_own = kind == "figure" and _matplotlib_figure(path / name)
        check_output(path / name, kind, reads=reads, force=force or old_own, option=option,
                     force_word="--force")
    _writable_directory(option, path)
    return path


def output_file(option: str, path: Path, kind: str, *, reads: Iterable[Path] = (),
                force: bool | None = None) -> Path:
    """Check, before any work, that ``path`` can be written as a file of ``kind`` (a key of
    :data:`seahelm.output_files.KINDS`): not a directory (nor given with a trailing slash),
    its directory existing (or creatable) and writable, none of the files the command reads
    (``reads``), not inside a store (:func:`protect_inputs`), and an existing file only if it
    is this command's own output of an earlier run or with ``force`` (default: the command's
    ``--force``) (:func:`seahelm.output_files.check_output`); returns ``path``."""
    force = _force_state["on"] if force is None else force
    reads = tuple(reads)
    raw = _raw_value(path)
    if raw.endswith("/"):
        check_output(raw, kind, option=option)  # (refused: names a directory)
    if path.is_dir():
        raise ParameterError(f"`{option}` must be a file name, but {path} is a directory")
    if path.parent.exists() and not path.parent.is_dir():
        raise ParameterError(f"`{option}`: {path.parent} is a file, not a directory")
    protect_inputs(option, path, reads)
    check_output(path, kind, reads=reads, force=force, option=option, force_word="--force",
                 command=command_path())
    _writable_directory(option, path.parent)
    return path


def command_path() -> str | None:
    """The running command as a user types it (``"seahelm identify nomoto"``), or None."""
    ctx = _current_context()
    if ctx is None:
        return None
    names = []
    while ctx.parent is not None:
        names.append(ctx.info_name)
        ctx = ctx.parent
    return " ".join(["seahelm", *reversed(names)])


def _matplotlib_figure(path: Path) -> bool:
    try:
        with path.open("rb") as fh:
            return b"atplotlib" in fh.read(65536)
    except OSError:
        return False


def write_ship_file(ship: Any, out: Path, option: str = "--out") -> Path:
    """Write a ship file a command made (``ship scale``, ``ship estimate``, ``identify``) by
    the output policy (:func:`seahelm.output_files.write_output`: checked again as it is
    written, so a file another program put there meanwhile is not replaced; the command's own
    output of an earlier run -- a seahelm ship file -- is, and so is what ``--force`` approved
    in :func:`output_file`)."""
    from ..output_files import write_output
    from ..ships.writing import ship_to_toml

    from ..output_files import written_by_line

    command = command_path()
    text = ship_to_toml(ship) + (written_by_line(command) if command else "")
    return write_output(out, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"), "toml",
                        option=option, force_word="--force", command=command)


def write_scenario_file(out: Path, ship: str, scenario: Any, comment: str = "",
                        option: str = "--out") -> Path:
    """Write the scenario a tuning command made (``autopilot tune``, ``dp tune``) by the output
    policy, as :func:`write_ship_file` does a ship file.

    Parameters
    ----------
    out : Path
        The scenario file (checked before the work by :func:`output_file`).
    ship : str
        The ship as the command was given it: a ship file is named by its path from the
        scenario's folder (a scenario's paths are its own: the pair stays valid where it is
        copied together), a catalog name as it is.
    scenario : callable
        ``scenario(ship_ref)``: the scenario mapping naming the ship by ``ship_ref``
        (:meth:`~seahelm.analysis.steering.autopilot_tuning.AutopilotTuning.scenario`).
    comment : str, optional
        Its first ``#`` lines (the tuning's ``comment()``).
    option : str, optional
        The command's option for the file, named in its errors.

    Returns
    -------
    Path
    """
    from ..analysis.steering.autopilot_tuning import scenario_toml
    from ..output_files import write_output, written_by_line

    ship_ref = (os.path.relpath(Path(ship).resolve(), Path(out).resolve().parent)
                if Path(ship).suffix == ".toml" else ship)
    command = command_path()
    text = scenario_toml(scenario(ship_ref), comment)
    text += written_by_line(command) if command else ""
    return write_output(out, lambda tmp: Path(tmp).write_text(text), "toml", option=option,
                        force_word="--force", command=command)


def _raw_value(path: Path) -> str:
    """``path`` as the command line gave it: with its trailing slash, if it had one."""
    for word in _raw_args:
        value = word.partition("=")[2] if word.startswith("-") and "=" in word else word
        if value.endswith("/") and value.rstrip("/") and Path(value.rstrip("/")) == path:
            return value
    return str(path)


#: Files that mark a directory as a Zarr store (a seahelm sweep store is one): nothing of a
#: command's output may be written inside one.
STORE_MARKERS = ("zarr.json", ".zgroup", ".zarray")


def store_containing(path: Path) -> Path | None:
    """The Zarr store (a sweep store) that ``path`` is, or lies inside; None if there is none.

    Parameters
    ----------
    path : pathlib.Path
        A file or directory (need not exist).

    Returns
    -------
    pathlib.Path or None
    """
    resolved = path.resolve()
    found = None  # the outermost: an array inside a store is part of the store
    for candidate in (resolved, *resolved.parents):
        if candidate.is_dir() and any((candidate / m).is_file() for m in STORE_MARKERS):
            found = candidate
    return found


def protect_inputs(option: str, target: Path, reads: Iterable[Path] = ()) -> None:
    """Refuse an output that would destroy what the user has: one of the files the command
    reads, a place inside a store the command reads, or a place inside any store.

    Parameters
    ----------
    option : str
        The output option, for the message (``--out``).
    target : pathlib.Path
        What would be written (symbolic links are followed: a link to an input is the input).
    reads : iterable of pathlib.Path
        The files and stores the command reads.

    Raises
    ------
    ParameterError
        Naming the option, the target and what it would destroy.
    """
    try:
        t = target.resolve()
    except RuntimeError:  # (Python's word for a symbolic-link loop)
        raise ParameterError(f"`{option}` {target} is a loop of symbolic links") from None
    for read in reads:
        r = Path(read).resolve()
        if t == r:
            same = "" if Path(read) == target else f" ({read})"
            raise ParameterError(
                f"`{option}` {target} is a file this command reads{same}: writing it would "
                "destroy it; choose another path")
        if r.is_dir() and r in t.parents:
            raise ParameterError(
                f"`{option}` {target} is inside {read}, which this command reads: writing "
                "there would corrupt it; choose a path outside it")
    if target.is_symlink() and not target.is_dir():  # (a linked directory is written into)
        raise ParameterError(
            f"`{option}` {target} is a symbolic link (to {os.readlink(target)}): the file "
            "written would replace the link; give the path of the file itself")
    if target.exists() and not target.is_file() and not target.is_dir():
        raise ParameterError(
            f"`{option}` {target} is not a regular file (a device, a FIFO or a socket): "
            "writing it would replace it; choose a file path")
    store = store_containing(t)
    if store is not None:
        raise ParameterError(
            f"`{option}` {target} is inside the store {store}: writing there would corrupt "
            "it; choose a path outside it")


def _writable_directory(option: str, directory: Path) -> None:
    """Create ``directory`` if needed (remembered: :func:`remove_created_dirs`) and check that
    a file can be written in it."""
    missing = [p for p in (directory, *directory.parents) if not p.exists()]
    try:
        directory.mkdir(parents=True, exist_ok=True)
        _created_dirs.extend(missing)  # (deepest first)
    except OSError as exc:
        raise ParameterError(f"`{option}`: cannot create the directory {directory} "
                             f"({exc.strerror or exc})") from None
    _check_writable(option, directory)


def remove_created_dirs() -> None:
    """Remove the directories this command created that are still empty (deepest first)."""
    for path in list(_created_dirs):
        try:
            path.rmdir()
        except OSError:  # (not empty, or gone: kept as it is)
            pass
    _created_dirs.clear()


def _check_writable(option: str, directory: Path) -> None:
    try:  # (os.access is True for root everywhere; a real file tells)
        fd, probe = tempfile.mkstemp(dir=directory, prefix=".seahelm-probe-")
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise ParameterError(f"`{option}`: cannot write in {directory} "
                             f"({exc.strerror or exc})") from None


def check_figure_suffix(option: str, path: Path) -> None:
    """A figure file name whose suffix matplotlib can write (checked before any work)."""
    from ..plotting.save import check_figure_path

    try:
        check_figure_path(path)
    except ParameterError as exc:
        raise ParameterError(f"`{option}`: {exc}") from None


def input_file(option: str, path: Path) -> Path:
    """Check that ``path`` is an existing regular file (not a directory, FIFO or device)."""
    if not path.exists():
        raise ParameterError(f"`{option}`: no such file: {path}")
    if path.is_dir():
        raise ParameterError(f"`{option}`: {path} is a directory, not a file")
    if not path.is_file():
        raise ParameterError(f"`{option}`: {path} is not a regular file")
    return path


def _current_context() -> Any:
    """The running command's click context (None outside a command)."""
    import importlib

    # the click typer runs on: click itself (typer < 0.26) or typer's vendored copy
    core = next(c.__module__ for c in typer.Context.__mro__ if c.__name__ == "Context"
                and c.__module__.endswith(".core"))
    return importlib.import_module(core[:-len("core")] + "globals").get_current_context(
        silent=True)
