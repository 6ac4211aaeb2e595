"""Wave filter: the steady-state estimation error variance equals the filter's covariance; in an
irregular sea the filtered PID moves the rudder far less at equal low-frequency heading error."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.control.pid import PID_HEADING
from seahelm.control.wave_filter import WAVE_FILTER_OUTPUTS, design_wave_filter, wave_filtered
from seahelm.environment.wave_yaw import wave_yaw_filter
from seahelm.environment.shaping import shaping_filter
from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.errors import ParameterError

K, T = 0.1848, 107.2
H3, MOMENT_PER_SLOPE = 6.0, 3e9  # [m], [N·m per rad of wave slope]
RUDDER_PER_NM = 5.8348e-09  # Mariner: equivalent rudder [rad] per yaw moment [N·m]


@pytest.fixture(scope="module")
def design():
    ordinate = shaping_filter(spectrum_from_wave_height("rakhmanin-firsov-2", H3))
    wave = wave_yaw_filter(ordinate, gain=K, time_constant=T,
                           rudder_per_slope=MOMENT_PER_SLOPE * RUDDER_PER_NM)
    return design_wave_filter(K, T, wave, 0.5, measurement_std=math.radians(0.05))


def test_steady_state_error_variance_matches_the_covariance(design):
    """4000 independent runs started from the filter's prior: the variance of the posterior
    error of ψ_L and r_L after 300 samples is P⁺ within sampling error (relative standard
    error √(2/4000) = 2.2 %; the test allows 4 of them)."""
    sim = design.simulate(300, rudder=0.01, runs=4000, seed=7)
    err = sim["state"][:, -1, :2] - sim["estimate"][:, -1, :2]
    expected = np.diag(design.covariance)[:2]
    tol = 4 * math.sqrt(2 / 4000)
    np.testing.assert_allclose(err.var(axis=0), expected, rtol=tol)
    assert abs(err.mean(axis=0) / np.sqrt(expected)).max() < 4 / math.sqrt(4000)
    # the filter removes the waves: its LF heading error is far below the WF heading
    assert math.sqrt(expected[0]) < 0.1 * math.sqrt(
        design.c_wave @ design.prior_covariance @ design.c_wave)


def test_the_wave_model_has_no_low_frequency_content():
    ordinate = shaping_filter(spectrum_from_wave_height("rakhmanin-firsov-2", H3))
    wave = wave_yaw_filter(ordinate, gain=K, time_constant=T, rudder_per_slope=10.0)
    assert abs(wave.frequency_response(np.array([1e-6]))[0, 0]) < 1e-5
    with pytest.raises(ParameterError, match="time_constant"):
        wave_yaw_filter(ordinate, gain=K, time_constant=-1.0, rudder_per_slope=1.0)


def test_validation(design):
    ordinate = shaping_filter(spectrum_from_wave_height("rakhmanin-firsov-2", H3))
    wave = wave_yaw_filter(ordinate, gain=K, time_constant=T, rudder_per_slope=10.0)
    with pytest.raises(ParameterError, match="dt"):
        design_wave_filter(K, T, wave, 0.0)
    with pytest.raises(ParameterError, match="gain"):
        design_wave_filter(0.0, T, wave, 0.5)
    from seahelm.control.open_loop import OPEN_LOOP

    with pytest.raises(ParameterError, match="heading controller"):
        wave_filtered(OPEN_LOOP, design)


@pytest.mark.slow
def test_in_an_irregular_sea_it_cuts_rudder_activity_at_equal_lf_error(design):
    """The Mariner (nonlinear model, steering gear 5°/s) holding course in a sea of h3% = 6 m
    whose wave yaw moment is 3·10⁹ N·m per rad of slope. The PID of bandwidth 0.05 rad/s on the
    measured heading and yaw rate, and the PID of bandwidth 0.07 rad/s on the filter's
    estimates, reach the same low-frequency heading error (heading low-passed at 0.1 rad/s,
    within 15 %), while the filtered one moves the rudder > 10 times less (RMS rate and travel;
    the figures of docs/guide/control-design.rst: 4.5 vs 0.14 °/s)."""
    from scipy import signal

    from seahelm.analysis.equilibria.equilibrium import approach_state
    from seahelm.control.autopilot_design import pid_pole_placement
    from seahelm.ships import get_ship
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.signals import Sea

    ship = get_ship("mariner-nonlinear")
    dt, tf = 0.1, 2000.0
    t = np.arange(0.0, tf + dt / 2, dt)
    moment = np.stack([MOMENT_PER_SLOPE * Sea(h3=H3, quantity="slope", seed=s)(t)
                       for s in range(2)])[:, :, None]
    start = approach_state(ship, trim=True)
    plain = pid_pole_placement(K, T, bandwidth=0.05, max_command=ship.max_rudder)
    faster = pid_pole_placement(K, T, bandwidth=0.07, max_command=ship.max_rudder)
    filtered = wave_filtered(PID_HEADING, design)
    assert filtered.output_labels[-3:] == WAVE_FILTER_OUTPUTS
    stats = {}
    for name, ctl, gains in (("plain", PID_HEADING, plain.params),
                             ("filtered", filtered, faster.params)):
        res = simulate(ship=ship, x0=start.state, actuator_x0=[start.inputs["rudder_angle"]],
                       t_final=tf, dt=dt, controller=ctl, controller_params=gains,
                       controller_dt=0.5, reference={"heading": 0.0},
                       disturbance={"moment_z": moment})
        assert np.all(res.status == 0)
        k0 = int(500 / dt)
        delta, psi = res["rudder_angle"], res["heading"]
        b, a = signal.butter(4, 0.1 / (math.pi / dt))
        stats[name] = (np.sqrt(np.mean((np.diff(delta, axis=1)[:, k0:] / dt) ** 2)),
                       np.abs(np.diff(delta[:, k0:], axis=1)).sum(axis=1).mean(),
                       np.sqrt(np.mean(signal.filtfilt(b, a, psi, axis=1)[:, k0:] ** 2)))
    (rate0, travel0, lf0), (rate1, travel1, lf1) = stats["plain"], stats["filtered"]
    assert lf1 == pytest.approx(lf0, rel=0.15)
    assert rate1 < rate0 / 10 and travel1 < travel0 / 10
    assert filtered.sample_period == 0.5
    with pytest.raises(ParameterError, match="`controller_dt` must be 0.5 s"):  # enforced
        simulate(ship=ship, x0=start.state, t_final=10.0, dt=dt, controller=filtered,
                 controller_params=faster.params, controller_dt=1.0,
                 reference={"heading": 0.0})
