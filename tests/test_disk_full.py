"""A full disk is one line naming the path (exit 1: the machine failed, not the input), with
nothing half-written and no temporary file left (issue 33, part 3). The disk is a 200 kB tmpfs
the test mounts (root only; skipped with the reason where the machine does not allow it)."""

from __future__ import annotations

import subprocess
import uuid
from pathlib import Path

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture
def small_disk(tmp_path):
    mount = tmp_path / f"small-{uuid.uuid4().hex[:6]}"
    mount.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=200k", "tmpfs", str(mount)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs here ({done.stderr.strip() or 'not root'})")
    try:
        yield mount
    finally:
        subprocess.run(["umount", str(mount)], check=False)


def _full(args, path_in_message):
    res = runner.invoke(app, args)
    assert res.exit_code == 1, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert lines == [f"failed: No space left on device: {path_in_message}"], lines


def _nothing_left(directory: Path) -> None:
    assert [p.name for p in directory.rglob("*")] == []


def test_run_on_a_full_disk(small_disk):
    out = small_disk / "out"
    _full(["run", str(EXAMPLES / "mariner_pid_sweep.toml"), "--out", str(out)],
          out / "result.nc")
    _nothing_left(small_disk / "out")


def test_a_manoeuvre_on_a_full_disk_leaves_no_lone_metrics_file(small_disk):
    out = small_disk / "m"
    # the metrics file (~70 kB) fits, the runs file does not: neither appears
    _full(["maneuver", "turning", "--out", str(out)], out / "turning-circle-runs.nc")
    _nothing_left(out)


def test_a_sweep_on_a_full_disk_names_its_store(small_disk, tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text((EXAMPLES / "mariner_pid_sweep.toml").read_text())
    store = small_disk / "s.zarr"
    _full(["sweep", str(scenario), "--store", str(store), "--chunk-size", "20"], store)
    assert not [p for p in small_disk.rglob("*") if p.name.endswith((".tmp", ".partial"))]


def test_a_report_on_a_full_disk_names_its_file(small_disk, tmp_path):
    import numpy as np

    from seahelm.ships import get_ship
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2

    result = simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros((2, 5)),
                      t_final=5.0, dt=0.1, reference=[0.1])
    source = result.to_netcdf(tmp_path / "result.nc")
    target = small_disk / "r.html"  # the report inlines plotly.js: ~4 MB
    _full(["report", str(source), "-o", str(target)], target)
    _nothing_left(small_disk)
