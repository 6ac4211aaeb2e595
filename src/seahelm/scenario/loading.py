"""Reading a scenario file: TOML, then the schema, then the runs or the manoeuvre it describes."""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from ..simulation.batch import RunBatch
from .errors import ScenarioError
from .maneuver import ManeuverJob, prepare_maneuver
from .runs import prepare_runs
from .schema import Scenario

__all__ = ["default_scenario_text", "parse_scenario", "load_scenario", "validate_scenario"]


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
    """
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{source}: not valid TOML: {exc}") from None
    try:
        return Scenario.model_validate(raw)
    except ValidationError as exc:
        lines = []
        for err in exc.errors():
            path = ".".join(str(p) for p in err["loc"])
            value = err.get("input")
            shown = "" if isinstance(value, dict) else f", got {value!r}"
            message = err["msg"].removeprefix("Value error, ")
            where = f" [{path}]" if path else ""  # (a whole-file check names no key)
            lines.append(f"{source}:{where} {message}{shown}")
        raise ScenarioError("\n".join(lines)) from None


def parse_scenario(text: str, *, source: str = "<string>") -> RunBatch | ManeuverJob:
    """Parse and validate scenario text into what it describes; nothing runs.

    A ``[simulation]`` scenario gives the :class:`~seahelm.simulation.batch.RunBatch` of its
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

    Returns
    -------
    RunBatch or ManeuverJob

    Raises
    ------
    ScenarioError
        If the text is not valid TOML or fails validation (one line per error).
    """
    scn = validate_scenario(text, source=source)
    if scn.maneuver is not None:
        return prepare_maneuver(scn, source=source, text=text)
    return prepare_runs(scn, source=source, text=text)


def load_scenario(path: str | Path) -> Any:
    """Read, parse and validate a scenario file (UTF-8, a byte-order mark is allowed).

    Parameters
    ----------
    path : str or pathlib.Path
        TOML scenario file.

    Returns
    -------
    RunBatch or ManeuverJob
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
