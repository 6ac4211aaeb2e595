"""A single run's metrics Dataset built in one pass is the one the general path builds.

:func:`seahelm.analysis.maneuvers.datasets._single_run_dataset` fills the 0-d variables of a
grid without dimensions directly (issue 46: the per-variable checks of the general path were
a fifth of a circle's Python calls). Every manoeuvre's single-run metrics must be identical
to the general path's, slot by slot, and anything it does not assume falls back to it.
"""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest

from seahelm.analysis.maneuvers import crash_stop, pull_out, turning_circle, zigzag

datasets = importlib.import_module("seahelm.analysis.maneuvers.datasets")
common = importlib.import_module("seahelm.analysis.maneuvers.common")

CASES = {
    "turning": lambda: turning_circle("kvlcc2-l7", math.radians(35.0), sides=1,
                                      t_final=40.0).metrics,
    "turning-mariner": lambda: turning_circle("mariner-nonlinear", math.radians(20.0),
                                              sides=-1).metrics,
    "zigzag": lambda: zigzag("kvlcc2-l7", math.radians(10.0)).metrics,
    "pullout": lambda: pull_out("kvlcc2-l7", math.radians(20.0), sides=1).metrics,
    "stopping": lambda: crash_stop("kvlcc2-l7").metrics,
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_single_run_metrics_equal_the_general_paths(case, monkeypatch):
    calls = []
    real = datasets._single_run_dataset

    def spy(*args):
        out = real(*args)
        calls.append(out is not None)
        return out

    monkeypatch.setattr(common, "_single_run_dataset", spy)
    fast = CASES[case]()
    monkeypatch.setattr(common, "_single_run_dataset", lambda *args: None)
    slow = CASES[case]()
    assert fast.identical(slow) and repr(fast) == repr(slow)
    assert list(fast.variables) == list(slow.variables)
    assert list(fast.coords) == list(slow.coords) and dict(fast.sizes) == dict(slow.sizes)
    for name in slow.variables:
        a, b = fast.variables[name], slow.variables[name]
        assert a.dtype == b.dtype and a.dims == b.dims, name
        assert type(a._attrs) is type(b._attrs) and a._attrs == b._attrs, name
        assert a._encoding == b._encoding, name
    if case in ("turning", "turning-mariner", "pullout", "stopping"):  # (taken there)
        assert calls == [True]


@pytest.mark.parametrize("variables, coords", [
    ({"a": (np.array([1.0, 2.0]), "m", "two values")}, {}),            # not one run's
    ({"a": (np.array([[1.0]]), "m", "2-D")}, {}),
    ({"a": (np.array([np.datetime64("2020-01-01")]), "", "a date")}, {}),
    ({"a": (np.array([1.0]), "m", "one")}, {"x": (("x",), np.arange(2.0), {})}),  # an index
    ({"a": (np.array([1.0]), "m", "one")}, {"a": ((), 1.0, {})}),      # a shared name
])
def test_what_the_single_run_path_does_not_assume_falls_back(variables, coords):
    assert datasets._single_run_dataset(variables, coords, {}) is None


def test_plain_values_and_strings_of_one_run():
    ds = datasets._single_run_dataset(
        {"v": ([2.5], "m/s", "speed"), "ok": (np.array([True]), "", "flag"),
         "message": (np.array(["ok"], dtype=object), "", "text")},
        {"ship_name": ((), np.str_("kvlcc2-l7"), {"long_name": "ship"})}, {"k": 1})
    assert float(ds["v"]) == 2.5 and ds["v"].attrs == {"long_name": "speed", "units": "m/s"}
    assert ds["ok"].dtype == bool and ds["message"].dtype.kind == "U"
    assert str(ds["message"].values) == "ok" and ds.attrs == {"k": 1}
    assert str(ds.coords["ship_name"].values) == "kvlcc2-l7" and not ds.indexes
    general = datasets._indexless_dataset(
        {"v": datasets._variable((), np.array(2.5), {"long_name": "speed", "units": "m/s"}),
         "ok": datasets._variable((), np.array(True), {"long_name": "flag"}),
         "message": datasets._variable((), np.array("ok"), {"long_name": "text"})},
        {"ship_name": datasets._variable((), np.asarray(np.str_("kvlcc2-l7")),
                                         {"long_name": "ship"})}, {"k": 1})
    assert ds.identical(general) and repr(ds) == repr(general)
