"""Encounter geometry (seahelm.encounters.geometry): CPA/TCPA against the closed form written
here independently (the vertex of the squared range, a quadratic in time), relative bearings,
the COLREG situation on every sector boundary by hand-made cases, mirror symmetry, the Fujii
domain and bad thresholds."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.encounters.geometry import (ColregSectors, FujiiDomain, Situation, classify,
                                         cpa_tcpa, relative_bearing)
from seahelm.errors import ParameterError

S = Situation


def _quadratic_cpa(p_o, v_o, p_t, v_t):
    """|r + w t|^2 = a t^2 + b t + c; its minimum at t = -b / 2a is c - b^2 / 4a."""
    rn, re_ = p_t[0] - p_o[0], p_t[1] - p_o[1]
    wn, we = v_t[0] - v_o[0], v_t[1] - v_o[1]
    a = wn ** 2 + we ** 2
    b = 2.0 * (rn * wn + re_ * we)
    c = rn ** 2 + re_ ** 2
    t = -b / (2.0 * a)
    return math.sqrt(max(c - b * b / (4.0 * a), 0.0)), t


def test_cpa_tcpa_equals_the_closed_form_over_a_batch_and_time():
    rng = np.random.default_rng(51)
    n, m = 200, 7
    p_o = rng.uniform(-5e3, 5e3, (n, 1, 2))
    v_o = rng.uniform(-8, 8, (n, 1, 2))
    p_t = rng.uniform(-5e3, 5e3, (n, 1, 2))
    v_t = rng.uniform(-8, 8, (n, 1, 2))
    t = np.linspace(0.0, 600.0, m)[None, :, None]  # straight-line motion, sampled in time
    dcpa, tcpa = cpa_tcpa(p_o + v_o * t, v_o, p_t + v_t * t, v_t)
    assert dcpa.shape == tcpa.shape == (n, m)
    for i in range(n):
        d0, t0 = _quadratic_cpa(p_o[i, 0], v_o[i, 0], p_t[i, 0], v_t[i, 0])
        for k in range(m):
            tk = float(t[0, k, 0])
            assert tcpa[i, k] == pytest.approx(t0 - tk, rel=1e-9, abs=1e-9 * 600)
            assert dcpa[i, k] == pytest.approx(d0, rel=1e-9, abs=1e-9 * 5e3)


def test_cpa_of_a_head_on_pair_and_of_a_pair_at_equal_velocity():
    dcpa, tcpa = cpa_tcpa([0, 0], [5, 0], [1000, 30], [-5, 0])
    assert tcpa == pytest.approx(100.0, rel=1e-12) and dcpa == pytest.approx(30.0, rel=1e-12)
    dcpa, tcpa = cpa_tcpa([0, 0], [5, 1], [300, 400], [5, 1])
    assert tcpa == 0.0 and dcpa == pytest.approx(500.0)
    dcpa, tcpa = cpa_tcpa([0, 0], [5, 0], [-1000, 0], [-5, 0])  # opening: past
    assert tcpa < 0


def test_relative_bearing():
    assert relative_bearing([0, 0], 0.0, [0, 1000]) == pytest.approx(math.pi / 2)
    assert relative_bearing([0, 0], math.pi / 2, [0, 1000]) == 0.0
    assert relative_bearing([0, 0], 0.0, [0, -1000]) == pytest.approx(1.5 * math.pi)
    assert relative_bearing([0, 0], math.pi, [1000, 0]) == pytest.approx(math.pi)


def _case(beta_deg, alpha_deg, sectors=None):
    """Own ship at the origin heading north; the target at relative bearing β, heading so that
    the own ship is at relative bearing α from the target's bow."""
    beta, alpha = math.radians(beta_deg), math.radians(alpha_deg)
    p_t = [1000.0 * math.cos(beta), 1000.0 * math.sin(beta)]
    psi_t = beta + math.pi - alpha
    return int(classify([0.0, 0.0], 0.0, p_t, psi_t, sectors))


E = 1e-6  # [deg] either side of a boundary


