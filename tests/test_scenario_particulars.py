"""``[vessel.particulars]``: a scenario's ship estimated from its main particulars, and one
estimated ship per Monte-Carlo sample of them (:mod:`seahelm.scenario.particulars`).

The references are built independently: :func:`~seahelm.ships.estimate.estimate_ship` of the
:class:`~seahelm.ships.estimate.Design` of the same particulars, and the manoeuvre of the ships
so rebuilt, run by the library.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from seahelm.analysis.maneuvers import maneuver_ship, turning_circle
from seahelm.errors import ValidityRangeWarning, strict_validity
from seahelm.scenario import ManeuverJob, ScenarioError, load_scenario, parse_scenario
from seahelm.ships.estimate import Design, estimate_ship

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "cargo_particulars_monte_carlo.toml"

CARGO = dict(length=120.0, beam=18.0, draft=7.0, block_coefficient=0.70, speed=6.5)
PARTICULARS = """[vessel.particulars]
name = "cargo-120"
length = 120.0
beam = 18.0
draft = 7.0
block_coefficient = 0.70
speed = 6.5
"""
TURNING = PARTICULARS + """[maneuver]
kind = "turning"
rudder_deg = 35
sides = "starboard"
t_final = 200.0
dt = 0.2
"""
MC = TURNING + """[batch.monte_carlo]
runs = 4
seed = 7
[batch.monte_carlo.draws]
"vessel.particulars.block_coefficient" = { distribution = "normal", mean = 0.70, std = 0.02 }
"vessel.particulars.draft" = { distribution = "uniform", low = 6.5, high = 7.5 }
"""
SIMULATION = PARTICULARS + """[controller]
model = "pid-heading-rps"
[controller.params]
kp = 2.0
kd = 20.0
propeller_rps = 1.93
[controller.reference]
heading_deg = 10.0
[vessel.initial]
surge_speed = 6.5
[simulation]
t_final = 10.0
dt = 0.1
"""


def _design(**changes):
    return Design(**{**CARGO, "name": "cargo-120", **changes})


def test_a_particulars_scenario_is_the_estimated_ship():
    job = parse_scenario(TURNING)
    ship = estimate_ship(_design())
    assert job.ship.params == ship.params
    assert job.ship.servo == ship.servo and job.ship.name == "cargo-120"
    assert job.ship.model is ship.model


def test_angles_in_degrees_and_the_steering_gear():
    job = parse_scenario(TURNING.replace("speed = 6.5\n", "speed = 6.5\nmax_rudder_deg = 40\n"
                                         "rudder_rate_deg = 3.0\n", 1))
    ship = estimate_ship(_design(max_rudder=math.radians(40), rudder_rate=math.radians(3.0)))
    assert job.ship.params == ship.params and job.ship.servo == ship.servo


@pytest.mark.parametrize("where", ["vessel", "particulars"])
def test_the_water_depth_in_either_place(where):
    text = (TURNING.replace("[vessel.particulars]\n", "[vessel]\nwater_depth = 12.0\n"
                            "[vessel.particulars]\n") if where == "vessel"
            else TURNING.replace("speed = 6.5\n", "speed = 6.5\nwater_depth = 12.0\n", 1))
    job = parse_scenario(text)
    ship = estimate_ship(_design(water_depth=12.0))
    assert ship.in_shallow_water
    assert job.ship.params == ship.params


def test_params_override_the_estimated_coefficients_in_deep_water():
    text = TURNING.replace("[maneuver]", "[vessel]\nwater_depth = 12.0\n[vessel.params]\n"
                           "N_r = -0.06\n[maneuver]")
    job = parse_scenario(text)
    expected = estimate_ship(_design(water_depth=12.0)).replace(params={"N_r": -0.06})
    assert job.ship.params == expected.params
    assert job.ship.params.N_r != -0.06  # corrected for the depth, as a ship file's [params]


def test_a_simulation_scenario_runs_the_estimated_ship():
    batch = parse_scenario(SIMULATION)
    np.testing.assert_array_equal(batch.params[0], estimate_ship(_design()).params.to_array())
    text = SIMULATION.replace("[controller]", "[vessel.params]\nY_v = -0.3\n[controller]")
    batch = parse_scenario(text)
    expected = estimate_ship(_design()).replace(params={"Y_v": -0.3}).params
    np.testing.assert_array_equal(batch.params[0], expected.to_array())


def _rebuilt(job, text_overrides=None):
    """The samples' ships rebuilt from their drawn particulars, by hand."""
    drawn = job.draws(np.arange(job.n_samples))
    ships = []
    for i in range(job.n_samples):
        values = {**CARGO, "name": "cargo-120"}
        values.update({k.rsplit(".", 1)[1]: float(v[i]) for k, v in drawn.items()
                       if k.startswith("vessel.particulars.")})
        ship = estimate_ship(Design.from_mapping(values))
        if text_overrides:
            ship = ship.replace(params=text_overrides)
        ships.append(maneuver_ship(ship, name=f"s{i}"))
    return ships


