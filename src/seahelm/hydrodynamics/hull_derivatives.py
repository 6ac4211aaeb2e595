"""MMG hull derivatives and added masses from the main particulars.

The hull forces of the MMG standard model (Yasukawa & Yoshimura 2015; :mod:`seahelm.vessels.mmg`)
are polynomials in v'_m and r' whose coefficients are found in captive model tests. Without
tests they are estimated from L, B, d, τ, C_b by regressions over databases of such tests:

**Linear terms: Kijima et al. (1990)**, with k = 2d/L, τ' = τ/d (trim by the stern
positive), m' = ∇/(½L²d)::

    Y'_v = −(π/2 k + 1.4 C_b B/L)(1 + 0.67 τ')
    Y'_r = (m' + m'_x) − 1.5 C_b B/L (1 + 0.8 τ')
    N'_v = −k (1 − 0.27 τ'/l'_v),        l'_v = N'_v/Y'_v at even keel
    N'_r = (−0.54 k + k²)(1 + 0.3 τ')

Kijima writes the sway terms with the drift angle β ≈ −v'; in the MMG sign convention the
signs above follow (Y'_v < 0, N'_v < 0, N'_r < 0). At even keel Y'_r equals Yoshimura &
Masumoto's (2012) m'_x + 0.5 C_b B/L when ∇ = C_b L B d (then m' = 2 C_b B/L).

**Nonlinear terms: Yoshimura & Masumoto (2012)**, in the cubic form of the MMG standard
method (Kijima's nonlinear terms are in the form β|β|, r|r|, which the MMG polynomial does not
have)::

    X'_vv = 1.15 C_b B/L − 0.18          X'_vvvv = −6.68 C_b B/L + 1.1
    X'_vr = m'_y − 1.91 C_b B/L + 0.08   X'_rr   = −0.085 C_b B/L + 0.008
    Y'_vvv = −0.185 L/B + 0.48           Y'_vvr  = −0.75
    Y'_vrr = −(0.26 (1 − C_b) L/B + 0.11)   Y'_rrr = −0.051
    N'_vvv = −(−0.69 C_b + 0.66)         N'_vvr  = 1.55 C_b B/L − 0.76
    N'_vrr = −0.075 (1 − C_b) L/B − 0.098    N'_rrr = 0.25 C_b B/L − 0.056

We have not seen the 2012 paper itself: these are its formulas as transcribed, identically,
in two independent open implementations (``nikpau/mmgdynamics``, whose source comments quote
them, and an MMG coefficient module citing the MANSIM review of Sukas, Kinaci & Bal 2019).
One of them writes X'_rr with an extra −x_G m'_y (dimensional x_G: not consistent), the other
without; seahelm takes it without (the term is small: 0.003 for the KVLCC2).

**Added masses: regressions of Motora's charts** (m_x, m_y, J_z as fractions of the ship's
mass and inertia; as collected in the MANSIM review, Sukas, Kinaci & Bal 2019)::

    m_x/m = [0.398 + 11.97 C_b (1 + 3.73 d/B) − 2.89 C_b L/B (1 + 1.13 d/B)
             + 0.175 C_b (L/B)² (1 + 0.541 d/B) − 1.107 (L/B)(d/B)] / 100
    m_y/m = 0.882 − 0.54 C_b (1 − 1.6 d/B) − 0.156 (1 − 0.673 C_b) L/B
            + 0.826 (d/B)(L/B)(1 − 0.678 d/B) − 0.638 C_b (d/B)(L/B)(1 − 0.669 d/B)
    J_z/(m L²) = {[33 − 76.85 C_b (1 − 0.784 C_b) + 3.43 L/B (1 − 0.63 C_b)] / 100}²

For the KVLCC2 (L/B 5.52, d/B 0.359, C_b 0.81) they give m'_x 0.0231, m'_y 0.224, J'_z 0.0112
against the captive-test 0.022, 0.223, 0.011 of Yasukawa & Yoshimura (2015): a check that the
transcription is right (tested).

Data ranges (warned outside; approximate ranges of the ships behind the regressions, the
papers give their databases as tables rather than bounds): C_b 0.48–0.85, L/B 4–8,
B/d 2–4.5, C_b B/L 0.06–0.16, |τ'| ≤ 0.6 (Kijima's trim terms were fitted to ballast trims).

References
----------
Kijima, K., Katsuno, T., Nakiri, Y., Furukawa, Y. (1990). On the manoeuvring performance of a
ship with the parameter of loading condition. J. Soc. Naval Arch. Japan 168, 141–148.
Yoshimura, Y., Masumoto, Y. (2012). Hydrodynamic database and manoeuvring prediction method
with medium high-speed merchant ships and fishing vessels. MARSIM 2012, Singapore.
Sukas, O.F., Kinaci, O.K., Bal, S. (2019). Theoretical background and application of MANSIM
for ship maneuvering simulations. Ocean Eng. 192, 106239.
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
"""

