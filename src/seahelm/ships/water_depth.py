"""A ship in shallow water: its MMG coefficients corrected for a water depth.

:func:`ship_at_depth` (also :meth:`Ship.at_depth <seahelm.ships.Ship.at_depth>`) corrects the
deep-water MMG coefficients of a ship by the shallow-water set of
:mod:`seahelm.hydrodynamics.shallow_water` (hull: Taimuri et al. 2020; resistance: Lackenby
1963) and keeps the deep-water ones on
the ship, so a ship file of a ship in shallow water holds its deep-water parameters and its
depth, and reading it makes the same ship. :func:`hull_particulars` gives the hull particulars
the corrections (and the estimates of :mod:`seahelm.ships.estimate`) read.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..hydrodynamics.hull import HullParticulars
from ..hydrodynamics.shallow_water import MIN_DEPTH_RATIO, shallow_water_coefficients

if TYPE_CHECKING:  # pragma: no cover
    from .ship import Ship

__all__ = ["ship_at_depth", "hull_particulars", "params_at_depth"]


def hull_particulars(ship: "Ship", params: Any = None) -> HullParticulars:
    """The hull particulars of a ship: its particulars, with ∇ and x_G from MMG parameters.

    Parameters
    ----------
    ship : Ship
    params : Params, optional
        The (deep-water) parameters to take ∇ and x_G from (default: the ship's).

    Returns
    -------
    HullParticulars

    Raises
    ------
    ParameterError
        When the ship has no particulars.
    """
    p = ship.particulars
    if p is None:
        raise ParameterError(f"ship '{ship.name}' has no particulars (L, B, T, C_b: a ship "
                             "file's [particulars])", field="particulars")
    params = params if params is not None else (ship.deep_water_params or ship.params)
    names = params.field_names()
    volume = float(params.displacement) if "displacement" in names else p.displacement
    x_G = float(params.x_G) if "x_G" in names else 0.0
    return HullParticulars(length=p.length, beam=p.beam, draft=p.draft,
                           block_coefficient=p.block_coefficient, displacement=volume, x_G=x_G)


def ship_at_depth(ship: "Ship", depth: float, *, strict: bool | None = None) -> "Ship":
    """``ship`` in water of depth ``depth`` [m] (module docstring).

    Parameters
    ----------
    ship : Ship
        A ship of the MMG model with particulars.
    depth : float
        Water depth h [m] (> draft; ``inf``: deep water).
    strict : bool, optional
        Raise instead of warning below h/d = 1.2.

    Returns
    -------
    Ship
        With the corrected parameters, ``water_depth`` = h and the deep-water parameters kept.

    Raises
    ------
    ParameterError
        A depth not above the draft, a model other than the MMG model, a ship without
        particulars.
    """
    if isinstance(depth, bool) or not isinstance(depth, (int, float)) or math.isnan(depth) \
            or not depth > 0:
        raise ParameterError(f"must be a number > 0 [m] (inf: deep water), got {depth!r}",
                             field="water_depth", unit="m", value=depth)
    deep = ship.deep_water_params or ship.params
    if math.isinf(depth):
        if not ship.in_shallow_water:
            return ship
        return dataclasses.replace(ship, params=deep, water_depth=math.inf,
                                   deep_water_params=None,
                                   validity=_validity(ship.validity, None))
    if not ship.model.supports("shallow-water"):
        raise ParameterError(
            f": ship '{ship.name}' uses model '{ship.model.name}'; the shallow-water corrections "
            "are for the MMG model's coefficients", field="water_depth", unit="m", value=depth)
    hull = hull_particulars(ship)
    corrected = shallow_water_coefficients(deep.as_dict(), hull, float(depth), strict=strict)
    params = type(deep).from_mapping(corrected)
    return dataclasses.replace(ship, params=params, water_depth=float(depth),
                               deep_water_params=deep,
                               validity=_validity(ship.validity, float(depth) / hull.draft))


def params_at_depth(ship: "Ship", deep: Any) -> Any:
    """Deep-water parameters ``deep`` of ``ship``'s model corrected for the ship's water depth
    (unchanged in deep water): what a scenario's parameter override on a ship in shallow water
    becomes (the override is to the deep-water value, as in the ship file).

    Parameters
    ----------
    ship : Ship
    deep : Params
        Deep-water parameters of the ship's model.

    Returns
    -------
    Params
    """
    if not ship.in_shallow_water:
        return deep
    corrected = shallow_water_coefficients(deep.as_dict(), hull_particulars(ship, deep),
                                           ship.water_depth)
    return type(deep).from_mapping(corrected)


def _validity(notes: tuple[str, ...], ratio: float | None) -> tuple[str, ...]:
    """The validity notes with the water-depth note (``deep water`` or the shallow-water one)
    in the place of the old one (appended if there was none)."""
    if ratio is None:
        note = "deep water"
    else:
        note = (f"shallow water: h/d = {ratio:.3g} (hull corrections of Taimuri et al. 2020, "
                f"data range h/d ≥ {MIN_DEPTH_RATIO:g}; resistance by Lackenby 1963)")
    depth_notes = [i for i, n in enumerate(notes)
                   if n == "deep water" or n.startswith("shallow water: h/d")]
    if not depth_notes:
        return tuple(notes) + (note,)
    out = [n for i, n in enumerate(notes) if i not in depth_notes[1:]]
    out[depth_notes[0]] = note
    return tuple(out)
