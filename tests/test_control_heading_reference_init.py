"""The craft autopilots start their heading reference model in one place
(:func:`seahelm.control.heading_reference.heading_reference_init`)."""

from __future__ import annotations

import numpy as np

from seahelm.control import auv_depth_heading, thrust_heading
from seahelm.control.heading_reference import heading_reference_init


def test_heading_reference_init_starts_at_rest_on_the_heading():
    cs = np.full(5, 7.0)
    heading_reference_init(cs, 3, 1, 4, 0.25)
    np.testing.assert_array_equal(cs, [7.0, 0.0, 7.0, 0.25, 0.0])
    cs = np.full(3, 7.0)
    heading_reference_init.py_func(cs, 0, 1, 2, -1.5)
    np.testing.assert_array_equal(cs, [-1.5, 0.0, 0.0])


def test_both_craft_autopilots_use_it():
    for init in (thrust_heading.thrust_heading_init, auv_depth_heading.auv_depth_heading_init):
        names = init.py_func.__code__.co_names
        assert "heading_reference_init" in names and "desired_yaw_acceleration" in names
        assert names.count("desired_heading") == 1
