"""Monte-Carlo of encounter geometry (seahelm.encounters.monte_carlo): the drawn targets have
the drawn relative bearing, range, speed and CPA at detection (checked with straight-line
motion sampled in time, not with the sampler's formula); summary rates with Wilson intervals;
bad ranges name the key."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.encounters.monte_carlo import monte_carlo_vessels, sample_geometry
from seahelm.encounters.result import wilson_interval
from seahelm.errors import ParameterError


def test_drawn_geometry_has_the_drawn_bearing_range_and_cpa():
    u = 7.5
    g = sample_geometry(300, own_speed=u, detection_range=(5000.0, 9000.0), dcpa=(-900, 900),
                        target_speed=(3.0, 9.0), tcpa=(0.0, 3000.0), seed=11)
    assert np.hypot(g["north"], g["east"]) == pytest.approx(g["range"], rel=1e-12)
    bearing = np.arctan2(g["east"], g["north"]) % (2 * math.pi)
    assert np.allclose(bearing, g["bearing"], atol=1e-12)
    t = np.linspace(0.0, 4000.0, 400_001)  # 0.01 s
    for i in range(0, 300, 37):
        tn = g["north"][i] + g["target_speed"][i] * math.cos(g["course"][i]) * t - u * t
        te = g["east"][i] + g["target_speed"][i] * math.sin(g["course"][i]) * t
        d = np.hypot(tn, te)
        k = int(np.argmin(d))
        assert d[k] == pytest.approx(abs(g["dcpa"][i]), abs=1e-3)
        assert t[k] == pytest.approx(g["tcpa"][i], abs=0.02)
    assert (g["tcpa"] <= 3000.0).all()


def test_the_sign_of_dcpa_chooses_the_side():
    a = sample_geometry(50, own_speed=7.0, bearing=0.5, dcpa=500.0, seed=1)
    b = sample_geometry(50, own_speed=7.0, bearing=0.5, dcpa=-500.0, seed=1)
    assert not np.allclose(a["course"], b["course"])


def test_vessels_and_seed():
    v1, g1 = monte_carlo_vessels(20, own_ship="kvlcc2-full", target_ship="kvlcc2-full", seed=4)
    _, g2 = monte_carlo_vessels(20, own_ship="kvlcc2-full", target_ship="kvlcc2-full", seed=4)
    assert v1[0].avoid and not v1[1].avoid
    assert np.array_equal(g1["course"], g2["course"])


@pytest.mark.parametrize("kw, match", [
    ({"dcpa": (-20000.0, 0.0)}, "dcpa"), ({"detection_range": (-1.0, 5.0)}, "detection_range"),
    ({"target_speed": (5.0, 1.0)}, "target_speed"), ({"tcpa": (10.0, 5.0)}, "tcpa"),
    ({"target_speed": 0.5, "bearing": math.pi, "dcpa": 0.0}, "target_speed"),
])
def test_bad_ranges(kw, match):
    with pytest.raises(ParameterError, match=match):
        sample_geometry(10, own_speed=7.0, **kw)


def test_wilson_interval():
    # Wilson (1927): 0 of 10 -> (0, 0.2775); 5 of 10 -> (0.2366, 0.7634)
    lo, hi = wilson_interval(0, 10)
    assert lo == 0.0 and hi == pytest.approx(0.2775, abs=1e-4)
    lo, hi = wilson_interval(5, 10)
    assert (lo, hi) == pytest.approx((0.2366, 0.7634), abs=1e-4)


def test_overtaking_draws_give_every_situation_and_keep_the_drawn_cpa():
    """A share of overtaking draws: as many as asked, classified (by geometry, not by how they
    were drawn) as overtaking / overtaken, with the drawn CPA and TCPA by the closed form of
    the straight-line motion (own ship at its own speed of each draw); without the share the
    draws are those of before."""
    from seahelm.encounters.geometry import Situation, classify, cpa_tcpa, velocity

    u, n = 7.97, 400
    kw = dict(own_speed=u, detection_range=(6750.0, 9000.0), target_speed=(3.0, 8.0),
              tcpa=(120.0, 720.0), seed=51)
    g = sample_geometry(n, overtaking=0.25, overtaking_range=(1350.0, 3150.0), **kw)
    assert [(g["kind"] == k).sum() for k in (0, 1, 2)] == [300, 50, 50]
    own = np.zeros((n, 2))
    tgt = np.stack([g["north"], g["east"]], -1)
    sit = classify(own, np.zeros(n), tgt, g["course"])
    assert (sit[g["kind"] == 2] == Situation.OVERTAKEN).all()
    assert (sit[g["kind"] == 1] == Situation.OVERTAKING).mean() > 0.95
    assert set(np.unique(sit[g["kind"] == 0])) == {Situation.HEAD_ON, Situation.CROSSING_GIVE_WAY,
                                                   Situation.CROSSING_STAND_ON}
    assert (g["own_speed"][g["kind"] == 2] == round(u / 2, 2)).all()  # (half, 0.01 m/s)
    assert (g["target_speed"][g["kind"] == 2] > g["own_speed"][g["kind"] == 2]).all()
    assert (g["target_speed"][g["kind"] == 1] < u).all()
    d, t = cpa_tcpa(own, velocity(np.zeros(n), g["own_speed"]), tgt,
                    velocity(g["course"], g["target_speed"]))
    np.testing.assert_allclose(np.abs(d), np.abs(g["dcpa"]), rtol=0, atol=1e-6)
    np.testing.assert_allclose(t, g["tcpa"], rtol=1e-9)
    assert ((g["tcpa"] >= 120.0) & (g["tcpa"] <= 720.0)).all()
    # the default draw is unchanged by the option's existence
    a, b = sample_geometry(50, **kw), sample_geometry(50, overtaking=0.0, **kw)
    assert all(np.array_equal(a[k], b[k]) for k in a)
    assert (a["kind"] == 0).all()
    with pytest.raises(ParameterError, match="overtaking"):
        sample_geometry(5, overtaking=1.5, **kw)
    with pytest.raises(ParameterError, match="overtaking range"):
        sample_geometry(5, overtaking=0.5, overtaking_range=(500.0, 900.0), **kw)


def test_monte_carlo_command_has_overtaking_in_the_outcome_table():
    import json

    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, ["encounter", "--monte-carlo", "12", "--overtaking", "0.5",
                                   "--t-final", "600", "--detection", "4000", "--seed", "5",
                                   "--avoidance", "rule-based", "--json"])
    assert res.exit_code == 0, res.output
    rows = {r["situation"]: r for r in json.loads(res.output)["methods"]["rule-based"]}
    assert rows["overtaking"]["encounters"] + rows["overtaken"]["encounters"] >= 5
    assert rows["all"]["encounters"] == 12
    # own ship overtaking gives way (Rule 13) and acts; overtaken it stands on (Rule 17)
    assert rows["overtaking"]["own_acted"] is not None
    assert rows["overtaken"]["own_kept_course"] is not None
    res = CliRunner().invoke(app, ["encounter", "--monte-carlo", "3", "--overtaking", "2"])
    assert res.exit_code == 2 and "--overtaking" in res.output
    res = CliRunner().invoke(app, ["encounter", "--monte-carlo", "10", "--t-final", "100",
                                   "--detection", "1400"])  # (too short to be overtaken)
    assert res.exit_code == 2 and "--overtaking" in res.output and "--t-final" in res.output


def test_the_default_avoidance_is_the_one_the_help_names():
    """``--monte-carlo`` without ``--avoidance`` ran with no avoidance while the help said
    velocity obstacles; ``--avoidance none`` on situation files ran velocity obstacles."""
    import json

    from typer.testing import CliRunner

    from seahelm.cli.main import app

    args = ["encounter", "--monte-carlo", "4", "--overtaking", "0", "--t-final", "600",
            "--detection", "4000", "--seed", "5", "--json"]
    for extra, expected in (([], "velocity-obstacles"), (["--avoidance", "none"], "none")):
        res = CliRunner().invoke(app, [*args, *extra])
        assert res.exit_code == 0, res.output
        assert list(json.loads(res.output)["methods"]) == [expected]
