"""The suite's processes run OpenBLAS on one thread (tests/conftest.py): two xdist workers on
2 cores, each with a BLAS thread per core, oversubscribe the machine and the idle threads
spin-wait (tests/test_analysis_nomoto_fit.py took 57 s of CPU instead of 10 s)."""

from __future__ import annotations

import os
import subprocess
import sys


def test_the_workers_and_subprocesses_inherit_one_openblas_thread():
    # set by conftest unless the caller set it (then the caller's value is kept)
    value = os.environ.get("OPENBLAS_NUM_THREADS")
    assert value is not None
    out = subprocess.run([sys.executable, "-c",
                          "import os; print(os.environ.get('OPENBLAS_NUM_THREADS'))"],
                         capture_output=True, text=True, timeout=60, check=True)
    assert out.stdout.strip() == value
