"""``[maneuver]`` scenarios: the same manoeuvres as the library and ``seahelm maneuver``, from a
file, with their bad input named by file and key; strict numbers and file encodings.

Uses the MMG open-loop and zigzag-rps kernels and the Mariner open-loop and zigzag kernels.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from seahelm.analysis.imo.check import imo_check
from seahelm.analysis.maneuvers import maneuver_ship, turning_circle, zigzag
from seahelm.cli.main import app
from seahelm.scenario import ManeuverJob, ScenarioError, load_scenario, parse_scenario, run_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
runner = CliRunner()

TURN = """title = "turning"
[vessel]
catalog = "kvlcc2-l7"
[maneuver]
kind = "turning"
rudder_deg = 35.0
sides = "starboard"
t_final = 60.0
"""


def test_turning_scenario_equals_the_library_call():
    job = parse_scenario(TURN, source="t.toml")
    assert isinstance(job, ManeuverJob) and job.kind == "turning"
    assert job.options == {"rudder": pytest.approx(math.radians(35.0)), "sides": 1,
                           "t_final": 60.0}
    got = run_scenario(job).metrics
    lib = turning_circle("kvlcc2-l7", math.radians(35.0), sides=1, t_final=60.0).metrics
    for name in ("advance", "transfer", "tactical_diameter", "time_90", "steady_yaw_rate"):
        assert float(got[name]) == float(lib[name]), name  # the same batch, bit for bit
    assert got.attrs["title"] == "turning" and got.attrs["scenario_source"] == "t.toml"
    assert got.attrs["scenario_text"] == TURN


def test_radians_and_degrees_and_lists_give_the_same_runs():
    deg = parse_scenario(TURN.replace("rudder_deg = 35.0", "rudder_deg = [20.0, 35.0]"))
    rad = parse_scenario(TURN.replace("rudder_deg = 35.0",
                                      f"rudder = [{math.radians(20.0)!r}, {math.radians(35.0)!r}]"))
    a, b = run_scenario(deg).metrics, run_scenario(rad).metrics
    assert a["advance"].dims == ("rudder",) and a.sizes["rudder"] == 2
    assert a["advance"].values.tolist() == b["advance"].values.tolist()
    assert a["advance"].values[0] > a["advance"].values[1]  # less rudder, wider turn


def test_the_steering_gear_and_the_ship_can_be_overridden():
    """A slower rudder (3 instead of 5 deg/s) checks the Mariner's yaw later: larger first
    overshoot; the override reaches the run (and the label says the ship was modified)."""
    text = (EXAMPLES / "mariner_zigzag.toml").read_text()
    slow = run_scenario(parse_scenario(text)).metrics
    base = zigzag("mariner-nonlinear", math.radians(20.0), math.radians(20.0), sides=1).metrics
    first = {"n": 1}
    assert float(slow["overshoot"].sel(first)) > float(base["overshoot"].sel(first)) + \
        math.radians(1.0)
    ship = maneuver_ship("mariner-nonlinear")
    same = zigzag(maneuver_ship(ship, servo=type(ship.servo).from_mapping(
        {"max_rate_deg": 3.0}, base=ship.servo)), math.radians(20.0), math.radians(20.0),
        sides=1).metrics
    assert float(slow["overshoot"].sel(first)) == float(same["overshoot"].sel(first))
    modified = parse_scenario(TURN.replace("[maneuver]", "[vessel.params]\nw_P0 = 0.35\n[maneuver]"))
    assert modified.ship.params.w_P0 == 0.35 and modified.ship.name == "kvlcc2-l7 (modified: w_P0)"


def test_imo_scenario_is_the_imo_check():
    text = '[vessel]\ncatalog = "mariner-nonlinear"\n[maneuver]\nkind = "imo"\n'
    report = run_scenario(parse_scenario(text))
    lib = imo_check("mariner-nonlinear")
    assert [c.as_dict() for c in report.criteria] == [c.as_dict() for c in lib.criteria]


@pytest.mark.parametrize(
    "edit, match",
    [
        (('kind = "turning"', 'kind = "circle"'),
         r"t.toml: \[maneuver.kind\] Input should be 'turning', 'zigzag', 'pullout', 'spiral', "
         r"'imo' or 'stopping', got 'circle'"),
        (("t_final = 60.0", "heading_deg = 10.0"),
         r"t.toml: \[maneuver\] `heading_deg` is not a key of a 'turning' manoeuvre; its keys: "
         r"rudder \(or rudder_deg\), sides, speed, rps, t_final, dt, record_dt"),
        (("t_final = 60.0", "rudder = 0.5"),
         r"\[maneuver\] give `rudder` \[rad\] or `rudder_deg` \[deg\], not both"),
        (("t_final = 60.0", "speed = 1.0\nrps = 10.0"),
         r"\[maneuver\] give the approach `speed` \[m/s\] or the propeller `rps` \[1/s\], not both"),
        (("t_final = 60.0", "speed = -1.0"),
         r"t.toml: \[maneuver\] `speed` must be > 0 \[m/s\], got -1.0"),
        (("t_final = 60.0", "rps = [10.0, 0.0]"),
         r"t.toml: \[maneuver\] `rps` must be > 0 \[1/s\], got 0.0"),
        (("t_final = 60.0", 't_final = "60"'),
         r"\[maneuver.t_final\] must be a number \[s\] \(not a string or a boolean\), got '60'"),
        (('sides = "starboard"', 'sides = "left"'),
         r"\[maneuver.sides\] Input should be 'both', 'starboard' or 'port', got 'left'"),
        (('catalog = "kvlcc2-l7"', 'catalog = "mariner-nomoto2"'),
         r"\[vessel.catalog\] a manoeuvre needs a ship with a steering gear: a catalog ship "
         r"\(esso-osaka-3m, kvlcc2-full, .*\) or a ship file with a \[steering_gear\], "
         r"got 'mariner-nomoto2' "
         r"\(it has no \[steering_gear\]\)"),
        (('catalog = "kvlcc2-l7"', 'model = "mmg"'),
         r"\[vessel.ship\] a manoeuvre needs a ship with a steering gear: .* got none"),
        (('catalog = "kvlcc2-l7"', 'catalog = "kvlcc2-l7"\nmodel = "mariner"'),
         r"\[vessel.model\] 'kvlcc2-l7' is a ship of model 'mmg', not 'mariner'"),
        (("[maneuver]", "[vessel.initial]\nyaw_rate = 0.1\n[maneuver]"),
         r"\[vessel.initial\] a manoeuvre starts from its steady straight approach"),
        (("[maneuver]", '[actuator]\nmodel = "direct"\n[maneuver]'),
         r"\[actuator.model\] a manoeuvre steers with the ship's steering gear"),
        (("[maneuver]", "[vessel.params]\nw_P0 = 1.5\n[maneuver]"),
         r"\[vessel.params\] `w_P0` must be in .*got 1.5"),
        (("[maneuver]", "[vessel.params]\nk9 = 1.0\n[maneuver]"),
         r"\[vessel.params\] .*k9"),
        (("[maneuver]", "[simulation]\nt_final = 10.0\ndt = 0.1\n[maneuver]"),
         r"a \[maneuver\] scenario takes no \[simulation\] section"),
        (("[maneuver]", '[batch.grid]\n"vessel.params.w_p0" = [0.3, 0.4]\n[maneuver]'),
         r"a \[maneuver\] scenario takes no \[batch\] section"),
    ],
)
def test_bad_maneuver_scenarios_name_file_key_and_value(edit, match):
    assert edit[0] in TURN
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(TURN.replace(*edit), source="t.toml")


STOP = """title = "crash stop"
[vessel]
catalog = "kvlcc2-l7"
[maneuver]
kind = "stopping"
order = [-1.0, -0.5]
"""


def test_stopping_scenario_equals_the_library_call(tmp_path):
    from seahelm.analysis.maneuvers import crash_stop

    job = parse_scenario(STOP, source="s.toml")
    assert job.kind == "stopping" and job.options == {"order": [-1.0, -0.5]}
    got = run_scenario(job).metrics
    lib = crash_stop("kvlcc2-l7", order=[-1.0, -0.5]).metrics
    assert got["track_reach"].values.tolist() == lib["track_reach"].values.tolist()
    assert got.attrs["title"] == "crash stop"
    path = tmp_path / "stop.toml"
    path.write_text(STOP)
    res = runner.invoke(app, ["run", str(path), "--json", "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.stderr
    out = json.loads(res.stdout)
    assert out["maneuver"] == "stopping" and len(out["runs"]) == 2
    assert sorted(Path(p).name for p in out["files"].values()) == [
        "stopping-metrics.nc", "stopping-runs.nc", "stopping.png"]


@pytest.mark.parametrize("edit, match", [
    ("order = [-1.0, -0.5]",
     r"\[maneuver\] `order` must be an astern engine order in \[-1, 0\)"),
    ("order = 0.5", r"\[maneuver\] `order` must be an astern engine order .* got 0.5"),
    ("dead_fraction = 1.5", r"\[maneuver\] `dead_fraction` must be in \[0, 1\)"),
    ("rudder_deg = 10.0", r"`rudder_deg` is not a key of a 'stopping' manoeuvre"),
])
def test_bad_stopping_scenarios(edit, match):
    text = STOP.replace("order = [-1.0, -0.5]", edit)
    if edit.startswith("order = [-1.0"):
        text = STOP.replace("-0.5]", "0.0]")
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(text, source="s.toml")
    ship = STOP.replace('catalog = "kvlcc2-l7"', 'catalog = "mariner-nonlinear"')
    with pytest.raises(ScenarioError, match=r"s.toml: .*no propeller"):
        run_scenario(parse_scenario(ship, source="s.toml"))


def test_a_value_the_manoeuvre_rejects_names_the_key():
    job = parse_scenario(TURN.replace("rudder_deg = 35.0", "rudder_deg = 40.0"), source="t.toml")
    with pytest.raises(ScenarioError, match=r"t.toml: \[maneuver.rudder_deg\] `rudder` .*"):
        run_scenario(job)


def test_strict_numbers_in_simulation_scenarios():
    base = (EXAMPLES / "mariner_course_change.toml").read_text()
    for edit, match in (
        (("kp = 3.0", "kp = true"), r"\[controller.params.kp\] must be a number \(not a string or a boolean\), got True"),
        (("t_final = 900.0", 't_final = "900"'), r"\[simulation.t_final\] must be a number \[s\]"),
        (("t_final = 900.0", "t_final = inf"), r"\[simulation.t_final\] must be a finite number \[s\], got inf"),
        (("dt = 0.1", "dt = nan"), r"\[simulation.dt\] must be a finite number \[s\], got nan"),
    ):
        assert edit[0] in base
        with pytest.raises(ScenarioError, match=match):
            parse_scenario(base.replace(*edit), source="s.toml")


def test_encodings(tmp_path):
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + TURN.encode())
    assert isinstance(load_scenario(bom), ManeuverJob)  # a UTF-8 byte-order mark is fine
    latin = tmp_path / "latin.toml"
    latin.write_bytes(TURN.replace('title = "turning"', 'title = "Kurs\xe4nderung"')
                      .encode("latin-1"))
    with pytest.raises(ScenarioError, match=r"latin.toml: not UTF-8 text \(byte \d+: "
                                            r"b'\\xe4'\); save the scenario as UTF-8"):
        load_scenario(latin)


def test_cli_runs_a_maneuver_scenario(tmp_path):
    path = tmp_path / "turn.toml"
    path.write_text(TURN)
    res = runner.invoke(app, ["run", str(path), "--json", "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.stderr
    out = json.loads(res.stdout)
    assert out["scenario"] == "turning" and out["maneuver"] == "turning-circle"
    (row,) = out["runs"]
    lib = turning_circle("kvlcc2-l7", math.radians(35.0), sides=1, t_final=60.0).metrics
    assert row["advance_m"] == pytest.approx(float(lib["advance"]), rel=1e-12)
    assert sorted(Path(p).name for p in out["files"].values()) == [
        "turning-circle-metrics.nc", "turning-circle-runs.nc", "turning.png"]
    res = runner.invoke(app, ["run", str(path), "--csv"])
    assert res.exit_code == 2
    assert res.stderr.strip().splitlines() == [
        "error: `--csv` writes the time series of a [simulation] scenario; a [maneuver] "
        "scenario (turning) writes NetCDF only"]


def test_spiral_scenario_prints_what_the_spiral_command_prints(tmp_path):
    path = tmp_path / "spiral.toml"
    path.write_text('[vessel]\ncatalog = "kvlcc2-l7"\n[maneuver]\nkind = "spiral"\n'
                    "max_rudder_deg = 10.0\nhold = 150.0\n")
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.stderr
    cmd = runner.invoke(app, ["maneuver", "spiral", "--max-rudder", "10", "--hold", "150",
                              "--json"])
    assert cmd.exit_code == 0, cmd.stderr
    got, want = json.loads(res.stdout), json.loads(cmd.stdout)
    assert got == want and len(got["direct"]) == 33 and got["direct"][0]["rudder_deg"] == 10.0


def test_a_rejected_angle_is_named_as_written():
    job = parse_scenario(TURN.replace("rudder_deg = 35.0", "rudder_deg = 50.0"), source="t.toml")
    with pytest.raises(ScenarioError, match=r"t.toml: \[maneuver.rudder_deg\] .* \(as written: "
                                            r"rudder_deg = 50 deg\)$"):
        run_scenario(job)
