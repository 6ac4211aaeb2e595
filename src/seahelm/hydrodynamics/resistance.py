"""Calm-water resistance, wake fraction and thrust deduction by Holtrop & Mennen (1982, 1984).

The total resistance of a displacement ship is split as (Holtrop 1984, p. 272)::

    R_total = R_F (1 + k_1) + R_APP + R_W + R_B + R_TR + R_A

with R_F the frictional resistance by the ITTC-1957 line, (1 + k_1) the hull form factor,
R_APP the appendage resistance, R_W the wave resistance, R_B the pressure resistance of a
bulbous bow near the surface, R_TR that of an immersed transom and R_A the model-ship
correlation resistance. :func:`holtrop_mennen` returns them named, in newtons, broadcast over
the speed; :func:`resistance_coefficient` turns the total into the MMG model's
R'_0 = R_T/(½ ρ L_pp d U²) (:class:`seahelm.vessels.mmg.MMGParams` ``R_0``).
:func:`wake_fraction` and :func:`thrust_deduction` are Holtrop's (1984) estimates of w and t for
single-screw ships (the MMG model's w_P0 and t_P).

Two variants are registered in :data:`METHODS` (a name or the object itself is accepted):

* ``"holtrop-1984"`` (default): the form factor and the wave resistance of Holtrop (1984),
  R_W-A for Fn ≤ 0.4 (c_1, c_2, c_5, m_1, m_4, λ), R_W-B for Fn ≥ 0.55 (c_17, m_3) and the
  linear interpolation between them;
* ``"holtrop-mennen-1982"``: the form factor (c_12, c_13) and the wave resistance (m_2, for
  Fn ≤ 0.45) of Holtrop & Mennen (1982), the version the paper's worked example was computed
  with; the tests reproduce that example with it.

Everything else (S, i_E, L_R, C_F, R_APP, R_B, R_TR, C_A) is the same in both papers.

The hull is a :class:`~seahelm.hydrodynamics.hull_form.HullForm` (its defaults and estimates of
C_M, C_WP, S, i_E are documented there), the water a
:class:`~seahelm.hydrodynamics.hull_form.Water`.

The model-ship correlation resistance is computed as printed, R_A = ½ρV²S C_A. Both papers'
worked examples agree better with R_A on S + S_APP: the 1982 example prints C_A = 0.000352
and R_A = 221.98 kN, where ½ρV²S C_A gives 220.57 kN and ½ρV²(S + S_APP) C_A 222.07 kN; the
1984 example's totals are 0.4 to 0.6 % above the sum computed with S alone and within 0.07 %
with S + S_APP. The printed formula is kept; the tests state the difference.

Validity
--------
The regression sample's ranges per ship type (:data:`SHIP_TYPES`: maximum Fn and ranges of
C_P, L/B, B/T), as the method's validity table is commonly reproduced (the table itself could
not be read in the sources at hand; check it against the paper before relying on it);
without a ship type the envelope of all types is checked (Fn ≤ 0.45, 0.55 ≤ C_P ≤ 0.85,
3.9 ≤ L/B ≤ 9.5, 2.1 ≤ B/T ≤ 4.0). Outside: :class:`~seahelm.errors.ValidityRangeWarning` naming the formula,
the parameter, its value and the range (an error under
:class:`~seahelm.errors.strict_validity`). Holtrop (1984) extended the wave resistance to
higher Froude numbers (R_W-B, Fn ≥ 0.55) with the Series 64 hulls; the table's Fn limits still
apply and the warning says so. The wake and thrust-deduction estimates are for single-screw
ships with a conventional stern (Holtrop 1984, p. 273–274), from the same data.

References
----------
Holtrop, J. & Mennen, G. G. J. (1982). An approximate power prediction method. International
Shipbuilding Progress 29(335), 166–170.
Holtrop, J. (1984). A statistical re-analysis of resistance and propulsion data. International
Shipbuilding Progress 31(363), 272–276.
ITTC (1957). Proceedings of the 8th ITTC, Madrid: the ITTC-1957 model-ship correlation line.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_positive, lookup_name
from ..errors import ParameterError, warn_validity
from .hull_form import SEAWATER_15C, HullForm, Water

__all__ = [
    "ValidityRange",
    "SHIP_TYPES",
    "HoltropMethod",
    "METHODS",
    "ResistanceComponents",
    "frictional_coefficient",
    "holtrop_mennen",
    "resistance_coefficient",
    "wake_fraction",
    "thrust_deduction",
]

FORMULA = "Holtrop & Mennen (1982) / Holtrop (1984)"


@dataclass(frozen=True)
class ValidityRange:
    """The regression sample's range for one ship type.

    Attributes
    ----------
    froude_max : float
        Largest Fn [-].
    prismatic : (float, float)
        C_P range [-].
    length_beam : (float, float)
        L/B range [-].
    beam_draft : (float, float)
        B/T range [-].
    """

    froude_max: float
    prismatic: tuple[float, float]
    length_beam: tuple[float, float]
    beam_draft: tuple[float, float]


SHIP_TYPES: dict[str, ValidityRange] = {
    "tanker-bulk-carrier": ValidityRange(0.24, (0.73, 0.85), (5.1, 7.1), (2.4, 3.2)),
    "trawler-coaster-tug": ValidityRange(0.38, (0.55, 0.65), (3.9, 6.3), (2.1, 3.0)),
    "container-destroyer": ValidityRange(0.45, (0.55, 0.67), (6.0, 9.5), (3.0, 4.0)),
    "cargo-liner": ValidityRange(0.30, (0.56, 0.75), (5.3, 8.0), (2.4, 4.0)),
    "roro-car-ferry": ValidityRange(0.35, (0.55, 0.67), (5.3, 8.0), (3.2, 4.0)),
}
"""Validity ranges per ship type (max Fn, C_P, L/B, B/T), the method's table as reproduced."""

