"""A complete MMG ship from its main particulars: every coefficient estimated, with its source.

:func:`estimate_ship` turns a :class:`Design` — L, B, T (fore/aft), C_b and the test speed, plus
whatever else the user knows (displacement, x_G, propeller, rudder, water depth) — into a
:class:`~seahelm.ships.Ship` of the MMG standard model (:mod:`seahelm.vessels.mmg`) that runs
wherever a catalog ship runs. Each coefficient comes from a published estimate of
:mod:`seahelm.hydrodynamics`, and its formula is kept on the ship
(:attr:`Ship.coefficient_sources <seahelm.ships.Ship.coefficient_sources>`, written into the ship
file's ``[provenance.coefficients]``):

=====================================  ======================================================
hull: m'_x, m'_y, J'_z                 Motora's charts as regressions (``hull_derivatives``)
hull: Y'_v, Y'_r, N'_v, N'_r           Kijima et al. (1990), with trim
hull: X'_vv … N'_rrr                   Yoshimura & Masumoto (2012)
R'_0                                   Holtrop & Mennen (1982), Holtrop (1984) at the test speed
K_T(J): k_0, k_1, k_2                  Wageningen B-series (Oosterveld & van Oossanen 1975), fit
w_P0, t_P                              Holtrop (1984), single screw
f_α                                    Fujii & Tsuda (1961)
t_R, a_H, ε, κ, γ_R                    Kijima et al. (1990)
x'_H, l'_R, x'_R, x'_P, C_1, C_2       typical values (said so)
A_R, H_R, D_P, P/D, A_E/A_0, Z         the user's, else DNV's minimum rudder area, H_R = 0.75 T,
                                       D_P = 0.65 T, B4-55 with P/D 0.8 (said so)
=====================================  ======================================================

Every regression warns (:class:`~seahelm.errors.ValidityRangeWarning`) when the design is outside
its data, naming the formula, the parameter and the range; under
:class:`~seahelm.errors.strict_validity` that is an error. A value that is not physical is a
:class:`~seahelm.errors.ParameterError` naming the field, its unit and the value.

:func:`estimate_nomoto` gives the linear model of Clarke et al. (1983) with the same rudder and
the Nomoto K, T_1, T_2, T_3 it implies, as a ``nomoto2`` or ``nomoto1`` ship.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings
from typing import Any

import numpy as np

from ..constants import GRAVITY
from ..errors import ParameterError, ValidityRangeWarning, warn_validity
from ..hydrodynamics.hull import Coefficient, HullParticulars, check_ranges
from ..hydrodynamics.hull_derivatives import hull_derivatives
from ..hydrodynamics.linear_model import NomotoConstants, clarke_derivatives, nomoto_constants
from ..hydrodynamics.propeller_series import fit_thrust_polynomial
from ..hydrodynamics.rudder_propeller import (
    interaction_coefficients,
    rudder_area_dnv,
    rudder_lift_slope,
    wake_fraction_taylor,
)
from ..vessels.particulars import Particulars
from .ship import Propulsion, Ship, SteeringGear

__all__ = ["Design", "estimate_ship", "estimate_nomoto", "DESIGN_FIELDS"]

#: IMO's minimum steering-gear rate (SOLAS II-1/29: 35° one side to 30° the other in 28 s).
IMO_RUDDER_RATE = math.radians(65.0 / 28.0)

#: The fields of :class:`Design`: (name, unit, required, what it is); the CLI options and the
#: particulars file's keys are these (angles in degrees there, with ``_deg``).
DESIGN_FIELDS: tuple[tuple[str, str, bool, str], ...] = (
    ("name", "", False, "the ship's name"),
    ("length", "m", True, "length between perpendiculars L_pp"),
    ("beam", "m", True, "moulded breadth B"),
    ("draft", "m", False, "mean draught T (or draft_fore and draft_aft)"),
    ("draft_fore", "m", False, "draught at the fore perpendicular"),
    ("draft_aft", "m", False, "draught at the aft perpendicular"),
    ("block_coefficient", "-", True, "block coefficient C_b"),
    ("speed", "m/s", True, "test (approach) speed U_0"),
    ("displacement", "m³", False, "displacement volume ∇ (default C_b L B T)"),
    ("x_G", "m", False, "centre of gravity forward of midship (default 0)"),
    ("propeller_diameter", "m", False, "propeller diameter D_P (default 0.65 T)"),
    ("pitch_ratio", "-", False, "propeller pitch ratio P/D (default 0.8)"),
    ("area_ratio", "-", False, "expanded blade-area ratio A_E/A_0 (default 0.55)"),
    ("blades", "-", False, "number of blades Z (default 4)"),
    ("rudder_area", "m²", False, "movable rudder area A_R (default DNV's minimum)"),
    ("rudder_span", "m", False, "rudder span H_R (default 0.75 T, at least D_P)"),
    ("max_rudder", "rad", False, "steering-gear angle limit (default 35°)"),
    ("rudder_rate", "rad/s", False, "steering-gear rate (default IMO's minimum 2.32°/s)"),
    ("rho", "kg/m³", False, "water density (default 1025, sea water)"),
    ("water_depth", "m", False, "water depth h (default deep water)"),
    ("wetted_surface", "m²", False, "wetted surface S (default Holtrop's estimate)"),
    ("lcb", "%", False, "longitudinal centre of buoyancy, % of L forward of midship (default "
                        "0; Holtrop's resistance and wake use it)"),
    ("metacentric_height", "m", False, "transverse metacentric height GM (kept in the "
                                       "particulars: the closed-form roll RAO; default unknown)"),
    # the windage (seahelm.ships.windage): estimated with vessel_type, what is missing of it
    ("vessel_type", "", False, "Blendermann's vessel type: with it the windage is written "
                               "(what is not given of it estimated; default none)"),
    ("hull_depth", "m", False, "moulded depth D (the windage's freeboard D - T)"),
    ("length_overall", "m", False, "length overall L_oa (windage)"),
    ("lateral_area", "m²", False, "lateral windage area A_L"),
    ("frontal_area", "m²", False, "frontal windage area A_F"),
    ("windage_centre", "m", False, "centre of A_L forward of midships s_L"),
)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Design:
    """What is known of a single-screw, single-rudder ship (SI units, radians).

    See :data:`DESIGN_FIELDS` for every field, its unit and default. Give ``draft`` or both
    ``draft_fore`` and ``draft_aft`` (trim τ = T_a − T_f).
    """

    length: float
    beam: float
    block_coefficient: float
    speed: float
    name: str = "estimated-ship"
    draft: float | None = None
    draft_fore: float | None = None
    draft_aft: float | None = None
    displacement: float | None = None
    x_G: float = 0.0
    propeller_diameter: float | None = None
    pitch_ratio: float | None = None
    area_ratio: float | None = None
    blades: int = 4
    rudder_area: float | None = None
    rudder_span: float | None = None
    max_rudder: float = math.radians(35.0)
    rudder_rate: float = IMO_RUDDER_RATE
    rho: float = 1025.0
    water_depth: float = math.inf
    wetted_surface: float | None = None
    lcb: float = 0.0
    metacentric_height: float | None = None
    vessel_type: str | None = None
    hull_depth: float | None = None
    length_overall: float | None = None
    lateral_area: float | None = None
    frontal_area: float | None = None
    windage_centre: float | None = None

    def __post_init__(self) -> None:
        units = {n: u for n, u, _, _ in DESIGN_FIELDS}
        if not isinstance(self.name, str) or not self.name.strip():
            raise ParameterError(f"must be a non-empty text, got {self.name!r}", field="name")
        for name, unit in units.items():
            value = getattr(self, name)
            if name in ("name", "vessel_type") or value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
                raise ParameterError(f"must be a number [{unit}], got {value!r}", field=name,
                                     unit=unit, value=value)
            value = float(value)
            if math.isnan(value) or (math.isinf(value) and name != "water_depth"):
                raise ParameterError(f"must be finite [{unit}], got {value!r}", field=name,
                                     unit=unit, value=value)
            if name not in ("x_G", "lcb", "windage_centre") and not value > 0:
                raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=name,
                                     unit=unit, value=value)
            object.__setattr__(self, name, int(value) if name == "blades" else value)
        if self.blades != getattr(self, "blades") or not 2 <= self.blades <= 7:
            raise ParameterError(f"must be a whole number of blades, 2 to 7 (the B-series), got "
                                 f"{self.blades!r}", field="blades", unit="-", value=self.blades)
        fore_aft = (self.draft_fore is not None, self.draft_aft is not None)
        if self.draft is None and not all(fore_aft):
            raise ParameterError("is required [m] (or both draft_fore and draft_aft)",
                                 field="draft", unit="m")
        if any(fore_aft) and not all(fore_aft):
            missing = "draft_aft" if fore_aft[0] else "draft_fore"
            raise ParameterError(f"is required [m] with {'draft_fore' if fore_aft[0] else 'draft_aft'}",
                                 field=missing, unit="m")
        if self.draft is not None and all(fore_aft):
            mean = 0.5 * (self.draft_fore + self.draft_aft)
            if abs(mean - self.draft) > 1e-6 * self.draft:
                raise ParameterError(
                    f"is {self.draft!r} [m] but (draft_fore + draft_aft)/2 = {mean!r} [m]; give "
                    "one of them", field="draft", unit="m", value=self.draft)
        if self.max_rudder > math.radians(90.0):
            raise ParameterError(f"must be at most 90° (π/2 rad), got {self.max_rudder!r} [rad]",
                                 field="max_rudder", unit="rad", value=self.max_rudder)
        if self.froude_number > 1.0:  # (the regressions are for displacement ships, Fn < 0.45)
            raise ParameterError(
                f"gives a Froude number {self.froude_number:.3g} > 1 (a displacement ship's "
                f"estimates hold below 0.45) [m/s], got {self.speed!r}", field="speed",
                unit="m/s", value=self.speed)
        draft = self.mean_draft
        if self.propeller_diameter is not None and not self.propeller_diameter < draft:
            raise ParameterError(f"must be less than the draft {draft!r} [m], got "
                                 f"{self.propeller_diameter!r}", field="propeller_diameter",
                                 unit="m", value=self.propeller_diameter)
        if not self.water_depth > draft:
            raise ParameterError(f"must be greater than the draft {round(draft, 12)!r} [m], got "
                                 f"{self.water_depth!r}", field="water_depth", unit="m",
                                 value=self.water_depth)
        self.hull  # (validates L, B, C_b, trim, ∇, x_G)
        self.windage(warn=False)  # (validates the windage's fields)

    def windage(self, *, warn: bool = True) -> Any:
        """The windage (:func:`seahelm.ships.windage.design_windage`; None without
        ``vessel_type``).

        Parameters
        ----------
        warn : bool, default True
            Warn once when areas are estimated rather than given.

        Returns
        -------
        object or None
            The windage particulars, or None without ``vessel_type``.
        """
        from .windage import design_windage

        return design_windage(self, warn=warn)

    @property
    def mean_draft(self) -> float:
        """Mean draught T [m]."""
        if self.draft is not None:
            return float(self.draft)
        return 0.5 * (float(self.draft_fore) + float(self.draft_aft))

    @property
    def trim(self) -> float:
        """Trim τ = T_a − T_f [m] (0 without fore and aft draughts)."""
        if self.draft_fore is None:
            return 0.0
        return float(self.draft_aft) - float(self.draft_fore)

    @property
    def hull(self) -> HullParticulars:
        """The hull particulars of the estimates."""
        return HullParticulars(length=self.length, beam=self.beam, draft=self.mean_draft,
                               block_coefficient=self.block_coefficient, trim=self.trim,
                               displacement=self.displacement, x_G=self.x_G)

    @property
    def froude_number(self) -> float:
        """Fn = U/√(g L) [-]."""
        return self.speed / math.sqrt(GRAVITY * self.length)

    @classmethod
    def from_mapping(cls, values: dict[str, Any]) -> "Design":
        """From a mapping of :data:`DESIGN_FIELDS` (angles also as ``<name>_deg``).

        Parameters
        ----------
        values : dict
            The particulars by field name (SI units; ``max_rudder_deg``, ``rudder_rate_deg``
            in degrees).

        Returns
        -------
        Design

        Raises
        ------
        ParameterError
            An unknown key (naming the close match), a missing required one, a bad value.
        """
        import difflib

        valid = {n for n, _, _, _ in DESIGN_FIELDS}
        angles = {n for n, u, _, _ in DESIGN_FIELDS if u.startswith("rad")}
        kwargs: dict[str, Any] = {}
        for key, value in values.items():
            if key.endswith("_deg") and key[:-4] in angles:
                if key[:-4] in values:
                    raise ParameterError(f"give `{key[:-4]}` or `{key}`, not both", field=key)
                if isinstance(value, bool) or not isinstance(value, (int, float)):
                    raise ParameterError(f"must be a number [deg], got {value!r}", field=key,
                                         unit="deg", value=value)
                kwargs[key[:-4]] = math.radians(value)
            elif key in valid:
                kwargs[key] = value
            else:
                close = difflib.get_close_matches(key, sorted(valid), n=1)
                hint = f" (did you mean '{close[0]}'?)" if close else ""
                raise ParameterError(f"is not a particular{hint}; valid: "
                                     f"{', '.join(n for n, _, _, _ in DESIGN_FIELDS)}", field=key)
        missing = [f"{n} [{u}]" for n, u, req, _ in DESIGN_FIELDS if req and n not in kwargs]
        if missing:
            raise ParameterError(f"misses required particular(s): {', '.join(missing)}",
                                 field=missing[0].split()[0])
        return cls(**kwargs)


@functools.lru_cache(maxsize=64)
def _fit_and_warnings(pitch_ratio: float, area_ratio: float, blades: int
                      ) -> tuple[Any, tuple[tuple[str, type[Warning]], ...]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fit = fit_thrust_polynomial(pitch_ratio, area_ratio, blades, strict=False)
    return fit, tuple((str(w.message), w.category) for w in caught)


def _thrust_fit(pitch_ratio: float, area_ratio: float, blades: int, strict: bool | None
                ) -> Any:
    """:func:`fit_thrust_polynomial` of one propeller, fitted once per process and reused, its
    warnings said again (an error in strict mode) at every use: a Monte-Carlo study that
    varies the hull, not the propeller, estimates a ship per sample, and the fit was three
    quarters of each estimate."""
    fit, said = _fit_and_warnings(float(pitch_ratio), float(area_ratio), int(blades))
    for message, category in said:
        if issubclass(category, ValidityRangeWarning):
            warn_validity(message, strict=strict)
        else:
            warnings.warn(message, category, stacklevel=4)
    return fit


def _propeller(design: Design, strict: bool | None) -> dict[str, Coefficient]:
    draft = design.mean_draft
    out: dict[str, Coefficient] = {}
    if design.propeller_diameter is None:
        out["propeller_diameter"] = Coefficient(0.65 * draft, "seahelm assumption: D_P = 0.65 T")
    else:
        out["propeller_diameter"] = Coefficient(design.propeller_diameter, "given")
    pd = design.pitch_ratio if design.pitch_ratio is not None else 0.8
    ae = design.area_ratio if design.area_ratio is not None else 0.55
    given = "given" if design.pitch_ratio is not None and design.area_ratio is not None \
        else "P/D, A_E/A_0 assumed 0.8, 0.55 where not given"
    fit = _thrust_fit(pd, ae, design.blades, strict)
    text = (f"Wageningen B-series (Oosterveld & van Oossanen 1975) B{design.blades}-"
            f"{round(ae * 100)} P/D {pd:g} ({given}), least-squares quadratic over J "
            f"{fit.J_min:.3g}..{fit.J_max:.3g} (max. error {fit.max_error:.2g} in K_T)")
    for name in ("k_0", "k_1", "k_2"):
        out[name] = Coefficient(float(getattr(fit, name)), text)
    return out


def _rudder(design: Design, diameter: float, strict: bool | None) -> dict[str, Coefficient]:
    hull = design.hull
    out: dict[str, Coefficient] = {}
    if design.rudder_area is None:
        out["rudder_area"] = rudder_area_dnv(hull)
    else:
        out["rudder_area"] = Coefficient(design.rudder_area, "given")
    if design.rudder_span is None:
        span = max(0.75 * design.mean_draft, diameter)
        out["rudder_span"] = Coefficient(span, "seahelm assumption: H_R = 0.75 T (at least D_P)")
    else:
        if design.rudder_span < diameter:
            raise ParameterError(f"must be at least the propeller diameter {diameter:.6g} [m], "
                                 f"got {design.rudder_span!r}", field="rudder_span", unit="m",
                                 value=design.rudder_span)
        out["rudder_span"] = Coefficient(design.rudder_span, "given")
    out["f_alpha"] = rudder_lift_slope(out["rudder_span"].value, out["rudder_area"].value,
                                       strict=strict)
    return out


def _resistance(design: Design, diameter: float, strict: bool | None
                ) -> dict[str, Coefficient]:
    """R'_0 at the test speed, w_P0 and t_P by Holtrop & Mennen (single screw)."""
    from ..hydrodynamics.hull_form import HullForm, Water
    from ..hydrodynamics.resistance import resistance_coefficient, thrust_deduction, wake_fraction

    hull = design.hull
    form = HullForm(length=design.length, beam=design.beam, draft=design.mean_draft,
                    displacement_volume=hull.volume, draft_fore=design.draft_fore,
                    draft_aft=design.draft_aft, wetted_surface=design.wetted_surface,
                    lcb=design.lcb)
    water = Water(density=design.rho)
    r0 = float(resistance_coefficient(form, design.speed, water=water, strict=strict))
    holtrop = "Holtrop (1984)"
    try:
        w = float(wake_fraction(form, design.speed, diameter, water=water))
    except (ValueError, ZeroDivisionError):  # (1.45 C_P − 0.315 − 0.0225 lcb ≥ 1: no root)
        w = math.nan
    wake_source = f"{holtrop}, single screw, conventional stern, at the test speed"
    if not 0.0 <= w <= 0.7:
        from ..errors import warn_validity

        taylor = wake_fraction_taylor(hull, strict=False)
        warn_validity(
            f"{holtrop}'s wake fraction is not defined for C_P = "
            f"{form.prismatic_coefficient:.3g} (it gives {w:.3g}; its data: C_P <= 0.85): "
            f"Taylor's w_P0 = 0.5 C_b - 0.05 = {taylor.value:.3g} used instead", strict=strict,
            stacklevel=3)
        w, wake_source = taylor.value, taylor.source + f" ({holtrop}'s is not defined here)"
    t = float(thrust_deduction(form, diameter))
    surface = ("given S" if design.wetted_surface is not None
               else "S by Holtrop & Mennen's estimate")
    return {
        "R_0": Coefficient(r0, f"Holtrop & Mennen (1982) / {holtrop} total resistance at the "
                               f"test speed ({surface}; L_WL = L_pp, no bulb, transom or "
                               "appendages), R'_0 = R_T/(½ρ L d U²)"),
        "w_P0": Coefficient(w, wake_source),
        "t_P": Coefficient(t, f"{holtrop}, single screw, conventional stern"),
    }


