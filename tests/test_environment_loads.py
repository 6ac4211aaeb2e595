"""Wind and waves acting on a ship model in the closed loop (seahelm.environment.loads and the
engine's environment stage): calm-water equivalence, symmetry, the live state, batches of
irregular seas, and the registries."""

from __future__ import annotations

import dataclasses

import math
import warnings

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.maneuvers.common import steady_approach
from seahelm.constants import wrap_angle
from seahelm.environment.blendermann import blendermann_wind_loads
from seahelm.environment.loads import (
    WAVE_LOADS,
    WIND_LOADS,
    Conditions,
    LvovWindParams,
    blendermann_wind_params,
    environment,
    lvov_wave_params,
    lvov_wind_loads,
    wave_load_fluctuation,
)
from seahelm.environment.wave_forces import wave_disturbance_body, wave_forces
from seahelm.environment.wind import wind_lateral_force, wind_yaw_moment
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.parameters import as_records
from seahelm.simulation.engine import simulate
from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO, MMG
from seahelm.vessels.nomoto import NOMOTO2
from seahelm.ships import get_ship

# one environment for the whole file (each combination of components compiles once)
ENV = environment(wind="blendermann", waves="lvov")
SHIP = get_ship("kvlcc2-l7").particulars
SPEED = 1.179  # KVLCC2 L7 approach [m/s]


def env_params(**values):
    values = {"wind_speed": 0.0, "wave_height": 0.0, "wave_length": 5.0, **values}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)  # C_b 0.81 > 0.8 of eq. (5)-(7)
        waves = lvov_wave_params(length=SHIP.length, beam=SHIP.beam, draft=SHIP.draft,
                                 block_coefficient=SHIP.block_coefficient)
    return ENV.params(**blendermann_wind_params(
        SHIP.vessel_type, windage_frontal_area=SHIP.frontal_area,
        windage_lateral_area=SHIP.lateral_area, windage_centre=SHIP.windage_centre,
        length_overall=SHIP.length_overall), **waves, **values)


def run(params, *, rudder=0.0, t_final=60.0, environment=ENV, disturbance=None, x0=None):
    app = steady_approach(MMG, KVLCC2_L7, SPEED)
    return simulate(MMG, KVLCC2_L7, app.state if x0 is None else x0, t_final=t_final, dt=0.05,
                    actuator=RUDDER_SERVO, actuator_params=KVLCC2_L7_SERVO,
                    actuator_x0=[app.rudder],
                    reference={"rudder_command": rudder, "propeller_rps": app.rps},
                    environment=environment, environment_params=params,
                    disturbance=disturbance)


def test_zero_wind_and_waves_reproduce_the_calm_water_run_to_rounding():
    calm = run(None, rudder=math.radians(20.0), environment=None)
    still = run(env_params(wind_direction=1.0, wave_direction=2.0), rudder=math.radians(20.0))
    # two kernels (with and without the environment stage), compiled with fastmath's
    # reassociation: the same arithmetic up to the order LLVM picks for each (measured: at most
    # 1 ulp apart)
    assert np.ptp(calm["heading"][0]) > 0.1  # the ship turned
    np.testing.assert_allclose(still.state, calm.state, rtol=1e-13, atol=1e-15)
    # the recorded loads are zero, the apparent wind is the ship's own
    for name in ("wind_force_x", "wind_force_y", "wind_moment_z", "wave_force_x",
                 "wave_force_y", "wave_moment_z"):
        assert np.all(still[name] == 0.0), name
    speed = np.hypot(calm["surge_speed"], calm["sway_speed"])
    np.testing.assert_allclose(still["apparent_wind_speed"], speed, rtol=1e-12)


def test_head_wind_and_head_seas_on_a_symmetric_hull_give_no_yaw():
    res = run(env_params(wind_speed=2.5, wave_height=0.08, wave_length=5.0), t_final=120.0)
    for name in ("wind_force_y", "wind_moment_z", "wave_force_y", "wave_moment_z",
                 "yaw_rate", "heading", "sway_speed", "east"):
        assert np.all(res[name] == 0.0), name
    assert np.all(res["wind_force_x"][0, 1:] < 0.0)  # the head wind resists
    assert np.all(res["wave_force_x"][0, 1:] < 0.0)  # added resistance in head seas
    calm = run(None, t_final=120.0, environment=None)
    assert res["surge_speed"][0, -1] < calm["surge_speed"][0, -1] - 0.01


