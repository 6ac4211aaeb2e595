"""Wind loads on ships from Blendermann's (1994) coefficient model, by vessel type.

Blendermann (1994) fits the wind force and moment measured on ship models in wind tunnels
with a few parameters per vessel type. With γ the angle of the apparent wind (0 head wind)
the coefficients are (Blendermann, 1994; Fossen, 2021, §10.1.2)::

    CD_l = CD_l,AF(γ) · A_F / A_L            longitudinal drag, referred to A_L
    D(γ) = 1 − δ/2 · (1 − CD_l / CD_t) · sin²(2γ)
    CX   = −CD_l cos γ / D(γ)                (referred to A_L)
    CY   =  CD_t sin γ / D(γ)                (referred to A_L)
    CN   = [s_L / L_oa − 0.18 (γ − π/2)] · CY   (referred to A_L L_oa)

    X = ½ ρ_a V_rw² CX A_L,   Y = ½ ρ_a V_rw² CY A_L,   N = ½ ρ_a V_rw² CN A_L L_oa

with CD_t the transverse drag coefficient (beam wind, referred to A_L), CD_l,AF(γ) the
longitudinal drag coefficient referred to the frontal area A_F, taken as CD_l,AF(0) for
|γ| ≤ π/2 (wind from ahead of the beam) and CD_l,AF(π) otherwise, δ the cross-force
parameter, A_L the lateral and A_F the frontal projected area above the water line, L_oa the
length overall, s_L the longitudinal position of the centre of A_L and V_rw the apparent
wind speed. The roll coefficient CK = κ (s_H / H_M) CY is not implemented; κ is carried in
:class:`BlendermannCoefficients` for it.

At the tabulated angles the formulas give back the table: CY(±π/2) = ∓CD_t (D = 1 there, in
seahelm's signs below), CX(0) = −CD_l,AF(0) A_F/A_L and CX(π) = +CD_l,AF(π) A_F/A_L.

Conventions and conversions
---------------------------
seahelm's body axes are north-east-down: x forward, y to starboard, the yaw moment positive
turning the bow to starboard. ``angle`` is the bearing the *apparent* wind comes **from**,
measured from the bow, positive from starboard (0 head wind, +π/2 wind on the starboard beam,
±π stern wind); any real angle is accepted and wrapped. The returned X is positive forward
(a head wind gives X < 0), Y positive to starboard (a wind from starboard gives Y < 0), N
positive bow-to-starboard.

* **Angle sign.** Fossen (2021, §10.1) writes the relative wind angle
  γ_rw = −atan2(v_rw, u_rw) with (u_rw, v_rw) = ship velocity minus wind velocity in body
  axes. The apparent wind comes from the direction of (u_rw, v_rw), i.e. from the bearing
  atan2(v_rw, u_rw) = seahelm's ``angle``; so γ_rw = −``angle``: Fossen's angle is positive
  for wind from *port*. With it CY = CD_t sin γ_rw gives Y > 0 (to starboard) for wind from
  port, which is right. In seahelm's angle the sway coefficient is therefore
  CY = −CD_t sin(angle) / D; CX is even and unchanged; N has the same positive sense (z down)
  in both.
* **Moment arm.** Blendermann's arm s_L/L_oa − 0.18 (γ − π/2) is a fit over one side,
  0 ≤ γ ≤ π: it runs from s_L/L_oa + 0.28 (head wind) through s_L/L_oa (beam wind) to
  s_L/L_oa − 0.28 (stern wind), so a wind from forward of the beam turns the bow away from
  the wind and one from abaft the beam turns it into the wind. The other side is the mirror
  image, so here the arm uses |angle| and CN is odd in the angle. (MSS ``blendermann94.m``
  evaluates the arm at negative γ_rw too, where it is not the mirror image — at
  γ_rw = −150°, a starboard-quarter wind, it gives an arm of s_L/L_oa + 0.75 and a moment
  turning the bow to port, the wrong way; this module does not follow it there.) With
  s_L = 0 a wind from the starboard bow (angle 30°) turns the bow to port (N < 0), a wind
  from the starboard quarter (150°) turns it to starboard (N > 0).
* **Centre of the lateral area.** Fossen and MSS measure s_L "from the main section", i.e.
  from midships, positive forward (at beam wind CN = (s_L/L_oa) CY: a side force acting
  ahead of midships turns the bow away from the wind). ``lateral_centre`` is that s_L [m],
  forward of midships; no conversion is needed.
* **Reference area of CX.** Blendermann refers CX to A_L, as here. MSS ``blendermann94.m``
  returns CX = −CD_l,AF cos γ / D referred to A_F (X = ½ ρ_a V² CX A_F); its CX is this
  module's CX times A_L/A_F, the force is the same.
* **Air density.** The default is seahelm's :data:`~seahelm.constants.RHO_AIR` = 1.225 kg/m³
  (15 °C); MSS uses 1.224 kg/m³ (labelled "20 °C").

Provenance and disagreements
----------------------------
The table (:data:`BLENDERMANN_VESSEL_TYPES`) is Blendermann's (1994) table of CD_t,
CD_l,AF(0), CD_l,AF(π), δ and κ per vessel type as reproduced in Fossen (2021), §10.1.2; the
values were read from Fossen's Marine Systems Simulator, ``LIBRARY/environment/blendermann94.m``
(github.com/cybergalactic/MSS, commit 736a3d12, whose ``BDATA`` cites "Fossen 2021,
Ch. 10.1.2"; the same numbers are in its 2008 version ``GNC/blendermann94.m``). The book and
the paper themselves were not available to check against. Known differences:

* Drilling vessel: the table gives ranges, CD_l,AF(0) = 0.70–1.00 and CD_l,AF(π) =
  0.75–1.10; MSS (and this module) use the mid-points 0.85 and 0.925.
* MSS's header swaps the two distances: it calls ``sH`` the horizontal and ``sL`` the
  vertical distance of the centroid of A_L, but its formulas use ``sL`` in the yaw arm
  (a longitudinal distance) and ``sH`` in the roll coefficient (a height), and its example
  ``exWindForce.m`` sets sL = 1.48 m, sH = 5.1 m accordingly. Here s_L is the longitudinal
  position, as the formula needs.

References
----------
Blendermann, W. (1994). Parameter identification of wind loads on ships. Journal of Wind
Engineering and Industrial Aerodynamics 51, 339–351.

Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.,
Wiley, §10.1.2; Marine Systems Simulator (MSS), ``blendermann94.m``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_positive, check_range, lookup_name
from ..constants import RHO_AIR
from ..errors import ParameterError

__all__ = [
    "blendermann_loads_folded",
    "BlendermannCoefficients",
    "BLENDERMANN_VESSEL_TYPES",
    "get_blendermann_type",
    "WindCoefficients",
    "WindLoads",
    "blendermann_coefficients",
    "blendermann_wind_loads",
    "blendermann_loads",
]

#: Slope of Blendermann's yaw-moment arm per radian of wind angle [1/rad].
_ARM_SLOPE = 0.18


@dataclass(frozen=True, kw_only=True)
class BlendermannCoefficients:
    """Blendermann's (1994) wind-load parameters of one vessel type.

    Attributes
    ----------
    cd_transverse : float
        Transverse drag coefficient CD_t [-] (beam wind, referred to A_L); > 0.
    cd_longitudinal_head : float
        Longitudinal drag coefficient CD_l,AF(0) [-] for wind from ahead of the beam,
        referred to the frontal area A_F; > 0.
    cd_longitudinal_stern : float
        Longitudinal drag coefficient CD_l,AF(π) [-] for wind from abaft the beam, referred
        to A_F; > 0.
    delta : float
        Cross-force parameter δ [-], in [0, 1] (the tabulated values are 0.1–0.8; the bound
        keeps the denominator D(γ) ≥ 1/2).
    kappa : float
        Rolling-moment factor κ [-] (CK = κ (s_H/H_M) CY; roll is not implemented); > 0.
    description : str
        The vessel type as the table names it, e.g. "Car carrier".
    """

    cd_transverse: float
    cd_longitudinal_head: float
    cd_longitudinal_stern: float
    delta: float
    kappa: float
    description: str = ""

    def __post_init__(self) -> None:
        for name in ("cd_transverse", "cd_longitudinal_head", "cd_longitudinal_stern", "kappa"):
            value = getattr(self, name)
            _check_scalar(name, value)
            check_positive(name, value, "-")
            object.__setattr__(self, name, float(value))
        _check_scalar("delta", self.delta)
        check_range("delta", self.delta, 0.0, 1.0, "-")
        object.__setattr__(self, "delta", float(self.delta))
        if not isinstance(self.description, str):
            raise ParameterError(
                f"`description` must be a string, got {type(self.description).__name__}"
            )


def _check_scalar(name: str, value: object) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ParameterError(f"`{name}` must be a real number [-], got {value!r}")


def _row(cd_t: float, head: float, stern: float, delta: float, kappa: float, description: str):
    return BlendermannCoefficients(
        cd_transverse=cd_t,
        cd_longitudinal_head=head,
        cd_longitudinal_stern=stern,
        delta=delta,
        kappa=kappa,
        description=description,
    )


#: Blendermann's (1994) parameters per vessel type (Fossen (2021), §10.1.2, as in MSS
#: ``blendermann94.m``): CD_t, CD_l,AF(0), CD_l,AF(π), δ, κ.
BLENDERMANN_VESSEL_TYPES: dict[str, BlendermannCoefficients] = {
    "car-carrier": _row(0.95, 0.55, 0.60, 0.80, 1.2, "Car carrier"),
    "cargo-loaded": _row(0.85, 0.65, 0.55, 0.40, 1.7, "Cargo vessel, loaded"),
    "cargo-container-on-deck": _row(0.85, 0.55, 0.50, 0.40, 1.4,
                                    "Cargo vessel, container on deck"),
    "container-loaded": _row(0.90, 0.55, 0.55, 0.40, 1.4, "Container ship, loaded"),
    "destroyer": _row(0.85, 0.60, 0.65, 0.65, 1.1, "Destroyer"),
    "diving-support-vessel": _row(0.90, 0.60, 0.80, 0.55, 1.7, "Diving support vessel"),
    # the table gives ranges 0.70-1.00 and 0.75-1.10: their mid-points, as MSS
    "drilling-vessel": _row(1.00, 0.85, 0.925, 0.10, 1.7, "Drilling vessel"),
    "ferry": _row(0.90, 0.45, 0.50, 0.80, 1.1, "Ferry"),
    "fishing-vessel": _row(0.95, 0.70, 0.70, 0.40, 1.1, "Fishing vessel"),
    "lng-tanker": _row(0.70, 0.60, 0.65, 0.50, 1.1, "Liquefied natural gas tanker"),
    "offshore-supply-vessel": _row(0.90, 0.55, 0.80, 0.55, 1.2, "Offshore supply vessel"),
    "passenger-liner": _row(0.90, 0.40, 0.40, 0.80, 1.2, "Passenger liner"),
    "research-vessel": _row(0.85, 0.55, 0.65, 0.60, 1.4, "Research vessel"),
    "speed-boat": _row(0.90, 0.55, 0.60, 0.60, 1.1, "Speed boat"),
    "tanker-loaded": _row(0.70, 0.90, 0.55, 0.40, 3.1, "Tanker, loaded"),
    "tanker-ballast": _row(0.70, 0.75, 0.55, 0.40, 2.2, "Tanker, in ballast"),
    "tender": _row(0.85, 0.55, 0.55, 0.65, 1.1, "Tender"),
}


def get_blendermann_type(
    vessel_type: str | BlendermannCoefficients,
) -> BlendermannCoefficients:
    """Blendermann parameters by vessel-type name (or the parameters themselves).

    Parameters
    ----------
    vessel_type : str or BlendermannCoefficients
        A key of :data:`BLENDERMANN_VESSEL_TYPES` (e.g. ``"car-carrier"``), or a
        :class:`BlendermannCoefficients`, returned as it is.

    Returns
    -------
    BlendermannCoefficients

    Raises
    ------
    ValueError
        If ``vessel_type`` is not a known name (the message lists the valid ones).
    """
    if isinstance(vessel_type, BlendermannCoefficients):
        return vessel_type
    return lookup_name("Blendermann vessel type", BLENDERMANN_VESSEL_TYPES, vessel_type,
                       sort=True)


class WindCoefficients(NamedTuple):
    """Blendermann wind-load coefficients in seahelm's signs."""

    cx: np.ndarray
    """Surge coefficient CX [-], referred to A_L, positive forward."""
    cy: np.ndarray
    """Sway coefficient CY [-], referred to A_L, positive to starboard."""
    cn: np.ndarray
    """Yaw coefficient CN [-], referred to A_L L_oa, positive bow-to-starboard."""


