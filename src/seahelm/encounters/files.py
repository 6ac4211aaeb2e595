"""Encounters from files: a scenario with a ``[[vessel]]`` array of tables (TOML), and traffic
situations in the ``maritime-schema`` JSON that DNV's ``trafficgen`` writes.

Scenario (TOML; degrees at this edge, as in every seahelm scenario)::

    title = "crossing, own ship gives way"

    [encounter]
    t_final = 1200.0            # [s]
    dt = 0.1                    # [s]
    controller_dt = 1.0         # [s]
    avoidance = "velocity-obstacles"   # or "rule-based"; omitted: nobody avoids

    [encounter.sensor]          # AIS (all optional)
    update_interval = 10.0      # [s]
    delay = 2.0                 # [s]
    position_noise = 5.0        # [m]

    [encounter.colreg]
    head_on_deg = 6.0
    overtaking_deg = 22.5       # abaft the beam

    [[vessel]]                  # the own ship first
    ship = "kvlcc2-full"        # catalog name or ship file (relative to this file)
    course_deg = 0.0
    avoid = true

    [[vessel]]
    ship = "kvlcc2-full"
    north = 4000.0              # [m]
    east = 4000.0               # [m]
    course_deg = 270.0
    speed = 7.0                 # [m/s]; or route = [[n, e], ...] [m]

A single-vessel scenario (a ``[vessel]`` table) is an ordinary scenario, unchanged.

Traffic situations: :func:`read_traffic_situations` validates each file with
``maritime_schema.types.caga.TrafficSituation`` (positions in WGS-84 degrees, SOG in knots,
COG and heading in degrees), puts the vessels on a local flat-earth north/east frame at the own
ship's start (a sphere of radius 6,371,000 m; fine over the few nautical miles of an encounter),
and stacks situations with the same number of targets into one batch.
"""

from __future__ import annotations

import json
import math
import tomllib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from .encounter import Encounter, Vessel
from .geometry import ColregSectors
from .sensing import AIS

__all__ = ["parse_encounter_scenario", "load_encounter_scenario", "is_encounter_scenario",
           "read_traffic_situations", "KNOT", "EARTH_RADIUS"]

KNOT = 1852.0 / 3600.0  #: [m/s]
EARTH_RADIUS = 6_371_000.0  #: [m] (mean radius; local flat-earth frame)

_VESSEL_KEYS = {"ship", "north", "east", "course_deg", "speed", "route", "avoid", "name",
                "acceptance"}
_ENCOUNTER_KEYS = {"t_final", "dt", "controller_dt", "avoidance", "sensor", "colreg",
                   "record_every"}
_SENSOR_KEYS = {"update_interval": "s", "delay": "s", "position_noise": "m",
                "course_noise_deg": "deg", "speed_noise": "m/s", "heading_noise_deg": "deg",
                "seed": ""}


def is_encounter_scenario(data: Mapping[str, Any]) -> bool:
    """Whether a parsed scenario holds several vessels (a ``[[vessel]]`` array of tables).

    Parameters
    ----------
    data : mapping
        The parsed TOML.
    """
    return isinstance(data.get("vessel"), list)


