"""Ship files: a :class:`~seahelm.ships.ship.Ship` as a TOML file, and back.

A ship file is the same object as a catalog ship, on disk: ``seahelm ship show NAME --toml``
writes one, every command and scenario key that takes a ship takes its path, and reading back
what was written gives the same ship, bit for bit (floats are written with the shortest text
that reads back to the same double)::

    format = 1
    name = "my-tanker"
    description = "..."
    model = "mmg"                       # the manoeuvring model (seahelm models lists them)
    # test_speed = 1.179                # [m/s]; only for a model without a design speed
    validity = ["deep water", "..."]
    # base = "kvlcc2-l7"                # optional: a catalog ship or ship file to start from

    [params]                            # every parameter of the model, SI units, radians
    length = 7.0                        # [m] L_pp: ...
    max_angle_deg = 35                  # (any angle may be given in degrees: <name>_deg)

    [steering_gear]                     # optional
    actuator = "rudder-servo"
    [steering_gear.params]
    max_angle = 0.6108652381980153      # [rad] (35 deg)

    [propulsion]                        # optional
    kind = "single fixed-pitch propeller"
    inputs = ["propeller_rps"]

    [particulars]                       # optional; L, B, T, C_b required within it
    length = 7.0                        # [m]

    [provenance]                        # where the numbers come from
    params = "..."
    steering_gear = "..."
    particulars = "..."
    propulsion = "..."
    [provenance.coefficients]           # optional: sources of single coefficients
    Y_v = "fit to trial 3, standard error 0.0004"

Without ``base``, ``[params]`` must give every parameter of the model: a ship file never
takes a coefficient silently from a class default. With ``base``, everything not given comes
from that ship (tables merge key by key). :data:`FORMAT_REFERENCE` documents every key; the
docs generate their reference page from it (:mod:`.file_format`).
"""

from __future__ import annotations

import contextvars
import dataclasses
import os
import tomllib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from ..errors import ParameterError
from ..parameters import Params
from ..vessels.particulars import FIELD_UNITS, Particulars
from .file_format import FORMAT, ShipFileError, is_ship_path
from .ship import Propulsion, Ship, SteeringGear
from .writing import ship_to_mapping

#: The keys of a ship file, and of each of its tables (other than the parameter tables).
TOP_KEYS = {"format", "name", "description", "model", "base", "test_speed", "validity", "params",
            "steering_gear", "propulsion", "particulars", "provenance", "water_depth", "thrusters"}
SECTION_KEYS = {"steering_gear": {"actuator", "params"}, "propulsion": {"kind", "inputs"},
                "particulars": {n for n, _, _ in FIELD_UNITS},
                "provenance": {"params", "steering_gear", "propulsion", "particulars",
                               "coefficients", "thrusters"}}

#: Largest ship file read [bytes] (a ship file is a few kB; anything this large is not one).
MAX_FILE_BYTES = 10_000_000

#: The ship files being read (their ``base`` chain), to find a cycle.
_READING: "contextvars.ContextVar[tuple[str, ...]]" = contextvars.ContextVar(
    "seahelm_reading_ship_files", default=())

#: Top-level keys that make a file a scenario, not a ship file.
SCENARIO_KEYS = frozenset({"title", "vessel", "simulation", "maneuver", "controller",
                           "actuator", "batch", "environment", "guidance"})

#: How a ``base`` ship is found: a catalog name or a ship-file path -> Ship
#: (:func:`seahelm.ships.get_ship`; the catalog passes it, as it reads ship files itself).
BaseLookup = Callable[[str], Ship]

__all__ = ["read_ship", "ship_from_mapping"]

# ------------------------------------------------------------------------------------------
def read_ship(path: str | os.PathLike[str], *, lookup: BaseLookup | None = None) -> Ship:
    """Read a ship file.

    Parameters
    ----------
    path : str or path-like
        The TOML file.
    lookup : callable, optional
        Finds a ``base`` ship by catalog name or path (:func:`seahelm.ships.get_ship`, which
        :func:`seahelm.ships.read_ship` passes); without it a file with ``base`` is an error.

    Returns
    -------
    Ship

    Raises
    ------
    ShipFileError
        If the file cannot be read or parsed, or a key is unknown, missing, of the wrong type
        or out of its range (the message names the file, the key and its unit).
    """
    p = Path(path)
    source = str(path)
    try:
        if p.is_dir():
            raise ShipFileError("is a directory, not a ship file", source=source)
        if not p.exists():
            raise ShipFileError("no such ship file", source=source)
        if not p.is_file():  # a FIFO would block, /dev/zero never end
            raise ShipFileError("is not a regular file (a ship file is a TOML file)",
                                source=source)
        if p.stat().st_size > MAX_FILE_BYTES:
            raise ShipFileError(f"is {p.stat().st_size / 1e6:.3g} MB: not a ship file (at most "
                                f"{MAX_FILE_BYTES / 1e6:g} MB)", source=source)
        text = p.read_text(encoding="utf-8-sig")  # (a byte-order mark is allowed)
    except ShipFileError:
        raise
    except RuntimeError:  # (Python's word for a symbolic-link loop)
        raise ShipFileError("is a loop of symbolic links", source=source) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ShipFileError(f"cannot be read ({exc})", source=source) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ShipFileError(f"is not valid TOML ({exc})", source=source) from None
    key = str(p.resolve())
    chain = _READING.get()
    if key in chain:
        names = " -> ".join(Path(c).name for c in (*chain, key))
        raise _BaseCycle(f"forms a cycle: {names}", source=source, field="base")
    token = _READING.set((*chain, key))
    try:
        return ship_from_mapping(data, source=source, directory=p.parent, lookup=lookup)
    finally:
        _READING.reset(token)


