"""Time signals for references and disturbances, sampled on the simulation grid.

A signal is a small frozen object with ``__call__(t) -> values``; :func:`make_signal` builds one
from a number or a table (as written in scenario files) through the registry :data:`SIGNALS`::

    20.0                                                  constant
    {kind = "step", time = 10.0, before = 0.0, after = 1.0}
    {kind = "steps", times = [0, 300, 600], values = [5, 10, 15]}   piecewise constant
    {kind = "samples", times = [0, 0.1, 0.2], values = [0, 1, 3]}   piecewise linear
    {kind = "sine", amplitude = 0.0072, period = 250.0, offset = 0.0, phase = 0.0}
    {kind = "ramp", start_time = 0.0, end_time = 60.0, start = 0.0, end = 0.8}
    {kind = "sea", h3 = 3.0, gain = 0.01, quantity = "ordinate", seed = 7}   irregular sea
    {kind = "gust", mean_speed = 15.0, spectrum = "norsok", seed = 3}       wind gust [m/s]

``scale`` multiplies every value (degrees → radians at the edges).

The ``sea`` signal is random: a stationary Gaussian sea from the Rakhmanin–Firsov spectrum for
the wave height h3% (Sushchenko & Lutsko, 2010), sampled exactly on the grid
(:mod:`seahelm.environment.shaping`), times ``gain``. Calling it with ``seed=`` draws the
realisation of that seed; scenario batches give every run its own seed (spawned from the
signal's ``seed``), so Monte-Carlo runs see independent seas.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._validate import as_float_array, check_finite, check_positive, lookup_name, uniform_time_step
from ..errors import ParameterError

__all__ = ["Constant", "Step", "Steps", "Samples", "Sine", "Ramp", "Sea", "Gust", "SIGNALS",
           "make_signal"]


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


def _check_times_values(times: tuple[float, ...], values: tuple[float, ...], *,
                        finite: bool) -> None:
    """A time series' ``times`` and ``values``: non-empty, of one length, times increasing
    (and every number finite, for an interpolated series)."""
    if len(times) != len(values) or not times:
        raise ParameterError(
            f"`times` and `values` must be non-empty and of equal length, got "
            f"{len(times)} and {len(values)}"
        )
    if finite and not (np.all(np.isfinite(times)) and np.all(np.isfinite(values))):
        raise ParameterError("`times` and `values` must be finite numbers")
    step = np.diff(times)
    if np.any(step <= 0):
        i = int(np.flatnonzero(step <= 0)[0]) + 1
        raise ParameterError(f"`times` must increase [s], got {times[i - 1]!r} then "
                             f"{times[i]!r} at index {i}")


@dataclasses.dataclass(frozen=True)
class Steps:
    """Piecewise constant: ``values[i]`` from ``times[i]`` [s] on (``values[0]`` before)."""

    times: tuple[float, ...]
    values: tuple[float, ...]

    def __post_init__(self) -> None:
        _check_times_values(self.times, self.values, finite=False)

    def __call__(self, t: Any) -> np.ndarray:
        idx = np.searchsorted(np.asarray(self.times), np.asarray(t), side="right") - 1
        return np.asarray(self.values, dtype=float)[np.clip(idx, 0, None)]


@dataclasses.dataclass(frozen=True)
class Samples:
    """A sampled time series, linearly interpolated (first-order hold): ``values[i]`` at
    ``times[i]`` [s], straight lines between samples, the first and last value held before and
    after them. The measured inputs of a replayed record (:mod:`seahelm.analysis.replay`).
    """

    times: tuple[float, ...]
    values: tuple[float, ...]

    def __post_init__(self) -> None:
        _check_times_values(self.times, self.values, finite=True)

    def __call__(self, t: Any) -> np.ndarray:
        return np.interp(np.asarray(t, dtype=float), np.asarray(self.times, dtype=float),
                         np.asarray(self.values, dtype=float))


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


@dataclasses.dataclass(frozen=True)
class Sea:
    """``mean + gain · q(t)``, q a seeded irregular-sea quantity sampled exactly on the grid.

    ``quantity`` is one of ``ordinate`` [m], ``ordinate_rate`` [m/s], ``slope`` [rad] of the
    wave surface (see :data:`seahelm.environment.shaping.QUANTITIES`); ``spectrum`` a
    Rakhmanin–Firsov registry name. The grid must be uniform.
    """

    h3: float
    gain: float = 1.0
    mean: float = 0.0
    quantity: str = "ordinate"
    spectrum: str = "rakhmanin-firsov-2"
    seed: int = 0

    random = True

    def __post_init__(self) -> None:
        check_positive("h3", self.h3, "m")
        from ..environment.sea_state import check_table_height
        from ..environment.shaping import QUANTITIES

        check_table_height("h3", self.h3)

        lookup_name("sea quantity", dict.fromkeys(("ordinate", "ordinate_rate", "slope")),
                    self.quantity, error=ParameterError, suffix=f" (of {', '.join(QUANTITIES)})")

    def __call__(self, t: Any, *, seed: Any = None) -> np.ndarray:
        from ..environment.shaping import shaping_filter
        from ..environment.spectra import spectrum_from_wave_height

        t, dt = uniform_time_step(t, "a `sea` signal")
        spec = spectrum_from_wave_height(self.spectrum, self.h3)
        filt = shaping_filter(spec, outputs=(self.quantity,))
        draw = filt.sample(n_steps=t.size, dt=dt,
                           seed=self.seed if seed is None else seed)
        return self.mean + self.gain * draw.values[0, :, 0]

    def draw_runs(self, t: Any, seeds: list[Any]) -> np.ndarray:
        """Many runs' realisations in one vectorised draw: row i equals
        ``self(t, seed=seeds[i])``.

        Parameters
        ----------
        t : array_like
            The uniform time grid [s].
        seeds : list
            One seed (int or SeedSequence) per run.

        Returns
        -------
        numpy.ndarray, shape (len(seeds), len(t))
        """
        from ..environment.discretisation import single_run_stream
        from ..environment.shaping import shaping_filter
        from ..environment.spectra import spectrum_from_wave_height

        t, dt = uniform_time_step(t, "a `sea` signal")
        filt = shaping_filter(spectrum_from_wave_height(self.spectrum, self.h3),
                              outputs=(self.quantity,))
        draw = filt.sample(n_steps=t.size, dt=dt,
                           seed=[single_run_stream(s) for s in seeds], runs=len(seeds))
        return self.mean + self.gain * draw.values[:, :, 0]


@dataclasses.dataclass(frozen=True)
class Gust:
    """``gain · u(t)``, u a seeded wind gust [m/s] of a gust spectrum for the one-hour mean
    wind speed ``mean_speed`` [m/s] at ``height`` [m] (:mod:`seahelm.environment.wind_gust`;
    ``spectrum`` a name in its registry). In ``[environment.wind] gust``, ``mean_speed``
    defaults to the section's ``speed``. The grid must be uniform.
    """

    mean_speed: float
    gain: float = 1.0
    height: float = 10.0
    spectrum: str = "norsok"
    seed: int = 0

    random = True

    def __post_init__(self) -> None:
        check_positive("mean_speed", self.mean_speed, "m/s")
        check_positive("height", self.height, "m")
        from ..environment.wind_gust import get_gust_spectrum

        get_gust_spectrum(self.spectrum)

    def __call__(self, t: Any, *, seed: Any = None) -> np.ndarray:
        from ..environment.wind_gust import gust_realisation

        return self.gain * gust_realisation(t, self.mean_speed,
                                            self.seed if seed is None else seed,
                                            spectrum=self.spectrum, height=self.height)


SIGNALS: dict[str, type] = {"constant": Constant, "step": Step, "steps": Steps,
                            "samples": Samples, "sine": Sine, "ramp": Ramp, "sea": Sea,
                            "gust": Gust}
"""Registry of signal kinds by name."""

_SCALED = {"value", "before", "after", "values", "amplitude", "offset", "start", "end",
           "gain", "mean"}
_TEXT = {"quantity", "spectrum"}


def make_signal(spec: Any, *, scale: float = 1.0) -> Any:
    """A signal from a number, a mapping ``{kind = ..., ...}`` or a signal object.

    ``scale`` multiplies the value-like fields (not times, periods or phases).

    Parameters
    ----------
    spec : float, mapping or signal
        A constant, a table with ``kind`` (a name in :data:`SIGNALS`) and the signal's fields,
        or a signal object (returned unchanged).
    scale : float, optional
        Factor applied to the value-like fields, e.g. π/180 for degrees (default 1).

    Returns
    -------
    signal
        A callable signal ``sig(t_grid)``.
    """
    if isinstance(spec, (int, float)) and not isinstance(spec, bool):
        check_finite("value", spec)
        return Constant(float(spec) * scale)
    if isinstance(spec, tuple(SIGNALS.values())) or (
            callable(spec) and not isinstance(spec, type)):
        return spec  # a signal object (a registered kind, or any callable sig(t_grid))
    if not isinstance(spec, Mapping):
        raise ParameterError(f"a signal must be a number or a table with `kind`, got {spec!r}")
    spec = dict(spec)
    kind = spec.pop("kind", None)
    cls = lookup_name("signal kind", SIGNALS, kind, error=ParameterError)
    names = {f.name for f in dataclasses.fields(cls)}
    unknown = set(spec) - names
    if unknown:
        raise ParameterError(
            f"signal '{kind}' has no field(s) {', '.join(sorted(unknown))}; valid: "
            f"{', '.join(sorted(names))}"
        )
    kwargs: dict[str, Any] = {}
    for key, value in spec.items():
        if key in _TEXT:
            if not isinstance(value, str):
                raise ParameterError(f"signal '{kind}': `{key}` must be a name, got {value!r}")
            kwargs[key] = value
            continue
        if key == "seed":
            if isinstance(value, bool) or not isinstance(value, int) or value < 0:
                raise ParameterError(f"signal '{kind}': `seed` must be an integer >= 0, "
                                     f"got {value!r}")
            kwargs[key] = value
            continue
        items = value if isinstance(value, (list, tuple)) else [value]
        if any(isinstance(v, (bool, str)) for v in items):  # true is not 1.0, "3" not 3
            raise ParameterError(f"signal '{kind}': `{key}` must be a number, got {value!r}")
        arr = as_float_array(key, value)
        if key in _SCALED:
            arr = arr * scale
        kwargs[key] = tuple(arr.tolist()) if arr.ndim else float(arr)
    try:
        return cls(**kwargs)
    except TypeError as exc:
        raise ParameterError(f"signal '{kind}': {exc}") from None
