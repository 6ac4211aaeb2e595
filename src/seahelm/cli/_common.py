"""Shared pieces of the ``seahelm`` command: error handling, JSON output, consoles.

Exit codes: 0 success, 2 bad input (one-line reason on stderr), 1 any other failure, 3 runs
diverged, 4 a compliance check that ran and did not pass (``seahelm imo --check``).
``--json`` prints exactly one JSON object on stdout and nothing else there, also on an error:
``{"error": "...", "exit_code": 2}`` (the one-line reason is on stderr as well).

Bad input is reported the same way whether a command finds it (:func:`handle_errors`) or the
command-line parser does (an unknown option, a missing argument, a value that is not a
number or not one of an option's choices): every ``typer.Typer`` of the CLI is built with
``cls=OneLineErrors``, which prints the parser's message as one ``error: `` line instead of
typer's usage box.
"""

from __future__ import annotations

import errno
import functools
import json
import math
import os
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, NoReturn, TypeVar

import numpy as np
import typer
from rich.console import Console
from rich.text import Text
from typer.core import TyperGroup

from .. import stop_request
from ..errors import ParameterError, SeahelmError
from ..output_files import approved_outputs
from ._outputs import (  # noqa: F401 - the commands import the output checks from here
    STORE_MARKERS,
    _created_dirs,
    _current_context,
    _force_state,
    _raw_args,
    _writable_directory,
    check_figure_suffix,
    command_path,
    input_file,
    output_dir,
    output_file,
    protect_inputs,
    remove_created_dirs,
    store_containing,
    write_scenario_file,
    write_ship_file,
)
from ._tables import FitTables

F = TypeVar("F", bound=Callable[..., Any])

#: Human output goes to stdout unless --json, where it goes to stderr. Outside a terminal (a
#: pipe, a file) rich takes 80 columns (or $COLUMNS); every table printed on either console
#: is fitted to that width or printed as key/value lines (:mod:`seahelm.cli._tables`).
console = Console()
err_console = Console(stderr=True)
for _console in (console, err_console):
    _console.push_render_hook(FitTables(_console))

#: OS errors that are the machine's failure, not bad input (exit 1): a full disk, a quota, an
#: I/O error. Every file is written to a temporary file and renamed, so nothing half-written
#: is left.
ENVIRONMENT_ERRNOS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.EFBIG})

EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2
#: Everything ran and was written, but some runs diverged (their time, state and reason are in
#: the results and the summary).
EXIT_DIVERGED = 3
#: Everything ran, and the ship does not comply (``seahelm imo --check``: a criterion failed).
#: Opt-in: a verdict is the output of a command that worked, not a failure of the command.
EXIT_NONCOMPLIANT = 4
#: Stopped by Ctrl-C (128 + SIGINT, as a shell reports it).
EXIT_INTERRUPTED = 130

#: Whether the running command line asked for ``--json`` and whether its one JSON object has
#: been printed (set by the root :class:`OneLineErrors` when it parses a command line).
_json_state = {"wanted": False, "printed": False}



def _json_error(message: str, code: int) -> None:
    """With ``--json``, the error as the command's one JSON object on stdout."""
    if _json_state["wanted"] and not _json_state["printed"]:
        print_json({"error": message, "exit_code": code})


def exit_if_diverged(n_failed: int) -> None:
    """Exit with :data:`EXIT_DIVERGED` after a command's output when runs diverged.

    Parameters
    ----------
    n_failed : int
        How many runs did not end ok.
    """
    if n_failed:
        raise typer.Exit(EXIT_DIVERGED)


#: The one ``--json`` flag of every command (stdout then holds one JSON object, nothing else).
JsonFlag = Annotated[bool, typer.Option("--json", help="Print one JSON object on stdout.")]

#: The one ``--force`` flag of every command that writes files (:func:`output_file`).
ForceFlag = Annotated[bool, typer.Option(
    "--force", help="Replace an existing output file that is not this command's own output "
    "of an earlier run (a file the command reads is never replaced).")]


def fail_bad_input(message: str) -> NoReturn:
    """Print a one-line reason on stderr (and, with ``--json``, as a JSON object on stdout)
    and exit with code 2."""
    _json_error(message, EXIT_BAD_INPUT)
    err_console.print(Text.assemble(("error: ", "bold red"), message), highlight=False,
                      soft_wrap=True)
    raise typer.Exit(EXIT_BAD_INPUT)


def fail(message: str) -> NoReturn:
    """Print a one-line reason on stderr (and, with ``--json``, as a JSON object on stdout)
    and exit with code 1."""
    _json_error(message, EXIT_FAILURE)
    err_console.print(Text.assemble(("failed: ", "bold red"), message), highlight=False,
                      soft_wrap=True)
    raise typer.Exit(EXIT_FAILURE)


#: click's base exception as typer uses it: click's own (typer < 0.26) or typer's vendored copy.
_ClickException: type[Exception] = next(
    c for c in typer.BadParameter.__mro__ if c.__name__ == "ClickException")


