"""The metrics' variables filled directly are the ones xarray's constructor makes.

:func:`seahelm.analysis.maneuvers.datasets._variable` fills an ``xr.Variable``'s four slots
itself where the probe :func:`~seahelm.analysis.maneuvers.datasets._raw_variables` found the
constructor to fill them so (a fifth of its cost, paid twenty times by a single run's metrics:
issue 46 item 6); every slot, the Datasets built from them and their repr must be the same.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from seahelm.analysis.maneuvers import datasets, turning_circle

ARRAYS = [((), np.array(1.5), {"units": "m", "long_name": "advance"}),
          ((), np.array(True), {"long_name": "complete"}),
          ((), np.array("ok"), {}),
          (("side",), np.array([1, -1]), {"long_name": "side"}),
          (("ship", "side"), np.arange(6.0).reshape(3, 2), {"units": "s"})]


def test_the_probe_finds_this_xarray_fills_the_slots_as_expected():
    assert datasets._raw_variables()


@pytest.mark.parametrize("dims, arr, attrs", ARRAYS)
def test_a_variable_filled_directly_is_the_constructors(dims, arr, attrs):
    got = datasets._variable(dims, arr, attrs)
    want = xr.Variable(dims, arr, attrs)
    assert type(got) is type(want) and got.identical(want)
    for slot in ("_dims", "_attrs", "_encoding"):
        assert getattr(got, slot) == getattr(want, slot), slot
        assert type(getattr(got, slot)) is type(getattr(want, slot)), slot
    assert got._data is arr  # (no copy, as the constructor's fast path)
    assert got.attrs is not attrs or not attrs  # (its own dict)


def test_metrics_equal_those_built_by_the_constructor(monkeypatch):
    def metrics():
        return turning_circle("kvlcc2-l7", math.radians(35.0), sides=1, t_final=40.0).metrics

    fast = metrics()
    monkeypatch.setattr(datasets, "_raw_variables", lambda: False)
    slow = metrics()
    assert fast.identical(slow) and repr(fast) == repr(slow)
    assert list(fast.variables) == list(slow.variables)
