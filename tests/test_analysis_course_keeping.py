"""Course-keeping metrics of recorded runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.maneuvers import course_keeping as ck


def test_heading_metrics_synthetic():
    dt = 0.1
    t = np.arange(0, 60 + dt / 2, dt)
    e = np.full_like(t, math.radians(0.5))
    rud = np.radians(5.0) * np.sin(2 * np.pi * t / 10.0)
    m = ck.heading_metrics(e, rud, dt=dt)
    assert float(m["mean_abs_error"]) == pytest.approx(math.radians(0.5))
    assert float(m["iae"]) == pytest.approx(math.radians(0.5) * 60.0)
    # the rudder first moves up; it turns at 2.5, 7.5, …, 57.5 s: 12 reversals in one minute
    assert float(m["reversals_per_min"]) == pytest.approx(12.0)
    assert float(m["settling_time"]) == 0.0
