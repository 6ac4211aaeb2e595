"""The 6-DOF rigid-body framework (seahelm.vessels.six_dof): physics and bad input.

Physics checks with independent references written here from the published equations
(Fossen 2021, ch. 2, 3): the Coriolis–centripetal matrix is skew-symmetric and does no work,
the kinetic energy ½ νᵀ M ν of an unforced, undamped body is conserved, quaternion and Euler
kinematics agree where both are defined, and a loop through pitch 90° works with quaternions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.vessels.six_dof import rigid_body as rb
from seahelm.vessels.six_dof.otter import OTTER, OTTER_QUATERNION, otter_params
from seahelm.vessels.six_dof.params import SixDofParams


def skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def kirchhoff_matrix(M, nu):
    """C(ν) = [[0, −S(M₁₁ν₁ + M₁₂ν₂)], [−S(·), −S(M₂₁ν₁ + M₂₂ν₂)]] (Fossen 2021, Thm 3.2)."""
    M = 0.5 * (M + M.T)
    a1 = M[:3, :3] @ nu[:3] + M[:3, 3:] @ nu[3:]
    a2 = M[3:, :3] @ nu[:3] + M[3:, 3:] @ nu[3:]
    C = np.zeros((6, 6))
    C[:3, 3:] = -skew(a1)
    C[3:, :3] = -skew(a1)
    C[3:, 3:] = -skew(a2)
    return C


def random_spd(rng, n=6):
    a = rng.normal(size=(n, n))
    return a @ a.T + n * np.eye(n)


def compiled_matrix(M, nu):
    """C(ν) element by element from the compiled masked product (one element kept at a time)."""
    C = np.zeros((6, 6))
    for i in range(6):
        for j in range(6):
            mask = np.zeros(36)
            mask[6 * i + j] = 1.0
            C[i, j] = rb.masked_coriolis_times_velocity(M.ravel(), mask, *nu)[i] / nu[j]
    return C


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_coriolis_matrix_is_skew_symmetric_and_matches_kirchhoff(seed):
    rng = np.random.default_rng(seed)
    M, nu = random_spd(rng), rng.normal(size=6)
    C = compiled_matrix(M, nu)
    np.testing.assert_allclose(C, kirchhoff_matrix(M, nu), atol=1e-12)
    np.testing.assert_allclose(C + C.T, 0.0, atol=1e-12)
    cnu = np.array(rb.coriolis_times_velocity(M.ravel(), *nu))
    np.testing.assert_allclose(cnu, kirchhoff_matrix(M, nu) @ nu, atol=1e-12)
    assert abs(nu @ cnu) < 1e-10 * np.abs(cnu).max()  # no work


def test_rigid_body_coriolis_equals_kirchhoff_of_m_rb():
    rng = np.random.default_rng(5)
    m, rg, nu = 80.0, np.array([0.15, -0.02, -0.25]), rng.normal(size=6)
    ig = random_spd(rng, 3)
    mrb = rb.rigid_body_mass_matrix(m, rg, ig)
    # M_RB written out from §3.3 as an independent check of the H-transformation
    want = np.block([[m * np.eye(3), -m * skew(rg)], [m * skew(rg), ig - m * skew(rg) @ skew(rg)]])
    np.testing.assert_allclose(mrb, want, atol=1e-12)
    got = rb.rigid_body_coriolis(m, *rg, ig.ravel(), *nu)
    np.testing.assert_allclose(got, kirchhoff_matrix(mrb, nu) @ nu, atol=1e-10)
    np.testing.assert_allclose(rb.rigid_body_momentum(m, *rg, ig.ravel(), *nu), mrb @ nu,
                               atol=1e-12)


def test_block_solve_inverts_the_mass_matrix():
    rng = np.random.default_rng(3)
    M, b = random_spd(rng), rng.normal(size=6)
    A, B, C = M[:3, :3].ravel(), M[:3, 3:].ravel(), M[3:, 3:].ravel()
    np.testing.assert_allclose(rb.solve_blocks(tuple(A), tuple(B), tuple(C), *b),
                               np.linalg.solve(M, b), rtol=1e-12)


def free_body(**changes):
    """An unforced, undamped rigid body with added mass (no restoring, no actuators)."""
    rng = np.random.default_rng(7)
    ma = random_spd(rng) * 2.0
    base = dict(mass=50.0, center_of_gravity=(0.1, -0.05, 0.2),
                inertia_cg=(8.0, 0.3, -0.2, 0.3, 12.0, 0.1, -0.2, 0.1, 10.0),
                added_mass=tuple(ma.ravel()), thruster_count=0.0)
    base.update(changes)
    return SixDofParams(**base)


def rk4(f, x, dt, n):
    for _ in range(n):
        k1 = f(x)
        k2 = f(x + 0.5 * dt * k1)
        k3 = f(x + 0.5 * dt * k2)
        k4 = f(x + dt * k3)
        x = x + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


def energy(p, nu):
    M = p.mass_matrix
    return 0.5 * nu @ M @ nu


def generic_model(kinematics="euler"):
    from seahelm.vessels.six_dof.model import six_dof_model

    return six_dof_model("free-body", "test body", SixDofParams, thrusters=(),
                         kinematics=kinematics)


def test_energy_of_the_unforced_undamped_body_is_conserved():
    p = free_body()
    model = generic_model()
    x = model.initial_state(surge_speed=1.0, sway_speed=-0.4, heave_speed=0.3, roll_rate=0.5,
                            pitch_rate=-0.2, yaw_rate=0.4)
    e0 = energy(p, x[6:12])
    f = lambda s: model.derivative(0.0, s, np.zeros(0), p)  # noqa: E731
    x1 = rk4(f, x, 0.01, 2000)
    # the velocities change (the motion is not trivial) but the energy does not
    assert np.abs(x1[6:12] - x[6:12]).max() > 0.1
    assert energy(p, x1[6:12]) == pytest.approx(e0, rel=1e-8)


def test_the_model_helpers_compile_no_literal_index_signatures():
    """The 6-DOF helpers are called with constant indices: _sym and _row (27 + 6 literal
    pairs) inlined, the models' first actuator state and velocity indices (12 Euler, 13
    quaternion) typed int64 by numba locals, so none is compiled once per Literal[int] and
    _kinetics is compiled once for both model kinds (issue 47 item 7)."""
    from numba import njit
    from numba.core import types

    from seahelm.vessels.six_dof import model as six_dof_model

    p = otter_params()
    rec = p.to_record()
    u = np.array([90.0, 50.0])
    # fresh, uncached compilations (with the decorators' locals) type their calls again,
    # whatever is on disk
    for rhs, model in ((six_dof_model.six_dof_euler_rhs, OTTER),
                       (six_dof_model.six_dof_quaternion_rhs, OTTER_QUATERNION)):
        x = model.initial_state(surge_speed=1.0, sway_speed=0.2, yaw_rate=0.1)
        dx, ref = np.empty_like(x), np.empty_like(x)
        njit(locals=rhs.locals)(rhs.py_func)(0.0, x, u, np.zeros(model.n_disturbances), rec, dx)
        rhs(0.0, x, u, np.zeros(model.n_disturbances), rec, ref)
        assert np.array_equal(dx, ref)
    blocks = njit(six_dof_model._mass_blocks.py_func)(rec)
    assert blocks == six_dof_model._mass_blocks(rec)
    names = ("_sym", "_row", "_mass_blocks", "_kinetics", "_actuator_rates", "_common_outputs")
    literal = {name: [str(s) for s in getattr(six_dof_model, name).signatures] for name in names
               if any(isinstance(t, types.Literal)
                      for s in getattr(six_dof_model, name).signatures for t in s)}
    assert literal == {}
    assert len(six_dof_model._kinetics.signatures) == 1


def quaternion_state(model, x_euler):
    q = rb.quaternion_from_euler(*x_euler[3:6])
    return np.concatenate([x_euler[:3], q, x_euler[6:]])


def test_quaternion_and_euler_kinematics_agree():
    p = otter_params()
    x = OTTER.initial_state(surge_speed=1.5, sway_speed=0.2, roll=0.1, pitch=-0.05,
                            heading=0.3, yaw_rate=0.2, roll_rate=0.1,
                            propeller_port_speed=80.0, propeller_starboard_speed=60.0)
    u = np.array([90.0, 50.0])
    fe = lambda s: OTTER.derivative(0.0, s, u, p)  # noqa: E731
    fq = lambda s: OTTER_QUATERNION.derivative(0.0, s, u, p)  # noqa: E731
    xe = rk4(fe, x, 0.01, 1000)
    xq = rk4(fq, quaternion_state(OTTER_QUATERNION, x), 0.01, 1000)
    np.testing.assert_allclose(xq[:3], xe[:3], atol=1e-7)  # positions [m]
    np.testing.assert_allclose(rb.euler_from_quaternion(*xq[3:7]), xe[3:6], atol=1e-8)
    np.testing.assert_allclose(xq[7:], xe[6:], atol=1e-7)
    assert np.linalg.norm(xq[3:7]) == pytest.approx(1.0, abs=1e-6)


def test_a_loop_through_pitch_90_degrees_with_quaternions():
    # a body with diagonal inertia spinning about its y axis keeps ω = (0, q, 0): θ = q t
    p = SixDofParams(mass=10.0, inertia_cg=(1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 3.0))
    model = generic_model("quaternion")
    qrate = 0.5
    x = np.zeros(13)
    x[3] = 1.0
    x[11] = qrate  # pitch rate
    f = lambda s: model.derivative(0.0, s, np.zeros(0), p)  # noqa: E731
    quarter = math.pi / 2 / qrate
    x90 = rk4(f, x, quarter / 400, 400)
    # R(q) maps body x to NED −down (nose up): R e_x = (cos θ, 0, −sin θ) at θ = 90°
    R = np.array(rb.rotation_quaternion(*x90[3:7])).reshape(3, 3)
    np.testing.assert_allclose(R[:, 0], [0.0, 0.0, -1.0], atol=1e-6)
    # (θ = asin(−R₃₁) is ill-conditioned at 90°: 1e-7 in R is 4e-4 rad in θ)
    assert rb.euler_from_quaternion(*x90[3:7])[1] == pytest.approx(math.pi / 2, abs=1e-3)
    xfull = rk4(f, x, quarter / 400, 1600)  # the whole loop
    np.testing.assert_allclose(np.abs(xfull[3:7]), [1.0, 0.0, 0.0, 0.0], atol=1e-6)
    assert np.all(np.isfinite(xfull))
    # the Euler-angle kinematics are singular there
    assert abs(rb.euler_rates(0.0, math.pi / 2 - 1e-9, 0.0, 0.1, 0.1)[2]) > 1e6


def test_rotation_from_quaternion_equals_zyx_euler():
    rng = np.random.default_rng(11)
    for phi, theta, psi in rng.uniform(-1.4, 1.4, size=(5, 3)):
        q = rb.quaternion_from_euler(phi, theta, psi)
        np.testing.assert_allclose(rb.rotation_quaternion(*q), rb.rotation_euler(phi, theta, psi),
                                   atol=1e-14)
        np.testing.assert_allclose(rb.euler_from_quaternion(*q), (phi, theta, psi), atol=1e-12)


# -- bad input ------------------------------------------------------------------------------
def test_a_mass_matrix_that_is_not_positive_definite_is_refused():
    with pytest.raises(ParameterError, match="positive definite") as exc:
        otter_params(added_mass=tuple((-np.eye(6) * 1000.0).ravel()))
    assert exc.value.field == "added_mass"


def test_an_asymmetric_mass_matrix_is_refused():
    ma = np.zeros((6, 6))
    ma[0, 5] = 3.0
    with pytest.raises(ParameterError, match="symmetric"):
        otter_params(added_mass=tuple(ma.ravel()))


def test_a_thruster_outside_the_hull_is_refused():
    with pytest.raises(ParameterError, match=r"outside the hull: `thruster_y` = 0\.9 \[m\]") as e:
        otter_params(thruster_y=(-0.395, 0.9, 0.0, 0.0))
    assert e.value.field == "thruster_y[1]"


def test_a_thruster_with_zero_thrust_coefficient_is_refused():
    with pytest.raises(ParameterError, match=r"thruster 1: `thruster_k_pos`.*> 0 \[N·s²\]"):
        otter_params(thruster_k_pos=(0.0, 0.01108, 0.0, 0.0))


def test_a_layout_other_than_the_models_is_refused():
    with pytest.raises(ParameterError, match="OtterParams has 2 thrusters"):
        otter_params(thruster_count=1.0)


def test_stiffness_on_position_or_heading_is_refused():
    g = np.zeros((6, 6))
    g[5, 5] = 1.0
    with pytest.raises(ParameterError, match="depth, roll and pitch only"):
        otter_params(hydrostatic_stiffness=tuple(g.ravel()))