def test_each_sample_is_the_ship_of_its_drawn_particulars():
    job = parse_scenario(MC)
    assert isinstance(job, ManeuverJob) and job.n_samples == 4
    ships = job.ships()
    assert [s.name for s in ships] == [f"cargo-120 #{i}" for i in range(4)]
    for ship, ref in zip(ships, _rebuilt(job)):
        assert ship.params == ref.params and ship.servo == ref.servo
    assert len({s.params.Y_v for s in ships}) == 4  # the samples differ
    # any range of samples, alone, gives the same ships
    assert [s.params for s in job.ships(2, 4)] == [s.params for s in ships[2:]]


def test_the_batch_equals_the_rebuilt_ships_manoeuvre():
    job = parse_scenario(MC)
    result = job.run()
    ref = turning_circle(_rebuilt(job), math.radians(35.0), sides=1, t_final=200.0,
                         dt=0.2).metrics
    for name in ("advance", "transfer", "tactical_diameter", "time_90"):
        assert np.array_equal(result.metrics[name].values, ref[name].values,
                              equal_nan=True), name
    one = turning_circle(_rebuilt(job)[1], math.radians(35.0), sides=1, t_final=200.0,
                         dt=0.2).metrics  # a sample alone: as in the batch
    np.testing.assert_allclose(np.ravel(one["advance"].values),
                               np.ravel(result.metrics["advance"].values)[1], rtol=1e-9)


def test_drawn_params_and_fixed_overrides_apply_to_every_sample():
    text = MC.replace("[maneuver]", "[vessel.params]\nN_r = -0.06\n[actuator.params]\n"
                      "time_constant = 2.0\n[maneuver]").replace(
        '"vessel.particulars.draft"', '"vessel.params.Y_v" = { distribution = "normal", '
        'mean = -0.33, std = 0.01 }\n"vessel.particulars.draft"')
    job = parse_scenario(text)
    drawn = job.draws(np.arange(4))
    for i, (ship, ref) in enumerate(zip(job.ships(), _rebuilt(job, {"N_r": -0.06}))):
        assert ship.params.N_r == -0.06 and ship.servo.time_constant == 2.0
        assert ship.params.Y_v == drawn["vessel.params.Y_v"][i]
        assert ship.params.replace(Y_v=ref.params.Y_v) == ref.params


def test_the_sweep_stores_the_drawn_particulars(tmp_path):
    from seahelm.sweep import open_sweep, run_sweep

    (tmp_path / "mc.toml").write_text(MC)
    run_sweep(tmp_path / "mc.toml", tmp_path / "mc.zarr", chunk_size=3)
    ds = open_sweep(tmp_path / "mc.zarr").load()
    job = parse_scenario(MC)
    for key, values in job.draws(np.arange(4)).items():
        assert np.array_equal(ds[key].values, values)
        assert ds[key].attrs["kind"] == "batch_values" and ds[key].attrs["key"] == key
    assert ds["vessel.particulars.draft"].attrs["distribution"] == "uniform"
    assert ds["vessel.particulars.draft"].attrs["units"] == "m"
    assert ds["vessel.particulars.block_coefficient"].attrs["units"] == "-"
    ref = job.run().metrics
    assert np.array_equal(ds["tactical_diameter"].values,
                          np.ravel(ref["tactical_diameter"].values))


def test_the_example_with_a_few_samples(tmp_path):
    text = EXAMPLE.read_text().replace("runs = 100", "runs = 3")
    assert "runs = 3" in text
    job = parse_scenario(text)
    result = job.run()
    assert bool(result.metrics["complete"].all())
    td = np.ravel(result.metrics["tactical_diameter"].values) / 120.0
    assert np.all((2.0 < td) & (td < 3.5)), td  # a cargo ship's 35° circle: 2-3.5 L