def _number(table: Mapping[str, Any], key: str, where: str, unit: str, default: Any = None,
            positive: bool = False) -> Any:
    if key not in table:
        return default
    v = table[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or (
            positive and v <= 0):
        need = "a number > 0" if positive else "a finite number"
        raise ParameterError(f"must be {need} [{unit}], got {v!r}", field=f"{where}.{key}",
                             unit=unit, value=v)
    return float(v)


def _unknown(table: Mapping[str, Any], allowed: Any, where: str) -> None:
    extra = sorted(set(table) - set(allowed))
    if extra:
        raise ParameterError(f": unknown key {extra[0]!r}; valid: {', '.join(sorted(allowed))}",
                             field=f"{where}.{extra[0]}" if where else extra[0],
                             value=extra[0])


def parse_encounter_scenario(data: Mapping[str, Any], *, base: Path | None = None) -> Encounter:
    """An :class:`~seahelm.encounters.encounter.Encounter` from a parsed scenario (module
    notes).

    Parameters
    ----------
    data : mapping
        The parsed TOML.
    base : Path, optional
        Directory that relative ship-file paths are relative to.

    Returns
    -------
    Encounter

    Raises
    ------
    ParameterError
        Naming the TOML key (``vessel[1].course_deg``), unit and value.
    """
    _unknown(data, {"title", "description", "encounter", "vessel"}, "")
    enc = data.get("encounter", {})
    if not isinstance(enc, Mapping):
        raise ParameterError("must be a table", field="encounter")
    _unknown(enc, _ENCOUNTER_KEYS, "encounter")
    if "t_final" not in enc:
        raise ParameterError(": missing (the duration [s])", field="encounter.t_final",
                             unit="s")
    t_final = _number(enc, "t_final", "encounter", "s", positive=True)
    dt = _number(enc, "dt", "encounter", "s", 0.1, positive=True)
    cdt = _number(enc, "controller_dt", "encounter", "s", 1.0, positive=True)
    sensor = enc.get("sensor", {})
    _unknown(sensor, _SENSOR_KEYS, "encounter.sensor")
    kw = {}
    for key, unit in _SENSOR_KEYS.items():
        if key == "seed":
            if "seed" in sensor:
                kw["seed"] = int(sensor["seed"])
            continue
        v = _number(sensor, key, "encounter.sensor", unit)
        if v is not None:
            kw[key.replace("_deg", "")] = math.radians(v) if key.endswith("_deg") else v
    try:
        ais = AIS(**kw)
        colreg = enc.get("colreg", {})
        _unknown(colreg, {"head_on_deg", "overtaking_deg"}, "encounter.colreg")
        sectors = ColregSectors(**{k.replace("_deg", ""): math.radians(
            _number(colreg, k, "encounter.colreg", "deg")) for k in colreg})
    except ParameterError as err:
        raise _renamed(err, "encounter.sensor" if "sensor" in (err.field or "") else
                       "encounter.colreg") from None
    vessels = []
    rows = data.get("vessel")
    if not isinstance(rows, list) or not rows:
        raise ParameterError("must be an array of tables ([[vessel]]), own ship first",
                             field="vessel")
    for i, row in enumerate(rows):
        where = f"vessel[{i}]"
        _unknown(row, _VESSEL_KEYS, where)
        if "ship" not in row:
            raise ParameterError(": missing (a catalog name or a ship file)",
                                 field=f"{where}.ship")
        ship = row["ship"]
        if base is not None and str(ship).endswith(".toml") and not Path(ship).is_absolute():
            ship = str(base / ship)
        course = _number(row, "course_deg", where, "deg")
        route = row.get("route")
        if course is None and route is None:
            raise ParameterError(": a vessel needs course_deg [deg] or a route [m]; got "
                                 "neither", field=f"{where}.course_deg", unit="deg")
        if route is not None:
            arr = np.asarray(route, dtype=float) if _is_points(route) else None
            if arr is None or arr.ndim != 2 or arr.shape[1] != 2 or not np.isfinite(arr).all():
                raise ParameterError(f"must be waypoints [[north, east], ...] [m], got "
                                     f"{route!r}", field=f"{where}.route", unit="m",
                                     value=route)
            route = arr
        vessels.append(Vessel(ship=ship, north=_number(row, "north", where, "m", 0.0),
                              east=_number(row, "east", where, "m", 0.0),
                              course=None if course is None else math.radians(course),
                              speed=_number(row, "speed", where, "m/s", positive=True),
                              route=route, avoid=bool(row.get("avoid", False)),
                              name=str(row.get("name", "")),
                              acceptance=_number(row, "acceptance", where, "ship lengths", 2.0,
                                                 positive=True)))
    try:
        return Encounter(vessels, t_final=t_final, dt=dt, controller_dt=cdt, sensor=ais,
                         avoidance=enc.get("avoidance"), sectors=sectors,
                         record_every=int(enc.get("record_every", 10)))
    except ParameterError as err:
        raise _renamed(err, "") from None


def _is_points(value: Any) -> bool:
    return isinstance(value, Sequence) and all(
        isinstance(p, Sequence) and all(isinstance(c, (int, float)) and not isinstance(c, bool)
                                        for c in p) for p in value)


def _renamed(err: ParameterError, prefix: str) -> ParameterError:
    """The library's field in the scenario's words (``vessels[1].course`` ->
    ``vessel[1].course_deg``, ``sensor.delay`` -> ``encounter.sensor.delay``)."""
    field = err.field or ""
    if field.startswith("vessels["):
        field = "vessel" + field[len("vessels"):]
        if field.endswith(".course"):
            field += "_deg"
    elif field.startswith("sensor."):
        field = "encounter." + field
    elif field.startswith("avoidance"):
        field = "encounter." + field
    elif prefix and field and not field.startswith(prefix):
        field = f"{prefix}.{field}"
    return ParameterError(err.reason, field=field or None, unit=err.unit, value=err.value,
                          run=err.run)


def load_encounter_scenario(path: str | Path) -> Encounter:
    """:func:`parse_encounter_scenario` of a TOML file.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    Encounter
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f": not valid TOML: {err}", field=str(path)) from None
    return parse_encounter_scenario(data, base=path.parent)


def _situation(path: Path) -> Any:
    from .._optional import optional_import
    caga = optional_import("maritime_schema.types.caga", extra="traffic",
                           purpose="maritime-schema traffic situations")
    pydantic = optional_import("pydantic")
    try:
        raw = json.loads(path.read_text())
    except json.JSONDecodeError as err:
        raise ParameterError(f": not valid JSON: {err}", field=str(path)) from None
    _check_courses(raw, path)
    try:
        return caga.TrafficSituation.model_validate(raw)
    except pydantic.ValidationError as err:
        first = err.errors()[0]
        loc = ".".join(str(p) for p in first["loc"] if str(p) not in _MODEL_TAGS)
        raise ParameterError(f": does not validate against maritime-schema "
                             f"TrafficSituation: {first['msg']} (got {first.get('input')!r})",
                             field=f"{path.name}:{loc}", value=first.get("input")) from None
    except (TypeError, ValueError) as err:  # (the schema's own validators can fail so)
        raise ParameterError(f": does not validate against maritime-schema TrafficSituation: "
                             f"{err}", field=path.name) from None


#: Union tags pydantic puts in an error's location (not JSON keys).
_MODEL_TAGS = {"OwnShip", "TargetShip", "Ship"}


def _check_courses(raw: Any, path: Path) -> None:
    """A ship without initial cog/heading and without waypoints has no course: say where
    (before the schema, whose waypoint generator fails on it with a TypeError)."""
    if not isinstance(raw, Mapping):
        return
    ships = [("ownShip", raw.get("ownShip"))] + [
        (f"targetShips.{j}", t) for j, t in enumerate(raw.get("targetShips") or [])]
    for where, ship in ships:
        if not isinstance(ship, Mapping):
            continue
        init = ship.get("initial")
        if isinstance(init, Mapping) and init.get("cog") is None and init.get(
                "heading") is None and not ship.get("waypoints"):
            raise ParameterError(": a ship needs initial.cog or initial.heading [deg], or "
                                 "waypoints; got none", field=f"{path.name}:{where}.initial.cog",
                                 unit="deg")


def _ship_state(ship: Any, lat0: float, lon0: float, where: str) -> dict[str, Any]:
    init = ship.initial
    if init is None or init.position is None:
        raise ParameterError(": missing (the start position)", field=f"{where}.initial.position")
    p = init.position
    north = math.radians(p.latitude - lat0) * EARTH_RADIUS
    east = math.radians(p.longitude - lon0) * EARTH_RADIUS * math.cos(math.radians(lat0))
    heading = init.heading if init.heading is not None else init.cog
    route = None
    if ship.waypoints:
        route = [[math.radians(w.position.latitude - lat0) * EARTH_RADIUS,
                  math.radians(w.position.longitude - lon0) * EARTH_RADIUS
                  * math.cos(math.radians(lat0))] for w in ship.waypoints]
        if len(route) > 1 and math.hypot(route[0][0] - north, route[0][1] - east) < 1.0:
            route = route[1:]  # (the first waypoint is the start)
    if heading is None and route is None:
        raise ParameterError(": a target needs initial.heading or initial.cog [deg], or "
                             "waypoints; got none", field=f"{where}.initial.heading",
                             unit="deg")
    if init.sog is None or init.sog <= 0:
        raise ParameterError(f"must be > 0 [knot], got {init.sog!r}",
                             field=f"{where}.initial.sog", unit="knot", value=init.sog)
    return {"north": north, "east": east, "course": None if heading is None
            else math.radians(heading), "speed": init.sog * KNOT, "route": route}


def read_traffic_situations(paths: Sequence[str | Path], *, own_ship: Any, target_ship: Any,
                            targets_avoid: bool = False, **encounter: Any) -> Encounter:
    """An :class:`~seahelm.encounters.encounter.Encounter` batch from maritime-schema JSON
    files (module notes): one encounter per file, the own ship avoiding.

    Parameters
    ----------
    paths : sequence of str or Path
        Traffic-situation files (``trafficgen`` output), each with the same number of targets.
    own_ship, target_ship : Ship or str
        The seahelm ships that play the situation's own ship and targets (the schema gives
        lengths and types, not manoeuvring models).
    targets_avoid : bool, optional
        The targets run the encounter's avoidance too (default False: they keep their course
        or route).
    **encounter
        Keyword arguments of :class:`Encounter` (``t_final`` required).

    Returns
    -------
    Encounter

    Raises
    ------
    ParameterError
        Naming the file and JSON path (``situation.json:ownShip.initial.sog``), unit and value.
    """
    paths = [Path(p) for p in paths]
    if not paths:
        raise ParameterError("must name at least one file", field="paths")
    states: list[list[dict[str, Any]]] = []
    for path in paths:
        sit = _situation(path)
        own = sit.own_ship
        if own.initial is None or own.initial.position is None:
            raise ParameterError(": missing (the start position)",
                                 field=f"{path.name}:ownShip.initial.position")
        lat0, lon0 = own.initial.position.latitude, own.initial.position.longitude
        row = [_ship_state(own, lat0, lon0, f"{path.name}:ownShip")]
        for j, t in enumerate(sit.target_ships or []):
            row.append(_ship_state(t, lat0, lon0, f"{path.name}:targetShips.{j}"))
        if states and len(row) != len(states[0]):
            raise ParameterError(f": has {len(row) - 1} targets, {paths[0].name} has "
                                 f"{len(states[0]) - 1}; a batch needs the same number",
                                 field=f"{path.name}:targetShips", value=len(row) - 1)
        states.append(row)
    vessels = []
    for i in range(len(states[0])):
        col = [s[i] for s in states]
        routes = [c["route"] for c in col]
        courses = [c["course"] for c in col]
        if any(r is not None for r in routes):
            if any(r is None for r in routes) or len({len(r) for r in routes}) != 1:
                raise ParameterError(": vessels must all have routes of the same length in "
                                     "a batch, or none", field=f"targetShips.{i - 1}.waypoints")
            route = np.asarray(routes, dtype=float)
        else:
            route = None
        course = None if any(c is None for c in courses) else np.array(courses)
        vessels.append(Vessel(ship=own_ship if i == 0 else target_ship,
                              north=np.array([c["north"] for c in col]),
                              east=np.array([c["east"] for c in col]), course=course,
                              speed=np.array([c["speed"] for c in col]), route=route,
                              avoid=i == 0 or bool(targets_avoid),
                              name="own" if i == 0 else f"target {i}"))
    return Encounter(vessels, **encounter)