def estimate_coefficients(design: Design, *, strict: bool | None = None
                          ) -> dict[str, Coefficient]:
    """Every :class:`~seahelm.vessels.mmg.MMGParams` field of ``design``, with its source.

    Parameters
    ----------
    design : Design
    strict : bool, optional
        Raise instead of warning outside a regression's data.

    Returns
    -------
    dict of str to Coefficient
    """
    hull = design.hull
    check_ranges("the MMG estimates (Froude number)", {"Fn": (design.froude_number, 0.05,
                                                              0.35)}, strict=strict)
    out: dict[str, Coefficient] = {
        "length": Coefficient(design.length, "given"),
        "breadth": Coefficient(design.beam, "given"),
        "draft": Coefficient(design.mean_draft, "given"),
        "displacement": Coefficient(hull.volume, "given" if design.displacement is not None
                                    else "C_b L B T"),
        "x_G": Coefficient(design.x_G, "given" if design.x_G else "assumed 0 (not given)"),
        "gyration_radius": Coefficient(0.25, "seahelm assumption: k_zz = 0.25 L_pp (the MMG "
                                             "standard method's value for the KVLCC2)"),
        "rho": Coefficient(design.rho, "given" if design.rho != 1025.0 else "sea water"),
        "approach_speed": Coefficient(design.speed, "given"),
    }
    out.update(hull_derivatives(hull, strict=strict))
    out.update(interaction_coefficients(hull, strict=strict))
    prop = _propeller(design, strict)
    out.update(prop)
    out.update(_rudder(design, prop["propeller_diameter"].value, strict))
    out.update(_resistance(design, prop["propeller_diameter"].value, strict))
    return out


