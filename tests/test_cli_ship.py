"""``seahelm ship list|show|check`` and ship files wherever the CLI takes a ship (CliRunner)."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.ships import get_ship, read_ship, ship_names

runner = CliRunner()


def test_ship_list_names_the_catalog():
    res = runner.invoke(app, ["ship", "list", "--json"])
    assert res.exit_code == 0, res.stderr
    rows = json.loads(res.stdout)["ships"]
    assert [r["name"] for r in rows] == list(ship_names())
    l7 = next(r for r in rows if r["name"] == "kvlcc2-l7")
    assert (l7["model"], l7["steering_gear"], l7["test_speed_mps"]) == ("mmg", "rudder-servo",
                                                                        1.179)
    table = runner.invoke(app, ["ship", "list"], terminal_width=80)
    assert table.exit_code == 0 and "shushlyapin2017-consistent" in table.stdout  # whole names


def test_ship_show_prints_parameters_with_units_and_sources():
    res = runner.invoke(app, ["ship", "show", "kvlcc2-l7"], terminal_width=120)
    assert res.exit_code == 0, res.stderr
    for text in ("rudder-servo: ±35 deg, 15.8 deg/s, lag 0.1 s", "single fixed-pitch propeller",
                 "Y_v", "[m]", "Yasukawa & Yoshimura (2015)", "deep water"):
        assert text in res.stdout, text
    data = json.loads(runner.invoke(app, ["ship", "show", "kvlcc2-l7", "--json"]).stdout)
    y_v = next(p for p in data["parameters"] if p["name"] == "Y_v")
    assert y_v["value"] == -0.315 and y_v["unit"] == "-" and "Yasukawa" in y_v["source"]


def test_show_toml_writes_a_ship_file_that_reads_back_identical(tmp_path):
    res = runner.invoke(app, ["ship", "show", "mariner-nonlinear", "--toml"])
    assert res.exit_code == 0, res.stderr
    path = tmp_path / "m.toml"
    path.write_text(res.stdout)
    assert read_ship(path) == get_ship("mariner-nonlinear")
    ok = runner.invoke(app, ["ship", "check", str(path)])
    assert ok.exit_code == 0 and "valid ship 'mariner-nonlinear'" in ok.stdout


def test_imo_of_a_ship_file_equals_imo_of_the_catalog_ship(tmp_path):
    path = tmp_path / "k.toml"
    path.write_text(runner.invoke(app, ["ship", "show", "kvlcc2-l7", "--toml"]).stdout)
    by_file = runner.invoke(app, ["imo", str(path), "--json"])
    by_name = runner.invoke(app, ["imo", "kvlcc2-l7", "--json"])
    assert by_file.exit_code == 0 and by_name.exit_code == 0, by_file.stderr
    assert json.loads(by_file.stdout) == json.loads(by_name.stdout)
    turn = runner.invoke(app, ["maneuver", "turning", "--ship", str(path), "--rudder", "35",
                               "--t-final", "30", "--json"])
    assert turn.exit_code == 0 and json.loads(turn.stdout)["ship"] == "kvlcc2-l7"


def test_bad_ship_files_exit_2_with_one_line_naming_file_key_and_unit(tmp_path):
    text = runner.invoke(app, ["ship", "show", "kvlcc2-l7", "--toml"]).stdout
    cases = {
        "unknown.toml": (text.replace("[params]", "[params]\nY_vv = 1.0", 1),
                         "`params.Y_vv` is an unknown key: not a parameter of MMGParams"),
        "range.toml": (text.replace("rudder_area = 0.0539", "rudder_area = -0.0539", 1),
                       "`params.rudder_area` must be in (0, inf] [m²], got -0.0539"),
        "model.toml": (text.replace('model = "mmg"', 'model = "mgm"', 1),
                       "`model` 'mgm' is not a vessel model; valid:"),
        "missing.toml": ("\n".join(ln for ln in text.splitlines()
                                   if not ln.startswith("draft =")) + "\n",
                         "misses 1 parameter(s) of MMGParams: draft [m]"),
    }
    for name, (content, message) in cases.items():
        path = tmp_path / name
        path.write_text(content)
        for args in (["imo", str(path)], ["ship", "check", str(path)],
                     ["maneuver", "turning", "--ship", str(path)]):
            res = runner.invoke(app, args)
            assert res.exit_code == 2, (args, res.stdout, res.stderr, res.exception)
            lines = res.stderr.strip().splitlines()
            assert len(lines) == 1 and lines[0].startswith(f"error: {path}: "), lines
            assert message in lines[0], (message, lines[0])
    res = runner.invoke(app, ["ship", "show", "kvlcc2-l7", "--toml", "--json"])
    assert res.exit_code == 2