from __future__ import annotations

import math

from .hull import Coefficient, HullParticulars, check_ranges

__all__ = ["added_masses", "linear_hull_derivatives", "nonlinear_hull_derivatives",
           "hull_derivatives", "DATA_RANGES"]

KIJIMA = "Kijima et al. (1990)"
YOSHIMURA = "Yoshimura & Masumoto (2012), as transcribed in two open implementations"
MOTORA = "regression of Motora's added-mass charts (Sukas, Kinaci & Bal 2019)"

#: Approximate data ranges of the regressions (see the module docstring).
DATA_RANGES: dict[str, tuple[float, float]] = {
    "C_b": (0.48, 0.85), "L/B": (4.0, 8.0), "B/d": (2.0, 4.5), "C_b B/L": (0.06, 0.16),
    "trim/d": (-0.6, 0.6),
}


def _ratios(hull: HullParticulars) -> dict[str, float]:
    return {"C_b": hull.block_coefficient, "L/B": hull.length / hull.beam,
            "B/d": hull.beam / hull.draft, "C_b B/L": hull.cb_b_over_l,
            "trim/d": hull.trim_ratio}


def _check(hull: HullParticulars, formula: str, names: tuple[str, ...],
           strict: bool | None) -> None:
    ratios = _ratios(hull)
    check_ranges(formula, {n: (ratios[n], *DATA_RANGES[n]) for n in names}, strict=strict,
                 stacklevel=4)


def added_masses(hull: HullParticulars, *, strict: bool | None = None
                 ) -> dict[str, Coefficient]:
    """Added masses m'_x, m'_y and added yaw inertia J'_z (MMG non-dimensional).

    Parameters
    ----------
    hull : HullParticulars
        The hull.
    strict : bool, optional
        Raise instead of warning outside the data range.

    Returns
    -------
    dict of str to Coefficient
        ``m_x``, ``m_y`` (÷ ½ρL²d) and ``J_z`` (÷ ½ρL⁴d), the :class:`~seahelm.vessels.mmg.
        MMGParams` field names.
    """
    _check(hull, "Motora's added-mass regressions", ("C_b", "L/B", "B/d"), strict)
    cb = hull.block_coefficient
    lb = hull.length / hull.beam
    db = hull.draft / hull.beam
    m = hull.mass_nd
    mx = (0.398 + 11.97 * cb * (1 + 3.73 * db) - 2.89 * cb * lb * (1 + 1.13 * db)
          + 0.175 * cb * lb ** 2 * (1 + 0.541 * db) - 1.107 * lb * db) / 100.0
    my = (0.882 - 0.54 * cb * (1 - 1.6 * db) - 0.156 * (1 - 0.673 * cb) * lb
          + 0.826 * db * lb * (1 - 0.678 * db) - 0.638 * cb * db * lb * (1 - 0.669 * db))
    jz = ((33.0 - 76.85 * cb * (1 - 0.784 * cb) + 3.43 * lb * (1 - 0.63 * cb)) / 100.0) ** 2
    return {
        "m_x": Coefficient(m * mx, f"{MOTORA}: m_x/m = [0.398 + 11.97 C_b (1 + 3.73 d/B) − "
                                   "2.89 C_b L/B (1 + 1.13 d/B) + 0.175 C_b (L/B)² (1 + 0.541 "
                                   "d/B) − 1.107 (L/B)(d/B)]/100"),
        "m_y": Coefficient(m * my, f"{MOTORA}: m_y/m = 0.882 − 0.54 C_b (1 − 1.6 d/B) − 0.156 "
                                   "(1 − 0.673 C_b) L/B + 0.826 (d/B)(L/B)(1 − 0.678 d/B) − "
                                   "0.638 C_b (d/B)(L/B)(1 − 0.669 d/B)"),
        "J_z": Coefficient(m * jz, f"{MOTORA}: J_z/(m L²) = {{[33 − 76.85 C_b (1 − 0.784 C_b) "
                                   "+ 3.43 L/B (1 − 0.63 C_b)]/100}}²"),
    }


