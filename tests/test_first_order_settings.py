"""The first-order motions' settings are typed (issue 46): a scenario's runs carry
:class:`~seahelm.scenario.first_order.FirstOrderSettings` to the post-pass and to the in-loop
motions (``FirstOrderInLoop.settings``), not JSON in the problem's metadata; the JSON is only
the result's (file) record of them. And the first-order stage's constants exist only with the
motions (the dead "no motions" branch of ``wave_constants`` is gone)."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.environment import rao_io
from seahelm.registry import get_controller, get_model
from seahelm.scenario import parse_scenario, run_scenario
from seahelm.scenario.first_order import FirstOrderSettings
from seahelm.simulation.composition import compose
from seahelm.simulation.wave_motion_stage import wave_constants

EXAMPLE = Path(__file__).parents[1] / "examples" / "container_waves_motions.toml"
BARGE = rao_io.box_barge_database()
pytestmark = pytest.mark.filterwarnings("ignore:Lvov:seahelm.errors.ValidityRangeWarning")


def _text(*extra: str) -> str:
    out = EXAMPLE.read_text().replace("t_final = 600.0", "t_final = 20.0").replace(
        "runs = 4", "runs = 2")
    return out.replace("components = 64", "components = 64\n" + "\n".join(extra))


def test_the_post_pass_settings_are_typed():
    problem = parse_scenario(_text())
    specs = problem.post_pass.specs
    assert len(specs) == 2 and all(type(s) is FirstOrderSettings for s in specs)
    s = specs[0]
    # the example's [environment.waves] (h3 3 m, direction 60 deg, seed 34) and its ship's hull
    assert (s.h3, s.spectrum, s.seed, s.components) == (3.0, "rakhmanin-firsov-2", 34, 64)
    assert s.direction == math.radians(60.0) and s.autopilot_sees is False
    assert s.hull == (175.0, 25.4, 8.5, 0.5617) and hash(s) == hash(specs[1])
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.h3 = 2.0  # type: ignore[misc]
    assert "first_order_settings" not in problem.metadata


def test_in_the_loop_the_settings_travel_typed_and_the_result_records_them_as_json():
    problem = parse_scenario(_text(f'rao_file = "{BARGE}"', "autopilot_sees_first_order = true"))
    assert "first_order_settings" not in problem.metadata  # (was JSON there)
    settings = problem.first_order.settings
    assert len(settings) == 2 and all(type(s) is FirstOrderSettings for s in settings)
    assert settings[0].autopilot_sees is True and settings[0].rao_file == str(BARGE)
    # a chunk of the runs keeps its runs' settings
    assert problem.first_order.select_runs(1, 2).settings == settings[1:]
    result = run_scenario(problem)
    record = json.loads(result.metadata["first_order_settings"])
    assert record[0] == {"h3": 3.0, "spectrum": "rakhmanin-firsov-2", "seed": 34,
                         "rao_file": str(BARGE), "autopilot_sees": True,
                         "direction": math.radians(60.0), "gm": 0.3, "components": 64,
                         "spreading": None, "spreading_parameter": 2.0,
                         "hull": [175.0, 25.4, 8.5, 0.5617]}
    assert np.isfinite(result["heading_total"]).all()


def test_wave_constants_has_no_branch_without_the_motions():
    """The stage is in the loop only with first-order motions: ``wave_constants`` has no
    'no motions' answer (it returned HAS_WAVES False and zero indices, used by nothing)."""
    model, ctrl = get_model("container"), get_controller("pid-heading-rps")
    from seahelm.actuators.servo import RUDDER_SERVO

    meas = tuple(compose(model, RUDDER_SERVO, ctrl).measurement_from)
    with pytest.raises(TypeError):
        wave_constants(model, ctrl, meas, 0, None)  # type: ignore[arg-type]
    w = wave_constants(model, ctrl, meas, 0, (("heave", "roll", "yaw"), True))
    assert "HAS_WAVES" not in w
    assert w["NWD"] == 3 and w["WAVE_YAW"] == 2 and w["WAVE_ROLL"] == 1
    src = Path(wave_constants.__code__.co_filename).read_text()
    assert "HAS_WAVES" not in src and "first_order is None" not in src
