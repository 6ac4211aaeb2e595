"""Issue 43, items 3, 5 and 6: exceptions that became one-line refusals, messages in the
user's words instead of internal ones, and a bound on bootstrap refits."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from interruptible import popen_interruptible
from seahelm.cli.main import app
from seahelm.errors import ParameterError

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
ESTIMATE = ["ship", "estimate", "--length", "320", "--beam", "58", "--draft", "20.8", "--cb",
            "0.81", "--speed", "7.97"]


def _error(args: list[str]) -> str:
    res = runner.invoke(app, args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    line = res.stderr.strip().splitlines()[-1]
    assert line.startswith("error: "), res.stderr
    return line


# -- item 3: exceptions --------------------------------------------------------------------
@pytest.mark.parametrize("lcb", ["50", "-50", "9"])
def test_lcb_outside_holtrops_terms_is_refused_with_its_range(lcb):
    # C_P = 0.815 here: 1 - C_P - 0.0225 lcb > 0 needs lcb < 8.23 (it was "TypeError: must
    # be real number, not complex", exit 1)
    line = _error(ESTIMATE + ["--lcb", lcb])
    assert "`--lcb` must be in (-8.23, 8.23) [% of L]" in line and "C_P = 0.815" in line


def test_lcb_inside_its_range_estimates():
    assert runner.invoke(app, ESTIMATE + ["--lcb", "3"]).exit_code == 0


def _kernel_dir(tmp_path, monkeypatch) -> Path:
    where = tmp_path / "kernels"
    monkeypatch.setenv("SEAHELM_CACHE_DIR", str(where))
    (where / "__pycache__").mkdir(parents=True)
    for i in range(5):
        (where / f"seahelm_kernel_{i}.py").write_text("x = 1\n")
        (where / "__pycache__" / f"seahelm_kernel_{i}.run-1.py311.nbc").write_bytes(b"0" * 10)
    return where


def test_cache_clear_tolerates_files_another_clear_removes(tmp_path, monkeypatch):
    """Two `seahelm cache --clear` at once: a file the other one deletes between this one's
    listing and its look at the file is not counted, not an error ("[Errno 2] No such file
    or directory: ...nbc" before)."""
    where = _kernel_dir(tmp_path, monkeypatch)
    real_stat = Path.stat
    victim = where / "__pycache__" / "seahelm_kernel_3.run-1.py311.nbc"

    def racing_stat(self, *args, **kwargs):
        out = real_stat(self, *args, **kwargs)
        if self == victim and os.path.exists(self):  # the other process deletes it now
            os.unlink(self)
        return out

    monkeypatch.setattr(Path, "stat", racing_stat)
    res = runner.invoke(app, ["cache", "--clear", "--json"])
    assert res.exit_code == 0, res.stderr
    assert json.loads(res.stdout)["cleared"] is True
    assert not any(p.is_file() for p in where.rglob("*"))


def test_two_cache_clears_at_once(tmp_path, monkeypatch):
    where = _kernel_dir(tmp_path, monkeypatch)
    for i in range(5, 400):
        (where / "__pycache__" / f"seahelm_kernel_{i}.run-1.py311.nbc").write_bytes(b"0")
    env = {**os.environ, "SEAHELM_CACHE_DIR": str(where)}
    cmd = [sys.executable, "-m", "seahelm", "cache", "--clear"]
    procs = [subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True) for _ in range(2)]
    for p in procs:
        _, err = p.communicate(timeout=120)
        assert p.returncode == 0, err


# -- item 5: messages in the user's words --------------------------------------------------
def test_an_impossible_length_to_beam_names_the_particulars():
    line = _error(["ship", "estimate", "--length", "2900", "--beam", "58", "--draft", "20.8",
                   "--cb", "0.81", "--speed", "7.97"])
    assert "`epsilon`" not in line  # ("`epsilon` must be in (0, inf]" before)
    assert "C_b B/L = 0.0162 (`--cb` 0.81, `--length`/`--beam` L/B = 50)" in line
    assert "0.05279 < C_b B/L < 0.213, for this C_b an L/B in (3.8, 15.3)" in line


