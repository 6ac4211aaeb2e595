"""Reading a scenario file: TOML, then the schema, then the runs or the manoeuvre it describes."""

from __future__ import annotations

import os
import re
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from ..simulation.problem import Problem
from .environment import KEY_UNITS as _ENV_UNITS
from .errors import ScenarioError
from .maneuver import ManeuverJob, prepare_maneuver
from .runs import prepare_runs
from .schema import Scenario

__all__ = ["default_scenario_text", "parse_scenario", "load_scenario", "validate_scenario",
           "section_model"]


def default_scenario_text() -> str:
    """The embedded default scenario: a 20° course change of the Mariner under PID."""
    return resources.files("seahelm").joinpath("data/default.toml").read_text()


def validate_scenario(text: str, *, source: str = "<string>") -> Scenario:
    """Parse TOML text and validate its structure (sections, keys, types, simple ranges).

    Parameters
    ----------
    text : str
        TOML scenario text.
    source : str, optional
        Name of the source used in error messages (default "<string>").

    Returns
    -------
    Scenario

    Raises
    ------
    ScenarioError
        If the text is not valid TOML or fails validation (one line per error).
    TypeError
        If ``text`` is not a str (a path: :func:`load_scenario` reads a file).
    """
    if not isinstance(text, str):
        hint = (" (a file is read by seahelm.load_scenario(path))"
                if isinstance(text, (os.PathLike, bytes)) else "")
        raise TypeError(f"`text` must be the scenario's TOML text (a str), got "
                        f"{type(text).__name__} {text!r:.60}{hint}")
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{source}: not valid TOML: {exc}") from None
    try:
        return Scenario.model_validate(raw)
    except ValidationError as exc:
        lines: list[str] = []
        errors: dict[str, list[Any]] = {}
        for err in exc.errors():
            # a value of a union type (a number or a signal table) fails once per member: the
            # members' type tags are not part of the key path, the errors are said once
            path = ".".join(str(p) for p in err["loc"] if not _TYPE_TAG.match(str(p)))
            errors.setdefault(path, []).append(err)
        for path, errs in errors.items():
            err = errs[0]
            value = err.get("input")
            shown = "" if isinstance(value, dict) else f", got {value!r}"
            where = f" [{path}]" if path else ""  # (a whole-file check names no key)
            unit = _unit_of(path)
            if any(e["type"] == "too_short" for e in errs):  # a number or a list of them
                message = f"must be a number or a non-empty list of numbers{_bracket(unit)}"
            elif err["type"] == "extra_forbidden":
                message, shown = _unknown_key(path), ""
            else:
                message = _message(err, unit)
            lines.append(f"{source}:{where} {message}{shown}")
        raise ScenarioError("\n".join(lines)) from None


def _bracket(unit: str) -> str:
    return f" [{unit}]" if unit else ""


def _unknown_key(path: str) -> str:
    """"is an unknown key (did you mean `record_every`?); valid here: ..." for a key the
    section does not have."""
    import difflib

    parts = path.split(".")
    model: Any = Scenario
    for part in parts[:-1]:
        field = getattr(model, "model_fields", {}).get(part)
        model = section_model(field.annotation) if field is not None else None
        if model is None:
            return "is an unknown key"
    valid = sorted(model.model_fields)
    close = difflib.get_close_matches(parts[-1], valid, n=1)
    hint = f" (did you mean `{close[0]}`?)" if close else ""
    section = ".".join(parts[:-1])
    return (f"is an unknown key{hint}; valid in {f'[{section}]' if section else 'the file'}: "
            f"{', '.join(valid)}")


def section_model(annotation: Any) -> Any:
    """The pydantic model an annotation of the schema holds (itself, optional, in a union or
    as a mapping's values); None for a plain value.

    Parameters
    ----------
    annotation : object
        A field's annotation.

    Returns
    -------
    type or None
    """
    import inspect
    import typing

    from pydantic import BaseModel

    if inspect.isclass(annotation) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = section_model(arg)
        if found is not None:
            return found
    return None


_TYPE_TAG = re.compile(r"^(float|int|str|bool|constrained-float|function-\w+\[.*\]|"
                       r"list\[.*\]|dict\[.*\]|tuple\[.*\])$")

