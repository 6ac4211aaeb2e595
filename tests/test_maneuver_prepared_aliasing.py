"""A kept circle's results share nothing a caller can change with the next result (review).

:mod:`seahelm.analysis.maneuvers.prepared` keeps one :class:`Plan` per request, and the plan's
axes give every result its coordinates and their attributes. The values are read-only
(``Plan.freeze``, tested in tests/test_maneuver_prepared_requests.py); the attribute dicts
must be each result's own: a caller labelling a coordinate of one result (``attrs[...] =``)
must not relabel the next circle's. Here every attribute dict and every writable number of a
result is scribbled on, and the next result of the same request must equal a fresh one's.
"""

from __future__ import annotations

import importlib
import math

import pytest

from seahelm.analysis.maneuvers import turning_circle

prepared = importlib.import_module("seahelm.analysis.maneuvers.prepared")

TIMING = ("wall_time_s", "compile_time_s", "created")  # (the clock's: differ every run)


@pytest.fixture(autouse=True)
def _fresh():
    prepared.clear()
    yield
    prepared.clear()


def _circle(kw):
    kw = {"rudder": math.radians(35.0), "t_final": 30.0, "dt": 0.5} | kw
    return turning_circle("kvlcc2-l7", kw.pop("rudder"), **kw)


def _scribble(ds):
    ds.attrs["scribbled"] = 1
    for var in ds.variables.values():
        var.attrs["scribbled"] = 1
        values = var.values
        if values.flags.writeable and values.dtype.kind == "f":
            values[...] = 123.0


def _untimed(ds):
    out = ds.copy()
    out.attrs = {k: v for k, v in out.attrs.items() if k not in TIMING}
    return out


@pytest.mark.parametrize("kw", [{"sides": 1}, {}, {"rudder": (0.3, 0.5), "sides": (1, -1)}],
                         ids=["single-run", "two-sides", "grid"])
def test_changing_a_results_attrs_and_numbers_changes_not_the_next_one(kw):
    first = _circle(kw)
    for ds in (first.metrics, first.runs):
        _scribble(ds)
    again = _circle(kw)  # (from the kept plan and batch)
    assert len(prepared._READY) == 1
    prepared.clear()
    fresh = _circle(kw)
    assert again.metrics.identical(fresh.metrics)
    assert _untimed(again.runs).identical(_untimed(fresh.runs))
    for ds in (again.metrics, again.runs):
        assert all("scribbled" not in v.attrs for v in ds.variables.values())