class WindLoads(NamedTuple):
    """Wind force and moment on the ship in body axes (north-east-down)."""

    surge: np.ndarray
    """Surge force X [N], positive forward."""
    sway: np.ndarray
    """Sway force Y [N], positive to starboard."""
    yaw: np.ndarray
    """Yaw moment N [N·m], positive turning the bow to starboard."""


@njit(cache=True)
def blendermann_loads(speed, angle, cd_transverse, cd_longitudinal_head, cd_longitudinal_stern,
                      delta, kappa, frontal_area, lateral_area, length_overall, lateral_centre,
                      rho_air):  # pragma: no cover - compiled
    """Blendermann (1994) wind force and moment for one apparent wind (compiled, scalar).

    Allocation-free (floats and :mod:`math` only), so it can be called from compiled loops
    built without the numba runtime. Inputs are not validated: check them once outside the
    loop (:func:`blendermann_wind_loads` does).

    Parameters
    ----------
    speed : float
        Apparent wind speed V_rw [m/s].
    angle : float
        Bearing the apparent wind comes from [rad], from the bow, positive from starboard.
    cd_transverse, cd_longitudinal_head, cd_longitudinal_stern, delta, kappa : float
        CD_t, CD_l,AF(0), CD_l,AF(π), δ, κ [-] (κ is unused: no roll).
    frontal_area, lateral_area : float
        Projected areas A_F, A_L [m²].
    length_overall : float
        L_oa [m].
    lateral_centre : float
        s_L, centre of A_L forward of midships [m].
    rho_air : float
        Air density ρ_a [kg/m³].

    Returns
    -------
    tuple of float
        ``(X [N], Y [N], N [N·m])``: surge forward, sway to starboard, yaw bow-to-starboard.
    """
    # fold the angle to a side (sign) and a bearing a in [0, π] from the bow
    g = angle
    if g > math.pi or g < -math.pi:  # angles in [−π, π] are used exactly as given
        g -= 2.0 * math.pi * math.floor((g + math.pi) / (2.0 * math.pi))
    side = -1.0 if g < 0.0 else 1.0
    a = abs(g)
    # sin and cos through the nearer of 0 and π, so that a stern wind has sin = 0 exactly
    if a > 0.5 * math.pi:
        b = math.pi - a
        s = math.sin(b)
        c = -math.cos(b)
    else:
        s = math.sin(a)
        c = math.cos(a)
    return blendermann_loads_folded(
        speed * speed, side, a, s, c, cd_transverse,
        cd_longitudinal_head * (frontal_area / lateral_area),
        cd_longitudinal_stern * (frontal_area / lateral_area), delta,
        lateral_centre / length_overall, 0.5 * rho_air * lateral_area, length_overall)


