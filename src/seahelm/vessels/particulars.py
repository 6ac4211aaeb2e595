"""Main dimensions and windage of a ship, for wind and wave loads.

A load model needs what a manoeuvring model does not: the hull's beam, draft and block
coefficient (Lvov's wave-load coefficients, eq. (5)-(7)), and the projected windage areas above
the water (wind loads). A :class:`~seahelm.ships.Ship` carries its :class:`Particulars`; the
catalog ships' are in their ship files (``seahelm/ships/data/``, each with its provenance);
a scenario's ``[environment.wind]``/``[environment.waves]`` keys override any of them.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from ..errors import ParameterError

__all__ = ["Particulars", "FIELD_UNITS"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Particulars:
    """Main dimensions and windage of one ship (SI units).

    The hull's length, beam, draft and block coefficient are required; the rest is optional
    (``None``: not known), and a load model that needs a missing value says so.

    Attributes
    ----------
    length : float
        Length between perpendiculars L [m].
    beam, draft : float
        B, T [m].
    block_coefficient : float
        C_b [-], in (0, 1].
    displacement : float or None
        Displacement volume ∇ [m³] (C_b L B T when not given).
    length_overall : float or None
        L_oa [m].
    frontal_area, lateral_area : float or None
        Projected windage areas above the water A_F, A_L [m²].
    windage_centre : float or None
        Centre of the lateral windage area, forward of midships [m].
    metacentric_height : float or None
        Transverse metacentric height GM [m] of the loading condition (the closed-form roll
        RAO's natural period, :func:`seahelm.environment.rao.closed_form_rao`).
    superstructure_lateral_area, superstructure_centre, superstructure_height : float or None
        Fujiwara et al. (1998) wind data: lateral projected area of the superstructure and the
        deck structures A_OD [m²], the longitudinal position of its centre, forward of midships
        C_BR [m], and the height of the top of the superstructure above the waterline H_BR [m].
    windage_height : float or None
        Height of the centre of the lateral windage area above the waterline H_C [m]
        (Fujiwara et al. 1998).
    model_scale : float or None
        Froude scale λ ≥ 1 [-] of a model: the ship is 1/λ of the full-scale ship it models
        (the stopping test's engine timings are the full-scale ones / √λ); None for a
        full-scale ship or where not known.
    vessel_type : str or None
        Blendermann (1994) vessel type (:mod:`seahelm.environment.blendermann`).
    provenance : str
        Where the numbers come from.
    """

    length: float
    beam: float
    draft: float
    block_coefficient: float
    displacement: float | None = None
    length_overall: float | None = None
    frontal_area: float | None = None
    lateral_area: float | None = None
    windage_centre: float | None = None
    metacentric_height: float | None = None
    superstructure_lateral_area: float | None = None
    superstructure_centre: float | None = None
    superstructure_height: float | None = None
    windage_height: float | None = None
    model_scale: float | None = None
    vessel_type: str | None = None
    provenance: str = ""

    def __post_init__(self) -> None:
        for name, unit, required in FIELD_UNITS:
            value = getattr(self, name)
            if name == "vessel_type":
                if value is not None and not isinstance(value, str):
                    raise ParameterError(f"must be a text, got {value!r}", field=name)
                continue
            if value is None:
                if required:
                    raise ParameterError(f"is required [{unit}]", field=name, unit=unit)
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ParameterError(f"must be a finite number [{unit}], got {value!r}",
                                     field=name, unit=unit, value=value)
            if name not in _SIGNED and not value > 0:
                raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=name,
                                     unit=unit, value=value)
        if self.model_scale is not None and not self.model_scale >= 1:
            raise ParameterError(f"must be a Froude scale >= 1 [-], got {self.model_scale!r}",
                                 field="model_scale", unit="-", value=self.model_scale)
        if self.block_coefficient > 1:
            raise ParameterError(f"must be in (0, 1] [-], got {self.block_coefficient!r}",
                                 field="block_coefficient", unit="-",
                                 value=self.block_coefficient)

    @property
    def displacement_volume(self) -> float:
        """∇ [m³]: the given displacement, else C_b L B T."""
        if self.displacement is not None:
            return float(self.displacement)
        return self.block_coefficient * self.length * self.beam * self.draft

    def require(self, name: str, purpose: str) -> Any:
        """A field that ``purpose`` needs; ParameterError naming it if it is not known.

        Parameters
        ----------
        name : str
            The field (``"lateral_area"``, ...).
        purpose : str
            What needs it, for the message (``"Lvov's wind loads"``).

        Returns
        -------
        float or str
            Its value.
        """
        value = getattr(self, name)
        if value is None:
            unit = next(u for n, u, _ in FIELD_UNITS if n == name)
            raise ParameterError(f"is not known [{unit}] and {purpose} needs it",
                                 field=f"particulars.{name}", unit=unit)
        return value

    def scaled(self, factor: float, provenance: str = "") -> "Particulars":
        """The same ship at ``factor`` times the size (lengths × factor, areas × factor²,
        volumes × factor³).

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

        def times(value: float | None, k: float) -> float | None:
            return None if value is None else value * k

        return dataclasses.replace(
            self, length=self.length * f, beam=self.beam * f, draft=self.draft * f,
            displacement=times(self.displacement, f * f * f),
            length_overall=times(self.length_overall, f),
            frontal_area=times(self.frontal_area, f * f),
            lateral_area=times(self.lateral_area, f * f),
            windage_centre=times(self.windage_centre, f),
            metacentric_height=times(self.metacentric_height, f),
            superstructure_lateral_area=times(self.superstructure_lateral_area, f * f),
            superstructure_centre=times(self.superstructure_centre, f),
            superstructure_height=times(self.superstructure_height, f),
            windage_height=times(self.windage_height, f),
            model_scale=_model_scale(self.model_scale, f),
            provenance=provenance or self.provenance)


def _model_scale(scale: float | None, factor: float) -> float | None:
    """The Froude scale of a model ``factor`` times the size: λ / factor (None at or past the
    full-scale ship's size, or where λ is not known)."""
    if scale is None or not scale / factor > 1.0:
        return None
    return scale / factor


#: The fields of :class:`Particulars` with their units and whether they are required.
FIELD_UNITS: tuple[tuple[str, str, bool], ...] = (
    ("length", "m", True), ("beam", "m", True), ("draft", "m", True),
    ("block_coefficient", "-", True), ("displacement", "m³", False),
    ("length_overall", "m", False), ("frontal_area", "m²", False),
    ("lateral_area", "m²", False), ("windage_centre", "m", False),
    ("metacentric_height", "m", False), ("superstructure_lateral_area", "m²", False),
    ("superstructure_centre", "m", False), ("superstructure_height", "m", False),
    ("windage_height", "m", False), ("model_scale", "-", False), ("vessel_type", "", False))

#: Fields that may be negative or zero (positions along the ship).
_SIGNED = ("windage_centre", "superstructure_centre")
