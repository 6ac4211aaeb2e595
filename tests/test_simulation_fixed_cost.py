"""The per-call fixed cost of ``simulate``: its shortcuts give what the general paths give."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.parameters import as_records, stack_params
from seahelm.simulation import inputs
from seahelm.simulation.inputs import _by_name, _TimeGrid
from seahelm.vessels.nomoto import Nomoto1Params

LABELS = ("rudder_command", "propeller_rps")
GRID = _TimeGrid(10, 0.1)


def test_one_sample_arrays_by_name_take_the_set_point_row(monkeypatch):
    # a manoeuvre's schedule gives constant channels as (1, 1, 1) arrays: one row, without a
    # per-channel pass through _signal (the general path, some 10 us a call)
    value = {"rudder_command": np.array([[[0.6108652381980153]]]),
             "propeller_rps": np.array(11.85159032)}
    general = _by_name("reference", {k: v + 0.0 for k, v in value.items()} | {}, LABELS, GRID,
                       "")

    def no_signal(*args, **kwargs):
        raise AssertionError("the general path was taken")

    monkeypatch.setattr(inputs, "_signal", no_signal)
    fast = _by_name("reference", value, LABELS, GRID, "")
    assert fast.shape == (1, 1, 2) and fast.dtype == np.float64 and fast.flags.c_contiguous
    assert np.array_equal(fast, general)
    assert fast.tolist() == [[[0.6108652381980153, 11.85159032]]]


@pytest.mark.parametrize("bad", [np.array([[[np.nan]]]), np.array([np.inf])])
def test_a_non_finite_one_sample_array_is_still_named(bad):
    with pytest.raises(ParameterError, match="propeller_rps"):
        _by_name("reference", {"rudder_command": 0.1, "propeller_rps": bad}, LABELS, GRID, "")


def test_one_parameter_set_stacks_to_a_row_of_its_own():
    p = Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0)
    rows = stack_params(p, Nomoto1Params)
    assert rows.shape == (1, Nomoto1Params.n_values()) and rows.flags.writeable and rows.flags.c_contiguous
    assert np.array_equal(rows, np.stack([p.to_array()]))
    rows[0, 0] = 99.0  # the parameter set's packed values are not the caller's rows
    assert p.to_array()[0] == 0.1
    with pytest.raises(ParameterError, match="expected Params"):
        stack_params(p, type("Params", (Nomoto1Params,), {}))
    rec = as_records(stack_params(p), Nomoto1Params)
    assert rec[0].time_constant == 20.0 and isinstance(rec[0], np.record)


def _nomoto_run(x0, **kw):
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO1

    return simulate(NOMOTO1, Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0), x0,
                    t_final=1.0, dt=0.1, **kw)


def test_the_first_initial_state_outside_a_bound_is_named():
    x0 = np.zeros((4, 4))
    x0[2, 3] = 0.5  # the yaw rate beyond the bound given below
    x0[3, 3] = -0.5
    with pytest.raises(ParameterError, match="initial state of run 2"):
        _nomoto_run(x0, bounds={"yaw_rate": (-0.4, 0.4), "rudder_angle": (-1.0, 1.0)})
    x0 = np.zeros((3, 4))
    with pytest.raises(ParameterError, match="initial state of run 0"):  # (the actuator's)
        _nomoto_run(x0, bounds={"rudder_angle": (0.1, 1.0)})
    x0[1, 3] = 0.5
    assert _nomoto_run(x0, bounds={"yaw_rate": (-0.5, 0.5)}).ok.all()  # (on the bound: in)


@pytest.mark.parametrize("every, steps", [(3, [0, 3, 6, 9, 10]), (5, [0, 5, 10]),
                                          (1, list(range(11))), (10, [0, 10]), (7, [0, 7, 10])])
def test_recorded_times_are_every_nth_step_and_the_last(every, steps):
    res = _nomoto_run(np.zeros(4), record_every=every)
    assert np.array_equal(res.time, np.array(steps) * 0.1)
    assert res.state.shape[1] == len(steps)


def test_records_of_a_class_share_one_dtype_object():
    # numba's dispatcher types a record array by its dtype object: a new, equal dtype each call
    # cost some 10 us per kernel call (three a run: warm-up, controllers' init, the loop)
    p = Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0)
    a = as_records(stack_params(p), Nomoto1Params)
    b = as_records(np.zeros((3, Nomoto1Params.n_values())), Nomoto1Params)
    assert a.dtype is b.dtype
    assert a.dtype == np.dtype((np.record, Nomoto1Params.record_dtype()))
