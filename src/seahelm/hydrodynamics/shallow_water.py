"""Shallow-water corrections of the MMG coefficients for a water depth h.

Hull forces and added masses: the set collected by Taimuri et al. (2020) for the MMG model, as
implemented in the open ``mmgdynamics`` (v1.0.8, ``_shallow_water_hdm``); formulas carried
over, not code. Resistance: Lackenby (1963). With d the draught, t = d/h, H = h/d − 1 and
B_1 = C_b B (1 + B/L)² (all in metres):

Ankudinov's depth functions::

    K_0 = 1 + 0.0775/H² − 0.011/H³ + 0.000068/H⁵
    K_1 = −0.0643/H + 0.0724/H² − 0.0113/H³ + 0.0000767/H⁵
    K_2 = 0.0342/H (B/d ≤ 4),  0.137 d/(H B) (B/d > 4)
    f_yr = K_0 + 2/5 K_1 B_1/d + 24/105 K_2 (B_1/d)²,  f_nr = K_0 + 1/2 K_1 B_1/d + 1/3 K_2 (B_1/d)²
    f_yv = 1.5 f_nr − 0.5,  f_nv = K_0 + K_1 B_1/d + K_2 (B_1/d)²
    g_v  = K_0 + 2/3 K_1 B_1/d + 8/15 K_2 (B_1/d)²,  g_nr = K_0 + 8/15 K_1 B_1/d + 40/105 K_2 (B_1/d)²

(The transcription has 0.137 B/(H d) for B/d > 4, sixteen times the other branch at B/d = 4;
0.137 d/(H B) joins the two branches, 0.137/4 = 0.0342, and is taken here. Neither the KVLCC2
nor the tankers and cargo ships of the docs have B/d > 4.)

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
grows by 40 %, so the KVLCC2 turns *tighter* at h/d = 2 than in deep water (2.7 L against
3.1 L), and Kijima's cubic multiplies N'_vrr by 5.7 at h/d = 1.43 for a C_b 0.7 cargo ship,
which with the negative N'_vrr of Yoshimura & Masumoto's regression makes the ship spin up
in a 35° turn: kept so the published set can be reproduced, not the default.

Both: X'_vv, X'_vvvv, Y'_vvv, N'_vvv, Y'_vvr, Y'_vrr × f_yv; X'_rr × f_nr; X'_vr × f_yr;
Y'_rrr, N'_rrr × g_nr; the added masses m'_y × g_v and J'_z × g_nr (Ankudinov's factors for
the sway added mass and the yaw added inertia, which the transcription computes but does not
apply; m'_x unchanged); the flow-straightening coefficient γ_R by the regression of the same
set (it peaks near h/d = 1.5: × 1.67 for the KVLCC2, × 1.29 at h/d = 1.2).

Resistance (every set): R'_0 × 1/(1 − ΔV/V_∞)², with Lackenby's (1963) speed loss
(:func:`lackenby_speed_loss`; ITTC Recommended Procedure 7.5-04-01-01.2 (2014), the
shallow-water correction of speed trials)::

    ΔV/V_∞ = 0.1242 (A_M/h² − 0.05) + 1 − (tanh(g h/V_∞²))^½      (A_M/h² ≥ 0.05; else the
                                                                  first term 0)

the speed at which the ship in depth h meets the resistance it meets at V_∞ in deep water
(Schlichting 1934; Lackenby's fit of his charts), so with R'_0 constant R'_0,h = R'_0 (V_∞/V_h)².
A_M = C_M B d with C_M of Kerlen (1970); V_∞ is the parameter set's test speed
(``approach_speed``), the tanh term being below 0.4 % of speed at depth Froude numbers up to
0.6.
R'_0 × 1.06, 1.16, 1.33, 1.62 at h/d = 3, 2, 1.5, 1.2 for the 304.8 m tanker of Van Berlekom &
Goddard (1972), against 1.08, 1.16, 1.32, 1.81 by their model (Fossen's MSS ``tanker.m``:
X_uu + X_uuz d/(h − d)). Warned at a depth Froude number V_∞/√(g h) > 1, where the subcritical
argument has no meaning.

Wake fraction and thrust deduction (:data:`PROPULSION_SETS`): ``"deep"`` (the default) keeps
the deep-water w_P0 and t_P, as Van Berlekom & Goddard's shallow-water model keeps its
propeller thrust; ``"taimuri"`` applies the regressions of the Taimuri et al. set,
w_P0 × [1 + (−4.932 + 0.6425 C_b L/d − 0.0165 (C_b L/d)²) t^1.655] and (1 − t_P) × [1 +
(29.495 − 14.089 C_b L/B + 1.6486 (C_b L/B)²)(1/250 − 7t/200 − 13t²/125)]. Not the default:
with the published resistance increases (Lackenby's, or Van Berlekom & Goddard's)
the wake increase outweighs it at moderate depth, so at a fixed propeller rps an estimated
304.8 m tanker runs *faster* at h/d = 2–4 than in deep water (8.32 against 8.23 m/s at h/d = 3),
which ships do not; it also halves the rudder's inflow at h/d = 1.2 and doubles the tactical
diameter. The thrust-deduction regression also does not tend to 1 in deep water (1 + 0.004
(29.495 − 14.089 C_b L/B + 1.6486 (C_b L/B)²)). Their source's data range was not available
to check.

Range: 1.2 ≤ h/d (warned below, an error at h ≤ d). Deep water, h = ∞, changes nothing; at a
finite but large depth every factor tends to 1 (with ``"taimuri"``, except the thrust
deduction's).

References
----------
Taimuri, G., Matusiak, J., Mikkola, T., Kujala, P., Hirdaris, S. (2020). A 6-DoF maneuvering
model for the rapid estimation of hydrodynamic actions in deep and shallow waters. Ocean Eng.
218, 108103.
Kijima, K., Nakiri, Y., Tsutsui, Y., Matsunaga, M. (1990). Prediction method of ship
manoeuvrability in deep and shallow waters. MARSIM & ICSM 90, Tokyo.
Ankudinov, V., Miller, E.R., Jakobsen, B.K., Daggett, L.L. (1990). Manoeuvring performance of
tug/barge assemblies in restricted waterways. MARSIM & ICSM 90, Tokyo.
Lackenby, H. (1963). The effect of shallow water on ship speed. The Shipbuilder and Marine
Engine-Builder 70, 446–450.
ITTC (2014). Recommended Procedures and Guidelines 7.5-04-01-01.2, Speed and power trials,
part 2: analysis of speed/power trial data.
Van Berlekom, W.B., Goddard, T.A. (1972). Maneuvering of large tankers. Trans. SNAME 80,
264–298.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from .._validate import lookup_name
from ..errors import ParameterError
from ..constants import GRAVITY
from .hull import HullParticulars, check_ranges

__all__ = ["shallow_water_factors", "shallow_water_coefficients", "lackenby_speed_loss",
           "MIN_DEPTH_RATIO", "CORRECTED", "LINEAR_SETS", "PROPULSION_SETS"]

#: The sets of factors on Y'_v, Y'_r, N'_v, N'_r (module docstring); the first is the default.
LINEAR_SETS = ("ankudinov", "kijima")

#: The sets of factors on the wake fraction and thrust deduction (module docstring); the first
#: is the default.
PROPULSION_SETS = ("deep", "taimuri")

#: Lower end of the data range of the corrections, h/d.
MIN_DEPTH_RATIO = 1.2

SOURCE = "Taimuri et al. (2020) shallow-water set"

#: The MMGParams fields the corrections change.
CORRECTED = ("R_0", "X_vv", "X_vvvv", "X_rr", "X_vr", "Y_v", "Y_r", "Y_vvv", "Y_vvr", "Y_vrr",
             "Y_rrr", "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr", "m_y", "J_z", "w_P0",
             "t_P", "gamma_R_minus", "gamma_R_plus")


def lackenby_speed_loss(hull: HullParticulars, depth: float,
                        speed: float | None = None) -> float:
    """Lackenby's (1963) speed loss in shallow water, ΔV/V_∞ (module docstring).

    ΔV/V_∞ = 0.1242 (A_M/h² − 0.05) + 1 − (tanh(g h/V_∞²))^½ (ITTC 7.5-04-01-01.2 (2014),
    the shallow-water correction of speed trials), with the midship-section area A_M = C_M B d
    and C_M = 1.006 − 0.0056 C_b^−3.56 (Kerlen 1970, as :attr:`HullForm.midship
    <seahelm.hydrodynamics.hull_form.HullForm.midship>`). Stated for A_M/h² ≥ 0.05: below, the
    first term is taken as 0 (the correction fades out, continuously).

    Parameters
    ----------
    hull : HullParticulars
    depth : float
        Water depth h [m] (``inf``: 0).
    speed : float, optional
        Deep-water speed V_∞ [m/s]; omitted, the low-speed limit (the tanh term 0).

    Returns
    -------
    float
        ΔV/V_∞ [-]: the ship at V_∞ (1 − ΔV/V_∞) in depth h meets the resistance it meets at
        V_∞ in deep water.
    """
    h = float(depth)
    if math.isinf(h):
        return 0.0
    cb = hull.block_coefficient
    cm = min(1.006 - 0.0056 * cb ** -3.56, 0.999)
    area = cm * hull.beam * hull.draft
    loss = 0.1242 * max(area / h ** 2 - 0.05, 0.0)
    if speed is not None and speed > 0.0:
        loss += 1.0 - math.sqrt(math.tanh(GRAVITY * h / speed ** 2))
    return loss


def _check_depth(hull: HullParticulars, depth: float, strict: bool | None) -> float:
    h = float(depth)
    if math.isnan(h) or not h > hull.draft:
        raise ParameterError(f"must be greater than the draft {round(hull.draft, 12)!r} [m], "
                             f"got {depth!r}",
                             field="water_depth", unit="m", value=depth)
    check_ranges(f"{SOURCE} (Kijima, Ankudinov)", {"h/d": (h / hull.draft, MIN_DEPTH_RATIO,
                                                           math.inf)},
                 strict=strict, stacklevel=4)
    return h


def shallow_water_factors(hull: HullParticulars, depth: float, *, linear: str = "ankudinov",
                          propulsion: str = "deep", speed: float | None = None,
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
    propulsion : {"deep", "taimuri"}
        The factors on the wake fraction and thrust deduction (:data:`PROPULSION_SETS`).
    speed : float, optional
        The deep-water speed V_∞ [m/s] at which Lackenby's resistance factor is taken (default:
        its low-speed limit).
    strict : bool, optional
        Raise instead of warning below h/d = 1.2.

    Returns
    -------
    dict of str to float
        Factor per field of :data:`CORRECTED`, except ``t_P`` whose correction is on 1 − t_P
        (the factor given multiplies 1 − t_P).
    """
    lookup_name("set of linear shallow-water factors", LINEAR_SETS, linear)
    lookup_name("set of shallow-water propulsion factors", PROPULSION_SETS, propulsion)
    h = _check_depth(hull, depth, strict)
    if math.isinf(h):
        return {name: 1.0 for name in CORRECTED}
    L, B, T, cb = hull.length, hull.beam, hull.draft, hull.block_coefficient
    H = h / T - 1.0
    t = T / h
    K0 = 1 + 0.0775 / H ** 2 - 0.011 / H ** 3 + 0.000068 / H ** 5
    K1 = -0.0643 / H + 0.0724 / H ** 2 - 0.0113 / H ** 3 + 0.0000767 / H ** 5
    K2 = 0.0342 / H if B / T <= 4 else 0.137 * T / (H * B)  # continuous at B/T = 4
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
    if propulsion == "deep":
        wake = thrust = 1.0
    if speed is not None:
        check_ranges("Lackenby (1963) shallow-water resistance",
                     {"V/√(g h)": (speed / math.sqrt(GRAVITY * h), 0.0, 1.0)},
                     strict=strict, stacklevel=3)
    resistance = 1.0 / (1.0 - lackenby_speed_loss(hull, h, speed)) ** 2
    return {
        "R_0": resistance, "X_vv": f_yv, "X_vvvv": f_yv, "X_rr": f_nr, "X_vr": f_yr,
        "Y_vvv": f_yv, "Y_vvr": f_yv, "Y_vrr": f_yv, "Y_rrr": g_nr,
        "N_vvv": f_yv, "N_rrr": g_nr, **lin,
        "m_y": g_v, "J_z": g_nr, "w_P0": wake, "t_P": thrust,
        "gamma_R_minus": gamma, "gamma_R_plus": gamma,
    }


def shallow_water_coefficients(coefficients: Mapping[str, float], hull: HullParticulars,
                               depth: float, *, linear: str = "ankudinov",
                               propulsion: str = "deep",
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
    propulsion : {"deep", "taimuri"}
        The factors on the wake fraction and thrust deduction (:data:`PROPULSION_SETS`).
    strict : bool, optional
        Raise instead of warning below h/d = 1.2.

    Returns
    -------
    dict of str to float
        R'_0 is corrected at the deep-water test speed ``approach_speed`` when the mapping has
        it (Lackenby's tanh term), else at the low-speed limit.
    """
    speed = coefficients.get("approach_speed")
    factors = shallow_water_factors(hull, depth, linear=linear, propulsion=propulsion,
                                    speed=None if speed is None else float(speed),
                                    strict=strict)
    out = dict(coefficients)
    if math.isinf(float(depth)):
        return out
    for name, factor in factors.items():
        if name not in out or factor == 1.0:  # (1 − (1 − t_P) is not t_P to the last bit)
            continue
        if name == "t_P":
            out[name] = 1.0 - factor * (1.0 - out[name])
        else:
            out[name] = out[name] * factor
    return out
