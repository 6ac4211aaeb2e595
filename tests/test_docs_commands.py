"""Every command of the README and of the getting-started page runs as written, in order, in a
fresh directory (issue 44).

The commands are taken from the files themselves (the README's fenced blocks, the page's
literal blocks): every line that starts with ``seahelm`` or ``python -m seahelm``, with its
``\\`` continuation lines. They run in groups (:func:`command_groups`): a command that reads a
file an earlier one writes (``zz/zigzag-runs.nc``, ``my.toml``) runs after it, in the same
directory, in the files' order; commands that share nothing are separate tests, so a parallel
run balances them (one test per file took 142 s and serialised the end of the run). Each
group runs in a directory of its own that holds only ``examples/`` (a link to the
repository's, as a fresh clone has it), through ``bash`` with ``seahelm`` and ``python`` on
``PATH`` meaning this interpreter's seahelm, so redirections (``> my.toml``) and ``&&`` work as
they do for a reader. A command that fails names the file, the line and the output.

The fast tests check the README as a front page: its size, its picture and its links.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
GETTING_STARTED = ROOT / "docs" / "getting-started.rst"

_COMMAND = re.compile(r"^(seahelm|python -m seahelm)(\s|$)")


def _join_continuations(lines: list[tuple[int, str]]) -> list[tuple[int, str]]:
    """``(line number, text)`` of each command, ``\\``-continued lines joined."""
    out: list[tuple[int, str]] = []
    pending: tuple[int, str] | None = None
    for number, text in lines:
        if pending is not None:
            pending = (pending[0], pending[1] + " " + text.strip())
        elif _COMMAND.match(text.strip()):
            pending = (number, text.strip())
        else:
            continue
        if pending[1].endswith("\\"):
            pending = (pending[0], pending[1][:-1].rstrip())
        else:
            out.append(pending)
            pending = None
    return out


def markdown_commands(text: str) -> list[tuple[int, str]]:
    """The commands in a Markdown file's fenced code blocks (none of ``toml``, ``python``)."""
    lines, inside, language = [], False, ""
    for number, line in enumerate(text.splitlines(), 1):
        fence = re.match(r"^```(\w*)", line)
        if fence:
            inside, language = (not inside), fence.group(1)
            continue
        if inside and language in ("", "bash", "sh", "console", "shell"):
            lines.append((number, line))
    return _join_continuations(lines)


def rest_commands(text: str) -> list[tuple[int, str]]:
    """The commands in a reST file's literal blocks (``::`` and ``code-block:: bash``)."""
    lines, inside, indent = [], False, 0
    raw = text.splitlines()
    for number, line in enumerate(raw, 1):
        if inside:
            if line.strip() and (len(line) - len(line.lstrip())) <= indent:
                inside = False
            else:
                lines.append((number, line))
                continue
        stripped = line.rstrip()
        if (stripped.endswith("::") and not stripped.lstrip().startswith(".. ")) or re.match(
                r"^\s*\.\. code-block:: (bash|console|shell|sh)\s*$", stripped):
            inside, indent = True, len(line) - len(line.lstrip())
    return _join_continuations(lines)


def test_the_extractors_find_commands_and_their_continuations():
    md = ("text\n```\nseahelm a --x 1 \\\n    --y 2   # c\nmake demo\n```\n```toml\n"
          "seahelm = 1\n```\n```\npython -m seahelm --help\n```\n")
    assert markdown_commands(md) == [(3, "seahelm a --x 1 --y 2   # c"),
                                     (11, "python -m seahelm --help")]
    rst = ("A tour::\n\n    seahelm b\n    seahelm c \\\n        --z\n\nback to text\n"
           "seahelm not-a-command\n\n.. code-block:: toml\n\n    seahelm = 2\n")
    assert rest_commands(rst) == [(3, "seahelm b"), (4, "seahelm c --z")]


