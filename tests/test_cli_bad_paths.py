"""Bad paths and bad values found by a bad-input campaign (issue 18): every one exits 2 with
one ``error:`` line naming the option or key, and an output problem is found before anything
runs (the commands that would run are replaced by a tripwire here)."""

from __future__ import annotations

import math
import os

import pytest
from typer.testing import CliRunner

from conftest import one_error
from seahelm.cli.main import app
from seahelm.errors import ParameterError

runner = CliRunner()


@pytest.fixture
def no_simulation(monkeypatch):
    """Fail the test if a scenario or manoeuvre runs (the path must be refused first)."""
    import seahelm.analysis.maneuvers as maneuvers
    import seahelm.scenario as scenario

    def tripwire(*args, **kwargs):
        raise AssertionError("ran before the output path was checked")

    monkeypatch.setattr(scenario, "run_scenario", tripwire)
    monkeypatch.setattr(maneuvers, "turning_circle", tripwire)
    monkeypatch.setattr(maneuvers, "spirals", tripwire)


def test_output_directories_are_checked_before_anything_runs(tmp_path, no_simulation):
    afile = tmp_path / "afile"
    afile.write_text("x")
    assert one_error(["demo", "--out", str(afile)]) == \
        f"error: `--out` must be a directory, but {afile} is a file"
    assert "cannot create the directory" in one_error(["demo", "--out", str(afile / "sub")])
    (tmp_path / "o" / "overview.png").mkdir(parents=True)
    assert one_error(["demo", "--out", str(tmp_path / "o")]) == (
        f"error: `--out`: {tmp_path / 'o' / 'overview.png'} is a directory; it would be "
        "overwritten by a file")
    (tmp_path / "t" / "turning.png").mkdir(parents=True)
    assert "turning.png is a directory" in one_error(
        ["maneuver", "turning", "--side", "starboard", "--out", str(tmp_path / "t")])
    assert "must be a directory" in one_error(["maneuver", "spiral", "--out", str(afile)])
    assert not any((tmp_path / "o").glob("*.nc"))  # nothing half-written


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes everywhere")
def test_an_unwritable_directory(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        assert "cannot write in" in one_error(["waves", "figure", "--out", str(ro / "w.png")])
    finally:
        ro.chmod(0o700)


def test_file_outputs(tmp_path):
    assert one_error(["waves", "figure", "--out", str(tmp_path)]) == \
        f"error: `--out` must be a file name, but {tmp_path} is a directory"
    assert "cannot write a figure as '.xyz'" in one_error(
        ["waves", "figure", "--out", str(tmp_path / "w.xyz")])
    assert "cannot write a figure as '.xyz'" in one_error(
        ["waves", "spectrum", "--h3", "3", "--plot", str(tmp_path / "s.xyz")])


def test_plot_refuses_what_is_not_a_result(tmp_path):
    text = tmp_path / "notes.nc"
    text.write_text("not netcdf\n")
    assert one_error(["plot", str(text)]) == (
        f"error: {text}: not a NetCDF-4/HDF5 file written by seahelm (a results file of "
        "`seahelm run --out` or SimResult.to_netcdf)")
    assert one_error(["plot", str(tmp_path)]) == \
        f"error: `RESULT`: {tmp_path} is a directory, not a file"
    import numpy as np
    import xarray as xr

    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(foreign, engine="h5netcdf")
    assert "not a seahelm simulation result" in one_error(["plot", str(foreign)])
    if hasattr(os, "mkfifo"):
        fifo = tmp_path / "p.nc"
        os.mkfifo(fifo)
        assert one_error(["plot", str(fifo)]) == f"error: `RESULT`: {fifo} is not a regular file"


def test_scenario_paths(tmp_path):
    assert one_error(["run", str(tmp_path)]) == \
        f"error: {tmp_path} is a directory, not a scenario file"


@pytest.mark.parametrize("args, match", [
    (["waves", "sample", "--h3", "3", "--duration", "10.3", "--dt", "0.5", "--seed", "1"],
     "`--duration` must be a whole multiple (>= 1) of `--dt` [s]: duration=10.3, dt=0.5"),
    (["averaging", "cpp", "--grid", "20000"], "`--grid` must be in [6, 2000] [directions], got "
                                              "20000"),
    (["waves", "figure", "--duration", "1e9"], "`--duration` must be in (0, 100000] [s]"),
    (["maneuver", "spiral", "--hold", "1e9"], "`--hold`: 33 holds of 1e+09 s"),
    (["compensate", "--length", "160", "--beam", "23", "--draft", "8", "--block-coefficient",
      "0.65", "--speed", "7.7", "--wind-speed", "15", "--wind-angle", "60", "--wave-height", "3",
      "--wave-angle", "60", "--rudder-area", "0"], "`--rudder-area` must be > 0 [m²], got 0.0"),
])
def test_values_that_used_to_hang_blow_up_or_be_ignored(args, match):
    assert match in one_error(args)


@pytest.mark.parametrize("args", [
    ["waves", "sample", "--h3", "3", "--duration", "10", "--dt", "0.5", "--seed", "-1"],
    ["waves", "figure", "--seed", "-1"],
])
def test_a_negative_seed_names_the_option(args):
    assert one_error(args) == ("error: Invalid value for '--seed': Input should be greater than "
                               f"or equal to 0, got '-1' (see 'seahelm waves {args[1]} --help')")


def test_manoeuvre_timing_values():
    from seahelm.analysis.maneuvers import turning_circle

    with pytest.raises(ParameterError, match=r"`record_dt` must be a whole multiple of `dt` "
                                             r"\[s\]: record_dt=0.5, dt=0.2"):
        turning_circle("kvlcc2-l7", sides=1, dt=0.2, record_dt=0.5, t_final=10.0)
    with pytest.raises(ParameterError, match=r"`t_final` must be at least one step `dt` \[s\]"):
        turning_circle("kvlcc2-l7", sides=1, dt=5.0, t_final=1.0)


def test_the_engine_refuses_a_controller_slower_than_the_run():
    import numpy as np

    from seahelm.control.pid import PID_HEADING, PIDHeadingParams
    from seahelm.simulation.engine import simulate
    from seahelm.ships import get_ship
    from seahelm.vessels.nomoto import NOMOTO2

    with pytest.raises(ParameterError, match=r"`controller_dt` = 120.0 s exceeds `t_final` = "
                                             r"60.0 s"):
        simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros(5), t_final=60.0, dt=0.1,
                 controller=PID_HEADING, controller_params=PIDHeadingParams(),
                 controller_dt=120.0, reference=[math.radians(10.0)])


