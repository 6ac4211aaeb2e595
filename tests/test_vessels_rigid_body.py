"""The 3-DOF rigid-body code written once (seahelm.vessels.rigid_body) and used by the models.

The functions are checked against the equations they solve (not against themselves), and the
models' derivatives against the rows as each model wrote them out before it called them: the
same floating-point operations in the same order, so the same numbers to the bit.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numba import njit

from seahelm.parameters import as_records, stack_params
from seahelm.vessels import container, mariner, mmg, mmg_four_quadrant, mmg_low_speed, nomoto
from seahelm.vessels.rigid_body import cramer_2x2, horizontal_velocity, midship_accelerations


@pytest.mark.parametrize("psi, expected", [(0.0, (2.0, 0.5)), (math.pi / 2, (-0.5, 2.0)),
                                           (math.pi, (-2.0, -0.5))])
def test_horizontal_velocity_rotates_the_body_velocity(psi, expected):
    north, east = horizontal_velocity(2.0, 0.5, psi, 0.0, 0.0)
    assert (north, east) == pytest.approx(expected, abs=1e-15)
    # a current is added over ground
    n2, e2 = horizontal_velocity(2.0, 0.5, psi, 0.3, -0.2)
    assert (n2 - north, e2 - east) == pytest.approx((0.3, -0.2), abs=1e-15)


def test_cramer_solves_an_asymmetric_system():
    # [[2, 1], [4, 3]] x = [3, 5]: x = (2, -1), determinant 2
    d1, d2, det = cramer_2x2(2.0, 1.0, 4.0, 3.0, 3.0, 5.0)
    assert det == 2.0 and (d1 / det, d2 / det) == (2.0, -1.0)


def test_midship_accelerations_satisfy_the_equations_of_motion():
    m, m_x, m_y, I_zG, J_z, x_G = 3.0e8, 6.0e6, 6.5e7, 1.9e12, 3.2e11, 11.2
    X, Y, N, u, v, r = 1.5e6, -2.0e6, 3.0e8, 7.5, -0.4, 0.004
    du, dv, dr = midship_accelerations(X, Y, N, u, v, r, m, m_x, m_y, I_zG, J_z, x_G)
    # Yasukawa & Yoshimura (2015), the motion equations about midship
    assert (m + m_x) * du - (m + m_y) * v * r - x_G * m * r * r == pytest.approx(X, rel=1e-12)
    assert (m + m_y) * dv + (m + m_x) * u * r + x_G * m * dr == pytest.approx(Y, rel=1e-12)
    assert ((I_zG + x_G ** 2 * m + J_z) * dr + x_G * m * (dv + u * r)
            == pytest.approx(N, rel=1e-12))


def _states(rng, n, nx, lo):
    x = np.zeros((n, nx))
    x[:, 0] = rng.uniform(lo, 8.0, n)
    x[:, 1] = rng.uniform(-2.0, 2.0, n)
    x[:, 2] = rng.uniform(-0.03, 0.03, n)
    x[:, 5] = rng.uniform(-7.0, 7.0, n)
    return x


@njit
def _mmg_forces(x, u, rec, out):  # the compiled force function the right-hand side calls
    for i in range(x.shape[0]):
        X_H, Y_H, N_H, X_P, X_R, Y_R, N_R, _T, _F, _w, _uR, _vR, _U, _b = mmg._forces(
            x[i, 0], x[i, 1], x[i, 2], u[i, 0], u[i, 1], rec[i])
        out[i, 0] = X_H + X_P + X_R
        out[i, 1] = Y_H + Y_R
        out[i, 2] = N_H + N_R


@njit
def _mmg4q_forces(x, u, rec, out):
    for i in range(x.shape[0]):
        (X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, _T, _Q, _F, _uR, _vR, _U, _b,
         _ba) = mmg_four_quadrant._forces4q(x[i, 0], x[i, 1], x[i, 2], u[i, 0], x[i, 6], rec[i])
        out[i, 0] = X_H + X_P + X_R
        out[i, 1] = Y_H + Y_R + Y_P
        out[i, 2] = N_H + N_R + N_P


def _forces_of(fn, x, u, p):
    rec = as_records(stack_params([p] * x.shape[0]), type(p))
    out = np.zeros((x.shape[0], 3))
    fn(x, u, rec, out)
    return out


def _mmg_rows_as_written(X, Y, N, uu, v, r, psi, cn, ce, p):
    """The rows of mmg_rhs before it called rigid_body (plain float64: the same rounding)."""
    L = p.length
    m = p.rho * p.displacement
    scale = 0.5 * p.rho * L * L * p.draft
    m_x = p.m_x * scale
    m_y = p.m_y * scale
    J_z = p.J_z * scale * L * L
    k = p.gyration_radius * L
    I_zG = m * k * k
    xg = p.x_G
    du = (X + (m + m_y) * v * r + xg * m * r * r) / (m + m_x)
    a11 = m + m_y
    a12 = xg * m
    a22 = I_zG + xg * xg * m + J_z
    b1 = Y - (m + m_x) * uu * r
    b2 = N - xg * m * uu * r
    det = a11 * a22 - a12 * a12
    c = math.cos(psi)
    s = math.sin(psi)
    return (du, (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det,
            uu * c - v * s + cn, uu * s + v * c + ce)


def test_mmg_derivative_equals_the_rows_as_written_bit_for_bit():
    rng = np.random.default_rng(5)
    n = 50
    x = _states(rng, n, 6, 0.3)
    u = np.column_stack([rng.uniform(-0.6, 0.6, n), rng.uniform(0.3, 2.0, n)])
    d = np.column_stack([rng.uniform(-1e6, 1e6, (n, 3)), rng.uniform(-1.0, 1.0, (n, 2))])
    p = mmg.KVLCC2_FULL
    got = mmg.MMG.derivative(0.0, x, u, p, d)
    f = _forces_of(_mmg_forces, x, u, p)
    for i in range(n):
        rows = _mmg_rows_as_written(f[i, 0] + d[i, 0], f[i, 1] + d[i, 1], f[i, 2] + d[i, 2],
                                    x[i, 0], x[i, 1], x[i, 2], x[i, 5], d[i, 3], d[i, 4], p)
        assert tuple(got[i, :5]) == rows


def test_four_quadrant_derivative_equals_the_rows_as_written_bit_for_bit():
    rng = np.random.default_rng(6)
    n = 50
    x = np.column_stack([_states(rng, n, 6, -3.0), rng.uniform(-1.5, 1.5, n),
                         rng.uniform(0.0, 100.0, n)])
    u = np.column_stack([rng.uniform(-0.6, 0.6, n), rng.uniform(-1.0, 1.0, n)])
    d = np.column_stack([rng.uniform(-1e6, 1e6, (n, 3)), rng.uniform(-1.0, 1.0, (n, 2))])
    p = mmg_four_quadrant.KVLCC2_FULL_4Q
    got = mmg_four_quadrant.MMG_4Q.derivative(0.0, x, u, p, d)
    f = _forces_of(_mmg4q_forces, x, u, p)
    for i in range(n):
        rows = _mmg_rows_as_written(f[i, 0] + d[i, 0], f[i, 1] + d[i, 1], f[i, 2] + d[i, 2],
                                    x[i, 0], x[i, 1], x[i, 2], x[i, 5], d[i, 3], d[i, 4], p)
        assert tuple(got[i, :5]) == rows


def test_mariner_rows_as_written_bit_for_bit():
    # every hydrodynamic coefficient 0 but the added masses: the forces are the external loads
    # alone, so the rows as written can be evaluated here
    base = mariner.MARINER_NONLINEAR
    keep = {"X_udot", "Y_vdot", "Y_rdot", "N_vdot", "N_rdot"}
    p = dataclasses.replace(base, **{f: 0.0 for f in base.field_names()
                                     if f[:2] in ("X_", "Y_", "N_") and f not in keep})
    rng = np.random.default_rng(7)
    n = 50
    x = _states(rng, n, 6, -2.0)
    d = np.column_stack([rng.uniform(-1e5, 1e5, (n, 3)), rng.uniform(-1.0, 1.0, (n, 2))])
    got = mariner.MARINER.derivative(0.0, x, rng.uniform(-0.4, 0.4, (n, 1)), p, d)
    L = p.length
    half_rho_l2 = 0.5 * p.rho * L * L
    m11 = p.mass - p.X_udot
    m22 = p.mass - p.Y_vdot
    m23 = p.mass * p.x_G - p.Y_rdot
    m32 = p.mass * p.x_G - p.N_vdot
    m33 = p.inertia - p.N_rdot
    det = m22 * m33 - m23 * m32
    for i in range(n):
        fx = d[i, 0] / half_rho_l2
        fy = d[i, 1] / half_rho_l2
        mz = d[i, 2] / (half_rho_l2 * L)
        surge = p.nominal_speed + x[i, 0]
        c, s = math.cos(x[i, 5]), math.sin(x[i, 5])
        assert tuple(got[i, :5]) == (fx / (m11 * L), (m33 * fy - m23 * mz) / (det * L),
                                     (-m32 * fy + m22 * mz) / (det * L * L),
                                     surge * c - x[i, 1] * s + d[i, 3],
                                     surge * s + x[i, 1] * c + d[i, 4])


def test_container_and_nomoto_kinematics_as_written_bit_for_bit():
    rng = np.random.default_rng(8)
    n = 50
    x = np.column_stack([_states(rng, n, 6, 0.5), rng.uniform(-0.1, 0.1, n),
                         rng.uniform(-0.5, 0.5, n)])
    u = np.column_stack([rng.uniform(-0.3, 0.3, n), rng.uniform(0.5, 3.0, n)])
    d = np.column_stack([np.zeros((n, 4)), rng.uniform(-1.0, 1.0, (n, 2))])
    assert container.CONTAINER.disturbance_labels[4:] == ("current_north", "current_east")
    got = container.CONTAINER.derivative(0.0, x, u, container.CONTAINER_SHIP, d)
    for i in range(n):
        c, s = math.cos(x[i, 5]), math.sin(x[i, 5])
        vc = x[i, 1] * math.cos(x[i, 7])
        assert (got[i, 3], got[i, 4]) == (x[i, 0] * c - vc * s + d[i, 4],
                                          x[i, 0] * s + vc * c + d[i, 5])
    for model, p in ((nomoto.NOMOTO1, nomoto.Nomoto1Params(gain=0.1, time_constant=20.0,
                                                             speed=7.0)),
                     (nomoto.NOMOTO2, nomoto.Nomoto2Params(gain=0.1, t1=20.0, t2=2.0, t3=5.0,
                                                             speed=7.0))):
        xn = np.zeros((n, model.n_states))
        xn[:, 2] = rng.uniform(-7.0, 7.0, n)
        assert model.disturbance_labels[1:4] == ("sway_velocity", "current_north",
                                                 "current_east")
        dn = np.column_stack([np.zeros(n), rng.uniform(-1.0, 1.0, (n, 3))])
        got = model.derivative(0.0, xn, rng.uniform(-0.3, 0.3, (n, 1)), p, dn)
        for i in range(n):
            c, s = math.cos(xn[i, 2]), math.sin(xn[i, 2])
            v, cn, ce = dn[i, 1], dn[i, 2], dn[i, 3]
            assert (got[i, 0], got[i, 1]) == (7.0 * c - v * s + cn, 7.0 * s + v * c + ce)


@pytest.mark.parametrize("rhs", [mmg.mmg_rhs, mmg_four_quadrant.mmg4q_rhs,
                                 mmg_low_speed.mmg_ls_rhs, mariner.mariner_rhs,
                                 container.container_rhs, nomoto.nomoto1_rhs,
                                 nomoto.nomoto2_rhs])
def test_every_3dof_model_moves_through_the_shared_kinematics(rhs):
    names = rhs.py_func.__code__.co_names
    if "write_mmg_rates" in names:  # the MMG family: its state rates written in one place
        names = mmg.write_mmg_rates.py_func.__code__.co_names
    assert "horizontal_velocity" in names
    assert "cos" not in names or rhs is container.container_rhs  # (the roll angle's cosine)


def test_the_mmg_family_shares_its_rates_and_its_rudder():
    for rhs in (mmg.mmg_rhs, mmg_four_quadrant.mmg4q_rhs, mmg_low_speed.mmg_ls_rhs):
        names = rhs.py_func.__code__.co_names
        assert "write_mmg_rates" in names and "north" not in names  # (not written twice)
    for forces in (mmg._forces, mmg_four_quadrant._forces4q):
        assert "mmg_rudder_forces" in forces.py_func.__code__.co_names