_ENVELOPE = ValidityRange(0.45, (0.55, 0.85), (3.9, 9.5), (2.1, 4.0))


def frictional_coefficient(reynolds: ArrayLike) -> np.ndarray:
    """ITTC-1957 model-ship correlation line C_F = 0.075/(log₁₀ Rn − 2)² [-].

    Parameters
    ----------
    reynolds : array_like
        Rn = V L/ν [-], > 100.

    Returns
    -------
    numpy.ndarray
        C_F [-].
    """
    rn = as_float_array("reynolds", reynolds, "-")
    if np.any(rn <= 100.0):
        raise ParameterError(f"must be > 100 [-], got {rn.min()!r}", field="reynolds", unit="-",
                             value=reynolds)
    return 0.075 / (np.log10(rn) - 2.0) ** 2


# -- the two variants: form factor and wave resistance -----------------------------------------
def _form_factor_1982(h: HullForm) -> float:
    """1 + k_1, Holtrop & Mennen (1982), p. 166 (c_12, c_13)."""
    t_l, cp = h.draft / h.length, h.prismatic_coefficient
    if t_l > 0.05:
        c12 = t_l ** 0.2228446
    elif t_l > 0.02:
        c12 = 48.20 * (t_l - 0.02) ** 2.078 + 0.479948
    else:
        c12 = 0.479948
    c13 = 1.0 + 0.003 * h.stern_shape
    return c13 * (0.93 + c12 * (h.beam / h.run_length) ** 0.92497 * (0.95 - cp) ** -0.521448
                  * (1.0 - cp + 0.0225 * h.lcb) ** 0.6906)


def _form_factor_1984(h: HullForm) -> float:
    """1 + k_1, Holtrop (1984), p. 272 (c_14)."""
    L, c14 = h.length, 1.0 + 0.011 * h.stern_shape
    return 0.93 + 0.487118 * c14 * (h.beam / L) ** 1.06806 * (h.draft / L) ** 0.46106 * (
        L / h.run_length) ** 0.121563 * (L**3 / h.displacement_volume) ** 0.36486 * (
        1.0 - h.prismatic_coefficient) ** -0.604247