def linear_hull_derivatives(hull: HullParticulars, m_x: float, *,
                            strict: bool | None = None) -> dict[str, Coefficient]:
    """Linear sway and yaw derivatives Y'_v, Y'_r, N'_v, N'_r by Kijima et al. (1990).

    Parameters
    ----------
    hull : HullParticulars
        The hull (its trim enters through τ' = τ/d).
    m_x : float
        Added mass in surge m'_x [-] (in Y'_r).
    strict : bool, optional
        Raise instead of warning outside the data range.

    Returns
    -------
    dict of str to Coefficient
        ``Y_v``, ``Y_r``, ``N_v``, ``N_r``.
    """
    _check(hull, f"{KIJIMA} linear hull derivatives", ("C_b", "L/B", "B/d", "C_b B/L",
                                                         "trim/d"), strict)
    k = hull.k
    tau = hull.trim_ratio
    cbl = hull.cb_b_over_l
    y_beta = 0.5 * math.pi * k + 1.4 * cbl
    l_v = k / y_beta  # N'_β / Y'_β at even keel
    return {
        "Y_v": Coefficient(-y_beta * (1 + 0.67 * tau),
                           f"{KIJIMA}: Y'_v = −(π/2 k + 1.4 C_b B/L)(1 + 0.67 τ/d), k = 2d/L"),
        "Y_r": Coefficient(hull.mass_nd + m_x - 1.5 * cbl * (1 + 0.8 * tau),
                           f"{KIJIMA}: Y'_r = (m' + m'_x) − 1.5 C_b B/L (1 + 0.8 τ/d)"),
        "N_v": Coefficient(-k * (1 - 0.27 * tau / l_v),
                           f"{KIJIMA}: N'_v = −k (1 − 0.27 (τ/d)/l'_v), l'_v = k/(π/2 k + "
                           "1.4 C_b B/L)"),
        "N_r": Coefficient((-0.54 * k + k * k) * (1 + 0.3 * tau),
                           f"{KIJIMA}: N'_r = (−0.54 k + k²)(1 + 0.3 τ/d)"),
    }


def nonlinear_hull_derivatives(hull: HullParticulars, m_y: float, *,
                               strict: bool | None = None) -> dict[str, Coefficient]:
    """Surge and nonlinear sway/yaw derivatives by Yoshimura & Masumoto (2012).

    Parameters
    ----------
    hull : HullParticulars
        The hull.
    m_y : float
        Added mass in sway m'_y [-] (in X'_vr).
    strict : bool, optional
        Raise instead of warning outside the data range.

    Returns
    -------
    dict of str to Coefficient
        ``X_vv``, ``X_vr``, ``X_rr``, ``X_vvvv``, ``Y_vvv``, ``Y_vvr``, ``Y_vrr``, ``Y_rrr``,
        ``N_vvv``, ``N_vvr``, ``N_vrr``, ``N_rrr``.
    """
    _check(hull, "Yoshimura & Masumoto (2012) hull derivatives", ("C_b", "L/B", "C_b B/L"),
           strict)
    cb = hull.block_coefficient
    cbl = hull.cb_b_over_l
    lb = hull.length / hull.beam
    y = YOSHIMURA
    return {
        "X_vv": Coefficient(1.15 * cbl - 0.18, f"{y}: X'_vv = 1.15 C_b B/L − 0.18"),
        "X_vr": Coefficient(m_y - 1.91 * cbl + 0.08, f"{y}: X'_vr = m'_y − 1.91 C_b B/L + 0.08"),
        "X_rr": Coefficient(-0.085 * cbl + 0.008, f"{y}: X'_rr = −0.085 C_b B/L + 0.008"),
        "X_vvvv": Coefficient(-6.68 * cbl + 1.1, f"{y}: X'_vvvv = −6.68 C_b B/L + 1.1"),
        "Y_vvv": Coefficient(-0.185 * lb + 0.48, f"{y}: Y'_vvv = −0.185 L/B + 0.48"),
        "Y_vvr": Coefficient(-0.75, f"{y}: Y'_vvr = −0.75"),
        "Y_vrr": Coefficient(-(0.26 * (1 - cb) * lb + 0.11),
                             f"{y}: Y'_vrr = −(0.26 (1 − C_b) L/B + 0.11)"),
        "Y_rrr": Coefficient(-0.051, f"{y}: Y'_rrr = −0.051"),
        "N_vvv": Coefficient(-(-0.69 * cb + 0.66), f"{y}: N'_vvv = −(−0.69 C_b + 0.66)"),
        "N_vvr": Coefficient(1.55 * cbl - 0.76, f"{y}: N'_vvr = 1.55 C_b B/L − 0.76"),
        "N_vrr": Coefficient(-0.075 * (1 - cb) * lb - 0.098,
                             f"{y}: N'_vrr = −0.075 (1 − C_b) L/B − 0.098"),
        "N_rrr": Coefficient(0.25 * cbl - 0.056, f"{y}: N'_rrr = 0.25 C_b B/L − 0.056"),
    }


def hull_derivatives(hull: HullParticulars, *, strict: bool | None = None
                     ) -> dict[str, Coefficient]:
    """Every MMG hull coefficient but the resistance: added masses, linear and nonlinear terms.

    Parameters
    ----------
    hull : HullParticulars
        The hull.
    strict : bool, optional
        Raise instead of warning outside a regression's data range.

    Returns
    -------
    dict of str to Coefficient
        Keyed by the :class:`~seahelm.vessels.mmg.MMGParams` field names.
    """
    masses = added_masses(hull, strict=strict)
    out = dict(masses)
    out.update(linear_hull_derivatives(hull, masses["m_x"].value, strict=strict))
    out.update(nonlinear_hull_derivatives(hull, masses["m_y"].value, strict=strict))
    return out
