"""Twin-thruster catamaran (Shushlyapin et al., 2017): constants, Jacobian, kinematics, errata."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.registry import get_controller, get_model
from seahelm.simulation.engine import simulate
from seahelm.vessels.base import NAV_OUTPUTS
from seahelm.ships import catalog
from seahelm.vessels.catamaran import (
    CATAMARAN,
    CATAMARAN_SERVO,
    CatamaranParams,
    CatamaranServoParams,
    consistent_params,
    drift,
    jacobian,
    paper_params,
    steady_turn,
)

VARIANTS = {
    "listing": paper_params(),
    "consistent": consistent_params(),
    "printed-sway": paper_params(sway_resistance=0.0),
    "printed-resistance": paper_params(resistance_speed_power=1.0),
}


def test_listing_constants_reproduce_eq_10_and_11():
    p = paper_params()
    # eq. (10): C_d = 0.148, A_Ls = 24.092 m² — only with the mean draft T_m = 1.55 m
    assert p.damping_coefficient == pytest.approx(0.148, abs=5e-4)
    assert p.lateral_area == pytest.approx(24.092, abs=1e-3)
    assert p.yaw_inertia == pytest.approx(0.05 / 1000 * 1.025 * 155000 * 22.3**2, rel=1e-12)
    assert p.surge_mass == pytest.approx(1.05 * 155000)
    assert p.sway_mass == pytest.approx(1.7 * 155000)
    assert p.yaw_moment_of_inertia == pytest.approx(1.6 * 3950.347, rel=1e-6)
    c = consistent_params()
    assert c.yaw_inertia == pytest.approx(155000 * (22.3 / 4) ** 2)
    assert c.yaw_inertia / p.yaw_inertia == pytest.approx(1219.5, rel=1e-3)


def test_catalog_and_registry_entries():
    assert catalog.get("shushlyapin2017-listing").params == paper_params()
    assert catalog.get("shushlyapin2017-consistent").params == consistent_params()
    assert catalog.get("shushlyapin2017-listing").model is CATAMARAN
    assert get_model("catamaran") is CATAMARAN
    assert get_model("catamaran-servo") is CATAMARAN_SERVO
    for name in ("fsm-yaw-rate", "fsm-yaw-rate-simple", "fsm-heading", "heading-rate-baseline",
                 "drift-thruster-baseline", "pid-yaw-rate", "fsm-yaw-rate-drive",
                 "fsm-yaw-rate-simple-drive", "fsm-heading-drive"):
        assert get_controller(name).name == name


def test_straight_run_speed_is_the_root_of_the_resistance_fit():
    # 2 T_v = 2000 R_K(V): 2.536 V² − 8.436 V + 8.1 − 20.4 = 0
    v_exact = (8.436 + math.sqrt(8.436**2 + 4 * 2.536 * 12.3)) / (2 * 2.536)
    p = paper_params()
    assert p.straight_speed() == pytest.approx(v_exact, rel=1e-9)
    res = simulate(CATAMARAN, p, np.zeros(7), t_final=200.0, dt=0.01, controller=OPEN_LOOP,
                   actuator=DIRECT, reference=[0.0], record_every=100)
    assert res["surge_speed"][0, -1] == pytest.approx(v_exact, rel=1e-6)
    assert res["north"][0, -1] > 0 and abs(res["east"][0, -1]) < 1e-9


@pytest.mark.parametrize("variant", list(VARIANTS))
def test_jacobian_matches_central_differences(variant):
    p = VARIANTS[variant]
    rng = np.random.default_rng(5)
    X = np.column_stack([
        rng.uniform(0.5, 5.0, 6), rng.uniform(-1.5, 1.5, 6), rng.uniform(-0.2, 0.2, 6),
        rng.uniform(-50, 50, 6), rng.uniform(-50, 50, 6), rng.uniform(-3, 3, 6),
        rng.uniform(-1.5, 1.5, 6),
    ])
    X[0, 0] = -2.0  # going astern: atan2 keeps the kinematics right
    Ja = jacobian(X, p)
    assert Ja.shape == (6, 7, 7)
    for i, x in enumerate(X):
        Jn = np.empty((7, 7))
        for j in range(7):
            h = 1e-6 * max(1.0, abs(x[j]))
            e = np.zeros(7)
            e[j] = h
            Jn[:, j] = (drift(x + e, p) - drift(x - e, p)) / (2 * h)
        scale = np.abs(Jn).max(axis=1, keepdims=True) + 1e-12
        np.testing.assert_allclose(Ja[i] / scale, Jn / scale, atol=1e-6)
    # W_37 of eq. (19) is ∂Φ_3/∂δ = L T_v cos δ / J_ω
    np.testing.assert_allclose(
        Ja[:, 2, 6], p.length * p.thrust * np.cos(X[:, 6]) / p.yaw_moment_of_inertia, rtol=1e-12
    )


def _rhs(model, x, u, p):
    # VesselModel.derivative cannot broadcast a model without disturbance channels
    # (reshape(-1, 0) in seahelm.vessels.base — reported); call the compiled rhs directly
    dx = np.empty(7)
    model.rhs(0.0, np.asarray(x, float), np.array([u], float), np.empty(0), p.to_record(), dx)
    return dx


def test_rhs_is_control_affine_and_outputs_follow_nav_convention():
    p = paper_params()
    x = np.array([4.0, 0.3, 0.02, 10.0, -5.0, 0.7, 0.4])
    dx = _rhs(CATAMARAN, x, 0.05, p)
    f = drift(x, p)
    np.testing.assert_allclose(dx[:6], f[:6])
    assert dx[6] == 0.05 and f[6] == 0.0
    # kinematics V cos(K − β), V sin(K − β) with β = atan2(V_y, V_x)
    V, beta = math.hypot(x[0], x[1]), math.atan2(x[1], x[0])
    assert dx[3] == pytest.approx(V * math.cos(x[5] - beta), rel=1e-12)
    assert dx[4] == pytest.approx(V * math.sin(x[5] - beta), rel=1e-12)
    # nav outputs: ẋ_N = U cos ψ − v sin ψ, ẏ_E = U sin ψ + v cos ψ with v = −V_y
    y = dict(zip(CATAMARAN.output_labels, CATAMARAN.outputs(0.0, x, [0.0], p)))
    north, east, psi, r, u, v = (y[k] for k in NAV_OUTPUTS)
    assert (north, east, psi, r, u) == (10.0, -5.0, 0.7, 0.02, 4.0)
    assert v == -0.3
    # and what else the model reports: speed V, drift angle β (port positive), thruster angle δ
    assert y["speed"] == pytest.approx(V, rel=1e-15)
    assert (y["drift_angle"], y["thruster_angle"]) == (beta, 0.4)
    assert dx[3] == pytest.approx(u * math.cos(psi) - v * math.sin(psi), rel=1e-12)
    assert dx[4] == pytest.approx(u * math.sin(psi) + v * math.cos(psi), rel=1e-12)


def test_at_rest_the_drift_angle_is_zero_and_finite():
    f = drift(np.zeros(7), paper_params())
    assert np.all(np.isfinite(f))
    # thrust 40.8 kN minus R_x = 2000 R_K(0) = 16.2 kN
    assert f[0] == pytest.approx((40800 - 16200) / (1.05 * 155000))
    assert np.all(np.isfinite(jacobian(np.zeros(7), paper_params())))


def test_printed_eq6_7_variant_multiplies_the_resistance_by_v():
    x = np.array([3.0, 0.4, 0.0, 0.0, 0.0, 0.0, 0.0])
    p0, p1 = paper_params(), paper_params(resistance_speed_power=1.0)
    V = math.hypot(3.0, 0.4)
    rk = 8.1 - 8.436 * V + 2.536 * V * V
    mx = p0.surge_mass
    assert drift(x, p0)[0] == pytest.approx((40800 - 2000 * rk * 3.0 / V) / mx)
    assert drift(x, p1)[0] == pytest.approx((40800 - 2000 * rk * 3.0) / mx)
    assert p1.straight_speed() == pytest.approx(3.1276, abs=1e-3)


def test_printed_sway_variant_omits_lateral_resistance():
    x = np.array([4.0, 0.5, 0.01, 0.0, 0.0, 0.0, 0.2])
    p1, p0 = paper_params(), paper_params(sway_resistance=0.0)
    V = math.hypot(4.0, 0.5)
    ry = 2000 * (8.1 - 8.436 * V + 2.536 * V * V) * 0.5 / V
    assert (drift(x, p0)[1] - drift(x, p1)[1]) * p1.sway_mass == pytest.approx(ry, rel=1e-9)


def test_listing_has_the_lightly_damped_fast_yaw_mode_the_consistent_set_not():
    # the paper's "strong oscillations" at constant δ: a 14.5 rad/s mode from the small J_zz
    x = np.array([paper_params().straight_speed(), 0, 0, 0, 0, 0, 0.0])
    ev = np.linalg.eigvals(jacobian(x, paper_params())[:3, :3])
    assert np.abs(ev.imag).max() == pytest.approx(14.5, abs=0.1)
    assert ev.real.max() < 0
    ev_c = np.linalg.eigvals(jacobian(x, consistent_params())[:3, :3])
    assert np.abs(ev_c.imag).max() < 0.5


def test_servo_variant_follows_eq_22():
    p = CatamaranServoParams(servo_time_constant=2.0, servo_gain=0.5)
    x = np.array([4.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1])
    dx = _rhs(CATAMARAN_SERVO, x, 0.6, p)
    assert dx[6] == pytest.approx((-0.1 + 0.5 * 0.6) / 2.0)
    np.testing.assert_allclose(dx[:6], drift(x, p)[:6])


@pytest.mark.parametrize(
    "field, value, match",
    [
        ("displacement", 0.0, "displacement"),
        ("displacement", -155000.0, "displacement"),
        ("thrust", 0.0, "thrust"),
        ("thrust", -1.0, r"thrust.*\[N\]"),
        ("length", 0.0, "length"),
        ("yaw_inertia", 0.0, "yaw_inertia"),
        ("block_coefficient", 1.5, "block_coefficient"),
        ("sway_resistance", 2.0, "sway_resistance"),
        ("resistance_c2", 0.0, "resistance_c2"),
        ("k22", -0.1, "k22"),
    ],
)
def test_bad_parameters_raise(field, value, match):
    with pytest.raises(ParameterError, match=match):
        CatamaranParams(**{field: value})


def test_bad_state_shape_raises():
    with pytest.raises(ParameterError, match="7 catamaran states"):
        jacobian(np.zeros(6), paper_params())


def test_why_the_printed_variants_fail_to_reproduce_the_paper():
    # listing (with −R_y, no extra V): ω = 0.08 rad/s at δ = 86.2°, circle 96.9 m (paper 85°, 95 m)
    vx, vy, d = steady_turn(paper_params(), 0.08)
    assert math.degrees(d) == pytest.approx(86.24, abs=0.01)
    assert 2 * math.hypot(vx, vy) / 0.08 == pytest.approx(96.94, abs=0.01)
    # printed sway equation: the turn saturates near 0.071 rad/s, 0.08 is unreachable
    with pytest.raises(ParameterError, match="steady turn"):
        steady_turn(paper_params(sway_resistance=0.0), 0.08)
    _, _, d70 = steady_turn(paper_params(sway_resistance=0.0), 0.070)
    assert math.degrees(d70) > 75.0
    # printed eq. (6)-(7): 0.08 rad/s already at δ ≈ 45°, not 85°
    _, _, d1 = steady_turn(paper_params(resistance_speed_power=1.0), 0.08)
    assert math.degrees(d1) == pytest.approx(44.8, abs=0.5)


def test_plot_overview_draws_the_papers_three_panels():
    import matplotlib.pyplot as plt

    from seahelm.control.final_state import FSM_YAW_RATE_SIMPLE, yaw_rate_params
    from seahelm.plotting.catamaran import plot_overview, plot_yaw_rate

    res = simulate(CATAMARAN, paper_params(), np.zeros(7), t_final=5.0, dt=0.001,
                   controller=FSM_YAW_RATE_SIMPLE,
                   controller_params=yaw_rate_params(time_constant=1.0, step=0.01),
                   actuator=DIRECT, reference=[0.01], record_every=100)
    fig = plot_overview(res)
    assert len(fig.axes) == 3
    ax = plot_yaw_rate(res)
    assert len(ax.lines) == 2  # yaw rate and its reference
    plt.close("all")


# ----------------------------------------------------------------------------------------
# an independent, hand-typed copy of the MathCAD listing (Table 1 of the paper) with the
# errata's Tm = 1.55 m, the listing's R_x and the lateral resistance in the sway equation
# ----------------------------------------------------------------------------------------
def _listing_rhs(z):
    import math as m

    D, L, Tv, Tm, s, rov = 155000.0, 22.3, 20400.0, 1.55, 0.697, 1.025
    mx, my, jw = 1.05 * D, 1.7 * D, 1.6 * (0.05 / 1000 * rov * D * L**2)
    vx, vy, w, _x, _y, k, d = z
    v, b = m.hypot(vx, vy), m.atan2(vy, vx)
    rk = 8.1 - 8.436 * v + 2.536 * v * v
    rx, ry = 2000 * rk * m.cos(b), 2000 * rk * m.sin(b)
    cd = (0.739 + 8.7 * Tm / L) * (1.611 * s * s - 2.873 * s + 1.33)
    mk = 0.4 * L * (0.5 - b / 3.14) * ry
    md = -cd * v * rov / 2 * (L * Tm * s) * L**2 * w
    return np.array([(2 * Tv * m.cos(d) - rx - my * w * vy) / mx,
                     (2 * Tv * m.sin(d) - ry - mx * w * vx) / my,
                     (L * Tv * m.sin(d) + mk + md - vx * vy * (mx - my)) / jw,
                     v * m.cos(k - b), v * m.sin(k - b), w, 0.0])


def test_drift_equals_the_hand_typed_listing_at_random_states():
    from seahelm.vessels.catamaran import drift, paper_params

    rng = np.random.default_rng(2017)
    z = np.column_stack([rng.uniform(0.5, 6.0, 200), rng.uniform(-1.5, 1.5, 200),
                         rng.uniform(-0.2, 0.2, 200), rng.normal(0, 50, 200),
                         rng.normal(0, 50, 200), rng.uniform(-3, 3, 200),
                         rng.uniform(-1.4, 1.4, 200)])
    got = drift(z, paper_params())
    want = np.array([_listing_rhs(row) for row in z])
    np.testing.assert_allclose(got, want, rtol=1e-11, atol=1e-12)


def test_steady_turn_at_008_from_the_listing_matches_the_model_and_the_paper():
    """δ and the circle for ω = 0.08 rad/s solved on the independent listing copy."""
    from scipy.optimize import fsolve

    from seahelm.vessels.catamaran import paper_params, steady_turn

    def residual(q):
        vx, vy, d = q
        return _listing_rhs([vx, vy, 0.08, 0.0, 0.0, 0.0, d])[:3]

    vx, vy, d = fsolve(residual, [2.0, 0.5, 1.4], xtol=1e-13)
    diameter = 2 * math.hypot(vx, vy) / 0.08
    mvx, mvy, md = steady_turn(paper_params(), 0.08)
    assert md == pytest.approx(d, abs=1e-9)
    assert 2 * math.hypot(mvx, mvy) / 0.08 == pytest.approx(diameter, rel=1e-9)
    # the paper: thruster angle "near 85°", circle "about 95 m"
    assert 84.0 < math.degrees(d) < 88.0
    assert 90.0 < diameter < 100.0
