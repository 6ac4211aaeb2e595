"""Ships: the Ship object, the catalog of ship files, reading and writing ship files."""

from __future__ import annotations

import dataclasses
import json
import math
import pickle
import shutil
import tomllib

import numpy as np
import pytest

from seahelm.actuators.servo import ServoParams
from seahelm.errors import ParameterError
from seahelm.ships import (
    CATALOG,
    Propulsion,
    Ship,
    ShipFileError,
    SteeringGear,
    get_ship,
    read_ship,
    ship_names,
    ship_to_toml,
    with_steering_gear,
    write_ship,
)
from seahelm.ships import catalog as catalog_module
from seahelm.ships.files import ship_from_mapping
from seahelm.ships.writing import ship_to_mapping
from seahelm.vessels import catamaran, container, mariner, mmg, voitkunsky
from seahelm.vessels.mmg_low_speed import ESSO_OSAKA_3M
from seahelm.vessels.nomoto import Nomoto1Params, Nomoto2Params
from seahelm.vessels.particulars import Particulars

# ------------------------------------------------------------------------------------------
# the catalog: ship files that give the vessel modules' published sets, bit for bit
# ------------------------------------------------------------------------------------------
# the Esso Osaka 3 m model's steering gear: its ship file (assumed from the records, no
# published value)
ESSO_SERVO = ServoParams(max_angle=math.radians(35.0), max_rate=math.radians(40.0),
                         time_constant=0.05)
from seahelm.vessels.six_dof.otter import otter_params  # noqa: E402
from seahelm.vessels.six_dof.remus100 import remus100_params  # noqa: E402

def _supply_params():
    """Fossen's supply vessel: m = 6000e3 kg, L = 76.2 m, the bis-scaled M'' and D'' of Fossen
    (2021) App. D (as PVS supply.py gives them), M = m T⁻¹M''T⁻¹, D = m √(g/L) T⁻¹D''T⁻¹."""
    from seahelm.vessels.dp_three_dof import DpThreeDofParams

    m, length, g = 6000.0e3, 76.2, 9.81
    tinv = np.diag([1.0, 1.0, length])
    mbis = np.array([[1.1274, 0, 0], [0, 1.8902, -0.0744], [0, -0.0744, 0.1278]])
    dbis = np.array([[0.0358, 0, 0], [0, 0.1183, -0.0124], [0, -0.0041, 0.0308]])
    mm = m * tinv @ mbis @ tinv
    dd = m * math.sqrt(g / length) * tinv @ dbis @ tinv
    return DpThreeDofParams(**{f"{k}{i + 1}{j + 1}": float(a[i, j]) for k, a in (("m", mm),
                                                                                ("d", dd))
                               for i in range(3) for j in range(3)})


PRESETS = {
    "kvlcc2-full": (mmg.KVLCC2_FULL, mmg.KVLCC2_FULL_SERVO),
    "kvlcc2-l7": (mmg.KVLCC2_L7, mmg.KVLCC2_L7_SERVO),
    "kvlcc2-l7-wp0-0.35": (mmg.KVLCC2_L7_WP0_035, mmg.KVLCC2_L7_SERVO),
    "kvlcc2-l7-xp-0.5": (mmg.KVLCC2_L7_XP_050, mmg.KVLCC2_L7_SERVO),
    "mariner-nonlinear": (mariner.MARINER_NONLINEAR, mariner.MARINER_SERVO),
    "mariner-voitkunsky": (voitkunsky.MARINER_VOITKUNSKY, None),
    "mariner-nomoto2": (Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7175,
                                      length=160.93), None),
    "mariner-nomoto1": (Nomoto1Params(gain=0.185, time_constant=118.0 + 7.8 - 18.5,
                                      speed=7.7175, length=160.93), None),
    "shushlyapin2017-listing": (catamaran.paper_params(), None),
    "shushlyapin2017-consistent": (catamaran.consistent_params(), None),
    "son-nomoto-container": (container.CONTAINER_SHIP, container.CONTAINER_SERVO),
    "esso-osaka-3m": (ESSO_OSAKA_3M, ESSO_SERVO),
    "otter": (otter_params(), None),
    "remus100": (remus100_params(), None),
    "shushlyapin2017-dp": (catamaran.consistent_params(), None),
    "supply": (_supply_params(), None),
}


