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
