"""Shared pieces of the ``seahelm`` command: error handling, JSON output, consoles.

Exit codes: 0 success, 2 bad input (one-line reason on stderr), 1 any other failure.
``--json`` prints exactly one JSON object on stdout and nothing else there.
"""

from __future__ import annotations

import functools
import json
import math
import os
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, NoReturn, TypeVar

import numpy as np
import typer
from rich.console import Console
from rich.text import Text

from ..errors import ParameterError, SeahelmError

F = TypeVar("F", bound=Callable[..., Any])

#: Human output goes to stdout unless --json, where it goes to stderr.
console = Console()
err_console = Console(stderr=True)

EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2


#: The one ``--json`` flag of every command (stdout then holds one JSON object, nothing else).
JsonFlag = Annotated[bool, typer.Option("--json", help="Print one JSON object on stdout.")]


def fail_bad_input(message: str) -> NoReturn:
    """Print a one-line reason on stderr and exit with code 2."""
    err_console.print(Text.assemble(("error: ", "bold red"), message), highlight=False,
                      soft_wrap=True)
    raise typer.Exit(EXIT_BAD_INPUT)


def fail(message: str) -> NoReturn:
    """Print a one-line reason on stderr and exit with code 1."""
    err_console.print(Text.assemble(("failed: ", "bold red"), message), highlight=False,
                      soft_wrap=True)
    raise typer.Exit(EXIT_FAILURE)


def handle_errors(func: F) -> F:
    """Decorator for command functions: bad input -> exit 2, other seahelm errors -> exit 1."""

    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except typer.Exit:
            raise
        except (ParameterError, ValueError, FileNotFoundError, KeyError) as exc:
            fail_bad_input(_one_line(exc))
        except OSError as exc:  # a path the user gave: exists, not a directory, no permission
            where = f": {exc.filename}" if getattr(exc, "filename", None) else ""
            fail_bad_input(f"{exc.strerror or type(exc).__name__}{where}")
        except SeahelmError as exc:
            fail(_one_line(exc))
        except Exception as exc:  # noqa: BLE001 - the CLI's last line of defence
            if os.environ.get("SEAHELM_DEBUG"):
                raise
            fail(f"{type(exc).__name__}: {_one_line(exc)} (set SEAHELM_DEBUG=1 for a traceback)")

    return wrapper  # type: ignore[return-value]


def output_dir(option: str, path: Path, names: tuple[str, ...] = ()) -> Path:
    """Check, before any work, that ``path`` is (or can be made) a writable directory and that
    none of the files to be written there (``names``) is a directory; returns ``path``.

    Raises
    ------
    ParameterError
        Naming the option and the path: an empty path, an existing file, a parent that is a
        file, a directory that cannot be created or written, a target that is a directory.
    """
    if path.exists() and not path.is_dir():
        raise ParameterError(f"`{option}` must be a directory, but {path} is a file")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError(f"`{option}`: cannot create the directory {path} "
                             f"({exc.strerror or exc})") from None
    _check_writable(option, path)
    for name in names:
        if (path / name).is_dir():
            raise ParameterError(f"`{option}`: {path / name} is a directory; it would be "
                                 "overwritten by a file")
    return path


def output_file(option: str, path: Path) -> Path:
    """Check, before any work, that ``path`` can be written as a file: not empty, not a
    directory, its directory existing (or creatable) and writable; returns ``path``."""
    if path.is_dir():
        raise ParameterError(f"`{option}` must be a file name, but {path} is a directory")
    parent = path.parent
    if parent.exists() and not parent.is_dir():
        raise ParameterError(f"`{option}`: {parent} is a file, not a directory")
    try:
        parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError(f"`{option}`: cannot create the directory {parent} "
                             f"({exc.strerror or exc})") from None
    _check_writable(option, parent)
    return path


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


def _one_line(exc: BaseException) -> str:
    text = str(exc) or type(exc).__name__
    return " | ".join(line.strip() for line in text.splitlines() if line.strip())


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def print_json(obj: dict[str, Any]) -> None:
    """Write one JSON object to stdout (NaN/inf become null)."""
    sys.stdout.write(json.dumps(_jsonable(obj), indent=2, allow_nan=False) + "\n")
    sys.stdout.flush()