def test_the_catalog_is_its_ship_files():
    assert ship_names() == tuple(sorted(PRESETS))
    assert sorted(p.stem for p in catalog_module.DATA_DIR.glob("*.toml")) == sorted(PRESETS)
    assert set(CATALOG) == set(PRESETS) and len(CATALOG) == len(PRESETS)
    assert with_steering_gear() == ("esso-osaka-3m", "kvlcc2-full", "kvlcc2-l7", "kvlcc2-l7-wp0-0.35",
                                    "kvlcc2-l7-xp-0.5", "mariner-nonlinear",
                                    "son-nomoto-container")


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_catalog_ships_give_the_published_sets_bit_for_bit(name):
    params, servo = PRESETS[name]
    ship = get_ship(name)
    assert ship.name == name and ship.params == params
    assert ship.params.to_array().tobytes() == params.to_array().tobytes()
    assert ship.model.params_type is type(params)
    if servo is None:
        assert ship.steering_gear is None
    else:
        assert ship.steering_gear.params == servo
        assert ship.steering_gear.actuator.name == "rudder-servo"
    assert ship.provenance and ship.description and ship.validity


def test_catalog_particulars_are_the_published_dimensions_and_the_stated_windage():
    # KVLCC2 (SIMMAN 2008): L 320, B 58, T 20.8, C_b 0.8098; windage: freeboard 9.2 m of hull
    # plus a 40 m x 15 m superstructure 140 m aft of midships (the file's provenance says so)
    full = get_ship("kvlcc2-full").particulars
    assert (full.length, full.beam, full.draft, full.block_coefficient) == (320, 58, 20.8, 0.8098)
    assert full.lateral_area == 320 * 9.2 + 600 and full.frontal_area == 58 * 9.2 + 600
    assert full.windage_centre == pytest.approx(-600 * 140 / (320 * 9.2 + 600), rel=1e-15)
    assert full.displacement == mmg.KVLCC2_FULL.displacement == 312600.0
    l7 = get_ship("kvlcc2-l7").particulars
    k = 7.0 / 320.0
    assert l7.beam == pytest.approx(58 * k, rel=1e-15)
    assert l7.lateral_area == pytest.approx(full.lateral_area * k * k, rel=1e-15)
    assert l7.displacement == mmg.KVLCC2_L7.displacement
    mar = get_ship("mariner-nonlinear").particulars
    assert mar.lateral_area == pytest.approx(0.8 * 160.93 * 8.23, rel=1e-15)
    assert mar.vessel_type == "cargo-loaded" and mar.windage_centre == 0.0
    assert "estimates" in mar.provenance and "estimates" in full.provenance


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_a_ship_file_reads_back_to_the_same_ship(name, tmp_path):
    ship = get_ship(name)
    path = write_ship(ship, tmp_path / f"{name}.toml")
    again = read_ship(path)
    assert again == ship
    assert again.params.to_array().tobytes() == ship.params.to_array().tobytes()
    assert ship_to_toml(again) == ship_to_toml(ship)
    # the text says each number's unit
    text = path.read_text()
    assert "# [m]" in text or "# [m/s]" in text or "# [1/s]" in text


def test_adding_a_catalog_ship_is_one_file(tmp_path, monkeypatch):
    data = tmp_path / "data"
    shutil.copytree(catalog_module.DATA_DIR, data)
    mine = get_ship("kvlcc2-l7").replace(name="my-l7", params={"Y_v": -0.3})
    write_ship(mine, data / "my-l7.toml")
    monkeypatch.setattr(catalog_module, "DATA_DIR", data)
    for cached in (catalog_module._file_names, catalog_module._read,
                   catalog_module._file_has_steering_gear):
        cached.cache_clear()
    try:
        assert "my-l7" in ship_names() and "my-l7" in with_steering_gear()
        assert get_ship("my-l7") == mine and get_ship("my-l7").params.Y_v == -0.3
    finally:
        monkeypatch.undo()
        for cached in (catalog_module._file_names, catalog_module._read,
                       catalog_module._file_has_steering_gear):
            cached.cache_clear()
    assert "my-l7" not in ship_names()


def test_get_ship_takes_a_ship_a_name_or_a_path(tmp_path):
    ship = get_ship("mariner-nonlinear")
    assert get_ship(ship) is ship
    path = write_ship(ship, tmp_path / "m.toml")
    assert get_ship(path) == ship and get_ship(str(path)) == ship
    with pytest.raises(ValueError, match=r"unknown catalog ship 'titanic'; valid: esso-osaka-3m, kvlcc2-full, "
                                         r".* \(or the path of a ship file, \*.toml\)"):
        get_ship("titanic")
    with pytest.raises(ParameterError, match="`ship` must be a Ship, a catalog name or a ship "
                                             "file path, got int"):
        get_ship(3)


