"""A Simulator's run indices behave one way, and a step of more intervals than the horizon has
is refused.

Before: ``sim.state(-1)`` was the last run but ``runs=[-1]`` was refused ("must be in 0 ... 2");
``sim.state(True)`` was run 1; ``runs=[2, 0]`` with two rows of commands gave run 0 the first
row (the rows were taken in sorted order); ``runs=[0, 0]`` said the commands had the wrong
shape; ``step(n=10**9)`` stopped silently at t_final.
"""
from __future__ import annotations

import numpy as np
import pytest

from seahelm import Problem, Simulator
from seahelm.errors import ParameterError
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

RUNS = 3


@pytest.fixture
def sim():
    problem = Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0,
                                                          speed=5.0),
                      x0=np.zeros((RUNS, 4)), t_final=20.0, dt=0.1, controller_dt=1.0)
    with Simulator(problem) as s:
        s.reset()
        yield s


def test_negative_run_indices_count_from_the_end_on_every_accessor(sim):
    sim.step({"rudder_command": [0.1]}, runs=[-1])  # step(runs=...)
    assert sim.time.tolist() == [0.0, 0.0, 1.0]
    assert sim.state(-1) == sim.state(RUNS - 1) and sim.state(-1)["rudder_angle"] > 0.0
    sim.set_state(-2, {"heading": 0.5})
    assert sim.state(1)["heading"] == 0.5
    assert sim.failure(-1) is None
    sim.reset(runs=[-1])
    assert sim.time.tolist() == [0.0, 0.0, 0.0]
    sim.step(runs=-3)
    assert sim.time.tolist() == [1.0, 0.0, 0.0]


@pytest.mark.parametrize("call, field", [
    (lambda s: s.state(RUNS), "run"),
    (lambda s: s.state(-RUNS - 1), "run"),
    (lambda s: s.set_state(RUNS, {"heading": 0.0}), "run"),
    (lambda s: s.failure(-RUNS - 1), "run"),
    (lambda s: s.step(runs=[RUNS]), "runs"),
    (lambda s: s.step(runs=[-RUNS - 1]), "runs"),
    (lambda s: s.reset(runs=[0, RUNS]), "runs"),
])
def test_an_index_out_of_range_has_one_message(sim, call, field):
    with pytest.raises(ParameterError, match=rf"`{field}` must be a run index in -3 \.\.\. 2 "
                                             r"\(negative: from the end"):
        call(sim)


def test_a_boolean_is_not_a_run_index(sim):
    with pytest.raises(ParameterError, match="`run` must be a run index"):
        sim.state(True)


def test_command_rows_follow_the_order_of_runs(sim):
    sim.step(np.array([[0.3], [0.0]]), runs=[2, 0])
    assert sim.state(2)["rudder_angle"] > 0.0 and sim.state(0)["rudder_angle"] == 0.0
    sim.reset()
    sim.step({"rudder_command": [0.0, 0.3]}, runs=[-1, 1])  # a mapping too
    assert sim.state(1)["rudder_angle"] > 0.0 and sim.state(2)["rudder_angle"] == 0.0


def test_a_run_given_twice_is_refused(sim):
    with pytest.raises(ParameterError, match="`runs` must name each run once, got run 0 2 "
                                             "times") as err:
        sim.step(np.array([[0.3], [0.0]]), runs=[0, -3])
    assert err.value.field == "runs"
    assert sim.time.tolist() == [0.0, 0.0, 0.0]  # nothing stepped


@pytest.mark.parametrize("n", [21, 10**9, np.int64(2**62)])
def test_more_intervals_than_the_horizon_has_are_refused(sim, n):
    with pytest.raises(ParameterError, match=rf"`n` = {int(n)} exceeds the 20 controller "
                                             r"intervals of the horizon \(t_final = 20 s, "
                                             r"controller_dt = 1 s\)") as err:
        sim.step(n=n)
    assert err.value.field == "n"
    assert sim.time.tolist() == [0.0, 0.0, 0.0]


def test_the_whole_horizon_in_one_step_is_allowed(sim):
    sim.step(n=5)
    obs = sim.step(n=20)  # (15 left: the runs stop at t_final, as documented)
    assert obs.time.tolist() == [20.0] * RUNS


def test_a_bad_state_is_said_as_a_number(sim):
    # (it read "state 'heading' = np.float64(nan) is not finite")
    with pytest.raises(ParameterError, match=r"`values`: state 'heading' = nan is not finite"):
        sim.set_state(0, {"heading": float("nan")})