def _wave_common(h: HullForm) -> dict[str, float]:
    """c_1 (with c_7, i_E), c_2 (c_3), c_5, c_15, c_16, m_1, λ: both papers."""
    L, B, T, cp, vol = h.length, h.beam, h.draft, h.prismatic_coefficient, h.displacement_volume
    b_l = B / L
    c7 = 0.229577 * b_l ** 0.33333 if b_l < 0.11 else (b_l if b_l < 0.25 else
                                                         0.5 - 0.0625 * L / B)
    c1 = 2223105.0 * c7 ** 3.78613 * (T / B) ** 1.07961 * (90.0 - h.entrance_angle) ** -1.37565
    c3 = 0.0
    if h.bulb_area > 0:
        c3 = 0.56 * h.bulb_area ** 1.5 / (B * T * (0.31 * math.sqrt(h.bulb_area) + h.fore_draft
                                                   - h.bulb_centre))
    c16 = (8.07981 * cp - 13.8673 * cp**2 + 6.984388 * cp**3 if cp < 0.8
           else 1.73014 - 0.7067 * cp)
    slender = L**3 / vol
    c15 = (-1.69385 if slender < 512.0 else
           (-1.69385 + (L / vol ** (1 / 3) - 8.0) / 2.36 if slender < 1726.91 else 0.0))
    return dict(
        c1=c1, c2=math.exp(-1.89 * math.sqrt(c3)), c3=c3, c15=c15, c16=c16,
        c5=1.0 - 0.8 * h.transom_area / (B * T * h.midship),
        m1=0.0140407 * L / T - 1.75254 * vol ** (1 / 3) / L - 4.79323 * b_l - c16,
        lam=1.446 * cp - 0.03 * L / B if L / B < 12.0 else 1.446 * cp - 0.36)


def _wave_1982(h: HullForm, fn: np.ndarray, rho_g: float) -> np.ndarray:
    """R_W, Holtrop & Mennen (1982), p. 167: c_1 c_2 c_5 ∇ρg exp{m_1 Fn^d + m_2 cos(λ Fn⁻²)}."""
    k = _wave_common(h)
    m2 = k["c15"] * h.prismatic_coefficient**2 * np.exp(-0.1 * fn**-2.0)
    return (k["c1"] * k["c2"] * k["c5"] * h.displacement_volume * rho_g
            * np.exp(k["m1"] * fn**-0.9 + m2 * np.cos(k["lam"] * fn**-2.0)))


def _wave_1984(h: HullForm, fn: np.ndarray, rho_g: float) -> np.ndarray:
    """R_W, Holtrop (1984), p. 272–273: R_W-A (Fn ≤ 0.4), R_W-B (Fn ≥ 0.55), interpolated."""
    k = _wave_common(h)
    L, B, T = h.length, h.beam, h.draft
    base = k["c2"] * k["c5"] * h.displacement_volume * rho_g
    c17 = (6919.3 * h.midship ** -1.3346 * (h.displacement_volume / L**3) ** 2.00977
           * (L / B - 2.0) ** 1.40692)
    m3 = -7.2035 * (B / L) ** 0.326869 * (T / B) ** 0.605375

    def m4(f: np.ndarray) -> np.ndarray:
        return k["c15"] * 0.4 * np.exp(-0.034 * f**-3.29)

    def r_a(f: np.ndarray) -> np.ndarray:
        return k["c1"] * base * np.exp(k["m1"] * f**-0.9 + m4(f) * np.cos(k["lam"] * f**-2.0))

    def r_b(f: np.ndarray) -> np.ndarray:
        return c17 * base * np.exp(m3 * f**-0.9 + m4(f) * np.cos(k["lam"] * f**-2.0))

    low, high = r_a(np.float64(0.4)), r_b(np.float64(0.55))
    between = low + (10.0 * fn - 4.0) * (high - low) / 1.5
    return np.where(fn <= 0.4, r_a(fn), np.where(fn >= 0.55, r_b(fn), between))


@dataclass(frozen=True)
class HoltropMethod:
    """A variant of the method: its form factor and wave resistance.

    Attributes
    ----------
    name : str
        Registry name.
    form_factor : callable
        ``HullForm -> 1 + k_1`` [-].
    wave_resistance : callable
        ``(HullForm, Fn array, ρ g) -> R_W`` [N].
    """

    name: str
    form_factor: Callable[[HullForm], float]
    wave_resistance: Callable[[HullForm, np.ndarray, float], np.ndarray]


METHODS: dict[str, HoltropMethod] = {
    "holtrop-1984": HoltropMethod("holtrop-1984", _form_factor_1984, _wave_1984),
    "holtrop-mennen-1982": HoltropMethod("holtrop-mennen-1982", _form_factor_1982, _wave_1982),
}
"""The registered variants (module notes)."""


def _method(method: str | HoltropMethod) -> HoltropMethod:
    if isinstance(method, HoltropMethod):
        return method
    return lookup_name("Holtrop method", METHODS, method, sort=True)


