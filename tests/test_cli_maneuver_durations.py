"""Each manoeuvre's ``--t-final`` help says how its default is made (issue 44, item 7): the
turning circle, the zig-zag and the pull-out all said "estimated from the steady turn"; the
pull-out's default is 60 L/U0 and has no steady turn in it, the zig-zag's is made of rudder
swings and trigger angles."""

from __future__ import annotations

import json
import math

from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.ships import get_ship

runner = CliRunner()


def _help(*args: str) -> str:
    res = runner.invoke(app, [*args, "--help"], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    return " ".join(res.stdout.replace("│", " ").split())


def _t_final_help(text: str) -> str:
    return text.split("--t-final", 1)[1].split(" --dt ", 1)[0]


def test_no_manoeuvre_says_its_default_duration_is_estimated_from_the_steady_turn():
    for name in ("turning", "zigzag", "pullout"):
        assert "estimated from the steady turn" not in _help("maneuver", name), name


def test_each_duration_help_gives_its_rule():
    assert "1.3 x 360 deg / the slowest yaw rate of the batch's steady turns" in \
        _t_final_help(_help("maneuver", "turning"))
    zz = _t_final_help(_help("maneuver", "zigzag"))
    assert "4 rudder swings + 24 x the trigger angle" in zz and "reachable" in zz
    po = _t_final_help(_help("maneuver", "pullout"))
    assert "60 L/U0" in po and "steady turn" not in po


def test_the_pull_out_default_is_what_its_help_says():
    ship = get_ship("mariner-nonlinear")
    res = runner.invoke(app, ["maneuver", "pullout", "--ship", "mariner-nonlinear",
                              "--rudder", "20", "--side", "starboard", "--json"])
    assert res.exit_code == 0, res.output
    got = json.loads(res.stdout)
    t_final, dt = got["t_final_s"], got["dt_s"]
    expected = 60.0 * ship.length / ship.test_speed  # 60 L/U0, up to a whole step
    assert expected <= t_final < expected + dt + 1e-9 and math.isfinite(t_final)