def test_a_compensating_angle_no_rudder_gives_is_flagged():
    args = ["compensate", "--length", "160", "--beam", "23", "--draft", "8",
            "--block-coefficient", "0.65", "--speed", "7.7", "--wind-speed", "15",
            "--wind-angle", "60", "--wave-height", "60", "--wave-angle", "60"]
    res = runner.invoke(app, args)
    assert res.exit_code == 0
    assert "warning: delta_k_wave = 759.6 deg is beyond any rudder's 35 deg" in res.stderr
    assert one_error(args + ["--strict"]).startswith("error: ")
    calm = runner.invoke(app, args[:-3] + ["3", "--wave-angle", "60"])  # the README's case
    assert calm.exit_code == 0 and "beyond any rudder" not in calm.stderr


def test_warnings_are_one_line_and_name_the_cause():
    res = runner.invoke(app, ["maneuver", "turning", "--side", "starboard", "--speed", "2.5",
                              "--t-final", "20", "--json"])
    assert res.exit_code == 0
    warned = [line for line in res.stderr.splitlines() if line.startswith("warning: ")]
    assert warned == [line for line in res.stderr.splitlines() if line.strip()]  # nothing else
    assert any("approach speed 2.5 m/s is 2.12 x the speed of 'kvlcc2-l7''s parameter set"
               in line for line in warned)
    res = runner.invoke(app, ["maneuver", "turning", "--side", "starboard", "--dt", "1",
                              "--t-final", "20", "--json"])
    assert any("`--dt` = 1 s is 20 x the usual step of this ship (0.05 s" in line
               for line in res.stderr.splitlines())


def test_identify_smoothing_longer_than_the_log():
    from pathlib import Path

    log = Path(__file__).resolve().parents[1] / "examples" / "steady_turn_log.csv"
    assert "`--smoothing` = 1e+09 s is longer than the whole log" in one_error(
        ["identify", "steady-turn", str(log), "--smoothing", "1e9"])


@pytest.mark.parametrize("option, value, unit", [
    ("--wind-angle", "nan", "deg"), ("--wave-angle", "inf", "deg"), ("--a1", "nan", "-"),
    ("--speed", "-inf", "m/s"),
])
def test_compensate_names_the_option_of_a_non_finite_value(option, value, unit):
    args = {"--length": "160", "--beam": "23", "--draft": "8", "--block-coefficient": "0.65",
            "--speed": "7.7", "--wind-speed": "15", "--wind-angle": "60", "--wave-height": "3",
            "--wave-angle": "60"}
    args[option] = value
    flat = ["compensate"] + [x for kv in args.items() for x in kv]
    assert one_error(flat) == (f"error: `{option}` must be a finite number [{unit}], got "
                               f"{float(value)!r}")


