"""Rudder and propeller of the MMG model from their particulars and the hull's.

Rudder lift slope (Fujii & Tsuda 1961), with the aspect ratio Λ = H_R²/A_R::

    f_α = 6.13 Λ / (Λ + 2.25)

Hull–rudder–propeller interaction, each a regression on the hull's fullness (Kijima et al.
1990, as used in the MMG literature and transcribed in open implementations; the 1990 paper was
not available to us, so every one is also compared with the KVLCC2's captive values in the
docs)::

    1 − t_R = 0.28 C_b + 0.55                              (steering resistance deduction)
    a_H     = 0.627 C_b − 0.153                            (rudder force increase)
    ε       = −156.5 (C_b B/L)² + 41.6 C_b B/L − 1.76      (wake ratio (1 − w_R)/(1 − w_P))
    κ       = 0.55 − 0.8 C_b B/L                           (propeller-slipstream correction)
    γ_R     = 2.06 C_b B/L + 0.14                          (flow straightening, both signs)

Constants with no regression (seahelm's assumptions, said so in each coefficient's source):
x'_H = −0.45 (captive tests give −0.4…−0.5; KVLCC2 −0.464), l'_R = −0.9 (Yoshimura & Masumoto
2012's typical value), x'_R = −0.5 (rudder at the aft perpendicular), x'_P = −0.48, C_1 = 2.0,
C_2 = 1.6 / 1.1 (the KVLCC2's, Yasukawa & Yoshimura 2015).

Wake fraction in straight motion (Taylor, single screw): w_P0 = 0.5 C_b − 0.05.

Rudder size where not given: the minimum area of DNV's rules for ships,
A_R = (d L/100) [1 + 25 (B/L)²], and a span H_R = 0.75 d (KVLCC2: 0.76 d).

References
----------
Fujii, H., Tsuda, T. (1961). Experimental researches on rudder performance (2). J. Zosen
Kiokai 110, 31–42.
Kijima, K., Katsuno, T., Nakiri, Y., Furukawa, Y. (1990). On the manoeuvring performance of a
ship with the parameter of loading condition. J. Soc. Naval Arch. Japan 168, 141–148.
Taylor, D.W. (1933). The speed and power of ships. (w = 0.5 C_b − 0.05.)
DNV Rules for Classification of Ships, Pt. 3 Ch. 3 Sec. 2 (rudder area).
"""

from __future__ import annotations

import math

from ..errors import ParameterError
from .hull import Coefficient, HullParticulars, check_ranges

__all__ = ["rudder_lift_slope", "interaction_coefficients", "wake_fraction_taylor",
           "rudder_area_dnv"]

KIJIMA = "Kijima et al. (1990), as transcribed in open implementations"
ASSUMED = "seahelm assumption"


def rudder_lift_slope(span: float, area: float, *, strict: bool | None = None) -> Coefficient:
    """Rudder normal-force slope f_α = 6.13 Λ/(Λ + 2.25), Λ = H_R²/A_R (Fujii & Tsuda 1961).

    Parameters
    ----------
    span : float
        Rudder span H_R [m].
    area : float
        Movable rudder area A_R [m²].
    strict : bool, optional
        Raise instead of warning when Λ is outside 0.5–3 (Fujii's tests).

    Returns
    -------
    Coefficient
        f_α [-].
    """
    for name, value, unit in (("rudder_span", span, "m"), ("rudder_area", area, "m²")):
        if not value > 0:
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=name, unit=unit,
                                 value=value)
    aspect = span * span / area
    check_ranges("Fujii & Tsuda (1961) rudder lift slope", {"aspect ratio Λ": (aspect, 0.5, 3.0)},
                 strict=strict)
    return Coefficient(6.13 * aspect / (aspect + 2.25),
                       f"Fujii & Tsuda (1961): f_α = 6.13 Λ/(Λ + 2.25), Λ = H_R²/A_R = "
                       f"{aspect:.4g}")


