"""The signals a report plots, found by name in a flat result Dataset, and the ways a large
batch is cut down to what a page can hold.

Signals are found by their names (every seahelm result names its channels and gives their
units): the track is ``north``/``east`` (``x``/``y`` for a model that calls them so), then
heading, rudder angle, yaw rate and speed (``speed``, else the magnitude of surge and sway
speed). Angles are shown in degrees.

A batch is summarised, not dumped: at most :data:`MAX_RUNS_PLOTTED` runs are drawn (spread
evenly over the batch, diverged runs first), each time series decimated to at most
:data:`MAX_POINTS` samples, and the whole batch is shown as a 5-95 % band.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np

from ..units import to_display

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["MAX_POINTS", "MAX_RUNS_PLOTTED", "Signal", "find_signal", "TIME_SERIES",
           "coordinate_text", "decimation", "decimated_index", "plotted_runs", "run_labels",
           "ship_length",
           "ship_breadth", "ship_outlines", "outline_interval"]

#: Runs whose time series and track are drawn (the rest are in the band and the tables).
MAX_RUNS_PLOTTED = 20
#: Samples per plotted time series at most (decimated by a whole stride).
MAX_POINTS = 2000

#: Names a signal is looked for under, in this order.
_NAMES: dict[str, tuple[str, ...]] = {
    "north": ("north", "x"),
    "east": ("east", "y"),
    "heading": ("heading", "psi"),
    "rudder": ("rudder_angle", "rudder", "delta"),
    "yaw_rate": ("yaw_rate", "r"),
    "speed": ("speed",),
    "propeller": ("propeller_rps",),
    "engine_order": ("engine_order",),
}
#: Time series panels: (role, label).
TIME_SERIES = (("heading", "heading"), ("rudder", "rudder angle"), ("yaw_rate", "yaw rate"),
               ("speed", "speed"), ("propeller", "propeller"),
               ("engine_order", "engine order"))


@dataclasses.dataclass(frozen=True)
class Signal:
    """A signal over ``(run, time)`` in display units.

    Attributes
    ----------
    name : str
        The variable's name in the file (or how it was computed).
    units : str
        Display units (degrees for angles).
    values : numpy.ndarray
        ``(n_runs, n_time)``.
    """

    name: str
    units: str
    values: np.ndarray


def find_signal(runs: "xr.Dataset", role: str) -> Signal | None:
    """The signal of ``role`` (``north``, ``east``, ``heading``, ``rudder``, ``yaw_rate``,
    ``speed``, ``propeller``, ``engine_order``) in a flat result Dataset, in display units
    (:func:`seahelm.units.to_display`); None if the result has none.

    Parameters
    ----------
    runs : xarray.Dataset
        Flat view (dims ``run``, ``time``).
    role : str
        One of the keys above.

    Returns
    -------
    Signal or None
    """
    for name in _NAMES[role]:
        if name in runs.data_vars and runs[name].dims == ("run", "time"):
            var = runs[name]
            values, units = to_display(np.asarray(var.values, dtype=float),
                                       str(var.attrs.get("units", "")), name)
            return Signal(name, units, values)
    if role == "speed":
        for u, v in (("surge_speed", "sway_speed"), ("u", "v")):
            if u in runs.data_vars and v in runs.data_vars:
                values = np.hypot(np.asarray(runs[u].values, float),
                                  np.asarray(runs[v].values, float))
                return Signal(f"|({u}, {v})|", str(runs[u].attrs.get("units", "")), values)
    return None


def decimation(n_time: int, max_points: int = MAX_POINTS) -> int:
    """The stride that leaves at most ``max_points`` of ``n_time`` samples.

    Parameters
    ----------
    n_time : int
        Samples of the series.
    max_points : int, optional
        Samples kept at most (default :data:`MAX_POINTS`).

    Returns
    -------
    int
    """
    return max(1, math.ceil(n_time / max_points))


def decimated_index(n_time: int, max_points: int = MAX_POINTS) -> np.ndarray:
    """Indices of the kept samples: every ``decimation``-th and the last, at most
    ``max_points``.

    Parameters
    ----------
    n_time : int
        Samples of the series.
    max_points : int, optional
        Samples kept at most (default :data:`MAX_POINTS`).

    Returns
    -------
    numpy.ndarray
    """
    idx = np.arange(0, n_time, decimation(n_time, max(2, max_points - 1)))
    if idx[-1] != n_time - 1:
        idx = np.append(idx, n_time - 1)
    return idx


def plotted_runs(status: np.ndarray, max_runs: int = MAX_RUNS_PLOTTED) -> np.ndarray:
    """The runs drawn: all if there are at most ``max_runs``; else up to a quarter of them
    diverged runs (the first ones) and the rest spread evenly over the batch.

    Parameters
    ----------
    status : numpy.ndarray
        Status code per run (0 = ok).
    max_runs : int, optional
        Runs drawn at most (default :data:`MAX_RUNS_PLOTTED`).

    Returns
    -------
    numpy.ndarray
        Sorted run indices.
    """
    status = np.asarray(status).reshape(-1)
    n = status.size
    if n <= max_runs:
        return np.arange(n)
    diverged = np.flatnonzero(status != 0)[: max_runs // 4]
    rest = max_runs - diverged.size
    spread = np.unique(np.linspace(0, n - 1, rest).round().astype(int))
    chosen = np.unique(np.concatenate([diverged, spread]))
    extra = np.setdiff1d(np.arange(n), chosen)[: max_runs - chosen.size]
    return np.sort(np.concatenate([chosen, extra]))


def coordinate_text(name: str, value: object, units: str) -> str:
    """A batch coordinate as text: ``kp 4``, ``rudder 35°`` (radians shown in degrees),
    ``starboard``/``port`` for a side.

    Parameters
    ----------
    name : str
        The coordinate's name.
    value : object
        Its value.
    units : str
        Its units.

    Returns
    -------
    str
    """
    if isinstance(value, (float, np.floating)):
        shown, unit = to_display(float(value), units, name)
        if unit == "deg":
            return f"{name} {shown:.4g}°"
        return f"{name} {shown:.4g}" + (f" {unit}" if unit else "")
    if name == "side" and value in (1, -1):
        return "starboard" if value == 1 else "port"
    return f"{name} {value}"


def run_labels(runs: "xr.Dataset") -> list[str]:
    """A short label per run: ``run i`` (``i`` the run's index in its batch, the ``run``
    coordinate: a sweep store's global index) and its batch coordinates (angles in degrees).

    Parameters
    ----------
    runs : xarray.Dataset
        Flat view (dims ``run``, ``time``).

    Returns
    -------
    list of str
    """
    n = runs.sizes["run"]
    coords = [(str(name), c) for name, c in runs.coords.items()
              if c.dims == ("run",) and name != "run"]
    index = (np.asarray(runs["run"].values).reshape(-1) if "run" in runs.coords
             else np.arange(n))
    labels = []
    for i in range(n):
        parts = [coordinate_text(name, c.values[i].item(), str(c.attrs.get("units", "")))
                 for name, c in coords]
        labels.append(f"run {index[i]}" + (f" ({', '.join(parts)})" if parts else ""))
    return labels


def ship_length(runs: "xr.Dataset", metrics: "xr.Dataset | None" = None) -> float | None:
    """The ship length [m] of a result: the vessel's ``length`` parameter, else the metrics'
    ``length``; None if neither has one.

    Parameters
    ----------
    runs : xarray.Dataset
        Flat view of the runs.
    metrics : xarray.Dataset, optional
        A manoeuvre's metrics.

    Returns
    -------
    float or None
    """
    for ds, name in ((runs, "vessel.length"), (metrics, "length")):
        if ds is not None and name in ds:
            values = np.asarray(ds[name].values, dtype=float).reshape(-1)
            values = values[np.isfinite(values) & (values > 0)]
            if values.size:
                return float(values[0])
    return None


def ship_breadth(runs: "xr.Dataset") -> float | None:
    """The ship breadth [m] (the vessel's ``breadth`` parameter), None if not in the file.

    Parameters
    ----------
    runs : xarray.Dataset
        Flat view of the runs.

    Returns
    -------
    float or None
    """
    if "vessel.breadth" in runs:
        values = np.asarray(runs["vessel.breadth"].values, dtype=float).reshape(-1)
        if values.size and np.isfinite(values[0]) and values[0] > 0:
            return float(values[0])
    return None


def outline_interval(duration: float, count: int = 12) -> float:
    """Seconds between drawn outlines: about ``count`` over ``duration``, rounded up to
    1-2-5.

    Parameters
    ----------
    duration : float
        Length of the track in time [s].
    count : int, optional
        Outlines wanted, about.

    Returns
    -------
    float
    """
    if not (math.isfinite(duration) and duration > 0):
        return 1.0
    raw = duration / count
    exp = math.floor(math.log10(raw))
    for step in (1.0, 2.0, 5.0, 10.0):
        if step * 10**exp >= raw:
            return step * 10**exp
    return 10.0 ** (exp + 1)  # pragma: no cover - the loop always returns


#: A plain hull in units of the length (forward, starboard) and breadth: bow point, shoulders,
#: square stern.
_HULL = np.array([[0.5, 0.0], [0.3, 0.5], [-0.5, 0.5], [-0.5, -0.5], [0.3, -0.5], [0.5, 0.0]])


def ship_outlines(time: np.ndarray, north: np.ndarray, east: np.ndarray, heading_deg: np.ndarray,
                  length: float, breadth: float, interval: float
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Hull outlines along one track, every ``interval`` seconds (heading clockwise from
    north): (east, north) coordinates of the polygons separated by NaN (a break in a line).

    Parameters
    ----------
    time, north, east, heading_deg : numpy.ndarray
        One run's samples [s], [m], [m], [deg].
    length, breadth : float
        Hull size [m].
    interval : float
        Seconds between outlines.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        East and north coordinates [m].
    """
    finite = np.isfinite(north) & np.isfinite(east) & np.isfinite(heading_deg)
    marks = np.arange(time[0], time[-1] + 1e-9 * max(1.0, abs(time[-1])), interval)
    idx = np.unique(np.searchsorted(time, marks).clip(0, time.size - 1))
    idx = idx[finite[idx]]
    fwd = _HULL[:, 0] * length
    stb = _HULL[:, 1] * breadth
    xs, ys = [], []
    for i in idx:
        psi = math.radians(float(heading_deg[i]))
        c, s = math.cos(psi), math.sin(psi)
        # body (forward, starboard) -> (north, east) with the heading clockwise from north
        n = north[i] + fwd * c - stb * s
        e = east[i] + fwd * s + stb * c
        xs.append(np.append(e, np.nan))
        ys.append(np.append(n, np.nan))
    if not xs:
        return np.array([]), np.array([])
    return np.concatenate(xs), np.concatenate(ys)