def estimate_ship(design: Design, *, strict: bool | None = None) -> Ship:
    """The MMG ship of ``design`` (module docstring), in its water depth.

    Parameters
    ----------
    design : Design
    strict : bool, optional
        Raise instead of warning outside a regression's data.

    Returns
    -------
    Ship
    """
    from ..actuators.servo import ServoParams
    from ..vessels.mmg import MMGParams

    coefficients = estimate_coefficients(design, strict=strict)
    params = MMGParams(**{k: float(c.value) for k, c in coefficients.items()})
    gear = SteeringGear(
        actuator="rudder-servo",
        params=ServoParams(max_angle=design.max_rudder, max_rate=design.rudder_rate,
                           time_constant=1.0),
        provenance="given" if design.rudder_rate != IMO_RUDDER_RATE else
        "IMO's minimum rate (SOLAS II-1/29: 35° to 30° the other side in 28 s, 2.32°/s); "
        "lag 1 s (assumed)")
    from .windage import windage_particulars

    wind, said, noted = windage_particulars(design.windage())
    particulars = Particulars(length=design.length, beam=design.beam, draft=design.mean_draft,
                              block_coefficient=design.block_coefficient,
                              displacement=design.displacement,
                              metacentric_height=design.metacentric_height,
                              provenance="given (seahelm ship estimate)" + said, **wind)
    sources = tuple((k, c.source) for k, c in coefficients.items() if c.source != "given")
    ship = Ship(
        name=design.name, model="mmg", params=params,
        description=f"estimated from main particulars (L {design.length:g} m, B "
                    f"{design.beam:g} m, T {design.mean_draft:g} m, C_b "
                    f"{design.block_coefficient:g})",
        steering_gear=gear,
        propulsion=Propulsion(kind="single fixed-pitch propeller (B-series estimate)",
                              inputs=("propeller_rps",),
                              provenance="seahelm ship estimate"),
        particulars=particulars,
        provenance="estimated from the main particulars by seahelm ship estimate: every "
                   "coefficient's formula is in provenance.coefficients",
        coefficient_sources=sources,
        validity=("deep water", "estimated from main particulars by regressions: expect tens of "
                  "per cent on some derivatives (see the docs' validation)",
                  "ahead motion only (u > 0)") + noted)
    if not math.isinf(design.water_depth):
        ship = ship.at_depth(design.water_depth, strict=strict)
    return ship