@dataclass(frozen=True)
class ResistanceComponents:
    """Resistance components [N] at each speed (arrays shaped like the speed), Holtrop (1984),
    p. 272, and the coefficients they came from.

    Attributes
    ----------
    frictional : numpy.ndarray
        R_F = ½ρV²S C_F [N] (without the form factor).
    form_factor : float
        1 + k_1 [-].
    appendage : numpy.ndarray
        R_APP = ½ρV² S_APP (1 + k_2)_eq C_F [N].
    wave : numpy.ndarray
        R_W [N].
    bulb : numpy.ndarray
        R_B [N].
    transom : numpy.ndarray
        R_TR [N].
    correlation : numpy.ndarray
        R_A = ½ρV²S C_A [N].
    friction_coefficient : numpy.ndarray
        C_F [-] (ITTC-1957).
    correlation_coefficient : float
        C_A [-].
    froude_number : numpy.ndarray
        Fn = V/√(gL) [-].
    """

    frictional: np.ndarray
    form_factor: float
    appendage: np.ndarray
    wave: np.ndarray
    bulb: np.ndarray
    transom: np.ndarray
    correlation: np.ndarray
    friction_coefficient: np.ndarray
    correlation_coefficient: float
    froude_number: np.ndarray

    @property
    def total(self) -> np.ndarray:
        """R_total = R_F (1 + k_1) + R_APP + R_W + R_B + R_TR + R_A [N]."""
        return (self.frictional * self.form_factor + self.appendage + self.wave + self.bulb
                + self.transom + self.correlation)


def _check_validity(hull: HullForm, fn: np.ndarray, ship_type: str | None,
                    strict: bool | None) -> None:
    if ship_type is None:
        rng, where = _ENVELOPE, "all ship types"
    else:
        rng = lookup_name("ship type", SHIP_TYPES, ship_type, sort=True,
                          suffix=" (or None: all types)")
        where = f"ship type {ship_type!r}"
    problems = []
    for name, value, (low, high) in (
            ("C_P", hull.prismatic_coefficient, rng.prismatic),
            ("L/B", hull.length / hull.beam, rng.length_beam),
            ("B/T", hull.beam / hull.draft, rng.beam_draft)):
        if not low <= value <= high:
            problems.append(f"{name} = {value:.4g} outside {low:g} <= {name} <= {high:g}")
    if np.any(fn > rng.froude_max):
        problems.append(f"Fn = {float(np.max(fn)):.4g} above Fn <= {rng.froude_max:g}")
    if problems:
        warn_validity(f"{FORMULA} resistance used outside the data range ({where}): "
                      + "; ".join(problems), strict=strict, stacklevel=4)


