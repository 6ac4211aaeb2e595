"""Sweeps of a ``[maneuver]`` scenario: turning-circle metrics per Monte-Carlo sample of the
KVLCC2 L7's hull coefficients (the turning kernel the manoeuvre tests compile already).

The reference is the same manoeuvre run by the library on the same ships in one batch
(``turning_circle`` of the list of sampled ships), not values computed by the sweep.
"""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.analysis.maneuvers import maneuver_ship, turning_circle
from seahelm.scenario import ManeuverJob, ScenarioError, parse_scenario
from seahelm.sweep import open_sweep, run_sweep
from seahelm.ships import get_ship

TURNING = """
title = "KVLCC2 L7: turning under uncertain linear derivatives"
[vessel]
catalog = "kvlcc2-l7"
[maneuver]
kind = "turning"
rudder_deg = 35
sides = "both"
t_final = 30.0
[batch.monte_carlo]
runs = 5
seed = 3
[batch.monte_carlo.draws]
"vessel.params.Y_v" = { distribution = "normal", mean = -0.315, std = 0.0315 }
[[batch.monte_carlo.correlated]]
keys = ["vessel.params.N_v", "vessel.params.N_r"]
mean = [-0.137, -0.049]
covariance = [[1.9e-4, 1.0e-5], [1.0e-5, 2.4e-5]]
"""


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    base = tmp_path_factory.mktemp("turning")
    (base / "turning.toml").write_text(TURNING)
    report = run_sweep(base / "turning.toml", base / "turning.zarr", chunk_size=2)
    return report, open_sweep(base / "turning.zarr").load()


def test_the_sweep_equals_the_manoeuvre_of_the_sampled_ships(swept):
    report, ds = swept
    assert (report.n_runs, report.n_chunks) == (5, 3)
    assert dict(ds["advance"].sizes) == {"sample": 5, "side": 2}
    entry = get_ship("kvlcc2-l7")
    ships = []
    for i in range(5):  # the ships built by hand from the stored draws
        values = {k.rsplit(".", 1)[1]: float(ds[k].values[i])
                  for k in ("vessel.params.Y_v", "vessel.params.N_v", "vessel.params.N_r")}
        params = type(entry.params).from_mapping(values, base=entry.params)
        ships.append(maneuver_ship(params, servo=maneuver_ship("kvlcc2-l7").servo,
                                   model=maneuver_ship("kvlcc2-l7").model, name=f"s{i}"))
    ref = turning_circle(ships, np.radians(35.0), t_final=30.0).metrics
    for name in ("advance", "tactical_diameter", "transfer", "time_90"):
        assert np.array_equal(ds[name].values, ref[name].values, equal_nan=True), name
    assert len({float(v) for v in ds["advance"].sel(side=1).values}) == 5  # the ships differ


def test_the_draws_are_the_scenarios(swept):
    _, ds = swept
    job = parse_scenario(TURNING)
    assert isinstance(job, ManeuverJob) and job.n_samples == 5
    drawn = job.draws(np.arange(5))
    for key, values in drawn.items():
        assert np.array_equal(ds[key].values, values)
    assert ds.attrs["seed"] == 3 and ds.attrs["maneuver"] == "turning"


def test_summary_has_each_side_and_the_completion_count(swept):
    report, ds = swept
    rows = [r for r in report.summary["metrics"] if r["name"] == "advance"]
    assert [r["where"] for r in rows] == ["side=1", "side=-1"]
    assert rows[0]["mean"] == pytest.approx(float(ds["advance"].sel(side=1).mean()), rel=1e-12)
    assert report.summary["n_ok"] + report.summary["n_failed"] == 5


@pytest.mark.parametrize("edit, match", [
    (('"vessel.params.Y_v"', '"vessel.initial.u"'), "vary the ship's parameters"),
    (('"vessel.params.Y_v"', '"vessel.params.Y_q"'), "sample 0"),
    (('kind = "turning"', 'kind = "spiral"'), "not 'spiral'"),
])
def test_bad_manoeuvre_draws(edit, match):
    text = TURNING.replace(*edit)
    if "spiral" in text:
        text = text.replace('rudder_deg = 35\nsides = "both"\nt_final = 30.0\n', "")
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(text)


def test_a_grid_is_still_refused_in_a_manoeuvre():
    with pytest.raises(ScenarioError, match=r"takes no \[batch\] section"):
        parse_scenario(TURNING + '[batch.grid]\n"vessel.params.Y_v" = [-0.3, -0.31]\n')


@pytest.mark.parametrize("names, speeds", [
    (["kvlcc2-l7"], [0.5, 1.179]),
    (["kvlcc2-l7", "kvlcc2-full"], [1.179, 7.97]),
    (["mariner-nonlinear", "kvlcc2-l7"], [3.0, 7.0, 1.0]),
])
def test_the_usual_step_is_the_smallest_over_every_ship_and_speed(names, speeds):
    """Evaluated once per distinct ship (10⁴ sampled ships were 10⁸ evaluations)."""
    from seahelm.analysis.maneuvers.common import default_time_step, usual_time_step

    ships = [maneuver_ship(n) for n in names]
    every = min(default_time_step(s, u) for s in ships for u in speeds)
    assert usual_time_step(ships, speeds) == every
