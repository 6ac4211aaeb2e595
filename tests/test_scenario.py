"""Scenario files: every validation branch names file, key path, value; batches; examples."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.scenario import ScenarioError, default_scenario_text, load_scenario, parse_scenario, run_scenario

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
    prepared = parse_scenario(default_scenario_text(), source="default")
    assert prepared.n_runs == 1
    assert prepared.reference[0, 0, 0] == pytest.approx(math.radians(20.0))
    assert prepared.actuator_params[0, 0] == pytest.approx(math.radians(35.0))


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (_with(replace=('model = "nomoto2"', 'model = "nomoto3"')),
         r"s.toml: \[vessel.model\] unknown vessel model 'nomoto3'; valid: .*nomoto1, nomoto2"),
        (_with(replace=('catalog = "mariner-nomoto2"', 'catalog = "titanic"')),
         r"\[vessel.catalog\] unknown catalog entry 'titanic'; valid: .*mariner-nomoto2"),
        (_with(replace=('catalog = "mariner-nomoto2"', 'catalog = "mariner-nomoto1"')),
         r"\[vessel.catalog\] 'mariner-nomoto1' is a parameter set for model 'nomoto1'"),
        (_with("[vessel.params]\ngain = -0.1\n"),
         r"\[vessel.params\] `gain` must be in \(0, inf\] \[1/s\], got -0.1"),
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
         r"\[simulation.t_final\] must be a whole multiple of simulation.dt = 0.1 s, got 20.05"),
        (_with(replace=("t_final = 20.0", "t_final = -5")),
         r"\[simulation.t_final\] Input should be greater than 0, got -5"),
        (_with(replace=("dt = 0.1", 'dt = "fast"')),
         r"\[simulation.dt\] Input should be a valid number.*got 'fast'"),
        (_with(replace=('model = "pid-heading"', 'model = "pid-heading"\ndt = 0.25'),),
         r"\[controller.dt\] must be a whole multiple of simulation.dt = 0.1 s, got 0.25"),
        (_with(replace=('model = "pid-heading"', 'model = "lqr"')),
         r"\[controller.model\] unknown controller 'lqr'; valid: .*pid-heading"),
        (_with("[actuator]\nmodel = \"jet\"\n"),
         r"\[actuator.model\] unknown actuator 'jet'; valid: direct, rudder-propeller, rudder-servo"),
        (_with("[environment.disturbance]\nwave = 1.0\n"),
         r"\[environment.disturbance.wave\] unknown channel 'wave'; valid: rudder_disturbance"),
        (_with("[simulation.bounds]\nspeed = [0, 1]\n"),
         r"\[simulation.bounds.speed\] unknown state; valid: north"),
        (_with("[batch.grid]\n\"vessel.colour\" = [1.0]\n"),
         r"\[batch.vessel.colour\] cannot vary 'vessel.colour'"),
        (_with("[batch.grid]\n\"vessel.params.gain\" = [0.1, -0.2]\n"),
         r"\[vessel.params\] `gain` must be in .* got -0.2 \(run 1: \{'vessel.params.gain': -0.2\}\)"),
        (_with("[batch.monte_carlo]\nruns = 3\nseed = 1\n[batch.monte_carlo.draws]\n"
               "\"vessel.params.gain\" = { distribution = \"normal\", mean = 0.2 }\n"),
         r"\[batch.monte_carlo.draws.vessel.params.gain\] Value error, a normal draw needs `mean` and `std`"),
        (_with("colour = \"red\"\n"), r"\[simulation.colour\] Extra inputs are not permitted, got .red."),
        ("[vessel\nmodel=1", r"s.toml: not valid TOML"),
        (_with(replace=("[simulation]\nt_final = 20.0\ndt = 0.1\n", "")),
         r"\[simulation\] Field required"),
    ],
)
def test_bad_scenarios_name_file_key_value_and_expectation(text, match):
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(text, source="s.toml")


def test_missing_file(tmp_path):
    with pytest.raises(ScenarioError, match="scenario file not found"):
        load_scenario(tmp_path / "none.toml")


def test_grid_is_a_cartesian_product():
    prepared = parse_scenario(_with('[batch.grid]\n"controller.params.kp" = [1.0, 2.0, 3.0]\n'
                                    '"vessel.initial.heading_deg" = [0.0, 5.0]\n'))
    assert prepared.n_runs == 6
    assert sorted(set(prepared.controller_params[:, 0])) == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(sorted(set(prepared.x0[:, 2])), [0.0, math.radians(5.0)])


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
    prepared = parse_scenario(_with(
        '[batch.grid]\n"controller.reference.heading_deg" = [5.0, 10.0]\n',
        replace=("heading_deg = 10.0", 'heading_deg = { kind = "step", time = 5.0, after = 1.0 }'),
    ))
    assert prepared.reference.shape == (2, 1, 1)  # the grid value replaces the signal
    np.testing.assert_allclose(prepared.reference[:, 0, 0], np.radians([5.0, 10.0]))


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.name)
def test_every_example_scenario_runs(path):
    prepared = load_scenario(path)
    result = run_scenario(prepared)
    assert result.ok.all(), result.messages()


SEA = ('[environment.disturbance]\nrudder_disturbance = {{ kind = "sea", h3 = {h3}, gain = 1.0, '
       'quantity = "{q}", seed = {seed} }}\n')


def test_sea_signal_has_the_spectrum_variance_and_a_realisation_per_run():
    from seahelm.environment.spectra import spectrum_from_wave_height

    text = _with(SEA.format(h3=3.0, q="ordinate", seed=5)
                 + "[batch.monte_carlo]\nruns = 3\nseed = 1\n",
                 replace=("t_final = 20.0\ndt = 0.1", "t_final = 20000.0\ndt = 1.0"))
    prepared = parse_scenario(text)
    dist = prepared.disturbance[:, :, 0]
    assert dist.shape == (3, 20001)
    assert not np.allclose(dist[0], dist[1])
    # D_r = 0.143 (h3/2)^2; the sample variance of a long record is within a few percent
    d_r = spectrum_from_wave_height("rakhmanin-firsov-2", 3.0).variance
    assert d_r == pytest.approx(0.143 * 1.5**2)
    np.testing.assert_allclose(dist.var(axis=1), d_r, rtol=0.1)
    again = parse_scenario(text)
    np.testing.assert_array_equal(again.disturbance, prepared.disturbance)


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