@njit(cache=True)
def blendermann_loads_folded(speed_squared, side, a, s, c, cd_transverse, cd_l_head, cd_l_stern,
                             delta, centre_ratio, dynamic_area,
                             length_overall):  # pragma: no cover - compiled
    """Blendermann (1994) loads of a wind given by its folded bearing (compiled, scalar).

    The closed loop calls this form: it has the bearing's cosine and sine from the relative
    wind's components (no trigonometric call) and the per-run constants computed once.

    Parameters
    ----------
    speed_squared : float
        V_rw² [m²/s²].
    side : float
        +1 for a wind from starboard (or dead ahead/astern), −1 from port.
    a, s, c : float
        |γ| ∈ [0, π] [rad] and its sine (≥ 0) and cosine.
    cd_transverse : float
        CD_t [-].
    cd_l_head, cd_l_stern : float
        CD_l,AF(0) A_F/A_L and CD_l,AF(π) A_F/A_L [-] (CD_l referred to A_L).
    delta : float
        Cross-force parameter δ [-].
    centre_ratio : float
        s_L/L_oa [-].
    dynamic_area : float
        ½ ρ_a A_L [kg/m].
    length_overall : float
        L_oa [m].

    Returns
    -------
    tuple of float
        ``(X [N], Y [N], N [N·m])`` as :func:`blendermann_loads`.
    """
    cd_l = cd_l_stern if a > 0.5 * math.pi else cd_l_head
    sin2 = 2.0 * s * c
    den = 1.0 - 0.5 * delta * (1.0 - cd_l / cd_transverse) * sin2 * sin2
    cx = -cd_l * c / den
    cy = -side * cd_transverse * s / den
    cn = (centre_ratio - _ARM_SLOPE * (a - 0.5 * math.pi)) * cy
    q = dynamic_area * speed_squared
    return q * cx, q * cy, q * cn * length_overall


