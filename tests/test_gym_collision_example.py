"""The collision-avoidance learning example runs (a two-iteration smoke: its learning curve is
in the docs, docs/_static/rl_collision_cross_entropy.png)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("gymnasium")

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "rl_collision_cross_entropy.py"


def test_the_collision_example_runs_two_iterations(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLE), str(tmp_path), "--iterations", "2",
                           "--population", "6", "--episodes", "1"], capture_output=True,
                          text=True, timeout=600, env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "held-out encounters (6), mean return: initial policy (on course)" in proc.stdout
    assert (tmp_path / "rl_collision_cross_entropy.png").stat().st_size > 10_000
