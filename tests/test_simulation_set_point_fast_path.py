"""A reference given as a mapping of numbers (a set-point) takes a short path in the engine
(one row, no per-channel arrays: part of the Otter's one-run fixed cost, issue 49 Speed); it
must give what the same reference given as an array gives, and refuse what the general path
refuses, in the same words."""
from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.simulation.inputs import _signal, _TimeGrid

LABELS = ("heading", "surge_force")


@pytest.mark.parametrize("value", [{"heading": math.radians(100.0), "surge_force": 120},
                                   {"surge_force": 7.5}, {}])
def test_a_set_point_equals_the_general_path(value):
    grid = _TimeGrid(10, 0.1)
    fast = _signal("reference", value, 2, grid, "", LABELS)
    general = _signal("reference", np.array([float(value.get(lab, 0.0)) for lab in LABELS]), 2,
                      grid, "", LABELS)
    assert fast.dtype == general.dtype and fast.shape == general.shape == (1, 1, 2)
    assert np.array_equal(fast, general) and fast.flags.c_contiguous


@pytest.mark.parametrize("bad, match", [
    (math.inf, r"reference\['surge_force'\]"),
    (math.nan, r"reference\['surge_force'\]"),
    (10 ** 400, r"reference\['surge_force'\]"),
    (True, r"reference\['surge_force'\].*booleans"),
    ("1", r"reference\['surge_force'\].*text"),
])
def test_what_is_not_a_finite_number_is_refused_by_name(bad, match):
    with pytest.raises(ParameterError, match=match):
        _signal("reference", {"heading": 0.0, "surge_force": bad}, 2, _TimeGrid(10, 0.1), "",
                LABELS)
