"""Every benchmark runs in its quick mode (so a moved import or a renamed option fails here, not
in a user's ``make bench``): exit 0, figures printed, within a timeout."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = sorted((Path(__file__).parents[1] / "benchmarks").glob("bench_*.py"))
#: A figure: a number with a unit or a ratio (e.g. "0.123 s", "1.2e+06 steps/s", "333 x").
#: Seconds a quick run may take: a hang, not a speed (a fresh clone's empty kernel cache compiles
#: bench_imo_probability's kernels in about 65 s on an idle 2-core machine, and twice that
#: beside the suite's other worker: 120 s failed a fresh-clone run).
QUICK_TIMEOUT = 300
FIGURE = re.compile(r"\d(\.\d+)?(e[+-]?\d+)?\s*(s\b|ms\b|x\b|×|%|runs/s|steps/s|samples/s)")


def test_every_benchmark_is_found():
    assert len(BENCHMARKS) >= 10
    assert {p.name for p in BENCHMARKS} >= {"bench_sweep.py", "bench_approaches.py"}


@pytest.mark.parametrize("path", BENCHMARKS, ids=[p.stem for p in BENCHMARKS])
def test_benchmark_quick_mode_runs_and_prints_its_figures(path, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    # (-X faulthandler: a crash of the interpreter -- bench_gym's run aborted once with glibc's
    # "corrupted double-linked list" after its last figure, not reproduced since -- leaves
    # every thread's Python traceback in stderr, which the assertion shows)
    proc = subprocess.run([sys.executable, "-X", "faulthandler", str(path), "--quick"],
                          capture_output=True, text=True, timeout=QUICK_TIMEOUT, cwd=tmp_path,
                          env=env)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert FIGURE.search(proc.stdout), proc.stdout[-2000:]
