"""Main dimensions and windage of the catalog ships, for wind and wave loads.

A load model needs what a manoeuvring model does not: the hull's beam, draft and block
coefficient (Lvov's wave-load coefficients, eq. (5)-(7)), and the projected windage areas above
the water (wind loads). :data:`PARTICULARS` gives them for the catalog entries by name; a
scenario's ``[environment.wind]``/``[environment.waves]`` keys override any of them.

Provenance: the main dimensions are the published ones (KVLCC2: SIMMAN 2008 / Yasukawa &
Yoshimura 2015, L_pp 320 m, B 58 m, T 20.8 m, depth 30 m, C_b 0.8098; Mariner: Chislett &
Strøm-Tejsen 1965 via Fossen's ``mariner.m``, C_b from m'). **The windage areas are estimates**,
not published data: KVLCC2 — the hull above the waterline (freeboard 30 − 20.8 = 9.2 m) plus
a typical aft superstructure of 40 m × 15 m (lateral) and 40 m × 15 m (frontal), giving
A_L ≈ 3,540 m², A_F ≈ 1,130 m², the lateral centre ≈ 24 m aft of midships; the L7 model is
the same scaled by 7/320; Mariner — Lvov's (2014) working assumption S_n = 0.8 L T centred
amidships (as :data:`seahelm.studies.lvov2014.MARINER_PARTICULARS`), and A_F = 0.8 B T.
Blendermann's vessel type for the KVLCC2 is a loaded tanker and for the Mariner a loaded
general cargo ship.
"""

from __future__ import annotations

import dataclasses
from types import MappingProxyType
from typing import Mapping

from ..errors import ParameterError

__all__ = ["Particulars", "PARTICULARS", "particulars"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Particulars:
    """Main dimensions and windage of one ship (SI units).

    Attributes
    ----------
    length : float
        Length between perpendiculars L [m].
    beam, draft : float
        B, T [m].
    block_coefficient : float
        C_b [-].
    length_overall : float
        L_oa [m].
    frontal_area, lateral_area : float
        Projected windage areas above the water A_F, A_L [m²].
    windage_centre : float
        Centre of the lateral windage area, forward of midships [m].
    vessel_type : str
        Blendermann (1994) vessel type (:mod:`seahelm.environment.blendermann`).
    provenance : str
        Where the numbers come from.
    """

    length: float
    beam: float
    draft: float
    block_coefficient: float
    length_overall: float
    frontal_area: float
    lateral_area: float
    windage_centre: float
    vessel_type: str
    provenance: str = ""

    def __post_init__(self) -> None:
        for name, unit in (("length", "m"), ("beam", "m"), ("draft", "m"),
                           ("block_coefficient", "-"), ("length_overall", "m"),
                           ("frontal_area", "m²"), ("lateral_area", "m²")):
            value = getattr(self, name)
            if not value > 0:
                raise ParameterError(f"`{name}` must be > 0 [{unit}], got {value!r}")

    def scaled(self, factor: float, provenance: str = "") -> "Particulars":
        """The same ship at ``factor`` times the size (lengths × factor, areas × factor²).

        Parameters
        ----------
        factor : float
            Scale of lengths [-].
        provenance : str, optional
            Provenance of the scaled ship (default: this ship's).

        Returns
        -------
        Particulars
        """
        f = float(factor)
        return dataclasses.replace(
            self, length=self.length * f, beam=self.beam * f, draft=self.draft * f,
            length_overall=self.length_overall * f, frontal_area=self.frontal_area * f * f,
            lateral_area=self.lateral_area * f * f, windage_centre=self.windage_centre * f,
            provenance=provenance or self.provenance)


_KVLCC2 = Particulars(
    length=320.0, beam=58.0, draft=20.8, block_coefficient=0.8098, length_overall=325.0,
    frontal_area=58.0 * 9.2 + 40.0 * 15.0, lateral_area=320.0 * 9.2 + 40.0 * 15.0,
    windage_centre=-(40.0 * 15.0 * 140.0) / (320.0 * 9.2 + 40.0 * 15.0),
    vessel_type="tanker-loaded",
    provenance="KVLCC2 main dimensions (SIMMAN 2008; Yasukawa & Yoshimura 2015); windage "
               "areas estimated (module docstring)")
_MARINER = Particulars(
    length=160.93, beam=23.17, draft=8.23, block_coefficient=0.542, length_overall=171.8,
    frontal_area=0.8 * 23.17 * 8.23, lateral_area=0.8 * 160.93 * 8.23, windage_centre=0.0,
    vessel_type="cargo-loaded",
    provenance="Mariner main dimensions (Chislett & Strøm-Tejsen 1965, Fossen's mariner.m); "
               "windage S_n = 0.8 L T amidships as Lvov (2014) assumes, A_F = 0.8 B T")

#: Particulars of the catalog entries, by catalog name.
PARTICULARS: Mapping[str, Particulars] = MappingProxyType({
    "kvlcc2-full": _KVLCC2,
    **{name: _KVLCC2.scaled(7.0 / 320.0, "KVLCC2 L7 model: the full-scale particulars scaled "
                                          "by 7/320")
       for name in ("kvlcc2-l7", "kvlcc2-l7-wp0-0.35", "kvlcc2-l7-xp-0.5")},
    "mariner-nonlinear": _MARINER,
    "mariner-voitkunsky": _MARINER,
    "mariner-nomoto1": _MARINER,
    "mariner-nomoto2": _MARINER,
})


def particulars(name: str) -> Particulars:
    """The particulars of a catalog ship (ValueError listing the ships that have them).

    Parameters
    ----------
    name : str
        Catalog name.

    Returns
    -------
    Particulars
    """
    try:
        return PARTICULARS[name]
    except KeyError:
        raise ValueError(f"no particulars (dimensions, windage) for '{name}'; known: "
                         f"{', '.join(PARTICULARS)}") from None
