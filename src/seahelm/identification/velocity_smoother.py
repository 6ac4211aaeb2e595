"""Velocities from measured position and heading: an extended Kalman filter and RTS smoother.

Sea trials log position (GNSS) and heading (gyro), rarely the surge and sway speed through the
water. For the MMG identification (:mod:`seahelm.identification.mmg_fit`) the body velocities u, v
and the yaw rate r are reconstructed from x (north), y (east) and ψ by a kinematic model with
random-walk velocities (the "nearly constant velocity" model of tracking, in body axes)::

    ẋ = u cos ψ − v sin ψ,   ẏ = u sin ψ + v cos ψ,   ψ̇ = r,
    u̇ = w_u,   v̇ = w_v,   ṙ = w_r          (white accelerations of spectral densities q)

measured x, y, ψ with white noise. An extended Kalman filter runs forward and the
Rauch–Tung–Striebel smoother backward (Rauch, Tung & Striebel 1965; the extended form, Särkkä
2013, §9.2), so each estimate uses the whole record; the smoother's standard deviations come
with the velocities. Why this and not a dynamic model of the ship: the smoother must not assume
the hydrodynamics that the identification is to find, only kinematics that hold for any ship.
Discretisation: the exact transition of the velocities' random walk (Q = q Δt) and the
linearised rotation at each step (first order in Δt; the record's own sampling).

References
----------
Rauch, H.E., Tung, F., Striebel, C.T. (1965). Maximum likelihood estimates of linear dynamic
systems. AIAA J. 3(8), 1445–1450.
Särkkä, S. (2013). Bayesian Filtering and Smoothing. Cambridge University Press, §9.2.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from numba import njit

from ..errors import ParameterError
from .records import ManoeuvreRecord

__all__ = ["reconstruct_velocities"]


@njit(cache=True)
def _inverse(a):  # pragma: no cover - compiled
    """Inverse of a small symmetric positive-definite matrix by Gauss–Jordan elimination
    (written out: numba's LAPACK bindings take tens of seconds to compile)."""
    n = a.shape[0]
    m = a.copy()
    inv = np.eye(n)
    for col in range(n):
        piv = col
        for row in range(col + 1, n):
            if abs(m[row, col]) > abs(m[piv, col]):
                piv = row
        if piv != col:
            for j in range(n):
                m[col, j], m[piv, j] = m[piv, j], m[col, j]
                inv[col, j], inv[piv, j] = inv[piv, j], inv[col, j]
        d = m[col, col]
        for j in range(n):
            m[col, j] /= d
            inv[col, j] /= d
        for row in range(n):
            if row != col:
                f = m[row, col]
                if f != 0.0:
                    for j in range(n):
                        m[row, j] -= f * m[col, j]
                        inv[row, j] -= f * inv[col, j]
    return inv


@njit(cache=True)
def _mm(a, b):  # pragma: no cover - compiled
    """a @ b by loops (no BLAS: quick to compile)."""
    out = np.zeros((a.shape[0], b.shape[1]))
    for i in range(a.shape[0]):
        for k in range(a.shape[1]):
            aik = a[i, k]
            if aik != 0.0:
                for j in range(b.shape[1]):
                    out[i, j] += aik * b[k, j]
    return out


@njit(cache=True)
def _mv(a, x):  # pragma: no cover - compiled
    out = np.zeros(a.shape[0])
    for i in range(a.shape[0]):
        for k in range(a.shape[1]):
            out[i] += a[i, k] * x[k]
    return out


@njit(cache=True)
def _ekf_rts(t, z, r_diag, q, x0, p0):  # pragma: no cover - compiled
    """Forward EKF and backward RTS over the samples; returns smoothed states and variances."""
    n = t.size
    xs = np.zeros((n, 6))
    ps = np.zeros((n, 6, 6))
    xp_all = np.zeros((n, 6))
    pp_all = np.zeros((n, 6, 6))
    fs = np.zeros((n, 6, 6))
    x = x0.copy()
    p = p0.copy()
    h = np.zeros((3, 6))
    h[0, 0] = 1.0
    h[1, 1] = 1.0
    h[2, 2] = 1.0
    rm = np.zeros((3, 3))
    for j in range(3):
        rm[j, j] = r_diag[j]
    for k in range(n):
        if k > 0:
            dt = t[k] - t[k - 1]
            c = math.cos(x[2])
            s = math.sin(x[2])
            u, v, r = x[3], x[4], x[5]
            f = np.eye(6)
            f[0, 2] = (-u * s - v * c) * dt
            f[0, 3] = c * dt
            f[0, 4] = -s * dt
            f[1, 2] = (u * c - v * s) * dt
            f[1, 3] = s * dt
            f[1, 4] = c * dt
            f[2, 5] = dt
            xn = x.copy()
            xn[0] += (u * c - v * s) * dt
            xn[1] += (u * s + v * c) * dt
            xn[2] += r * dt
            qm = np.zeros((6, 6))
            for j in range(3):
                qm[3 + j, 3 + j] = q[j] * dt
            x = xn
            p = _mm(_mm(f, p), f.T.copy()) + qm
            fs[k] = f
        xp_all[k] = x
        pp_all[k] = p
        innov = z[k] - _mv(h, x)
        sm = _mm(_mm(h, p), h.T.copy()) + rm
        gain = _mm(_mm(p, h.T.copy()), _inverse(sm))
        x = x + _mv(gain, innov)
        p = _mm(np.eye(6) - _mm(gain, h), p)
        xs[k] = x
        ps[k] = p
    # Rauch–Tung–Striebel, backward
    for k in range(n - 2, -1, -1):
        g = _mm(_mm(ps[k], fs[k + 1].T.copy()), _inverse(pp_all[k + 1]))
        xs[k] = xs[k] + _mv(g, xs[k + 1] - xp_all[k + 1])
        ps[k] = ps[k] + _mm(_mm(g, ps[k + 1] - pp_all[k + 1]), g.T.copy())
    var = np.zeros((n, 6))
    for k in range(n):
        for j in range(6):
            var[k, j] = ps[k, j, j]
    return xs, var


def reconstruct_velocities(record: ManoeuvreRecord, *, position_noise: float = 1.0,
                           heading_noise: float = math.radians(0.1),
                           acceleration: float | None = None,
                           yaw_acceleration: float | None = None,
                           length: float | None = None) -> ManoeuvreRecord:
    """The record with u, v and r estimated from its x, y, ψ (module docstring).

    Parameters
    ----------
    record : ManoeuvreRecord
        With channels ``x``, ``y`` [m] and a heading [rad].
    position_noise : float, optional
        σ of the position measurements [m] (default 1 m, a GNSS fix).
    heading_noise : float, optional
        σ of the heading measurements [rad] (default 0.1°).
    acceleration : float, optional
        σ of the surge and sway accelerations over one second [m/s²] (the random walk's
        √q; default 0.1 U²/L with the ship's length, else 2 % of the mean speed per second).
    yaw_acceleration : float, optional
        The same for the yaw rate [rad/s²] (default 0.5 (U/L)² with the length, else
        0.05°/s²): manoeuvres scale with U/L, so a model's are far quicker than its ship's.
    length : float, optional
        The ship's length L [m], for the default accelerations.

    Returns
    -------
    ManoeuvreRecord
        The same times, rudder and heading (smoothed), with ``surge_speed``, ``sway_speed``,
        ``yaw_rate`` estimated, and their standard deviations as ``surge_speed_std`` … in
        :attr:`~seahelm.identification.records.ManoeuvreRecord.channels` alongside the others.

    Raises
    ------
    ParameterError
        Without position or heading; a non-positive noise level.
    """
    ch = record.channels
    if "x" not in ch or "y" not in ch or record.heading is None:
        raise ParameterError(f"{record.name}: x, y and heading are needed to reconstruct the "
                             "velocities", field="x")
    for name, value in (("position_noise", position_noise), ("heading_noise", heading_noise),
                        ("acceleration", acceleration), ("yaw_acceleration", yaw_acceleration)):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0, got {value!r}", field=name, value=value)
    t = record.time
    x, y, psi = ch["x"], ch["y"], record.heading
    dt = np.diff(t)
    speed = float(np.median(np.hypot(np.diff(x), np.diff(y)) / dt))
    if length is not None and not (math.isfinite(length) and length > 0):
        raise ParameterError(f"must be > 0 [m], got {length!r}", field="length", unit="m",
                             value=length)
    if length is None:
        acc_default, yacc_default = max(0.02 * speed, 1e-4), math.radians(0.05)
    else:
        acc_default, yacc_default = 0.1 * speed ** 2 / length, 0.5 * (speed / length) ** 2
    acc = acceleration if acceleration is not None else acc_default
    yacc = yaw_acceleration if yaw_acceleration is not None else yacc_default
    q = np.array([acc ** 2, acc ** 2, yacc ** 2])
    z = np.column_stack([x, y, psi])
    c, s = math.cos(psi[0]), math.sin(psi[0])
    vn, ve = (x[1] - x[0]) / dt[0], (y[1] - y[0]) / dt[0]
    x0 = np.array([x[0], y[0], psi[0], c * vn + s * ve, -s * vn + c * ve,
                   (psi[1] - psi[0]) / dt[0]])
    p0 = np.diag([position_noise ** 2, position_noise ** 2, heading_noise ** 2,
                  speed ** 2 + 1.0, speed ** 2 + 1.0, 0.01])
    r_diag = np.array([position_noise ** 2, position_noise ** 2, heading_noise ** 2])
    states, var = _ekf_rts(np.asarray(t, float), z, r_diag, q, x0, p0)
    channels = dict(ch)
    for j, name in ((3, "surge_speed"), (4, "sway_speed")):
        channels[name] = states[:, j]
        channels[name + "_std"] = np.sqrt(var[:, j])
    channels["yaw_rate_std"] = np.sqrt(var[:, 5])
    return dataclasses.replace(record, name=f"{record.name} (smoothed)", heading=states[:, 2],
                               yaw_rate=states[:, 5], channels=channels)
