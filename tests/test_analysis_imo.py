"""IMO MSC.137(76) check (seahelm.analysis.imo): limits by hand, the check of KVLCC2 L7.

The runs use the MMG kernels of test_analysis_maneuvers (open loop, zigzag-rps).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.imo.check import (
    ImoReport,
    imo_check,
    imo_overshoot_limits,
)
from seahelm.analysis.maneuvers import maneuver_ship
from seahelm.errors import ParameterError
from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO

# (L/V [s], first, second [deg]) from the table of MSC.137(76), worked by hand:
# L/V < 10: 10, 25; 10 <= L/V < 30: 5 + L/V/2, 17.5 + 0.75 L/V; L/V >= 30: 20, 40
TABLE = [
    (5.0, 10.0, 25.0),
    (10.0, 10.0, 25.0),   # 5 + 5 = 10, 17.5 + 7.5 = 25
    (20.0, 15.0, 32.5),   # 5 + 10, 17.5 + 15
    (30.0, 20.0, 40.0),
    (40.0, 20.0, 40.0),
]


@pytest.mark.parametrize("lv, first, second", TABLE)
def test_overshoot_limits_against_the_table(lv, first, second):
    lim = imo_overshoot_limits(lv)
    assert lim.first == pytest.approx(math.radians(first), rel=1e-15)
    assert lim.second == pytest.approx(math.radians(second), rel=1e-15)


def test_overshoot_limits_are_continuous_and_vectorised():
    lv = np.array([9.999999, 10.0, 29.999999, 30.0])
    lim = imo_overshoot_limits(lv)
    np.testing.assert_allclose(np.degrees(lim.first), [10.0, 10.0, 20.0, 20.0], atol=1e-5)
    np.testing.assert_allclose(np.degrees(lim.second), [25.0, 25.0, 40.0, 40.0], atol=1e-5)
    # not the flat 25 deg of the second overshoot that a secondary source gives
    assert math.degrees(imo_overshoot_limits(20.0).second) == pytest.approx(32.5)


@pytest.mark.parametrize("bad", [0.0, -5.0, math.nan])
def test_overshoot_limits_validation(bad):
    with pytest.raises(ParameterError, match=r"`L_over_V` must be"):
        imo_overshoot_limits(bad)


def test_kvlcc2_l7_report(kvlcc2_l7_imo):
    r = kvlcc2_l7_imo
    assert isinstance(r, ImoReport)
    assert r.ship == "kvlcc2-l7" and r.length == 7.0 and r.speed == 1.179
    assert r.L_over_V == pytest.approx(7.0 / 1.179)
    keys = [(c.ability, c.criterion, c.side) for c in r.criteria]
    assert len(keys) == len(set(keys)) == 13
    by = {k: c for k, c in zip(keys, r.criteria)}
    # values are the manoeuvre metrics over L, limits the table's for L/V = 5.94 s
    tm = r.turning.metrics
    adv = by[("turning", "advance", "starboard")]
    assert adv.value == pytest.approx(float(tm["advance"].isel(rudder=0).sel(side=1)) / 7.0)
    assert adv.limit == 4.5 and adv.margin == pytest.approx(4.5 - adv.value)
    assert math.degrees(float(tm["rudder"][0])) == pytest.approx(35.0)
    assert math.degrees(float(tm["rudder"][1])) == pytest.approx(10.0)
    first = by[("10/10 zig-zag", "first overshoot", "port")]
    assert first.limit == pytest.approx(math.radians(10.0))
    assert first.value == pytest.approx(
        float(r.zigzag.metrics["overshoot"].isel(pair=0).sel(side=-1, n=1)))
    assert by[("10/10 zig-zag", "second overshoot", "starboard")].limit == pytest.approx(
        math.radians(25.0))
    assert by[("20/20 zig-zag", "first overshoot", "port")].limit == pytest.approx(
        math.radians(25.0))
    init = by[("initial turning", "distance to 10 deg heading change", "port")]
    assert init.limit == 2.5 and 1.0 < init.value < 2.5
    stop = by[("stopping", "track reach (full astern)", "-")]
    sm = r.stopping.metrics
    assert stop.status == "pass" and stop.value == pytest.approx(float(sm["track_reach"]) / 7.0)
    assert stop.limit == 15.0 and 5.0 < stop.value < 9.0
    assert float(sm["approach_speed_value"]) == 1.179
    assert any("the engine is an estimate" in note for note in r.notes)
    for c in r.criteria:
        assert c.status == ("pass" if c.margin >= 0 else "fail")
    assert r.passed
    assert any("100 m" in note for note in r.notes)
    data = r.to_dict()
    assert data["passed"] is True and len(data["criteria"]) == 13


def test_a_ship_with_a_small_rudder_fails():
    small = maneuver_ship(KVLCC2_L7.replace(rudder_area=0.4 * KVLCC2_L7.rudder_area),
                          servo=KVLCC2_L7_SERVO, name="kvlcc2-l7-small-rudder")
    r = imo_check(small)
    assert not r.passed
    status = {(c.ability, c.criterion, c.side): c.status for c in r.criteria}
    assert status[("initial turning", "distance to 10 deg heading change", "starboard")] == "fail"
    assert status[("10/10 zig-zag", "second overshoot", "starboard")] == "fail"
    failing = [c for c in r.criteria if c.status == "fail"]
    assert all(c.margin < 0 or math.isnan(c.value) for c in failing)


def test_imo_check_validation():
    with pytest.raises(ParameterError, match=r"must be scalars"):
        imo_check("kvlcc2-l7", speed=[1.0, 1.1])
    with pytest.raises(ParameterError, match=r"`approach_speed` must be > 0 \[m/s\]"):
        imo_check("kvlcc2-l7", speed=-1.0)


def test_a_ship_without_a_propeller_is_not_evaluated_for_stopping():
    r = imo_check("mariner-nonlinear")
    stop = r.criteria[-1]
    assert (stop.ability, stop.status) == ("stopping", "not evaluated")
    assert "no propeller input" in stop.note and r.stopping is None
