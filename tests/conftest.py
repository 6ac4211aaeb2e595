"""Shared fixtures: a non-interactive matplotlib backend and the Mariner parameters."""

from __future__ import annotations

import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture
def mariner2():
    from seahelm.ships import get_ship

    return get_ship("mariner-nomoto2").params


@pytest.fixture
def mariner1():
    from seahelm.ships import get_ship

    return get_ship("mariner-nomoto1").params


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


# ------------------------------------------------------------------------------------------
# result files of the HTML report's tests (tests/test_report*.py), made once per session on
# component combinations the suite compiles anyway (the demo's; the KVLCC2 MMG of
# `seahelm imo`)
# ------------------------------------------------------------------------------------------
#: A 2-point grid × 5 Monte-Carlo samples on the demo's components (tests/test_cli_inspect.py
#: runs the same combination): kp = 4 leaves the yaw-rate bounds in every sample (diverged,
#: "state out of bounds"), kp = 1 never does.
REPORT_BATCH_SCENARIO = """
title = "report test batch"
[vessel]
catalog = "mariner-nomoto2"
[actuator]
model = "rudder-servo"
[controller]
model = "pid-heading"
dt = 0.5
[controller.params]
kp = 3.0
kd = 60.0
[controller.reference]
heading_deg = 20.0
[simulation]
t_final = 120.0
dt = 0.1
record_every = 5
bounds = { yaw_rate = [-0.006, 0.006] }
[batch.grid]
"controller.params.kp" = [1.0, 4.0]
[batch.monte_carlo]
runs = 5
seed = 3
[batch.monte_carlo.draws]
"vessel.params.gain" = {distribution = "normal", mean = 0.185, std = 0.04}
"""


def one_error(args: list[str]) -> str:
    """Run ``seahelm ARGS``; assert exit 2 with one ``error:`` line on stderr and nothing on
    stdout; return that line."""
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert res.stdout == "", res.stdout
    return lines[0]


def _invoke(args, exit_code=0):
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, args)
    assert res.exit_code == exit_code, (res.stdout, res.stderr)
    return res


@pytest.fixture(scope="session")
def report_demo_dir(tmp_path_factory):
    """`seahelm demo --out DIR`: result.nc, overview.png and report.html."""
    out = tmp_path_factory.mktemp("report-demo")
    _invoke(["demo", "--out", str(out)])
    return out


@pytest.fixture(scope="session")
def report_batch_dir(tmp_path_factory):
    """`seahelm run --report` of :data:`REPORT_BATCH_SCENARIO`: a grid × Monte-Carlo batch
    with diverged runs (result.nc and report.html)."""
    where = tmp_path_factory.mktemp("report-batch")
    scenario = where / "batch.toml"
    scenario.write_text(REPORT_BATCH_SCENARIO)
    # exit code 3: all written, some runs diverged
    _invoke(["run", str(scenario), "--out", str(where / "out"), "--no-plot", "--report"],
            exit_code=3)
    return where / "out"


@pytest.fixture(scope="session")
def report_imo_dir(tmp_path_factory):
    """`seahelm imo kvlcc2-l7 --out DIR` (turning and zig-zag runs and metrics, the criteria)
    and `seahelm report` of it (report.html)."""
    out = tmp_path_factory.mktemp("report-imo")
    _invoke(["imo", "kvlcc2-l7", "--out", str(out)])
    _invoke(["report", str(out / "turning-circle-runs.nc"), "-o", str(out / "report.html")])
    return out


@pytest.fixture(scope="session")
def report_sweep_dir(tmp_path_factory):
    """`seahelm sweep` of :data:`REPORT_BATCH_SCENARIO` (the demo's components: its kernel is
    compiled once for the suite) in chunks of 4 into a store, and `seahelm report` of it."""
    where = tmp_path_factory.mktemp("report-sweep")
    scenario = where / "batch.toml"
    scenario.write_text(REPORT_BATCH_SCENARIO)
    _invoke(["sweep", str(scenario), "--store", str(where / "sweep.zarr"), "--chunk-size", "4"],
            exit_code=3)  # (some runs diverge)
    _invoke(["report", str(where / "sweep.zarr"), "-o", str(where / "report.html")])
    return where