def usage_error_message(exc: Exception) -> str:
    """The one-line text of a command-line parser error (``click.UsageError`` and the like).

    click's message names the option and, for a bad choice, the value and the valid choices;
    where typer's type check hides the value (``--h3 abc``: "Input should be a valid number")
    the value is appended (``, got 'abc'``), and where the error has a command the line ends
    with where its help is (``(see 'seahelm waves spectrum --help')``).
    """
    message = exc.format_message()  # type: ignore[attr-defined]
    # typer >= 0.29 checks values with pydantic, whose message for a check that raised
    # ValueError (a bad choice) starts "Value error, "
    message = message.replace(": Value error, ", ": ", 1)
    errors = getattr(exc.__cause__, "errors", None)
    if callable(errors):
        try:
            value = errors()[0]["input"]
        except Exception:  # noqa: BLE001 - no value to show is fine
            value = None
        if isinstance(value, str) and repr(value) not in message:
            message = f"{message.rstrip('.')}, got {value!r}"
    ctx = getattr(exc, "ctx", None)
    if ctx is not None:
        message = f"{message.rstrip().rstrip('.')} (see '{ctx.command_path} --help')"
    return _one_line(message)


def _report_parser_error(exc: Exception) -> NoReturn:
    """Exit on a click exception: code 2 (usage errors) with one ``error:`` line, any other
    code with one ``failed:`` line."""
    if type(exc).__name__ == "NoArgsIsHelpError":  # `seahelm` alone: the help on stdout, exit 2
        sys.stdout.write(exc.ctx.get_help() + "\n")  # type: ignore[attr-defined]
        raise typer.Exit(EXIT_BAD_INPUT)
    code = getattr(exc, "exit_code", EXIT_FAILURE)
    if code == EXIT_BAD_INPUT:
        fail_bad_input(usage_error_message(exc))
    _json_error(usage_error_message(exc), code)
    err_console.print(Text.assemble(("failed: ", "bold red"), usage_error_message(exc)),
                      highlight=False, soft_wrap=True)
    raise typer.Exit(code)


class OneLineErrors(TyperGroup):
    """A typer group whose parser errors are one ``error: `` line on stderr and exit code 2.

    typer prints click's usage errors (unknown option, missing argument, a value that is not
    a number or not one of the choices) as the usage, a hint and a boxed message. Options are
    parsed when a group or command makes its context, so the group catches click's exceptions
    there (its own options) and in ``invoke`` (its subcommands'), and reports them as
    :func:`fail_bad_input` reports the commands' own checks. Use it for every app:
    ``typer.Typer(cls=OneLineErrors, ...)`` (mounted sub-apps keep their ``cls``).

    Its help, and its commands', is plain text as written (:func:`~seahelm.cli._help.plain_help`:
    no rich markup, metavars ``FLOAT``/``PATH``, none after flags).
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        from ._help import plain_help

        plain_help(self)

    def make_context(self, info_name: str | None, args: list[str], parent: Any = None,
                     **extra: Any) -> Any:
        if parent is None:  # a new command line: does it ask for one JSON object?
            words = args[:args.index("--")] if "--" in args else args
            _json_state.update(wanted="--json" in words, printed=False)
            _raw_args[:] = list(args)
        try:
            return super().make_context(info_name, args, parent=parent, **extra)
        except _ClickException as exc:
            _report_parser_error(exc)

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except _ClickException as exc:
            _report_parser_error(exc)


def handle_errors(func: F) -> F:
    """Decorator for command functions: bad input -> exit 2, other seahelm errors -> exit 1."""

    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        _created_dirs.clear()
        _shown_warnings.clear()
        _force_state["on"] = bool(kwargs.get("force", False))
        done = False
        try:
            with warnings.catch_warnings(), approved_outputs():
                warnings.simplefilter("default")
                warnings.showwarning = _show_warning  # one line each: warning: ...
                out = func(*args, **kwargs)
                done = True
                return out
        except typer.Exit as exc:
            done = exc.exit_code == 0
            raise
        except KeyboardInterrupt:
            stop_request.clear()  # (handled here: not raised again by a later check)
            message = ("Ctrl-C before the end; what was written before it is complete and "
                       "nothing half-written is left (a sweep resumes from its store with the "
                       "same command)")
            _json_error(f"interrupted: {message}", EXIT_INTERRUPTED)
            err_console.print(Text.assemble(("interrupted: ", "bold red"), message),
                              highlight=False, soft_wrap=True)
            raise typer.Exit(EXIT_INTERRUPTED) from None
        except (ParameterError, ValueError, FileNotFoundError, KeyError) as exc:
            fail_bad_input(cli_message(exc))
        except OSError as exc:
            where = f": {exc.filename}" if getattr(exc, "filename", None) else ""
            text = (f"{exc.strerror}{where}" if exc.strerror
                    else _one_line(exc) if str(exc) else f"{type(exc).__name__}{where}")
            if exc.errno in ENVIRONMENT_ERRNOS:  # the machine failed, not the input: exit 1
                fail(text)
            fail_bad_input(text)  # a path the user gave: exists, not a directory, no access
        except SeahelmError as exc:
            fail(_one_line(exc))
        except Exception as exc:  # noqa: BLE001 - the CLI's last line of defence
            if os.environ.get("SEAHELM_DEBUG"):
                raise
            fail(f"{type(exc).__name__}: {_one_line(exc)} (set SEAHELM_DEBUG=1 for a traceback)")
        finally:
            if not done:
                remove_created_dirs()

    return wrapper  # type: ignore[return-value]


#: The warnings this command has printed (a sweep's 60 runs warned the same line 60 times).
_shown_warnings: set[str] = set()


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                  file: Any = None, line: str | None = None) -> None:
    text = as_option(_one_line(Exception(str(message))))
    from ..sweep.store import is_markers_warning

    if is_markers_warning(text):  # (the store's own markers: see sweep.store._quiet)
        return
    if text in _shown_warnings:  # the same words again (another run, chunk or sample)
        return
    _shown_warnings.add(text)
    err_console.print(Text.assemble(("warning: ", "yellow"), text), highlight=False,
                      soft_wrap=True)


def _command_options() -> dict[str, str]:
    """The running command's options by parameter name (``{"t_final": "--t-final"}``)."""
    ctx = _current_context()
    if ctx is None:
        return {}
    return {p.name: p.opts[0] for p in ctx.command.params
            if getattr(p, "opts", None) and p.opts[0].startswith("--")}