def test_register_adds_a_ship_for_this_process():
    ship = get_ship("mariner-nomoto2").replace(name="test-registered-nomoto")
    catalog_module.register(ship)
    try:
        assert get_ship("test-registered-nomoto") is ship
        with pytest.raises(ValueError, match="exists already"):
            catalog_module.register(ship)
    finally:
        catalog_module._REGISTERED.pop("test-registered-nomoto")


# ------------------------------------------------------------------------------------------
# the Ship object
# ------------------------------------------------------------------------------------------
def test_a_ship_checks_itself():
    p = mmg.KVLCC2_L7
    with pytest.raises(ParameterError, match="`model` unknown vessel model 'mmgg'"):
        Ship(name="x", model="mmgg", params=p)
    with pytest.raises(ParameterError, match="`params` model 'mariner' takes MarinerParams, "
                                             "got MMGParams"):
        Ship(name="x", model="mariner", params=p)
    with pytest.raises(ParameterError, match=r"`test_speed` is 2.0 \[m/s\] but the parameter "
                                             r"set's design speed `params.approach_speed` is "
                                             r"1.179 \[m/s\]"):
        Ship(name="x", model="mmg", params=p, test_speed=2.0)
    with pytest.raises(ParameterError, match=r"`test_speed` must be > 0 \[m/s\], got -1.0"):
        Ship(name="x", model="catamaran", params=catamaran.paper_params(), test_speed=-1.0)
    with pytest.raises(ParameterError, match="`propulsion.inputs` model 'mmg' has no input "
                                             "'thruster_rate'"):
        Ship(name="x", model="mmg", params=p, propulsion=Propulsion(kind="azimuth",
                                                                    inputs=("thruster_rate",)))
    with pytest.raises(ParameterError, match="`coefficient_sources` names no parameter of "
                                             "MMGParams: Y_q"):
        Ship(name="x", model="mmg", params=p, coefficient_sources={"Y_q": "fit"})
    with pytest.raises(ParameterError, match="`name` must be a non-empty text"):
        Ship(name=" ", model="mmg", params=p)
    with pytest.raises(ParameterError, match="`params` actuator 'rudder-servo' takes "
                                             "ServoParams"):
        SteeringGear(actuator="rudder-servo", params=p)


def test_ship_derived_values_and_sources():
    ship = get_ship("kvlcc2-l7")
    assert ship.test_speed == ship.approach_speed == 1.179 and ship.length == 7.0
    assert ship.max_rudder == pytest.approx(math.radians(35.0), rel=1e-15)
    assert ship.has_propeller and ship.servo is ship.steering_gear.params
    fitted = ship.replace(coefficient_sources={"Y_v": "fit to trial 3 (s.e. 0.004)"})
    assert fitted.source_of("Y_v") == "fit to trial 3 (s.e. 0.004)"
    assert fitted.source_of("N_v") == ship.provenance
    faster = ship.replace(params={"approach_speed": 1.5})
    assert faster.test_speed == 1.5  # the test speed follows the parameter set
    cat = get_ship("shushlyapin2017-listing")
    assert cat.test_speed is None and math.isnan(cat.approach_speed) and cat.length == 22.3
    with pytest.raises(ParameterError, match="has no steering gear"):
        _ = cat.servo


def test_particulars_check_and_derive():
    with pytest.raises(ParameterError, match=r"`beam` must be > 0 \[m\], got -1"):
        Particulars(length=100.0, beam=-1.0, draft=5.0, block_coefficient=0.7)
    with pytest.raises(ParameterError, match=r"`block_coefficient` must be in \(0, 1\] \[-\]"):
        Particulars(length=100.0, beam=10.0, draft=5.0, block_coefficient=1.2)
    p = Particulars(length=100.0, beam=10.0, draft=5.0, block_coefficient=0.7)
    assert p.displacement_volume == pytest.approx(3500.0, rel=1e-15)
    with pytest.raises(ParameterError, match=r"`particulars.lateral_area` is not known \[m²\] "
                                             "and wind loads needs it"):
        p.require("lateral_area", "wind loads")
    big = p.scaled(2.0)
    assert big.length == 200.0 and big.lateral_area is None


