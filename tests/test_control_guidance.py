"""Course setter of Lvov (2014), Fig. 1 block 1: great-circle course and course to steer."""

from __future__ import annotations

import math

import pytest

from seahelm.control import guidance as gd
from seahelm.errors import ParameterError


def test_great_circle_course_and_course_to_steer():
    r = math.radians
    assert float(gd.initial_great_circle_course(0, 0, 0, r(10))) == pytest.approx(r(90))
    assert float(gd.initial_great_circle_course(0, 0, r(10), 0)) == pytest.approx(0.0)
    assert float(gd.initial_great_circle_course(r(10), 0, 0, 0)) == pytest.approx(r(180))
    # φ1 = 0, φ2 = 45°, Δλ = 90°: tan C = cos 45°/sin 45° = 1
    assert float(gd.initial_great_circle_course(0, 0, r(45), r(90))) == pytest.approx(r(45))
    assert float(gd.course_to_steer(r(10), r(2), r(1))) == pytest.approx(r(13))
    assert float(gd.course_to_steer(r(359), r(2))) == pytest.approx(r(1))
    with pytest.raises(ParameterError, match="lat_arrival"):
        gd.initial_great_circle_course(0, 0, 2.0, 0)