def _coefficient_arrays(angle, p, frontal_area, lateral_area, length_overall, lateral_centre):
    """CX, CY, CN as arrays (the same operations as :func:`blendermann_loads`)."""
    outside = (angle > math.pi) | (angle < -math.pi)
    turns = np.floor((angle + math.pi) / (2.0 * math.pi))
    g = np.where(outside, angle - 2.0 * math.pi * turns, angle)
    side = np.where(g < 0.0, -1.0, 1.0)
    a = np.abs(g)
    aft = a > 0.5 * math.pi
    b = np.where(aft, math.pi - a, a)
    s = np.sin(b)
    c = np.where(aft, -np.cos(b), np.cos(b))
    cd_l_af = np.where(aft, p.cd_longitudinal_stern, p.cd_longitudinal_head)
    cd_l = cd_l_af * (frontal_area / lateral_area)
    sin2 = 2.0 * s * c
    den = 1.0 - 0.5 * p.delta * (1.0 - cd_l / p.cd_transverse) * sin2 * sin2
    cx = -cd_l * c / den
    cy = -side * p.cd_transverse * s / den
    cn = (lateral_centre / length_overall - _ARM_SLOPE * (a - 0.5 * math.pi)) * cy
    return cx, cy, cn


def _geometry(frontal_area, lateral_area, length_overall, lateral_centre):
    af = as_float_array("frontal_area", frontal_area, "m²")
    check_positive("frontal_area", af, "m²")
    al = as_float_array("lateral_area", lateral_area, "m²")
    check_positive("lateral_area", al, "m²")
    loa = as_float_array("length_overall", length_overall, "m")
    check_positive("length_overall", loa, "m")
    sl = as_float_array("lateral_centre", lateral_centre, "m")
    half, sl_b = np.broadcast_arrays(0.5 * loa, sl)
    if not np.all(np.abs(sl_b) <= half):
        bad = sl_b[np.abs(sl_b) > half]
        raise ParameterError(
            "`lateral_centre` must lie within the ship, |s_L| <= length_overall/2 [m], "
            f"got {float(bad.ravel()[0])!r} with length_overall/2 = "
            f"{float(half[np.abs(sl_b) > half].ravel()[0])!r}"
        )
    return af, al, loa, sl