def ship_from_mapping(data: Mapping[str, Any], *, source: str = "<mapping>",
                      directory: str | os.PathLike[str] | None = None,
                      lookup: BaseLookup | None = None) -> Ship:
    """A :class:`Ship` from the contents of a ship file (a parsed TOML mapping).

    Parameters
    ----------
    data : mapping
        The file's tables (:data:`FORMAT_REFERENCE`).
    source : str, optional
        The file, for error messages.
    directory : path-like, optional
        Where a relative ``base`` path is looked for (default: the working directory).
    lookup : callable, optional
        Finds a ``base`` ship (as :func:`read_ship`).

    Returns
    -------
    Ship

    Raises
    ------
    ShipFileError
        As :func:`read_ship`.
    """
    fail = _Fail(source)
    if not isinstance(data, Mapping):
        raise fail(None, f"must be a table of keys, got {type(data).__name__}")
    _check_keys(data, fail)
    version = data.get("format")
    if version is None:
        raise fail("format", f"is required (this seahelm reads format {FORMAT})")
    if isinstance(version, bool) or version != FORMAT:
        raise fail("format", f"must be {FORMAT} (the format this seahelm reads), "
                             f"got {version!r}", value=version)
    data = dict(data)
    if "base" in data:
        data = _merged_with_base(data, fail, directory, lookup)
    for key in ("name", "model"):
        if key not in data:
            raise fail(key, "is required")
    name = _text(data, "name", fail)
    model_name = _text(data, "model", fail)
    from ..registry import VESSEL_MODELS, get_model

    if model_name not in VESSEL_MODELS:
        raise fail("model", f"'{model_name}' is not a vessel model; valid: "
                            f"{', '.join(sorted(VESSEL_MODELS))}", value=model_name)
    model = get_model(model_name)
    prov = _table(data, "provenance", fail)
    params = _params(model.params_type, _table(data, "params", fail, required=True), "params",
                     fail, complete=True)
    steering = None
    if "steering_gear" in data:
        steering = _steering_gear(_table(data, "steering_gear", fail), fail,
                                  _opt_text(prov, "provenance.steering_gear", "steering_gear",
                                            fail))
    propulsion = None
    if "propulsion" in data:
        sec = _table(data, "propulsion", fail)
        if "kind" not in sec:
            raise fail("propulsion.kind", "is required in [propulsion]")
        inputs = sec.get("inputs", [])
        if not isinstance(inputs, list) or not all(isinstance(i, str) for i in inputs):
            raise fail("propulsion.inputs", f"must be a list of texts, got {inputs!r}")
        propulsion = _build(Propulsion, "propulsion", fail,
                            kind=_text(sec, "kind", fail, prefix="propulsion."),
                            inputs=tuple(inputs),
                            provenance=_opt_text(prov, "provenance.propulsion", "propulsion",
                                                 fail))
    particulars = None
    if "particulars" in data:
        sec = dict(_table(data, "particulars", fail))
        missing = [f"{n} [{u}]" for n, u, req in FIELD_UNITS if req and n not in sec]
        if missing:
            raise fail("particulars", f"misses required particular(s): {', '.join(missing)}")
        for n, u, _ in FIELD_UNITS:
            if n in sec and n != "vessel_type":
                sec[n] = _number(sec[n], f"particulars.{n}", u, fail)
        particulars = _build(Particulars, "particulars", fail, **sec,
                             provenance=_opt_text(prov, "provenance.particulars", "particulars",
                                                  fail))
    thrusters = None
    if "thrusters" in data:
        from .thrusters_file import layout_from_tables

        try:
            thrusters = layout_from_tables(data["thrusters"])
        except ParameterError as exc:
            raise fail(exc.field, exc.reason, unit=exc.unit, value=exc.value) from None
    validity = data.get("validity", ())
    if isinstance(validity, str):
        validity = (validity,)
    if not isinstance(validity, (list, tuple)) or not all(isinstance(v, str) for v in validity):
        raise fail("validity", f"must be a text or a list of texts, got {validity!r}")
    sources = prov.get("coefficients", {})
    if not isinstance(sources, Mapping):
        raise fail("provenance.coefficients", "must be a table: parameter name = \"source\"")
    for key, value in sources.items():
        if key not in params.field_names():
            raise fail(f"provenance.coefficients.{key}",
                       f"is not a parameter of model '{model_name}'; valid: "
                       f"{', '.join(params.field_names())}")
        if not isinstance(value, str):
            raise fail(f"provenance.coefficients.{key}", f"must be a text, got {value!r}")
    test_speed = data.get("test_speed")
    if test_speed is not None:
        test_speed = _number(test_speed, "test_speed", "m/s", fail)
    ship = _build(
        Ship, None, fail, name=name, model=model, params=params,
        description=_opt_text(data, "description", "description", fail),
        steering_gear=steering, propulsion=propulsion, particulars=particulars,
        test_speed=test_speed,
        provenance=_opt_text(prov, "provenance.params", "params", fail),
        coefficient_sources=tuple(sources.items()), validity=tuple(validity),
        thrusters=thrusters,
        thruster_provenance=_opt_text(prov, "provenance.thrusters", "thrusters", fail))
    if "water_depth" in data:  # [params] are the deep-water ones, corrected for the depth
        depth = data["water_depth"]
        if not (isinstance(depth, str) and depth.strip().lower() in ("inf", "infinity")):
            depth = _number(depth, "water_depth", "m", fail)
        ship = _build(ship.at_depth, None, fail, depth=float(depth))
    return ship