@pytest.mark.parametrize("beta, alpha, expected", [
    (0.0, 0.0, S.HEAD_ON),                         # exactly ahead of each other
    (6.0 - E, 6.0 - E, S.HEAD_ON), (6.0 + E, 0.0, S.CROSSING_GIVE_WAY),
    (0.0, 6.0 + E, S.CROSSING_GIVE_WAY),            # own ahead of it, it not nearly ahead
    (354.0 + E, 354.0 + E, S.HEAD_ON), (354.0 - E, 0.0, S.CROSSING_STAND_ON),
    (3.0, 357.0, S.HEAD_ON),
    (90.0, 0.0, S.CROSSING_GIVE_WAY), (270.0, 0.0, S.CROSSING_STAND_ON),
    (112.5 - E, 0.0, S.CROSSING_GIVE_WAY), (112.5 + E, 0.0, S.OVERTAKEN),
    (247.5 + E, 0.0, S.CROSSING_STAND_ON), (247.5 - E, 0.0, S.OVERTAKEN),
    (0.0, 112.5 - E, S.CROSSING_GIVE_WAY), (0.0, 112.5 + E, S.OVERTAKING),
    (0.0, 247.5 + E, S.CROSSING_GIVE_WAY), (0.0, 247.5 - E, S.OVERTAKING),
    (350.0, 180.0, S.OVERTAKING), (180.0, 10.0, S.OVERTAKEN),
    (180.0, 180.0, S.NONE), (112.5 + E, 247.5 - E, S.NONE),
])
def test_situation_on_every_sector_boundary(beta, alpha, expected):
    assert _case(beta, alpha) == expected


def test_thresholds_are_configurable():
    wide = ColregSectors(head_on=math.radians(10.0), overtaking=math.radians(30.0))
    assert _case(8.0, 8.0) == S.CROSSING_GIVE_WAY and _case(8.0, 8.0, wide) == S.HEAD_ON
    assert _case(115.0, 0.0) == S.OVERTAKEN and _case(115.0, 0.0, wide) == S.CROSSING_GIVE_WAY
    assert _case(121.0, 0.0, wide) == S.OVERTAKEN


@pytest.mark.parametrize("kw, match", [
    ({"head_on": 0.0}, "head_on"), ({"head_on": math.radians(30)}, "head_on"),
    ({"overtaking": -0.1}, "overtaking"), ({"overtaking": math.pi / 2}, "overtaking"),
    ({"head_on": float("nan")}, "head_on"),
])
def test_bad_thresholds(kw, match):
    with pytest.raises(ParameterError, match=match) as err:
        ColregSectors(**kw)
    assert err.value.unit == "rad"


def test_mirror_symmetry_swaps_port_and_starboard():
    """Reflecting the geometry about the north axis (east -> -east, heading -> -heading) keeps
    head-on and overtaking and swaps give-way and stand-on in crossing."""
    rng = np.random.default_rng(7)
    n = 5000
    p_o, p_t = rng.uniform(-3e3, 3e3, (n, 2)), rng.uniform(-3e3, 3e3, (n, 2))
    h_o, h_t = rng.uniform(-np.pi, np.pi, n), rng.uniform(-np.pi, np.pi, n)
    flip = np.array([1.0, -1.0])
    a = classify(p_o, h_o, p_t, h_t)
    b = classify(p_o * flip, -h_o, p_t * flip, -h_t)
    swap = {S.CROSSING_GIVE_WAY: S.CROSSING_STAND_ON, S.CROSSING_STAND_ON: S.CROSSING_GIVE_WAY}
    expected = np.array([swap.get(S(v), S(v)) for v in a])
    np.testing.assert_array_equal(b, expected)
    assert set(np.unique(a)) == set(int(s) for s in S)  # every situation drawn


def test_fujii_domain():
    dom = FujiiDomain()
    L = 100.0
    # along the heading (north) the boundary is at 4 L, athwartships at 1.6 L
    assert dom.distance([0, 0], 0.0, L, [400.0, 0.0]) == pytest.approx(1.0)
    assert dom.distance([0, 0], 0.0, L, [0.0, -160.0]) == pytest.approx(1.0)
    assert dom.intruded([0, 0], 0.0, L, [0.0, 150.0])
    assert not dom.intruded([0, 0], 0.0, L, [0.0, 170.0])
    # heading east: the long axis turns with the ship
    assert dom.intruded([0, 0], math.pi / 2, L, [0.0, 390.0])
    assert not dom.intruded([0, 0], math.pi / 2, L, [390.0, 0.0])
    with pytest.raises(ParameterError, match="along"):
        FujiiDomain(along=0.0)
