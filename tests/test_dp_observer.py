"""The passive wave-filtering observer (dp-pid-observer) on the supply vessel in the engine: its
measurements are position and heading with the first-order surge, sway and yaw of an irregular
sea and seeded noise, made by the sensor stage inside the compiled loop
(seahelm.simulation.sensor_stage), against the raw dp-pid fed the same measured positions. The
runs are in the sea of examples/supply_dp_observer_waves.toml, its mean wave loads included
(:func:`sea_problem`): the observer's loop is that example's kernel."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.control.dp_observer import DP_PID_OBSERVER, DpObserverParams
from seahelm.control.dp_pid import DP_PID, DpPidParams, dp_pid_params
from seahelm.environment import rao_io
from seahelm.environment.first_order_in_loop import first_order_in_loop
from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.errors import ValidityRangeWarning
from seahelm.registry import get_controller
from seahelm.scenario import parse_scenario
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.simulation.sensor_stage import PositionSensors

SHIP = get_ship("supply")
H = 0.1
T_FINAL = 400.0
SET = np.array([5.0, 5.0, math.radians(5.0)])
#: The sea: h3% 4 m (Rakhmanin–Firsov), from 135° (off the port bow at ψ = 5°), peak 0.85 rad/s
SEA = spectrum_from_wave_height("rakhmanin-firsov-2", 4.0)
W0 = SEA.peak_frequency
NOISE = dict(noise_north=0.05, noise_east=0.05, noise_heading=math.radians(0.1))
#: The example of this loop: its sea's mean loads and first-order motions in six DOFs are
#: those of :func:`sea_problem` (one kernel for both: the example's components)
EXAMPLE = Path(__file__).parents[1] / "examples" / "supply_dp_observer_waves.toml"
SIX_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


@functools.cache
def example_wave_loads():
    """The environment and its parameters of :data:`EXAMPLE`, as its scenario builds them:
    Lvov's (2014) mean wave loads, eq. (8)-(10), of the same sea (h3% 4 m, 7.4 s, from 135°).
    They warn: the supply vessel's L/B = 4.2 is below the coefficients' fitted 5-12."""
    with pytest.warns(ValidityRangeWarning, match="L/B"):
        example = parse_scenario(EXAMPLE.read_text(), source=str(EXAMPLE))
    return example.environment, example.environment_params


def dp_problem(controller, params, runs=1, seed=4, sensors=None, t_final=T_FINAL,
               wave_dofs=("surge", "sway", "yaw"), components=None, wave_loads=False):
    """The supply vessel held at SET from rest, the box barge's panel-method RAOs for its
    first-order ``wave_dofs`` (the catalog vessel has none of its own), its controller
    measuring what the sensor stage gives; with ``wave_loads``, the sea's mean loads too
    (:func:`example_wave_loads`)."""
    barge = rao_io.read_rao(rao_io.box_barge_database())
    fo = first_order_in_loop(SEA, barge, wave_direction=math.radians(135.0), runs=runs,
                             seed=seed, dofs=wave_dofs, components=components)
    ref = {"north": SET[0], "east": SET[1], "heading": SET[2], "wind_force_x": 0.0,
           "wind_force_y": 0.0, "wind_moment_z": 0.0}
    environment, environment_params = example_wave_loads() if wave_loads else (None, None)
    return Problem(ship=SHIP, t_final=t_final, dt=H, controller_dt=H, x0=np.zeros((runs, 6)),
                   controller=controller, controller_params=params, actuator="direct",
                   reference=ref, first_order=fo, environment=environment,
                   environment_params=environment_params,
                   sensors=sensors or PositionSensors(**NOISE, wave_motion=True, seed=1))


def sea_problem(controller, params, **kw):
    """:func:`dp_problem` in the sea of :data:`EXAMPLE`: its mean wave loads and first-order
    motions in six DOFs (the sensors measure the surge, sway and yaw of them), so that the
    observer's loop is the example's kernel (compiled once for both)."""
    return dp_problem(controller, params, wave_dofs=SIX_DOFS, wave_loads=True, **kw)


def observer_params():
    """dp-pid's gains and the observer at the sea's peak frequency; κ₄ = 0.01 1/s² (the
    default 0.1 lets the irregular sea's band into ν̂, and the derivative gain passes it:
    wave-band thrust 0.96, 0.84, 0.28 of the raw PID's in surge, sway, yaw)."""
    return DpObserverParams(**dp_pid_params(SHIP).as_dict(), wave_frequency=W0,
                            observer_stiffness=0.01)


@pytest.fixture(scope="module")
def runs():
    obs = simulate(sea_problem(DP_PID_OBSERVER, observer_params())).to_xarray()
    raw = simulate(sea_problem(DP_PID, dp_pid_params(SHIP))).to_xarray()
    return obs, raw


def _late(ds, after):
    return ds.time.values > after


def test_the_observer_is_registered():
    assert get_controller("dp-pid-observer") is DP_PID_OBSERVER
    assert DP_PID_OBSERVER.measurement_labels == ("north", "east", "heading")
    assert DP_PID_OBSERVER.output_labels[-3:] == ("estimated_north", "estimated_east",
                                                  "estimated_heading")


def test_the_measurements_carry_the_waves_and_the_noise(runs):
    """What the controller saw: the true position plus the first-order motion rotated to
    north/east (0.23 m, 0.27 m, 0.48° standard deviations here) and the noise."""
    obs, _ = runs
    psi = obs.heading.values[0]
    xi1, xi2 = obs.surge_wave.values[0], obs.sway_wave.values[0]
    wave_n = np.cos(psi) * xi1 - np.sin(psi) * xi2
    noise = obs.measured_north.values[0] - obs.north.values[0] - wave_n
    assert 0.045 < noise.std() < 0.055 and abs(noise.mean()) < 0.005
    assert obs.surge_wave.values.std() > 0.1 and obs.sway_wave.values.std() > 0.1
    assert np.degrees(obs.yaw_wave.values.std()) > 0.3


def test_the_vessel_reaches_its_set_point_on_the_estimates(runs):
    """Held within 0.3 m and 0.3° over the last 100 s against the sea's mean loads (measured:
    0.17 m, 0.09 m, 0.07°; the loads 17 kN, -58 kN, 0.71 MN·m, the thrust balancing them)."""
    obs, _ = runs
    late = _late(obs, T_FINAL - 100.0)
    assert obs.status.values[0] == 0
    pos = np.stack([obs[n].values[0, late] for n in ("north", "east", "heading")], 1)
    assert np.max(np.abs(pos[:, :2] - SET[:2])) < 0.3
    assert np.max(np.abs(pos[:, 2] - SET[2])) < math.radians(0.3)


def test_the_estimates_filter_the_waves_out(runs):
    """The estimate η̂ follows the true (low-frequency) position: its rms error is a part of
    the measurement's (the first-order motion and the noise). Measured: 0.55, 0.53, 0.23 in
    north, east, heading (the notch at ω₀ takes a sinusoid there out, as the last session's
    Python loop had it, to 0.15; the irregular sea's band is wider than the notch; 0.53, 0.52,
    0.20 without the mean wave loads)."""
    obs, _ = runs
    late = _late(obs, 100.0)
    err_est, err_meas = [], []
    for est, meas, true in (("estimated_north", "measured_north", "north"),
                            ("estimated_east", "measured_east", "east"),
                            ("estimated_heading", "measured_heading", "heading")):
        t = obs[true].values[0, late]
        err_est.append(np.sqrt(np.mean((obs[est].values[0, late] - t) ** 2)))
        err_meas.append(np.sqrt(np.mean((obs[meas].values[0, late] - t) ** 2)))
    err_est, err_meas = np.array(err_est), np.array(err_meas)
    print("estimate / measurement rms error:", err_est / err_meas)
    assert np.all(err_est < 0.6 * err_meas), (err_est, err_meas)


def test_the_thrusters_do_not_chase_the_waves(runs):
    """The thrust's fluctuation in the wave band (what is left after a moving mean over one
    peak period) with the observer is a fraction of that of the PID fed the same measured
    positions (and the true velocities, which no DP sensor gives). Measured in the engine:
    0.34, 0.30, 0.16 in surge, sway, yaw (in the last session's Python loop, a sinusoid at
    ω₀: 0.23, 0.25, 0.14); the rest is mostly the noise and the sea's band off ω₀."""
    obs, raw = runs
    width = int(round(2.0 * math.pi / W0 / H))

    def wave_band(ds):
        thrust = np.stack([ds[n].values[0] for n in ("thrust_surge", "thrust_sway",
                                                      "thrust_yaw")], 1)
        kernel = np.ones(width) / width
        mean = np.stack([np.convolve(thrust[:, j], kernel, mode="same") for j in range(3)], 1)
        t = ds.time.values
        late = (t > 100.0) & (t < T_FINAL - width * H)
        return (thrust - mean)[late].std(axis=0)

    sd_obs, sd_raw = wave_band(obs), wave_band(raw)
    print("wave-band thrust std, observer / raw:", sd_obs / sd_raw)
    assert np.all(sd_obs < 0.45 * sd_raw), (sd_obs, sd_raw)


def test_observer_params_are_the_pid_params_and_more():
    assert set(DpPidParams.field_names()) < set(DpObserverParams.field_names())


def _regular_wave(amplitude=2.0, omega=W0):
    """One wave component at ω (regular waves from 135°, travelling towards 315°)."""
    from seahelm.environment.first_order import WaveComponents

    one = lambda v: np.array([[v]])  # noqa: E731
    return WaveComponents(frequency=one(omega), wavenumber=one(omega ** 2 / 9.81),
                          direction=one(math.radians(135.0 + 180.0)), amplitude=one(amplitude),
                          phase=one(0.3), band=(0.5 * omega, 2.0 * omega),
                          seeds=[np.random.SeedSequence(4)])


@pytest.fixture(scope="module")
def regular_runs():
    """The same two loops (the same kernels) in regular waves at the observer's ω₀, with its
    default κ₄: the case its notch is designed for (the mean wave loads are the irregular
    sea's, of the example: a steady push the integral action takes, not in the wave band)."""
    obs_params = DpObserverParams(**dp_pid_params(SHIP).as_dict(), wave_frequency=W0)
    obs = simulate(sea_problem(DP_PID_OBSERVER, obs_params,
                               components=_regular_wave())).to_xarray()
    raw = simulate(sea_problem(DP_PID, dp_pid_params(SHIP), components=_regular_wave())
                   ).to_xarray()
    return obs, raw


def test_in_regular_waves_at_the_notch_the_estimates_drop_the_wave_motion(regular_runs):
    """A sinusoid at ω₀ is what the observer's wave model takes out (Fossen & Strand 1999):
    the estimate's rms error is a small part of the measurement's (the claim of the last
    session's Python loop, 0.15, now in the engine)."""
    obs, _ = regular_runs
    late = _late(obs, 100.0)
    ratio = []
    for est, meas, true in (("estimated_north", "measured_north", "north"),
                            ("estimated_east", "measured_east", "east"),
                            ("estimated_heading", "measured_heading", "heading")):
        t = obs[true].values[0, late]
        ratio.append(np.sqrt(np.mean((obs[est].values[0, late] - t) ** 2))
                     / np.sqrt(np.mean((obs[meas].values[0, late] - t) ** 2)))
    print("regular waves, estimate / measurement rms error:", ratio)
    assert obs.surge_wave.values.std() > 0.1 and obs.sway_wave.values.std() > 0.1
    assert np.all(np.array(ratio) < 0.15), ratio


def test_in_regular_waves_at_the_notch_the_thrusters_do_not_chase_them(regular_runs):
    """The wave-band thrust with the observer against the raw PID's in regular waves at ω₀:
    the last session's Python-loop bound (0.3), now in the engine."""
    obs, raw = regular_runs
    width = int(round(2.0 * math.pi / W0 / H))

    def wave_band(ds):
        thrust = np.stack([ds[n].values[0] for n in ("thrust_surge", "thrust_sway",
                                                      "thrust_yaw")], 1)
        mean = np.stack([np.convolve(thrust[:, j], np.ones(width) / width, mode="same")
                         for j in range(3)], 1)
        t = ds.time.values
        return (thrust - mean)[(t > 100.0) & (t < T_FINAL - width * H)].std(axis=0)

    ratio = wave_band(obs) / wave_band(raw)
    print("regular waves, wave-band thrust std, observer / raw:", ratio)
    assert np.all(ratio < 0.3), ratio
