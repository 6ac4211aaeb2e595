"""Per-model knowledge declared by the model (issue 47, item 4): shallow water, MMG hull
identification and the stopping test's engine estimate are capabilities a VesselModel
declares (``model.supports``), not checks of ``model.name == "mmg"``; a model ship's Froude
scale is what its ship file declares (``[particulars] model_scale``), not a table of catalog
names."""
from __future__ import annotations

import dataclasses
import math
import warnings

import pytest

from seahelm.errors import ParameterError
from seahelm.registry import VESSEL_MODELS, get_model
from seahelm.ships import get_ship
from seahelm.vessels.base import CAPABILITIES, VesselModel
from seahelm.vessels.mmg import MMG


def _on(ship, model):
    return dataclasses.replace(ship, model=model)


def test_the_mmg_model_declares_what_was_keyed_by_its_name():
    assert MMG.capabilities == {"shallow-water", "hull-identification", "engine-estimate",
                                "closed-form-self-propulsion"}  # (the last: issue 47 item 3)
    # every other registered model declares none of them: what the name checks allowed
    others = {name: get_model(name).capabilities for name in VESSEL_MODELS if name != "mmg"}
    # mmg-ls declares the output-error fit of measured records (issue 48 item 3), no other
    assert others.pop("mmg-ls") == {"record-identification"}
    assert all(not caps for caps in others.values()), others


def test_a_capability_must_be_one_of_the_known_names():
    with pytest.raises(ValueError, match=r"unknown capabilities \['shallow_water'\]; valid: "
                                         "shallow-water, hull-identification"):
        dataclasses.replace(MMG, capabilities=frozenset({"shallow_water"}))
    with pytest.raises(ValueError, match="unknown capability 'shallow'"):
        MMG.supports("shallow")
    assert set(CAPABILITIES) == {"shallow-water", "hull-identification", "engine-estimate",
                                 "record-identification", "closed-form-self-propulsion"}


def test_shallow_water_follows_the_capability_not_the_name():
    ship = get_ship("kvlcc2-full")
    renamed = _on(ship, dataclasses.replace(MMG, name="my-mmg"))  # declares it, another name
    assert renamed.at_depth(40.0).water_depth == 40.0
    assert renamed.at_depth(40.0).params == ship.at_depth(40.0).params
    stripped = _on(ship, dataclasses.replace(MMG, capabilities=frozenset()))  # named "mmg"
    with pytest.raises(ParameterError, match="the shallow-water corrections are for the MMG "
                                             "model's coefficients") as err:
        stripped.at_depth(40.0)
    assert err.value.field == "water_depth"


def test_the_stopping_ship_follows_the_capability_not_the_name():
    from seahelm.analysis.maneuvers.stopping import stopping_ship

    ship = get_ship("kvlcc2-l7")
    renamed = _on(ship, dataclasses.replace(MMG, name="my-mmg"))
    assert stopping_ship(renamed).model.name == "mmg-4q"
    stripped = _on(ship, dataclasses.replace(MMG, capabilities=frozenset()))
    with pytest.raises(ParameterError, match="the stopping test needs an MMG ship"):
        stopping_ship(stripped)


def test_the_l7_models_declare_their_froude_scale_in_their_ship_files():
    for name in ("kvlcc2-l7", "kvlcc2-l7-wp0-0.35", "kvlcc2-l7-xp-0.5"):
        assert get_ship(name).particulars.model_scale == 45.7
    assert get_ship("kvlcc2-full").particulars.model_scale is None


def test_the_stopping_test_takes_the_declared_scale_whatever_the_name():
    from seahelm.analysis.maneuvers.stopping import stopping_ship

    l7 = get_ship("kvlcc2-l7")
    # before: the scale was STOPPING_ENGINE_SCALES[ship.name]; a renamed L7 copy kept it only
    # through the geometry rule. Another declared scale is now taken as it is
    declared = dataclasses.replace(
        l7, name="my-model", particulars=dataclasses.replace(l7.particulars, model_scale=20.0))
    at_20 = stopping_ship(declared)
    assert at_20.params == stopping_ship(l7, scale=20.0).params
    assert stopping_ship(dataclasses.replace(l7, name="my-l7")).params == \
        stopping_ship(l7).params == stopping_ship(l7, scale=45.7).params


def test_a_scaled_model_declares_its_new_scale():
    l7 = get_ship("kvlcc2-l7")
    assert l7.scaled(14.0).particulars.model_scale == pytest.approx(22.85, rel=1e-12)
    # scaled to (or past) the full-scale ship: full scale, no model scale
    assert l7.scaled(7.0 * 45.7).particulars.model_scale is None
    assert get_ship("kvlcc2-full").scaled(7.0).particulars.model_scale is None


def test_a_model_scale_below_one_is_refused():
    l7 = get_ship("kvlcc2-l7")
    for bad in (0.5, -1.0, math.nan):
        with pytest.raises(ParameterError, match="`model_scale` must be") as err:
            dataclasses.replace(l7.particulars, model_scale=bad)
        assert err.value.field == "model_scale"


def test_the_ship_file_round_trip_keeps_the_scale(tmp_path):
    from seahelm.ships import read_ship
    from seahelm.ships.writing import write_ship

    path = write_ship(get_ship("kvlcc2-l7"), tmp_path / "l7.toml")
    assert "model_scale = 45.7 # [-]" in path.read_text()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert read_ship(path).particulars.model_scale == 45.7


@pytest.mark.parametrize("capable", [True, False])
def test_the_identify_mmg_base_ship_follows_the_capability(monkeypatch, tmp_path, capable):
    from typer.testing import CliRunner

    import seahelm.ships
    from seahelm.cli.identify import app

    model = (dataclasses.replace(MMG, name="my-mmg") if capable
             else dataclasses.replace(MMG, capabilities=frozenset()))
    ship = _on(get_ship("kvlcc2-l7"), model)
    monkeypatch.setattr(seahelm.ships, "get_ship", lambda name: ship)
    log = tmp_path / "log.csv"
    log.write_text("time,rudder_angle\n0,0\n")
    result = CliRunner().invoke(app, ["mmg", str(log), "--ship", "kvlcc2-l7"])
    assert result.exit_code == 2
    refused = "the MMG identification needs an MMG ship" in result.output
    assert refused is not capable, result.output
