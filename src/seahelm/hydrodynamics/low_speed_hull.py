"""Hull forces at low speed, astern and at large drift: the cross-flow model of Yoshimura.

The MMG hull polynomials (:mod:`seahelm.vessels.mmg`) are fits at small drift and ahead
speed; divided by U² they blow up as the speed goes to zero with the yaw rate kept. The
"unified model for ocean and harbour manoeuvring" of Yoshimura, Nakao & Ishibashi (2009)
writes the hull forces for any drift angle β and any sign of u as the linear
(lift-like) derivatives times the velocities with the signs that keep every term's direction
right astern, plus the **cross-flow drag** of the hull's strips (strip theory, Hooft 1994)::

    X_H = ½ρLd [X'_0(β) u U + X'_vr v r L]
    Y_H = ½ρLd [Y'_v v |u| + Y'_r u r L]  − ½ρLd C_D ∫ |v + C_rY r L x'| (v + C_rY r L x') dx'
    N_H = ½ρL²d [N'_v u v + N'_r |u| r L] − ½ρL²d C_D ∫ x' |v + C_rN r L x'| (v + C_rN r L x') dx'
    X'_0(β) = X'_0F + (X'_0A − X'_0F) |β| / π,   X'_0F = −R'_0,   X'_0A = −R'_0,astern

with U = √(u² + v²), β = atan2(−v, u) (the MMG's convention, 0 ahead, ±π astern), the
integrals over x' = x / L from −½ to ½ (x forward of midship), C_D the cross-flow drag
coefficient of the hull (uniform along the length here) and C_rY, C_rN the correction factors
of the yaw rate in the cross-flow velocity of the sway force and the yaw moment. This is the
simplified form (linear derivatives, uniform C_D) in which the model is used for berthing
simulation by Miyauchi et al. (2022), whose hull force model is based on Yoshimura et al.
(2009) (the equation numbers of the MARSIM paper could not be checked: the paper was not in
the stored sources beyond its abstract, and its form was taken from that restatement as
implemented in the authors' public simulator of the Esso Osaka model,
``NAOE-5thLab/mmg-1p1r-simulator``, ``hullforce.py``, read for the formula only).
X'_0(β) interpolates the ahead and astern resistance linearly in |β| (ibid.). The mass and
added-mass terms ((m + m_y) v r, (m + m_x) u r) stay in the equations of motion, as in the
MMG model.

Properties (tested)
    At β = 0 the linear terms are the MMG's: ½ρLd Y'_v v |u| = ½ρLdU² Y'_v v' with u = U,
    and the same for X'_0, X'_vr, Y'_r, N'_v, N'_r. Reversing u and r (the fore-aft mirror)
    changes the sign of X and N and leaves Y, as mirroring the hull does, apart from the
    resistance (X'_0A in place of X'_0F). Every term is
    continuous through u = 0 and stays finite as U → 0 (no division by U). In pure sway
    (u = r = 0) the hull feels Y = −½ρLd C_D v |v| and no yaw moment (uniform C_D).

The cross-flow integrals are computed exactly: ∫ |a + b x|(a + b x) dx and ∫ x |a + b x|(a +
b x) dx over [−½, ½] are split at the zero of a + b x, where the integrand is ±(a + b x)² or
±x (a + b x)², polynomials integrated in closed form (:func:`cross_flow_integrals`).

Coefficients for a ship of the MMG model
    X'_0F, X'_vr, Y'_v, Y'_r, N'_v, N'_r are the MMG ship's own (the linear derivatives of the
    MMG set, which Yoshimura's model uses unchanged); X'_0A from R'_0,astern (no astern
    resistance data: R'_0 by default); C_rY = C_rN = 1 (plain strip theory; Yoshimura et al.
    fit them per ship, no KVLCC2 values were found). C_D: Yoshimura et al. give regression
    formulas, not available to us; :func:`matching_cross_flow_drag` takes the C_D for which
    the model's sway force in steady drift equals the MMG polynomials' at the edge of their
    range (|β| = 30°): 0.888 for the KVLCC2 (for comparison, Hoerner's two-dimensional
    cross-flow drag of a section of the KVLCC2's B/2T = 1.39 is about 0.74, read from the curve
    of C_D against B/2T of Leite et al. 1998 as digitized in Fossen's MSS, ``HYDRO/Hoerner.m``;
    a 3-D hull has end effects both ways).

Range
    Yoshimura et al. built the model for harbour manoeuvring, large drift angles and turning
    at low forward speed, and applied it to captive tests of several ship models over "a very
    wide range of manoeuvring motion" (abstract). The model neglects wave-making (the
    resistance coefficient is a constant), so its stated range here is Froude number
    Fn = U/√(gL) ≤ :data:`FROUDE_MAX` (0.10) wherever it contributes (:func:`low_speed_weight`
    > 0); outside, :func:`check_range` warns (:class:`~seahelm.errors.ValidityRangeWarning`,
    an error in strict mode).

References
----------
Yoshimura, Y., Nakao, I. & Ishibashi, A. (2009). Unified mathematical model for ocean and
harbour manoeuvring. Proc. MARSIM 2009, Panama City, M3-1–M3-9.
Miyauchi, Y., Maki, A., Umeda, N., Rachman, D. M. & Akimoto, Y. (2022). System parameter
exploration of ship maneuvering model for automatic docking/berthing using CMA-ES. J. Mar.
Sci. Technol. 27, 1065–1083.
Hooft, J. P. (1994). The cross flow drag on a manoeuvring ship. Ocean Eng. 21(3), 329–342.
Leite, A. J. P., Aranha, J. A. P., Umeda, C. & de Conti, M. B. (1998). Current force in
tankers and bifurcation of equilibrium of turret systems: hydrodynamic model and experiments.
Applied Ocean Research 20.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..constants import GRAVITY
from ..errors import ParameterError, warn_validity

__all__ = ["cross_flow_integrals", "low_speed_hull", "low_speed_weight",
           "matching_cross_flow_drag", "check_range", "DRIFT_MMG", "DRIFT_LOW_SPEED",
           "YAW_RATE_MMG", "YAW_RATE_LOW_SPEED", "FROUDE_MAX"]

#: |β| [rad] up to which the MMG hull polynomials are used alone (their fitted range).
DRIFT_MMG = math.radians(30.0)
_TAN_DRIFT_MMG = math.tan(DRIFT_MMG)
#: |β| [rad] from which the cross-flow model is used alone (linear blend in between).
DRIFT_LOW_SPEED = math.radians(45.0)
#: |r'| = |r| L / U up to which the MMG polynomials are used alone.
YAW_RATE_MMG = 1.0
#: |r'| from which the cross-flow model is used alone.
YAW_RATE_LOW_SPEED = 1.5
#: Largest Froude number at which the cross-flow model is stated valid (module docstring).
FROUDE_MAX = 0.10


@njit(cache=True)
def _piece(a, b, lo, hi, sign):  # pragma: no cover - compiled
    """sign × (∫ (a + b x)² dx, ∫ x (a + b x)² dx) over [lo, hi]."""
    fy = (a * a * (hi - lo) + a * b * (hi * hi - lo * lo)
          + b * b * (hi * hi * hi - lo * lo * lo) / 3.0)
    fn = (a * a * (hi * hi - lo * lo) / 2.0 + 2.0 * a * b * (hi ** 3 - lo ** 3) / 3.0
          + b * b * (hi ** 4 - lo ** 4) / 4.0)
    return sign * fy, sign * fn


@njit(cache=True)
def cross_flow_integrals(a, b):  # pragma: no cover - compiled
    """∫ |a + b x|(a + b x) dx and ∫ x |a + b x|(a + b x) dx over x in [−½, ½], exactly.

    Parameters
    ----------
    a : float
        Constant part of the cross-flow velocity (v) [m/s].
    b : float
        Its slope over the length (C_r r L) [m/s].

    Returns
    -------
    tuple of float
        (I_Y, I_N) [m²/s²].
    """
    lo, hi = -0.5, 0.5
    # the sign of a + b x at each end; split at the zero x0 = −a/b if it is inside
    s_lo = a + b * lo
    s_hi = a + b * hi
    if s_lo >= 0.0 and s_hi >= 0.0:
        return _piece(a, b, lo, hi, 1.0)
    if s_lo <= 0.0 and s_hi <= 0.0:
        return _piece(a, b, lo, hi, -1.0)
    x0 = -a / b
    y1, n1 = _piece(a, b, lo, x0, 1.0 if s_lo > 0.0 else -1.0)
    y2, n2 = _piece(a, b, x0, hi, 1.0 if s_hi > 0.0 else -1.0)
    return y1 + y2, n1 + n2


@njit(cache=True)
def low_speed_hull(u, v, r, L, d, rho, X_0F, X_0A, X_vr, Y_v, Y_r, N_v, N_r, C_D, C_rY,
                   C_rN):  # pragma: no cover - compiled
    """(X_H, Y_H, N_H) [N, N, N·m] of the cross-flow model (module docstring).

    Parameters
    ----------
    u, v : float
        Surge and sway speed of midship [m/s].
    r : float
        Yaw rate [rad/s].
    L, d : float
        Length between perpendiculars and draught [m].
    rho : float
        Water density [kg/m³].
    X_0F, X_0A : float
        Surge-force coefficients ahead (−R'_0) and astern (−R'_0,astern) [-].
    X_vr, Y_v, Y_r, N_v, N_r : float
        Linear derivatives (the MMG's) [-].
    C_D : float
        Cross-flow drag coefficient [-].
    C_rY, C_rN : float
        Yaw-rate correction factors of the cross-flow in Y and N [-].

    Returns
    -------
    tuple of float
    """
    speed = math.sqrt(u * u + v * v)
    beta = math.atan2(-v, u)
    q = 0.5 * rho * L * d
    X_0 = X_0F + (X_0A - X_0F) * abs(beta) / math.pi
    X = q * (X_0 * u * speed + X_vr * v * r * L)
    iy, _in = cross_flow_integrals(v, C_rY * r * L)
    _iy, i_n = cross_flow_integrals(v, C_rN * r * L)
    Y = q * (Y_v * v * abs(u) + Y_r * u * r * L - C_D * iy)
    N = q * L * (N_v * u * v + N_r * abs(u) * r * L - C_D * i_n)
    return X, Y, N


@njit(cache=True)
def low_speed_weight(u, v, r, L, u_floor):  # pragma: no cover - compiled
    """Share w in [0, 1] of the cross-flow model in the hull forces (1 − w the MMG's).

    0 while |β| ≤ 30° and |r'| ≤ 1 (the MMG's range), 1 from |β| ≥ 45° or |r'| ≥ 1.5, linear
    in |β| and in |r'| in between (the larger share of the two); r' = r L / max(U, u_floor).

    Parameters
    ----------
    u, v : float
        Surge and sway speed [m/s].
    r : float
        Yaw rate [rad/s].
    L : float
        Length [m].
    u_floor : float
        Smallest speed of the non-dimensional r' [m/s] (the MMG's Fn_min √(gL)).

    Returns
    -------
    float
    """
    s2 = u * u + v * v
    rl = r * L
    if (u > 0.0 and abs(v) <= _TAN_DRIFT_MMG * u
            and rl * rl <= YAW_RATE_MMG * YAW_RATE_MMG * max(s2, u_floor * u_floor)):
        return 0.0  # inside the MMG's range (the usual case: no square root, no atan2)
    speed = math.sqrt(s2)
    beta = abs(math.atan2(-v, u))
    rn = abs(rl) / max(speed, u_floor)
    wb = min(max((beta - DRIFT_MMG) / (DRIFT_LOW_SPEED - DRIFT_MMG), 0.0), 1.0)
    wr = min(max((rn - YAW_RATE_MMG) / (YAW_RATE_LOW_SPEED - YAW_RATE_MMG), 0.0), 1.0)
    return max(wb, wr)


def matching_cross_flow_drag(Y_v: float, Y_vvv: float, drift: float = DRIFT_MMG) -> float:
    """The C_D for which the cross-flow model's sway force in steady drift (r = 0) equals the
    MMG polynomial's, Y'_v v' + Y'_vvv v'³, at the drift angle ``drift`` (v' = −sin β).

    Parameters
    ----------
    Y_v : float
        MMG Y'_v [-].
    Y_vvv : float
        MMG Y'_vvv [-].
    drift : float, optional
        Drift angle β [rad] where they meet, in (0, π/2) (default 30°).

    Returns
    -------
    float
        C_D [-].

    Raises
    ------
    ParameterError
        If the match gives C_D ≤ 0 (the polynomial's nonlinear sway force does not resist the
        drift), naming ``Y_vvv``.
    """
    if not 0.0 < drift < 0.5 * math.pi:
        raise ParameterError(f"must be in (0, pi/2) [rad], got {drift!r}", field="drift",
                             unit="rad", value=drift)
    vn = -math.sin(drift)
    mmg = Y_v * vn + Y_vvv * vn ** 3
    c_d = (mmg - Y_v * vn * math.cos(drift)) / (-vn * abs(vn))
    if not (math.isfinite(c_d) and c_d > 0.0):
        raise ParameterError(
            f"no positive cross-flow drag matches the MMG sway force at {math.degrees(drift):g}"
            f" deg of drift (Y_v={Y_v!r}, Y_vvv={Y_vvv!r} give C_D = {c_d:.4g}): give "
            "cross_flow_drag", field="Y_vvv", unit="-", value=Y_vvv)
    return float(c_d)


def check_range(speed, drift, yaw_rate, length: float, u_floor: float, *, where: str = "",
                strict: bool | None = None, stacklevel: int = 3) -> np.ndarray:
    """Which runs used the cross-flow model above Fn = :data:`FROUDE_MAX`; warn if any did.

    Parameters
    ----------
    speed : array_like
        Speed through the water U [m/s], shape (runs, samples) (or (samples,)).
    drift : array_like
        Drift angle β [rad], same shape.
    yaw_rate : array_like
        Yaw rate [rad/s], same shape.
    length : float or array_like
        L_pp [m] (per run: shape (runs,)).
    u_floor : float or array_like
        Smallest speed of r' [m/s] (per run: shape (runs,)).
    where : str, optional
        What the runs were (for the message).
    strict : bool, optional
        Raise instead of warning (default: the global strict mode).
    stacklevel : int, optional
        Passed to :func:`warnings.warn`.

    Returns
    -------
    numpy.ndarray
        bool per run (shape (runs,), or a scalar for one series): outside the range.
    """
    U = np.atleast_2d(np.asarray(speed, dtype=float))
    beta = np.abs(np.atleast_2d(np.asarray(drift, dtype=float)))
    r = np.abs(np.atleast_2d(np.asarray(yaw_rate, dtype=float)))
    L = np.asarray(length, dtype=float).reshape(-1, 1)
    floor = np.asarray(u_floor, dtype=float).reshape(-1, 1)
    rn = r * L / np.maximum(U, floor)
    share = (beta > DRIFT_MMG) | (rn > YAW_RATE_MMG)
    fn = U / np.sqrt(GRAVITY * L)
    outside = np.any(share & (fn > FROUDE_MAX), axis=1)
    if outside.any():
        worst = float(np.max(np.where(share, fn, 0.0)))
        warn_validity(
            f"{int(outside.sum())} of {outside.size} run(s){' of ' + where if where else ''} "
            f"use the low-speed cross-flow hull (Yoshimura et al. 2009; |drift| > 30 deg or "
            f"|r'| > 1) at Fn up to {worst:.3g} > {FROUDE_MAX:g}, its stated range (low speed, "
            "no wave-making)", strict=strict, stacklevel=stacklevel)
    return outside if np.ndim(speed) > 1 else outside[0]
