"""Shallow-water corrections of the MMG coefficients for a water depth h.

The set collected by Taimuri et al. (2020) for the MMG model, as implemented in the open
``mmgdynamics`` (v1.0.8, ``_shallow_water_hdm``); formulas carried over, not code. With
d the draught, t = d/h, H = h/d − 1 and B_1 = C_b B (1 + B/L)² (all in metres):

Ankudinov's depth functions::

    K_0 = 1 + 0.0775/H² − 0.011/H³ + 0.000068/H⁵
    K_1 = −0.0643/H + 0.0724/H² − 0.0113/H³ + 0.0000767/H⁵
    K_2 = 0.0342/H (B/d ≤ 4),  0.137 B/(H d) (B/d > 4)
    f_yr = K_0 + 2/5 K_1 B_1/d + 24/105 K_2 (B_1/d)²,  f_nr = K_0 + 1/2 K_1 B_1/d + 1/3 K_2 (B_1/d)²
    f_yv = 1.5 f_nr − 0.5,  f_nv = K_0 + K_1 B_1/d + K_2 (B_1/d)²
    g_v  = K_0 + 2/3 K_1 B_1/d + 8/15 K_2 (B_1/d)²,  g_nr = K_0 + 8/15 K_1 B_1/d + 40/105 K_2 (B_1/d)²

Two sets are registered (:data:`LINEAR_SETS`), differing in the four linear derivatives and
the two cross terms of the yaw moment N'_vvr, N'_vrr:

``"ankudinov"`` (the default): Ankudinov's own factors, Y'_v × f_yv, Y'_r × f_yr, N'_v × f_nv,
N'_r × f_nr, and N'_vvr, N'_vrr × f_nv (seahelm's choice: the factor of the sway-induced yaw
moment they extend). With them the KVLCC2's tactical diameter grows steadily as the depth
falls (h/d 2.0, 1.5, 1.2; the docs' validation).

``"kijima"`` (the transcription's choice): Kijima et al.'s (1990) corrections for Y'_v, Y'_r,
N'_r, N'_vvr, N'_vrr and Ankudinov's f_nv for N'_v::

    Y'_v × [1/(1 − t)^(0.4 C_b B/d) − t],   N'_r × [1/(1 − t)^(1.5 − 14.28 d/L) − t]
    Y'_r, N'_vvr, N'_vrr × (1 + A_1 t + A_2 t² + A_3 t³)   (A_i quadratics in C_b B/d, C_b d/B)

With it N'_r barely grows at moderate depth (× 0.99 at h/d = 2 for the KVLCC2) while N'_v
grows by 40 %, so the KVLCC2 turns *tighter* at h/d = 2 than in deep water (2.9 L against
3.1 L), and Kijima's cubic multiplies N'_vrr by 5.7 at h/d = 1.43 for a C_b 0.7 cargo ship,
which with the negative N'_vrr of Yoshimura & Masumoto's regression makes the ship spin up
in a 35° turn: kept so the published set can be reproduced, not the default.

Both: X'_vv, X'_vvvv, Y'_vvv, N'_vvv, Y'_vvr, Y'_vrr × f_yv; X'_rr × f_nr; X'_vr × f_yr;
Y'_rrr, N'_rrr × g_nr; the added masses m'_y × g_v and J'_z × g_nr (Ankudinov's factors for
the sway added mass and the yaw added inertia, which the transcription computes but does not
apply; m'_x unchanged); the wake fraction, thrust deduction and flow-straightening
coefficient by the regressions of the same set.

Range: 1.2 ≤ h/d (warned below, an error at h ≤ d). Deep water, h = ∞, changes nothing; at a
finite but large depth every factor tends to 1 except the thrust deduction's, which tends to
1 + 0.004 (29.495 − 14.089 C_b L/B + 1.6486 (C_b L/B)²) (a property of the regression: 0.998
for the KVLCC2).

References
----------
Taimuri, G., Matusiak, J., Mikkola, T., Kujala, P., Hirdaris, S. (2020). A 6-DoF maneuvering
model for the rapid estimation of hydrodynamic actions in deep and shallow waters. Ocean Eng.
218, 108103.
Kijima, K., Nakiri, Y., Tsutsui, Y., Matsunaga, M. (1990). Prediction method of ship
manoeuvrability in deep and shallow waters. MARSIM & ICSM 90, Tokyo.
Ankudinov, V., Miller, E.R., Jakobsen, B.K., Daggett, L.L. (1990). Manoeuvring performance of
tug/barge assemblies in restricted waterways. MARSIM & ICSM 90, Tokyo.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..errors import ParameterError
from .hull import HullParticulars, check_ranges

__all__ = ["shallow_water_factors", "shallow_water_coefficients", "MIN_DEPTH_RATIO",
           "CORRECTED", "LINEAR_SETS"]

#: The sets of factors on Y'_v, Y'_r, N'_v, N'_r (module docstring); the first is the default.
LINEAR_SETS = ("ankudinov", "kijima")

#: Lower end of the data range of the corrections, h/d.
MIN_DEPTH_RATIO = 1.2

SOURCE = "Taimuri et al. (2020) shallow-water set"

#: The MMGParams fields the corrections change.
CORRECTED = ("X_vv", "X_vvvv", "X_rr", "X_vr", "Y_v", "Y_r", "Y_vvv", "Y_vvr", "Y_vrr", "Y_rrr",
             "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr", "m_y", "J_z", "w_P0", "t_P",
             "gamma_R_minus", "gamma_R_plus")


def _check_depth(hull: HullParticulars, depth: float, strict: bool | None) -> float:
    h = float(depth)
    if math.isnan(h) or not h > hull.draft:
        raise ParameterError(f"must be greater than the draft {hull.draft!r} [m], got {depth!r}",
                             field="water_depth", unit="m", value=depth)
    check_ranges(f"{SOURCE} (Kijima, Ankudinov)", {"h/d": (h / hull.draft, MIN_DEPTH_RATIO,
                                                           math.inf)},
                 strict=strict, stacklevel=4)
    return h


def shallow_water_factors(hull: HullParticulars, depth: float, *, linear: str = "ankudinov",
                          strict: bool | None = None) -> dict[str, float]:
    """The factor on each MMG coefficient at water depth ``depth`` (module docstring).

    Parameters
    ----------
    hull : HullParticulars
        The hull (L, B, d, C_b).
    depth : float
        Water depth h [m], > d; ``inf`` for deep water (every factor 1).
    linear : {"ankudinov", "kijima"}
        The factors on the linear derivatives (:data:`LINEAR_SETS`).
    strict : bool, optional
        Raise instead of warning below h/d = 1.2.

    Returns
    -------
    dict of str to float
        Factor per field of :data:`CORRECTED`, except ``t_P`` whose correction is on 1 − t_P
        (the factor given multiplies 1 − t_P).
    """
    if linear not in LINEAR_SETS:
        raise ValueError(f"unknown set of linear shallow-water factors '{linear}'; valid: "
                         f"{', '.join(LINEAR_SETS)}")
    h = _check_depth(hull, depth, strict)
    if math.isinf(h):
        return {name: 1.0 for name in CORRECTED}
    L, B, T, cb = hull.length, hull.beam, hull.draft, hull.block_coefficient
    H = h / T - 1.0
    t = T / h
    K0 = 1 + 0.0775 / H ** 2 - 0.011 / H ** 3 + 0.000068 / H ** 5
    K1 = -0.0643 / H + 0.0724 / H ** 2 - 0.0113 / H ** 3 + 0.0000767 / H ** 5
    K2 = 0.0342 / H if B / T <= 4 else 0.137 * B / (H * T)
    b1 = cb * B * (1 + B / L) ** 2 / T
    g_v = K0 + 2 / 3 * K1 * b1 + 8 / 15 * K2 * b1 ** 2
    g_nr = K0 + 8 / 15 * K1 * b1 + 40 / 105 * K2 * b1 ** 2
    f_yr = K0 + 2 / 5 * K1 * b1 + 24 / 105 * K2 * b1 ** 2
    f_nr = K0 + 1 / 2 * K1 * b1 + 1 / 3 * K2 * b1 ** 2
    f_yv = 1.5 * f_nr - 0.5
    f_nv = K0 + K1 * b1 + K2 * b1 ** 2
    cbt = cb * B / T
    a_yr = (-5.5 * cbt ** 2 + 26 * cbt - 31.5, 37 * cbt ** 2 - 185 * cbt + 230,
            -38 * cbt ** 2 + 197 * cbt - 250)
    a_nvvr = (91 * cb * T / B - 25, -515 * cb * T / B + 144, 508 * cb * T / B - 143)
    a_nvrr = (40 * cb * B / T - 88, -295 * cb * B / T + 645, 312 * cb * B / T - 678)

    def cubic(a: tuple[float, float, float]) -> float:
        return 1 + a[0] * t + a[1] * t ** 2 + a[2] * t ** 3

    cl_t = cb * L / T
    cl_b = cb * L / B
    cbl = cb * B / L
    wake = 1 + (-4.932 + 0.6425 * cl_t - 0.0165 * cl_t ** 2) * t ** 1.655
    thrust = 1 + ((29.495 - 14.089 * cl_b + 1.6486 * cl_b ** 2)
                  * (1 / 250 - 7 * t / 200 - 13 * t ** 2 / 125))
    if t <= -0.332 * T / B + 0.581:
        gamma = 1 + (-541 / 4 + 2432.95 * cbl - 10137.7 * cbl ** 2) * t ** 4.81
    else:
        gamma = 1 + ((-5129 / 500 + 178.207 * cbl - 2745 / 4 * cbl ** 2)
                     * (-1927 / 500 + 2733 * t / 200 - 2617 * t ** 2 / 250))
    if linear == "ankudinov":
        lin = {"Y_v": f_yv, "Y_r": f_yr, "N_v": f_nv, "N_r": f_nr, "N_vvr": f_nv, "N_vrr": f_nv}
    else:
        lin = {"Y_v": 1 / (1 - t) ** (0.4 * cbt) - t, "Y_r": cubic(a_yr), "N_v": f_nv,
               "N_r": 1 / (1 - t) ** (1.5 - 14.28 * T / L) - t, "N_vvr": cubic(a_nvvr),
               "N_vrr": cubic(a_nvrr)}
    return {
        "X_vv": f_yv, "X_vvvv": f_yv, "X_rr": f_nr, "X_vr": f_yr,
        "Y_vvv": f_yv, "Y_vvr": f_yv, "Y_vrr": f_yv, "Y_rrr": g_nr,
        "N_vvv": f_yv, "N_rrr": g_nr, **lin,
        "m_y": g_v, "J_z": g_nr, "w_P0": wake, "t_P": thrust,
        "gamma_R_minus": gamma, "gamma_R_plus": gamma,
    }


def shallow_water_coefficients(coefficients: Mapping[str, float], hull: HullParticulars,
                               depth: float, *, linear: str = "ankudinov",
                               strict: bool | None = None) -> dict[str, float]:
    """MMG coefficients at water depth ``depth`` from their deep-water values.

    Parameters
    ----------
    coefficients : mapping of str to float
        Deep-water values by :class:`~seahelm.vessels.mmg.MMGParams` field name; the fields of
        :data:`CORRECTED` present are corrected, the others returned as given.
    hull : HullParticulars
        The hull.
    depth : float
        Water depth h [m] (``inf``: deep water, the values unchanged).
    linear : {"ankudinov", "kijima"}
        The factors on the linear derivatives (:data:`LINEAR_SETS`).
    strict : bool, optional
        Raise instead of warning below h/d = 1.2.

    Returns
    -------
    dict of str to float
    """
    factors = shallow_water_factors(hull, depth, linear=linear, strict=strict)
    out = dict(coefficients)
    if math.isinf(float(depth)):
        return out
    for name, factor in factors.items():
        if name not in out:
            continue
        if name == "t_P":
            out[name] = 1.0 - factor * (1.0 - out[name])
        else:
            out[name] = out[name] * factor
    return out