# ------------------------------------------------------------------------------------------
# bad ship files: one line naming the file, the key and the unit
# ------------------------------------------------------------------------------------------
def _mariner_file(tmp_path, edit=None, drop=None):
    text = ship_to_toml(get_ship("mariner-nonlinear"))
    lines = text.splitlines()
    if drop is not None:
        lines = [ln for ln in lines if not ln.startswith(drop)]
    text = "\n".join(lines) + "\n"
    if edit is not None:
        text = text.replace(*edit, 1)
    path = tmp_path / "m.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(("edit", "drop", "match"), [
    (("\nlength = 160.93", "\nlenght = 160.93"), None,
     r"m.toml: `params.lenght` is an unknown key: not a parameter of MarinerParams \(did you "
     r"mean `length`\?\)"),
    (("[propulsion]", "[propulsion]"), "beam =",
     r"m.toml: `particulars` misses required particular\(s\): beam \[m\]"),
    (("max_rate = ", "max_rate = -"), None,
     r"m.toml: `steering_gear.params.max_rate` must be in \(0, inf\] \[rad/s\], got -0.08"),
    (('model = "mariner"', 'model = "marnier"'), None,
     r"m.toml: `model` 'marnier' is not a vessel model; valid: catamaran, .*mmg"),
    (("format = 1", "format = 2"), None,
     r"m.toml: `format` must be 1 \(the format this seahelm reads\), got 2"),
    (("format = 1", "format = 1\nnmae = 'x'"), None,
     r"m.toml: `nmae` is an unknown key \(did you mean `name`\?\); valid here: base, "),
    (("[particulars]", "[particulars]\ndraught = 8.0"), None,
     r"m.toml: `particulars.draught` is an unknown key \(did you mean `draft`\?\)"),
    (("nominal_speed = 7.7175", "nominal_speed = 'fast'"), None,
     r"m.toml: `params.nominal_speed` must be a number \[m/s\], got 'fast'"),
    (("[particulars]\n", "[particulars]\n"), "length =",
     r"m.toml: `params` misses 1 parameter\(s\) of MarinerParams: length \[m\]"),
    (('actuator = "rudder-servo"', 'actuator = "tiller"'), None,
     r"m.toml: `steering_gear.actuator` 'tiller' is not an actuator; valid: direct, "),
    (("format = 1", "format = 1\ntest_speed = 5.0"), None,
     r"m.toml: `test_speed` is 5.0 \[m/s\] but the parameter set's design speed"),
    (("format = 1", "format = 1 ="), None, r"m.toml: is not valid TOML"),
])
def test_bad_ship_files_name_the_file_the_key_and_the_unit(tmp_path, edit, drop, match):
    path = _mariner_file(tmp_path, edit, drop)
    with pytest.raises(ShipFileError, match=match):
        read_ship(path)


def test_unreadable_ship_files(tmp_path):
    with pytest.raises(ShipFileError, match="nope.toml: no such ship file"):
        read_ship(tmp_path / "nope.toml")
    with pytest.raises(ShipFileError, match="is a directory, not a ship file"):
        read_ship(tmp_path)


def test_attribution_uses_the_error_fields_not_the_message_words(tmp_path, monkeypatch):
    # reword the parameter checks' messages: the ship file still names the key and the unit
    import seahelm.parameters as parameters

    def reworded(f, name, value):
        if isinstance(value, (int, float)) and value < 0 and f.metadata.get("low", 0) >= 0:
            raise ParameterError("is quite wrong (reworded)", field=name,
                                 unit=f.metadata.get("unit"), value=value)

    monkeypatch.setattr(parameters, "_check_number", reworded)
    path = _mariner_file(tmp_path, ("max_rate = ", "max_rate = -"))
    with pytest.raises(ShipFileError) as info:
        read_ship(path)
    err = info.value
    assert (err.field, err.unit, err.source) == ("steering_gear.params.max_rate", "rad/s",
                                                 str(path))
    assert str(err) == f"{path}: `steering_gear.params.max_rate` is quite wrong (reworded)"


def test_parameter_errors_carry_fields_and_survive_pickling():
    with pytest.raises(ParameterError) as info:
        ServoParams(max_rate=-1.0)
    err = info.value
    assert (err.field, err.unit, err.value) == ("max_rate", "rad/s", -1.0)
    outer = err.within("actuator.params", run=3)
    assert outer.field == "actuator.params.max_rate" and outer.run == 3
    assert str(outer).startswith("`actuator.params.max_rate` must be in (0, inf]")
    again = pickle.loads(pickle.dumps(outer))
    assert type(again) is ParameterError and again.__dict__ == outer.__dict__
    assert str(again) == str(outer)
    file_err = ShipFileError("must be > 0", source="a.toml", field="params.x", unit="m")
    back = pickle.loads(pickle.dumps(file_err))
    assert str(back) == "a.toml: `params.x` must be > 0" and back.source == "a.toml"


