"""Compiled kernels of the 6-DOF rigid body: kinematics, Coriolis, restoring, cross-flow, solve.

Axes and symbols of Fossen (2021): NED position p = (N, E, D) [m], Euler angles Θ = (φ, θ, ψ)
(roll, pitch, yaw; zyx convention) or the unit quaternion q = (η, ε₁, ε₂, ε₃), body velocity
ν = (u, v, w, p, q, r) = (ν₁, ν₂) with ν₁ linear [m/s], ν₂ angular [rad/s].

Kinematics (Fossen 2021, §2.2)
    ṗ = R(Θ) ν₁ with R = R_z(ψ) R_y(θ) R_x(φ) (§2.2.1);
    Θ̇ = T(Θ) ν₂, T = [[1, sφ tθ, cφ tθ], [0, cφ, −sφ], [0, sφ/cθ, cφ/cθ]], singular at
    θ = ±90° (§2.2.1);
    q̇ = ½ T(q) ν₂ + (γ/2)(1 − qᵀq) q, T(q) = [[−ε₁, −ε₂, −ε₃], [η, −ε₃, ε₂], [ε₃, η, −ε₁],
    [−ε₂, ε₁, η]], with the normalisation term of §2.2.2 (γ ≥ 0; it vanishes on the unit
    sphere, so it only pulls integration error back), and R(q) of §2.2.2.

Coriolis–centripetal forces (Fossen 2021, §3.3 Theorem 3.2 for M_RB, §6.3 for M_A)
    For a symmetric mass matrix M = [[M₁₁, M₁₂], [M₂₁, M₂₂]] the Kirchhoff parametrisation
    C(ν) = [[0, −S(a₁)], [−S(a₁), −S(a₂)]], a₁ = M₁₁ν₁ + M₁₂ν₂, a₂ = M₂₁ν₁ + M₂₂ν₂, is
    skew-symmetric, so νᵀC(ν)ν = 0 (the forces do no work), and
    C(ν)ν = (ν₂ × a₁, ν₁ × a₁ + ν₂ × a₂).

Restoring forces (Fossen 2021, §4.1, submerged body)
    With k = Rᵀ e₃ = (−sθ, cθ sφ, cθ cφ), weight W at r_g and buoyancy B at r_b:
    g(η) = −[(W − B) k; (W r_g − B r_b) × k].

Cross-flow drag (Fossen 2021, §6.7, strip theory)
    Y = −½ ρ T C_d Σ_k |v + x_k r|(v + x_k r) Δx,  N = −½ ρ T C_d Σ_k x_k |v + x_k r|(v + x_k r) Δx
    over the points x_k = −L/2 + k Δx, k = 0 … n, Δx = L/n (n + 1 points, each weighted Δx, as
    in MSS/PVS ``crossFlowDrag``), C_d the 2-D coefficient (Hoerner's curve,
    :func:`seahelm.vessels.six_dof.params.hoerner_cross_flow_coefficient`).

All kernels work on scalars and tuples (no allocation: the closed loop inlines them), so a
3 × 3 matrix is a row-major 9-tuple and the 6 × 6 mass matrix is solved by its 3 × 3 blocks.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = [
    "rotation_euler", "rotation_quaternion", "euler_rates", "quaternion_rates",
    "quaternion_from_euler", "euler_from_quaternion", "coriolis_times_velocity",
    "masked_coriolis_times_velocity", "restoring_submerged", "cross_flow_drag", "solve_blocks",
    "rigid_body_momentum",
    "skew", "system_transformation", "rigid_body_mass_matrix",
]


# ------------------------------------------------------------------------------------------
# numpy helpers (parameters, tests)
# ------------------------------------------------------------------------------------------
def skew(a: np.ndarray) -> np.ndarray:
    """S(a), the 3 × 3 skew-symmetric matrix with S(a) b = a × b (Fossen 2021, §2.1).

    Parameters
    ----------
    a : array_like, shape (3,)

    Returns
    -------
    numpy.ndarray, shape (3, 3)
    """
    a = np.asarray(a, dtype=float)
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def system_transformation(r: np.ndarray) -> np.ndarray:
    """H(r) = [[I, S(r)ᵀ], [0, I]]: M_CO = H(r_g)ᵀ M_CG H(r_g) (Fossen 2021, §3.3).

    Parameters
    ----------
    r : array_like, shape (3,)
        The point (e.g. the CG) from the body origin CO [m].

    Returns
    -------
    numpy.ndarray, shape (6, 6)
    """
    h = np.eye(6)
    h[0:3, 3:6] = skew(r).T
    return h


def rigid_body_mass_matrix(mass: float, center_of_gravity: np.ndarray,
                           inertia_cg: np.ndarray) -> np.ndarray:
    """M_RB about the body origin CO from the mass [kg], r_g [m] and I_g [kg·m²] about the CG.

    M_RB = H(r_g)ᵀ diag(m I₃, I_g) H(r_g) = [[m I₃, −m S(r_g)], [m S(r_g), I_g − m S²(r_g)]]
    (Fossen 2021, §3.3).

    Parameters
    ----------
    mass : float
        m [kg].
    center_of_gravity : array_like, shape (3,)
        r_g from CO [m].
    inertia_cg : array_like, shape (9,) or (3, 3)
        I_g about the CG [kg·m²].

    Returns
    -------
    numpy.ndarray, shape (6, 6)
    """
    m_cg = np.zeros((6, 6))
    m_cg[0:3, 0:3] = mass * np.eye(3)
    m_cg[3:6, 3:6] = np.asarray(inertia_cg, dtype=float).reshape(3, 3)
    h = system_transformation(np.asarray(center_of_gravity, dtype=float))
    return h.T @ m_cg @ h


# ------------------------------------------------------------------------------------------
# kinematics
# ------------------------------------------------------------------------------------------
@njit(cache=True)
def rotation_euler(phi, theta, psi):  # pragma: no cover - compiled
    """R(Θ) = R_z(ψ) R_y(θ) R_x(φ) as a row-major 9-tuple (§2.2.1)."""
    cf, sf = math.cos(phi), math.sin(phi)
    ct, st = math.cos(theta), math.sin(theta)
    cp, sp = math.cos(psi), math.sin(psi)
    return (cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st,
            sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf,
            -st, ct * sf, ct * cf)


@njit(cache=True)
def rotation_quaternion(eta, e1, e2, e3):  # pragma: no cover - compiled
    """R(q) of a unit quaternion q = (η, ε₁, ε₂, ε₃), row-major 9-tuple (§2.2.2)."""
    return (1.0 - 2.0 * (e2 * e2 + e3 * e3), 2.0 * (e1 * e2 - e3 * eta),
            2.0 * (e1 * e3 + e2 * eta),
            2.0 * (e1 * e2 + e3 * eta), 1.0 - 2.0 * (e1 * e1 + e3 * e3),
            2.0 * (e2 * e3 - e1 * eta),
            2.0 * (e1 * e3 - e2 * eta), 2.0 * (e2 * e3 + e1 * eta),
            1.0 - 2.0 * (e1 * e1 + e2 * e2))


@njit(cache=True)
def euler_rates(phi, theta, p, q, r):  # pragma: no cover - compiled
    """(φ̇, θ̇, ψ̇) = T(Θ) ν₂ (§2.2.1; singular at θ = ±90°)."""
    cf, sf = math.cos(phi), math.sin(phi)
    ct = math.cos(theta)
    tt = math.tan(theta)
    return (p + (sf * q + cf * r) * tt, cf * q - sf * r, (sf * q + cf * r) / ct)


@njit(cache=True)
def quaternion_rates(eta, e1, e2, e3, p, q, r, gain):  # pragma: no cover - compiled
    """q̇ = ½ T(q) ν₂ + (γ/2)(1 − qᵀq) q, γ = ``gain`` [1/s] (§2.2.2)."""
    k = 0.5 * gain * (1.0 - (eta * eta + e1 * e1 + e2 * e2 + e3 * e3))
    return (0.5 * (-e1 * p - e2 * q - e3 * r) + k * eta,
            0.5 * (eta * p - e3 * q + e2 * r) + k * e1,
            0.5 * (e3 * p + eta * q - e1 * r) + k * e2,
            0.5 * (-e2 * p + e1 * q + eta * r) + k * e3)


@njit(cache=True)
def quaternion_from_euler(phi, theta, psi):  # pragma: no cover - compiled
    """The unit quaternion (η, ε₁, ε₂, ε₃) of the zyx Euler angles (§2.2.2)."""
    cf, sf = math.cos(0.5 * phi), math.sin(0.5 * phi)
    ct, st = math.cos(0.5 * theta), math.sin(0.5 * theta)
    cp, sp = math.cos(0.5 * psi), math.sin(0.5 * psi)
    return (cf * ct * cp + sf * st * sp, sf * ct * cp - cf * st * sp,
            cf * st * cp + sf * ct * sp, cf * ct * sp - sf * st * cp)


@njit(cache=True)
def euler_from_quaternion(eta, e1, e2, e3):  # pragma: no cover - compiled
    """(φ, θ, ψ) of a unit quaternion, from the elements of R(q) (§2.2.2); θ ∈ [−90°, 90°]."""
    r32 = 2.0 * (e2 * e3 + e1 * eta)
    r33 = 1.0 - 2.0 * (e1 * e1 + e2 * e2)
    r31 = 2.0 * (e1 * e3 - e2 * eta)
    r21 = 2.0 * (e1 * e2 + e3 * eta)
    r11 = 1.0 - 2.0 * (e2 * e2 + e3 * e3)
    s = -r31
    if s > 1.0:
        s = 1.0
    elif s < -1.0:
        s = -1.0
    return math.atan2(r32, r33), math.asin(s), math.atan2(r21, r11)


# ------------------------------------------------------------------------------------------
# kinetics
# ------------------------------------------------------------------------------------------
@njit(cache=True)
def _momenta(M, u, v, w, p, q, r):  # pragma: no cover - compiled
    """a = sym(M) ν (6-tuple) for a flat row-major 6 × 6 ``M``."""
    nu = (u, v, w, p, q, r)
    a0 = a1 = a2 = a3 = a4 = a5 = 0.0
    for j in range(6):
        x = nu[j]
        a0 += 0.5 * (M[j] + M[6 * j]) * x
        a1 += 0.5 * (M[6 + j] + M[6 * j + 1]) * x
        a2 += 0.5 * (M[12 + j] + M[6 * j + 2]) * x
        a3 += 0.5 * (M[18 + j] + M[6 * j + 3]) * x
        a4 += 0.5 * (M[24 + j] + M[6 * j + 4]) * x
        a5 += 0.5 * (M[30 + j] + M[6 * j + 5]) * x
    return a0, a1, a2, a3, a4, a5


@njit(cache=True)
def _kirchhoff(a0, a1, a2, a3, a4, a5, u, v, w, p, q, r):  # pragma: no cover - compiled
    """C(ν)ν = (ν₂ × a₁, ν₁ × a₁ + ν₂ × a₂) for the momenta a = M ν."""
    return (q * a2 - r * a1, r * a0 - p * a2, p * a1 - q * a0,
            v * a2 - w * a1 + q * a5 - r * a4,
            w * a0 - u * a2 + r * a3 - p * a5,
            u * a1 - v * a0 + p * a4 - q * a3)


@njit(cache=True)
def coriolis_times_velocity(M, u, v, w, p, q, r):  # pragma: no cover - compiled
    """C(ν)ν (6-tuple) of the Kirchhoff parametrisation for the mass matrix ``M`` (flat 36)."""
    a0, a1, a2, a3, a4, a5 = _momenta(M, u, v, w, p, q, r)
    return _kirchhoff(a0, a1, a2, a3, a4, a5, u, v, w, p, q, r)


@njit(cache=True)
def masked_coriolis_times_velocity(M, mask, u, v, w, p, q, r):  # pragma: no cover - compiled
    """Σ_j mask_ij C_ij(ν) ν_j: C(ν)ν with the elements of C where ``mask`` is 0 removed.

    C(ν) = [[0, −S(a₁)], [−S(a₁), −S(a₂)]] with −S(a) = [[0, a_z, −a_y], [−a_z, 0, a_x],
    [a_y, −a_x, 0]].
    """
    a0, a1, a2, a3, a4, a5 = _momenta(M, u, v, w, p, q, r)
    k = mask
    return (k[4] * a2 * q - k[5] * a1 * r,
            -k[9] * a2 * p + k[11] * a0 * r,
            k[15] * a1 * p - k[16] * a0 * q,
            k[19] * a2 * v - k[20] * a1 * w + k[22] * a5 * q - k[23] * a4 * r,
            -k[24] * a2 * u + k[26] * a0 * w - k[27] * a5 * p + k[29] * a3 * r,
            k[30] * a1 * u - k[31] * a0 * v + k[33] * a4 * p - k[34] * a3 * q)


@njit(cache=True)
def rigid_body_momentum(m, gx, gy, gz, Ig, u, v, w, p, q, r):  # pragma: no cover - compiled
    """M_RB ν = (m (ν₁ + ν₂ × r_g), m r_g × ν₁ + (I_g − m S(r_g)²) ν₂), Fossen 2021, §3.3."""
    g2 = gx * gx + gy * gy + gz * gz
    gw = gx * p + gy * q + gz * r
    # (I_g − m S(r_g)²) ν₂ = I_g ν₂ + m (|r_g|² ν₂ − r_g (r_g·ν₂))
    return (m * (u + q * gz - r * gy), m * (v + r * gx - p * gz), m * (w + p * gy - q * gx),
            m * (gy * w - gz * v) + Ig[0] * p + Ig[1] * q + Ig[2] * r + m * (g2 * p - gx * gw),
            m * (gz * u - gx * w) + Ig[3] * p + Ig[4] * q + Ig[5] * r + m * (g2 * q - gy * gw),
            m * (gx * v - gy * u) + Ig[6] * p + Ig[7] * q + Ig[8] * r + m * (g2 * r - gz * gw))


@njit(cache=True)
def rigid_body_coriolis(m, gx, gy, gz, Ig, u, v, w, p, q, r):  # pragma: no cover - compiled
    """C_RB(ν)ν (Kirchhoff, Theorem 3.2 of Fossen 2021, §3.3) from the mass properties."""
    a0, a1, a2, a3, a4, a5 = rigid_body_momentum(m, gx, gy, gz, Ig, u, v, w, p, q, r)
    return _kirchhoff(a0, a1, a2, a3, a4, a5, u, v, w, p, q, r)


@njit(cache=True)
def restoring_submerged(weight, buoyancy, rg, rb, k0, k1, k2):  # pragma: no cover - compiled
    """−g(η) of a submerged body (§4.1): [(W − B) k; (W r_g − B r_b) × k], k = Rᵀe₃."""
    wb = weight - buoyancy
    mx = weight * rg[0] - buoyancy * rb[0]
    my = weight * rg[1] - buoyancy * rb[1]
    mz = weight * rg[2] - buoyancy * rb[2]
    return (wb * k0, wb * k1, wb * k2, my * k2 - mz * k1, mz * k0 - mx * k2, mx * k1 - my * k0)


@njit(cache=True)
def cross_flow_drag(length, draft, cd, rho, strips, v, r):  # pragma: no cover - compiled
    """(Y [N], N [N·m]) of the cross-flow drag by strip theory (§6.7; module docstring)."""
    n = int(strips)
    dx = length / n
    c = -0.5 * rho * draft * cd * dx
    y_force = 0.0
    n_moment = 0.0
    x = -0.5 * length
    for _ in range(n + 1):
        vr = v + x * r
        f = c * abs(vr) * vr
        y_force += f
        n_moment += x * f
        x += dx
    return y_force, n_moment


@njit(cache=True)
def _inv3(a):  # pragma: no cover - compiled
    """Inverse of a 3 × 3 matrix (row-major 9-tuple) by cofactors."""
    c0 = a[4] * a[8] - a[5] * a[7]
    c1 = a[5] * a[6] - a[3] * a[8]
    c2 = a[3] * a[7] - a[4] * a[6]
    det = a[0] * c0 + a[1] * c1 + a[2] * c2
    i = 1.0 / det
    return (c0 * i, (a[2] * a[7] - a[1] * a[8]) * i, (a[1] * a[5] - a[2] * a[4]) * i,
            c1 * i, (a[0] * a[8] - a[2] * a[6]) * i, (a[2] * a[3] - a[0] * a[5]) * i,
            c2 * i, (a[1] * a[6] - a[0] * a[7]) * i, (a[0] * a[4] - a[1] * a[3]) * i)


@njit(cache=True)
def _mul3(a, b):  # pragma: no cover - compiled
    """a b of two 3 × 3 matrices (row-major 9-tuples)."""
    return (a[0] * b[0] + a[1] * b[3] + a[2] * b[6], a[0] * b[1] + a[1] * b[4] + a[2] * b[7],
            a[0] * b[2] + a[1] * b[5] + a[2] * b[8],
            a[3] * b[0] + a[4] * b[3] + a[5] * b[6], a[3] * b[1] + a[4] * b[4] + a[5] * b[7],
            a[3] * b[2] + a[4] * b[5] + a[5] * b[8],
            a[6] * b[0] + a[7] * b[3] + a[8] * b[6], a[6] * b[1] + a[7] * b[4] + a[8] * b[7],
            a[6] * b[2] + a[7] * b[5] + a[8] * b[8])


@njit(cache=True)
def _vec3(a, x0, x1, x2):  # pragma: no cover - compiled
    return (a[0] * x0 + a[1] * x1 + a[2] * x2, a[3] * x0 + a[4] * x1 + a[5] * x2,
            a[6] * x0 + a[7] * x1 + a[8] * x2)


@njit(cache=True)
def solve_blocks(A, B, C, b0, b1, b2, b3, b4, b5):  # pragma: no cover - compiled
    """x = M⁻¹ b for M = [[A, B], [Bᵀ, C]] (3 × 3 blocks, row-major 9-tuples), by the Schur
    complement S = C − Bᵀ A⁻¹ B: x₂ = S⁻¹ (b₂ − Bᵀ A⁻¹ b₁), x₁ = A⁻¹ (b₁ − B x₂)."""
    ai = _inv3(A)
    bt = (B[0], B[3], B[6], B[1], B[4], B[7], B[2], B[5], B[8])
    aib = _mul3(ai, B)
    btaib = _mul3(bt, aib)
    s = (C[0] - btaib[0], C[1] - btaib[1], C[2] - btaib[2], C[3] - btaib[3], C[4] - btaib[4],
         C[5] - btaib[5], C[6] - btaib[6], C[7] - btaib[7], C[8] - btaib[8])
    y0, y1, y2 = _vec3(ai, b0, b1, b2)
    z0, z1, z2 = _vec3(bt, y0, y1, y2)
    x3, x4, x5 = _vec3(_inv3(s), b3 - z0, b4 - z1, b5 - z2)
    w0, w1, w2 = _vec3(B, x3, x4, x5)
    x0, x1, x2 = _vec3(ai, b0 - w0, b1 - w1, b2 - w2)
    return x0, x1, x2, x3, x4, x5
