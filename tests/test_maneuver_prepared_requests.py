"""A turning circle asked for again reuses its validated grid and batch, and only that.

:mod:`seahelm.analysis.maneuvers.prepared` keeps what a request derives before anything runs
(the ship, approach, grid and validated Problem: a third of one circle's Python calls, issue
46). The simulation and metrics are computed at every call, so a repeated request gives the
same numbers bit for bit; what is not derived from the request alone (the JIT switch, a ship
re-registered under the same name) or what warns is never taken from there.
"""

from __future__ import annotations

import importlib
import math
import warnings

import numpy as np
import pytest

from seahelm.analysis.maneuvers import turning_circle
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.ships import catalog, get_ship
from seahelm.simulation.problem import Problem

prepared = importlib.import_module("seahelm.analysis.maneuvers.prepared")
common = importlib.import_module("seahelm.analysis.maneuvers.common")

R = math.radians(35.0)


@pytest.fixture(autouse=True)
def _fresh():
    prepared.clear()
    yield
    prepared.clear()


def _circle(**kw):
    kw = {"sides": 1, "t_final": 40.0, "dt": 0.5} | kw
    return turning_circle(kw.pop("ship", "kvlcc2-l7"), kw.pop("rudder", R), **kw)


def _count_plans(monkeypatch):
    made = []
    real = common.Plan.__init__

    def counting(self, *args, **kwargs):
        made.append(1)
        real(self, *args, **kwargs)

    monkeypatch.setattr(common.Plan, "__init__", counting)
    return made


def _same(a, b):
    assert a.metrics.identical(b.metrics) and repr(a.metrics) == repr(b.metrics)
    for field in ("time", "state", "output", "command", "reference", "status"):
        assert np.array_equal(getattr(a.simulation, field), getattr(b.simulation, field))
    timing = ("wall_time_s", "compile_time_s", "created")  # (the clock's: differ every run)
    ra, rb = a.runs.copy(), b.runs.copy()
    for ds in (ra, rb):
        ds.attrs = {k: v for k, v in ds.attrs.items() if k not in timing}
    assert ra.identical(rb)


def test_a_repeated_request_is_prepared_once_and_gives_the_same_numbers(monkeypatch):
    made = _count_plans(monkeypatch)
    first = _circle()
    again = _circle()
    assert len(made) == 1  # (the second call took the kept plan and problem)
    _same(first, again)
    assert again.simulation is not first.simulation  # (run again: no result is kept)
    prepared.clear()
    fresh = _circle()
    assert len(made) == 2
    _same(first, fresh)


@pytest.mark.parametrize("kw", [
    {"rudder": (0.3, 0.5), "sides": (1, -1)},  # a grid: rudder x side
    {"ship": "mariner-nonlinear", "rudder": 0.35, "t_final": None, "dt": None},
    {"speed": 1.0},
    {"record_dt": 1.0},
])
def test_other_requests_repeat_bit_for_bit(kw, monkeypatch):
    made = _count_plans(monkeypatch)
    first, again = _circle(**kw), _circle(**kw)
    assert len(made) == 1
    _same(first, again)


def test_a_different_request_is_prepared_anew(monkeypatch):
    made = _count_plans(monkeypatch)
    a = _circle()
    b = _circle(rudder=math.radians(20.0))
    c = _circle(t_final=50.0)
    assert len(made) == 3
    assert float(b.metrics["advance"]) > float(a.metrics["advance"])  # (40 s: 90 deg reached)
    assert c.simulation.time[-1] == 50.0 and a.simulation.time[-1] == 40.0


@pytest.mark.parametrize("kw", [
    {"rudder": np.float64(R)},           # a numpy scalar
    {"rudder": [R]},                     # a list
    {"sides": True},                     # a bool
    {"ship": get_ship("kvlcc2-l7").params},  # a bare parameter set
])
def test_what_is_not_plain_is_prepared_at_every_call(kw, monkeypatch):
    made = _count_plans(monkeypatch)
    first, again = _circle(**kw), _circle(**kw)
    assert len(made) == 2
    _same(first, again)


def test_a_request_that_warns_warns_at_every_call(monkeypatch):
    made = _count_plans(monkeypatch)
    for _ in range(2):  # dt = 1 s is 20 x the usual step of the KVLCC2 L7 (0.05 s)
        with pytest.warns(ValidityRangeWarning, match="usual step"):
            _circle(dt=1.0)
    assert len(made) == 2


def test_a_request_that_raises_raises_again():
    for _ in range(2):
        with pytest.raises(ParameterError, match="rudder"):
            _circle(rudder=math.radians(40.0))  # beyond the KVLCC2's 35 deg


def test_the_jit_switch_is_read_at_every_call(monkeypatch):
    assert _circle().simulation.metadata["execution"] == "compiled"
    monkeypatch.setenv("SEAHELM_DISABLE_JIT", "1")
    slow = _circle()
    assert slow.simulation.metadata["execution"] == "python"
    monkeypatch.delenv("SEAHELM_DISABLE_JIT")
    assert _circle().simulation.metadata["execution"] == "compiled"


def test_a_ship_registered_again_under_its_name_is_the_new_one():
    base = get_ship("kvlcc2-l7")
    name = "test-prepared-kvlcc2"
    try:
        catalog.register(base.with_name(name) if hasattr(base, "with_name")
                         else _renamed(base, name))
        first = _circle(ship=name)
        catalog._REGISTERED.pop(name)
        longer = _renamed(base, name, servo_rate=0.5)
        catalog.register(longer)
        second = _circle(ship=name)
    finally:
        catalog._REGISTERED.pop(name, None)
    assert second.ships[0] is longer and first.ships[0] is not longer
    assert float(second.metrics["time_90"]) != float(first.metrics["time_90"])


def _renamed(ship, name, servo_rate=None):
    import dataclasses

    gear = ship.steering_gear
    if servo_rate is not None:
        gear = dataclasses.replace(gear, params=dataclasses.replace(
            gear.params, max_rate=gear.params.max_rate * servo_rate))
    return dataclasses.replace(ship, name=name, steering_gear=gear)


def test_at_most_kept_requests_are_kept(monkeypatch):
    monkeypatch.setattr(prepared, "KEPT", 3)
    for t_final in (20.0, 21.0, 22.0, 23.0, 24.0):
        _circle(t_final=t_final)
    assert len(prepared._READY) == 3
    made = _count_plans(monkeypatch)
    _circle(t_final=24.0)  # (the most recent: kept)
    _circle(t_final=20.0)  # (the oldest: dropped)
    assert len(made) == 1


def test_the_kept_problem_is_a_validated_problem():
    _circle()
    (_, (plan, problem)), = prepared._READY.values()
    assert type(problem) is Problem and problem.t_final == 40.0 and problem.dt == 0.5
    assert not plan.warned
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _circle()  # (no warning from a kept request)


def test_circles_in_threads_give_the_same_numbers():
    from concurrent.futures import ThreadPoolExecutor

    want = _circle()
    with ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda _: _circle(), range(16)))
    for r in got:
        _same(want, r)


def test_a_results_coordinates_cannot_change_the_next_ones():
    first = _circle(rudder=(0.3, 0.5), sides=(1, -1))
    with pytest.raises(ValueError):
        first.metrics["rudder"].values[0] = 9.0  # (read-only: shared with the kept plan)
    again = _circle(rudder=(0.3, 0.5), sides=(1, -1))
    assert again.metrics["rudder"].values.tolist() == [0.3, 0.5]
    _same(first, again)
