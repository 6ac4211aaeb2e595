"""The outputs every 3-DOF surface model with sway begins with, written in one place
(:func:`seahelm.vessels.rigid_body.write_planar_outputs`, :data:`~seahelm.vessels.rigid_body.
PLANAR_OUTPUTS`)."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.registry import get_model
from seahelm.vessels import container, mariner, mmg
from seahelm.vessels.rigid_body import PLANAR_OUTPUTS, write_planar_outputs


def test_write_planar_outputs_writes_the_first_eight_in_order():
    y = np.full(10, -9.0)
    write_planar_outputs(y, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0)
    np.testing.assert_array_equal(y, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, -9.0, -9.0])
    assert PLANAR_OUTPUTS == ("north", "east", "heading", "yaw_rate", "surge_speed",
                              "sway_speed", "speed", "drift_angle")


@pytest.mark.parametrize("name", ["mmg", "mmg-4q", "mmg-ls", "mariner", "container"])
def test_the_models_begin_with_the_planar_outputs(name):
    model = get_model(name)
    assert model.output_labels[:8] == PLANAR_OUTPUTS
    assert model.output_units[:8] == ("m", "m", "rad", "rad/s", "m/s", "m/s", "m/s", "rad")


def test_their_output_functions_write_them_through_the_one_function():
    for out in (mmg.write_mmg_outputs, mariner.mariner_output, container.container_output):
        names = out.py_func.__code__.co_names
        assert "write_planar_outputs" in names and "drift_angle" not in names
