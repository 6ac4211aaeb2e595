"""The compiled inner loop of the first-order wave motions (:mod:`seahelm.environment.first_order`).

For one run it sums, at every sample t_k of the record and for every degree of freedom j,

    η_j(t_k) = Σ_i Re(a_i H_j(ω_i, ε_i(t_k), U(t_k)) e^{iθ_i(t_k)}),
    θ_i(t_k) = ω_i t_k − k_i (x_k cos β_i + y_k sin β_i) + ϕ_i,   ε_i = β_i − ψ_k,

with a_i H_j tabulated per component over a uniform heading grid (and the RAOs' speeds) and
interpolated linearly in heading and speed. cos θ and sin θ come from :func:`sincos`: a
Cody–Waite reduction by π/2 and the Taylor polynomials of sin and cos on [−π/4, π/4] (to
r¹⁵/15! and r¹⁶/16!, truncation below 5e-17), written without branches so that LLVM
vectorises the loop over components (libm's scalar cos and sin are not vectorised; the pass
is about 3× faster with the polynomial). Agreement with numpy's sin and cos: tested to 1e-15.
"""

from __future__ import annotations

import math
from decimal import Decimal, getcontext

import numpy as np
from numba import njit

__all__ = ["sincos", "first_order_sample", "first_order_run"]

getcontext().prec = 60
_HALF_PI = Decimal("1.57079632679489661923132169163975144209858469968755291048747")
#: π/2 = _P1 + _P2 (Cody–Waite): _P1 has 33 significant bits, so n·_P1 is exact for |n| < 2^20.
_P1 = float(Decimal(round(_HALF_PI * (1 << 32))) / Decimal(1 << 32))
_P2 = float(_HALF_PI - Decimal(_P1))
_TWO_OVER_PI = 2.0 / math.pi
_S = tuple((-1.0) ** k / math.factorial(2 * k + 1) for k in range(8))  # r, r³, ..., r¹⁵
_C = tuple((-1.0) ** k / math.factorial(2 * k) for k in range(9))      # 1, r², ..., r¹⁶
S0, S1, S2, S3, S4, S5, S6, S7 = _S
C0, C1, C2, C3, C4, C5, C6, C7, C8 = _C