@pytest.mark.parametrize("argv", [
    ["run", "scenario.toml", "--out", ""],
    ["demo", "--out="],
    ["maneuver", "turning", "kvlcc2-l7", "--out", ""],
    ["waves", "sample", "--duration", ""],
])
def test_an_empty_option_value_is_refused_before_anything_runs(argv, monkeypatch, capsys):
    """The parser turns an empty path into '.', which would write into the current directory."""
    import sys

    cli_main = sys.modules["seahelm.cli.main"]
    monkeypatch.setattr("sys.argv", ["seahelm", *argv])
    monkeypatch.setattr(type(app), "__call__", lambda *a, **k: pytest.fail("the command ran"))
    with pytest.raises(SystemExit) as exc:
        cli_main.main()
    assert exc.value.code == 2
    name = argv[-2] if argv[-1] == "" else argv[-1][:-1]
    assert f"error: `{name}` must not be empty" in capsys.readouterr().err


def test_a_write_killed_by_sigterm_leaves_no_temporary_file(tmp_path):
    """The console script turns SIGTERM into SystemExit, so atomic_write's cleanup runs."""
    import signal
    import subprocess
    import sys

    script = (
        "import sys, time\n"
        "from seahelm import stop_request\n"
        "from seahelm.results import atomic_write\n"
        "if sys.argv[2] == 'handled':\n"
        "    stop_request.install()\n"
        "def writer(tmp):\n"
        "    open(tmp, 'w').write('half')\n"
        "    print('writing', flush=True)\n"
        "    time.sleep(60)\n"
        "atomic_write(sys.argv[1], writer)\n")
    for mode in ("handled", "default"):
        target = tmp_path / mode / "result.nc"
        proc = subprocess.Popen([sys.executable, "-c", script, str(target), mode],
                                stdout=subprocess.PIPE, text=True)
        assert proc.stdout.readline().strip() == "writing"
        proc.send_signal(signal.SIGTERM)
        code = proc.wait(timeout=120)  # (a loaded machine: the exit, not the signal, is slow)
        left = sorted(p.name for p in target.parent.iterdir())
        if mode == "handled":
            assert code == 143 and left == []  # nothing half-written, no temporary file
        else:  # the contrast: Python's default leaves the temporary file behind
            assert code == -signal.SIGTERM and len(left) == 1 and left[0].endswith(".tmp")


LONG_RUN = """title = "long"
[vessel]
ship = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 60000000.0
dt = 0.1
record_every = 1000000
"""


def test_ctrl_c_exits_130_with_a_message_and_leaves_no_empty_out_directory(tmp_path):
    """Ctrl-C during `seahelm run` (it exited 130 silently and left the empty --out
    directory it had made): one line on stderr, exit 130, the directories it made removed."""
    import signal
    import subprocess
    import sys
    import time

    scenario = tmp_path / "long.toml"
    scenario.write_text(LONG_RUN)
    out = tmp_path / "made" / "by-run"
    from interruptible import popen_interruptible

    # (SIGINT at its default: from a suite started as a background job it was ignored, and the
    # 6e8-step run went on past the 120 s below)
    proc = popen_interruptible([sys.executable, "-m", "seahelm", "run", str(scenario), "--out",
                                str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    deadline = time.monotonic() + 120
    while not out.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert out.exists(), proc.communicate()
    time.sleep(0.5)  # (into the run)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1].startswith("interrupted: Ctrl-C before the end")
    assert not (tmp_path / "made").exists()


def test_ctrl_c_with_json_prints_one_object(tmp_path, monkeypatch):
    import json

    import seahelm.scenario

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(seahelm.scenario, "run_scenario", interrupted)
    scenario = tmp_path / "long.toml"
    scenario.write_text(LONG_RUN)
    res = CliRunner().invoke(app, ["run", str(scenario), "--out", str(tmp_path / "o"), "--json"])
    assert res.exit_code == 130, res.output
    payload = json.loads(res.stdout)
    assert payload["exit_code"] == 130 and payload["error"].startswith("interrupted: Ctrl-C")
    assert not (tmp_path / "o").exists()


def test_the_same_warning_is_printed_once_per_command(capsys):
    """A warning repeated in one command (a sweep's 60 runs each warned Lvov's range: 60
    identical lines) is printed once; the next command prints it again."""
    import warnings

    from seahelm.cli._common import handle_errors

    @handle_errors
    def command():
        for _ in range(3):  # a fresh registry each time: shown each time by "default"
            warnings.warn_explicit("Lvov: block coefficient 0.56 outside 0.6..0.8",
                                   UserWarning, "runs.py", 1)
        warnings.warn_explicit("another cause", UserWarning, "runs.py", 2)

    command()
    command()
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert lines == ["warning: Lvov: block coefficient 0.56 outside 0.6..0.8",
                     "warning: another cause"] * 2