def holtrop_mennen(hull: HullForm, speed: ArrayLike, *, water: Water = SEAWATER_15C,
                   method: str | HoltropMethod = "holtrop-1984", ship_type: str | None = None,
                   strict: bool | None = None) -> ResistanceComponents:
    """Calm-water resistance components of a displacement ship, Holtrop & Mennen (1982, 1984).

    R_F = ½ρV²S C_F, C_F = 0.075/(log₁₀ Rn − 2)² (ITTC 1957); R_APP = ½ρV² S_APP (1 + k_2)_eq
    C_F; R_W by the chosen method; R_B = 0.11 exp(−3 P_B⁻²) Fn_i³ A_BT^1.5 ρg/(1 + Fn_i²) with
    P_B = 0.56 √A_BT/(T_F − 1.5 h_B), Fn_i = V/√(g (T_F − h_B − 0.25 √A_BT) + 0.15 V²);
    R_TR = ½ρV² A_T c_6, c_6 = 0.2 (1 − 0.2 Fn_T) for Fn_T = V/√(2 g A_T/(B + B C_WP)) < 5,
    else 0; R_A = ½ρV²S C_A, C_A = 0.006 (L + 100)^−0.16 − 0.00205 + 0.003 √(L/7.5) C_B⁴ c_2
    (0.04 − c_4), c_4 = min(T_F/L, 0.04) (Holtrop & Mennen 1982, p. 167–168).

    Parameters
    ----------
    hull : HullForm
        Main particulars.
    speed : array_like
        Ship speed V [m/s], ≥ 0 (any shape; 0 gives zero resistance).
    water : Water, optional
        ρ, ν, g (default :data:`SEAWATER_15C`).
    method : str or HoltropMethod, optional
        A name in :data:`METHODS` or a method (default ``"holtrop-1984"``).
    ship_type : str, optional
        A name in :data:`SHIP_TYPES` whose data range is checked (default: the envelope).
    strict : bool, optional
        Raise instead of warning outside the data range (default: the global strict mode).

    Returns
    -------
    ResistanceComponents
        The components [N] shaped like ``speed``; ``.total`` their sum.

    Raises
    ------
    ParameterError
        A negative or non-finite speed.
    ValueError
        An unknown method or ship type.

    Warns
    -----
    ValidityRangeWarning
        C_P, L/B, B/T or Fn outside the ship type's (or all types') data range.
    """
    m = _method(method)
    v = as_float_array("speed", speed, "m/s")
    check_nonnegative("speed", v, "m/s")
    rho, g = water.density, water.gravity
    L, B, h = hull.length, hull.beam, hull
    moving = v > 0
    vs = np.where(moving, v, 1.0)  # (evaluated at 1 m/s where V = 0, then masked)
    fn = vs / np.sqrt(g * L)
    _check_validity(hull, np.where(moving, fn, 0.0), ship_type, strict)
    q = 0.5 * rho * vs**2
    cf = frictional_coefficient(vs * L / water.kinematic_viscosity)
    c2 = _wave_common(hull)["c2"]
    c4 = min(h.fore_draft / L, 0.04)
    ca = (0.006 * (L + 100.0) ** -0.16 - 0.00205
          + 0.003 * math.sqrt(L / 7.5) * h.block_coefficient**4 * c2 * (0.04 - c4))
    bulb = np.zeros_like(vs)
    if h.bulb_area > 0:
        pb = 0.56 * math.sqrt(h.bulb_area) / (h.fore_draft - 1.5 * h.bulb_centre)
        fni = vs / np.sqrt(g * (h.fore_draft - h.bulb_centre - 0.25 * math.sqrt(h.bulb_area))
                           + 0.15 * vs**2)
        bulb = 0.11 * math.exp(-3.0 * pb**-2) * fni**3 * h.bulb_area**1.5 * rho * g / (1 + fni**2)
    transom = np.zeros_like(vs)
    if h.transom_area > 0:
        fnt = vs / math.sqrt(2.0 * g * h.transom_area / (B + B * h.waterplane))
        transom = q * h.transom_area * np.where(fnt < 5.0, 0.2 * (1.0 - 0.2 * fnt), 0.0)

    def masked(x: np.ndarray) -> np.ndarray:
        return np.where(moving, x, 0.0)

    return ResistanceComponents(
        frictional=masked(q * h.surface * cf), form_factor=float(m.form_factor(hull)),
        appendage=masked(q * h.appendage_area * h.appendage_form_factor * cf),
        wave=masked(m.wave_resistance(hull, fn, rho * g)), bulb=masked(bulb),
        transom=masked(transom), correlation=masked(q * h.surface * ca),
        friction_coefficient=np.where(moving, cf, np.nan), correlation_coefficient=float(ca),
        froude_number=masked(fn))


def resistance_coefficient(hull: HullForm, speed: ArrayLike, length: float | None = None,
                           draft: float | None = None, **options: object) -> np.ndarray:
    """The MMG model's resistance coefficient R'_0 = R_T/(½ ρ L_pp d U²) [-].

    Parameters
    ----------
    hull : HullForm
        Main particulars.
    speed : array_like
        U [m/s], > 0.
    length : float, optional
        L_pp [m] of the MMG non-dimensionalisation (default ``hull.length``, L_WL).
    draft : float, optional
        d [m] (default ``hull.draft``).
    **options
        ``water``, ``method``, ``ship_type``, ``strict`` of :func:`holtrop_mennen`.

    Returns
    -------
    numpy.ndarray
        R'_0 [-], shaped like ``speed``.
    """
    v = as_float_array("speed", speed, "m/s")
    check_positive("speed", v, "m/s")
    lpp = hull.length if length is None else float(length)
    d = hull.draft if draft is None else float(draft)
    check_positive("length", lpp, "m")
    check_positive("draft", d, "m")
    water = options.get("water", SEAWATER_15C)
    r = holtrop_mennen(hull, v, **options).total  # type: ignore[arg-type]
    return r / (0.5 * water.density * lpp * d * v**2)  # type: ignore[attr-defined]


def _propeller_diameter(hull: HullForm, diameter: float) -> float:
    check_positive("propeller_diameter", diameter, "m")
    if diameter >= 1.5 * hull.aft_draft:
        raise ParameterError(f"must be < 1.5 T_A = {1.5 * hull.aft_draft:g} [m] (a propeller "
                             f"under the hull), got {diameter!r}", field="propeller_diameter",
                             unit="m", value=diameter)
    return float(diameter)