def blendermann_coefficients(
    angle: ArrayLike,
    vessel_type: str | BlendermannCoefficients,
    *,
    frontal_area: ArrayLike,
    lateral_area: ArrayLike,
    length_overall: ArrayLike,
    lateral_centre: ArrayLike = 0.0,
) -> WindCoefficients:
    """Blendermann (1994) wind-load coefficients CX, CY, CN in seahelm's signs.

    Parameters
    ----------
    angle : array_like
        Bearing the apparent wind comes from [rad], measured from the bow, positive from
        starboard (0 head wind, π/2 starboard beam, ±π stern wind); wrapped internally.
    vessel_type : str or BlendermannCoefficients
        A key of :data:`BLENDERMANN_VESSEL_TYPES` or the parameters themselves.
    frontal_area : array_like
        Frontal projected area above water A_F [m²] (> 0).
    lateral_area : array_like
        Lateral projected area above water A_L [m²] (> 0).
    length_overall : array_like
        Length overall L_oa [m] (> 0).
    lateral_centre : array_like, optional
        s_L, longitudinal position of the centre of A_L forward of midships [m]
        (|s_L| ≤ L_oa/2; default 0).

    Returns
    -------
    WindCoefficients
        ``(cx, cy, cn)`` [-], broadcast over the arguments' shapes: CX and CY referred to
        A_L, CN to A_L L_oa; X forward, Y to starboard, N bow-to-starboard positive.

    Raises
    ------
    ParameterError
        If an area or the length is not > 0, the angle is not finite, or s_L is outside the
        ship.
    ValueError
        If ``vessel_type`` is an unknown name.

    Notes
    -----
    With a = |angle| and σ = sign(angle) (Blendermann, 1994; Fossen, 2021, §10.1.2, with
    Fossen's γ_rw = −angle)::

        CD_l = CD_l,AF A_F / A_L   (CD_l,AF(0) for a ≤ π/2, CD_l,AF(π) otherwise)
        D    = 1 − δ/2 (1 − CD_l/CD_t) sin²(2a)
        CX   = −CD_l cos a / D,   CY = −σ CD_t sin a / D,
        CN   = [s_L/L_oa − 0.18 (a − π/2)] CY

    References
    ----------
    Blendermann, W. (1994). Parameter identification of wind loads on ships. J. Wind Eng.
    Ind. Aerodyn. 51, 339–351. Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics
    and Motion Control, 2nd ed., §10.1.2.
    """
    p = get_blendermann_type(vessel_type)
    gamma = as_float_array("angle", angle, "rad")
    af, al, loa, sl = _geometry(frontal_area, lateral_area, length_overall, lateral_centre)
    cx, cy, cn = _coefficient_arrays(gamma, p, af, al, loa, sl)
    return WindCoefficients(np.asarray(cx), np.asarray(cy), np.asarray(cn))


