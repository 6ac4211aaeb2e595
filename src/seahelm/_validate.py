"""Validation helpers for public boundaries: messages name parameter, unit and value."""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Mapping
from typing import Any

import numpy as np

from .errors import ParameterError

__all__ = ["check_finite", "check_positive", "check_nonnegative", "check_range", "as_float_array",
           "as_finite_series", "lookup_name"]


def _fmt(value: Any) -> str:
    arr = np.asarray(value)
    if arr.ndim == 0:
        return repr(float(arr)) if np.issubdtype(arr.dtype, np.number) else repr(value)
    bad = arr.ravel()
    return np.array2string(bad[:6], precision=6) + (" ..." if bad.size > 6 else "")


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""


def check_finite(name: str, value: Any, unit: str = "") -> None:
    """Raise :class:`ParameterError` if ``value`` has NaN or inf.

    Parameters
    ----------
    name : str
        Argument name used in the error message.
    value : float or array_like
        Value(s) to check.
    unit : str, optional
        Unit shown in brackets in the error message (default: none).
    """
    if isinstance(value, float) and math.isfinite(value):  # (the common scalar, quickly)
        return
    arr = np.asarray(value, dtype=float)
    if not np.isfinite(arr).all():
        raise ParameterError(f"must be finite{_unit(unit)}, got {_fmt(value)}",
                             field=name, unit=unit or None, value=value)


def check_positive(name: str, value: Any, unit: str = "") -> None:
    """Raise :class:`ParameterError` unless every element of ``value`` is finite and > 0.

    Parameters
    ----------
    name : str
        Argument name used in the error message.
    value : float or array_like
        Value(s) to check.
    unit : str, optional
        Unit shown in brackets in the error message (default: none).
    """
    if isinstance(value, float) and 0.0 < value < math.inf:  # (the common scalar, quickly)
        return
    check_finite(name, value, unit)
    if not np.all(np.asarray(value, dtype=float) > 0):
        raise ParameterError(f"must be > 0{_unit(unit)}, got {_fmt(value)}",
                             field=name, unit=unit or None, value=value)


def check_nonnegative(name: str, value: Any, unit: str = "") -> None:
    """Raise :class:`ParameterError` unless every element of ``value`` is finite and >= 0.

    Parameters
    ----------
    name : str
        Argument name used in the error message.
    value : float or array_like
        Value(s) to check.
    unit : str, optional
        Unit shown in brackets in the error message (default: none).
    """
    check_finite(name, value, unit)
    if not np.all(np.asarray(value, dtype=float) >= 0):
        raise ParameterError(f"must be >= 0{_unit(unit)}, got {_fmt(value)}",
                             field=name, unit=unit or None, value=value)


def check_range(
    name: str,
    value: Any,
    low: float = -math.inf,
    high: float = math.inf,
    unit: str = "",
    *,
    inclusive: bool = True,
) -> None:
    """Raise :class:`ParameterError` unless ``low <= value <= high`` (or strict if not inclusive).

    Parameters
    ----------
    name : str
        Argument name used in the error message.
    value : float or array_like
        Value(s) to check.
    low, high : float, optional
        Bounds of the admissible interval, in the unit of ``value`` (default -inf, +inf).
    unit : str, optional
        Unit shown in brackets in the error message (default: none).
    inclusive : bool, optional
        Closed interval ``[low, high]`` if True (default), open ``(low, high)`` otherwise.
    """
    check_finite(name, value, unit)
    arr = np.asarray(value, dtype=float)
    ok = (arr >= low) & (arr <= high) if inclusive else (arr > low) & (arr < high)
    if not np.all(ok):
        lo, hi = ("[", "]") if inclusive else ("(", ")")
        raise ParameterError(
            f"must be in {lo}{low:g}, {high:g}{hi}{_unit(unit)}, got {_fmt(value)}",
            field=name, unit=unit or None, value=value)


def check_on_hull(name: str, centre: Any, length: Any) -> None:
    """Raise :class:`ParameterError` unless a centre measured from midships [m] lies on the
    ship: ``|centre| <= length / 2``.

    Parameters
    ----------
    name : str
        Argument name used in the error message (e.g. ``sail_centre``).
    centre, length : float or array_like
        The centre forward of midships and the ship length [m] (broadcast together).
    """
    c, half = np.broadcast_arrays(np.asarray(centre, dtype=float),
                                  0.5 * np.asarray(length, dtype=float))
    bad = ~(np.abs(c) <= half)
    if np.any(bad):
        raise ParameterError(
            f"must lie on the ship, within ±L/2 = ±{float(half[bad].flat[0]):g} [m] of "
            f"midships, got {_fmt(float(c[bad].flat[0]))} [m]", field=name, unit="m",
            value=centre)