@njit(cache=True, nogil=True, inline="always")
def sincos(a: float) -> tuple[float, float]:  # pragma: no cover - compiled
    """(sin a, cos a) for |a| < 1.6e6 rad (module docstring), branch-free.

    Parameters
    ----------
    a : float
        Angle [rad].

    Returns
    -------
    (float, float)
        sin a, cos a.
    """
    n = math.floor(a * _TWO_OVER_PI + 0.5)
    r = (a - n * _P1) - n * _P2
    r2 = r * r
    s = r * (S0 + r2 * (S1 + r2 * (S2 + r2 * (S3 + r2 * (S4 + r2 * (S5 + r2 * (
        S6 + r2 * S7)))))))
    c = C0 + r2 * (C1 + r2 * (C2 + r2 * (C3 + r2 * (C4 + r2 * (C5 + r2 * (C6 + r2 * (
        C7 + r2 * C8)))))))
    q = np.int64(n) & 3
    swap = float(q & 1)
    sign_s = 1.0 - 2.0 * float((q >> 1) & 1)
    sign_c = 1.0 - 2.0 * float(((q + 1) >> 1) & 1)
    return (sign_s * (swap * c + (1.0 - swap) * s),
            sign_c * (swap * s + (1.0 - swap) * c))


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"}, inline="always")
def _sum_one(tr, ti, c, s, jj, ww, same, d):  # pragma: no cover - compiled
    """Σ_i Re(a_i H_j e^{iθ_i}) from one speed's table (d: the DOF)."""
    m = c.size
    acc = 0.0
    if same:  # long-crested: one heading for all components, contiguous loads
        j = jj[0]
        w = ww[0]
        r0 = tr[d, j]
        r1 = tr[d, j + 1]
        i0 = ti[d, j]
        i1 = ti[d, j + 1]
        for i in range(m):
            acc += (r0[i] + w * (r1[i] - r0[i])) * c[i] - (i0[i] + w * (i1[i] - i0[i])) * s[i]
    else:
        for i in range(m):
            j = jj[i]
            w = ww[i]
            acc += ((tr[d, j, i] + w * (tr[d, j + 1, i] - tr[d, j, i])) * c[i]
                    - (ti[d, j, i] + w * (ti[d, j + 1, i] - ti[d, j, i])) * s[i])
    return acc


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"}, inline="always")
def first_order_sample(t, xk, yk, pk, uk, omega, wavenumber, cos_beta, sin_beta, beta, phase,
                       table_re, table_im, heading_step, speeds, same, c, s, jj, ww, out
                       ):  # pragma: no cover - compiled
    """η_j at one instant into ``out[0:n_dof]`` (module docstring): the one evaluation that
    both the post-pass (:func:`first_order_run`) and the closed loop's in-loop stage
    (:mod:`seahelm.simulation.wave_motion_stage`) call.

    Parameters
    ----------
    t : float
        Time [s].
    xk, yk : float
        Position north and east [m].
    pk : float
        Heading ψ [rad].
    uk : float
        Speed [m/s] at which the RAOs are interpolated.
    omega, wavenumber, cos_beta, sin_beta, beta, phase : float64[m]
        As in :func:`first_order_run`.
    table_re, table_im : float64[n_speed, n_dof, n_head + 1, m]
        As in :func:`first_order_run`.
    heading_step : float
        Heading grid step [rad].
    speeds : float64[n_speed]
        Speeds of the tables [m/s].
    same : bool
        Long-crested (one direction for all components).
    c, s, ww : float64[m]
        Scratch (cos θ_i, sin θ_i, heading weights).
    jj : int64[m]
        Scratch (heading cells).
    out : float64[>= n_dof]
        The responses (the first n_dof overwritten).
    """
    m = omega.size
    n_speed = speeds.size
    n_head = table_re.shape[2] - 1
    n_dof = table_re.shape[1]
    two_pi = 2.0 * math.pi
    inv_step = 1.0 / heading_step
    for i in range(m):  # vectorised: the phases and their sine and cosine
        th = omega[i] * t - wavenumber[i] * (xk * cos_beta[i] + yk * sin_beta[i]) + phase[i]
        s[i], c[i] = sincos(th)
    m_head = 1 if same else m
    for i in range(m_head):  # the relative headings on the table's grid
        e = beta[i] - pk
        e -= two_pi * math.floor(e / two_pi)
        pos = e * inv_step
        j = min(np.int64(pos), n_head - 1)
        jj[i] = j
        ww[i] = pos - j
    s0 = 0
    ws = 0.0
    if n_speed > 1:
        if uk >= speeds[n_speed - 1]:
            s0 = n_speed - 2
            ws = 1.0
        elif uk > speeds[0]:
            while speeds[s0 + 1] <= uk:
                s0 += 1
            ws = (uk - speeds[s0]) / (speeds[s0 + 1] - speeds[s0])
    for d in range(n_dof):
        eta = _sum_one(table_re[s0], table_im[s0], c, s, jj, ww, same, d)
        if ws > 0.0:
            eta = (1.0 - ws) * eta + ws * _sum_one(table_re[s0 + 1], table_im[s0 + 1], c, s,
                                                   jj, ww, same, d)
        out[d] = eta


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def first_order_run(time, x, y, psi, u, omega, wavenumber, cos_beta, sin_beta, beta, phase,
                    table_re, table_im, heading_step, speeds, same, out):  # pragma: no cover
    """η_j(t_k) of one run into ``out`` (module docstring).

    Parameters
    ----------
    time : float64[n]
        t_k [s].
    x, y : float64[n]
        Position north and east [m].
    psi : float64[n]
        Heading ψ [rad].
    u : float64[n]
        Speed [m/s] at which the RAOs are interpolated.
    omega, wavenumber, cos_beta, sin_beta, beta, phase : float64[m]
        ω_i [rad/s], k_i [rad/m], cos β_i, sin β_i, β_i (direction of travel, clockwise from
        north) [rad] and ϕ_i [rad] of the components.
    table_re, table_im : float64[n_speed, n_dof, n_head + 1, m]
        a_i H_j at the speeds and at headings l·heading_step, l = 0 … n_head (the last = 2π).
    heading_step : float
        Heading grid step [rad].
    speeds : float64[n_speed]
        Speeds of the tables [m/s], increasing; held at the ends.
    same : bool
        All components travel in one direction (long-crested): the fast path.
    out : float64[n, n_dof]
        The responses (overwritten).

    Notes
    -----
    Compiled with reassociation (``fastmath``), so that the sums over the components
    vectorise: the order of the sum differs from a sequential one by rounding only, and is
    the same for a run alone and in a batch. Each sample is :func:`first_order_sample`.
    """
    m = omega.size
    c = np.empty(m)
    s = np.empty(m)
    jj = np.empty(m, np.int64)
    ww = np.empty(m)
    for k in range(time.size):
        first_order_sample(time[k], x[k], y[k], psi[k], u[k], omega, wavenumber, cos_beta,
                           sin_beta, beta, phase, table_re, table_im, heading_step, speeds,
                           same, c, s, jj, ww, out[k])
