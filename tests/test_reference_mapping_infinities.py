"""A reference or disturbance given by name with +inf and -inf in two channels is refused as
any non-finite value is, by a ParameterError naming the channel (the set-point fast path summed
the row with math.fsum, whose ``-inf + inf`` raised a bare ValueError, "-inf + inf in fsum",
that named nothing). Refused before anything compiles."""

from __future__ import annotations

import math

import pytest

from seahelm.errors import ParameterError
from seahelm.simulation.inputs import _signal, _TimeGrid


@pytest.mark.parametrize("values", [(math.inf, -math.inf), (-math.inf, math.inf)])
def test_opposite_infinities_by_name_are_named(values):
    labels = ("heading", "delta_k_wind")
    with pytest.raises(ParameterError, match="finite") as info:
        _signal("reference", dict(zip(labels, values)), 2, _TimeGrid(10, 0.1), "", labels)
    assert info.value.field.startswith("reference['")
