"""Help text of the ``seahelm`` command, rendered as written.

typer's default help interprets rich markup, which eats any word in square brackets
(``[dask]``, ``[maneuver]``, units such as ``[m/s]``) and shows type labels of its own
(``<bool>`` after flags, ``{scenario}`` in the usage line). :func:`plain_help` is applied to
every command of the CLI by :class:`~seahelm.cli._common.OneLineErrors` (the class of every
app) and makes the help plain text:

- no markup: help strings and docstrings are shown as written (a help string written for
  rich, with ``\\[`` escapes, is shown without the backslash; RST literals and roles in a
  docstring, ````seahelm_kernel_*```` or ``:func:`simulate```, are shown as plain words);
- metavars that say what a value is: ``FLOAT``, ``INTEGER``, ``TEXT``, ``PATH``, the choices
  ``[a|b]``; nothing after a flag; an argument as its name in capitals (``SCENARIO``);
- a group without subcommands (a command written as a typer callback) shows no
  ``COMMAND [ARGS]...`` in its usage.
"""

from __future__ import annotations

import enum
import re
from pathlib import Path
from typing import Any, get_args, get_origin

#: Metavars by the annotated type of a value (typer's type descriptor).
_TYPE_METAVARS = {float: "FLOAT", int: "INTEGER", str: "TEXT", Path: "PATH"}

_RST_LITERAL = re.compile(r"``([^`]+)``")
_RST_ROLE = re.compile(r":[a-z]+:`~?([^`<]+?)(?:\s*<[^`]*>)?`")


def plain_text(text: str | None) -> str | None:
    """Help text as a person reads it: rich escapes removed, RST literals and roles as words.

    Parameters
    ----------
    text : str or None

    Returns
    -------
    str or None
    """
    if not text:
        return text
    text = text.replace("\\[", "[")
    text = _RST_ROLE.sub(lambda m: m.group(1).rsplit(".", 1)[-1] + (
        "()" if m.group(0).startswith(":func:") and not m.group(1).endswith(")") else ""),
        text)
    return _RST_LITERAL.sub(r"'\1'", text)


def _choice(value: Any) -> str:
    return str(value.value) if isinstance(value, enum.Enum) else str(value)


def value_metavar(param: Any) -> str | None:
    """What a parameter's value is (``FLOAT``, ``PATH``, ``[a|b]``), or None to keep typer's.

    Parameters
    ----------
    param : typer's parameter (with a ``type_descriptor``)

    Returns
    -------
    str or None
    """
    desc = getattr(param, "type_descriptor", None)
    if desc is None:  # (typer on click: click's own metavars already read FLOAT, PATH, ...)
        return None
    if getattr(desc, "is_choice", False) and desc.choices:
        return "[" + "|".join(_choice(c) for c in desc.choices) + "]"
    annotation = desc.annotation
    if get_origin(annotation) is list:
        annotation = get_args(annotation)[0]
    if isinstance(annotation, type) and issubclass(annotation, Path):
        return "PATH"
    return _TYPE_METAVARS.get(annotation)


def _tidy_param(param: Any) -> None:
    param.help = plain_text(getattr(param, "help", None))
    if getattr(param, "param_type_name", "") == "argument":
        if param.metavar is None:
            param.metavar = param.name.upper()
        if hasattr(param, "_usage_display_name"):  # a typer that writes {name} / [name]
            name = param.metavar
            if param.nargs != 1 and not name.endswith("..."):
                name += "..."
            usage = name if param.required or name.startswith("[") else f"[{name}]"
            param.get_usage_pieces = lambda ctx, usage=usage: [usage]
            param.display_type_rich = lambda ctx: None  # the name says it; no <path> beside
        return
    if getattr(param, "is_flag", False) or getattr(param, "count", False):
        if hasattr(param, "type_descriptor"):
            param.metavar = ""  # (typer's rich help would show <bool>)
        return
    if param.metavar is None:
        param.metavar = value_metavar(param)


def plain_help(command: Any) -> None:
    """Make ``command``'s help (and its subcommands', recursively) plain text as written.

    Idempotent: applying it twice changes nothing more.

    Parameters
    ----------
    command : click/typer command or group
    """
    if hasattr(command, "rich_markup_mode"):
        command.rich_markup_mode = None  # no markup: every word as written
    command.help = plain_text(command.help)
    command.short_help = plain_text(getattr(command, "short_help", None))
    for param in command.params:
        _tidy_param(param)
    commands = getattr(command, "commands", None)
    if commands is not None:
        if not commands:  # a command written as a group callback: no COMMAND to give
            command.subcommand_metavar = ""
        for sub in commands.values():
            plain_help(sub)