#: Units of the scenario's own numeric keys (the components' parameters carry theirs).
_UNITS = {
    "simulation.t_final": "s", "simulation.dt": "s", "controller.dt": "s",
    "maneuver.t_final": "s", "maneuver.dt": "s", "maneuver.record_dt": "s",
    "maneuver.hold": "s", "maneuver.speed": "m/s", "maneuver.rps": "1/s",
    "maneuver.rudder": "rad", "maneuver.heading": "rad", "maneuver.max_rudder": "rad",
    "guidance.acceptance_radius": "m", "guidance.lookahead": "m", "guidance.lookahead_min": "m",
    "guidance.lookahead_gamma": "1/m²", "guidance.kappa": "m/s",
    "environment.current.speed": "m/s", "environment.current.direction_deg": "deg",
    **_ENV_UNITS,
}


def _unit_of(path: str) -> str:
    key = re.sub(r"\.\d+$", "", path)  # an element of a list has the list's unit
    if key.endswith("_deg"):
        return "deg"
    return _UNITS.get(key, "")


def _message(err: Any, unit: str) -> str:
    """pydantic's message in the scenario's words: ``must be > 0 [s]`` for a bound."""
    kind, ctx = err["type"], err.get("ctx") or {}
    u = f" [{unit}]" if unit else ""
    bounds = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<",
              "less_than_equal": "<="}
    if kind in bounds:
        key = {"greater_than": "gt", "greater_than_equal": "ge", "less_than": "lt",
               "less_than_equal": "le"}[kind]
        limit = ctx.get(key)
        shown = f"{limit:g}" if isinstance(limit, (int, float)) else str(limit)
        return f"must be {bounds[kind]} {shown}{u}"
    if kind == "finite_number":
        return f"must be a finite number{u}"
    if kind in ("int_type", "int_from_float") and isinstance(err.get("input"), float):
        return f"must be a whole number{u}"  # (record_every = 2.5: a number, but not whole)
    if kind in ("float_type", "float_parsing", "int_type", "int_parsing"):
        return f"must be a number{u} (not a string or a boolean)"
    return err["msg"].removeprefix("Value error, ")


def parse_scenario(text: str, *, source: str = "<string>", in_memory: bool = True
                   ) -> Problem | ManeuverJob:
    """Parse and validate scenario text into what it describes; nothing runs.

    A ``[simulation]`` scenario gives the :class:`~seahelm.simulation.problem.Problem` of its
    runs (what the engine runs -- timing, command counts, bounds labels -- is validated by the
    engine when the batch runs, before any step is integrated); a ``[maneuver]`` scenario gives
    a :class:`~seahelm.scenario.maneuver.ManeuverJob`. :func:`~seahelm.scenario.run_scenario`
    runs either.

    Parameters
    ----------
    text : str
        TOML scenario text.
    source : str, optional
        Name of the source used in error messages (default "<string>").

    in_memory : bool, optional
        The whole batch is to be held in memory (default True; False for a sweep, which streams
        it in chunks: :func:`~seahelm.scenario.runs.prepare_runs`).

    Returns
    -------
    Problem or ManeuverJob

    Raises
    ------
    ScenarioError
        If the text is not valid TOML or fails validation (one line per error).
    TypeError
        If ``text`` is not a str (:func:`validate_scenario`).
    """
    scn = validate_scenario(text, source=source)
    if scn.maneuver is not None:
        return prepare_maneuver(scn, source=source, text=text)
    return prepare_runs(scn, source=source, text=text, in_memory=in_memory)


def load_scenario(path: str | Path) -> Any:
    """Read, parse and validate a scenario file (UTF-8, a byte-order mark is allowed).

    Parameters
    ----------
    path : str or pathlib.Path
        TOML scenario file.

    Returns
    -------
    Problem or ManeuverJob
        See :func:`parse_scenario`.

    Raises
    ------
    ScenarioError
        If the file is missing or unreadable, not UTF-8, not valid TOML or fails validation.
    """
    path = Path(path)
    if not path.exists():
        raise ScenarioError(f"scenario file not found: {path}")
    if path.is_dir():
        raise ScenarioError(f"{path} is a directory, not a scenario file")
    if not path.is_file():
        raise ScenarioError(f"{path} is not a regular file (a TOML scenario file is needed)")
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ScenarioError(f"{path}: not UTF-8 text (byte {exc.start}: "
                            f"{exc.object[exc.start:exc.start + 1]!r}); save the scenario as "
                            "UTF-8") from None
    except OSError as exc:
        raise ScenarioError(f"{path}: cannot read the scenario file ({exc.strerror})") from None
    return parse_scenario(text, source=str(path))
