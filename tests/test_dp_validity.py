"""The dp-3dof model's range (seahelm.vessels.dp_three_dof.MAX_SPEED): a run faster than 2 m/s
through the water warns after it is done, naming the run and the speed; strict mode raises; a
station-keeping run does not warn."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from seahelm.control.dp_pid import DP_PID, dp_pid_params
from seahelm.errors import ParameterError, ValidityRangeWarning, strict_validity
from seahelm.simulation.engine import simulate
from seahelm.vessels.dp_three_dof import MAX_SPEED

from test_dp_observer import SHIP, dp_problem


def _problem(surge_speeds):
    x0 = np.zeros((len(surge_speeds), 6))
    x0[:, 3] = surge_speeds
    return dp_problem(DP_PID, dp_pid_params(SHIP), runs=len(surge_speeds), t_final=30.0
                      ).replace(first_order=None, sensors=None, x0=x0)


def test_station_keeping_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityRangeWarning)
        res = simulate(_problem([0.0, 1.9]))
    assert res.ok.all() and MAX_SPEED == 2.0


def test_a_fast_run_warns_naming_it():
    with pytest.warns(ValidityRangeWarning,
                      match=r"dp-3dof .* 1 run\(s\) faster than 2 m/s .* run 1 at 3 m/s"):
        simulate(_problem([0.0, 3.0]))


def test_strict_mode_raises():
    with strict_validity(), pytest.raises(ParameterError, match="faster than 2 m/s"):
        simulate(_problem([2.5]))


def test_the_warning_points_at_the_users_line():
    # (it named a line of seahelm/simulation/engine.py: the check runs three calls deep)
    with pytest.warns(ValidityRangeWarning) as caught:
        simulate(_problem([0.0, 3.0]))
    assert caught[0].filename == __file__, caught[0].filename


def test_a_formula_outside_its_range_points_at_the_users_line():
    from seahelm.hydrodynamics.propeller_series import thrust_coefficient

    with pytest.warns(ValidityRangeWarning) as caught:  # (P/D = 2.5: the series ends at 1.4)
        thrust_coefficient(0.5, 2.5, 0.55, 4)
    assert all(w.filename == __file__ for w in caught), [w.filename for w in caught]
