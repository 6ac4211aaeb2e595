"""Short reprs for the REPL and an HTML table for Jupyter (issue 44, item 6).

A ``ManeuverResult`` printed 215 lines (19 kB) of arrays, a ``Ship`` its ``CPUDispatcher``
objects; results, ships and problems now say in at most 15 lines what they hold.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm._repr import describe, names, shorten, summary_html, summary_text
from seahelm.analysis.imo.check import ImoCriterion, ImoReport
from seahelm.ships import get_ship
from seahelm.simulation.problem import Problem

MAX_LINES = 15


def _check_short(text: str, *must: str) -> None:
    lines = text.splitlines()
    assert len(lines) <= MAX_LINES, text
    assert max(len(line) for line in lines) <= 130, text
    assert "CPUDispatcher" not in text and "array([" not in text and "<function" not in text, text
    for word in must:
        assert word in text, (word, text)


def test_helpers():
    assert shorten("a\n  b") == "a b"
    assert shorten("x" * 100, 10) == "x" * 9 + "…"
    assert names([]) == "—"
    assert names(["a", "b", "c"], 2) == "a, b (+1 more)"
    assert summary_text("T", [("ab", 1), ("c", "two")]) == "T\n  ab  1\n  c   two"
    page = summary_html("<T>", [("k", "a < b & c")])
    assert page.startswith("<table") and "&lt;T&gt;" in page and "a &lt; b &amp; c" in page
    assert describe(None) == "—" and describe(0.5) == "0.5"
    assert describe(np.zeros((4, 1, 1))) == "array (4, 1, 1)"
    assert describe({"rudder_command": 1.0, "propeller_rps": 2.0}) == \
        "rudder_command, propeller_rps"
    assert describe(lambda t: t) == "a function"


@pytest.mark.parametrize("name", ["kvlcc2-l7", "mariner-nomoto2", "son-nomoto-container"])
def test_ship_repr_is_short_and_says_what_it_holds(name):
    ship = get_ship(name)
    text = repr(ship)
    _check_short(text, f"Ship '{name}'", ship.model.name, "parameters", "water depth")
    assert text.splitlines()[0] == f"Ship '{name}': {ship.model.name} model"
    page = ship._repr_html_()
    assert page.startswith("<table") and name in page and "CPUDispatcher" not in page


def test_ship_repr_gives_the_steering_gear_in_degrees():
    text = repr(get_ship("kvlcc2-l7"))
    # the L7's gear: 35 deg, 15.8 deg/s (Yasukawa & Yoshimura 2015)
    assert "rudder-servo, ±35°, 15.8°/s" in text
    assert "L 7 m" in text and "deep" in text


def test_problem_repr():
    problem = Problem(ship="kvlcc2-l7", x0=np.zeros(6) + [1.179, 0, 0, 0, 0, 0],
                      t_final=20.0, dt=0.05,
                      reference={"rudder_command": math.radians(35.0), "propeller_rps": 10.0})
    text = repr(problem)
    _check_short(text, "Problem: mmg (kvlcc2-l7)", "t_final 20 s, dt 0.05 s (400 steps)",
                 "rudder_command, propeller_rps", "rudder-servo", "open-loop", "rk4")
    assert "<table" in problem._repr_html_()


def test_simresult_repr(mariner2):
    from seahelm.control.pid import PID_HEADING, PIDHeadingParams
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2

    result = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=60.0, dt=0.1,
                      controller=PID_HEADING, controller_params=PIDHeadingParams(),
                      controller_dt=0.5, reference=np.radians([10.0, 20.0]).reshape(-1, 1, 1))
    text = repr(result)
    _check_short(text, "SimResult: 2 run(s)", "601 samples", "t = 0 … 60 s", "2 ok, 0 diverged",
                 "heading", "controller pid-heading", "to_xarray()")
    assert "<table" in result._repr_html_()


@pytest.fixture(scope="module")
def turning():
    from seahelm.analysis.maneuvers import turning_circle

    return turning_circle("kvlcc2-l7", rudder=math.radians(35.0))


def test_maneuver_result_repr(turning):
    text = repr(turning)  # was 215 lines, 19 kB
    _check_short(text, "ManeuverResult: turning-circle of kvlcc2-l7", "side: 2",
                 "tactical_diameter", "2 of 2 run(s)")
    assert len(text) < 1500
    page = turning._repr_html_()
    assert page.startswith("<table") and "turning-circle" in page and len(page) < 3000


def test_imo_report_repr_says_the_verdict_first(turning):
    criteria = (
        ImoCriterion("turning", "advance", "starboard", 3.1, 4.5, 1.4, "L", "pass"),
        ImoCriterion("turning", "advance", "port", 3.2, 4.5, 1.3, "L", "pass"),
        ImoCriterion("10/10 zig-zag", "first overshoot", "starboard", math.radians(12.0),
                     math.radians(10.0), math.radians(-2.0), "rad", "fail"),
        ImoCriterion("stopping", "track reach (full astern)", "-", math.nan, 15.0, math.nan,
                     "L", "not evaluated", "no propeller"),
    )
    report = ImoReport(ship="demo-ship", length=100.0, speed=5.0, L_over_V=20.0,
                       criteria=criteria, notes=("a note",), turning=turning, zigzag=turning)
    text = repr(report)
    _check_short(text)
    lines = text.splitlines()
    assert lines[0] == "ImoReport: demo-ship, FAILED (2 pass, 1 fail, 1 not evaluated)"
    assert "starboard 3.1 L pass; port 3.2 L pass (limit 4.5 L)" in text
    assert "starboard 12° fail (limit 10°)" in text  # angles in degrees
    assert "stopping: track reach (full astern)" in text and "— not evaluated" in text
    assert "<table" in report._repr_html_()
