"""Turning-circle metrics on analytic tracks (circles, with a straight lead-in)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.maneuvers.advance_transfer import heading_change_crossing, turning_metrics
from seahelm.errors import ParameterError

R, OMEGA = 50.0, 0.02  # radius [m], yaw rate [rad/s]


def circle(side=1.0, psi0=0.0, lead=0.0, speed=R * OMEGA, t_end=200.0, n=4001):
    """A straight lead-in of ``lead`` seconds, then a circle of radius R to ``side``."""
    t = np.linspace(0.0, t_end, n)
    tc = np.clip(t - lead, 0.0, None)
    straight = np.minimum(t, lead) * speed
    along = straight + R * np.sin(OMEGA * tc)
    across = side * R * (1 - np.cos(OMEGA * tc))
    north = along * math.cos(psi0) - across * math.sin(psi0)
    east = along * math.sin(psi0) + across * math.cos(psi0)
    return t, north, east, psi0 + side * OMEGA * tc


@pytest.mark.parametrize("side", [1.0, -1.0])
@pytest.mark.parametrize("psi0", [0.0, 1.0, -2.5])
def test_circle_from_the_order(side, psi0):
    t, n, e, psi = circle(side, psi0)
    m = turning_metrics(t, n, e, psi)
    assert m.advance[0] == pytest.approx(R, rel=1e-4)
    assert m.transfer[0] == pytest.approx(R, rel=1e-4)
    assert m.tactical_diameter[0] == pytest.approx(2 * R, rel=1e-4)
    assert m.time_90[0] == pytest.approx(0.5 * math.pi / OMEGA, rel=1e-9)
    assert m.time_180[0] == pytest.approx(math.pi / OMEGA, rel=1e-9)


def test_order_time_after_a_straight_lead_in():
    t, n, e, psi = circle(lead=20.0)
    m = turning_metrics(t, n, e, psi, order_time=20.0)
    assert m.advance[0] == pytest.approx(R, rel=1e-4)
    assert m.tactical_diameter[0] == pytest.approx(2 * R, rel=1e-4)
    assert m.time_90[0] == pytest.approx(20.0 + 0.5 * math.pi / OMEGA, rel=1e-9)
    # measured from t = 0 the lead-in adds to the advance, not to the tactical diameter
    m0 = turning_metrics(t, n, e, psi)
    assert m0.advance[0] == pytest.approx(R + 20.0 * R * OMEGA, rel=1e-4)
    assert m0.tactical_diameter[0] == pytest.approx(2 * R, rel=1e-4)


def test_batch_and_not_reached():
    t, n1, e1, p1 = circle(1.0)
    _, n2, e2, p2 = circle(-1.0)
    short = t <= 120.0  # 0.02 rad/s × 120 s = 137°: 180° never reached
    m = turning_metrics(t[short], np.stack([n1, n2])[:, short], np.stack([e1, e2])[:, short],
                        np.stack([p1, p2])[:, short])
    np.testing.assert_allclose(m.advance, [R, R], rtol=1e-4)
    assert np.all(np.isnan(m.tactical_diameter)) and np.all(np.isnan(m.time_180))


def test_crossing_interpolates_linearly():
    t = np.array([0.0, 1.0, 2.0])
    idx, w = heading_change_crossing(t, np.array([0.0, 1.0, 3.0]), 2.0)
    assert idx[0] == 2 and w[0] == pytest.approx(0.5)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: turning_metrics([0, 1, 2], [0, 1, 2], [0, 1], [0, 1, 2]),
         r"`north`, `east` and `heading` must have one shape"),
        (lambda: turning_metrics([0, 1, 2], [0, 1, 2], [0, 1, 2], [0, 1, 2], order_time=5.0),
         r"`order_time` must lie in the recorded interval \[0, 2\] \[s\], got 5.0"),
        (lambda: heading_change_crossing([0, 1], [0, 1], -1.0), r"`change` must be > 0 \[rad\]"),
        (lambda: heading_change_crossing([0, 1, 2], [0, 1], 1.0), r"`time` must be 1-D"),
    ],
)
def test_validation(call, match):
    with pytest.raises(ParameterError, match=match):
        call()