def test_uncertainty_beyond_its_range_is_named():
    line = _error(["imo", "kvlcc2-l7", "--monte-carlo", "4", "--uncertainty", "10"])
    assert "`--uncertainty` must be in (0, 1]" in line and "Y_vvv" not in line
    from seahelm.analysis.imo.probability import monte_carlo_ships
    from seahelm.ships import get_ship

    with pytest.raises(ParameterError, match=r"must be in \(0, 1\]") as info:
        monte_carlo_ships(get_ship("kvlcc2-l7"), 2, uncertainty=10.0)
    assert info.value.field == "uncertainty"


def test_linearize_at_no_speed_names_the_speed():
    line = _error(["linearize", "kvlcc2-l7", "--speed", "1e-9"])
    assert line.startswith("error: `--speed` 1e-09 m/s: ") and "`model`" not in line
    assert "its test speed is 1.179 m/s" in line


def test_a_header_only_rao_table_names_its_file(tmp_path):
    from seahelm.environment.rao_io import read_rao_table

    path = tmp_path / "empty-rao.csv"
    path.write_text("dof,frequency,heading_deg,amplitude,phase_deg,speed\n")
    with pytest.raises(ParameterError, match="has a header but no rows") as info:
        read_rao_table(path)
    assert str(path) in str(info.value)
    assert str(path) in _error(["seakeeping", "--hs", "2", "--tp", "8", "--rao", str(path),
                                "--dof", "heave"])


def _nomoto_csv(path: Path, comment: str = "") -> Path:
    t = np.arange(0.0, 200.0, 0.5)
    rudder = 10.0 * np.sign(np.sin(2 * np.pi * t / 100.0) + 1e-9)
    r = np.zeros_like(t)
    for i in range(1, t.size):
        r[i] = r[i - 1] + 0.5 * (0.1 * np.radians(rudder[i - 1]) - r[i - 1]) / 20.0
    heading = np.degrees(np.concatenate([[0.0], np.cumsum(0.5 * r[:-1])]))
    path.write_text(comment + "time,rudder_angle,heading\n"
                    + "".join(f"{a},{b},{c}\n" for a, b, c in zip(t, rudder, heading)))
    return path


def test_comment_lines_of_a_record_csv_are_skipped(tmp_path):
    plain = _nomoto_csv(tmp_path / "plain.csv")
    commented = _nomoto_csv(tmp_path / "units.csv",
                            "# units: time s, rudder_angle deg, heading deg\n# a log\n")
    fits = []
    for path in (plain, commented):
        res = runner.invoke(app, ["identify", "nomoto", str(path), "--json"])
        assert res.exit_code == 0, res.stderr  # (the `# units:` line was read as the header)
        fits.append([(p["name"], p["value"]) for p in json.loads(res.stdout)["parameters"]])
    assert fits[0] == fits[1]
    from seahelm.identification.records import read_turn_log_lines

    bad = commented.read_text().replace("\n0.5,", "\n0.5,x", 1)
    commented.write_text(bad)
    with pytest.raises(ParameterError, match=r"units.csv, line 5: column `rudder_angle`"):
        read_turn_log_lines(commented)


@pytest.mark.parametrize("spec, message", [
    ('Y_v = {distribution = "normal", mean = "a", std = 1}',
     "[draws.Y_v.mean] must be a number (not a string or a boolean), got 'a'"),
    ('Y_v = {distribution = "gauss", mean = 1, std = 1}',
     "[draws.Y_v.distribution] must be one of normal, uniform, lognormal or truncnormal, "
     "got 'gauss'"),
    ('Y_v = {distribution = "normal", mean = 1, std = 1, sigma = 2}',
     "[draws.Y_v.sigma] is an unknown key; valid in [draws.Y_v]: distribution, mean, std"),
    ("Y_v = 5", "[draws.Y_v] must be a table {distribution = ..., mean = ..., std = ...}, "
                "got 5"),
    ('Y_v = {distribution = "normal", mean = 1, std = -1}', "[draws.Y_v.std] must be >= 0, "
                                                            "got -1"),
])
def test_draws_file_errors_name_the_file_and_key(tmp_path, spec, message):
    path = tmp_path / "d.toml"
    path.write_text(f"[draws]\n{spec}\n")
    line = _error(["imo", "kvlcc2-l7", "--monte-carlo", "2", "--draws", str(path)])
    assert line == f"error: `--draws` {path}: {message}" or message in line, line
    assert "Input should" not in line