def uniform_time_step(t: Any, what: str) -> tuple[np.ndarray, float]:
    """A time grid as a float array and its step, or a ParameterError if it is not uniform.

    Parameters
    ----------
    t : array_like
        Time grid [s]: 1-D, 2 or more equally spaced samples.
    what : str
        What needs the grid, for the message (e.g. "a gust").

    Returns
    -------
    (numpy.ndarray, float)
        The grid and its step [s].
    """
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size < 2 or not np.allclose(np.diff(t), t[1] - t[0]):
        raise ParameterError(f"{what} needs a uniform time grid of 2 or more samples")
    return t, float(t[1] - t[0])


def as_float_array(name: str, value: Any, unit: str = "", *, finite: bool = True) -> np.ndarray:
    """Convert to a float64 array, naming the parameter when that fails or values are not finite.

    Parameters
    ----------
    name : str
        Argument name used in the error message.
    value : array_like
        Value(s) to convert.
    unit : str, optional
        Unit shown in brackets in the error message (default: none).
    finite : bool, optional
        Also require every element to be finite (default True).

    Returns
    -------
    numpy.ndarray
        ``value`` as a float64 array.
    """
    if type(value) is float and (math.isfinite(value) or not finite):  # (a number, quickly:
        return np.array(value)  # the 0-d float64 array of the general form, without its checks)
    if type(value) is np.ndarray and value.dtype == np.float64:  # (as it is, checked once)
        if finite:
            check_finite(name, value, unit)
        return value
    raw = np.asarray(value) if not isinstance(value, np.ndarray) else value
    if raw.dtype.kind in "cUSO" and raw.dtype != object or raw.dtype.kind == "b":
        # complex, text or booleans: not read as numbers (a complex part would be dropped)
        kind = {"c": "complex", "U": "text", "S": "text", "b": "booleans"}[raw.dtype.kind]
        raise ParameterError(f"must be real numbers{_unit(unit)}, got {kind}: {value!r}",
                             field=name, unit=unit or None, value=value)
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:  # (10**400: beyond floats)
        raise ParameterError(f"must be numeric{_unit(unit)}, got {value!r}",
                             field=name, unit=unit or None, value=value) from exc
    if finite:
        check_finite(name, arr, unit)
    return arr


def as_finite_series(name: str, value: Any, unit: str, *, what: str = "sample(s)") -> np.ndarray:
    """A finite 1-D float array, or ParameterError naming ``name``, ``unit`` and where.

    Parameters
    ----------
    name : str
        Argument name for the message.
    value : array_like
        The series.
    unit : str
        Unit for the message.
    what : str, optional
        What the indices of non-finite entries count ("sample(s)", "point(s)").
    """
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"must be numbers [{unit}], got {value!r}",
                             field=name, unit=unit or None, value=value) from None
    if a.ndim != 1:
        raise ParameterError(f"must be one-dimensional [{unit}], got shape {a.shape}",
                             field=name, unit=unit or None, value=value)
    bad = ~np.isfinite(a)
    if bad.any():
        raise ParameterError(
            f"must be finite [{unit}], got NaN/inf at {what} "
            f"{np.flatnonzero(bad)[:6].tolist()}", field=name, unit=unit or None
        )
    return a


def lookup_name(kind: str, table: Mapping[str, Any] | Collection[str], name: Any, *,
                error: type[Exception] = ValueError, sort: bool = False, quoted: bool = False,
                valid: Iterable[str] | None = None, suffix: str = "", **fields: Any) -> Any:
    """``table[name]`` for a name of ``table``; otherwise the one error of every lookup by
    name: ``unknown {kind} 'name'; valid: a, b, c``.

    The rule of :func:`seahelm.registry.lookup` (which resolves registry entries with it) for
    any table: the strategies, methods, forms and sets chosen by name.

    Parameters
    ----------
    kind : str
        What is looked up, for the message (``"Holtrop method"``, ``"guidance law"``).
    table : mapping of str to object, or collection of str
        The names and what each gives (or only the names: then the name is returned).
    name : object
        The name asked for (anything that is not a key of ``table`` is an error).
    error : type, optional
        The exception to raise: ValueError (default), :class:`~seahelm.errors.ParameterError`
        (then ``fields`` such as ``field=`` go to it), KeyError.
    sort : bool, optional
        List the valid names sorted (default: in the table's order).
    quoted : bool, optional
        List them quoted (``'a', 'b'``).
    valid : iterable of str, optional
        The names to list, where they are not the table's keys (aliases left out, say).
    suffix : str, optional
        Said after the list (``" (or None: all types)"``).
    **fields
        Keyword arguments of ``error`` (``field``, ``value``).

    Returns
    -------
    object
        ``table[name]`` (``name`` for a table of names only).

    Raises
    ------
    ValueError, or ``error``
        For a name that is not a key of ``table``, naming it and the valid ones.
    """
    if isinstance(name, str) and name in table:
        return table[name] if isinstance(table, Mapping) else name
    names = list(table if valid is None else valid)
    if sort:
        names = sorted(names)
    listed = ", ".join(repr(n) if quoted else str(n) for n in names)
    raise error(f"unknown {kind} {name!r}; valid: {listed}{suffix}", **fields) from None
