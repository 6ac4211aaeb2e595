"""Every ``--help`` of the ``seahelm`` command renders every word (issue 36, item 1).

The whole command tree is walked: each command's and subcommand's help is rendered at 80
columns and compared with its docstring and its options' help strings. Square brackets are
where markup interpretation loses words (``[dask]``, ``[maneuver]``, units such as ``[m/s]``).
"""

from __future__ import annotations

import re

import pytest
import typer
from typer.testing import CliRunner

from seahelm.cli._help import plain_text
from seahelm.cli.main import app

runner = CliRunner()
ROOT = typer.main.get_command(app)


def _commands(command, path=()):
    yield path, command
    for name, sub in sorted(getattr(command, "commands", {}).items()):
        yield from _commands(sub, (*path, name))


COMMANDS = list(_commands(ROOT))
IDS = [" ".join(path) or "seahelm" for path, _ in COMMANDS]


def _squeeze(text: str) -> str:
    """Text without whitespace: the help is re-wrapped (also at hyphens)."""
    return re.sub(r"\s+", "", text)


def _bracketed(text: str | None) -> list[str]:
    return re.findall(r"\[[^\[\]]*\]", (text or "").partition("\f")[0])


def test_the_tree_is_walked():
    names = {" ".join(path) for path, _ in COMMANDS}
    assert {"sweep", "run", "cache", "compensate", "identify steady-turn",
            "waves figure", "maneuver turning"} <= names


@pytest.mark.parametrize(("path", "command"), COMMANDS, ids=IDS)
def test_help_renders_every_word(path, command):
    result = runner.invoke(app, [*path, "--help"], terminal_width=80)
    assert result.exit_code == 0, result.output
    out = result.output
    flat = _squeeze(out)
    texts = [command.help] + [getattr(p, "help", None) for p in command.params
                              if not getattr(p, "hidden", False)]
    for text in texts:
        for word in _bracketed(text):
            assert _squeeze(word) in flat, f"{word!r} lost from {' '.join(path)} --help"
    assert "\\[" not in out  # rich escapes shown
    assert "``" not in out and not re.search(r":(func|class|data|mod|meth):`", out)  # RST
    assert not re.search(r"<(bool|int|float|str|path|datetime)>", out)  # typer's type labels
    usage = out.partition("\n\n")[0]
    assert "{" not in usage, usage
    if getattr(command, "commands", None) == {}:  # a callback command: nothing to choose
        assert "COMMAND" not in usage


@pytest.mark.parametrize(("path", "command"), COMMANDS, ids=IDS)
def test_metavars_say_what_a_value_is(path, command):
    for param in command.params:
        metavar = param.metavar or ""
        assert not re.fullmatch(r"\{.*\}|<.*>", metavar), (path, param.name, metavar)
        if getattr(param, "is_flag", False):
            assert not metavar, (path, param.name, metavar)


@pytest.mark.parametrize(("args", "expected"), [
    (["sweep", "--help"], ["[batch]", "[maneuver]", "'seahelm[dask]'", "SCENARIO",
                           "--timeout FLOAT", "--store PATH"]),
    (["run", "--help"], ["a [maneuver] scenario writes", "Usage: seahelm run [OPTIONS] SCENARIO"]),
    (["identify", "steady-turn", "--help"], ["(a [s²/rad], b [s], c [s/rad])",
                                             "Minimum settled duration [s]."]),
    (["waves", "figure", "--help"], ["Realisation length [s]."]),
    (["cache", "--help"], ["'seahelm_kernel_*'"]),
    (["compensate", "--help"], ["Usage: seahelm compensate [OPTIONS]\n", "A1 ∈ [1, 8.5]"]),
])
def test_help_examples_of_the_issue(args, expected):
    out = runner.invoke(app, args, terminal_width=80).output
    for text in expected:
        assert text in out or _squeeze(text) in _squeeze(out), (text, out)
    for flag in ("--json", "--overwrite", "--help"):
        assert not re.search(rf"{flag} +<", out)


@pytest.mark.parametrize(("text", "expected"), [
    ("Units [m/s] \\[deg]", "Units [m/s] [deg]"),
    ("Files ``seahelm_kernel_*`` here", "Files 'seahelm_kernel_*' here"),
    ("See :func:`seahelm.simulate` and :class:`~seahelm.Ship`", "See simulate() and Ship"),
    (None, None),
])
def test_plain_text(text, expected):
    assert plain_text(text) == expected
    assert plain_text(plain_text(text)) == expected
