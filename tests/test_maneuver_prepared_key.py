"""Every argument of ``turning_circle`` is part of its prepared request's key (review).

:mod:`seahelm.analysis.maneuvers.prepared` keeps a circle's validated grid and batch per
request; a request that differs in any argument must be prepared afresh, or it would be
given another request's plan and batch (stale numbers, silently). The existing tests vary the
rudder and ``t_final`` only; here each argument is changed alone, and the table must name
every parameter of the signature (a new argument left out of the key fails here).
"""

from __future__ import annotations

import importlib
import inspect
import math

import pytest
from test_maneuver_prepared_requests import _count_plans

from seahelm.analysis.maneuvers import turning_circle

prepared = importlib.import_module("seahelm.analysis.maneuvers.prepared")

R = math.radians(35.0)
BASE = {"ship": "kvlcc2-l7", "rudder": R, "sides": 1, "t_final": 40.0, "dt": 0.5}
#: argument -> another valid value (none of them warns: a request that warns is not kept)
CHANGED = {
    "ship": "kvlcc2-l7-xp-0.5",
    "rudder": math.radians(30.0),
    "sides": -1,
    "speed": 1.0,
    "rps": 10.0,
    "t_final": 41.0,
    "dt": 0.4,
    "record_dt": 1.0,
    "heading_change": math.pi,
}
NOT_KEPT = {"conditions"}  # (a request with conditions is prepared at every call)


@pytest.fixture(autouse=True)
def _fresh():
    prepared.clear()
    yield
    prepared.clear()


def test_the_table_names_every_argument():
    assert set(CHANGED) | NOT_KEPT == set(inspect.signature(turning_circle).parameters)


@pytest.mark.parametrize("name", sorted(CHANGED))
def test_a_request_differing_in_one_argument_is_prepared_anew(name, monkeypatch):
    made = _count_plans(monkeypatch)

    def circle(**kw):
        kw = BASE | kw
        return turning_circle(kw.pop("ship"), kw.pop("rudder"), **kw)

    circle()
    circle()
    assert len(made) == 1  # (the base request kept)
    changed = circle(**{name: CHANGED[name]})
    assert len(made) == 2, f"`{name}` changed, but the kept request was used"
    again = circle(**{name: CHANGED[name]})
    assert len(made) == 2  # (kept under its own key)
    assert changed.metrics.identical(again.metrics)
