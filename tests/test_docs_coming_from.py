"""The "Coming from MSS, PythonVehicleSimulator or shipmmg" page: every seahelm snippet on it
runs as written, and every row says what was measured (or "not compared yet").

Convention of the page (``docs/guide/coming-from.rst``): every code block is a
``.. code-block::`` with a ``:class:`` option, ``seahelm`` for seahelm's side (run here:
``python`` blocks in one fresh namespace each, ``console`` blocks line by line as
``python -m seahelm ...`` in a scratch directory), ``output`` for what the seahelm block just
before it prints (compared line by line with what it prints here) or ``theirs`` for the peer's
usage lines (not run: MATLAB, PythonVehicleSimulator and shipmmg are not installed here).
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "guide" / "coming-from.rst"

_BLOCK = re.compile(r"^\.\. code-block:: (?P<lang>\S+)\n(?P<options>(?:   :\w+:.*\n)*)\n"
                    r"(?P<body>(?:(?:   .*)?\n)+)", re.MULTILINE)


def _blocks(text: str) -> list[tuple[str, str, str, int]]:
    """``(language, class, code, line)`` of every ``code-block`` of the page."""
    found = []
    for m in _BLOCK.finditer(text):
        options = dict(re.findall(r"^   :(\w+):\s*(.*)$", m.group("options"), re.MULTILINE))
        body = "\n".join(line[3:] for line in m.group("body").splitlines()).strip("\n") + "\n"
        found.append((m.group("lang"), options.get("class", ""), body,
                      text.count("\n", 0, m.start()) + 1))
    return found


TEXT = PAGE.read_text(encoding="utf-8")
BLOCKS = _blocks(TEXT)
PYTHON = [(line, code, nxt[2] if nxt and nxt[1] == "output" else None)
          for (lang, cls, code, line), nxt in zip(BLOCKS, BLOCKS[1:] + [None])
          if cls == "seahelm" and lang == "python"]
CONSOLE = [(line, cmd) for lang, cls, code, line in BLOCKS if cls == "seahelm" and lang == "console"
           for cmd in code.splitlines() if cmd.startswith("$ ")]


def test_every_code_block_is_marked_and_the_convention_holds():
    # a literal block (``::``) or a code-block without a class would escape the run below
    assert not re.search(r"[^:]::\n\n   ", TEXT), "use `.. code-block::` with :class:, not `::`"
    n_directives = len(re.findall(r"^\.\. code-block::", TEXT, flags=re.MULTILINE))
    assert len(BLOCKS) == n_directives  # the parser saw every block
    for lang, cls, _, line in BLOCKS:
        assert cls in ("seahelm", "theirs", "output"), f"line {line}: :class: {cls!r}"
        if cls == "seahelm":
            assert lang in ("python", "console"), f"line {line}: {lang}"
    for before, (lang, cls, _, line) in zip(BLOCKS, BLOCKS[1:]):
        if cls == "output":  # the output of the seahelm Python block just before it
            assert lang == "text" and before[:2] == ("python", "seahelm"), f"line {line}"
    assert len(PYTHON) >= 15 and len(CONSOLE) >= 3
    assert sum(expected is not None for _, _, expected in PYTHON) >= 8


def test_the_page_is_in_the_guide_and_names_what_the_brief_asks():
    index = (ROOT / "docs" / "guide" / "index.rst").read_text(encoding="utf-8")
    assert re.search(r"^   coming-from$", index, flags=re.MULTILINE)
    for name in ("mariner.m", "container.m", "tanker.m", "clarke83.m", "wageningen.m",
                 "blendermann94.m", "waveSpectrum.m", "ILOSpsi.m", "LOSchi.m",
                 "PIDpolePlacement", "Kalman wave filter", "nomoto.m", "rk4.m", "euler2.m",
                 "exZigZag.m", "exTurnCircle.m", "shipClarke83", "otter", "remus100", "supply",
                 "ssa", "simulate_mmg_3dof", "simulate_kt", "Mmg3DofBasicParams", "KTParams",
                 "estimate_KT_LSM"):
        assert name in TEXT, name
    assert "issues 49, 50" in TEXT and "not in seahelm yet" in TEXT


def test_every_section_states_its_agreement():
    """Each peer function's section ends in an **Agreement.** paragraph (a measured figure or
    "Not compared"), and each row of the overview table has its third column filled."""
    sections = re.split(r"^.+\n\^{3,}\n", TEXT, flags=re.MULTILINE)[1:]
    assert len(sections) >= 18
    for body in sections:
        if "code-block" in body and "theirs" in body:
            assert "**Agreement.**" in body, body[:200]
    rows = re.findall(r"^   \* - (.+)\n     - (.+(?:\n       .+)*)\n     - (.+)$", TEXT,
                      flags=re.MULTILINE)
    assert len(rows) >= 17
    for theirs, _, agreement in rows:
        assert agreement.strip(), theirs


def test_the_files_and_pages_it_cites_exist():
    for path in set(re.findall(r"``((?:tests|benchmarks)/[\w/]+\.py)``", TEXT)):
        assert (ROOT / path).is_file(), path
    for doc in set(re.findall(r":doc:`([\w-]+)`", TEXT)):
        assert (PAGE.parent / f"{doc}.rst").is_file(), doc


@pytest.mark.parametrize("line, code, expected", PYTHON,
                         ids=[f"line{line}" for line, _, _ in PYTHON])
def test_python_snippet_runs(line, code, expected, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a snippet may show a validity warning; it must run
        exec(compile(code, f"{PAGE.name}:{line}", "exec"), {"__name__": "__coming_from__"})
    printed = capsys.readouterr().out
    assert printed.strip(), "a snippet prints what it shows"
    if expected is not None:  # the page shows its output: it is what the snippet prints
        assert printed.strip().splitlines() == expected.strip().splitlines()


@pytest.mark.parametrize("line, command", CONSOLE, ids=[f"line{line}" for line, _ in CONSOLE])
def test_console_snippet_runs(line, command, tmp_path):
    args = shlex.split(command[2:])
    assert args[0] == "seahelm"
    env = {**os.environ, "MPLBACKEND": "Agg", "PYTHONPATH": str(ROOT / "src")}
    proc = subprocess.run([sys.executable, "-m", "seahelm", *args[1:]], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, (command, proc.stderr[-2000:])
