"""A ship in shallow water: Ship.at_depth, ship files with water_depth, --depth, scenarios."""

from __future__ import annotations

import json
import math
import tomllib

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.hydrodynamics.shallow_water import shallow_water_factors
from seahelm.ships import get_ship, read_ship, ship_to_toml, write_ship
from seahelm.ships.files import ship_from_mapping
from seahelm.ships.water_depth import hull_particulars


def run_cli(*args: str):
    return CliRunner().invoke(app, list(args), terminal_width=200)


def test_deep_water_is_the_identity(kvlcc2_full):
    assert kvlcc2_full.water_depth == math.inf and not kvlcc2_full.in_shallow_water
    assert kvlcc2_full.at_depth(math.inf) is kvlcc2_full
    shallow = kvlcc2_full.at_depth(31.2)
    assert shallow.at_depth(math.inf) == kvlcc2_full


def test_at_depth_applies_the_factors_and_keeps_the_deep_parameters(kvlcc2_full):
    shallow = kvlcc2_full.at_depth(31.2)
    f = shallow_water_factors(hull_particulars(kvlcc2_full), 31.2)
    assert shallow.params.Y_v == pytest.approx(kvlcc2_full.params.Y_v * f["Y_v"], rel=1e-14)
    assert shallow.params.m_y == pytest.approx(kvlcc2_full.params.m_y * f["m_y"], rel=1e-14)
    assert shallow.params.m_x == kvlcc2_full.params.m_x
    assert shallow.deep_water_params == kvlcc2_full.params
    assert any(v.startswith("shallow water: h/d = 1.5") for v in shallow.validity)
    # a second depth starts from the deep-water parameters, not the corrected ones
    assert shallow.at_depth(41.6).params == kvlcc2_full.at_depth(41.6).params


def test_a_parameter_change_in_shallow_water_changes_the_deep_value(kvlcc2_full):
    shallow = kvlcc2_full.at_depth(31.2)
    changed = shallow.replace(params={"Y_v": -0.3})
    assert changed.deep_water_params.Y_v == -0.3
    assert changed.params.Y_v == pytest.approx(-0.3 * shallow.params.Y_v / kvlcc2_full.params.Y_v)
    assert changed.water_depth == 31.2


@pytest.mark.parametrize("depth, match", [
    (20.8, "greater than the draft"), (-5.0, "> 0"), (float("nan"), "> 0"), (True, "> 0"),
])
def test_bad_depths_are_errors_naming_water_depth(kvlcc2_full, depth, match):
    with pytest.raises(ParameterError, match=match) as info:
        kvlcc2_full.at_depth(depth)
    assert info.value.field == "water_depth"


def test_shallow_water_needs_the_mmg_model():
    with pytest.raises(ParameterError, match="model 'mariner'.*MMG"):
        get_ship("mariner-nonlinear").at_depth(20.0)


def test_ship_file_round_trip_in_shallow_water(kvlcc2_full, tmp_path):
    shallow = kvlcc2_full.at_depth(31.2)
    text = ship_to_toml(shallow)
    data = tomllib.loads(text)
    assert data["water_depth"] == 31.2
    assert data["params"]["Y_v"] == kvlcc2_full.params.Y_v  # the file holds the deep-water values
    assert ship_from_mapping(data) == shallow
    path = write_ship(shallow, tmp_path / "shallow.toml")
    assert read_ship(path) == shallow
    data["water_depth"] = 10.0
    with pytest.raises(ParameterError, match=r"water_depth.*greater than the draft"):
        ship_from_mapping(data)


def test_cli_depth_turns_wider_in_shallow_water():
    """Tactical diameter of the KVLCC2 (35°, starboard) grows as the depth falls."""
    def td(*extra):
        result = run_cli("maneuver", "turning", "--ship", "kvlcc2-full", "--side", "starboard",
                         "--json", *extra)
        assert result.exit_code == 0, result.output
        return json.loads(result.output)["runs"][0]["tactical_diameter_L"]

    diameters = [td(), td("--depth", str(2.0 * 20.8)), td("--depth", str(1.5 * 20.8)),
                 td("--depth", str(1.2 * 20.8))]
    assert all(b > a for a, b in zip(diameters, diameters[1:])), diameters


def test_cli_depth_bad_input_one_line():
    result = run_cli("maneuver", "turning", "--ship", "kvlcc2-full", "--depth", "10")
    assert result.exit_code == 2
    assert "`--depth` must be greater than the draft 20.8 [m], got 10.0" in result.output
    result = run_cli("imo", "mariner-nonlinear", "--depth", "30")
    assert result.exit_code == 2 and "MMG" in result.output


def test_scenario_water_depth(tmp_path):
    scn = tmp_path / "s.toml"
    scn.write_text('[vessel]\nship = "kvlcc2-full"\nwater_depth = 15\n'
                   '[maneuver]\nkind = "turning"\n')
    result = run_cli("run", str(scn))
    assert result.exit_code == 2
    assert "[vessel.water_depth] must be greater than the draft" in result.output


def test_froude_scaling_in_shallow_water_keeps_h_over_t(kvlcc2_full):
    l7 = get_ship("kvlcc2-l7")
    l7 = l7.at_depth(1.5 * l7.particulars.draft)
    big = l7.scaled(320.0)
    assert big.water_depth / big.particulars.draft == pytest.approx(1.5)
    assert big.deep_water_params == get_ship("kvlcc2-l7").scaled(320.0).params


def test_scenario_params_in_shallow_water_change_the_deep_value(tmp_path):
    """[vessel] params on a ship with water_depth: the deep-water value, corrected (as the ship
    file's [params]); a Monte-Carlo draw likewise."""
    from seahelm.scenario import load_scenario

    kvlcc2 = get_ship("kvlcc2-full")
    expected = kvlcc2.replace(params={"N_r": -0.06}).at_depth(31.2).params
    scn = tmp_path / "s.toml"
    scn.write_text('[vessel]\nship = "kvlcc2-full"\nwater_depth = 31.2\n'
                   '[vessel.params]\nN_r = -0.06\n[maneuver]\nkind = "turning"\n')
    job = load_scenario(scn)
    assert job.ship.params == expected


def test_ship_show_says_the_depth(kvlcc2_full, tmp_path):
    path = write_ship(kvlcc2_full.at_depth(31.2), tmp_path / "s.toml")
    res = run_cli("ship", "show", str(path))
    assert res.exit_code == 0 and "water depth" in res.output and "31.2 [m]" in res.output
    assert "│ deep" in run_cli("ship", "show", "kvlcc2-full").output
