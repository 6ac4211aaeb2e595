"""Time signals for references and disturbances, sampled on the simulation grid.

A signal is a small frozen object with ``__call__(t) -> values``; :func:`make_signal` builds one
from a number or a table (as written in scenario files) through the registry :data:`SIGNALS`::

    20.0                                                  constant
    {kind = "step", time = 10.0, before = 0.0, after = 1.0}
    {kind = "steps", times = [0, 300, 600], values = [5, 10, 15]}   piecewise constant
    {kind = "sine", amplitude = 0.0072, period = 250.0, offset = 0.0, phase = 0.0}
    {kind = "ramp", start_time = 0.0, end_time = 60.0, start = 0.0, end = 0.8}

``scale`` multiplies every value (degrees → radians at the edges).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._validate import as_float_array, check_finite, check_positive
from ..errors import ParameterError

__all__ = ["Constant", "Step", "Steps", "Sine", "Ramp", "SIGNALS", "make_signal"]


@dataclasses.dataclass(frozen=True)
class Constant:
    """A constant value."""

    value: float

    def __call__(self, t: Any) -> np.ndarray:
        return np.full(np.shape(t), float(self.value))


@dataclasses.dataclass(frozen=True)
class Step:
    """``before`` until ``time`` [s], ``after`` from then on."""

    time: float
    after: float
    before: float = 0.0

    def __call__(self, t: Any) -> np.ndarray:
        return np.where(np.asarray(t) < self.time, self.before, self.after).astype(float)


@dataclasses.dataclass(frozen=True)
class Steps:
    """Piecewise constant: ``values[i]`` from ``times[i]`` [s] on (``values[0]`` before)."""

    times: tuple[float, ...]
    values: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.times) != len(self.values) or not self.times:
            raise ParameterError(
                f"`times` and `values` must be non-empty and of equal length, got "
                f"{len(self.times)} and {len(self.values)}"
            )
        if np.any(np.diff(self.times) <= 0):
            raise ParameterError(f"`times` must increase [s], got {list(self.times)}")

    def __call__(self, t: Any) -> np.ndarray:
        idx = np.searchsorted(np.asarray(self.times), np.asarray(t), side="right") - 1
        return np.asarray(self.values, dtype=float)[np.clip(idx, 0, None)]


@dataclasses.dataclass(frozen=True)
class Sine:
    """``offset + amplitude · sin(2π t / period + phase)``."""

    amplitude: float
    period: float
    offset: float = 0.0
    phase: float = 0.0

    def __post_init__(self) -> None:
        check_positive("period", self.period, "s")

    def __call__(self, t: Any) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        return self.offset + self.amplitude * np.sin(2.0 * math.pi * t / self.period + self.phase)


@dataclasses.dataclass(frozen=True)
class Ramp:
    """``start`` until ``start_time``, linear to ``end`` at ``end_time``, then ``end``."""

    start_time: float
    end_time: float
    start: float
    end: float

    def __post_init__(self) -> None:
        if not self.end_time > self.start_time:
            raise ParameterError(
                f"`end_time` must be > `start_time` [s], got {self.end_time} <= {self.start_time}"
            )

    def __call__(self, t: Any) -> np.ndarray:
        return np.interp(np.asarray(t, dtype=float), [self.start_time, self.end_time],
                         [self.start, self.end])


SIGNALS: dict[str, type] = {"constant": Constant, "step": Step, "steps": Steps, "sine": Sine,
                            "ramp": Ramp}
"""Registry of signal kinds by name."""

_SCALED = {"value", "before", "after", "values", "amplitude", "offset", "start", "end"}


def make_signal(spec: Any, *, scale: float = 1.0) -> Any:
    """A signal from a number, a mapping ``{kind = ..., ...}`` or a signal object.

    ``scale`` multiplies the value-like fields (not times, periods or phases).
    """
    if isinstance(spec, (int, float)) and not isinstance(spec, bool):
        check_finite("value", spec)
        return Constant(float(spec) * scale)
    if isinstance(spec, tuple(SIGNALS.values())):
        return spec
    if not isinstance(spec, Mapping):
        raise ParameterError(f"a signal must be a number or a table with `kind`, got {spec!r}")
    spec = dict(spec)
    kind = spec.pop("kind", None)
    if kind not in SIGNALS:
        raise ParameterError(f"unknown signal kind {kind!r}; valid: {', '.join(SIGNALS)}")
    cls = SIGNALS[kind]
    names = {f.name for f in dataclasses.fields(cls)}
    unknown = set(spec) - names
    if unknown:
        raise ParameterError(
            f"signal '{kind}' has no field(s) {', '.join(sorted(unknown))}; valid: "
            f"{', '.join(sorted(names))}"
        )
    kwargs: dict[str, Any] = {}
    for key, value in spec.items():
        arr = as_float_array(key, value)
        if key in _SCALED:
            arr = arr * scale
        kwargs[key] = tuple(arr.tolist()) if arr.ndim else float(arr)
    try:
        return cls(**kwargs)
    except TypeError as exc:
        raise ParameterError(f"signal '{kind}': {exc}") from None
