"""Shared fixtures: a non-interactive matplotlib backend and the Mariner parameters."""

from __future__ import annotations

import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture
def mariner2():
    from seahelm.vessels.catalog import get

    return get("mariner-nomoto2").params


@pytest.fixture
def mariner1():
    from seahelm.vessels.catalog import get

    return get("mariner-nomoto1").params


def pytest_report_header(config):
    from seahelm.versions import version_report

    return f"seahelm tested with: {version_report()}"


def pytest_configure(config):
    """With SEAHELM_REQUIRE_EMPTY_CACHE=1 (set by .ci/run), refuse to start on a warm cache.

    A test that passes only because a kernel compiled by other code is still on disk is how a
    fresh-machine failure hid before; CI must start from nothing. Checked once, in the
    controlling process (not in xdist workers, which start after it).
    """
    if not os.environ.get("SEAHELM_REQUIRE_EMPTY_CACHE") or hasattr(config, "workerinput"):
        return
    from pathlib import Path

    kernels = os.environ.get("SEAHELM_CACHE_DIR")
    if not kernels:
        pytest.exit("SEAHELM_REQUIRE_EMPTY_CACHE is set but SEAHELM_CACHE_DIR is not", returncode=3)
    # numba makes empty per-package folders when cache=True functions are decorated: count files
    warm = [str(p) for p in (Path(kernels), Path(os.environ.get("NUMBA_CACHE_DIR", "")))
            if str(p) not in ("", ".") and p.is_dir() and any(f.is_file() for f in p.rglob("*"))]
    if warm:
        pytest.exit(f"the kernel cache is not empty at the start of the run: {warm}", returncode=3)