class _BaseCycle(ShipFileError):
    """Ship files whose ``base`` chain returns to one of them."""


class _Fail:
    """Makes the :class:`ShipFileError` of one key of one source."""

    def __init__(self, source: str) -> None:
        self.source = source

    def __call__(self, field: str | None, reason: str, unit: str | None = None,
                 value: Any = None) -> ShipFileError:
        return ShipFileError(reason, source=self.source, field=field, unit=unit, value=value)


def _check_keys(data: Mapping[str, Any], fail: Any) -> None:
    import difflib

    def unknown(path: str, key: str, valid: set[str]) -> ShipFileError:
        close = difflib.get_close_matches(key, sorted(valid), n=1)
        hint = f" (did you mean `{close[0]}`?)" if close else ""
        return fail(f"{path}{key}", f"is an unknown key{hint}; valid here: "
                                    f"{', '.join(sorted(valid))}")

    if "format" not in data and SCENARIO_KEYS & set(data):
        raise fail(None, "is a scenario file, not a ship file (run it with `seahelm run`; a "
                         "ship file has `format`, `name`, `model` and [params])")
    for key in data:
        if key not in TOP_KEYS:
            raise unknown("", key, TOP_KEYS)
    for section, valid in SECTION_KEYS.items():
        sec = data.get(section)
        if isinstance(sec, Mapping):
            for key in sec:
                if key not in valid:
                    raise unknown(f"{section}.", key, valid)


def _merged_with_base(data: dict[str, Any], fail: Any, directory: Any,
                      lookup: BaseLookup | None) -> dict[str, Any]:
    base_name = data.pop("base")
    if not isinstance(base_name, str):
        raise fail("base", f"must be a catalog ship or a ship file path, got {base_name!r}")
    if lookup is None:
        raise fail("base", "needs the catalog to find the base ship: read the file with "
                           "seahelm.ships.read_ship or get_ship")
    if is_ship_path(base_name) and not Path(base_name).is_absolute() and directory is not None:
        base_name = str(Path(directory) / base_name)
    try:
        base = lookup(base_name)
    except _BaseCycle:
        raise  # (said once, about the file the chain closes on)
    except (ParameterError, ValueError) as exc:
        raise fail("base", str(exc)) from None
    model = data.get("model")
    if isinstance(model, str) and model != base.model.name:
        raise fail("base", f"'{base.name}' is a ship of model '{base.model.name}', not "
                           f"'{model}': a base gives its parameters, so it must be of the same "
                           "model")
    merged = ship_to_mapping(base)
    if "params" in data:  # new parameters: the base's test speed no longer applies
        merged.pop("test_speed", None)
    if "description" not in data:
        merged["description"] = f"based on '{base.name}': {base.description}".rstrip(": ")
    changed = [key for section in ("params", "steering_gear", "particulars")
               for key in _key_paths(data.get(section), section)]
    prov = merged.setdefault("provenance", {})
    given = data.get("provenance") if isinstance(data.get("provenance"), Mapping) else {}
    if changed and "params" not in given:
        prov["params"] = (f"{prov.get('params', '')} Changed from the base ship "
                          f"'{base.name}': {', '.join(changed)} ({fail.source}).").strip()
    for key, value in data.items():
        if isinstance(value, Mapping) and isinstance(merged.get(key), Mapping):
            merged[key] = _merge(merged[key], value)
        else:
            merged[key] = value
    return merged


