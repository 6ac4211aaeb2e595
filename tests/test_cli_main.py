"""The seahelm command: demo, run, models, plot, --version; exit codes."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from seahelm import __version__
from seahelm.cli import app

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_version():
    res = runner.invoke(app, ["--version"])
    assert res.exit_code == 0
    assert __version__ in res.stdout
    import numba
    import numpy

    # the dependency versions a bug report needs, as installed (read from metadata)
    assert f"numpy {numpy.__version__}" in res.stdout
    assert f"numba {numba.__version__}" in res.stdout


def test_demo_writes_results_and_plot(tmp_path):
    res = runner.invoke(app, ["demo", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "result.nc").is_file()
    assert (tmp_path / "overview.png").stat().st_size > 10_000
    assert "settling time [s]" in res.stdout
    from seahelm.results import load_result

    ds = load_result(tmp_path / "result.nc")
    import numpy as np

    assert abs(np.degrees(float(ds["heading"][0, -1])) - 20.0) < 0.05
    assert np.degrees(float(abs(ds["rudder_angle"]).max())) <= 35.0 + 1e-9
    assert ds.attrs["scenario_text"].startswith("# The embedded default scenario")


def test_run_json_prints_one_object(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "mariner_course_change.toml"), "--json",
                              "--out", str(tmp_path), "--csv"])
    assert res.exit_code == 0, res.output
    payload = json.loads(res.stdout)
    assert payload["n_runs"] == 1 and payload["n_ok"] == 1
    for key in ("final_yaw_rate", "final_heading_rad", "turning_diameter_m", "settling_time_s",
                "rudder_angle_deg"):
        assert key in payload
    assert Path(payload["files"]["csv"]).is_file()


def test_bad_scenario_exits_2_with_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[vessel]\nmodel = "nomoto9"\n[simulation]\nt_final = 1.0\ndt = 0.1\n')
    res = runner.invoke(app, ["run", str(bad)])
    assert res.exit_code == 2
    assert "unknown vessel model 'nomoto9'" in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1
    assert res.stdout == ""


def test_missing_scenario_exits_2(tmp_path):
    res = runner.invoke(app, ["run", str(tmp_path / "none.toml")])
    assert res.exit_code == 2
    assert "scenario file not found" in res.stderr


def test_models_lists_parameters_with_units():
    res = runner.invoke(app, ["models", "--json"])
    assert res.exit_code == 0
    payload = json.loads(res.stdout)
    nomoto = payload["vessel_models"]["nomoto2"]
    gain = next(p for p in nomoto["parameters"] if p["name"] == "gain")
    assert gain["unit"] == "1/s" and gain["symbol"] == "K"
    assert "pid-heading" in payload["controllers"]
    assert "mariner-nomoto2" in payload["catalog"]
    human = runner.invoke(app, ["models"])
    assert human.exit_code == 0 and "Nomoto" in human.stdout


def test_models_lists_the_signals_a_scenario_author_wires():
    payload = json.loads(runner.invoke(app, ["models", "--json"]).stdout)
    mmg = {(s["kind"], s["name"]): s["unit"] for s in payload["vessel_models"]["mmg"]["signals"]}
    assert mmg[("input", "rudder_angle")] == "rad"
    assert mmg[("input", "propeller_rps")] == "1/s"
    assert mmg[("disturbance", "moment_z")] == "N·m"
    assert ("output", "drift_angle") in mmg
    pid = {(s["kind"], s["name"]) for s in payload["controllers"]["pid-heading"]["signals"]}
    assert {("measurement", "heading"), ("measurement", "yaw_rate"),
            ("command", "rudder_command"), ("reference", "heading")} <= pid
    servo = {(s["kind"], s["name"]) for s in payload["actuators"]["rudder-servo"]["signals"]}
    assert {("command", "rudder_command"), ("output", "rudder_angle")} <= servo
    assert payload["controllers"]["open-loop"]["passthrough"] is True
    human = runner.invoke(app, ["models", "mmg", "pid-heading"]).stdout
    assert "[rad/s]" in human and "propeller_rps" in human  # units survive rich markup


def test_plot_command(tmp_path):
    runner.invoke(app, ["demo", "--out", str(tmp_path)])
    res = runner.invoke(app, ["plot", str(tmp_path / "result.nc"), "--out",
                              str(tmp_path / "p.png")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "p.png").read_bytes().startswith(b"\x89PNG")
    # the format follows --out's suffix (it wrote PNG bytes under any name before)
    res = runner.invoke(app, ["plot", str(tmp_path / "result.nc"), "--out",
                              str(tmp_path / "p.pdf")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "p.pdf").read_bytes().startswith(b"%PDF")
    res = runner.invoke(app, ["plot", str(tmp_path / "result.nc"), "--out",
                              str(tmp_path / "p.docx")])
    assert res.exit_code == 2 and "supported:" in res.stderr
    assert not (tmp_path / "p.docx").exists()
    res = runner.invoke(app, ["plot", str(tmp_path / "result.nc"), "--run", "7"])
    assert res.exit_code == 2 and "--run [7] not in the file" in res.stderr
    res = runner.invoke(app, ["plot", str(tmp_path / "nothing.nc")])
    assert res.exit_code == 2


@pytest.mark.slow
def test_console_script_json_stdout_is_clean(tmp_path):
    exe = Path(sys.executable).parent / "seahelm"
    proc = subprocess.run([str(exe), "demo", "--json", "--out", str(tmp_path)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    json.loads(proc.stdout)


def test_quickstart_example_runs(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLES / "quickstart.py"), str(tmp_path)],
                          capture_output=True, text=True, timeout=300,
                          env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "course  20.0 deg -> final heading" in proc.stdout
    assert (tmp_path / "quickstart.png").is_file()


def test_progress_bar_appears_only_for_long_runs(monkeypatch):
    import importlib

    common = importlib.import_module("seahelm.cli._common")

    monkeypatch.delenv("SEAHELM_PROGRESS_DELAY", raising=False)
    clock = {"t": 0.0}
    monkeypatch.setattr(common.time, "perf_counter", lambda: clock["t"])
    bar = common.ProgressBar("x")
    bar(10, 100)  # after 0 s: no bar
    assert bar.bar is None
    clock["t"] = 1.5
    bar(20, 100)  # after 1.5 s: the bar starts
    assert bar.bar is not None
    assert bar.bar.tasks[0].completed == 20
    bar.close()
    quick = common.ProgressBar("y")
    clock["t"] = 10.0
    quick(100, 100)  # finished: never a bar
    assert quick.bar is None


def test_progress_delay_from_the_environment(monkeypatch):
    import importlib

    from seahelm.errors import ParameterError

    common = importlib.import_module("seahelm.cli._common")
    clock = {"t": 0.0}
    monkeypatch.setattr(common.time, "perf_counter", lambda: clock["t"])
    monkeypatch.setenv("SEAHELM_PROGRESS_DELAY", "0")
    bar = common.ProgressBar("x")
    bar(1, 6)  # at once
    assert bar.bar is not None and bar.bar.tasks[0].completed == 1
    bar.close()
    monkeypatch.setenv("SEAHELM_PROGRESS_DELAY", "2.5")
    late = common.ProgressBar("y")
    clock["t"] = 2.0
    late(1, 6)
    assert late.bar is None and late.delay == 2.5
    for bad in ("-1", "soon", "nan", "inf"):
        monkeypatch.setenv("SEAHELM_PROGRESS_DELAY", bad)
        with pytest.raises(ParameterError, match=rf"SEAHELM_PROGRESS_DELAY='{bad}': must be a "
                                                 r"number of seconds >= 0"):
            common.ProgressBar("z")


def test_cache_command_reports_and_clears_only_its_own_files(tmp_path, monkeypatch):
    where = tmp_path / "kernels"
    monkeypatch.setenv("SEAHELM_CACHE_DIR", str(where))
    where.mkdir()
    (where / "seahelm_kernel_0123.py").write_text("x = 1\n")
    (where / "__pycache__").mkdir()
    (where / "__pycache__" / "seahelm_kernel_0123.run_slice-1.py311.nbi").write_bytes(b"0" * 100)
    (where / "notes.txt").write_text("mine\n")  # a user's file in the directory they chose
    (where / "keep").mkdir()
    (where / "keep" / "data.csv").write_text("1,2\n")
    res = runner.invoke(app, ["cache", "--json"])
    assert res.exit_code == 0
    info = json.loads(res.stdout)
    assert info["kernels"] == 1 and info["files"] == 2 and info["bytes"] == 106
    assert info["other_files"] == 2
    res = runner.invoke(app, ["cache", "--clear", "--json"])
    assert json.loads(res.stdout)["cleared"] is True
    left = sorted(str(p.relative_to(where)) for p in where.rglob("*") if p.is_file())
    assert left == ["keep/data.csv", "notes.txt"]


def _run_json(name):
    res = runner.invoke(app, ["run", str(EXAMPLES / name), "--json", "--no-plot"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_catamaran_turn_json_reproduces_the_paper():
    import math

    from seahelm.vessels.catamaran import paper_params, steady_turn

    out = _run_json("catamaran_turn_0p08.toml")
    vx, vy, delta = steady_turn(paper_params(), 0.08)
    assert out["final_yaw_rate"] == pytest.approx(0.08, rel=1e-6)
    assert out["thruster_angle_deg"] == pytest.approx(math.degrees(delta), abs=0.01)
    assert out["turning_diameter_m"] == pytest.approx(2 * math.hypot(vx, vy) / 0.08, abs=0.2)
    assert 84.0 < out["thruster_angle_deg"] < 88.0 and 90.0 < out["turning_diameter_m"] < 100.0


def test_catamaran_small_yaw_rate_json_reproduces_the_paper():
    out = _run_json("catamaran_yaw_rate_0p00072.toml")
    assert out["thruster_angle_deg"] == pytest.approx(0.6, abs=0.02)  # "0.6 rad" is 0.6°
    assert 40.0 < out["settling_time_s"] < 60.0  # "about 50 s"


def test_catamaran_heading_json_reaches_the_course_to_three_decimals():
    out = _run_json("catamaran_heading_0p8.toml")
    assert abs(out["final_heading_rad"] - 0.8) < 5e-4


GRID_SCENARIO = """
title = "grid"
[vessel]
model = "nomoto2"
catalog = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 20.0
dt = 0.1
[batch.grid]
"controller.params.kp" = [1.0, 2.0, 3.0]
"controller.params.kd" = [10.0, 20.0, 30.0, 40.0]
"""


def test_run_grid_shows_coordinates_and_plot_reads_the_grid_file(tmp_path):
    path = tmp_path / "grid.toml"
    path.write_text(GRID_SCENARIO)
    res = runner.invoke(app, ["run", str(path), "--json", "--out", str(tmp_path), "--no-plot"])
    assert res.exit_code == 0, res.output
    payload = json.loads(res.stdout)
    assert payload["n_runs"] == 12 and payload["dims"] == {"kp": 3, "kd": 4}
    assert [(r["run"], r["kp"], r["kd"]) for r in payload["runs"][:5]] == [
        (0, 1.0, 10.0), (1, 1.0, 20.0), (2, 1.0, 30.0), (3, 1.0, 40.0), (4, 2.0, 10.0)]
    human = runner.invoke(app, ["run", str(path)], terminal_width=200)
    assert human.exit_code == 0, human.output
    heads = [line.split("┃")[1:5] for line in human.stdout.splitlines()
             if line.startswith("┃")]  # (a header may take two lines)
    header = [" ".join(h[k].strip() for h in heads if h[k].strip()) for k in range(4)]
    assert header == ["run", "kp [rad/rad]", "kd [s]", "status"]  # (their units)
    rows = [[c.strip() for c in line.split("│")[1:4]] for line in human.stdout.splitlines()
            if line.startswith("│")]
    assert rows[0] == ["0", "1", "10"] and rows[11] == ["11", "3", "40"]
    res = runner.invoke(app, ["plot", str(tmp_path / "result.nc"), "--run", "11",
                              "--out", str(tmp_path / "g.png")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "g.png").stat().st_size > 10_000
    res = runner.invoke(app, ["plot", str(tmp_path / "result.nc"), "--run", "12"])
    assert res.exit_code == 2 and "--run [12] not in the file" in res.stderr


def test_engine_error_in_a_scenario_exits_2_naming_file_and_key(tmp_path):
    bad = tmp_path / "timing.toml"
    bad.write_text(GRID_SCENARIO.replace("t_final = 20.0", "t_final = 20.05"))
    res = runner.invoke(app, ["run", str(bad)])
    assert res.exit_code == 2
    assert f"{bad}: [simulation.t_final] must be a positive whole multiple" in res.stderr
    assert res.stdout == ""


def test_the_one_run_summary_says_units_and_hides_internals(tmp_path):
    """The demo's summary (it showed final_yaw_aux, the heading twice in radians and
    turning_diameter_m nan): labels with units, no filter states, no repeated angle, the
    metrics the run did not reach named under the table; --json keeps every key."""
    res = runner.invoke(app, ["demo", "--out", str(tmp_path)], env={"COLUMNS": "100"})
    assert res.exit_code == 0, res.output
    out = res.stdout
    for label in ("final north [m]", "final heading [deg]", "max abs rudder angle [deg]",
                  "settling time [s]", "final yaw rate [deg/s]"):  # (angles in degrees)
        assert label in out, label
    for internal in ("yaw_aux", "yaw aux", "final_heading_rad", "heading rad", " nan "):
        assert internal not in out, internal
    # a course change never turns a circle: its turning diameter is not a "not reached"
    # note (issue 44: it was under every course change), and not a nan row either
    assert "turning_diameter" not in out and "turning diameter" not in out
    res = runner.invoke(app, ["inspect", str(tmp_path / "result.nc"), "--json"])
    assert res.exit_code == 0
    summary = json.loads(res.stdout)
    text = json.dumps(summary)
    assert "final_yaw_aux" in text and "turning_diameter_m" in text


def test_models_without_a_name_is_an_overview_and_a_name_filters():
    """`seahelm models` printed 1,769 lines and `seahelm models mmg` exited 2 (issue 44)."""
    overview = runner.invoke(app, ["models"], env={"COLUMNS": "100"})
    assert overview.exit_code == 0
    assert len(overview.stdout.splitlines()) < 200
    assert "mmg" in overview.stdout and "pid-heading" in overview.stdout
    assert "rudder_command" not in overview.stdout  # no signals in the overview
    one = runner.invoke(app, ["models", "mmg"], env={"COLUMNS": "100"})
    assert one.exit_code == 0, one.output
    assert "Y_v" in one.stdout and "drift_angle" in one.stdout and "pid-heading" not in one.stdout
    every = runner.invoke(app, ["models", "--all"], env={"COLUMNS": "100"})
    assert every.exit_code == 0 and len(every.stdout.splitlines()) > 1000
    assert json.loads(runner.invoke(app, ["models", "mmg", "--json"]).stdout) == {
        "vessel_models": {"mmg": json.loads(
            runner.invoke(app, ["models", "--json"]).stdout)["vessel_models"]["mmg"]}}
    bad = runner.invoke(app, ["models", "nope"])
    assert bad.exit_code == 2 and "unknown component 'nope'" in bad.stderr
    assert "pid-heading" in bad.stderr  # the valid names
