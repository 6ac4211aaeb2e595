"""Shushlyapin et al. (2017): the printed ship variants are named objects, and they differ from
the listing where the errata say so.

Expected values are the paper's published numbers and the errata of the seeds guide, typed in
here, never values produced by the code under test.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from seahelm.errors import ParameterError
from seahelm.studies import shushlyapin2017 as sh
from seahelm.ships import catalog
from seahelm.vessels.catamaran import steady_turn

ROOT = Path(__file__).resolve().parents[1]


def test_variants_are_reachable_by_name():
    assert sh.get_ship_variant("listing") is sh.LISTING
    assert sh.get_ship_variant("consistent") is sh.CONSISTENT
    assert sh.get_ship_variant("printed-eq3") is sh.PRINTED_SWAY_EQ3
    assert sh.get_ship_variant("printed-eq6-7") is sh.PRINTED_RESISTANCE_EQ6_7
    assert sh.get_ship_variant(sh.CONSISTENT) is sh.CONSISTENT
    with pytest.raises(ParameterError, match="unknown catamaran variant 'nope'.*listing"):
        sh.get_ship_variant("nope")
    # the listing and the consistent set are the catalog's entries
    assert catalog.get("shushlyapin2017-listing").params == sh.LISTING
    assert catalog.get("shushlyapin2017-consistent").params == sh.CONSISTENT


def test_the_listing_reproduces_the_constants_of_eq_10():
    # errata: T_m = 1.55 m reproduces C_d = 0.148 and A_Ls = 24.092 m²
    assert sh.LISTING.damping_coefficient == pytest.approx(0.148, abs=5e-4)
    assert sh.LISTING.lateral_area == pytest.approx(24.092, abs=5e-4)


def test_printed_sway_equation_cannot_reach_0_08():
    # errata: with the sway equation as printed, ω* = 0.08 rad/s is unreachable
    assert sh.PRINTED_SWAY_EQ3.sway_resistance == 0.0 and sh.LISTING.sway_resistance == 1.0
    with pytest.raises(ParameterError, match="no steady turn"):
        steady_turn(sh.PRINTED_SWAY_EQ3, 0.08)
    with pytest.raises(ParameterError, match="no steady turn"):
        sh.steady_turn_comparison("printed-eq3")


def test_printed_resistance_differs_from_the_listing():
    # errata: eq. (6)-(7) carry an extra factor V that the listing does not
    assert sh.PRINTED_RESISTANCE_EQ6_7.resistance_speed_power == 1.0
    assert sh.LISTING.resistance_speed_power == 0.0
    assert sh.PRINTED_RESISTANCE_EQ6_7.straight_speed() < sh.LISTING.straight_speed()


def test_the_listing_inertia_is_about_1000_times_below_the_physical_one():
    # errata: J_zz = 0.05/1000 · 1.025 · D · L² is about 1000× below ≈ 4.8e6 kg·m²
    listing = 0.05 / 1000 * 1.025 * 155000.0 * 22.3**2
    assert sh.LISTING.yaw_inertia == pytest.approx(listing)
    assert sh.CONSISTENT.yaw_inertia == pytest.approx(4.8e6, rel=0.02)
    assert 500 < sh.CONSISTENT.yaw_inertia / sh.LISTING.yaw_inertia < 2000


def test_published_steady_turns():
    fast, slow = sh.steady_turn_comparison()
    # published: ω* = 0.08 rad/s with δ ≈ 85° and a turning circle of about 95 m
    assert (fast.yaw_rate, fast.published_thruster_angle, fast.published_diameter) == (
        0.08, 85.0, 95.0)
    assert fast.thruster_angle == pytest.approx(85.0, abs=3.0)
    assert fast.diameter == pytest.approx(95.0, abs=5.0)
    # published "steady δ = 0.6 rad" for ω* = 0.00072 rad/s: 0.6 degrees (errata)
    assert slow.thruster_angle == pytest.approx(0.6, abs=0.01)
    assert math.isnan(slow.published_diameter)


def test_published_results_name_existing_examples():
    assert len(sh.PUBLISHED) == 5
    for row in sh.PUBLISHED:
        assert (ROOT / row.reproduced_by).is_file(), row
