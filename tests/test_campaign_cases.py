"""Cases found by the session's bad-input campaign (issue 33's note), each now one clear
error: ship files that loop, block or are something else; outputs that are devices, FIFOs or
links; ships that cannot be; Problem fields of the wrong kind."""

from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.ships import ShipFileError, get_ship, read_ship, ship_to_toml
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _one_error(args, match, code=2):
    t0 = time.monotonic()
    res = runner.invoke(app, args)
    assert res.exit_code == code, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and match in lines[0], lines
    assert time.monotonic() - t0 < 30.0  # (no hang)


def test_base_cycles_are_named(tmp_path):
    (tmp_path / "self.toml").write_text('format = 1\nname = "s"\nbase = "self.toml"\n')
    (tmp_path / "a.toml").write_text('format = 1\nname = "a"\nbase = "b.toml"\n')
    (tmp_path / "b.toml").write_text('format = 1\nname = "b"\nbase = "a.toml"\n')
    _one_error(["ship", "check", str(tmp_path / "self.toml")],
               "`base` forms a cycle: self.toml -> self.toml")
    with pytest.raises(ShipFileError, match=r"`base` forms a cycle: a.toml -> b.toml -> a.toml"):
        read_ship(tmp_path / "a.toml")


def test_a_ship_file_that_is_no_file_is_refused_at_once(tmp_path):
    fifo = tmp_path / "f.toml"
    os.mkfifo(fifo)
    _one_error(["ship", "check", str(fifo)], "is not a regular file")
    zero = tmp_path / "z.toml"
    zero.symlink_to("/dev/zero")
    _one_error(["maneuver", "turning", "--ship", str(zero)], "is not a regular file")
    (tmp_path / "adir").mkdir()
    _one_error(["maneuver", "turning", "--ship", str(tmp_path / "adir")],
               "is a directory, not a ship file")
    _one_error(["maneuver", "zigzag", "--ship", str(EXAMPLES / "mariner_zigzag.toml")],
               "is a scenario file, not a ship file")


def test_a_base_of_another_model_and_a_byte_order_mark(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text('format = 1\nname = "x"\nmodel = "nomoto2"\nbase = "kvlcc2-l7"\n')
    with pytest.raises(ShipFileError, match="`base` 'kvlcc2-l7' is a ship of model 'mmg', not "
                                            "'nomoto2'"):
        read_ship(path)
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + ship_to_toml(get_ship("kvlcc2-l7")).encode())
    assert read_ship(bom) == get_ship("kvlcc2-l7")


def test_outputs_that_are_devices_fifos_or_links_are_refused(tmp_path):
    result = tmp_path / "result.nc"
    result.write_bytes(b"\x89HDF\r\n\x1a\n" + b"\0" * 64)  # (refused before it is read)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    _one_error(["report", str(result), "-o", str(fifo)], "is not a regular file")
    assert fifo.is_fifo()
    loop_a, loop_b = tmp_path / "la.html", tmp_path / "lb.html"
    loop_a.symlink_to(loop_b)
    loop_b.symlink_to(loop_a)
    _one_error(["report", str(result), "-o", str(loop_a)], "is a loop of symbolic links")
    other = tmp_path / "important.txt"
    other.write_text("keep")
    link = tmp_path / "link.html"
    link.symlink_to(other)
    _one_error(["report", str(result), "-o", str(link)], "is a symbolic link (to")
    assert link.is_symlink() and other.read_text() == "keep"


def test_ships_that_cannot_be():
    ship = get_ship("kvlcc2-l7")
    with pytest.raises(ParameterError, match="`name` must be printable text"):
        ship.replace(name="tanker\x00\n\u202e")
    with pytest.raises(ParameterError, match="the actuator 'rudder-servo' drives rudder_angle, "
                                             "which model 'catamaran' takes no input of"):
        get_ship("shushlyapin2017-listing").replace(steering_gear=ship.steering_gear)
    import dataclasses

    with pytest.raises(ParameterError, match="'spaceship' is not one of Blendermann's"):
        ship.replace(particulars=dataclasses.replace(ship.particulars, vessel_type="spaceship"))


def test_a_scenarios_ship_file_is_relative_to_the_scenario_only(tmp_path, monkeypatch):
    from seahelm.scenario import load_scenario
    from seahelm.scenario.errors import ScenarioError
    from seahelm.ships import write_ship

    write_ship(get_ship("mariner-nomoto2"), tmp_path / "mine.toml")
    (tmp_path / "sub").mkdir()
    scenario = tmp_path / "sub" / "s.toml"
    scenario.write_text('title = "t"\n[vessel]\nship = "mine.toml"\n[simulation]\n'
                        't_final = 10.0\ndt = 0.1\n')
    monkeypatch.chdir(tmp_path)  # a mine.toml here must not be taken
    with pytest.raises(ScenarioError, match=r"\[vessel.ship\] .*sub/mine.toml: no such ship "
                                            r"file"):
        load_scenario(scenario)