def test_a_ship_file_may_start_from_a_base_ship(tmp_path):
    (tmp_path / "mine.toml").write_text(
        'format = 1\nname = "my-l7"\nmodel = "mmg"\nbase = "kvlcc2-l7"\n'
        '[params]\nY_v = -0.3\n[steering_gear.params]\nmax_angle_deg = 30\n')
    mine = read_ship(tmp_path / "mine.toml")
    base = get_ship("kvlcc2-l7")
    assert mine.params == base.params.replace(Y_v=-0.3)
    assert mine.steering_gear.params.max_angle == pytest.approx(math.radians(30), rel=1e-15)
    assert mine.steering_gear.params.max_rate == base.steering_gear.params.max_rate
    assert mine.particulars == base.particulars
    assert "Changed from the base ship 'kvlcc2-l7': params.Y_v, " \
           "steering_gear.params.max_angle_deg" in mine.provenance
    # a base given as a path, relative to the file
    (tmp_path / "mine2.toml").write_text(
        'format = 1\nname = "my-l7b"\nmodel = "mmg"\nbase = "mine.toml"\n[params]\nN_v = -0.1\n')
    mine2 = read_ship(tmp_path / "mine2.toml")
    assert mine2.params == mine.params.replace(N_v=-0.1)
    (tmp_path / "bad.toml").write_text(
        'format = 1\nname = "x"\nmodel = "mmg"\nbase = "kvlcc3"\n')
    with pytest.raises(ShipFileError, match=r"bad.toml: `base` unknown catalog ship 'kvlcc3'"):
        read_ship(tmp_path / "bad.toml")
    with pytest.raises(ShipFileError, match="`base` needs the catalog"):
        ship_from_mapping(tomllib.loads((tmp_path / "mine.toml").read_text()))


def test_a_ship_file_without_a_base_gives_every_parameter():
    data = {"format": 1, "name": "x", "model": "mmg", "params": {"Y_v": -0.3}}
    with pytest.raises(ShipFileError, match=r"`params` misses 50 parameter\(s\) of MMGParams: "
                                            r"length \[m\], breadth \[m\]"):
        ship_from_mapping(data)


def test_write_ship_does_not_overwrite_by_accident(tmp_path):
    ship = get_ship("mariner-nomoto2")
    path = write_ship(ship, tmp_path / "n.toml")
    with pytest.raises(FileExistsError, match="exists; pass overwrite=True"):
        write_ship(ship, path)
    write_ship(ship.replace(description="changed"), path, overwrite=True)
    assert read_ship(path).description == "changed"
    assert [p.name for p in tmp_path.iterdir()] == ["n.toml"]  # no temporary file left


def test_mapping_form_is_plain_data():
    data = ship_to_mapping(get_ship("kvlcc2-l7"))
    json.dumps(data)  # plain data only
    assert data["model"] == "mmg" and data["steering_gear"]["actuator"] == "rudder-servo"
    assert data["params"]["length"] == 7.0 and "test_speed" not in data


# ------------------------------------------------------------------------------------------
# ships where the manoeuvres take them
# ------------------------------------------------------------------------------------------
def test_maneuver_ship_takes_ships_names_paths_and_parameter_sets(tmp_path):
    from seahelm.analysis.maneuvers import maneuver_ship

    ship = get_ship("kvlcc2-l7")
    assert maneuver_ship("kvlcc2-l7") is ship and maneuver_ship(ship) is ship
    path = write_ship(ship, tmp_path / "k.toml")
    assert maneuver_ship(path) == ship
    assert maneuver_ship(mmg.KVLCC2_L7) is ship  # a catalog ship's own parameter set
    other = maneuver_ship(mmg.KVLCC2_L7.replace(Y_v=-0.3), servo=mmg.KVLCC2_L7_SERVO,
                          name="s1")
    assert other.name == "s1" and other.servo == mmg.KVLCC2_L7_SERVO
    slower = maneuver_ship(ship, servo=dataclasses.replace(mmg.KVLCC2_L7_SERVO, max_rate=0.1))
    assert slower.servo.max_rate == 0.1 and slower.params is ship.params
    with pytest.raises(ParameterError, match="ship 'mariner-nomoto2' has no steering gear"):
        maneuver_ship("mariner-nomoto2")


