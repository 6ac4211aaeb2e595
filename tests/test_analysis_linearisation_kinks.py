"""Linearisation at a non-smooth point (issue 45, item 2): one-sided Jacobians, kink detection,
the two one-sided linear models; the KVLCC2's straight run, where γ_R switches with β_R."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.equilibria.linearisation import linearize, richardson_jacobian
from seahelm.numerics.nonsmooth import kinked_columns, one_sided_jacobians, side_jacobians
from seahelm.analysis.steering.indices import steering_indices
from seahelm.cli.main import app
from seahelm.ships import get_ship

runner = CliRunner()
A0 = np.array([[-1.0, 0.5, 0.2], [0.3, -2.0, 0.1], [0.0, 0.4, -0.7]])
G = np.array([0.8, -0.3, 0.0])      # the switch acts on rows 0 and 1
N = np.array([1.0, -2.0, 0.0])       # across the surface x0 - 2 x1 = 0
G2 = np.array([0.0, 0.0, 0.5])       # a second switch, on row 2, across x0 + x1 = 0
N2 = np.array([1.0, 1.0, 0.0])


def kinked(X):
    s = X @ N
    return X @ A0.T + np.outer(np.where(s > 0, 0.7, 0.2) * s, G)  # gamma-like switch


def test_a_smooth_function_has_no_kinks():
    def f(X):
        return np.stack([np.sin(X[:, 0]) * X[:, 1], X[:, 0] * np.abs(X[:, 1]) ** 3,
                         np.exp(X[:, 2])], axis=1)

    x0, h = np.array([0.3, 0.0, 0.1]), np.full(3, 1e-3)
    kink = kinked_columns(*one_sided_jacobians(f, x0, h), h, f=f, x0=x0)
    assert kink.columns == ()


def test_the_two_sides_of_a_switch_are_its_two_pieces():
    x0, h = np.zeros(3), np.full(3, 1e-3)
    sided = one_sided_jacobians(kinked, x0, h)
    kink = kinked_columns(*sided, h, f=kinked, x0=x0)
    assert kink.columns == (0, 1)
    J, E = richardson_jacobian(kinked, x0, h)
    np.testing.assert_allclose(J, A0 + 0.45 * np.outer(G, N), atol=1e-12)  # the mean
    (Jp, _), (Jm, _) = side_jacobians(*sided, J, E, kink)
    # side "+": x0 increasing, s = x0 - 2 x1 > 0 (gamma 0.7); side "-": gamma 0.2
    np.testing.assert_allclose(Jp, A0 + 0.7 * np.outer(G, N), atol=1e-9)
    np.testing.assert_allclose(Jm, A0 + 0.2 * np.outer(G, N), atol=1e-9)


def test_two_switches_on_their_own_rows():
    def f(X):
        return kinked(X) + np.outer(np.abs(X @ N2), G2)

    x0, h = np.zeros(3), np.full(3, 1e-3)
    sided = one_sided_jacobians(f, x0, h)
    kink = kinked_columns(*sided, h, f=f, x0=x0)
    assert kink.switches == 2
    J, E = richardson_jacobian(f, x0, h)
    (Jp, _), (Jm, _) = side_jacobians(*sided, J, E, kink)
    np.testing.assert_allclose(Jp, A0 + 0.7 * np.outer(G, N) + np.outer(G2, N2), atol=1e-9)
    np.testing.assert_allclose(Jm, A0 + 0.2 * np.outer(G, N) - np.outer(G2, N2), atol=1e-9)


def test_smooth_ships_are_unchanged():
    lin = linearize("mariner-nonlinear")
    assert lin.smooth and lin.sides == () and lin.note == ""
    assert linearize("kvlcc2-l7", rudder=np.radians(10.0), actuator=False).smooth


def _uniform_gamma(gamma):
    """The ship with one γ_R and no wake change with β_P (C_1 = 0): smooth, and at β = r = 0
    its sway and yaw rows are those of the γ_R piece (the wake's |β_P| acts on the surge row
    to first order, and its product with β_R would give the central difference an O(h)
    error)."""
    ship = get_ship("kvlcc2-l7")
    params = dataclasses.replace(ship.params, gamma_R_minus=gamma, gamma_R_plus=gamma, C_1=0.0)
    lin = linearize(dataclasses.replace(ship, params=params), actuator=False)
    assert lin.smooth
    return steering_indices(lin)


def test_kvlcc2_straight_run_sides_are_the_two_gamma_pieces(kvlcc2_l7_linear):
    assert kvlcc2_l7_linear.kinks == ("sway_speed", "yaw_rate") and "γ_R" in kvlcc2_l7_linear.note
    plus, minus = (steering_indices(s) for s in kvlcc2_l7_linear.sides)
    # beta = atan2(-v, u): more sway speed is beta_R < 0, gamma_R_minus = 0.395
    for side, gamma in ((plus, 0.395), (minus, 0.640)):
        ref = _uniform_gamma(gamma)  # the same ship with one gamma_R: that side's own model
        assert side.nomoto.t1 == pytest.approx(ref.nomoto.t1, rel=1e-6)
        assert side.nomoto.gain == pytest.approx(ref.nomoto.gain, rel=1e-6)
    assert plus.nomoto.t1 == pytest.approx(-82.0, abs=0.1) and not plus.course_stable
    assert minus.nomoto.t1 == pytest.approx(91.1, abs=0.1) and minus.course_stable


def test_cli_prints_both_sides_never_the_mean(kvlcc2_l7_linear):
    mean = steering_indices(kvlcc2_l7_linear)  # the central difference: T1 about -2400 s
    res = runner.invoke(app, ["linearize", "kvlcc2-l7"], terminal_width=200)
    assert res.exit_code == 0, res.output
    assert f"{mean.nomoto.t1:.5g}" not in res.stdout and f"{mean.nomoto.gain:.5g}" not in res.stdout
    assert "-82.032" in res.stdout and "91.066" in res.stdout and "γ_R switches" in res.stdout
    assert "course stable on side sway_speed −" in res.stdout
    data = json.loads(runner.invoke(app, ["linearize", "kvlcc2-l7", "--json"]).stdout)
    assert data["smooth"] is False and data["indices"] is None and data["linear_model"] is None
    assert data["kinks"] == ["sway_speed", "yaw_rate"] and "γ_R" in data["why"]
    t1 = [s["indices"]["T1_s"] for s in data["one_sided"]]
    assert t1 == pytest.approx([-82.03, 91.07], abs=0.01)
    assert len(data["course_stable_sides"]) == 1
    assert data["one_sided"][1]["linear_model"]["state_labels"][-1] == "rudder_angle"


def test_cli_smooth_json_has_no_new_keys():
    data = json.loads(runner.invoke(app, ["linearize", "mariner-nonlinear", "--json"]).stdout)
    assert set(data) == {"ship", "operating_point", "speed_mps", "length_m", "rudder_deg",
                         "indices", "linear_model", "max_error"}
    assert "roll_coupling" not in data["indices"]