def blendermann_wind_loads(
    relative_speed: ArrayLike,
    angle: ArrayLike,
    vessel_type: str | BlendermannCoefficients,
    *,
    frontal_area: ArrayLike,
    lateral_area: ArrayLike,
    length_overall: ArrayLike,
    lateral_centre: ArrayLike = 0.0,
    rho_air: float = RHO_AIR,
) -> WindLoads:
    """Blendermann (1994) wind force and moment on a ship, in body axes.

    Parameters
    ----------
    relative_speed : array_like
        Apparent (relative) wind speed V_rw [m/s] (≥ 0).
    angle : array_like
        Bearing the apparent wind comes from [rad], measured from the bow, positive from
        starboard (0 head wind, π/2 starboard beam, ±π stern wind); wrapped internally.
    vessel_type : str or BlendermannCoefficients
        A key of :data:`BLENDERMANN_VESSEL_TYPES` or the parameters themselves.
    frontal_area : array_like
        Frontal projected area above water A_F [m²] (> 0).
    lateral_area : array_like
        Lateral projected area above water A_L [m²] (> 0).
    length_overall : array_like
        Length overall L_oa [m] (> 0).
    lateral_centre : array_like, optional
        s_L, longitudinal position of the centre of A_L forward of midships [m]
        (|s_L| ≤ L_oa/2; default 0).
    rho_air : float, optional
        Air density ρ_a [kg/m³] (default :data:`seahelm.constants.RHO_AIR`).

    Returns
    -------
    WindLoads
        ``(surge [N], sway [N], yaw [N·m])``, broadcast over the arguments' shapes; surge
        positive forward, sway to starboard, yaw turning the bow to starboard.

    Raises
    ------
    ParameterError
        If the speed is negative, an area, the length or ρ_a is not > 0, the angle is not
        finite, or s_L is outside the ship.
    ValueError
        If ``vessel_type`` is an unknown name.

    Notes
    -----
    X = ½ ρ_a V_rw² CX A_L, Y = ½ ρ_a V_rw² CY A_L, N = ½ ρ_a V_rw² CN A_L L_oa with CX, CY,
    CN from :func:`blendermann_coefficients` (Blendermann, 1994; Fossen, 2021, §10.1.2).
    :func:`blendermann_loads` is the same computation for one wind, compiled.

    References
    ----------
    Blendermann, W. (1994). Parameter identification of wind loads on ships. J. Wind Eng.
    Ind. Aerodyn. 51, 339–351. Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics
    and Motion Control, 2nd ed., §10.1.2.
    """
    p = get_blendermann_type(vessel_type)
    v = as_float_array("relative_speed", relative_speed, "m/s")
    check_nonnegative("relative_speed", v, "m/s")
    gamma = as_float_array("angle", angle, "rad")
    check_positive("rho_air", as_float_array("rho_air", rho_air, "kg/m³"), "kg/m³")
    af, al, loa, sl = _geometry(frontal_area, lateral_area, length_overall, lateral_centre)
    cx, cy, cn = _coefficient_arrays(gamma, p, af, al, loa, sl)
    q = 0.5 * rho_air * v * v * al
    return WindLoads(np.asarray(q * cx), np.asarray(q * cy), np.asarray(q * cn * loa))
