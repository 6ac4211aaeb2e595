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
from collections.abc import Callable
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
        except SeahelmError as exc:
            fail(_one_line(exc))
        except Exception as exc:  # noqa: BLE001 - the CLI's last line of defence
            if os.environ.get("SEAHELM_DEBUG"):
                raise
            fail(f"{type(exc).__name__}: {_one_line(exc)} (set SEAHELM_DEBUG=1 for a traceback)")

    return wrapper  # type: ignore[return-value]


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