def interaction_coefficients(hull: HullParticulars, *, strict: bool | None = None
                             ) -> dict[str, Coefficient]:
    """Hull–rudder–propeller interaction coefficients of the MMG model (module docstring).

    Parameters
    ----------
    hull : HullParticulars
        The hull.
    strict : bool, optional
        Raise instead of warning outside 0.06 ≤ C_b B/L ≤ 0.16, 0.48 ≤ C_b ≤ 0.85.

    Returns
    -------
    dict of str to Coefficient
        ``t_R``, ``a_H``, ``x_H``, ``epsilon``, ``kappa``, ``gamma_R_minus``, ``gamma_R_plus``,
        ``l_R``, ``x_R``, ``x_P``, ``C_1``, ``C_2_plus``, ``C_2_minus`` (MMGParams names).
    """
    cb = hull.block_coefficient
    cbl = hull.cb_b_over_l
    check_ranges("Kijima et al. (1990) interaction coefficients",
                 {"C_b": (cb, 0.48, 0.85), "C_b B/L": (cbl, 0.06, 0.16)}, strict=strict)
    _check_epsilon(hull)
    gamma = Coefficient(2.06 * cbl + 0.14, f"{KIJIMA}: γ_R = 2.06 C_b B/L + 0.14 (both signs "
                                           "of β_R)")
    kvlcc2 = "the KVLCC2's value (Yasukawa & Yoshimura 2015)"
    return {
        "t_R": Coefficient(1.0 - (0.28 * cb + 0.55), f"{KIJIMA}: 1 − t_R = 0.28 C_b + 0.55"),
        "a_H": Coefficient(0.627 * cb - 0.153, f"{KIJIMA}: a_H = 0.627 C_b − 0.153"),
        "x_H": Coefficient(-0.45, f"{ASSUMED}: x'_H = −0.45 (captive tests −0.4…−0.5; "
                                  "KVLCC2 −0.464)"),
        "epsilon": Coefficient(-156.5 * cbl ** 2 + 41.6 * cbl - 1.76,
                               f"{KIJIMA}: ε = −156.5 (C_b B/L)² + 41.6 C_b B/L − 1.76"),
        "kappa": Coefficient(0.55 - 0.8 * cbl, f"{KIJIMA}: κ = 0.55 − 0.8 C_b B/L"),
        "gamma_R_minus": gamma,
        "gamma_R_plus": gamma,
        "l_R": Coefficient(-0.9, f"{ASSUMED}: l'_R = −0.9, the typical value of Yoshimura & "
                                 "Masumoto (2012)"),
        "x_R": Coefficient(-0.5, f"{ASSUMED}: x'_R = −0.5 (rudder at the aft perpendicular)"),
        "x_P": Coefficient(-0.48, f"{ASSUMED}: x'_P = −0.48, {kvlcc2}"),
        "C_1": Coefficient(2.0, f"{ASSUMED}: C_1 = 2.0, {kvlcc2}"),
        "C_2_plus": Coefficient(1.6, f"{ASSUMED}: C_2 = 1.6 for β_P > 0, {kvlcc2}"),
        "C_2_minus": Coefficient(1.1, f"{ASSUMED}: C_2 = 1.1 for β_P < 0, {kvlcc2}"),
    }


#: The roots of Kijima et al. (1990)'s ε = −156.5 x² + 41.6 x − 1.76 (x = C_b B/L): ε > 0
#: only between them.
_EPSILON_ROOTS = tuple(sorted((41.6 + s * math.sqrt(41.6 ** 2 - 4 * 156.5 * 1.76)) / 313.0
                              for s in (-1.0, 1.0)))


def _check_epsilon(hull: HullParticulars) -> None:
    """Refuse a hull whose C_b B/L gives Kijima's ε <= 0, in the particulars' words."""
    cb, cbl = hull.block_coefficient, hull.cb_b_over_l
    eps = -156.5 * cbl ** 2 + 41.6 * cbl - 1.76
    if eps > 0:
        return
    lo, hi = _EPSILON_ROOTS
    raise ParameterError(
        f"the hull's C_b B/L = {cbl:.4g} (`block_coefficient` {cb:.4g}, `length`/`beam` "
        f"L/B = {hull.length / hull.beam:.4g}) gives the rudder's inflow ratio ε = {eps:.4g} "
        f"<= 0 (ε = −156.5 (C_b B/L)² + 41.6 C_b B/L − 1.76, {KIJIMA}): the formula needs "
        f"{lo:.4g} < C_b B/L < {hi:.4g}, for this C_b an L/B in ({cb / hi:.3g}, "
        f"{cb / lo:.3g})", field=None, unit="-", value=cbl)


def wake_fraction_taylor(hull: HullParticulars, *, strict: bool | None = None) -> Coefficient:
    """Wake fraction in straight motion, single screw: w_P0 = 0.5 C_b − 0.05 (Taylor).

    Parameters
    ----------
    hull : HullParticulars
        The hull.
    strict : bool, optional
        Raise instead of warning outside 0.48 ≤ C_b ≤ 0.85.

    Returns
    -------
    Coefficient
        w_P0 [-].
    """
    cb = hull.block_coefficient
    check_ranges("Taylor's wake fraction", {"C_b": (cb, 0.48, 0.85)}, strict=strict)
    return Coefficient(0.5 * cb - 0.05, "Taylor (1933), single screw: w_P0 = 0.5 C_b − 0.05")


def rudder_area_dnv(hull: HullParticulars) -> Coefficient:
    """The minimum rudder area of DNV's rules, A_R = (d L/100) [1 + 25 (B/L)²] [m²].

    Parameters
    ----------
    hull : HullParticulars
        The hull.

    Returns
    -------
    Coefficient
        A_R [m²].
    """
    bl = hull.beam / hull.length
    return Coefficient(hull.draft * hull.length / 100.0 * (1.0 + 25.0 * bl * bl),
                       "DNV rules' minimum rudder area: A_R = (d L/100)[1 + 25 (B/L)²]")
