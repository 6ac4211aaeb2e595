"""The engine's inputs converted to the kernel's arrays: parameter rows, signals on the grid.

:func:`_param_rows` turns parameter sets (records or arrays) into rows, :func:`_signal` a
reference or disturbance specification (a number, an array, a callable of time or a mapping by
channel name) into an array of shape (runs|1, steps+1|1, channels); :func:`_runs` checks that
batch sizes broadcast, :func:`_check_angles` that angle channels are angles and
:func:`check_rudder_angles` that a rudder is not told to turn beyond a right angle.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._validate import as_float_array
from ..errors import ParameterError
from ..parameters import Params, stack_params

__all__ = ["MAX_ANGLE", "MAX_RUDDER_ANGLE", "check_rudder_angles"]


@functools.lru_cache(maxsize=None)
def _default_params(cls: type[Params]) -> Params:
    """The default parameter set of a class (frozen, so one instance serves every run)."""
    return cls()


def _param_rows(name: str, params: Any, cls: type[Params]) -> tuple[np.ndarray, type[Params]]:
    """Parameter rows (runs, n_fields) and the class they were given as (a subclass of
    ``cls`` carries more fields; compiled code finds its fields by name)."""
    if params is None:
        try:
            params = _default_params(cls)
        except TypeError:
            raise ParameterError(f"is required for {cls.__name__}", field=name) from None
    if isinstance(params, Params) or (
        isinstance(params, Sequence) and len(params) > 0 and isinstance(params[0], Params)
    ):
        first = params if isinstance(params, Params) else params[0]
        return stack_params(params, cls), type(first)
    # a copy: the kernel and the result's ``params`` get rows of their own, never the caller's
    arr = np.array(np.atleast_2d(as_float_array(name, params)), dtype=float, order="C")
    if arr.ndim != 2 or arr.shape[1] != cls.n_values():
        raise ParameterError(
            f"as an array must have shape (runs, {cls.n_values()}) "
            f"({', '.join(cls.value_names())}), got {arr.shape}", field=name)
    for row in arr:  # validate every row through the dataclass
        cls.from_array(row)
    return arr, cls


class _TimeGrid:
    """The grid t_k = k dt, k = 0 … n_steps, built only if a signal is a function of time."""

    def __init__(self, n_steps: int, dt: float) -> None:
        self.size = n_steps + 1
        self.dt = dt
        self._array: np.ndarray | None = None

    def array(self) -> np.ndarray:
        if self._array is None:
            self._array = np.arange(self.size) * self.dt
        return self._array


def _number(value: Any) -> Any:
    """A one-sample constant as a Python number: a float64 array of one value, 0-d, (1,) or
    (1, 1, 1), which :func:`_signal` reads as that one value (a manoeuvre's schedule gives its
    constant channels so); anything else as it is."""
    if (type(value) is np.ndarray and value.dtype == np.float64 and value.size == 1
            and value.ndim in (0, 1, 3)):
        return value.item()
    return value


def _by_name(name: str, value: Mapping[str, Any], labels: tuple[str, ...],
             t_grid: "_TimeGrid", unit: str) -> np.ndarray:
    """A mapping channel name -> specification, assembled into (runs|1, steps+1|1, channels)."""
    unknown = [k for k in value if k not in labels]
    if unknown:
        raise ParameterError(
            f": unknown channel(s) {', '.join(map(repr, unknown))}; channels: "
            f"{', '.join(labels) if labels else 'none'}", field=name)
    if labels:  # every channel a finite number (a set-point): one row, no per-channel arrays
        row = [_number(value.get(lab, 0.0)) for lab in labels]
        if all(type(v) is float or type(v) is int for v in row):
            try:
                finite = math.isfinite(math.fsum(row))
            except (OverflowError, ValueError):  # (an int beyond floats, or inf and -inf
                finite = False  # together -- fsum's ValueError: the general path names them)
            if finite:
                return np.array(row, dtype=float).reshape(1, 1, len(labels))
    cols = [_signal(f"{name}['{lab}']", value.get(lab, 0.0), 1, t_grid, unit) for lab in labels]
    if not cols:
        return np.zeros((1, 1, 1))
    runs = _runs(*((f"{name}['{lab}']", c.shape[0]) for lab, c in zip(labels, cols)))
    steps = max(c.shape[1] for c in cols)
    return np.ascontiguousarray(np.concatenate(
        [np.broadcast_to(c, (runs, steps, 1)) for c in cols], axis=2))


def _signal(
    name: str, value: Any, n_channels: int, t_grid: "_TimeGrid", unit: str,
    labels: tuple[str, ...] = (),
) -> np.ndarray:
    """Convert a reference/disturbance specification to shape (runs|1, steps+1|1, channels)."""
    width = max(n_channels, 1)
    if value is None:
        return np.zeros((1, 1, width))
    if isinstance(value, Mapping):
        return _by_name(name, value, labels, t_grid, unit)
    if callable(value):
        value = value(t_grid.array())
        arr = as_float_array(name, value, unit)
        if arr.ndim == 1 and arr.shape[0] == t_grid.size:
            arr = arr[:, None]
        if arr.ndim == 2:
            arr = arr[None]
        if arr.ndim != 3 or arr.shape[1] != t_grid.size:
            raise ParameterError(
                f"callable must return shape (steps+1,), (steps+1, channels) or "
                f"(runs, steps+1, channels) for {t_grid.size} grid times, got {np.shape(value)}",
                field=name)
    else:
        arr = as_float_array(name, value, unit)
        if arr.ndim == 0:
            arr = arr.reshape(1, 1, 1)
        elif arr.ndim == 1:
            arr = arr.reshape(1, 1, -1)
        elif arr.ndim == 2:
            if arr.shape[0] != t_grid.size:
                raise ParameterError(
                    f"as a 2-D array is a time series on the grid and needs "
                    f"{t_grid.size} rows (steps+1), got {arr.shape}; per-run constants have "
                    "shape (runs, 1, channels)", field=name)
            arr = arr[None]
        elif arr.ndim != 3:
            raise ParameterError(f"must have at most 3 dimensions, got {arr.shape}", field=name)
        if arr.shape[1] not in (1, t_grid.size):
            raise ParameterError(
                f"time axis must have 1 or {t_grid.size} samples, got {arr.shape[1]}", field=name)
    if n_channels == 0:
        if arr.shape[-1] not in (0, 1) or np.any(arr != 0):
            raise ParameterError("given, but the component takes none", field=name)
        return np.zeros(arr.shape[:2] + (1,))
    if arr.shape[-1] != n_channels:
        named = f" ({', '.join(labels)})" if labels else ""
        raise ParameterError(
            f"must have {n_channels} channel(s){named}, got {arr.shape[-1]}", field=name)
    return np.ascontiguousarray(arr, dtype=float)



#: Largest magnitude of an angle signal [rad]: a thousand turns. A heading reference of 1e300
#: (a unit mix-up, a garbage file) is no course: wrapped, it is noise of float precision.
MAX_ANGLE = 2000.0 * math.pi


def _check_angles(name: str, values: np.ndarray, labels: tuple[str, ...],
                  units: tuple[str, ...]) -> None:
    """Angle channels ([rad]) of a signal within ±:data:`MAX_ANGLE` (rudders within
    ±:data:`MAX_RUDDER_ANGLE`, :func:`check_rudder_angles`): every rudder channel first,
    then every angle, as the two checks one after the other (each angle channel's magnitude
    found once, not again for the rudder check)."""
    n = min(len(labels), len(units), values.shape[-1])
    rad = [j for j in range(n) if units[j] == "rad"]
    if not rad:
        return
    # each angle channel's largest magnitude, once (a set-point, one sample a channel, as
    # Python floats: the same numbers without a reduction)
    if values.size == values.shape[-1]:
        worst_of = [abs(v) for v in values.ravel().tolist()]
    else:
        worst_of = {j: float(np.abs(values[..., j]).max()) for j in rad}
    for j in rad:
        if labels[j].startswith("rudder") and worst_of[j] > MAX_RUDDER_ANGLE:
            raise _rudder_error(name, labels[j], values[..., j])
    for j in rad:
        label, worst = labels[j], worst_of[j]
        if worst > MAX_ANGLE:
            raise ParameterError(
                f": channel '{label}' reaches {worst:.6g} rad, more than a thousand turns "
                f"(±{MAX_ANGLE:.6g} rad); an angle is given in radians here (degrees in a "
                "scenario as <name>_deg)", field=name, unit="rad", value=worst)


#: Largest rudder angle a command or reference may name [rad]: a right angle. No rudder turns
#: further (high-lift rudders reach 65-70 deg); ``rudder_command = 35.0`` is degrees given as
#: radians, which the rudder's limit would otherwise silently turn into hard over.
MAX_RUDDER_ANGLE = 0.5 * math.pi


def check_rudder_angles(name: str, values: np.ndarray, labels: tuple[str, ...],
                        units: tuple[str, ...], runs: np.ndarray | None = None) -> None:
    """Rudder channels (a label beginning ``rudder``, unit ``rad``) within
    ±:data:`MAX_RUDDER_ANGLE`.

    Parameters
    ----------
    name : str
        The parameter named in the error (``reference``, ``commands``).
    values : ndarray (..., channels)
        The channels, in the order of ``labels``.
    labels, units : tuple of str
        The channel names and units.
    runs : ndarray of int, optional
        The run of each row of ``values`` (default: row i is run i).

    Raises
    ------
    ParameterError
        Naming the channel, the run (of a batch of several), the value farthest out in rad
        and degrees, and that value read as degrees in radians.
    """
    for j, (label, unit) in enumerate(zip(labels, units)):
        if unit == "rad" and label.startswith("rudder") and j < values.shape[-1]:
            worst = float(np.abs(values[..., j]).max())
            if worst > MAX_RUDDER_ANGLE:  # (nan is not: callers name non-finite values)
                raise _rudder_error(name, label, values[..., j], runs)


def _rudder_error(name: str, label: str, column: np.ndarray,
                  runs: np.ndarray | None = None) -> ParameterError:
    """The error of a rudder channel beyond ±:data:`MAX_RUDDER_ANGLE`
    (:func:`check_rudder_angles`): ``column`` the channel (rows = runs, then samples), its
    value farthest out named with its sign and, in a batch of several, its run."""
    column = np.asarray(column)
    k = int(np.nanargmax(np.abs(column)))
    value = float(column.flat[k])
    run = None
    if column.ndim >= 1 and column.shape[0] > 1:
        run = int(np.unravel_index(k, column.shape)[0])
        run = int(runs[run]) if runs is not None else run
    where = f" of run {run}" if run is not None else ""
    return ParameterError(
        f": channel '{label}'{where} reaches {value:.6g} rad ({math.degrees(value):.6g} deg);"
        f" a rudder turns at most ±90 deg (±{MAX_RUDDER_ANGLE:.6g} rad). Angles are "
        f"radians here: {value:.6g} deg is {math.radians(value):.6g} rad "
        "(math.radians; degrees in a scenario as <name>_deg)",
        field=name, unit="rad", value=value, run=run)


def _runs(*sizes: tuple[str, int]) -> int:
    n = sizes[0][1]  # (the largest; a loop, not max() of a generator: a step a size)
    for _, s in sizes:
        if s > n:
            n = s
    for name, s in sizes:
        if s not in (1, n):
            others = ", ".join(f"{k}={v}" for k, v in sizes)
            raise ParameterError(f": batch sizes do not broadcast: `{name}` has {s} runs "
                                 f"({others})", field=name)
    return n