def _rudder_derivatives(params: Any) -> dict[str, float]:
    """The MMG rudder's linear derivatives (prime system on L·d) in a straight run at
    self-propulsion: Y'_δ, N'_δ and its contributions to Y'_v, Y'_r, N'_v, N'_r.

    The propeller loading 8 K_T/(π J²) follows from the thrust that balances the resistance,
    T = R'_0 ½ρ L d U² / (1 − t_P), without the rps: 8 K_T/(π J²) = 8 T/(π ρ D² u_P²). With
    F_N = ½ρ A_R f_α u_R (u_R δ − v_R), v_R = −γ_R (v + l'_R r L) for small motions, Y_R =
    −(1 + a_H) F_N and N_R = −(x_R + a_H x_H) F_N (Yasukawa & Yoshimura 2015).
    """
    p = params
    u_p = 1.0 - p.w_P0  # u_P / U
    thrust = p.R_0 * 0.5 * p.length * p.draft / (1.0 - p.t_P)  # T / (ρ U²)
    loading = 8.0 * thrust / (math.pi * p.propeller_diameter ** 2 * u_p ** 2)
    eta = p.propeller_diameter / p.rudder_span
    jet = 1.0 + p.kappa * (math.sqrt(1.0 + loading) - 1.0)
    u_r = p.epsilon * u_p * math.sqrt(eta * jet ** 2 + 1.0 - eta)  # u_R / U
    lift = p.rudder_area * p.f_alpha / (p.length * p.draft)
    arm_y = -(1.0 + p.a_H)
    arm_n = -(p.x_R + p.a_H * p.x_H)
    gamma = 0.5 * (p.gamma_R_plus + p.gamma_R_minus)
    return {"Y_delta": arm_y * lift * u_r * u_r, "N_delta": arm_n * lift * u_r * u_r,
            "Y_v": arm_y * lift * u_r * gamma, "N_v": arm_n * lift * u_r * gamma,
            "Y_r": arm_y * lift * u_r * gamma * p.l_R, "N_r": arm_n * lift * u_r * gamma * p.l_R}


