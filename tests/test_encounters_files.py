"""Encounters from files and the command line: a scenario with [[vessel]] tables (and
`seahelm run` of it), maritime-schema traffic situations (JSON as trafficgen writes them), the
`seahelm encounter` command, plots; bad input is exit 2 with one line naming the key (or the
JSON path), unit and value."""

from __future__ import annotations

import json
import math
import uuid

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.encounters.files import (EARTH_RADIUS, KNOT, load_encounter_scenario,
                                      read_traffic_situations)
from seahelm.errors import ParameterError

runner = CliRunner()

SCENARIO = """
title = "crossing, own ship gives way"

[encounter]
t_final = 600.0
avoidance = "rule-based"

[encounter.sensor]
update_interval = 10.0
delay = 2.0

[[vessel]]
ship = "kvlcc2-full"
course_deg = 0.0
avoid = true

[[vessel]]
ship = "kvlcc2-full"
north = 4000.0
east = 4000.0
course_deg = 270.0
speed = 7.0
"""


def _write(tmp_path, text, name="enc.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_a_scenario_with_vessel_tables(tmp_path):
    enc = load_encounter_scenario(_write(tmp_path, SCENARIO))
    assert enc.n_vessels == 2 and enc.n_encounters == 1
    assert enc.course0[0, 1] == pytest.approx(math.radians(270.0))
    assert enc.speed0[0, 1] == 7.0 and enc.sensor.delay == 2.0
    assert enc.avoid.tolist() == [True, False]
    assert type(enc.avoidance).__name__ == "RuleBased"


@pytest.mark.parametrize("old, new, key", [
    ('course_deg = 270.0\n', '', "vessel[1].course_deg"),
    ('north = 4000.0\neast = 4000.0\n', 'north = 100.0\n', "vessel[1].north"),
    ('delay = 2.0', 'delay = 600.0', "encounter.sensor.delay"),
    ('delay = 2.0\n', 'delay = 2.0\n[encounter.colreg]\nhead_on_deg = 40.0\n',
     "encounter.colreg.head_on"),
    ('speed = 7.0', 'speed = -7.0', "vessel[1].speed"),
    ('speed = 7.0', 'sped = 7.0', "vessel[1].sped"),
    ('avoidance = "rule-based"', 'avoidance = "magic"', "encounter.avoidance"),
])
def test_bad_scenarios_name_the_key(tmp_path, old, new, key):
    text = SCENARIO.replace(old, new, 1)
    assert text != SCENARIO
    path = _write(tmp_path, text)
    with pytest.raises(ParameterError) as err:
        load_encounter_scenario(path)
    assert err.value.field == key
    res = runner.invoke(app, ["run", str(path)])
    assert res.exit_code == 2
    line = res.output.strip()
    assert "\n" not in line and key in line, line


def test_seahelm_run_of_an_encounter_scenario_and_the_outputs(tmp_path):
    path = _write(tmp_path, SCENARIO)
    res = runner.invoke(app, ["run", str(path), "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert "crossing-give-way" in res.output and "rule-based" in res.output
    for name in ("encounters.nc", "tracks.png", "cpa.png", "rose.png"):
        assert (tmp_path / "out" / name).stat().st_size > 1000
    import xarray as xr
    with xr.open_dataset(tmp_path / "out" / "encounters.nc") as ds:
        assert ds["north"].dims == ("encounter", "vessel", "time")
        assert not bool(ds["collision"].any())
    # the single-vessel scenario is unchanged: `seahelm run` still runs it as before
    single = _write(tmp_path, 'title = "one"\n[vessel]\nmodel = "nomoto1"\ncatalog = '
                              '"mariner-nomoto1"\n[simulation]\nt_final = 5.0\ndt = 0.1\n',
                    "single.toml")
    res = runner.invoke(app, ["run", str(single), "--json"])
    assert res.exit_code == 0, res.output


def test_encounter_command_compares_methods_in_json(tmp_path):
    path = _write(tmp_path, SCENARIO)
    res = runner.invoke(app, ["encounter", str(path), "--compare", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert set(out["methods"]) == {"none", "rule-based", "velocity-obstacles"}
    rows = {m: {r["situation"]: r for r in v} for m, v in out["methods"].items()}
    assert rows["none"]["crossing-give-way"]["own_acted"] == 0.0
    assert rows["velocity-obstacles"]["crossing-give-way"]["own_acted"] == 1.0


def test_encounter_command_bad_options():
    res = runner.invoke(app, ["encounter", "--monte-carlo", "0"])
    assert res.exit_code == 2 and "--monte-carlo" in res.output
    res = runner.invoke(app, ["encounter", "--monte-carlo", "2", "--avoidance", "magic"])
    assert res.exit_code == 2 and "--avoidance" in res.output


def _situation(own_sog=15.5, target=None):
    from maritime_schema.types.caga import (Initial, OwnShip, Position, ShipStatic,
                                            TargetShip, TrafficSituation)

    def static():
        return ShipStatic(id=uuid.uuid4(), length=320.0, width=58.0)
    own = OwnShip(static=static(), initial=Initial(position=Position(latitude=58.0,
                                                                     longitude=10.0),
                                                   sog=own_sog, cog=0.0, heading=0.0))
    tgt = TargetShip(static=static(), initial=Initial(
        position=Position(latitude=58.036, longitude=10.068), sog=14.0, cog=270.0,
        heading=270.0))
    sit = TrafficSituation(title="crossing", own_ship=own, target_ships=[tgt])
    return json.loads(sit.model_dump_json(by_alias=True, exclude_none=True))


def test_maritime_schema_situations_run_as_a_batch(tmp_path):
    paths = []
    for i, lon in enumerate((10.068, 10.060)):
        raw = _situation()
        raw["targetShips"][0]["initial"]["position"]["longitude"] = lon
        raw["targetShips"][0]["waypoints"] = None
        raw["targetShips"][0].pop("waypoints")
        p = tmp_path / f"s{i}.json"
        p.write_text(json.dumps(raw))
        paths.append(p)
    enc = read_traffic_situations(paths, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                  t_final=600.0, avoidance="velocity-obstacles")
    assert enc.n_encounters == 2
    north = math.radians(0.036) * EARTH_RADIUS
    east = math.radians(0.068) * EARTH_RADIUS * math.cos(math.radians(58.0))
    assert enc.north0[0, 1] == pytest.approx(north) and enc.east0[0, 1] == pytest.approx(east)
    assert enc.speed0[0, 1] == pytest.approx(round(14.0 * KNOT, 2))
    assert enc.course0[0, 1] == pytest.approx(1.5 * math.pi)
    res = enc.run()
    assert res.situation[:, 0].tolist() == [2, 2]  # crossing, own ship gives way
    assert res.verdicts["acted"][:, 0, 0].all() and not res.collision.any()
    # the command line runs them as they are
    out = runner.invoke(app, ["encounter", *map(str, paths), "--t-final", "300", "--json"])
    assert out.exit_code == 0, out.output


@pytest.mark.parametrize("mischief, where", [
    (lambda raw: raw["ownShip"]["initial"].update(sog=-3.0), "ownShip.initial.sog"),
    (lambda raw: [raw["targetShips"][0]["initial"].pop(k) for k in ("cog", "heading")]
     and raw["targetShips"][0].pop("waypoints"), "targetShips.0.initial.cog"),
])
def test_a_situation_that_does_not_validate(tmp_path, mischief, where):
    raw = _situation()
    mischief(raw)
    p = tmp_path / "bad.json"
    p.write_text(json.dumps(raw))
    with pytest.raises(ParameterError) as err:
        read_traffic_situations([p], own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                t_final=60.0)
    assert err.value.field == f"bad.json:{where}"
    res = runner.invoke(app, ["encounter", str(p)])
    assert res.exit_code == 2 and where in res.output and "\n" not in res.output.strip()


def test_monte_carlo_plots(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    from seahelm.encounters import Encounter
    from seahelm.encounters.monte_carlo import monte_carlo_vessels
    from seahelm.plotting.encounters import (initial_bearing, plot_cpa, plot_encounter_tracks,
                                             plot_outcome_rose)

    vessels, geo = monte_carlo_vessels(6, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                       seed=2, detection_range=(2500.0, 3000.0),
                                       tcpa=(60.0, 250.0))
    res = Encounter(vessels, t_final=300.0).run()
    assert np.allclose(initial_bearing(res), geo["bearing"], atol=1e-9)
    ax = plot_outcome_rose(res)
    heights = sum(p.get_height() for p in ax.patches)
    assert heights == 6
    assert plot_encounter_tracks(res, 0).lines and plot_cpa(res).lines
