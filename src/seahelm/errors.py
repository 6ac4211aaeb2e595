"""Exceptions and warnings raised by seahelm.

Every seahelm exception subclasses :class:`SeahelmError` and, where it makes sense, the
matching built-in (``ValueError``, ``ImportError``, ``ArithmeticError``) so that callers can
catch either.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

__all__ = [
    "SeahelmError",
    "ParameterError",
    "ValidityRangeWarning",
    "SimulationDiverged",
    "MissingDependencyError",
    "strict_validity",
    "warn_validity",
]


class SeahelmError(Exception):
    """Base class of every seahelm exception."""


class ParameterError(SeahelmError, ValueError):
    """A parameter is outside its admissible domain (names the parameter, unit and value)."""


class ValidityRangeWarning(UserWarning):
    """An empirical formula is used outside the range of data it was fitted to."""


class SimulationDiverged(SeahelmError, ArithmeticError):
    """A simulated state became NaN/inf or left its declared bounds.

    Attributes
    ----------
    time : float
        Simulation time [s] of the first step at which the state was invalid.
    state : numpy.ndarray
        The state at that time (may contain NaN/inf).
    run : int
        Index of the run in the batch.
    """

    def __init__(self, message: str, *, time: float, state: Any, run: int = 0) -> None:
        super().__init__(message)
        self.time = float(time)
        self.state = np.asarray(state)
        self.run = int(run)


class MissingDependencyError(SeahelmError, ImportError):
    """An optional dependency is needed for this feature; the message names the extra."""


_STRICT = {"on": False}


class strict_validity:
    """Context manager (and function) turning :class:`ValidityRangeWarning` into errors.

    Examples
    --------
    >>> with strict_validity():
    ...     pass  # empirical formulas outside their range now raise ParameterError
    """

    def __init__(self, on: bool = True) -> None:
        self._on = on
        self._old = _STRICT["on"]

    def __enter__(self) -> "strict_validity":
        self._old = _STRICT["on"]
        _STRICT["on"] = self._on
        return self

    def __exit__(self, *exc: object) -> None:
        _STRICT["on"] = self._old


def warn_validity(message: str, *, strict: bool | None = None, stacklevel: int = 3) -> None:
    """Warn (or raise in strict mode) that an empirical formula is outside its validity range.

    Parameters
    ----------
    message : str
        Warning (or error) message.
    strict : bool, optional
        Raise :class:`ParameterError` instead of warning (default: the global strict mode).
    stacklevel : int, optional
        Passed to :func:`warnings.warn` (default 3).
    """
    if strict is None:
        strict = _STRICT["on"]
    if strict:
        raise ParameterError(message)
    warnings.warn(message, ValidityRangeWarning, stacklevel=stacklevel)
