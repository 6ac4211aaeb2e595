"""The cases issue 43 carried over from the campaign before ("still open from last round"),
rebuilt from the issue's words and tried through the CLI and the library: each is a correct
result or exit 2 with one line naming the key or option, its unit and value.

* Nomoto at zero speed: a Nomoto ship file with U = 0 passed ``ship check`` and every command
  then blamed ``--speed`` (not given); a scenario of a Nomoto ship at U = 0 ran with exit 0
  (K and T hold at U only; at rest the rudder turns nothing).
* Mixed-sign steady turns: ``identify steady-turn`` of turns to both sides with the default
  one-sided form (the paper's eq. (4)) fitted a ≈ 0, c ≈ 0 with exit 0.
* Guidance with a heading reference: ``[controller.reference] heading_deg`` beside a
  ``[guidance]`` route said "unknown channel 'heading_deg'; valid: (none)".
* A grid of waypoints (many, duplicate, zero-length legs, inside the acceptance radius, one
  point): already refused with the key; kept so by the last test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.identification.reduced.fitting import fit_steady_turns
from seahelm.ships import get_ship

from conftest import one_error

# the reduced steady-turn coefficients of examples/steady_turn_log.csv's fit (radian units)
A, B, C = -310.8, -5.573, 16.22


def _steady_points(yaw_rates):
    """Exact points of the odd form s(a ω² + c ω α) + b ω + α = 0, s = sign ω."""
    w = np.asarray(yaw_rates, dtype=float)
    s = np.sign(w)
    return w, -(s * A * w * w + B * w) / (1.0 + s * C * w)


# -- Nomoto at zero speed ------------------------------------------------------------------
@pytest.fixture(scope="module")
def nomoto_files(tmp_path_factory):
    where = tmp_path_factory.mktemp("nomoto")
    from seahelm.ships.writing import ship_to_toml

    text = ship_to_toml(get_ship("mariner-nomoto2"))
    lines = [("speed = 0.0" + line[line.index(" #"):] if line.startswith("speed = ") else line)
             for line in text.splitlines()]
    assert any(line.startswith("speed = 0.0") for line in lines)
    zero = where / "nomoto-u0.toml"
    zero.write_text("\n".join(lines) + "\n")
    return zero


@pytest.mark.parametrize("args", [["ship", "check"], ["ship", "show"], ["linearize"]])
def test_a_nomoto_ship_file_at_zero_speed_names_its_key(nomoto_files, args):
    line = one_error([*args, str(nomoto_files)])
    assert line.startswith(f"error: {nomoto_files}: `params.speed` must be in (0, inf] [m/s]"), \
        line
    assert line.endswith("got 0.0") and "--speed" not in line, line


def test_a_nomoto_scenario_at_zero_speed_is_refused(tmp_path):
    scenario = tmp_path / "u0.toml"
    scenario.write_text(
        'title = "u0"\n[vessel]\ncatalog = "mariner-nomoto2"\n[vessel.params]\nspeed = 0.0\n'
        '[controller]\nmodel = "pid-heading"\ndt = 0.5\n[controller.params]\nkp = 3.0\n'
        'ki = 0.0\nkd = 60.0\n[controller.reference]\nheading_deg = 20.0\n'
        '[simulation]\nt_final = 50.0\ndt = 0.1\n')
    line = one_error(["run", str(scenario)])
    assert line == (f"error: {scenario}: [vessel.params] `speed` must be in (0, inf] [m/s], "
                    "got 0.0"), line


def test_the_nomoto_parameters_refuse_zero_speed():
    from seahelm.vessels.nomoto import Nomoto1Params, Nomoto2Params

    with pytest.raises(ParameterError, match=r"`speed` must be in \(0, inf\] \[m/s\]"):
        Nomoto1Params(gain=0.1, time_constant=50.0, speed=0.0)
    with pytest.raises(ParameterError, match=r"`speed` must be in \(0, inf\] \[m/s\]"):
        Nomoto2Params(gain=0.1, t1=50.0, t2=5.0, t3=10.0, speed=0.0)
    assert Nomoto1Params(gain=0.1, time_constant=50.0, speed=1e-3).speed == 1e-3


def test_zero_speed_options_are_refused_by_name():
    assert one_error(["linearize", "mariner-nomoto2", "--speed", "0"]) == \
        "error: `--speed` must be > 0 [m/s], got 0.0"


# -- mixed-sign steady turns -------------------------------------------------------------
def test_turns_to_both_sides_need_an_odd_form(tmp_path):
    w, al = _steady_points([0.002, 0.004, 0.006, 0.008, -0.002, -0.004, -0.006, -0.008])
    with pytest.raises(ParameterError, match="turns are to both sides") as exc:
        fit_steady_turns(w, al, form="paper")
    assert exc.value.field == "form"
    fit = fit_steady_turns(w, al, form="paper-odd")
    assert fit.coef == pytest.approx((A, B, C), rel=1e-6)
    path = tmp_path / "mixed.csv"
    path.write_text("rudder_angle,yaw_rate\n" + "".join(
        f"{math.degrees(a):.9f},{math.degrees(r):.9f}\n" for a, r in zip(al, w)))
    line = one_error(["identify", "steady-turn", str(path)])
    assert line.startswith("error: `--form` 'paper' is the steady-turn equation of turns to one "
                           "side"), line
    assert "(4 with ω > 0, 4 with ω < 0): give form 'paper-odd'" in line, line


def test_turns_to_one_side_keep_the_paper_form():
    w, al = _steady_points([0.002, 0.004, 0.006, 0.008])
    assert fit_steady_turns(w, al, form="paper").coef == pytest.approx((A, B, C),
                                                                               rel=1e-6)
    # a small yaw rate of the other sign near zero rudder (an asymmetric ship) is one side
    w2, al2 = np.append(w, -0.0003), np.append(al, 0.0)
    fit_steady_turns(w2, al2, form="paper")


# -- guidance with a heading reference ------------------------------------------------------
ROUTE = ('title = "route"\n[vessel]\ncatalog = "mariner-nomoto2"\n[controller]\n'
         'model = "pid-heading"\ndt = 0.5\n[controller.params]\nkp = 3.0\nki = 0.0\nkd = 60.0\n'
         '{reference}[guidance]\nlaw = "los"\nwaypoints = {waypoints}\n'
         'acceptance_radius = {radius}\nlookahead = 800.0\n'
         '[simulation]\nt_final = 100.0\ndt = 0.1\n')


def _route(tmp_path, name, *, reference="", waypoints="[[0.0, 0.0], [0.0, 6000.0]]",
           radius=500.0):
    path = tmp_path / f"{name}.toml"
    path.write_text(ROUTE.format(reference=reference, waypoints=waypoints, radius=radius))
    return path


def test_a_route_with_a_heading_reference_is_refused(tmp_path):
    path = _route(tmp_path, "both", reference="[controller.reference]\nheading_deg = 20.0\n")
    line = one_error(["run", str(path)])
    assert line.startswith(f"error: {path}: [controller.reference.heading_deg] and [guidance] "
                           "both steer the ship: along a route the guidance law 'los' makes "
                           "the controller's reference"), line
    assert "drop [controller.reference] (and its [batch] keys), or [guidance]" in line
    assert "(none)" not in line


def test_a_route_with_a_heading_reference_in_the_batch_is_refused(tmp_path):
    # was, too: "[controller.reference.heading_deg] unknown channel 'heading_deg'; valid: (none)"
    path = _route(tmp_path, "grid-ref")
    path.write_text(path.read_text() + '[batch.grid]\n"controller.reference.heading_deg" = '
                                       '[10.0, 20.0]\n')
    line = one_error(["run", str(path)])
    assert line.startswith(f"error: {path}: [controller.reference.heading_deg] and [guidance] "
                           "both steer the ship"), line


@pytest.mark.parametrize("waypoints, radius, message", [
    ("[[0.0, 0.0]]", 500.0, "`waypoints`: a route needs 2 to 32 waypoints, got 1"),
    (str([[float(500 * i), 0.0] for i in range(40)]), 100.0,
     "`waypoints`: a route needs 2 to 32 waypoints, got 40"),
    ("[[0.0, 0.0], [0.0, 6000.0], [0.0, 6000.0]]", 500.0,
     "route: waypoints 1 and 2 are the same point (0, 6000) [m]"),
    ("[[0.0, 0.0], [0.0, 100.0], [100.0, 100.0]]", 500.0,
     "`acceptance_radius` must be shorter than the route's legs [m]: 500.0 >= the longest "
     "leg, 100 m"),
])
def test_a_grid_of_waypoints_is_refused_by_its_key(tmp_path, waypoints, radius, message):
    path = _route(tmp_path, "grid", waypoints=waypoints, radius=radius)
    line = one_error(["run", str(path)])
    assert line.startswith(f"error: {path}: [guidance] "), line
    assert message in line, line


# -- mixed-sign rudder angles in one manoeuvre batch ----------------------------------------
@pytest.mark.parametrize("call", [
    lambda f: f.turning_circle("kvlcc2-l7", np.radians([35.0, -35.0, 20.0]), sides=(1,)),
    lambda f: f.zigzag("kvlcc2-l7", np.radians([-20.0]), np.radians([20.0])),
    lambda f: f.pull_out("kvlcc2-l7", np.radians([20.0, -20.0])),
])
def test_a_negative_rudder_angle_in_a_manoeuvre_batch_is_refused(call):
    # was: run, the -35 deg turn to port labelled side = 1 (starboard) in the metrics, exit 0
    # through the library (the CLI and scenarios refuse it: "the side is `sides`")
    import seahelm.analysis.maneuvers as maneuvers

    with pytest.raises(ParameterError, match=r"must be > 0 \[rad\]: the side of the turn is "
                                             r"`sides`") as exc:
        call(maneuvers)
    assert exc.value.field == "rudder" and exc.value.value < 0