def estimate_nomoto(design: Design, *, order: int = 2, strict: bool | None = None) -> Ship:
    """The Nomoto ship of ``design``: Clarke et al.'s (1983) linear hull with the MMG rudder.

    The linear derivatives are Clarke's (prime system on L², converted to L·d by L/d), taken as
    the bare hull's; the rudder's Y'_δ, N'_δ and its share of the sway and yaw damping are the
    estimated MMG rudder's in a straight run at self-propulsion (:func:`_rudder_derivatives`).

    Parameters
    ----------
    design : Design
    order : {1, 2}
        Nomoto's first- (K, T = T_1 + T_2 − T_3) or second-order model (K, T_1, T_2, T_3).
    strict : bool, optional
        Raise instead of warning outside a regression's data.

    Returns
    -------
    Ship
        Of model ``nomoto1`` or ``nomoto2`` at the design speed. A course-unstable hull (a
        positive pole: T_1 < 0, K < 0, valid in Nomoto's form, Fossen 2021, §7.1) is returned
        as such, flagged in its description and ``validity`` (``course-unstable: ...``).

    Raises
    ------
    ParameterError
        For shallow water, a bad ``order``, complex poles, or a first-order T = T_1 + T_2 − T_3
        of the other sign than K.
    """
    if order not in (1, 2):
        raise ParameterError(f"must be 1 or 2, got {order!r}", field="order", value=order)
    if not math.isinf(design.water_depth):
        raise ParameterError("Clarke's linear model is for deep water; for shallow water use "
                             "the MMG estimate", field="water_depth", unit="m",
                             value=design.water_depth)
    constants, sources = nomoto_of(design, strict=strict)
    unstable = constants.t1 < 0
    mmg = estimate_ship(design, strict=strict)
    if order == 2:
        from ..vessels.nomoto import Nomoto2Params as P

        params = P(gain=constants.gain, t1=constants.t1, t2=constants.t2, t3=constants.t3,
                   speed=design.speed, length=design.length)
    else:
        from ..vessels.nomoto import Nomoto1Params as P  # type: ignore[assignment]

        params = P(gain=constants.gain, time_constant=constants.time_constant,
                   speed=design.speed, length=design.length)
    flag = (f"course-unstable: T1 = {constants.t1:.4g} s < 0 (a positive pole "
            f"{-1.0 / constants.t1:.3g} 1/s), K = {constants.gain:.4g} 1/s < 0",) if unstable \
        else ()
    return Ship(
        name=design.name, model=f"nomoto{order}", params=params,
        description=f"Nomoto {order} from Clarke et al. (1983) and the estimated rudder "
                    f"(L {design.length:g} m, U {design.speed:g} m/s)"
                    + (", course-unstable (T1 < 0)" if unstable else ""),
        steering_gear=mmg.steering_gear, particulars=mmg.particulars,
        provenance="Clarke, Gedling & Hine (1983) linear derivatives with the MMG rudder of "
                   "seahelm ship estimate, at the design speed: " + sources,
        validity=("linear: small rudder angles and yaw rates; constant speed U", "deep water")
        + flag)


