"""Scenario files: every validation branch names file, key path, value; batches; examples.

Checks made by the engine (timing, bounds labels, command counts) reach the user as a
:class:`ScenarioError` naming the file and key, with the engine's own message.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.errors import ParameterError, ValidityRangeWarning

from seahelm.scenario import ManeuverJob, ScenarioError, default_scenario_text, load_scenario, parse_scenario, run_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

BASE = """
title = "t"
[vessel]
model = "nomoto2"
catalog = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 20.0
dt = 0.1
"""


def _with(extra: str = "", replace: tuple[str, str] | None = None) -> str:
    text = BASE
    if replace:
        assert replace[0] in text
        text = text.replace(*replace)
    return text + extra


def test_default_scenario_is_valid_and_converts_degrees():
    batch = parse_scenario(default_scenario_text(), source="default")
    assert batch.n_runs == 1
    assert batch.reference[0, 0, 0] == pytest.approx(math.radians(20.0))
    assert batch.actuator_params[0, 0] == pytest.approx(math.radians(35.0))


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (_with(replace=('model = "nomoto2"', 'model = "nomoto3"')),
         r"s.toml: \[vessel.model\] unknown vessel model 'nomoto3'; valid: .*nomoto1, nomoto2"),
        (_with(replace=('catalog = "mariner-nomoto2"', 'catalog = "titanic"')),
         r"\[vessel.catalog\] unknown catalog ship 'titanic'; valid: .*mariner-nomoto2, .*\(or the "
         r"path of a ship file, \*.toml\)"),
        (_with(replace=('catalog = "mariner-nomoto2"', 'catalog = "mariner-nomoto1"')),
         r"\[vessel.catalog\] 'mariner-nomoto1' is a ship of model 'nomoto1', not 'nomoto2'"),
        (_with("[vessel.params]\ngain = -0.1\n"),
         r"\[vessel.params\] `gain` must be nonzero and of the sign of t1 .*got -0.1"),
        (_with("[vessel.params]\ngian = 0.1\n"),
         r"\[vessel.params\] unknown parameter `gian` for Nomoto2Params; valid: gain, t1"),
        (_with("[vessel.params]\nspeed_deg = 3.0\n"),
         r"\[vessel.params\] `speed_deg`: field `speed` is not an angle"),
        (_with(replace=('catalog = "mariner-nomoto2"\n', '')),
         r"\[vessel.params\] missing required parameter\(s\) gain, t1, t2, t3, speed"),
        (_with("[vessel.initial]\nheadin = 1.0\n"),
         r"\[vessel.initial.headin\] unknown channel 'headin'; valid: north, east, heading"),
        (_with(replace=("heading_deg = 10.0", "course = 10.0")),
         r"\[controller.reference.course\] unknown channel 'course'; valid: heading"),
        (_with(replace=("heading_deg = 10.0", 'heading = { kind = "square" }')),
         r"\[controller.reference.heading\] unknown signal kind 'square'; valid: constant"),
        (_with(replace=("t_final = 20.0", "t_final = 20.05")),
         r"s.toml: \[simulation.t_final\] must be a positive whole multiple of `dt` "
         r"\[s\]: t_final=20.05, dt=0.1"),
        (_with(replace=("t_final = 20.0", "t_final = -5")),
         r"\[simulation.t_final\] must be > 0 \[s\], got -5"),
        (_with(replace=("dt = 0.1", 'dt = "fast"')),
         r"\[simulation.dt\] must be a number \[s\] \(not a string or a boolean\), got 'fast'"),
        (_with(replace=('model = "pid-heading"', 'model = "pid-heading"\ndt = 0.25'),),
         r"s.toml: \[controller.dt\] must be a positive whole multiple of `dt` "
         r"\[s\]: controller_dt=0.25, dt=0.1"),
        (_with(replace=("dt = 0.1", "dt = 0.1\nrecord_every = 500")),
         r"s.toml: \[simulation.record_every\] = 500 exceeds the number of steps "
         r"\(200 = t_final/dt\): nothing after t = 0 would be recorded"),
        (_with(replace=("dt = 0.1", 'dt = 0.1\nintegrator = "rk5"')),
         r"s.toml: \[simulation.integrator\] unknown integrator 'rk5'; "
         r"valid: euler, midpoint, heun, ralston, bosh3, ssprk3, kutta3, rk4, rk38"),
        (_with(replace=('model = "pid-heading"', 'model = "lqr"')),
         r"\[controller.model\] unknown controller 'lqr'; valid: .*pid-heading"),
        (_with("[actuator]\nmodel = \"jet\"\n"),
         r"\[actuator.model\] unknown actuator 'jet'; valid: direct, rudder-propeller, rudder-servo"),
        (_with("[environment.disturbance]\nwave = 1.0\n"),
         r"\[environment.disturbance.wave\] unknown channel 'wave'; valid: rudder_disturbance"),
        (_with("[simulation.bounds]\nspeed = [0, 1]\n"),
         r"s.toml: \[simulation.bounds.speed\] is an unknown state; states: north"),
        (_with("[batch.grid]\n\"vessel.colour\" = [1.0]\n"),
         r"\[batch.vessel.colour\] cannot vary 'vessel.colour'"),
        (_with("[batch.grid]\n\"vessel.params.gain\" = [0.1, -0.2]\n"),
         r"\[vessel.params\] `gain` must be nonzero .* got -0.2 \(run 1: \{'vessel.params.gain': -0.2\}\)"),
        (_with("[batch.monte_carlo]\nruns = 3\nseed = 1\n[batch.monte_carlo.draws]\n"
               "\"vessel.params.gain\" = { distribution = \"normal\", mean = 0.2 }\n"),
         r"\[batch.monte_carlo.draws.vessel.params.gain\] a normal draw needs `mean` and `std`"),
        (_with("colour = \"red\"\n"), r"\[simulation.colour\] is an unknown key; valid in "
                                      r"\[simulation\]: bounds, dt, exact_actuator, integrator, "
                                      r"record_every, t_final$"),
        (_with("record_dt = 1.0\n"), r"\[simulation.record_dt\] is an unknown key \(did you "
                                     r"mean `record_every`\?\); valid in \[simulation\]: "),
        (_with(replace=("[vessel]", "[vesel]")), r"\[vesel\] is an unknown key \(did you mean "
                                                 r"`vessel`\?\)"),
        ("[vessel\nmodel=1", r"s.toml: not valid TOML"),
        (_with(replace=("[simulation]\nt_final = 20.0\ndt = 0.1\n", "")),
         r"s.toml: a scenario needs a \[simulation\] section \(t_final, dt, ...\) or a "
         r"\[maneuver\] section"),
    ],
)
def test_bad_scenarios_name_file_key_value_and_expectation(text, match):
    steps = []
    with pytest.raises(ScenarioError, match=match):
        # the scenario's checks raise while parsing, the engine's when the batch runs
        run_scenario(parse_scenario(text, source="s.toml"), progress=lambda k, n: steps.append(k))
    assert steps == []  # nothing was integrated


def test_missing_file(tmp_path):
    with pytest.raises(ScenarioError, match="scenario file not found"):
        load_scenario(tmp_path / "none.toml")


def test_grid_is_a_cartesian_product():
    batch = parse_scenario(_with('[batch.grid]\n"controller.params.kp" = [1.0, 2.0, 3.0]\n'
                                    '"vessel.initial.heading_deg" = [0.0, 5.0]\n'))
    assert batch.n_runs == 6
    assert sorted(set(batch.controller_params[:, 0])) == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(sorted(set(batch.x0[:, 2])), [0.0, math.radians(5.0)])


def test_monte_carlo_is_seeded_and_reproducible():
    mc = ('[batch.monte_carlo]\nruns = 50\nseed = {seed}\n[batch.monte_carlo.draws]\n'
          '"vessel.params.gain" = {{ distribution = "uniform", low = 0.1, high = 0.3 }}\n')
    a = parse_scenario(_with(mc.format(seed=1)))
    b = parse_scenario(_with(mc.format(seed=1)))
    c = parse_scenario(_with(mc.format(seed=2)))
    np.testing.assert_array_equal(a.params, b.params)
    assert not np.array_equal(a.params, c.params)
    gains = a.params[:, 0]
    assert gains.min() >= 0.1 and gains.max() <= 0.3 and np.unique(gains).size == 50
    result = run_scenario(a)
    assert result.metadata["seed"] == 1
    assert result.to_xarray().attrs["seed"] == 1


def test_time_varying_reference_per_run():
    batch = parse_scenario(_with(
        '[batch.grid]\n"controller.reference.heading_deg" = [5.0, 10.0]\n',
        replace=("heading_deg = 10.0", 'heading_deg = { kind = "step", time = 5.0, after = 1.0 }'),
    ))
    assert batch.reference.shape == (2, 1, 1)  # the grid value replaces the signal
    np.testing.assert_allclose(batch.reference[:, 0, 0], np.radians([5.0, 10.0]))


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.name)
def test_every_example_scenario_runs(path):
    text = path.read_text()
    if "\n[environment.waves]" in text and "\nheight = 0.0\n" not in text:
        # Lvov's wave-force coefficients warn outside their fitted hulls (the Mariner's
        # C_b = 0.542 < 0.6, the KVLCC2's 0.81 > 0.8): the example says so, and runs
        # (with no waves, height 0, the coefficients multiply zero: no warning); the supply
        # vessel's L/B = 4.2 < 5 (supply_dp_observer_waves.toml)
        with pytest.warns(ValidityRangeWarning, match="block coefficient|L/B"):
            job = load_scenario(path)
    else:
        job = load_scenario(path)
    result = run_scenario(job)
    if isinstance(job, ManeuverJob) and job.kind == "imo" and job.monte_carlo is not None:
        assert result.excluded == 0 and result.total == job.n_samples, result.reasons
    elif isinstance(job, ManeuverJob):  # every event of every run reached
        assert bool(result.metrics["complete"].all()), result.metrics["message"].values
    else:
        assert result.ok.all(), result.messages()


SEA = ('[environment.disturbance]\nrudder_disturbance = {{ kind = "sea", h3 = {h3}, gain = 1.0, '
       'quantity = "{q}", seed = {seed} }}\n')


def test_sea_signal_has_the_spectrum_variance_and_a_realisation_per_run():
    from seahelm.environment.spectra import spectrum_from_wave_height

    text = _with(SEA.format(h3=3.0, q="ordinate", seed=5)
                 + "[batch.monte_carlo]\nruns = 3\nseed = 1\n",
                 replace=("t_final = 20.0\ndt = 0.1", "t_final = 20000.0\ndt = 1.0"))
    batch = parse_scenario(text)
    t_grid = np.arange(20001) * 1.0  # the engine samples the signal on its own grid
    dist = batch.disturbance(t_grid)[:, :, 0]
    assert dist.shape == (3, 20001)
    assert not np.allclose(dist[0], dist[1])
    # D_r = 0.143 (h3/2)^2; the sample variance of a long record is within a few percent
    d_r = spectrum_from_wave_height("rakhmanin-firsov-2", 3.0).variance
    assert d_r == pytest.approx(0.143 * 1.5**2)
    np.testing.assert_allclose(dist.var(axis=1), d_r, rtol=0.1)
    again = parse_scenario(text)
    np.testing.assert_array_equal(again.disturbance(t_grid), batch.disturbance(t_grid))


def test_the_monte_carlo_seed_draws_new_seas():
    """Changing [batch.monte_carlo] seed changes the irregular-sea realisations (the file
    records that seed), keeping it reproduces them."""
    base = _with(SEA.format(h3=3.0, q="ordinate", seed=5) + "[batch.monte_carlo]\nruns = 2\n")
    t_grid = np.arange(201) * 0.1
    one = parse_scenario(base + "seed = 1\n").disturbance(t_grid)
    again = parse_scenario(base + "seed = 1\n").disturbance(t_grid)
    other = parse_scenario(base + "seed = 2\n").disturbance(t_grid)
    np.testing.assert_array_equal(one, again)
    assert not np.allclose(one[:, :, 0], other[:, :, 0])


def test_sea_signal_bad_input():
    with pytest.raises(ScenarioError, match=r"unknown sea quantity 'height'"):
        parse_scenario(_with(SEA.format(h3=3.0, q="height", seed=1)))
    with pytest.raises(ScenarioError, match=r"`h3` must be > 0 \[m\], got -1.0"):
        parse_scenario(_with(SEA.format(h3=-1.0, q="slope", seed=1)))
    with pytest.raises(ScenarioError, match=r"`seed` must be an integer >= 0"):
        parse_scenario(_with(SEA.format(h3=3.0, q="slope", seed=-4)))


def test_empty_grid_is_rejected():
    with pytest.raises(ScenarioError, match=r"\[batch.grid.controller.params.kp\] needs at least "
                                            r"one value, got \[\]"):
        parse_scenario(_with('[batch.grid]\n"controller.params.kp" = []\n'))


# -- results keep the shape of the question ------------------------------------------------
GRID = ('[batch.grid]\n"controller.params.kp" = [1.0, 2.0, 3.0]\n'
        '"controller.params.kd" = [10.0, 20.0, 30.0, 40.0]\n')
KPS, KDS = [1.0, 2.0, 3.0], [10.0, 20.0, 30.0, 40.0]


@pytest.fixture(scope="module")
def grid_result():
    return run_scenario(parse_scenario(_with(GRID), source="grid.toml"))


def test_grid_keeps_its_dimensions_and_coordinates(grid_result):
    ds = grid_result.to_xarray()
    assert ds["heading"].dims == ("kp", "kd", "time")
    assert ds["status"].dims == ("kp", "kd")
    assert ds["controller.kp"].dims == ("kp", "kd")
    assert dict(ds.sizes) == {"kp": 3, "kd": 4, "time": 201}
    assert ds["kp"].values.tolist() == KPS and ds["kd"].values.tolist() == KDS
    assert ds["kp"].attrs["key"] == "controller.params.kp"
    assert ds["kd"].attrs["key"] == "controller.params.kd"
    # the parameter actually used in each cell is the cell's coordinate
    np.testing.assert_array_equal(ds["controller.kp"].values, np.repeat([KPS], 4, axis=0).T)
    np.testing.assert_array_equal(ds["controller.kd"].values, np.repeat([KDS], 3, axis=0))


def test_each_grid_cell_equals_the_run_simulated_alone(grid_result, mariner2):
    from seahelm.control.pid import PID_HEADING, PIDHeadingParams
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2

    ds = grid_result.to_xarray()
    for kp, kd in [(1.0, 10.0), (2.0, 30.0), (3.0, 40.0), (3.0, 10.0)]:
        alone = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=20.0, dt=0.1,
                         controller=PID_HEADING, controller_params=PIDHeadingParams(kp=kp, kd=kd),
                         reference=[math.radians(10.0)])
        cell = ds.sel(kp=kp, kd=kd)
        np.testing.assert_allclose(cell["heading"].values, alone["heading"][0], rtol=1e-13,
                                   atol=1e-15)
        np.testing.assert_allclose(cell["rudder_angle"].values, alone["rudder_angle"][0],
                                   rtol=1e-13, atol=1e-15)


def test_flat_view_has_twelve_runs_in_c_order_of_the_grid(grid_result):
    ds = grid_result.to_xarray()
    flat = grid_result.to_xarray(flat=True)
    assert flat["heading"].dims == ("run", "time")
    assert flat.sizes["run"] == 12 and grid_result.n_runs == 12
    assert flat["run"].values.tolist() == list(range(12))
    assert flat["kp"].values.tolist() == [1.0] * 4 + [2.0] * 4 + [3.0] * 4
    assert flat["kd"].values.tolist() == KDS * 3
    for i in range(12):
        np.testing.assert_array_equal(flat["heading"].values[i],
                                      ds["heading"].values[i // 4, i % 4])
        np.testing.assert_array_equal(grid_result.state[i, :, 2], flat["heading"].values[i])


def test_grid_netcdf_round_trip_keeps_dims_and_coordinates(grid_result, tmp_path):
    from seahelm.results import flatten_runs, load_result

    back = load_result(grid_result.to_netcdf(tmp_path / "grid.nc"))
    ref = grid_result.to_xarray()
    assert back["heading"].dims == ("kp", "kd", "time")
    assert back["kp"].values.tolist() == KPS and back["kd"].values.tolist() == KDS
    assert back["kp"].attrs["key"] == "controller.params.kp"
    np.testing.assert_array_equal(back["heading"].values, ref["heading"].values)
    assert back["status_message"].dims == ("kp", "kd")
    flat = flatten_runs(back)
    assert flat["kd"].values.tolist() == KDS * 3
    np.testing.assert_array_equal(flat["heading"].values, grid_result["heading"])


def test_grid_csv_is_the_flat_view_with_coordinate_columns(grid_result, tmp_path):
    import pandas as pd

    frame = pd.read_csv(grid_result.to_csv(tmp_path / "grid.csv"))
    assert len(frame) == 12 * 201
    assert {"run", "time", "kp", "kd", "heading"} <= set(frame.columns)
    last = frame[frame.time == frame.time.max()].sort_values("run")
    assert last["kp"].tolist() == [1.0] * 4 + [2.0] * 4 + [3.0] * 4
    assert last["kd"].tolist() == KDS * 3


def test_grid_dimension_names_fall_back_to_the_key_path():
    batch = parse_scenario(_with('[batch.grid]\n"controller.params.kp" = [1.0, 2.0]\n'
                                 '"vessel.params.gain" = [0.1, 0.2, 0.3]\n'
                                 '"controller.reference.heading_deg" = [5.0]\n'
                                 '"vessel.initial.heading" = [0.0, 0.1]\n'))
    # "heading" is the name of a state variable and "heading_deg" of a summary metric (the
    # final heading in degrees, whose column it would overwrite): those dimensions keep their
    # full key paths
    assert batch.layout.dims == ("kp", "gain", "controller.reference.heading_deg",
                                 "vessel.initial.heading")
    assert batch.layout.shape == (2, 3, 1, 2)
    units = {a.name: a.units for a in batch.layout.axes}
    assert units == {"kp": "rad/rad", "gain": "1/s", "controller.reference.heading_deg": "deg",
                     "vessel.initial.heading": "rad"}
    clash = parse_scenario(_with('[batch.grid]\n"vessel.initial.heading_deg" = [5.0, 6.0]\n'
                                 '"controller.reference.heading_deg" = [1.0]\n'))
    assert clash.layout.dims == ("vessel.initial.heading_deg", "controller.reference.heading_deg")


def test_a_plain_scenario_has_one_run_dimension():
    batch = parse_scenario(_with())
    assert batch.layout.dims == ("run",) and batch.n_runs == 1


MC = ('[batch.monte_carlo]\nruns = 5\nseed = 11\n[batch.monte_carlo.draws]\n'
      '"vessel.params.gain" = { distribution = "uniform", low = 0.1, high = 0.3 }\n'
      '"vessel.initial.heading_deg" = { distribution = "normal", mean = 0.0, std = 2.0 }\n')


def _documented_draws(seed, n):
    """The draws as documented: run i uses default_rng(SeedSequence(seed).spawn(n)[i])."""
    gains, headings = [], []
    for child in np.random.SeedSequence(seed).spawn(n):
        rng = np.random.default_rng(child)
        gains.append(rng.uniform(0.1, 0.3))
        headings.append(rng.normal(0.0, 2.0))
    return np.array(gains), np.array(headings)


def test_monte_carlo_has_a_sample_dimension_and_stores_the_draws(tmp_path):
    from seahelm.results import load_result

    result = run_scenario(parse_scenario(_with(MC), source="mc.toml"))
    ds = result.to_xarray()
    assert ds["heading"].dims == ("sample", "time")
    assert ds["sample"].values.tolist() == [0, 1, 2, 3, 4]
    gains, headings = _documented_draws(11, 5)
    assert ds["vessel.params.gain"].dims == ("sample",)
    np.testing.assert_array_equal(ds["vessel.params.gain"].values, gains)
    np.testing.assert_array_equal(ds["vessel.initial.heading_deg"].values, headings)
    assert ds["vessel.initial.heading_deg"].attrs["units"] == "deg"
    assert ds["vessel.params.gain"].attrs["distribution"] == "uniform"
    # the drawn values are what ran
    np.testing.assert_array_equal(ds["vessel.gain"].values, gains)
    np.testing.assert_allclose(ds["heading"].values[:, 0], np.radians(headings), rtol=1e-15)
    back = load_result(result.to_netcdf(tmp_path / "mc.nc"))
    assert back["heading"].dims == ("sample", "time")
    np.testing.assert_array_equal(back["vessel.params.gain"].values, gains)
    assert back["vessel.params.gain"].dims == ("sample",)


def test_grid_times_monte_carlo_is_grid_dims_then_sample():
    text = _with('[batch.grid]\n"controller.params.kp" = [1.0, 2.0]\n' + MC)
    batch = parse_scenario(text)
    assert batch.layout.dims == ("kp", "sample") and batch.layout.shape == (2, 5)
    gains, _ = _documented_draws(11, 10)
    draws = {v.name: v.values for v in batch.layout.values}
    np.testing.assert_array_equal(draws["vessel.params.gain"], gains)
    np.testing.assert_array_equal(batch.controller_params[:, 0], [1.0] * 5 + [2.0] * 5)


# -- one validator: the Problem; the key from the error's field, never from its words -------
@pytest.mark.parametrize(
    ("edit", "key", "field"),
    [
        (("t_final = 20.0", "t_final = 20.05"), "simulation.t_final", "t_final"),
        (('model = "pid-heading"', 'model = "pid-heading"\ndt = 0.25'), "controller.dt",
         "controller_dt"),
        (("dt = 0.1", "dt = 0.1\n[simulation.bounds]\nspeed = [0, 1]"), "simulation.bounds.speed",
         "bounds.speed"),
    ],
)
def test_the_problem_checks_once_and_the_scenario_names_the_key(edit, key, field):
    from seahelm.errors import ParameterError
    from seahelm.simulation.problem import Problem

    with pytest.raises(ScenarioError) as scenario:
        parse_scenario(_with(replace=edit), source="s.toml")
    cause = scenario.value.__cause__
    assert isinstance(cause, ParameterError) and cause.field == field
    assert str(scenario.value) == f"s.toml: [{key}] {cause.reason.lstrip(': ')}"
    # the same check from Python names the Problem's field
    good = parse_scenario(_with(), source="s.toml")
    kwargs = good.simulate_kwargs()
    with pytest.raises(ParameterError) as direct:
        Problem(**_changed(kwargs, field))
    assert direct.value.field == field


def _changed(kwargs, field):
    changes = {"t_final": {"t_final": 20.05}, "controller_dt": {"controller_dt": 0.25},
               "bounds.speed": {"bounds": {"speed": (0, 1)}}}[field]
    return {**kwargs, **changes}


def test_attribution_survives_reworded_messages(monkeypatch):
    # reword the problem's timing message: the scenario still names the key, from the field
    import seahelm.simulation.problem as problem
    from seahelm.errors import ParameterError

    def reworded(t_final, dt, what="t_final"):
        raise ParameterError("is not what I wanted at all", field=what)

    monkeypatch.setattr(problem, "steps", reworded)
    with pytest.raises(ScenarioError, match=r"^s.toml: \[simulation.t_final\] is not what I "
                                            r"wanted at all$"):
        parse_scenario(_with(), source="s.toml")


def test_miswiring_comes_from_the_problem_with_the_key():
    import dataclasses

    batch = parse_scenario(_with(), source="s.toml")
    two = dataclasses.replace(batch.controller, command_labels=("a", "b"))
    with pytest.raises(ParameterError, match=r"`controller`: model 'nomoto2', "
                                             r"actuator 'rudder-servo', controller 'pid-heading': "
                                             r"actuator channel 'rudder_command' gets no command; "
                                             r"the controller gives a, b") as err:
        batch.replace(controller=two)
    assert err.value.field == "controller"


def test_engine_error_about_a_run_names_its_grid_point():
    batch = parse_scenario(_with('[simulation.bounds]\nheading = [-1.0, 1.0]\n[batch.grid]\n'
                                 '"vessel.initial.heading" = [0.0, 2.0]\n'), source="s.toml")
    with pytest.raises(ScenarioError, match=r"s.toml: \[vessel.initial\] the initial state of run 1 "
                                            r".*\(run 1: \{'vessel.initial.heading': 2.0\}\)"):
        run_scenario(batch)


@pytest.mark.parametrize("ship", ["kvlcc2-l7", "mariner-nonlinear"])
def test_a_named_ship_runs_with_its_own_steering_gear(ship):
    """[vessel] ship: the actuator is the ship's steering gear (KVLCC2 L7: 15.8 deg/s, lag
    0.1 s; not the default servo's 2.33 deg/s), [actuator.params] override it, and a named
    [actuator] model replaces it."""
    from seahelm.ships import get_ship

    gear = get_ship(ship).steering_gear
    text = f'title = "t"\n[vessel]\nship = "{ship}"\n[simulation]\nt_final = 1.0\ndt = 0.1\n'
    batch = parse_scenario(text)
    assert batch.actuator is gear.actuator
    np.testing.assert_array_equal(batch.actuator_params[0], gear.params.to_array())
    over = parse_scenario(text + "[actuator.params]\nmax_rate_deg = 1.0\n")
    expected = gear.params.replace(max_rate=math.radians(1.0)).to_array()
    np.testing.assert_allclose(over.actuator_params[0], expected, rtol=1e-15)
    direct = parse_scenario(text + '[actuator]\nmodel = "direct"\n[controller]\nmodel = '
                            '"open-loop"\n') if ship == "mariner-nonlinear" else None
    assert direct is None or direct.actuator.name == "direct"
