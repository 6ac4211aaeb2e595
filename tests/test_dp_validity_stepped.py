"""The dp-3dof range check (VesselModel.check_result) on the stepped loop: Simulator.result()
warns as simulate does, naming the same runs and speed; strict mode raises; a result read
before the records are all reached (NaN) looks at what was run and says nothing else."""

from __future__ import annotations

import warnings

import pytest

from seahelm.errors import ParameterError, ValidityRangeWarning, strict_validity
from seahelm.simulation.engine import simulate
from seahelm.simulation.stepping import Simulator

from test_dp_validity import _problem


def _messages(record):
    return [str(w.message) for w in record if issubclass(w.category, ValidityRangeWarning)]


def _stepped(problem, n=None):
    with Simulator(problem) as sim:
        sim.reset()
        sim.step(n=sim.n_intervals if n is None else n)
        return sim.result()


def test_stepped_warns_as_the_whole_horizon():
    problem = _problem([0.0, 3.0, 2.5])
    with pytest.warns(ValidityRangeWarning) as whole:
        simulate(problem)
    with pytest.warns(ValidityRangeWarning) as stepped:
        _stepped(problem)
    assert _messages(stepped) == _messages(whole)
    assert "2 run(s) faster than 2 m/s" in _messages(stepped)[0]
    assert "run 1 at 3 m/s" in _messages(stepped)[0]


def test_stepped_strict_mode_raises():
    with strict_validity(), pytest.raises(ParameterError, match="dp-3dof.*faster than 2 m/s"):
        _stepped(_problem([2.5]))


def test_a_station_keeping_stepped_run_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _stepped(_problem([0.0, 1.9]))


def test_a_result_read_part_way_looks_at_the_records_reached_only():
    """Right after reset and after a few steps the later records are NaN: no NumPy
    'All-NaN slice' warning, and the run at 3 m/s from the start is named already."""
    problem = _problem([0.0, 3.0])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        with Simulator(problem) as sim:
            sim.reset()
            sim.result()
            sim.step(n=2)
            sim.result()
    assert not [w for w in record if issubclass(w.category, RuntimeWarning)], \
        [str(w.message) for w in record]
    assert any("run 1 at 3 m/s" in m for m in _messages(record))
