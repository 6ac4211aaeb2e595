"""A scenario's problem carries its ship (issue 46 item 3): the ship's name, model and
provenance reach the result's metadata and the dataset's attributes, a ship file's path too;
the scenario's key table is derived from ``Problem``'s fields; ``Problem``, ``Ship``,
``get_ship`` and ``simulate`` are importable from ``seahelm``."""

from __future__ import annotations

import dataclasses
import shutil
from pathlib import Path

import pytest

import seahelm
from seahelm.scenario import parse_scenario, run_scenario
from seahelm.ships import get_ship

TEXT = """
title = "t"
[vessel]
ship = "{ship}"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 2.0
dt = 0.1
"""


def test_the_public_names_are_importable_from_seahelm():
    from seahelm.ships import Ship
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.problem import Problem

    assert seahelm.Problem is Problem and seahelm.Ship is Ship and seahelm.simulate is simulate
    assert seahelm.get_ship("mariner-nomoto2") is get_ship("mariner-nomoto2")


def test_a_catalog_ship_reaches_the_result_metadata_and_attrs():
    batch = parse_scenario(TEXT.format(ship="mariner-nomoto2"), source="s.toml")
    ship = get_ship("mariner-nomoto2")
    assert batch.ship is ship  # the problem is the ship's
    result = run_scenario(batch)
    assert result.metadata["ship"] == "mariner-nomoto2"
    assert result.metadata["ship_model"] == "nomoto2"
    assert result.metadata["ship_provenance"] == ship.provenance and ship.provenance
    assert "ship_file" not in result.metadata
    attrs = result.to_xarray().attrs
    assert attrs["ship"] == "mariner-nomoto2" and attrs["ship_provenance"] == ship.provenance


def test_a_ship_file_reaches_the_result_with_its_path(tmp_path):
    src = Path(seahelm.__file__).parent / "ships" / "data" / "mariner-nomoto2.toml"
    shutil.copy(src, tmp_path / "my-ship.toml")
    scenario = tmp_path / "s.toml"
    scenario.write_text(TEXT.format(ship="my-ship.toml"))
    batch = parse_scenario(scenario.read_text(), source=str(scenario))
    result = run_scenario(batch)
    assert result.metadata["ship_file"] == "my-ship.toml"
    assert result.metadata["ship_model"] == "nomoto2"
    assert result.to_xarray().attrs["ship_file"] == "my-ship.toml"


def test_a_bare_model_has_no_ship_metadata():
    text = TEXT.replace('ship = "{ship}"', 'model = "nomoto1"\n[vessel.params]\ngain = 0.1\n'
                        'time_constant = 20.0\nspeed = 5.0')
    result = run_scenario(parse_scenario(text, source="s.toml"))
    assert not any(k.startswith("ship") for k in result.metadata)


def test_the_key_table_is_derived_from_the_problems_fields():
    from seahelm.scenario import runs

    fields = [f.name for f in dataclasses.fields(seahelm.Problem)]
    assert set(runs._FIELD_KEYS) == set(fields)  # every field, no other
    assert list(runs._ENGINE_KEYS) == [f for f in fields if runs._FIELD_KEYS[f] is not None]


@pytest.mark.parametrize("field, key", [("post_pass", "environment.waves.first_order_motions"),
                                        ("ship", "vessel.ship")])
def test_the_key_table_names_the_scenario_keys(field, key):
    from seahelm.scenario import runs

    assert runs._ENGINE_KEYS[field] == key