def nomoto_of(design: Design, *, strict: bool | None = None) -> tuple[NomotoConstants, str]:
    """Nomoto constants of Clarke's linear hull with the estimated rudder, and their source."""
    from ..vessels.mmg import MMGParams

    hull = design.hull
    coefficients = estimate_coefficients(design, strict=strict)
    p = MMGParams(**{k: float(c.value) for k, c in coefficients.items()})
    c = {k: v.value for k, v in clarke_derivatives(hull, strict=strict).items()}
    scale = design.length / design.mean_draft  # prime on L² -> on L·d
    m = hull.mass_nd  # on L·d (∇/(½L²d))
    x_g = design.x_G / design.length
    inertia = m * 0.25 ** 2
    mass = np.array([[m - c["Y_vdot"] * scale, m * x_g - c["Y_rdot"] * scale],
                     [m * x_g - c["N_vdot"] * scale, inertia - c["N_rdot"] * scale]])
    damping = np.array([[-c["Y_v"] * scale, m - c["Y_r"] * scale],
                        [-c["N_v"] * scale, m * x_g - c["N_r"] * scale]])
    rudder = _rudder_derivatives(p)
    # Clarke's regressions are the hull's (as MSS's clarke83 uses them); the rudder's share of
    # the damping is added from the estimated rudder
    damping -= np.array([[rudder["Y_v"], rudder["Y_r"]], [rudder["N_v"], rudder["N_r"]]])
    constants = nomoto_constants(mass, damping, np.array([rudder["Y_delta"], rudder["N_delta"]]),
                                 length=design.length, speed=design.speed, require_stable=False)
    return constants, ("; ".join(f"{k}' {v:.4g}" for k, v in rudder.items())
                       + " (rudder, on L·d); Clarke's derivatives on L²: "
                       + ", ".join(f"{k} {v:.4g}" for k, v in c.items()))
