"""The windage of an estimated ship: L_oa, lateral and frontal areas, their centre, the type.

``seahelm ship estimate`` writes the windage particulars the wind loads need
(:func:`seahelm.environment.loads.ship_load_params`: Blendermann 1994's ``vessel_type``,
``length_overall`` L_oa, ``lateral_area`` A_L, ``frontal_area`` A_F, ``windage_centre`` s_L),
so that an estimated ship takes wind without hand edits. What the user gives is kept as given;
what is missing is estimated by :func:`estimate_windage`, said so in the ship file's
``[provenance] particulars`` and its ``validity``, and warned about.

Source and what it is not
-------------------------
No published regression of A_L and A_F on the main particulars with its numbers could be
reached for this (Fujiwara, Ueno & Nimura 1998 and the simple method of Ueno, Kitamura,
Sogihara & Fujiwara 2012 / Kitamura et al. 2017, which estimate A_L, A_F and the other
above-water parameters from L_oa and B per ship type, give their coefficients in tables that
were not available). The estimate is therefore a plain geometric relation, the rule the
catalog's KVLCC2 files document for their windage (``kvlcc2-full``: "the hull above the
waterline ... plus a typical aft superstructure of 40 m x 15 m"):

    A_L = L_oa (D − T) + l_s h_s,       A_F = B (D − T) + b_s h_s,

the freeboard band of the hull (moulded depth D less the draught T; no sheer, camber or
bulwark) plus one block of superstructure of length l_s, breadth b_s and height h_s above the
deck. The lateral centre s_L (forward of midships) is the area-weighted centre of the band
(at midships) and of the block (its centre at x_s). The block's proportions are the catalog
KVLCC2's (SIMMAN 2008 particulars L_pp 320 m, B 58 m, T 20.8 m, D 30 m; superstructure
40 m x 15 m x 40 m, its centre 140 m aft of midships): l_s = 0.125 L_pp, h_s = 0.0469 L_pp,
b_s = 0.69 B, x_s = −0.4375 L_pp, and D = T / 0.693 when D is not given (its T/D = 20.8/30).
L_oa, when not given, is 1.0156 L_pp (the KVLCC2's 325/320).

That is a tanker's arrangement (accommodation aft, a flush deck), so only Blendermann's tanker
types are estimated (:data:`ESTIMATED_TYPES`; ``tanker-ballast`` needs D, since its draught is
not the loaded one the T/D is of); for any other type give the areas (``lateral_area``,
``frontal_area``; ``windage_centre`` defaults to midships), or they are refused naming the
keys. The estimate is a rough one — expect tens of per cent on A_L and A_F for a ship whose
superstructure differs from the KVLCC2's.

References
----------
Blendermann, W. (1994). Parameter identification of wind loads on ships. Journal of Wind
Engineering and Industrial Aerodynamics 51, 339–351.

SIMMAN 2008. Workshop on Verification and Validation of Ship Manoeuvring Simulation Methods,
KVLCC2 main particulars (as in Yasukawa & Yoshimura 2015, J. Mar. Sci. Technol. 20, 37–52).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Any

from ..errors import ParameterError

__all__ = ["ESTIMATED_TYPES", "WINDAGE_FIELDS", "Windage", "WindageEstimateWarning",
           "design_windage", "estimate_windage", "windage_particulars"]

#: Blendermann's vessel types whose windage is estimated (module docstring).
ESTIMATED_TYPES = ("tanker-loaded", "tanker-ballast")

#: The windage particulars (name, unit).
WINDAGE_FIELDS = (("length_overall", "m"), ("lateral_area", "m²"), ("frontal_area", "m²"),
                  ("windage_centre", "m"))

#: The KVLCC2 catalog's superstructure and proportions (module docstring).
_SUPER_LENGTH = 40.0 / 320.0      # l_s / L_pp
_SUPER_HEIGHT = 15.0 / 320.0      # h_s / L_pp
_SUPER_BREADTH = 40.0 / 58.0      # b_s / B
_SUPER_CENTRE = -140.0 / 320.0    # x_s / L_pp (aft of midships)
_DRAFT_TO_DEPTH = 20.8 / 30.0     # T / D, loaded
_LOA_TO_LPP = 325.0 / 320.0       # L_oa / L_pp


class WindageEstimateWarning(UserWarning):
    """Windage particulars were estimated, not given (:mod:`seahelm.ships.windage`)."""


@dataclasses.dataclass(frozen=True)
class Windage:
    """The windage particulars of a ship (SI units) and where each came from.

    Attributes
    ----------
    vessel_type : str
        Blendermann's (1994) vessel type.
    length_overall, lateral_area, frontal_area, windage_centre : float
        L_oa [m], A_L [m²], A_F [m²], s_L [m] forward of midships.
    estimated : tuple of str
        The fields estimated (the others were given).
    source : str
        How the estimated ones were made (empty when none was).
    """

    vessel_type: str
    length_overall: float
    lateral_area: float
    frontal_area: float
    windage_centre: float
    estimated: tuple[str, ...] = ()
    source: str = ""


def estimate_windage(*, length: float, beam: float, draft: float, vessel_type: str,
                     hull_depth: float | None = None, length_overall: float | None = None,
                     lateral_area: float | None = None, frontal_area: float | None = None,
                     windage_centre: float | None = None, warn: bool = True) -> Windage:
    """The windage of a ship: the given particulars, the missing ones estimated.

    Parameters
    ----------
    length, beam, draft : float
        L_pp, B and the mean draught T [m].
    vessel_type : str
        Blendermann's vessel type (a key of
        :data:`~seahelm.environment.blendermann.BLENDERMANN_VESSEL_TYPES`).
    hull_depth : float, optional
        Moulded depth D [m] (default T / 0.693 for a loaded tanker).
    length_overall, lateral_area, frontal_area, windage_centre : float, optional
        Given windage particulars (L_oa [m], A_L, A_F [m²], s_L [m] forward of midships).
    warn : bool, optional
        Warn (:class:`WindageEstimateWarning`) when something was estimated (default True).

    Returns
    -------
    Windage

    Raises
    ------
    ParameterError
        An unknown vessel type; a type not in :data:`ESTIMATED_TYPES` without both areas; a
        ballast tanker without ``hull_depth``; a depth not above the draught; a value not
        finite and > 0.
    """
    from ..environment.blendermann import BLENDERMANN_VESSEL_TYPES

    if vessel_type not in BLENDERMANN_VESSEL_TYPES:
        raise ParameterError(f"must be one of Blendermann's vessel types: "
                             f"{', '.join(BLENDERMANN_VESSEL_TYPES)}, got {vessel_type!r}",
                             field="vessel_type", value=vessel_type)
    for name, value, unit in (("hull_depth", hull_depth, "m"),
                              ("length_overall", length_overall, "m"),
                              ("lateral_area", lateral_area, "m²"),
                              ("frontal_area", frontal_area, "m²")):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=name, unit=unit,
                                 value=value)
    if windage_centre is not None and not (math.isfinite(windage_centre)
                                           and abs(windage_centre) < length):
        raise ParameterError(f"must lie within the ship, |s_L| < L = {length:g} [m], got "
                             f"{windage_centre!r}", field="windage_centre", unit="m",
                             value=windage_centre)
    _check_proportions(length, beam, hull_depth, length_overall, lateral_area, frontal_area)
    estimated = []
    if length_overall is None:
        length_overall = _LOA_TO_LPP * length
        estimated.append("length_overall")
    if length_overall < length:
        raise ParameterError(f"must be at least L_pp = {length:g} [m], got {length_overall!r}",
                             field="length_overall", unit="m", value=length_overall)
    need = [n for n, v in (("lateral_area", lateral_area), ("frontal_area", frontal_area))
            if v is None]
    if not need:
        centre = 0.0 if windage_centre is None else windage_centre
        if windage_centre is None:
            estimated.append("windage_centre")
        return _done(Windage(vessel_type, length_overall, float(lateral_area),
                             float(frontal_area), centre, tuple(estimated),
                             "s_L at midships (not given)" if windage_centre is None else ""),
                     warn)
    if vessel_type not in ESTIMATED_TYPES:
        raise ParameterError(
            f"the windage of a '{vessel_type}' is not estimated (the relation of "
            f"seahelm.ships.windage is a tanker's: {', '.join(ESTIMATED_TYPES)}): give "
            "both windage areas, lateral A_L and frontal A_F [m²]", field=need[0], unit="m²")
    if hull_depth is None:
        if vessel_type != "tanker-loaded":
            raise ParameterError(
                f"is needed to estimate the windage of a '{vessel_type}' (its draught is not "
                "the loaded one that the default depth T/0.693 is of) [m]", field="hull_depth",
                unit="m")
        hull_depth = draft / _DRAFT_TO_DEPTH
        estimated.append("hull_depth")
    if not hull_depth > draft:
        raise ParameterError(f"must be greater than the draft {draft:g} [m], got {hull_depth!r}",
                             field="hull_depth", unit="m", value=hull_depth)
    freeboard = hull_depth - draft
    l_s, h_s, b_s = _SUPER_LENGTH * length, _SUPER_HEIGHT * length, _SUPER_BREADTH * beam
    band, block = length_overall * freeboard, l_s * h_s
    a_l = band + block if lateral_area is None else lateral_area
    a_f = beam * freeboard + b_s * h_s if frontal_area is None else frontal_area
    centre = (block * _SUPER_CENTRE * length / (band + block) if windage_centre is None
              else windage_centre)
    estimated += [n for n, v in (("lateral_area", lateral_area), ("frontal_area", frontal_area),
                                 ("windage_centre", windage_centre)) if v is None]
    source = (f"freeboard band L_oa (D - T) and B (D - T) with D = {hull_depth:.4g} m"
              + (" (T/0.693, the KVLCC2's T/D)" if "hull_depth" in estimated else "")
              + f", plus a superstructure of {l_s:.3g} m x {h_s:.3g} m (lateral) and "
              f"{b_s:.3g} m x {h_s:.3g} m (frontal) centred {abs(_SUPER_CENTRE) * length:.3g} "
              "m aft of midships, the catalog KVLCC2's scaled by L_pp and B "
              "(seahelm.ships.windage; no published regression was available)")
    return _done(Windage(vessel_type, length_overall, a_l, a_f, centre, tuple(estimated),
                         source), warn)


#: Bounds of a ship's proportions beyond which a windage value is a unit mix-up, not a ship
#: (L_oa/L_pp of merchant ships is about 1.0-1.1, D < B, A_L/L_oa² about 0.05-0.2 from tankers
#: to car carriers, A_F/B² about 0.3-1.5).
_MAX_LOA = 1.5        # L_oa / L_pp
_MAX_DEPTH = 0.5      # D / L_pp
_MAX_LATERAL = 0.5    # A_L / L_oa²
_MAX_FRONTAL = 4.0    # A_F / B²


def _check_proportions(length: float, beam: float, depth: float | None, loa: float | None,
                       lateral: float | None, frontal: float | None) -> None:
    span = loa if loa is not None else length
    for name, value, limit, unit, what in (
            ("length_overall", loa, _MAX_LOA * length, "m", f"{_MAX_LOA:g} L_pp"),
            ("hull_depth", depth, _MAX_DEPTH * length, "m", f"{_MAX_DEPTH:g} L_pp"),
            ("lateral_area", lateral, _MAX_LATERAL * span ** 2, "m²", f"{_MAX_LATERAL:g} L_oa²"),
            ("frontal_area", frontal, _MAX_FRONTAL * beam ** 2, "m²", f"{_MAX_FRONTAL:g} B²")):
        if value is not None and value > limit:
            raise ParameterError(f"must be at most {what} = {limit:.4g} [{unit}] (beyond a "
                                 f"ship's proportions: a unit mix-up?), got {value!r}",
                                 field=name, unit=unit, value=value)


def _done(windage: Windage, warn: bool) -> Windage:
    if warn and windage.estimated:
        how = ("a rough tanker relation" if "lateral_area" in windage.estimated
               or "frontal_area" in windage.estimated else "defaults")
        warnings.warn(
            f"windage estimated, not given: {', '.join(windage.estimated)} "
            f"(A_L {windage.lateral_area:.4g} m², A_F {windage.frontal_area:.4g} m², L_oa "
            f"{windage.length_overall:.4g} m, s_L {windage.windage_centre:.4g} m; {how}, see "
            "the ship file's provenance): give them where known", WindageEstimateWarning,
            stacklevel=3)
    return windage


def design_windage(design: Any, *, warn: bool = True) -> Windage | None:
    """The windage of a :class:`~seahelm.ships.estimate.Design` (its ``vessel_type``,
    ``hull_depth`` and windage fields; :func:`estimate_windage`).

    Parameters
    ----------
    design : Design
    warn : bool, optional
        Warn when something was estimated (default True).

    Returns
    -------
    Windage or None
        None without a ``vessel_type``.

    Raises
    ------
    ParameterError
        A windage field given without ``vessel_type``, or as :func:`estimate_windage`.
    """
    given = {n: getattr(design, n) for n, _ in (*WINDAGE_FIELDS, ("hull_depth", "m"))
             if getattr(design, n) is not None}
    if design.vessel_type is None:
        if given:
            raise ParameterError(f"is needed with {', '.join(given)} (Blendermann's vessel "
                                 "type, whose wind coefficients the areas go with)",
                                 field="vessel_type")
        return None
    return estimate_windage(length=design.length, beam=design.beam, draft=design.mean_draft,
                            vessel_type=design.vessel_type, warn=warn, **given)


def windage_particulars(windage: Windage | None
                        ) -> tuple[dict[str, Any], str, tuple[str, ...]]:
    """What an estimated ship's particulars get of its windage: the fields, the words added
    to their provenance (marking the estimated ones), and a ``validity`` note.

    Parameters
    ----------
    windage : Windage or None

    Returns
    -------
    tuple of (dict, str, tuple of str)
    """
    if windage is None:
        return {}, "", ()
    fields = {"vessel_type": windage.vessel_type, "length_overall": windage.length_overall,
              "lateral_area": windage.lateral_area, "frontal_area": windage.frontal_area,
              "windage_centre": windage.windage_centre}
    if not windage.estimated:
        return fields, "; windage given", ()
    listed = ", ".join(windage.estimated)
    return (fields, f"; ESTIMATED windage ({listed}): {windage.source}",
            (f"windage estimated, not measured ({listed}; seahelm.ships.windage)",))