def test_loads_follow_the_live_heading_and_speed():
    """In a turn under beam wind and waves the recorded loads are the formulas evaluated on
    the recorded heading and velocity (not on the initial course)."""
    p = env_params(wind_speed=2.5, wind_direction=math.radians(90.0), wave_height=0.06,
                   wave_length=6.0, wave_direction=math.radians(45.0))
    cur = (0.1, -0.05)
    dist = {"current_north": cur[0], "current_east": cur[1]}
    res = run(p, rudder=math.radians(35.0), t_final=80.0, disturbance=dist)
    assert res.ok.all()
    psi, u, v = res["heading"][0], res["surge_speed"][0], res["sway_speed"][0]
    assert np.ptp(psi) > math.pi  # it turned through more than half a circle
    vn = u * np.cos(psi) - v * np.sin(psi)
    ve = u * np.sin(psi) + v * np.cos(psi)
    an = -p.wind_speed * math.cos(p.wind_direction) - (vn + cur[0])
    ae = -p.wind_speed * math.sin(p.wind_direction) - (ve + cur[1])
    speed = np.hypot(an, ae)
    angle = wrap_angle(np.arctan2(-ae, -an) - psi)
    np.testing.assert_allclose(res["apparent_wind_speed"][0], speed, rtol=1e-10)
    np.testing.assert_allclose(np.cos(res["apparent_wind_angle"][0]), np.cos(angle), atol=1e-10)
    np.testing.assert_allclose(np.sin(res["apparent_wind_angle"][0]), np.sin(angle), atol=1e-10)
    geometry = dict(frontal_area=SHIP.frontal_area, lateral_area=SHIP.lateral_area,
                    length_overall=SHIP.length_overall, lateral_centre=SHIP.windage_centre)
    full = blendermann_wind_loads(speed, angle, SHIP.vessel_type, **geometry)
    sn, se = -(vn + cur[0]), -(ve + cur[1])
    still = blendermann_wind_loads(np.hypot(sn, se), wrap_angle(np.arctan2(-se, -sn) - psi),
                                   SHIP.vessel_type, **geometry)
    scale = np.max(np.abs(full.sway))
    for name, a, b in (("wind_force_x", full.surge, still.surge),
                       ("wind_force_y", full.sway, still.sway),
                       ("wind_moment_z", full.yaw, still.yaw)):
        ref = a - b
        np.testing.assert_allclose(res[name][0], ref, rtol=1e-8,
                                   atol=1e-9 * scale * (SHIP.length if "moment" in name else 1))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)
        coeffs = (p.wave_cx, p.wave_cy, p.wave_cm)
        q = p.wave_direction - psi
        along = -(vn * math.cos(p.wave_direction) + ve * math.sin(p.wave_direction))
        wf = wave_forces(q, p.wave_height, p.wave_length, coeffs, length=p.hull_length,
                         speed_along_waves=along)
    sway, yaw = wave_disturbance_body(wf)
    np.testing.assert_allclose(res["wave_force_x"][0], wf.surge, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(res["wave_force_y"][0], sway, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(res["wave_moment_z"][0], yaw, rtol=1e-9, atol=1e-12)


def test_a_batch_of_seeded_irregular_seas_equals_the_runs_one_by_one():
    n_runs, t_final, dt = 100, 20.0, 0.05
    n = int(round(t_final / dt)) + 1
    seeds = np.random.SeedSequence(11).spawn(n_runs)
    fluct = np.array([wave_load_fluctuation(2.0, n, dt, s) for s in seeds])
    assert not np.allclose(fluct[0], fluct[1])  # each run its own sea
    p = env_params(wave_height=0.05, wave_length=6.0, wave_direction=math.radians(60.0))
    nd = MMG.n_disturbances + len(ENV.signal_labels)
    dist = np.zeros((n_runs, n, nd))
    dist[:, :, nd - 1] = fluct  # wave_load_fluctuation, the last channel
    batch = run(p, t_final=t_final, disturbance=dist)
    assert batch.ok.all()
    for i in range(n_runs):
        one = run(p, t_final=t_final, disturbance=dist[i:i + 1])
        np.testing.assert_array_equal(one.state[0], batch.state[i])
        np.testing.assert_array_equal(one.output[0], batch.output[i])
    # the loads scale with 1 + f(t)
    mean_load = run(p, t_final=t_final).output[0, :, batch.output_labels.index("wave_force_y")]
    got = batch.output[3, :, batch.output_labels.index("wave_force_y")]
    assert np.std(got / (1.0 + fluct[3]) / mean_load) < 0.05  # the ship turns a little


def test_the_wave_load_fluctuation_has_zero_mean_and_a_floor_at_minus_one():
    f = wave_load_fluctuation(3.0, 200_000, 0.5, 5)
    assert f.min() >= -1.0
    assert abs(f.mean()) < 0.05  # E[A²]/E[A²] − 1 = 0 (the record is ~4,000 wave periods)
    assert 0.5 < f.std() < 1.5  # A²/E[A²] of a narrow-band sea is ~ exponential (std 1)
    np.testing.assert_array_equal(f, wave_load_fluctuation(3.0, 200_000, 0.5, 5))


def test_many_seas_drawn_at_once_equal_the_seas_drawn_one_by_one():
    seqs = np.random.SeedSequence(11).spawn(4)
    batch = wave_load_fluctuation(2.5, 300, 0.5, seqs, runs=4)
    assert batch.shape == (4, 300)
    for i, seq in enumerate(seqs):
        np.testing.assert_array_equal(batch[i], wave_load_fluctuation(2.5, 300, 0.5, seq))
    np.testing.assert_array_equal(wave_load_fluctuation(2.5, 300, 0.5, [7, 8], runs=2)[1],
                                  wave_load_fluctuation(2.5, 300, 0.5, 8))
    assert not np.array_equal(batch[0], batch[1])


def test_lvov_wind_kernel_equals_the_paper_functions():
    params = LvovWindParams(wind_speed=1.0, windage_lateral_area=1059.9, windage_centre=4.0,
                            windage_length=160.93)
    p = environment(wind="lvov").kernel_records(params.to_array()[None, :])[0]
    for angle in np.radians([0.0, 30.0, 60.0, 90.0, 150.0, -45.0, -120.0, 180.0]):
        x, y, n = lvov_wind_loads(p, 12.0, angle, math.cos(angle), math.sin(angle))
        assert x == 0.0
        np.testing.assert_allclose(y, -wind_lateral_force(12.0, angle, 1059.9), rtol=1e-12,
                                   atol=1e-9)
        np.testing.assert_allclose(n, -wind_yaw_moment(12.0, angle, 1059.9, length=160.93,
                                                       sail_centre=4.0), rtol=1e-12, atol=1e-6)


def test_the_wave_kernel_with_its_per_run_constants_equals_the_paper_functions():
    """The compiled wave loads read constants computed once per run (kernel_records)."""
    params = env_params(wave_height=3.0, wave_length=120.0, wave_direction=math.radians(40.0))
    rec = ENV.kernel_records(params.to_array()[None, :])[0]
    assert rec.wave_from_cos == math.cos(params.wave_direction)
    assert rec.wind_from_sin == math.sin(params.wind_direction)
    loads = WAVE_LOADS["lvov"].loads
    coeffs = (params.wave_cx, params.wave_cy, params.wave_cm)
    for q_deg, along in ((0.0, 0.0), (30.0, -2.0), (90.0, 1.5), (-135.0, 3.0), (180.0, 0.5)):
        q = math.radians(q_deg)
        got = loads(rec, q, math.cos(q), math.sin(q), along, 1.25)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityRangeWarning)
            wf = wave_forces(q, params.wave_height, params.wave_length, coeffs,
                             length=params.hull_length, speed_along_waves=along)
        sway, yaw = wave_disturbance_body(wf)
        scale = 1.25 * max(abs(wf.surge), abs(sway), 1.0)
        np.testing.assert_allclose(got, 1.25 * np.array([wf.surge, sway, yaw]), rtol=1e-12,
                                   atol=1e-12 * scale * params.hull_length)


def test_registries_and_the_component():
    assert set(WIND_LOADS) == {"blendermann", "lvov", "fujiwara"} and set(WAVE_LOADS) == {"lvov"}
    assert environment("lvov", "lvov") is environment("lvov", "lvov")
    with pytest.raises(ValueError, match="unknown wind load model 'isherwood'; valid: "
                                         "blendermann, lvov"):
        environment(wind="isherwood")
    with pytest.raises(ValueError, match="unknown wave load model 'faltinsen'; valid: lvov"):
        environment(waves="faltinsen")
    with pytest.raises(ValueError, match="needs wind and/or waves"):
        environment()
    assert ENV.signal_labels == ("wind_gust", "wave_load_fluctuation")
    assert ENV.output_units[ENV.output_labels.index("wind_moment_z")] == "N·m"
    with pytest.raises(ParameterError, match="`wind_speed` .*-1"):
        env_params(wind_speed=-1.0)


def test_a_model_without_force_channels_is_refused_by_name():
    with pytest.raises(ParameterError, match="no disturbance channel 'force_y' \\[N\\]"):
        simulate(NOMOTO2, NOMOTO2.params_type(gain=0.1, t1=50, t2=5, t3=10, speed=5.0),
                 np.zeros(5), t_final=10.0, dt=0.1, environment=ENV,
                 environment_params=env_params())
    with pytest.raises(ParameterError, match="`environment_params` given without"):
        run(env_params(), environment=None)


def test_conditions_validate_and_give_the_current_channels():
    c = Conditions(current_speed=0.5, current_direction=math.pi / 2)
    d = c.disturbance(MMG)
    assert d["current_north"] == pytest.approx(0.0, abs=1e-15) and d["current_east"] == 0.5
    with pytest.raises(ParameterError, match="no current channels"):
        Conditions(current_speed=0.5).disturbance(MMG.__class__(
            **{**MMG.__dict__, "name": "x", "disturbance_labels": ("force_x",),
               "disturbance_units": ("N",)}))
    with pytest.raises(ParameterError, match="`current_speed` must be >= 0 \\[m/s\\], got -1"):
        Conditions(current_speed=-1.0)
    with pytest.raises(ParameterError, match="`params` of the environment are required"):
        Conditions(ENV)


@pytest.mark.parametrize("catalog_name", ["kvlcc2-l7", "mariner-nonlinear", "mariner-voitkunsky"])
def test_a_models_motion_equals_its_outputs(catalog_name):
    """``motion`` (what the environment reads) is the model's own surge, sway and heading."""
    from seahelm.registry import get_model
    from seahelm.ships import catalog

    entry = catalog.get(catalog_name)
    model = get_model(entry.model)
    rng = np.random.default_rng(3)
    x = rng.normal(size=(20, model.n_states)) * 0.3
    u = np.zeros((20, model.n_inputs))
    y = model.outputs(0.0, x, u, entry.params)
    rec = as_records(entry.params.to_array()[None, :], type(entry.params))[0]
    for xi, yi in zip(x, y):
        got = model.motion(xi, rec)
        want = [yi[model.output_index(n)] for n in ("surge_speed", "sway_speed", "heading")]
        np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-15)