def wake_fraction(hull: HullForm, speed: ArrayLike, propeller_diameter: float, *,
                  water: Water = SEAWATER_15C, method: str | HoltropMethod = "holtrop-1984"
                  ) -> np.ndarray:
    """Effective wake fraction w of a single-screw ship [-], Holtrop (1984), p. 273–274.

    ::

        w = c_9 c_20 C_V (L/T_A) (0.050776 + 0.93405 c_11 C_V/(1 − C_P1))
            + 0.27915 c_20 √(B/(L (1 − C_P1))) + c_19 c_20

    with C_V = (1 + k_1) C_F + C_A, C_P1 = 1.45 C_P − 0.315 − 0.0225 lcb, c_8 = B S/(L D T_A)
    (B/T_A < 5) or S (7 B/T_A − 25)/(L D (B/T_A − 3)), c_9 = c_8 (c_8 < 28) or
    32 − 16/(c_8 − 24), c_11 = T_A/D (T_A/D < 2) or 0.0833333 (T_A/D)³ + 1.33333,
    c_19 = 0.12997/(0.95 − C_B) − 0.11056/(0.95 − C_P) (C_P < 0.7) or 0.18567/(1.3571 − C_M)
    − 0.71276 + 0.38648 C_P, c_20 = 1 + 0.015 C_stern. For a conventional single-screw stern,
    within the resistance data range; C_V makes it depend weakly on speed (Reynolds number).

    Parameters
    ----------
    hull : HullForm
        Main particulars.
    speed : array_like
        V [m/s], > 0.
    propeller_diameter : float
        D [m], < 1.5 T_A.
    water : Water, optional
        ρ, ν, g (default :data:`SEAWATER_15C`).
    method : str or HoltropMethod, optional
        Variant giving 1 + k_1 (default ``"holtrop-1984"``).

    Returns
    -------
    numpy.ndarray
        w [-] (the MMG model's w_P0), shaped like ``speed``.
    """
    D = _propeller_diameter(hull, propeller_diameter)
    v = as_float_array("speed", speed, "m/s")
    check_positive("speed", v, "m/s")
    h, L, B, ta = hull, hull.length, hull.beam, hull.aft_draft
    r = holtrop_mennen(hull, v, water=water, method=method, strict=False)
    cv = r.form_factor * r.friction_coefficient + r.correlation_coefficient
    cp, cb = h.prismatic_coefficient, h.block_coefficient
    cp1 = 1.45 * cp - 0.315 - 0.0225 * h.lcb
    c8 = (B * h.surface / (L * D * ta) if B / ta < 5.0
          else h.surface * (7.0 * B / ta - 25.0) / (L * D * (B / ta - 3.0)))
    c9 = c8 if c8 < 28.0 else 32.0 - 16.0 / (c8 - 24.0)
    c11 = ta / D if ta / D < 2.0 else 0.0833333 * (ta / D) ** 3 + 1.33333
    c19 = (0.12997 / (0.95 - cb) - 0.11056 / (0.95 - cp) if cp < 0.7
           else 0.18567 / (1.3571 - h.midship) - 0.71276 + 0.38648 * cp)
    c20 = 1.0 + 0.015 * h.stern_shape
    return (c9 * c20 * cv * L / ta * (0.050776 + 0.93405 * c11 * cv / (1.0 - cp1))
            + 0.27915 * c20 * math.sqrt(B / (L * (1.0 - cp1))) + c19 * c20)


def thrust_deduction(hull: HullForm, propeller_diameter: float) -> float:
    """Thrust deduction fraction t of a single-screw ship [-], Holtrop (1984), p. 274.

    ::

        t = 0.25014 (B/L)^0.28956 (√(B T)/D)^0.2624 / (1 − C_P + 0.0225 lcb)^0.01762
            + 0.0015 C_stern

    Parameters
    ----------
    hull : HullForm
        Main particulars.
    propeller_diameter : float
        D [m], < 1.5 T_A.

    Returns
    -------
    float
        t [-] (the MMG model's t_P).
    """
    D = _propeller_diameter(hull, propeller_diameter)
    h = hull
    return (0.25014 * (h.beam / h.length) ** 0.28956 * (math.sqrt(h.beam * h.draft) / D) ** 0.2624
            / (1.0 - h.prismatic_coefficient + 0.0225 * h.lcb) ** 0.01762
            + 0.0015 * h.stern_shape)
