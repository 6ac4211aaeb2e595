"""Main particulars of a hull and the water it floats in, for the empirical estimates.

:class:`HullForm` holds what Holtrop & Mennen's method (:mod:`.resistance`) reads, in SI units
and radians, and derives what the user does not give: the form coefficients by definition,
C_M and C_WP by the estimates below, the wetted surface S and the half entrance angle i_E by
Holtrop & Mennen's (1982) regressions, the run length L_R. :class:`Water` holds ρ, ν and g.

Defaults and estimates
----------------------
* C_B = ∇/(L B T) on the waterline length and mean draught; C_P = C_B/C_M (definitions).
* C_M, if not given: C_M = 1.006 − 0.0056 C_B^−3.56 (Kerlen 1970, as quoted by Schneekluth &
  Bertram 1998), capped at 0.999.
* C_WP, if not given: C_WP = (1 + 2 C_B)/3 (Schneekluth & Bertram 1998).
* lcb, if not given: 0 (% of L, at midships) -- no estimate; give it, R_W and (1 + k_1)
  depend on it.
* S, if not given: Holtrop & Mennen (1982), p. 167. i_E, if not given: Holtrop & Mennen
  (1982), p. 167. L_R: Holtrop & Mennen (1982), p. 166.
* T_F and T_A default to the mean draught; C_stern 0 (normal section shape); no bulb, transom
  or appendages unless given; (1 + k_2)_eq 1.5 (the appendage factor of Holtrop & Mennen's
  1982 example, rudder behind skeg).
* Water: ρ 1025 kg/m³, ν 1.18831·10⁻⁶ m²/s (ITTC, sea water at 15 °C), g 9.80665 m/s²
  (:data:`SEAWATER_15C`).

References
----------
Holtrop, J. & Mennen, G. G. J. (1982). An approximate power prediction method. International
Shipbuilding Progress 29(335), 166–170.
Schneekluth, H. & Bertram, V. (1998). Ship Design for Efficiency and Economy, 2nd ed.
Butterworth-Heinemann.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._validate import check_nonnegative, check_positive, check_range
from ..constants import GRAVITY, RHO_SEAWATER
from ..errors import ParameterError

__all__ = ["Water", "SEAWATER_15C", "HullForm"]


@dataclass(frozen=True, kw_only=True)
class Water:
    """Water properties for the resistance.

    Attributes
    ----------
    density : float
        ρ [kg/m³].
    kinematic_viscosity : float
        ν [m²/s].
    gravity : float
        g [m/s²].
    """

    density: float = RHO_SEAWATER
    kinematic_viscosity: float = 1.18831e-6
    gravity: float = GRAVITY

    def __post_init__(self) -> None:
        check_positive("density", self.density, "kg/m^3")
        check_positive("kinematic_viscosity", self.kinematic_viscosity, "m^2/s")
        check_positive("gravity", self.gravity, "m/s^2")


SEAWATER_15C = Water()
"""Sea water at 15 °C: ρ 1025 kg/m³, ν 1.18831·10⁻⁶ m²/s (ITTC), standard g."""


@dataclass(frozen=True, kw_only=True)
class HullForm:
    """Main particulars of a hull for Holtrop & Mennen's method (SI units, angles in rad).

    Attributes
    ----------
    length : float
        Waterline length L [m] (L_WL; every L of the method).
    beam : float
        Moulded breadth B [m].
    draft : float
        Mean moulded draught T [m].
    displacement_volume : float
        Moulded displacement volume ∇ [m³].
    draft_fore, draft_aft : float, optional
        T_F, T_A [m] (default: ``draft``).
    midship_coefficient : float, optional
        C_M [-] (default: estimate of Kerlen 1970, see the module notes).
    waterplane_coefficient : float, optional
        C_WP [-] (default: (1 + 2 C_B)/3, Schneekluth & Bertram 1998).
    lcb : float
        Longitudinal centre of buoyancy [% of L, forward of 0.5 L] (default 0).
    wetted_surface : float, optional
        S [m²] of the bare hull (default: Holtrop & Mennen 1982, p. 167).
    half_entrance_angle : float, optional
        i_E [rad] of the waterline at the bow (default: Holtrop & Mennen 1982, p. 167).
    bulb_area : float
        Transverse area of the bulb at the fore perpendicular A_BT [m²] (default 0).
    bulb_centre : float
        Height of the centre of A_BT above the keel h_B [m] (default 0).
    transom_area : float
        Immersed transom area at rest A_T [m²] (default 0).
    appendage_area : float
        Wetted area of the appendages S_APP [m²] (default 0).
    appendage_form_factor : float
        (1 + k_2)_eq [-] of the appendages (default 1.5).
    stern_shape : float
        C_stern [-]: −25 pram with gondola, −10 V sections, 0 normal (default), 10 U
        sections with Hogner stern.
    """

    length: float
    beam: float
    draft: float
    displacement_volume: float
    draft_fore: float | None = None
    draft_aft: float | None = None
    midship_coefficient: float | None = None
    waterplane_coefficient: float | None = None
    lcb: float = 0.0
    wetted_surface: float | None = None
    half_entrance_angle: float | None = None
    bulb_area: float = 0.0
    bulb_centre: float = 0.0
    transom_area: float = 0.0
    appendage_area: float = 0.0
    appendage_form_factor: float = 1.5
    stern_shape: float = 0.0

    def __post_init__(self) -> None:
        for name, unit in (("length", "m"), ("beam", "m"), ("draft", "m"),
                           ("displacement_volume", "m^3"), ("appendage_form_factor", "-")):
            check_positive(name, float(getattr(self, name)), unit)
        for name, unit in (("draft_fore", "m"), ("draft_aft", "m"), ("wetted_surface", "m^2")):
            if getattr(self, name) is not None:
                check_positive(name, float(getattr(self, name)), unit)
        for name, unit in (("bulb_area", "m^2"), ("bulb_centre", "m"), ("transom_area", "m^2"),
                           ("appendage_area", "m^2")):
            check_nonnegative(name, float(getattr(self, name)), unit)
        for name in ("midship_coefficient", "waterplane_coefficient"):
            if getattr(self, name) is not None:
                check_positive(name, float(getattr(self, name)), "-")
                check_range(name, float(getattr(self, name)), 0.0, 1.0, "-")
        check_range("lcb", float(self.lcb), -50.0, 50.0, "% of L")
        check_range("stern_shape", float(self.stern_shape), -25.0, 10.0, "-")
        if self.half_entrance_angle is not None:
            check_range("half_entrance_angle", float(self.half_entrance_angle), 0.0,
                        math.pi / 2, "rad", inclusive=False)
        if not self.block_coefficient < 1.0:
            raise ParameterError(
                f"gives C_B = ∇/(L B T) = {self.block_coefficient:.4g} >= 1 [-]",
                field="displacement_volume", unit="m^3", value=self.displacement_volume)
        if self.prismatic_coefficient >= 1.0:
            raise ParameterError(f"gives C_P = C_B/C_M = {self.prismatic_coefficient:.4g} >= 1 "
                                 "[-]", field="midship_coefficient", unit="-",
                                 value=self.midship_coefficient)
        self._check_lcb()
        if self.bulb_area > 0 and not self.bulb_centre < self.fore_draft:
            raise ParameterError(f"must be below the fore draught T_F = {self.fore_draft:g} [m], "
                                 f"got {self.bulb_centre!r}", field="bulb_centre", unit="m",
                                 value=self.bulb_centre)

    def _check_lcb(self) -> None:
        """lcb within what Holtrop & Mennen (1982)'s regressions can take for this C_P: their
        terms (1 − C_P + 0.0225 lcb) (form factor, thrust deduction) and, where the entrance
        angle is estimated, (1 − C_P − 0.0225 lcb) are raised to fractional powers, and the run
        length L_R must be > 0; outside, the powers are complex (``TypeError`` before)."""
        cp = self.prismatic_coefficient
        limit = (1.0 - cp) / 0.0225
        low, high = -limit, (limit if self.half_entrance_angle is None else 50.0)
        # L_R = L (1 − C_P + 0.06 C_P lcb/(4 C_P − 1)) > 0 bounds lcb below too
        if 4.0 * cp - 1.0 > 0:
            low = max(low, -(1.0 - cp) * (4.0 * cp - 1.0) / (0.06 * cp))
        if not low < self.lcb < high:
            raise ParameterError(
                f"must be in ({low:.3g}, {high:.3g}) [% of L] for the prismatic coefficient "
                f"C_P = {cp:.3g} (Holtrop & Mennen 1982's terms 1 − C_P ± 0.0225 lcb and the run "
                f"length must be > 0), got {self.lcb!r}", field="lcb", unit="% of L",
                value=self.lcb)

    # -- derived particulars (definitions and the documented estimates) -------------------
    @property
    def fore_draft(self) -> float:
        """T_F [m]."""
        return float(self.draft if self.draft_fore is None else self.draft_fore)

    @property
    def aft_draft(self) -> float:
        """T_A [m]."""
        return float(self.draft if self.draft_aft is None else self.draft_aft)

    @property
    def block_coefficient(self) -> float:
        """C_B = ∇/(L B T) [-]."""
        return float(self.displacement_volume / (self.length * self.beam * self.draft))

    @property
    def midship(self) -> float:
        """C_M [-], given or estimated: 1.006 − 0.0056 C_B^−3.56 (Kerlen 1970)."""
        if self.midship_coefficient is not None:
            return float(self.midship_coefficient)
        return min(1.006 - 0.0056 * self.block_coefficient ** -3.56, 0.999)

    @property
    def prismatic_coefficient(self) -> float:
        """C_P = C_B/C_M [-]."""
        return self.block_coefficient / self.midship

    @property
    def waterplane(self) -> float:
        """C_WP [-], given or estimated: (1 + 2 C_B)/3 (Schneekluth & Bertram 1998)."""
        if self.waterplane_coefficient is not None:
            return float(self.waterplane_coefficient)
        return (1.0 + 2.0 * self.block_coefficient) / 3.0

    @property
    def run_length(self) -> float:
        """L_R = L (1 − C_P + 0.06 C_P lcb/(4 C_P − 1)) [m], Holtrop & Mennen (1982)."""
        cp = self.prismatic_coefficient
        return self.length * (1.0 - cp + 0.06 * cp * self.lcb / (4.0 * cp - 1.0))

    @property
    def surface(self) -> float:
        """S [m²], given or Holtrop & Mennen (1982), p. 167::

            S = L (2T + B) √C_M (0.453 + 0.4425 C_B − 0.2862 C_M − 0.003467 B/T
                + 0.3696 C_WP) + 2.38 A_BT/C_B

        A given ``wetted_surface`` overrides it.
        """
        if self.wetted_surface is not None:
            return float(self.wetted_surface)
        L, B, T, cb, cm = self.length, self.beam, self.draft, self.block_coefficient, self.midship
        return (L * (2 * T + B) * math.sqrt(cm) * (0.453 + 0.4425 * cb - 0.2862 * cm
                                                    - 0.003467 * B / T + 0.3696 * self.waterplane)
                + 2.38 * self.bulb_area / cb)

    @property
    def entrance_angle(self) -> float:
        """i_E [deg] (the regression's unit), given or Holtrop & Mennen (1982), p. 167::

            i_E = 1 + 89 exp{−(L/B)^0.80856 (1 − C_WP)^0.30484 (1 − C_P − 0.0225 lcb)^0.6367
                  (L_R/B)^0.34574 (100 ∇/L³)^0.16302}

        A given ``half_entrance_angle`` overrides it.
        """
        if self.half_entrance_angle is not None:
            return math.degrees(self.half_entrance_angle)
        L, B, cp = self.length, self.beam, self.prismatic_coefficient
        return 1.0 + 89.0 * math.exp(
            -(L / B) ** 0.80856 * (1.0 - self.waterplane) ** 0.30484
            * (1.0 - cp - 0.0225 * self.lcb) ** 0.6367 * (self.run_length / B) ** 0.34574
            * (100.0 * self.displacement_volume / L**3) ** 0.16302)
