"""The 6-DOF right-hand side and :func:`six_dof_model`, which makes a craft a vessel model.

Equations of motion (Fossen 2021, ch. 3, 6, 7; relative velocity §10.3)::

    M ν̇_r + C_RB(ν_r) ν_r + C_A(ν_r) ν_r + D(ν_r) ν_r + g(η) = τ + τ_env
    ṗ = R(Θ) ν_r,1 + v_c,   Θ̇ = T(Θ) ν_r,2   (or q̇ = ½ T(q) ν_r,2, quaternion models)

M = M_RB + M_A; C_RB, C_A the Kirchhoff parametrisations of M_RB and M_A (C_A with the
elements ``added_mass_coriolis_mask`` removes set to zero); D(ν_r)ν_r = D_L(U_r) ν_r +
D_n |ν_r| ν_r + cross-flow drag (§6.7) + the hull's lift and drag (Beard & McLain 2012, as in
Fossen 2021, §8.4.2); g(η) the submerged restoring forces (§4.1) plus G (depth, φ, θ) and minus
a point weight (the Otter's payload). τ from the thrusters (thrust k_pos n|n| / k_neg n|n|,
+ k_J V_a|n| ahead, along the thruster's direction at its position) and fins (lift
½ ρ U² A C_Lδ δ, drag ½ ρ U² A C_Lδ δ²). τ_env: ``force_x``, ``force_y``, ``moment_z`` (body
axes, e.g. wind and wave loads).

Ocean current (``current_north``, ``current_east`` [m/s], over ground): the velocity states are
relative to the water, so every hydrodynamic force sees ν_r, and the position moves with the
current. For an irrotational current constant in NED this is exact (Fossen 2021, §10.3,
Property 10.1: M_RB ν̇ + C_RB(ν)ν = M_RB ν̇_r + C_RB(ν_r)ν_r; the Kirchhoff C_RB(ν)ν equals
the linear-velocity-independent parametrisation's product).

Actuators are states of the model: each thruster's shaft speed n [rad/s] follows its command
through a first-order lag ṅ = (sat(n_c) − n)/T_n with an acceleration limit; an azimuth
thruster's direction α likewise (with a turning-rate limit); each fin's angle δ follows
sat(δ_c) with its time constant and rate limit. Forces use the saturated values.

States (Euler models)::

    north, east, depth, roll, pitch, heading,
    surge_speed, sway_speed, heave_speed, roll_rate, pitch_rate, yaw_rate,
    <thruster>_speed …, <azimuth thruster>_angle …, <fin>_angle …

Quaternion models replace (roll, pitch, heading) by (quaternion_w, quaternion_x, quaternion_y,
quaternion_z): 13 rigid-body states.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import int64, njit

from ..._validate import lookup_name
from ...errors import ParameterError
from ...parameters import signal_indices
from ..base import VesselModel
from .params import FIN_STERN_PLANE, SixDofParams
from .rigid_body import (
    cross_flow_drag,
    euler_from_quaternion,
    euler_rates,
    masked_coriolis_times_velocity,
    quaternion_rates,
    restoring_submerged,
    rigid_body_coriolis,
    rotation_euler,
    rotation_quaternion,
    solve_blocks,
)

__all__ = ["six_dof_model", "EULER_STATES", "QUATERNION_STATES", "RIGID_OUTPUTS",
           "DISTURBANCES", "six_dof_euler_rhs", "six_dof_quaternion_rhs"]

EULER_STATES: tuple[str, ...] = (
    "north", "east", "depth", "roll", "pitch", "heading",
    "surge_speed", "sway_speed", "heave_speed", "roll_rate", "pitch_rate", "yaw_rate")
_EULER_UNITS = ("m", "m", "m", "rad", "rad", "rad", "m/s", "m/s", "m/s", "rad/s", "rad/s",
                "rad/s")
QUATERNION_STATES: tuple[str, ...] = (
    "north", "east", "depth", "quaternion_w", "quaternion_x", "quaternion_y", "quaternion_z",
    "surge_speed", "sway_speed", "heave_speed", "roll_rate", "pitch_rate", "yaw_rate")
_QUATERNION_UNITS = ("m", "m", "m", "-", "-", "-", "-", "m/s", "m/s", "m/s", "rad/s", "rad/s",
                     "rad/s")
#: Outputs of every 6-DOF model (then each thruster's thrust [N]).
RIGID_OUTPUTS: tuple[str, ...] = (
    "north", "east", "heading", "yaw_rate", "surge_speed", "sway_speed",
    "depth", "roll", "pitch", "heave_speed", "roll_rate", "pitch_rate", "speed")
_RIGID_OUTPUT_UNITS = ("m", "m", "rad", "rad/s", "m/s", "m/s", "m", "rad", "rad", "m/s",
                       "rad/s", "rad/s", "m/s")
DISTURBANCES: tuple[str, ...] = ("force_x", "force_y", "moment_z", "current_north",
                                 "current_east")
_DISTURBANCE_UNITS = ("N", "N", "N·m", "m/s", "m/s")

_E = signal_indices(EULER_STATES)
_Q = signal_indices(QUATERNION_STATES)
_Y = signal_indices(RIGID_OUTPUTS)
_D = signal_indices(DISTURBANCES)
_NE = len(EULER_STATES)
_NQ = len(QUATERNION_STATES)
_NY = len(RIGID_OUTPUTS)


@njit(cache=True)
def _clip(v, lo, hi):  # pragma: no cover - compiled
    return lo if v < lo else (hi if v > hi else v)


@njit(cache=True)
def _thrust(p, i, n, va):  # pragma: no cover - compiled
    """(thrust [N], shaft moment [N·m]) of thruster i at shaft speed n and advance speed va."""
    if n > 0.0:
        return (p.thruster_k_pos[i] * n * n + p.thruster_k_advance[i] * va * n,
                p.thruster_torque_pos[i] * n * n + p.thruster_torque_advance[i] * va * n)
    return -p.thruster_k_neg[i] * n * n, -p.thruster_torque_pos[i] * n * n


# _sym and _row are called with literal indices only (_sym(ma, 0, 1), _row(dl, 3, ...)):
# inlined at numba-IR level, not compiled for each Literal[int] pair (27 + 6 compilations)
@njit(cache=True, inline="always")
def _sym(a, i, j):  # pragma: no cover - compiled
    """Element (i, j) of ½ (A + Aᵀ) for a flat row-major 6 × 6 ``a``."""
    return 0.5 * (a[6 * i + j] + a[6 * j + i])


@njit(cache=True, inline="always")
def _row(a, i, u, v, w, p, q, r):  # pragma: no cover - compiled
    """Row i of a flat row-major 6 × 6 ``a`` times (u, v, w, p, q, r)."""
    k = 6 * i
    return (a[k] * u + a[k + 1] * v + a[k + 2] * w + a[k + 3] * p + a[k + 4] * q
            + a[k + 5] * r)


@njit(cache=True)
def _mass_blocks(p):  # pragma: no cover - compiled
    """The 3 × 3 blocks (A, B, C) of M = M_RB + M_A = [[A, B], [Bᵀ, C]] (symmetrised M_A).

    M_RB = [[m I, −m S(r_g)], [m S(r_g), I_g − m S(r_g)²]] (Fossen 2021, §3.3); from the
    parameters alone, so the compiled loop can keep it out of the time steps.
    """
    m = p.mass
    gx, gy, gz = p.center_of_gravity[0], p.center_of_gravity[1], p.center_of_gravity[2]
    ma = p.added_mass
    ig = p.inertia_cg
    g2 = gx * gx + gy * gy + gz * gz
    A = (m + _sym(ma, 0, 0), _sym(ma, 0, 1), _sym(ma, 0, 2),
         _sym(ma, 1, 0), m + _sym(ma, 1, 1), _sym(ma, 1, 2),
         _sym(ma, 2, 0), _sym(ma, 2, 1), m + _sym(ma, 2, 2))
    B = (_sym(ma, 0, 3), m * gz + _sym(ma, 0, 4), -m * gy + _sym(ma, 0, 5),
         -m * gz + _sym(ma, 1, 3), _sym(ma, 1, 4), m * gx + _sym(ma, 1, 5),
         m * gy + _sym(ma, 2, 3), -m * gx + _sym(ma, 2, 4), _sym(ma, 2, 5))
    C = (ig[0] + m * (g2 - gx * gx) + _sym(ma, 3, 3), ig[1] - m * gx * gy + _sym(ma, 3, 4),
         ig[2] - m * gx * gz + _sym(ma, 3, 5),
         ig[3] - m * gy * gx + _sym(ma, 4, 3), ig[4] + m * (g2 - gy * gy) + _sym(ma, 4, 4),
         ig[5] - m * gy * gz + _sym(ma, 4, 5),
         ig[6] - m * gz * gx + _sym(ma, 5, 3), ig[7] - m * gz * gy + _sym(ma, 5, 4),
         ig[8] + m * (g2 - gz * gz) + _sym(ma, 5, 5))
    return A, B, C


@njit(cache=True)
def _kinetics(x, a0, d, p, R, phi, theta, u, v, w, pr, qr, rr):  # pragma: no cover - compiled
    """ν̇_r (6-tuple) of M ν̇_r = τ − C(ν_r)ν_r − D(ν_r)ν_r − g(η) (module docstring).

    ``x`` the state, ``a0`` the index of its first actuator state, ``R`` the rotation (row-major
    9-tuple), ``phi``, ``theta`` roll and pitch (for G), (u, v, w, pr, qr, rr) = ν_r.
    """
    t0 = t1 = t2 = t3 = t4 = t5 = 0.0
    speed2 = u * u + v * v + w * w
    speed = math.sqrt(speed2)
    rho = p.water_density
    # thrusters
    n_t = int(p.thruster_count)
    k = a0 + n_t
    for i in range(n_t):
        n = _clip(x[a0 + i], p.thruster_min_speed[i], p.thruster_max_speed[i])
        if p.thruster_azimuthing[i] > 0.5:
            alpha = x[k]
            k += 1
        else:
            alpha = p.thruster_direction[i]
        thrust, moment = _thrust(p, i, n, (1.0 - p.thruster_wake[i]) * speed)
        ca, sa = math.cos(alpha), math.sin(alpha)
        fx = (1.0 - p.thruster_deduction[i]) * thrust * ca
        fy = (1.0 - p.thruster_deduction[i]) * thrust * sa
        rx, ry, rz = p.thruster_x[i], p.thruster_y[i], p.thruster_z[i]
        t0 += fx
        t1 += fy
        t3 += -rz * fy + moment * ca
        t4 += rz * fx + moment * sa
        t5 += rx * fy - ry * fx
    # fins
    for i in range(int(p.fin_count)):
        delta = _clip(x[k + i], -p.fin_max_angle[i], p.fin_max_angle[i])
        c = 0.5 * rho * p.fin_area[i] * p.fin_lift_slope[i]
        if p.fin_kind[i] == FIN_STERN_PLANE:
            q2 = u * u + w * w
            t0 -= c * q2 * delta * delta
            t2 -= c * q2 * delta
            t4 += p.fin_x[i] * c * q2 * delta
        else:
            q2 = u * u + v * v
            t0 -= c * q2 * delta * delta
            t1 -= c * q2 * delta
            t5 -= p.fin_x[i] * c * q2 * delta
    # hull lift and drag (Beard & McLain 2012; Fossen 2021, §8.4.2)
    if p.hull_lift_area > 0.0:
        alpha = math.atan2(w, u)
        ar = p.hull_lift_span * p.hull_lift_span / p.hull_lift_area
        cl = math.pi * ar / (1.0 + math.sqrt(1.0 + 0.25 * ar * ar)) * alpha
        cd = p.hull_drag_coefficient + cl * cl / (math.pi * p.hull_lift_efficiency * ar)
        qs = 0.5 * rho * speed2 * p.hull_lift_area
        ca, sa = math.cos(alpha), math.sin(alpha)
        t0 += -ca * qs * cd + sa * qs * cl
        t2 += -sa * qs * cd - ca * qs * cl
    # cross-flow drag (§6.7)
    if p.cross_flow_length > 0.0:
        yc, nc = cross_flow_drag(p.cross_flow_length, p.cross_flow_draft,
                                 p.cross_flow_coefficient, rho, p.cross_flow_strips, v, rr)
        t1 += yc
        t5 += nc
    # damping: linear (surge and sway fading with the speed) and quadratic
    fade = math.exp(-p.linear_damping_decay * speed) if p.linear_damping_decay > 0.0 else 1.0
    dl = p.linear_damping
    dq = p.quadratic_damping
    t0 -= _row(dl, 0, fade * u, fade * v, w, pr, qr, rr) + dq[0] * abs(u) * u
    t1 -= _row(dl, 1, fade * u, fade * v, w, pr, qr, rr) + dq[1] * abs(v) * v
    t2 -= _row(dl, 2, u, v, w, pr, qr, rr) + dq[2] * abs(w) * w
    t3 -= _row(dl, 3, u, v, w, pr, qr, rr) + dq[3] * abs(pr) * pr
    t4 -= _row(dl, 4, u, v, w, pr, qr, rr) + dq[4] * abs(qr) * qr
    t5 -= _row(dl, 5, u, v, w, pr, qr, rr) + dq[5] * abs(rr) * rr
    # Coriolis and centripetal forces: C_RB(ν_r)ν_r and the masked C_A(ν_r)ν_r
    c0, c1, c2, c3, c4, c5 = rigid_body_coriolis(
        p.mass, p.center_of_gravity[0], p.center_of_gravity[1], p.center_of_gravity[2],
        p.inertia_cg, u, v, w, pr, qr, rr)
    e0, e1, e2, e3, e4, e5 = masked_coriolis_times_velocity(
        p.added_mass, p.added_mass_coriolis_mask, u, v, w, pr, qr, rr)
    # restoring: submerged weight and buoyancy, linear stiffness on (depth, φ, θ), point weight
    g0, g1, g2, g3, g4, g5 = restoring_submerged(p.weight, p.buoyancy, p.center_of_gravity,
                                                 p.center_of_buoyancy, R[6], R[7], R[8])
    G = p.hydrostatic_stiffness
    z = x[_E.depth]
    h0 = G[2] * z + G[3] * phi + G[4] * theta
    h1 = G[8] * z + G[9] * phi + G[10] * theta
    h2 = G[14] * z + G[15] * phi + G[16] * theta
    h3 = G[20] * z + G[21] * phi + G[22] * theta
    h4 = G[26] * z + G[27] * phi + G[28] * theta
    h5 = G[32] * z + G[33] * phi + G[34] * theta
    wp = p.payload_weight
    fx, fy, fz = wp * R[6], wp * R[7], wp * R[8]
    rp = p.payload_position
    b0 = t0 - c0 - e0 + g0 - h0 + fx + d[_D.force_x]
    b1 = t1 - c1 - e1 + g1 - h1 + fy + d[_D.force_y]
    b2 = t2 - c2 - e2 + g2 - h2 + fz
    b3 = t3 - c3 - e3 + g3 - h3 + rp[1] * fz - rp[2] * fy
    b4 = t4 - c4 - e4 + g4 - h4 + rp[2] * fx - rp[0] * fz
    b5 = t5 - c5 - e5 + g5 - h5 + rp[0] * fy - rp[1] * fx + d[_D.moment_z]
    A, B, C = _mass_blocks(p)
    return solve_blocks(A, B, C, b0, b1, b2, b3, b4, b5)


@njit(cache=True)
def _actuator_rates(x, a0, u, p, dx):  # pragma: no cover - compiled
    """ṅ, α̇, δ̇ of the thrusters, azimuth angles and fins (first-order lags with limits)."""
    n_t = int(p.thruster_count)
    k = a0 + n_t
    ku = n_t
    for i in range(n_t):
        cmd = _clip(u[i], p.thruster_min_speed[i], p.thruster_max_speed[i])
        lim = p.thruster_max_acceleration[i]
        dx[a0 + i] = _clip((cmd - x[a0 + i]) / p.thruster_time_constant[i], -lim, lim)
        if p.thruster_azimuthing[i] > 0.5:
            lim = p.thruster_max_turn_rate[i]
            dx[k] = _clip((u[ku] - x[k]) / p.thruster_turn_time_constant[i], -lim, lim)
            k += 1
            ku += 1
    for i in range(int(p.fin_count)):
        cmd = _clip(u[ku + i], -p.fin_max_angle[i], p.fin_max_angle[i])
        lim = p.fin_max_rate[i]
        dx[k + i] = _clip((cmd - x[k + i]) / p.fin_time_constant[i], -lim, lim)


# (a0, iv: the models' constant state indices, typed int64 by numba locals, so _kinetics,
# _actuator_rates and _common_outputs compile once for both kinds, not once per Literal[int])
@njit(cache=True, locals={"a0": int64})
def six_dof_euler_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of a 6-DOF craft with Euler angles (module docstring)."""
    a0 = _NE
    phi, theta, psi = x[_E.roll], x[_E.pitch], x[_E.heading]
    R = rotation_euler(phi, theta, psi)
    u1, v1, w1 = x[_E.surge_speed], x[_E.sway_speed], x[_E.heave_speed]
    p1, q1, r1 = x[_E.roll_rate], x[_E.pitch_rate], x[_E.yaw_rate]
    (dx[_E.surge_speed], dx[_E.sway_speed], dx[_E.heave_speed], dx[_E.roll_rate],
     dx[_E.pitch_rate], dx[_E.yaw_rate]) = _kinetics(x, a0, d, p, R, phi, theta,
                                                     u1, v1, w1, p1, q1, r1)
    dx[_E.north] = R[0] * u1 + R[1] * v1 + R[2] * w1 + d[_D.current_north]
    dx[_E.east] = R[3] * u1 + R[4] * v1 + R[5] * w1 + d[_D.current_east]
    dx[_E.depth] = R[6] * u1 + R[7] * v1 + R[8] * w1
    dx[_E.roll], dx[_E.pitch], dx[_E.heading] = euler_rates(phi, theta, p1, q1, r1)
    _actuator_rates(x, a0, u, p, dx)


