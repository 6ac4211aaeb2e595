"""The catalog: a registry of ships, one ship file each.

Each catalog ship is a ship file in ``seahelm/ships/data/`` (named ``<name>.toml``): adding a
ship to the catalog is adding one file, no code. Listing the names reads no file; a ship is
read on first use and kept. :func:`get` is the one rule by which everything that takes a ship
finds it: a :class:`~seahelm.ships.ship.Ship` as it is, a path to a ship file, or a catalog
name (an unknown name raises ValueError listing the valid ones).
"""

from __future__ import annotations

import functools
import os
import tomllib
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from .._validate import lookup_name
from ..errors import ParameterError
from .files import read_ship as _read_ship_file
from .file_format import is_ship_path
from .ship import Ship

__all__ = ["CATALOG", "DATA_DIR", "get", "names", "read_ship", "register", "with_steering_gear"]

#: Where the catalog's ship files are.
DATA_DIR = Path(__file__).with_name("data")

_REGISTERED: dict[str, Ship] = {}


@functools.cache
def _file_names() -> tuple[str, ...]:
    return tuple(sorted(p.stem for p in DATA_DIR.glob("*.toml")))


def names() -> tuple[str, ...]:
    """The catalog's names (the ship files' and those registered in this process), sorted."""
    return tuple(sorted({*_file_names(), *_REGISTERED}))


def read_ship(path: str | os.PathLike[str]) -> Ship:
    """Read a ship file (its ``base``, if any, from the catalog or another file).

    Parameters
    ----------
    path : str or path-like
        The TOML file.

    Returns
    -------
    Ship

    Raises
    ------
    seahelm.ships.file_format.ShipFileError
        If the file cannot be read or is invalid (naming the key and its unit).
    """
    return _read_ship_file(path, lookup=get)


@functools.cache
def _read(name: str) -> Ship:
    ship = read_ship(DATA_DIR / f"{name}.toml")
    if ship.name != name:  # pragma: no cover - guarded by tests/test_ships.py
        raise ParameterError(f"catalog file {name}.toml names its ship '{ship.name}'")
    return ship


class _Catalog(Mapping[str, Ship]):
    """Read-only mapping name -> :class:`Ship` over the catalog (files read on first use)."""

    def __getitem__(self, name: str) -> Ship:
        if name in _REGISTERED:
            return _REGISTERED[name]
        if name in _file_names():
            return _read(name)
        raise KeyError(name)

    def __iter__(self) -> Iterator[str]:
        return iter(names())

    def __len__(self) -> int:
        return len(names())

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and (name in _REGISTERED or name in _file_names())


#: The catalog: name -> Ship.
CATALOG: Mapping[str, Ship] = _Catalog()


def register(ship: Ship) -> Ship:
    """Add a ship to this process's catalog (names are unique).

    Parameters
    ----------
    ship : Ship

    Returns
    -------
    Ship
        ``ship``.

    Raises
    ------
    ValueError
        If a ship of that name is in the catalog already.
    """
    if not isinstance(ship, Ship):
        raise ParameterError(f"`ship` must be a Ship, got {type(ship).__name__}")
    if ship.name in CATALOG:
        raise ValueError(f"catalog ship '{ship.name}' exists already")
    _REGISTERED[ship.name] = ship
    return ship


def get(ship: Any) -> Ship:
    """A ship: a :class:`Ship` as it is, a ship file by path, or a catalog ship by name.

    Parameters
    ----------
    ship : Ship, str or path-like
        The ship, a path to a ship file (``.toml``, or any text with a path separator), or a
        catalog name.

    Returns
    -------
    Ship

    Raises
    ------
    ValueError
        For an unknown catalog name (listing the valid ones).
    seahelm.ships.files.ShipFileError
        For a ship file that cannot be read or is invalid.
    """
    if isinstance(ship, Ship):
        return ship
    if isinstance(ship, os.PathLike):
        return read_ship(ship)
    if not isinstance(ship, str):
        raise ParameterError(
            f"`ship` must be a Ship, a catalog name or a ship file path, got "
            f"{type(ship).__name__}")
    if ship not in CATALOG and (is_ship_path(ship) or Path(ship).is_dir()):
        return read_ship(ship)  # (a directory: said as one)
    return lookup_name("catalog ship", CATALOG, ship, valid=names(),
                       suffix=" (or the path of a ship file, *.toml)")


@functools.cache
def _file_has_steering_gear(name: str) -> bool:
    # the file's tables only (tomllib, ~0.1 ms): the CLI's help lists these names, and building
    # the ships would import every vessel model
    with open(DATA_DIR / f"{name}.toml", "rb") as fh:
        return "steering_gear" in tomllib.load(fh)


def with_steering_gear() -> tuple[str, ...]:
    """The catalog ships that have a steering gear (the ones manoeuvres and ``imo`` take)."""
    return tuple(n for n in names()
                 if (_REGISTERED[n].steering_gear is not None if n in _REGISTERED
                     else _file_has_steering_gear(n)))
