"""Ships: one object per ship, the catalog of them, and ship files.

* :class:`Ship` — a manoeuvring model with its parameters, steering gear, propulsion, main
  particulars, test speed and the provenance of every number (:mod:`.ship`);
* :data:`CATALOG` and :func:`get_ship` — the catalog, one ship file per ship in
  ``seahelm/ships/data/`` (:mod:`.catalog`); :func:`get_ship` takes a ship, a catalog name or
  the path of a ship file;
* :func:`read_ship`, :func:`write_ship`, :func:`ship_to_toml` — ship files (TOML with units and
  provenance: :mod:`.file_format`, :mod:`.files` reads them, :mod:`.writing` writes them).
"""

from __future__ import annotations

from .catalog import (
    CATALOG,
    get as get_ship,
    names as ship_names,
    read_ship,
    register,
    with_steering_gear,
)
from .file_format import FORMAT_REFERENCE, ShipFileError
from .ship import Propulsion, Ship, SteeringGear
from .writing import ship_to_toml, write_ship

__all__ = ["Ship", "SteeringGear", "Propulsion", "CATALOG", "get_ship", "ship_names",
           "register", "with_steering_gear", "read_ship", "write_ship", "ship_to_toml",
           "ShipFileError", "FORMAT_REFERENCE"]