def cli_message(exc: BaseException) -> str:
    """An error as one line in the command's words.

    A :class:`~seahelm.errors.ParameterError` about a keyword of the running command's function
    is said about its option, from the error's ``field`` (``--t-final must be > 0 [s]``), not
    from its text; other argument names quoted in the prose are then given as options too
    (:func:`as_option`).

    Parameters
    ----------
    exc : BaseException
        The error.

    Returns
    -------
    str
    """
    field = getattr(exc, "field", None) if isinstance(exc, ParameterError) else None
    if field:
        head = field.partition(".")[0].partition("[")[0]
        option = _command_options().get(head)
        if option is not None:
            reason = exc.reason
            sep = "" if reason.startswith((":", ",", " ")) else " "
            return as_option(_one_line(Exception(
                f"`{option}{field[len(head):]}`{sep}{reason}")))
    return as_option(_one_line(exc))


def as_option(message: str) -> str:
    """Argument names quoted in a message's prose ("give a faster approach (`speed` or `rps`)")
    given as the running command's options ("(`--speed` or `--rps`)"): the user typed options,
    not Python keywords. (Which option an error is *about* comes from its field,
    :func:`cli_message`.)

    Parameters
    ----------
    message : str
        One line.

    Returns
    -------
    str
    """
    import re

    options = _command_options()
    if not options:
        return message
    return re.sub(r"`(\w+)`", lambda m: f"`{options.get(m.group(1), m.group(1))}`", message)


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
    _json_state["printed"] = True


#: Environment variable: seconds a command works before its progress bar appears (default 1;
#: ``0`` shows it at the first progress, e.g. to see it on a fast machine).
PROGRESS_DELAY_ENV = "SEAHELM_PROGRESS_DELAY"


def progress_delay() -> float:
    """The seconds before a progress bar appears: :data:`PROGRESS_DELAY_ENV`, else 1.

    Raises
    ------
    ParameterError
        If the variable is set to something other than a finite number of seconds >= 0.
    """
    text = os.environ.get(PROGRESS_DELAY_ENV, "").strip()
    if not text:
        return 1.0
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not math.isfinite(value) or value < 0:
        raise ParameterError(f"{PROGRESS_DELAY_ENV}={text!r}: must be a number of seconds >= 0")
    return value


class ProgressBar:
    """A progress callback ``(done, total)`` drawing a transient bar on stderr once the work has
    taken ``delay`` seconds (none if it finishes first); ``counted`` shows "done/total" instead
    of a percentage. ``delay`` defaults to :data:`PROGRESS_DELAY_ENV` (seconds, ``0``: at the
    first progress) or 1 s."""

    def __init__(self, label: str, *, enabled: bool = True, delay: float | None = None,
                 counted: bool = False) -> None:
        self.label = label
        self.enabled = enabled
        self.delay = progress_delay() if delay is None else delay
        self.counted = counted
        self.start = time.perf_counter()
        self.bar: Any = None
        self.task: Any = None

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            if time.perf_counter() - self.start < self.delay or done >= total:
                return
            from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn,
                                       TimeRemainingColumn)

            amount = MofNCompleteColumn() if self.counted else TextColumn(
                "{task.percentage:>3.0f}%")
            self.bar = Progress(TextColumn("{task.description}"), BarColumn(), amount,
                                TimeRemainingColumn(), console=err_console, transient=True)
            self.bar.start()
            self.task = self.bar.add_task(self.label, total=total)
        self.bar.update(self.task, completed=done)

    def close(self) -> None:
        """Remove the bar (if one was drawn)."""
        if self.bar is not None:
            self.bar.stop()
