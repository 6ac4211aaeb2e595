"""Writing ship files: a :class:`~seahelm.ships.ship.Ship` as TOML text, each number with its
unit and meaning, written atomically. Reading back what was written gives the same ship, bit for
bit (every float is written as its shortest exact decimal)."""

from __future__ import annotations

import errno
import math
import os
from pathlib import Path
from typing import Any

from ..parameters import Params
from ..vessels.particulars import FIELD_UNITS
from .file_format import FORMAT
from .ship import Ship

__all__ = ["ship_to_mapping", "ship_to_toml", "write_ship"]


# ------------------------------------------------------------------------------------------
def ship_to_mapping(ship: Ship) -> dict[str, Any]:
    """The contents of ``ship``'s file as plain data (what :func:`ship_from_mapping` reads).

    Parameters
    ----------
    ship : Ship

    Returns
    -------
    dict
    """
    out: dict[str, Any] = {"format": FORMAT, "name": ship.name}
    if ship.description:
        out["description"] = ship.description
    out["model"] = ship.model.name
    if ship.test_speed is not None and ship.design_speed is None:
        out["test_speed"] = ship.test_speed
    if ship.validity:
        out["validity"] = list(ship.validity)
    if ship.in_shallow_water:  # the deep-water parameters and the depth they are corrected to
        out["water_depth"] = ship.water_depth
    out["params"] = _values(ship.deep_water_params or ship.params)
    prov: dict[str, Any] = {"params": ship.provenance}
    if ship.steering_gear is not None:
        out["steering_gear"] = {"actuator": ship.steering_gear.actuator.name,
                                "params": _values(ship.steering_gear.params)}
        prov["steering_gear"] = ship.steering_gear.provenance
    if ship.propulsion is not None:
        out["propulsion"] = {"kind": ship.propulsion.kind, "inputs": list(ship.propulsion.inputs)}
        prov["propulsion"] = ship.propulsion.provenance
    if ship.particulars is not None:
        out["particulars"] = {n: getattr(ship.particulars, n) for n, _, _ in FIELD_UNITS
                              if getattr(ship.particulars, n) is not None}
        prov["particulars"] = ship.particulars.provenance
    if ship.thrusters is not None:
        from .thrusters_file import layout_to_tables

        out["thrusters"] = layout_to_tables(ship.thrusters)
        prov["thrusters"] = ship.thruster_provenance
    if ship.coefficient_sources:
        prov["coefficients"] = dict(ship.coefficient_sources)
    out["provenance"] = {k: v for k, v in prov.items() if v}
    return out


def _values(params: Params) -> dict[str, Any]:
    return {n: list(v) if isinstance(v, tuple) else float(v)
            for n, v in params.as_dict().items()}


def ship_to_toml(ship: Ship) -> str:
    """The ship file of ``ship`` (TOML text, each number with its unit and meaning).

    Reading the text back (:func:`ship_from_mapping` of ``tomllib.loads``) gives a ship equal
    to ``ship``: every float is written as its shortest exact decimal.

    Parameters
    ----------
    ship : Ship

    Returns
    -------
    str
    """
    import tomlkit

    data = ship_to_mapping(ship)
    doc = tomlkit.document()
    doc.add(tomlkit.comment(f"seahelm ship file (format {FORMAT}): SI units, angles in radians "
                            "(any angle may be given as <name>_deg in degrees)."))
    doc.add(tomlkit.comment("Every key: the docs' ship-file reference (seahelm.ships.files); "
                            "`seahelm ship show NAME --toml` writes one."))
    for key in ("format", "name", "description", "model", "test_speed", "water_depth",
                "validity"):
        if key in data:
            doc.add(key, data[key])
    if "test_speed" in data:
        doc["test_speed"].comment("[m/s] approach (test) speed")
    if "water_depth" in data:
        doc["water_depth"].comment("[m] water depth h: [params] below are the deep-water ones, "
                                   "corrected for h on reading")
    doc["model"].comment("the manoeuvring model (seahelm models lists them)")
    doc.add(tomlkit.nl())
    title = f"{type(ship.params).__name__} of model '{ship.model.name}'"
    if ship.in_shallow_water:
        title += " (deep water)"
    doc.add("params", _commented(ship.deep_water_params or ship.params, title))
    if ship.steering_gear is not None:
        gear = tomlkit.table()
        gear.add("actuator", ship.steering_gear.actuator.name)
        gear.add("params", _commented(ship.steering_gear.params,
                                      ship.steering_gear.actuator.description))
        doc.add("steering_gear", gear)
    if "propulsion" in data:
        doc.add("propulsion", data["propulsion"])
    if ship.particulars is not None:
        part = tomlkit.table()
        for n, unit, _ in FIELD_UNITS:
            value = getattr(ship.particulars, n)
            if value is not None:
                part.add(n, value)
                if unit:
                    part[n].comment(f"[{unit}]")
        doc.add("particulars", part)
    if "thrusters" in data:
        from .thrusters_file import THRUSTER_KEYS

        units = {k: u for k, u, *_ in THRUSTER_KEYS}
        aot = tomlkit.aot()
        for tab in data["thrusters"]:
            t = tomlkit.table()
            for key, value in tab.items():
                t.add(key, value)
                if units.get(key):
                    t[key].comment(f"[{units[key]}]")
            aot.append(t)
        doc.add("thrusters", aot)
    doc.add("provenance", data["provenance"])
    return tomlkit.dumps(doc)


def _commented(params: Params, title: str) -> Any:
    import tomlkit

    table = tomlkit.table()
    table.add(tomlkit.comment(title))
    for info in params.info():
        value = getattr(params, info.name)
        table.add(info.name, list(value) if isinstance(value, tuple) else float(value))
        bits = [f"[{info.unit}]" if info.unit else "[-]"]
        if info.unit == "rad" and not isinstance(value, tuple):
            bits.append(f"({math.degrees(value):.6g} deg)")
        if info.symbol:
            bits.append(info.symbol + (":" if info.doc else ""))
        if info.doc:
            bits.append(info.doc)
        table[info.name].comment(" ".join(bits))
    return table


def write_ship(ship: Ship, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
    """Write ``ship``'s file atomically (a temporary file in the same folder, then a rename).

    Parameters
    ----------
    ship : Ship
    path : str or path-like
        The file to write.
    overwrite : bool, optional
        Replace an existing file (default False: an existing file is an error).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    FileExistsError
        If ``path`` exists and ``overwrite`` is False.
    ParameterError
        If ``path`` is a directory, a symbolic link or ends with a slash (the output policy,
        :func:`seahelm.output_files.check_output`).

    Notes
    -----
    Written atomically (a temporary file in the same folder, then a rename); a new file gets
    the umask's permissions, a replaced one keeps its mode.
    """
    from ..output_files import OutputExistsError, write_output

    text = ship_to_toml(ship)
    try:
        return write_output(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"),
                            "toml", force=overwrite, replace_own=False)
    except OutputExistsError:
        raise FileExistsError(errno.EEXIST, "exists; pass overwrite=True to replace it",
                              os.fspath(path)) from None