def test_the_files_hold_the_commands_a_newcomer_needs():
    readme = [c for _, c in markdown_commands(README.read_text(encoding="utf-8"))]
    assert any(c.startswith("seahelm ship estimate") for c in readme)
    assert any(c.startswith("seahelm imo cargo.toml") for c in readme)
    assert any(c.startswith("seahelm report") for c in readme)
    page = [c for _, c in rest_commands(GETTING_STARTED.read_text(encoding="utf-8"))]
    assert len(page) >= 25, page
    # the four that could not run as written (issue 44): their inputs are made earlier now
    for prefix in ("seahelm identify nomoto", "seahelm identify mmg", "seahelm sweep",
                   "seahelm report"):
        assert any(c.startswith(prefix) for c in page), prefix


# ------------------------------------------------------------------------------------------
# the README as a front page
# ------------------------------------------------------------------------------------------
def test_the_readme_is_a_front_page():
    text = README.read_text(encoding="utf-8")
    assert len(text.encode()) <= 7000, len(text.encode())  # was 50,846 bytes
    headings = re.findall(r"^## (.+)$", text, flags=re.MULTILINE)
    assert headings == ["Two commands", "Your own ship, in five lines",
                        "What it is checked against", "Where to go next"], headings
    assert "make demo" in text and "make test" in text
    own_ship = text.split("## Your own ship")[1].split("##")[0]
    assert len(re.findall(r"^seahelm ", own_ship, flags=re.MULTILINE)) == 5


def test_the_readme_states_what_an_estimate_achieves_ship_by_ship():
    """The README cited the KVLCC2's 5 % alone; the own-ship page has the Mariner's 4.1 L
    against 6.4 L. Both (and the advance) are on the front page, with the page's numbers."""
    text = README.read_text(encoding="utf-8")
    page = (ROOT / "docs" / "guide" / "own-ship.rst").read_text(encoding="utf-8")
    for number in ("3.27", "3.12", "3.73", "3.08", "4.1 L", "6.4 L", "13.0", "7.8"):
        assert number in text and number in page, number
    assert "+21 %" in text and "+5 %" in text and "+28 %" in text


def test_the_readme_picture_and_links_exist():
    text = README.read_text(encoding="utf-8")
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert len(images) == 1
    picture = ROOT / images[0]
    assert picture.is_file() and picture.stat().st_size < 150_000
    links = [t for t in re.findall(r"(?<!!)\[[^\]]*\]\(([^)]+)\)", text)
             if not t.startswith("http")]
    assert links
    for target in links:
        assert (ROOT / target).is_file(), target