# --------------------------------------------------------------------------------------------
# warnings: one per formula, for all the samples
# --------------------------------------------------------------------------------------------
SLENDER = MC.replace("beam = 18.0", "beam = 15.0").replace(
    '"vessel.particulars.draft" = { distribution = "uniform", low = 6.5, high = 7.5 }',
    '"vessel.particulars.beam" = { distribution = "uniform", low = 13.5, high = 16.0 }').replace(
    "runs = 4", "runs = 12")


def test_range_warnings_are_said_once_per_formula():
    job = parse_scenario(SLENDER)  # (the samples' warnings are said when they are made)
    beams = job.draws(np.arange(12))["vessel.particulars.beam"]
    slender = 120.0 / beams > 8.0
    assert 0 < slender.sum() < 12
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        job.ships()
    said = [str(w.message) for w in caught if issubclass(w.category, ValidityRangeWarning)]
    kijima = [m for m in said if m.startswith("Kijima et al. (1990) linear hull")]
    assert len(kijima) == 1, said
    assert len(said) == len({m.split(" used outside")[0] for m in said})  # one per formula
    lb = np.sort(120.0 / beams[slender])
    n = int(slender.sum())
    assert f"in {n} of 12 samples: L/B = {lb[0]:.4g}..{lb[-1]:.4g} outside 4..8" in kijima[0]


def test_one_sample_keeps_the_formulas_own_warning():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        parse_scenario(TURNING.replace("beam = 18.0", "beam = 14.0"))
    said = [str(w.message) for w in caught if issubclass(w.category, ValidityRangeWarning)]
    assert any("L/B = 8.571 outside 4..8" in m for m in said), said
    assert not any("samples" in m for m in said)


def test_strict_mode_turns_a_sample_out_of_range_into_an_error():
    match = r"sample 0: `vessel.particulars` .* used outside the range of its data: L/B = "
    with strict_validity(), pytest.raises(ScenarioError, match=match):
        parse_scenario(SLENDER).ships()


# --------------------------------------------------------------------------------------------
# bad input: each names its key
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("edit, match", [
    (("block_coefficient = 0.70", "blok_coefficient = 0.70"),
     r"\[vessel.particulars.blok_coefficient\] is not a particular \(did you mean "
     r"'block_coefficient'\?\)"),
    (("speed = 6.5\n", ""), r"\[vessel.particulars.speed\] misses required particular"),
    (("block_coefficient = 0.70", "block_coefficient = 1.2"),
     r"\[vessel.particulars.block_coefficient\] .*1\.2"),
    (("beam = 18.0", "beam = -18.0"), r"\[vessel.particulars.beam\] must be > 0 \[m\], got -18"),
    (("beam = 18.0", 'beam = "18"'), r"\[vessel.particulars.beam\] must be a number"),
    (("beam = 18.0", "beam = true"), r"\[vessel.particulars.beam\] must be a number"),
    (("speed = 6.5\n", "speed = 6.5\nmax_rudder_deg = 120\n"),
     r"\[vessel.particulars.max_rudder_deg\] must be at most 90° .*\(as written: "
     r"max_rudder_deg = 120 deg\)"),
    (("speed = 6.5\n", "speed = 6.5\nmax_rudder_deg = 35\nmax_rudder = 0.6\n"),
     r"\[vessel.particulars.max_rudder_deg\] give `max_rudder` or `max_rudder_deg`"),
    (("speed = 6.5\n", "speed = 6.5\nwater_depth = 6.0\n"),
     r"\[vessel.particulars.water_depth\] must be greater than the draft 7\.0 \[m\]"),
    (("[vessel.particulars]\n", "[vessel]\nwater_depth = 6.0\n[vessel.particulars]\n"),
     r"\[vessel.water_depth\] must be greater than the draft 7\.0 \[m\]"),
    (("[vessel.particulars]\n", "[vessel]\nwater_depth = 12.0\n[vessel.particulars]\n"
      "water_depth = 12.0\n"), r"\[vessel\] the water depth is given twice"),
    (("[vessel.particulars]\n", '[vessel]\nship = "kvlcc2-l7"\n[vessel.particulars]\n'),
     r"\[vessel\] give `ship` or \[vessel.particulars\], not both"),
    (("[vessel.particulars]\n", '[vessel]\nmodel = "mmg"\n[vessel.particulars]\n'),
     r"\[vessel\] give `model` or \[vessel.particulars\], not both"),
    (("block_coefficient = 0.70", "block_coefficient = 1.05"),
     r"\[vessel.particulars.block_coefficient\] must be in \(0.3, 1\)"),
    (("speed = 6.5\n", "speed = 6.5\nrudder_span = 1.0\n"),
     r"\[vessel.particulars.rudder_span\] must be at least the propeller diameter"),
])
def test_bad_particulars_name_their_key(edit, match):
    with warnings.catch_warnings(), pytest.raises(ScenarioError, match=match):
        warnings.simplefilter("ignore", ValidityRangeWarning)
        parse_scenario(TURNING.replace(*edit, 1))


