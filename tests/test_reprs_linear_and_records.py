"""Short reprs of a linear model (also at a kink) and of a measured record (issue 43, open
items of the campaign): a ``LinearModel`` at the KVLCC2's straight-run kink printed 22 kB (its
matrices, errors and both one-sided models), a ``ManoeuvreRecord`` its arrays."""

from __future__ import annotations

import numpy as np

from seahelm.analysis.equilibria.linearisation import linearize
from seahelm.identification.records import ManoeuvreRecord

MAX_LINES = 15


def _check_short(text, *must):
    lines = text.splitlines()
    assert len(lines) <= MAX_LINES and max(len(line) for line in lines) <= 130, text
    assert "array(" not in text and "0.00000" not in text, text
    for word in must:
        assert word in text, (word, text)


def test_a_linear_model_at_a_kink_has_a_short_repr():
    lin = linearize("kvlcc2-full", actuator=False)
    assert lin.kinks  # (the precondition: the straight run of the KVLCC2 is a kink)
    _check_short(repr(lin), "LinearModel", "kvlcc2-full", "kink", "sway_speed", ".sides",
                 "poles", "surge_speed [m/s]")
    for side in lin.sides:
        _check_short(repr(side), "LinearModel", side.side)
    page = lin._repr_html_()
    assert page.startswith("<table") and "array(" not in page and len(page) < 3000


def test_a_smooth_linear_model_names_its_point_and_poles():
    lin = linearize("mariner-nomoto2", actuator=False)
    text = repr(lin)
    _check_short(text, "mariner-nomoto2", "5 states", "rudder_angle [rad]", "U 7.718 m/s")
    assert "kink" not in text


def test_a_record_repr_shows_what_was_logged_not_the_arrays():
    t = np.arange(0.0, 200.0, 0.1)
    rec = ManoeuvreRecord(name="trial.csv", time=t, rudder_angle=np.zeros_like(t),
                          heading=np.zeros_like(t),
                          channels={"surge_speed": np.full_like(t, 7.0)},
                          columns={"time": "t [s]"})
    text = repr(rec)
    _check_short(text, "ManoeuvreRecord: trial.csv", "2000 samples", "every 0.1 s",
                 "rudder_angle, heading, surge_speed", "time = 't [s]'")
    assert len(text) < 500
    assert rec._repr_html_().startswith("<table")