BASE = dict(ship="mariner-nomoto2", x0=np.zeros(5), t_final=2.0, dt=0.1,
            reference={"rudder_command": 0.1})


@pytest.mark.parametrize(("changes", "field", "match"), [
    ({"environment": "storm"}, "environment", "must be an Environment"),
    ({"metadata": [1, 2]}, "metadata", "must be a mapping"),
    ({"metadata": {"f": object()}}, "metadata.f", "values must be text or numbers"),
    ({"seed": "x"}, "seed", "must be a whole number >= 0"),
    ({"seed": -1}, "seed", "must be a whole number >= 0"),
    ({"seed": 1.5}, "seed", "must be a whole number >= 0"),
    ({"bounds": {"heading": (float("nan"), 1.0)}}, "bounds.heading", "low < high"),
    ({"bounds": {"heading": (1.0, -1.0)}}, "bounds.heading", "low < high"),
    ({"params": {"gain": 0.1}}, "params", "must be Nomoto2Params, a sequence of them"),
    ({"params": get_ship("kvlcc2-l7").params}, "params", "must be Nomoto2Params, got MMGParams"),
    ({"integrator": 4}, "integrator", "integrator"),
    ({"integrator": None}, "integrator", "integrator"),
])
def test_problem_fields_of_the_wrong_kind(changes, field, match):
    with pytest.raises(ParameterError, match=match) as err:
        Problem(**{**BASE, **changes})
    assert err.value.field == field


def test_simulate_says_what_it_takes():
    with pytest.raises(ParameterError, match="must be a VesselModel or a Problem, got str"):
        simulate("kvlcc2-l7")
    with pytest.raises(ParameterError, match="give a Problem, or a `model`"):
        simulate(None)


def test_more_cases_said_clearly(tmp_path):
    text = ship_to_toml(get_ship("mariner-nomoto2")) + (
        '[steering_gear]\nactuator = "rudder-servo"\n[steering_gear.params]\n'
        'max_angle = 0.6\nmax_rate = 0.04\ntime_constant = 1.0\n')
    path = tmp_path / "n.toml"
    path.write_text(text)
    # a constant-speed model with a steering gear runs the manoeuvres (issue 29, item 6)
    res = runner.invoke(app, ["maneuver", "turning", "--ship", str(path), "--json"])
    assert res.exit_code == 0, res.stderr
    _one_error(["maneuver", "turning", "--ship", str(path), "--speed", "5"],
               "`--speed` must be the constant speed U = 7.7175 [m/s] of model 'nomoto2'")
    _one_error(["maneuver", "turning", "--dt", "inf"], "`--dt` must be a finite number > 0 [s]")
    with pytest.raises(ParameterError, match=r"`t_final` must be a finite number > 0 \[s\]"):
        Problem(**{**BASE, "t_final": float("inf")})
    with pytest.raises(ParameterError, match="must be real numbers, got complex") as err:
        simulate(Problem(**{**BASE, "x0": np.zeros(5, dtype=complex)}))
    assert err.value.field == "x0"
    with pytest.raises(ParameterError, match="must be real numbers, got text"):
        simulate(Problem(**{**BASE, "reference": {"rudder_command": "0.1"}}))


def test_a_manoeuvre_scenario_on_a_constant_speed_ship_runs(tmp_path):
    text = ship_to_toml(get_ship("mariner-nomoto2")) + (
        '[steering_gear]\nactuator = "rudder-servo"\n[steering_gear.params]\n'
        'max_angle = 0.6\nmax_rate = 0.04\ntime_constant = 1.0\n')
    (tmp_path / "n.toml").write_text(text)
    scenario = tmp_path / "s.toml"
    scenario.write_text('title = "t"\n[vessel]\nship = "n.toml"\n[maneuver]\nkind = "turning"\n'
                        'rudder_deg = 20\n')
    res = runner.invoke(app, ["run", str(scenario)])
    assert res.exit_code == 0, res.stderr
    assert "mariner-nomoto2" in res.stdout


def test_the_default_rudder_never_exceeds_the_steering_gear(tmp_path):
    import json

    (tmp_path / "g30.toml").write_text('format = 1\nname = "g30"\nmodel = "mmg"\n'
                                       'base = "kvlcc2-l7"\n[steering_gear.params]\n'
                                       'max_angle_deg = 30\n')
    res = runner.invoke(app, ["maneuver", "turning", "--ship", str(tmp_path / "g30.toml"),
                              "--side", "starboard", "--t-final", "30", "--json"])
    assert res.exit_code == 0, res.stderr
    assert json.loads(res.stdout)["runs"][0]["rudder_deg"] == pytest.approx(30.0, rel=1e-12)
    _one_error(["maneuver", "turning", "--ship", str(tmp_path / "g30.toml"), "--rudder", "35"],
               "`--rudder` must be in (0, 30] [deg]")