def _key_paths(value: Any, path: str) -> list[str]:
    """The dotted paths of the leaves of a (nested) table."""
    if not isinstance(value, Mapping):
        return [] if value is None else [path]
    return [p for k, v in value.items() for p in _key_paths(v, f"{path}.{k}")]


def _merge(base: Mapping[str, Any], over: Mapping[str, Any]) -> dict[str, Any]:
    out = dict(base)
    for key, value in over.items():
        # an angle given in degrees replaces the base's radians, and the other way round
        twin = key[:-4] if key.endswith("_deg") else f"{key}_deg"
        out.pop(twin, None)
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = _merge(out[key], value)
        else:
            out[key] = value
    return out


def _table(data: Mapping[str, Any], key: str, fail: Any, *, required: bool = False
           ) -> Mapping[str, Any]:
    value = data.get(key, {} if not required else None)
    if value is None:
        raise fail(key, "is required (a table)")
    if not isinstance(value, Mapping):
        raise fail(key, f"must be a table [{key}], got {value!r}")
    return value


def _text(data: Mapping[str, Any], key: str, fail: Any, *, prefix: str = "") -> str:
    value = data[key]
    if not isinstance(value, str) or not value.strip():
        raise fail(prefix + key, f"must be a non-empty text, got {value!r}")
    return value


def _opt_text(data: Mapping[str, Any], path: str, key: str, fail: Any) -> str:
    value = data.get(key, "")
    if not isinstance(value, str):
        raise fail(path, f"must be a text, got {value!r}")
    return value


def _number(value: Any, path: str, unit: str, fail: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise fail(path, f"must be a number [{unit}], got {value!r}", unit=unit, value=value)
    return float(value)


def _params(cls: type[Params], values: Mapping[str, Any], path: str, fail: Any, *,
            complete: bool) -> Params:
    fields = {f.name: f for f in dataclasses.fields(cls)}
    for key in values:
        name = key[:-4] if key.endswith("_deg") and key not in fields else key
        if name not in fields:
            import difflib

            close = difflib.get_close_matches(key, sorted(fields), n=1)
            hint = f" (did you mean `{close[0]}`?)" if close else ""
            raise fail(f"{path}.{key}", f"is an unknown key: not a parameter of "
                                        f"{cls.__name__}{hint}")
    if complete:
        given = {k[:-4] if k.endswith("_deg") and k not in fields else k for k in values}
        missing = [n for n in fields if n not in given]
        if missing:
            listed = ", ".join(f"{n} [{fields[n].metadata.get('unit') or '-'}]"
                               for n in missing[:8])
            more = f" and {len(missing) - 8} more" if len(missing) > 8 else ""
            raise fail(path, f"misses {len(missing)} parameter(s) of {cls.__name__}: "
                             f"{listed}{more} (a ship file gives every parameter, or names a "
                             "`base` ship to take the others from)")
    try:
        return cls.from_mapping(values, base=None if complete else cls())
    except ParameterError as exc:
        if exc.field is not None:
            raise ShipFileError(exc.reason, source=fail.source,
                                field=f"{path}.{exc.field}", unit=exc.unit,
                                value=exc.value) from None
        raise fail(path, exc.reason) from None
    except TypeError as exc:
        raise fail(path, str(exc)) from None


def _steering_gear(sec: Mapping[str, Any], fail: Any, provenance: str) -> SteeringGear:
    from ..registry import ACTUATORS, get_actuator

    if "actuator" not in sec:
        raise fail("steering_gear.actuator", "is required in [steering_gear]")
    name = _text(sec, "actuator", fail, prefix="steering_gear.")
    if name not in ACTUATORS:
        raise fail("steering_gear.actuator", f"'{name}' is not an actuator; valid: "
                                             f"{', '.join(sorted(ACTUATORS))}")
    actuator = get_actuator(name)
    params = _params(actuator.params_type, _table(sec, "params", fail), "steering_gear.params",
                     fail, complete=True)
    return _build(SteeringGear, "steering_gear", fail, actuator=actuator, params=params,
                  provenance=provenance)


def _build(cls: type, path: str | None, fail: Any, **kwargs: Any) -> Any:
    try:
        return cls(**kwargs)
    except ParameterError as exc:
        field = exc.field if path is None else (f"{path}.{exc.field}" if exc.field else path)
        raise ShipFileError(exc.reason, source=fail.source, field=field,
                            unit=exc.unit, value=exc.value) from None