def test_the_readme_demo_output_is_what_the_demo_prints(tmp_path):
    """The README showed ``heading_deg`` where the demo prints ``final heading [deg]``: every
    row it shows is a row of the table ``seahelm demo`` prints today, with the same value."""
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    row = r"^\s*│ (.+?)\s+│\s+(\S+) │$"
    result = CliRunner().invoke(app, ["demo", "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    printed = re.findall(row, result.stdout, flags=re.MULTILINE)
    readme = README.read_text(encoding="utf-8").split("prints (abridged)")[1].split("```")[1]
    shown = re.findall(row, readme, flags=re.MULTILINE)
    assert len(shown) >= 4 and ("final heading [deg]", "20.022") in shown, shown
    assert set(shown) <= set(printed), set(shown) - set(printed)
    # the getting-started page shows the whole table
    page = GETTING_STARTED.read_text(encoding="utf-8").split("seahelm demo ")[1]
    assert re.findall(row, page.split("seahelm inspect")[0], flags=re.MULTILINE) == printed


# ------------------------------------------------------------------------------------------
# every command runs, in order, in a fresh directory
# ------------------------------------------------------------------------------------------
def _shell_env(tmp: Path) -> dict[str, str]:
    bin_dir = tmp / "_bin"
    bin_dir.mkdir()
    # scripts, not links: a link to a venv's python outside the venv loses the venv
    for name, args in (("seahelm", " -m seahelm"), ("python", "")):
        (bin_dir / name).write_text(
            f"#!/bin/sh\nexec {shlex.quote(sys.executable)}{args} \"$@\"\n")
        (bin_dir / name).chmod(0o755)
    env = dict(os.environ, MPLBACKEND="Agg", COLUMNS="100")
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    src = str(ROOT / "src")
    env["PYTHONPATH"] = src + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def _run_in_order(path: Path, commands: list[tuple[int, str]], tmp: Path) -> list[str]:
    work = tmp / "fresh"
    work.mkdir()
    (work / "examples").symlink_to(ROOT / "examples")
    env = _shell_env(tmp)
    timings = []
    for number, command in commands:
        start = time.perf_counter()
        proc = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=work, env=env,
                              capture_output=True, text=True, timeout=900)
        took = time.perf_counter() - start
        timings.append(f"{took:6.1f} s  {path.name}:{number}  {command}")
        assert proc.returncode == 0, (
            f"{path.name}:{number}: `{command}` exited {proc.returncode} after {took:.1f} s\n"
            f"--- stdout\n{proc.stdout[-3000:]}\n--- stderr\n{proc.stderr[-3000:]}")
    return timings


#: What a command writes without naming it (its default output), by the command's start.
IMPLICIT_OUTPUTS = {"seahelm demo": "seahelm-out"}
#: Options whose value is a file or directory the command writes (``>``: a redirection).
OUTPUT_OPTIONS = ("--out", "-o", "--store", "--plot", ">")
#: Commands that take a second or two: a group that reads what one writes runs it again
#: rather than joining every other group that reads it (the README's ``cargo.toml`` feeds
#: three commands that share nothing else).
CHEAP_PREREQUISITES = ("seahelm ship estimate ", "seahelm ship show ")
_PATH = re.compile(r"/|\.(nc|toml|zarr|csv|png|html|json)$")


def command_files(command: str) -> tuple[set[str], set[str]]:
    """``(reads, writes)`` of a command: the first path component of each file or directory
    it names (``zz`` of ``zz/zigzag-runs.nc``), outputs being the values of
    :data:`OUTPUT_OPTIONS` and :data:`IMPLICIT_OUTPUTS`, inputs every other path but those in
    ``examples/`` (a fresh clone's)."""
    words = shlex.split(command, comments=True)
    reads, writes = set(), set()
    for before, word in zip(["", *words], words):
        if word.startswith("-") or not _PATH.search(word):
            continue
        (writes if before in OUTPUT_OPTIONS else reads).add(word.split("/", 1)[0])
    writes |= {out for start, out in IMPLICIT_OUTPUTS.items()
               if command == start or command.startswith(start + " ")}
    return reads - {"examples"}, writes


def command_groups(commands: list[tuple[int, str]]) -> list[list[tuple[int, str]]]:
    """``commands`` (in the file's order) in groups that share no file, each in that order.

    A command joins the group of the last earlier command that writes what it reads; one in
    :data:`CHEAP_PREREQUISITES` is copied into each group that reads its output instead. A
    command that reads a path no earlier command writes is an error (a new command's input
    needs its writer named in :data:`IMPLICIT_OUTPUTS`)."""
    parent = list(range(len(commands)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    copies: dict[int, set[int]] = {}
    files = [command_files(c) for _, c in commands]
    for j, (reads, _) in enumerate(files):
        for path in sorted(reads):
            writers = [i for i in range(j) if path in files[i][1]]
            if not writers:
                raise AssertionError(f"line {commands[j][0]}: `{commands[j][1]}` reads {path!r},"
                                     " which no earlier command writes")
            i = writers[-1]
            if commands[i][1].startswith(CHEAP_PREREQUISITES):
                copies.setdefault(j, set()).add(i)
            else:
                parent[find(j)] = find(i)
    members: dict[int, set[int]] = {}
    for j in range(len(commands)):
        members.setdefault(find(j), set()).add(j)
    for group in members.values():
        group |= {i for j in list(group) for i in copies.get(j, ())}
    # a cheap command whose output only others read runs in their groups alone
    needed = {i for c in copies.values() for i in c}
    groups = [sorted(g) for g in members.values()
              if not (len(g) == 1 and next(iter(g)) in needed)]
    return [[commands[i] for i in g] for g in sorted(groups)]


def _group_id(path: Path, group: list[tuple[int, str]]) -> str:
    """``README.md:imo-cargo.toml-out-imo``: the file and the group's first command (that
    is not a copied prerequisite), without ``seahelm`` and its comment, in up to 40
    characters of whole words."""
    first = next((c for _, c in group if not c.startswith(CHEAP_PREREQUISITES)), group[0][1])
    words = shlex.split(first, comments=True)[1:]
    words = words[2:] if words[:2] == ["-m", "seahelm"] else words
    slug = ""
    for part in re.sub(r"[^A-Za-z0-9.]+", "-", " ".join(words)).strip("-").split("-"):
        if slug and len(slug) + 1 + len(part) > 40:
            break
        slug = f"{slug}-{part}" if slug else part
    return f"{path.name}:{slug}"


def docs_command_groups() -> list[tuple[Path, list[tuple[int, str]], str]]:
    """``(file, group, id)`` of every group of the README's and the page's commands."""
    out = []
    for path, extract in ((README, markdown_commands), (GETTING_STARTED, rest_commands)):
        for group in command_groups(extract(path.read_text(encoding="utf-8"))):
            out.append((path, group, _group_id(path, group)))
    return out


def test_the_commands_are_grouped_by_the_files_they_share():
    commands = list(enumerate([
        "seahelm demo", "seahelm inspect seahelm-out/result.nc",
        "seahelm ship show x --toml > my.toml", "seahelm maneuver zigzag --ship x --out zz/",
        "seahelm maneuver turning --ship my.toml --out turn/",
        "seahelm identify nomoto zz/zigzag-runs.nc --plot fit.png",
        "seahelm identify mmg zz/z.nc turn/t.nc --ship my.toml -o identified.toml",
        "seahelm ship check my.toml", "seahelm run examples/a.toml --out a/", "seahelm models"],
        1))
    assert command_files(commands[4][1]) == ({"my.toml"}, {"turn"})
    assert command_files(commands[8][1]) == (set(), {"a"})
    assert [[n for n, _ in g] for g in command_groups(commands)] == [
        [1, 2], [3, 4, 5, 6, 7], [3, 8], [9], [10]]
    with pytest.raises(AssertionError, match="line 2: .* reads 'nowhere'"):
        command_groups([(1, "seahelm models"), (2, "seahelm inspect nowhere/result.nc")])
    # every command of both files runs, each once (but the cheap prerequisites)
    for path, extract in ((README, markdown_commands), (GETTING_STARTED, rest_commands)):
        commands = extract(path.read_text(encoding="utf-8"))
        grouped = [c for g in command_groups(commands) for c in g]
        assert set(grouped) == set(commands)
        assert len(grouped) == len(commands) + sum(
            grouped.count(c) - 1 for c in commands if c[1].startswith(CHEAP_PREREQUISITES))
    ids = [i for _, _, i in docs_command_groups()]
    assert len(set(ids)) == len(ids), ids
    assert len(ids) >= 20


try:
    _GROUPS = docs_command_groups()
except AssertionError as exc:  # (a command reads what no earlier one writes: one failing test)
    _GROUPS = [(None, str(exc), "a-command-reads-what-no-earlier-one-writes")]


@pytest.mark.slow
@pytest.mark.parametrize("path, group", [(p, g) for p, g, _ in _GROUPS],
                         ids=[i for _, _, i in _GROUPS])
def test_every_command_runs_as_written_in_order(path, group, tmp_path, capsys):
    if path is None:
        pytest.fail(group)
    timings = _run_in_order(path, group, tmp_path)
    with capsys.disabled():
        print("\n" + "\n".join(timings))
