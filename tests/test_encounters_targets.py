"""Targets that avoid too: two identical ships on mirrored head-on courses, both running the
same avoidance method, give mirrored tracks (the second is the first turned by 180° about the
midpoint: both turn to starboard); the Monte-Carlo, the maritime-schema reader and
`seahelm encounter --targets-avoid` let the targets use the own ship's method."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.encounters import Encounter, Vessel
from seahelm.encounters.monte_carlo import monte_carlo_vessels

runner = CliRunner()

SHIP = "kvlcc2-full"


@pytest.mark.parametrize("method", ["rule-based", "velocity-obstacles"])
def test_mirrored_head_on_both_avoiding_give_mirrored_tracks(method):
    """A at (0, 0) heading north, B at (D, s) heading south (s: a small offset to A's
    starboard): the pair is symmetric under the half turn about (D/2, s/2), so B's track is
    A's turned: north_B = D - north_A, east_B = s - east_A, heading_B = heading_A + π."""
    D, s = 6000.0, 60.0
    a = Vessel(ship=SHIP, north=0.0, east=0.0, course=0.0, avoid=True)
    b = Vessel(ship=SHIP, north=D, east=s, course=math.pi, avoid=True)
    res = Encounter([a, b], t_final=900.0, avoidance=method, record_every=5).run()
    tr = res.tracks
    np.testing.assert_allclose(tr["north"][0, 1], D - tr["north"][0, 0], rtol=0, atol=1e-6)
    np.testing.assert_allclose(tr["east"][0, 1], s - tr["east"][0, 0], rtol=0, atol=1e-6)
    dpsi = np.angle(np.exp(1j * (tr["heading"][0, 1] - tr["heading"][0, 0] - math.pi)))
    np.testing.assert_allclose(dpsi, 0.0, rtol=0, atol=1e-9)
    # both avoided (a turn to starboard: heading increases for A), and both count as acting
    assert np.nanmax(tr["heading"][0, 0]) > math.radians(15)
    v = res.verdicts
    assert v["role"][0, 0].tolist() == [1, 1]  # head-on: both give way (Rule 14)
    assert v["acted"][0, 0].tolist() == [True, True]
    assert not res.collision[0, 0]


def test_the_target_keeps_course_unless_asked_to_avoid():
    kw = dict(own_ship=SHIP, target_ship=SHIP, seed=4, detection_range=(5000.0, 6000.0),
              tcpa=(200.0, 500.0))
    keep, _ = monte_carlo_vessels(3, **kw)
    both, geo = monte_carlo_vessels(3, targets_avoid=True, **kw)
    assert [v.avoid for v in keep] == [True, False]
    assert [v.avoid for v in both] == [True, True]
    assert np.array_equal(np.asarray(both[1].course), geo["course"])  # the same geometry


def test_cli_targets_avoid_makes_the_target_act(tmp_path):
    path = tmp_path / "headon.toml"
    path.write_text("""
[encounter]
t_final = 900.0
avoidance = "rule-based"

[[vessel]]
ship = "kvlcc2-full"
course_deg = 0.0
avoid = true

[[vessel]]
ship = "kvlcc2-full"
north = 6000.0
east = 60.0
course_deg = 180.0
""")
    out = {}
    for flag in ([], ["--targets-avoid"]):
        res = runner.invoke(app, ["encounter", str(path), "--json", "--out",
                                  str(tmp_path / f"o{len(flag)}"), *flag])
        assert res.exit_code == 0, res.output
        out[bool(flag)] = json.loads(res.output)["methods"]["rule-based"]
    import xarray as xr
    acted = {}
    for k in (0, 1):
        with xr.open_dataset(tmp_path / f"o{k}" / "encounters.nc") as ds:
            acted[k] = ds["verdict_acted"].values[0, 0].astype(bool).tolist()
            alter = ds["verdict_alteration"].values[0, 0]
        if k:
            assert alter[1] > math.radians(15)
        else:
            assert alter[1] < math.radians(1)
    assert acted == {0: [True, False], 1: [True, True]}
    # with both avoiding, the pair passes wider
    assert out[True][0]["min_range_median"] > out[False][0]["min_range_median"]