@njit(cache=True, locals={"a0": int64})
def six_dof_quaternion_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of a 6-DOF craft with a unit quaternion (module docstring)."""
    a0 = _NQ
    qw, qx, qy, qz = x[_Q.quaternion_w], x[_Q.quaternion_x], x[_Q.quaternion_y], x[_Q.quaternion_z]
    R = rotation_quaternion(qw, qx, qy, qz)
    phi, theta, _ = euler_from_quaternion(qw, qx, qy, qz)
    u1, v1, w1 = x[_Q.surge_speed], x[_Q.sway_speed], x[_Q.heave_speed]
    p1, q1, r1 = x[_Q.roll_rate], x[_Q.pitch_rate], x[_Q.yaw_rate]
    (dx[_Q.surge_speed], dx[_Q.sway_speed], dx[_Q.heave_speed], dx[_Q.roll_rate],
     dx[_Q.pitch_rate], dx[_Q.yaw_rate]) = _kinetics(x, a0, d, p, R, phi, theta,
                                                     u1, v1, w1, p1, q1, r1)
    dx[_Q.north] = R[0] * u1 + R[1] * v1 + R[2] * w1 + d[_D.current_north]
    dx[_Q.east] = R[3] * u1 + R[4] * v1 + R[5] * w1 + d[_D.current_east]
    dx[_Q.depth] = R[6] * u1 + R[7] * v1 + R[8] * w1
    (dx[_Q.quaternion_w], dx[_Q.quaternion_x], dx[_Q.quaternion_y],
     dx[_Q.quaternion_z]) = quaternion_rates(qw, qx, qy, qz, p1, q1, r1, p.quaternion_gain)
    _actuator_rates(x, a0, u, p, dx)


@njit(cache=True)
def _common_outputs(x, iv, a0, p, phi, theta, psi, y):  # pragma: no cover - compiled
    uu, vv, ww = x[iv], x[iv + 1], x[iv + 2]
    y[_Y.north] = x[_E.north]
    y[_Y.east] = x[_E.east]
    y[_Y.depth] = x[_E.depth]
    y[_Y.heading] = psi
    y[_Y.roll] = phi
    y[_Y.pitch] = theta
    y[_Y.surge_speed] = uu
    y[_Y.sway_speed] = vv
    y[_Y.heave_speed] = ww
    y[_Y.roll_rate] = x[iv + 3]
    y[_Y.pitch_rate] = x[iv + 4]
    y[_Y.yaw_rate] = x[iv + 5]
    speed = math.sqrt(uu * uu + vv * vv + ww * ww)
    y[_Y.speed] = speed
    n_t = int(p.thruster_count)
    for i in range(n_t):
        n = _clip(x[a0 + i], p.thruster_min_speed[i], p.thruster_max_speed[i])
        y[_NY + i] = _thrust(p, i, n, (1.0 - p.thruster_wake[i]) * speed)[0]


@njit(cache=True, locals={"iv": int64, "a0": int64})
def six_dof_euler_output(t, x, u, p, y):  # pragma: no cover - compiled
    iv, a0 = _E.surge_speed, _NE
    _common_outputs(x, iv, a0, p, x[_E.roll], x[_E.pitch], x[_E.heading], y)


@njit(cache=True, locals={"iv": int64, "a0": int64})
def six_dof_quaternion_output(t, x, u, p, y):  # pragma: no cover - compiled
    iv, a0 = _Q.surge_speed, _NQ
    phi, theta, psi = euler_from_quaternion(x[_Q.quaternion_w], x[_Q.quaternion_x],
                                            x[_Q.quaternion_y], x[_Q.quaternion_z])
    _common_outputs(x, iv, a0, p, phi, theta, psi, y)


@njit(cache=True)
def six_dof_euler_motion(x, p):  # pragma: no cover - compiled
    """(surge, sway speed through the water [m/s], heading [rad]) for the environment."""
    return x[_E.surge_speed], x[_E.sway_speed], x[_E.heading]


@njit(cache=True)
def six_dof_quaternion_motion(x, p):  # pragma: no cover - compiled
    psi = euler_from_quaternion(x[_Q.quaternion_w], x[_Q.quaternion_x], x[_Q.quaternion_y],
                                x[_Q.quaternion_z])[2]
    return x[_Q.surge_speed], x[_Q.sway_speed], psi


def _check_unit_quaternion(x0: Any) -> None:
    """x0 of a quaternion model: the quaternion (η, ε₁, ε₂, ε₃) of every run of unit length."""
    q = np.asarray(x0, dtype=float)[:, _Q.quaternion_w:_Q.quaternion_z + 1]
    norm = np.sqrt((q * q).sum(axis=1))
    bad = np.flatnonzero(np.abs(norm - 1.0) > 1e-9)
    if bad.size:
        i = int(bad[0])
        raise ParameterError(
            f"must hold a unit quaternion (quaternion_w, quaternion_x, quaternion_y, "
            f"quaternion_z), got length {float(norm[i])!r} [-] in run {i}", field="x0", unit="-",
            value=float(norm[i]), run=i)


def _check_submerged(x0: Any) -> None:
    """x0 of an underwater vehicle: the depth of every run at or below the surface (≥ 0)."""
    depth = np.asarray(x0, dtype=float)[:, _E.depth]
    bad = np.flatnonzero(~(depth >= 0.0))
    if bad.size:
        i = int(bad[0])
        raise ParameterError(
            f"`depth` must be >= 0 [m] (positive down; an underwater vehicle starts at or below "
            f"the surface), got {float(depth[i])!r} in run {i}", field="x0", unit="m",
            value=float(depth[i]), run=i)


def _checks(*checks: Any) -> Any:
    checks = tuple(c for c in checks if c is not None)
    if not checks:
        return None

    def check(x0: Any) -> None:
        for c in checks:
            c(x0)
    return check


_KINEMATICS = {
    "euler": (EULER_STATES, _EULER_UNITS, six_dof_euler_rhs, six_dof_euler_output,
              six_dof_euler_motion),
    "quaternion": (QUATERNION_STATES, _QUATERNION_UNITS, six_dof_quaternion_rhs,
                   six_dof_quaternion_output, six_dof_quaternion_motion),
}


def six_dof_model(name: str, description: str, params_type: type[SixDofParams], *,
                  thrusters: tuple[str, ...], azimuthing: tuple[str, ...] = (),
                  fins: tuple[str, ...] = (), kinematics: str = "euler",
                  submerged: bool = False) -> VesselModel:
    """A 6-DOF craft as a :class:`~seahelm.vessels.base.VesselModel`.

    Parameters
    ----------
    name, description : str
        Registry name and one line.
    params_type : type of SixDofParams
        The craft's parameter class; its ``layout`` must match the thrusters and fins named.
    thrusters : tuple of str
        Thruster names in parameter order (states ``<name>_speed`` [rad/s], inputs
        ``<name>_speed_command``, outputs ``<name>_thrust`` [N]).
    azimuthing : tuple of str, optional
        The azimuth thrusters among them (states ``<name>_angle``, inputs
        ``<name>_angle_command`` [rad]).
    fins : tuple of str, optional
        Fin names in parameter order (states ``<name>_angle``, inputs ``<name>_command``).
    kinematics : {"euler", "quaternion"}
        Attitude states: zyx Euler angles (12 rigid-body states) or a unit quaternion (13).
    submerged : bool, optional
        An underwater vehicle: an initial depth above the surface (< 0) is refused.

    Returns
    -------
    VesselModel
    """
    states, units, rhs, output, motion = lookup_name("kinematics", _KINEMATICS, kinematics)
    unknown = [a for a in azimuthing if a not in thrusters]
    if unknown:
        raise ValueError(f"azimuthing thrusters {unknown} are not among {list(thrusters)}")
    layout = (len(thrusters), tuple(int(t in azimuthing) for t in thrusters), len(fins))
    if params_type.layout is not None and params_type.layout != layout:
        raise ValueError(f"{params_type.__name__}.layout is {params_type.layout}, the model "
                         f"names {layout}")
    az = [t for t in thrusters if t in azimuthing]
    act_states = ([f"{t}_speed" for t in thrusters] + [f"{t}_angle" for t in az]
                  + [f"{f}_angle" for f in fins])
    act_units = ["rad/s"] * len(thrusters) + ["rad"] * (len(az) + len(fins))
    inputs = ([f"{t}_speed_command" for t in thrusters] + [f"{t}_angle_command" for t in az]
              + [f"{f}_command" for f in fins])
    return VesselModel(
        name=name, description=description, params_type=params_type,
        state_labels=states + tuple(act_states), state_units=units + tuple(act_units),
        input_labels=tuple(inputs), input_units=tuple(act_units),
        disturbance_labels=DISTURBANCES, disturbance_units=_DISTURBANCE_UNITS,
        rhs=rhs, output=output,
        output_labels=RIGID_OUTPUTS + tuple(f"{t}_thrust" for t in thrusters),
        output_units=_RIGID_OUTPUT_UNITS + ("N",) * len(thrusters),
        motion=motion,
        check_initial_state=_checks(
            _check_unit_quaternion if kinematics == "quaternion" else None,
            _check_submerged if submerged else None),
    )