@pytest.mark.parametrize("edit, match", [
    (('"vessel.particulars.draft"', '"vessel.particulars.drfat"'),
     r"\[batch.monte_carlo.vessel.particulars.drfat\] 'drfat' is not a particular \(did you "
     r"mean 'vessel.particulars.draft'\?\)"),
    (('std = 0.02', 'std = 0.3'),
     r"\[batch.monte_carlo\] sample \d+: `vessel.particulars.block_coefficient` .* \(its drawn "
     r"particulars: block_coefficient = "),
    (('low = 6.5, high = 7.5', 'low = -1.0, high = 0.0'),
     r"\[batch.monte_carlo\] sample 0: `vessel.particulars.draft` must be > 0 \[m\]"),
    (('"vessel.particulars.draft"', '"vessel.particulars.name"'),
     r"the ship's name is not drawn"),
    (('"vessel.particulars.draft" = { distribution = "uniform", low = 6.5, high = 7.5 }',
      '"vessel.particulars.water_depth" = { distribution = "uniform", low = 10, high = 12 }'
      '\n[vessel]\nwater_depth = 12.0'),
     r"\[batch.monte_carlo.vessel.particulars.water_depth\] the water depth is drawn here and "
     r"given in \[vessel\]"),
    (('"vessel.particulars.draft"', '"vessel.initial.draft"'), r"vessel.particulars.<name>"),
])
def test_bad_particulars_draws_name_their_key_and_sample(edit, match):
    text = MC.replace(*edit, 1)
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(text).ships()


def test_a_non_physical_sample_names_its_index_when_it_runs():
    text = MC.replace("runs = 4", "runs = 40").replace("std = 0.02", "std = 0.2")
    job = parse_scenario(text)  # (sample 0 is physical: checked when the scenario is read)
    drawn = job.draws(np.arange(40))["vessel.particulars.block_coefficient"]
    # C_b outside (0.3, 1) is not physical
    bad = int(np.flatnonzero((drawn >= 1.0) | (drawn <= 0.3))[0])
    assert bad > 0
    with pytest.raises(ScenarioError, match=rf"sample {bad}: `vessel.particulars"):
        job.run()


def test_particulars_drawn_without_particulars():
    text = MC.replace(PARTICULARS, '[vessel]\nship = "kvlcc2-l7"\n')
    with pytest.raises(ScenarioError, match=r"\[batch.monte_carlo.vessel.particulars."
                                            r"block_coefficient\] draws of the particulars "
                                            r"need .*\[vessel.particulars\]"):
        parse_scenario(text)


@pytest.mark.parametrize("batch", [
    '[batch.grid]\n"vessel.particulars.draft" = [6.5, 7.0]\n',
    '[batch.monte_carlo]\nruns = 2\nseed = 1\n[batch.monte_carlo.draws]\n'
    '"vessel.particulars.draft" = { distribution = "uniform", low = 6.5, high = 7.5 }\n',
])
def test_particulars_vary_only_in_a_maneuver_scenario(batch):
    kind = "grid" if "grid" in batch else "monte_carlo"
    with pytest.raises(ScenarioError, match=rf"\[batch.{kind}.vessel.particulars.draft\] the "
                                            r"particulars vary only in a \[maneuver\] scenario"):
        parse_scenario(SIMULATION + batch)


def test_the_cli_runs_a_particulars_scenario(tmp_path):
    from typer.testing import CliRunner

    from seahelm.cli import app

    scn = tmp_path / "cargo.toml"
    scn.write_text(TURNING)
    result = CliRunner().invoke(app, ["run", str(scn), "--no-plot", "--json"])
    assert result.exit_code == 0, result.output
    scn.write_text(TURNING.replace("beam = 18.0", "beam = 180.0"))
    result = CliRunner().invoke(app, ["run", str(scn), "--no-plot"])
    assert result.exit_code == 2
    assert "[vessel.particulars.beam]" in result.output


def test_load_scenario_reads_the_example():
    job = load_scenario(EXAMPLE)
    assert job.estimated is not None and job.n_samples == 100
    assert set(job.draws([0])) == {"vessel.particulars.block_coefficient",
                                   "vessel.particulars.draft"}
