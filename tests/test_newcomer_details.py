"""Small things a newcomer noticed (issue 44, item 7): notes that are noise, a figure titled
by its components, help texts that said the wrong thing."""

from __future__ import annotations

import math
import re

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app

runner = CliRunner()


def test_a_steered_run_does_not_note_its_turning_diameter():
    from seahelm.units import noted_unreached

    course_change = ["final_heading", "heading_error_deg", "turning_diameter_m",
                     "settling_time_s"]
    assert noted_unreached(["turning_diameter_m", "settling_time_s"], course_change) == [
        "settling_time_s"]
    route = ["final_heading", "max_abs_cross_track_error_m", "turning_diameter_m"]
    assert noted_unreached(["turning_diameter_m"], route) == []
    # a turn (open loop, a yaw-rate reference) that did not close its circle: still said
    turn = ["final_heading", "final_yaw_rate", "turning_diameter_m"]
    assert noted_unreached(["turning_diameter_m"], turn) == ["turning_diameter_m"]


def test_the_demo_prints_no_turning_diameter_note(tmp_path):
    res = runner.invoke(app, ["demo", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    assert "turning_diameter" not in res.stdout  # was "not reached in this run: turning_..."
    from seahelm.report import write_report

    write_report(tmp_path / "result.nc", tmp_path / "r.html")
    assert "turning_diameter" not in (tmp_path / "r.html").read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def turning_runs():
    from seahelm.analysis.maneuvers import turning_circle

    return turning_circle("kvlcc2-l7", rudder=math.radians(35.0)).runs


def test_a_manoeuvre_plot_names_the_manoeuvre_ship_and_sides(turning_runs):
    import matplotlib.pyplot as plt

    from seahelm.plotting.timeseries import plot_result

    fig = plot_result(turning_runs)
    try:
        title = fig._suptitle.get_text()
        assert title == "Turning circle: kvlcc2-l7 (mmg)", title  # was "mmg / open-loop"
        labels = [t.get_text() for ax in fig.axes if ax.get_legend()
                  for t in ax.get_legend().get_texts()]
        assert "run 0 (starboard)" in labels and "run 1 (port)" in labels, labels
        assert not any("side=" in label for label in labels)
    finally:
        plt.close(fig)


def test_legend_angles_in_degrees():
    from seahelm.plotting.timeseries import _coordinate_text

    assert _coordinate_text("rudder", math.radians(20.0), "rad") == "rudder=20°"
    assert _coordinate_text("kp", 3.0, None) == "kp=3"
    assert _coordinate_text("side", -1, None) == "port"
    assert _coordinate_text("ship_name", "my-ship", None) == "my-ship"


def _help(*args: str) -> str:
    res = runner.invoke(app, [*args, "--help"], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    return " ".join(res.stdout.split())


def test_the_stopping_help_gives_its_own_duration():
    text = _help("maneuver", "stopping")
    assert "steady turn" not in text  # a crash stop has none
    assert "bollard astern thrust" in text
    assert "steady turn" in _help("maneuver", "turning")  # the turns keep theirs


def test_the_rudder_rate_default_reads_as_a_number():
    text = _help("identify", "nomoto")
    assert "65/28)" not in text and re.search(r"rudder-rate FLOAT .*\[default: 2\.32\]", text)


def test_a_run_that_never_settles_says_so():
    from rich.console import Console

    from seahelm.cli._runs import summary_table

    rows = [{"run": 0, "status": "ok", "final_heading_rad": 0.1, "final_yaw_rate": 0.0,
             "settling_time_s": 93.8},
            {"run": 1, "status": "ok", "final_heading_rad": 0.2, "final_yaw_rate": 0.0,
             "settling_time_s": math.nan}]
    console = Console(width=120, record=True)
    console.print(summary_table(rows, "two runs"))
    text = console.export_text().replace("\u00a0", " ")  # (one line: a no-break space)
    assert "not settled" in text and "93.8" in text and "nan" not in text


def test_the_report_of_the_imo_check_gives_the_verdict_first(report_imo_dir):
    page = (report_imo_dir / "report.html").read_text(encoding="utf-8")
    verdict = page.index("the evaluated criteria")
    assert verdict < page.index('class="meta"'), "the verdict sat below the metadata tables"
    # the metadata table in words, not attribute names
    for raw in ("actuator_step", "seahelm_checksums", "compile_time_s"):
        assert f"<td>{raw}</td>" not in page, raw
    assert "<td>actuator step</td>" in page and "<td>checksums</td>" in page


def test_the_report_of_an_imo_ensemble_counts_its_samples(tmp_path):
    res = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", "6", "--seed", "1",
                              "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    res = runner.invoke(app, ["report", str(tmp_path / "imo-probabilities.nc"), "-o",
                              str(tmp_path / "p.html")])
    assert res.exit_code == 0, res.output
    assert "6 sample(s)" in res.stdout and "0 run(s)" not in res.stdout  # it said 0 run(s)


def test_autopilot_tune_writes_a_short_portable_scenario(tmp_path):
    """It wrote t_final = 15,000 s for the Mariner's 10° course change (a hundred time
    constants of the slowest pole) and the ship file's absolute path into title and ship."""
    import tomllib

    ship_file = tmp_path / "ships" / "m.toml"
    ship_file.parent.mkdir()
    res = runner.invoke(app, ["ship", "show", "mariner-nonlinear", "--toml"])
    ship_file.write_text(res.stdout)
    out = tmp_path / "scenarios" / "pid.toml"
    out.parent.mkdir()
    res = runner.invoke(app, ["autopilot", "tune", str(ship_file), "--bandwidth", "0.05",
                              "--damping", "0.9", "--out", str(out)])
    assert res.exit_code == 0, res.output
    scenario = tomllib.loads(out.read_text())
    assert scenario["vessel"]["ship"] == "../ships/m.toml"  # relative to the scenario
    assert str(tmp_path) not in out.read_text()
    assert scenario["title"].startswith("mariner-nonlinear: 10 deg course change")
    # five time constants of the slowest closed-loop pole (0.0067 1/s): 800 s; the
    # nonlinear run settles within 2 % in about 400 s
    assert scenario["simulation"]["t_final"] == 800.0
    run = runner.invoke(app, ["run", str(out), "--json"])
    assert run.exit_code == 0, run.output
    import json

    settling = json.loads(run.stdout)["runs"][0]["settling_time_s"]
    assert 100.0 < settling < 0.75 * 800.0


def test_a_wind_section_names_every_missing_key_at_once():
    """A wind scenario on an estimated ship took five failed runs, one key each, one of them
    garbled ("[environment.wind.vessel_type] own/ap_env.toml: [environment.wind.
    length_overall] needed")."""
    from seahelm.scenario import ScenarioError, parse_scenario as parse

    text = ('[vessel]\nmodel = "mariner"\n[environment.wind]\nspeed = 5.0\n'
            'direction_deg = 10\n[simulation]\nt_final = 10.0\ndt = 0.1\n')
    with pytest.raises(ScenarioError) as err:
        parse(text)
    message = str(err.value)
    assert "[environment.wind.lateral_area] needed [m²]" in message
    for key in ("`frontal_area` [m²]", "`length_overall` [m]", "`vessel_type`",
                "tanker-loaded"):
        assert key in message, key
    assert message.count("[environment.wind") == 1  # one key path: not garbled
    waves = text.replace("[environment.wind]\nspeed = 5.0\ndirection_deg = 10\n",
                         "[environment.waves]\nheight = 2.0\nperiod = 8.0\ndirection_deg = 0\n")
    with pytest.raises(ScenarioError) as err:
        parse(waves)
    for key in ("hull_length", "`beam` [m]", "`draft` [m]", "`block_coefficient`"):
        assert key in str(err.value), key
