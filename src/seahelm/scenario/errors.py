"""The error of a scenario file, naming the file and the key path."""

from __future__ import annotations

from ..errors import ParameterError

__all__ = ["ScenarioError", "at_key"]


class ScenarioError(ParameterError):
    """A scenario file is invalid (the message names the file, key path, value, expectation)."""


def at_key(source: str, path: str, message: str) -> ScenarioError:
    """The error of one key of a scenario file: ``<source>: [<path>] <message>``.

    Parameters
    ----------
    source : str
        The scenario file (or ``<string>``).
    path : str
        Key path, e.g. ``vessel.params``.
    message : str
        What is wrong: the value and what was expected.

    Returns
    -------
    ScenarioError
    """
    return ScenarioError(f"{source}: [{path}] {message}")