def test_ship_load_params_take_the_particulars():
    from seahelm.environment.loads import ship_load_params

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)
        got = ship_load_params(get_ship("kvlcc2-l7"), ENV, wind_speed=2.0, wave_height=0.05)
    assert got == env_params(wind_speed=2.0, wave_height=0.05, wave_length=100.0)
    lvov = environment(wind="lvov")
    p = ship_load_params(SHIP, lvov, wind_speed=1.0, windage_centre=0.1)
    assert (p.windage_lateral_area, p.windage_length, p.windage_centre) == (
        SHIP.lateral_area, SHIP.length, 0.1)
    with pytest.raises(ParameterError, match="Ship with particulars or a Particulars"):
        ship_load_params("kvlcc2-l7", lvov, wind_speed=1.0)
    with pytest.raises(ParameterError, match="without particulars"):
        ship_load_params(get_ship("mariner-nonlinear").replace(particulars=None), lvov)
    no_windage = dataclasses.replace(SHIP, lateral_area=None)
    with pytest.raises(ParameterError, match=r"`particulars.lateral_area` is not known \[m²\]"):
        ship_load_params(no_windage, lvov, wind_speed=1.0)


def test_a_sea_signal_draws_many_runs_at_once_as_one_by_one():
    from seahelm.simulation.signals import Sea

    sea = Sea(h3=3.0, gain=0.01, quantity="slope", seed=4)
    t = np.arange(400) * 0.25
    seqs = [np.random.SeedSequence(4, spawn_key=(i,)) for i in range(3)]
    rows = sea.draw_runs(t, seqs)
    for i, seq in enumerate(seqs):
        np.testing.assert_array_equal(rows[i], sea(t, seed=seq))
    assert not np.array_equal(rows[0], rows[1])
