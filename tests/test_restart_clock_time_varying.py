"""``restart_clock`` refuses a problem whose loop reads the time (review R).

The clock set back to t = 0 keeps every run's state, so it is exact only for a time-invariant
loop. It refused time-series references and disturbances, but not the first-order wave
motions in the loop (their sea is a function of t) nor noisy position sensors (their noise a
function of the step): the runs kept went on silently with the sea started again from its
t = 0 phase (the yaw wave motion after the restart was the one of t = 0, not of t = 10 s).
"""
from __future__ import annotations

import pytest

from seahelm.control.dp_pid import DP_PID, dp_pid_params
from seahelm.errors import ParameterError
from seahelm.simulation.sensor_stage import PositionSensors
from seahelm.simulation.stepping import Simulator
from seahelm.simulation.stepping_reference import restart_clock

from test_dp_observer import SHIP, dp_problem, sea_problem

T = 20.0


def test_in_loop_wave_motions_refuse_the_clock_set_back():
    # (no noise: the sea alone; test_dp_observer's raw dp-pid loop, its mean wave loads too)
    problem = sea_problem(DP_PID, dp_pid_params(SHIP), t_final=T,
                          sensors=PositionSensors(wave_motion=True, seed=1))
    with Simulator(problem) as sim:
        sim.reset()
        half = sim.n_intervals // 2
        sim.step(n=half)
        with pytest.raises(ParameterError, match=r"first_order.*function of the time"):
            restart_clock(sim)
        # nothing was changed: the clock goes on
        assert sim.step().time[0] == pytest.approx((half + 1) * problem.controller_dt)


def test_noisy_sensors_refuse_the_clock_set_back():
    base = dp_problem(DP_PID, dp_pid_params(SHIP), t_final=T,
                      sensors=PositionSensors(noise_north=0.5, seed=1, wave_motion=False))
    problem = base.replace(first_order=None)
    with Simulator(problem) as sim:
        sim.reset()
        sim.step(n=3)
        with pytest.raises(ParameterError, match=r"sensors.*noise.*step"):
            restart_clock(sim)


def test_a_time_invariant_loop_still_restarts():
    base = dp_problem(DP_PID, dp_pid_params(SHIP), t_final=T,
                      sensors=PositionSensors(seed=1, wave_motion=False))
    problem = base.replace(first_order=None)  # zero noise, no sea: time-invariant
    with Simulator(problem) as sim:
        sim.reset()
        sim.step(n=3)
        restart_clock(sim)
        assert sim.step().time[0] == pytest.approx(problem.controller_dt)