@pytest.mark.parametrize("text", [5, b"[simulation]", Path("scenario.toml")])
def test_parse_scenario_of_a_non_string_is_a_type_error(text):
    import seahelm

    with pytest.raises(TypeError, match="`text` must be the scenario's TOML text"):
        seahelm.parse_scenario(text)


@pytest.mark.skipif(sys.platform == "win32", reason="process groups")
def test_an_interrupted_sweep_on_workers_says_one_line(tmp_path):
    pytest.importorskip("distributed")
    store = tmp_path / "s.zarr"
    # (SIGINT at its default: a suite started as a background job ignores it, and so did the
    # sweep, which ran to its end and exited 0)
    proc = popen_interruptible(
        [sys.executable, "-m", "seahelm", "sweep", str(EXAMPLES / "mariner_monte_carlo.toml"),
         "--store", str(store), "--workers", "2", "--chunk-size", "1"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 240
    markers = store / "sweep-chunks"
    while time.monotonic() < deadline and proc.poll() is None:
        if markers.is_dir() and len(list(markers.iterdir())) >= 3:  # (chunks are coming in)
            break
        time.sleep(0.5)
    assert proc.poll() is None, proc.communicate()
    os.killpg(proc.pid, signal.SIGINT)  # as Ctrl-C at a terminal: the whole group
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, (len(list(markers.iterdir())), out[-2000:], err[-4000:])
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("interrupted: "), err  # (102 before)


def test_a_command_started_for_a_ctrl_c_takes_it_even_when_the_suite_ignores_it():
    """The interrupted sweep that exited 0 (a fresh-clone run): the suite had been started as a
    background job of a shell without job control, with SIGINT ignored, and the sweep inherited
    the ignore. ``popen_interruptible`` gives the command SIGINT at its default; plain
    ``Popen``, the contrast, passes the ignore on."""
    probe = "import signal; print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)"
    suite = (
        "import signal, subprocess, sys\n"
        "signal.signal(signal.SIGINT, signal.SIG_IGN)\n"  # (as `make test &` in a script)
        f"sys.path.insert(0, {str(Path(__file__).parent)!r})\n"
        "from interruptible import popen_interruptible\n"
        f"probe = [sys.executable, '-c', {probe!r}]\n"
        "for start in (popen_interruptible, subprocess.Popen):\n"
        "    print(start(probe, stdout=subprocess.PIPE, text=True).communicate()[0].strip())\n")
    res = subprocess.run([sys.executable, "-c", suite], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    assert res.stdout.split() == ["True", "False"]


# -- item 6: a bound on the bootstrap ------------------------------------------------------
def test_bootstrap_refits_are_bounded(tmp_path, monkeypatch):
    import seahelm.identification.nomoto_fit as nomoto_fit

    def refits(*args, **kwargs):  # 10^6 refits ran for days, with no bound
        raise AssertionError("the refits started")

    monkeypatch.setattr(nomoto_fit, "_bootstrap", refits)
    path = _nomoto_csv(tmp_path / "r.csv")
    line = _error(["identify", "nomoto", str(path), "--bootstrap", "1000000"])
    assert "`--bootstrap` must be in [0, 10000], got 1000000" in line
    assert "would take about 139 h" in line
    from seahelm.identification.records import read_records

    with pytest.raises(ParameterError, match=r"in \[0, 10000\]") as info:
        nomoto_fit.fit_nomoto(read_records([path]), bootstrap=10_001)
    assert info.value.field == "bootstrap"


def test_the_store_markers_warning_is_not_shown_even_when_a_thread_lost_its_filter(capsys):
    """zarr's "Object at sweep-chunks is not recognized" warning, raised in the sweep's writer
    thread after the command's catch_warnings ended in the main thread (a Ctrl-C: the store's
    filter lost, ``catch_warnings`` is not thread-safe), is not a second line beside the
    'interrupted' one (seen in a fresh-clone run: 2 lines)."""
    from seahelm.cli._common import _show_warning

    _show_warning(UserWarning("Object at sweep-chunks is not recognized as a component of a "
                              "Zarr hierarchy."), UserWarning, "x.py", 1)
    _show_warning(UserWarning("Object at other-dir is not recognized as a component of a "
                              "Zarr hierarchy."), UserWarning, "x.py", 1)
    err = capsys.readouterr().err
    assert "sweep-chunks" not in err and "other-dir" in err
