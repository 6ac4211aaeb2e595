"""The ship a scenario names: ``[vessel] ship`` (or its older name ``catalog``), a catalog name
or the path of a ship file, relative to the scenario file; or the ship estimated from
``[vessel.particulars]`` (:mod:`seahelm.scenario.particulars`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..errors import ParameterError
from .errors import at_key
from .schema import Scenario

__all__ = ["vessel_ship", "ship_key"]


def ship_key(scn: Scenario) -> str:
    """The key the scenario names its ship with.

    Parameters
    ----------
    scn : Scenario
        Validated scenario.

    Returns
    -------
    str
        ``"vessel.particulars"`` for an estimated ship, ``"vessel.catalog"`` when the scenario
        uses that older key, else ``"vessel.ship"``.
    """
    if scn.vessel.particulars is not None:
        return "vessel.particulars"
    return "vessel.catalog" if scn.vessel.ship is None and scn.vessel.catalog is not None \
        else "vessel.ship"


def vessel_ship(scn: Scenario, source: str) -> Any:
    """The scenario's :class:`~seahelm.ships.Ship`, or None when it names none.

    Parameters
    ----------
    scn : Scenario
        Validated scenario.
    source : str
        The scenario file (a relative ship-file path is taken from its folder), or
        ``<string>`` (then from the working directory).

    Returns
    -------
    Ship or None

    Raises
    ------
    ScenarioError
        At ``vessel.ship`` (or ``vessel.catalog``): an unknown catalog name (listing the valid
        ones), a ship file that cannot be read or is invalid (naming its key and unit); at
        ``vessel.particulars.<key>``: particulars that cannot be estimated
        (:func:`seahelm.scenario.particulars.estimated_ship`).
    """
    from ..ships import get_ship
    from ..ships.file_format import is_ship_path

    v = scn.vessel
    if v.particulars is not None:
        from .particulars import estimated_ship

        return estimated_ship(scn, source)
    ref = v.ship if v.ship is not None else v.catalog
    if ref is None:
        return None
    key = ship_key(scn)
    if is_ship_path(ref) and not Path(ref).is_absolute() and Path(source).is_file():
        ref = str(Path(source).parent / ref)  # relative to the scenario, wherever it is run
    try:
        ship = get_ship(ref)
    except ValueError as exc:
        raise at_key(source, key, str(exc)) from None
    if v.water_depth is not None:
        try:
            ship = ship.at_depth(v.water_depth)
        except ParameterError as exc:
            raise at_key(source, "vessel.water_depth", exc.reason.lstrip(": ")) from None
    return ship