def test_a_ship_file_turns_exactly_as_the_catalog_ship(tmp_path):
    from seahelm.analysis.maneuvers import turning_circle

    path = write_ship(get_ship("kvlcc2-l7"), tmp_path / "k.toml")
    a = turning_circle("kvlcc2-l7", math.radians(35.0), sides=1, t_final=30.0)
    b = turning_circle(path, math.radians(35.0), sides=1, t_final=30.0)
    for name in ("heading", "north", "east"):
        np.testing.assert_array_equal(a.runs[name].values, b.runs[name].values)


# ------------------------------------------------------------------------------------------
# ships in scenario files: [vessel] ship = a catalog name or a ship file
# ------------------------------------------------------------------------------------------
SCENARIO = """
title = "t"
[vessel]
{ship}
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 20.0
dt = 0.1
"""


def test_a_scenario_takes_a_ship_file_relative_to_itself(tmp_path):
    from seahelm.scenario import load_scenario, run_scenario

    folder = tmp_path / "study"
    folder.mkdir()
    write_ship(get_ship("mariner-nomoto2"), folder / "mine.toml")
    (folder / "a.toml").write_text(SCENARIO.format(ship='ship = "mine.toml"'))
    (folder / "b.toml").write_text(SCENARIO.format(ship='catalog = "mariner-nomoto2"'))
    a = run_scenario(load_scenario(folder / "a.toml"))
    b = run_scenario(load_scenario(folder / "b.toml"))
    np.testing.assert_array_equal(a.state, b.state)
    np.testing.assert_array_equal(a.command, b.command)
    (folder / "c.toml").write_text(SCENARIO.format(ship='ship = "nothere.toml"'))
    with pytest.raises(ParameterError, match=r"c.toml: \[vessel.ship\] .*nothere.toml: no such "
                                             "ship file"):
        load_scenario(folder / "c.toml")
    (folder / "d.toml").write_text(SCENARIO.format(ship='ship = "mine.toml"\n'
                                                        'catalog = "mariner-nomoto2"'))
    with pytest.raises(ParameterError, match="give `ship` or `catalog`"):
        load_scenario(folder / "d.toml")


def test_lvovs_particulars_come_from_the_ship():
    from seahelm.studies.lvov2014 import MARINER_PARTICULARS, ShipParticulars

    made = ShipParticulars.from_ship("mariner-voitkunsky",
                                     rudder_area=MARINER_PARTICULARS.rudder_area,
                                     sway_mass=MARINER_PARTICULARS.sway_mass,
                                     yaw_inertia=MARINER_PARTICULARS.yaw_inertia)
    assert made == MARINER_PARTICULARS  # the study's Mariner is the catalog's Mariner
    with pytest.raises(ParameterError, match="has no particulars"):
        ShipParticulars.from_ship("shushlyapin2017-listing")


def test_a_new_vessel_model_is_one_module_and_one_registry_line(tmp_path, monkeypatch):
    # the "module": a model declared by its signals over compiled functions (here Nomoto-2's)
    from seahelm.registry import VESSEL_MODELS
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.problem import Problem
    from seahelm.vessels.base import VesselModel
    from seahelm.vessels.nomoto import NOMOTO2

    toy = VesselModel(**{**{f.name: getattr(NOMOTO2, f.name)
                            for f in dataclasses.fields(VesselModel)},
                         "name": "toy", "description": "a new model"})
    monkeypatch.setitem(VESSEL_MODELS, "toy", toy)  # the one registry line
    # its ships are ship files, with nothing else to write
    path = tmp_path / "toy.toml"
    text = ship_to_toml(get_ship("mariner-nomoto2")).replace('model = "nomoto2"',
                                                             'model = "toy"')
    path.write_text(text.replace('name = "mariner-nomoto2"', 'name = "toy-ship"'))
    ship = read_ship(path)
    assert ship.model is toy and ship.test_speed == 7.7175
    kw = dict(x0=np.zeros(5), t_final=2.0, dt=0.1, reference={"rudder_command": 0.1})
    new = simulate(Problem(ship=path, jit=False, **kw))
    old = simulate(NOMOTO2, get_ship("mariner-nomoto2").params, **kw)
    np.testing.assert_allclose(new.state, old.state, rtol=1e-12, atol=1e-14)
