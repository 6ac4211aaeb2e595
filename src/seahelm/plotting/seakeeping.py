"""The polar seakeeping diagram: a response statistic over wave heading × ship speed.

The ship sits at the centre with its bow up; the angle is the mean wave heading ε relative to
the ship (:mod:`seahelm.environment.rao`: 0 following seas at the bottom, 180° head seas at the
top, 90° — waves travelling to starboard, i.e. coming from port — on the left); the radius is
the ship's speed. Filled contours of the statistic, a colour bar with its unit, and a limit
(a seakeeping criterion, e.g. RMS roll 6°) drawn as a thick contour.

matplotlib is imported inside the function; it takes ``ax=`` (polar) and returns it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array
from ..errors import ParameterError

__all__ = ["plot_polar_diagram", "plot_sweep_polar", "contour_levels"]


def contour_levels(low: float, high: float, levels: int = 12) -> np.ndarray:
    """Level boundaries at round values covering [low, high] (the colour bar's ticks).

    matplotlib's :class:`~matplotlib.ticker.MaxNLocator` picks at most ``levels`` intervals of
    1, 2, 2.5 or 5 times a power of ten (``linspace(low, high)`` gave ticks such as 0.640,
    1.281, ...). A constant field (``low == high``) gets the unit interval above it.

    Parameters
    ----------
    low, high : float
        The smallest and largest value drawn, in the unit shown.
    levels : int, optional
        Most intervals (default 12).

    Returns
    -------
    numpy.ndarray
        Increasing boundaries, the first <= ``low``, the last >= ``high``.
    """
    from matplotlib.ticker import MaxNLocator

    if not high > low:
        high = low + 1.0
    return MaxNLocator(nbins=levels, steps=[1, 2, 2.5, 5, 10]).tick_values(low, high)


def _closed(heading: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Append the first heading + 2π when the headings go round the circle but for one step."""
    if heading.size < 3:
        return heading, values
    step = float(np.max(np.diff(heading)))
    gap = heading[0] + 2.0 * math.pi - heading[-1]
    if 1e-9 < gap <= 1.01 * step:
        return np.append(heading, heading[0] + 2.0 * math.pi), np.concatenate(
            [values, values[:, :1]], axis=1)
    return heading, values


def plot_polar_diagram(speed: ArrayLike, heading: ArrayLike, values: ArrayLike, *,
                       label: str, unit: str, limit: float | None = None,
                       title: str | None = None, ax: Any = None, levels: int = 12,
                       value_range: tuple[float, float] | None = None) -> Any:
    """Filled contours of ``values`` over (speed, heading) on polar axes.

    With one speed the statistic is drawn as a curve over the heading (radius = the value).

    Parameters
    ----------
    speed : array_like, shape (n_speed,)
        Ship speeds [m/s], increasing.
    heading : array_like, shape (n_heading,)
        Mean wave headings ε relative to the ship [rad], increasing (0 following, π head).
    values : array_like, shape (n_speed, n_heading)
        The statistic in the unit shown (e.g. RMS roll in degrees).
    label : str
        What the values are (``"RMS roll"``).
    unit : str
        Their unit (``"deg"``), shown on the colour bar.
    limit : float, optional
        A criterion: drawn as a thick red contour (with one speed: a dashed circle).
    title : str, optional
        The axes' title.
    ax : matplotlib.projections.polar.PolarAxes, optional
        Polar axes to draw on (default: a new figure's).
    levels : int, optional
        Most filled-contour levels (default 12; :func:`contour_levels`).
    value_range : (float, float), optional
        The values the colour levels span (default the values' own range; give the same
        range to diagrams drawn side by side).

    Returns
    -------
    matplotlib.projections.polar.PolarAxes

    Raises
    ------
    ParameterError
        If the shapes disagree, a grid is empty or the values are not finite.
    """
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    U = np.atleast_1d(as_float_array("speed", speed, "m/s"))
    eps = np.atleast_1d(as_float_array("heading", heading, "rad"))
    z = np.asarray(as_float_array("values", values, unit, finite=False))
    if U.size == 0 or eps.size == 0 or z.shape != (U.size, eps.size):
        raise ParameterError(f"must have the shape (speed, heading) = {(U.size, eps.size)}, "
                             f"got {z.shape}", field="values", unit=unit)
    if not np.all(np.isfinite(z)):
        raise ParameterError(f"must be finite [{unit}]", field="values", unit=unit)
    if ax is None:
        fig = plt.figure(figsize=(7.0, 6.2))
        ax = fig.add_subplot(projection="polar")
    if getattr(ax, "name", "") != "polar":
        raise ParameterError("must be polar axes (projection='polar')", field="ax")
    ax.set_theta_zero_location("S")  # following seas (0) at the bottom, head seas on top
    ax.set_theta_direction(-1)  # clockwise: 90 deg (waves from port) on the left
    eps, z = _closed(eps, z)
    handles = []
    if U.size == 1:
        ax.plot(eps, z[0], color="tab:blue", lw=2)
        handles.append(Line2D([], [], color="tab:blue", lw=2,
                              label=f"{label} [{unit}] at {U[0]:.3g} m/s"))
        if limit is not None:
            t = np.linspace(0.0, 2.0 * math.pi, 361)
            ax.plot(t, np.full_like(t, limit), "r--", lw=1.5)
            handles.append(Line2D([], [], color="red", ls="--", lw=1.5,
                                  label=f"limit {limit:g} {unit}"))
        ax.set_rlabel_position(135)
    else:
        T, R = np.meshgrid(eps, U)
        top = float(np.max(z))
        lo, hi = (float(np.min(z)), top) if value_range is None else value_range
        cs = ax.contourf(T, R, z, levels=contour_levels(min(lo, float(np.min(z))),
                                                        max(hi, top), levels),
                         cmap="viridis")
        ax.figure.colorbar(cs, ax=ax, pad=0.1, shrink=0.85, label=f"{label} [{unit}]")
        if limit is not None:
            reached = float(np.min(z)) <= limit <= top
            if reached:
                ax.contour(T, R, z, levels=[limit], colors="red", linewidths=2.5)
            handles.append(Line2D([], [], color="red", lw=2.5, label=(
                f"limit {limit:g} {unit}" + ("" if reached else " (not reached)"))))
        ax.set_ylim(0.0, float(U[-1]))
        ax.set_rlabel_position(135)
    if handles:
        ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(-0.15, -0.12), fontsize=8)
    ax.text(1.0, -0.1, "radius: ship speed [m/s]" if U.size > 1 else f"radius: {label} "
            f"[{unit}]", transform=ax.transAxes, ha="right", va="top", fontsize=8)
    ax.set_xticks(np.radians(np.arange(0, 360, 30)))
    ax.set_xticklabels([f"{d}°" for d in range(0, 360, 30)])
    ax.set_title(title or f"{label} [{unit}]; heading 0° following, 180° head, "
                 "90° waves from port", fontsize=9)
    return ax


def plot_sweep_polar(polar: Any, dof: str = "roll", *, limit: float | None = None,
                     levels: int = 12) -> Any:
    """A time-domain sweep's RMS of ``dof`` beside the frequency-domain RMS of the same cells.

    Two polar diagrams (:func:`plot_polar_diagram`) with one set of colour levels: left the
    time domain (:class:`~seahelm.sweep.seakeeping.SweepSeakeeping`, each row at its mean
    speed and each column at its mean heading), right its frequency-domain counterpart (when
    the sweep has it). Roll and pitch in degrees, heave in metres.

    Parameters
    ----------
    polar : SweepSeakeeping
        From :func:`seahelm.sweep.seakeeping.sweep_seakeeping`.
    dof : str, optional
        ``"heave"``, ``"pitch"``, ``"roll"`` (first-order; default) or ``"roll_total"``.
    limit : float, optional
        A criterion in the unit shown (deg or m), drawn as a red contour.
    levels : int, optional
        Most colour levels (default 12).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    factor, unit = (1.0, "m") if dof == "heave" else (180.0 / math.pi, "deg")
    td = polar.rms(dof) * factor
    fd = polar.frequency_domain_rms(dof) * factor
    panels = [("time domain (sweep)", td)]
    if np.all(np.isfinite(fd)):
        panels.append(("frequency domain, same cells", fd))
    both = np.concatenate([p[1].ravel() for p in panels])
    fig = plt.figure(figsize=(7.0 * len(panels), 6.2))
    name = "total roll" if dof == "roll_total" else dof
    for k, (title, values) in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), k + 1, projection="polar")
        plot_polar_diagram(polar.row_speed, polar.column_heading, values,
                           label=f"RMS {name}", unit=unit, limit=limit, ax=ax, levels=levels,
                           value_range=(float(both.min()), float(both.max())),
                           title=f"RMS {name} [{unit}]: {title}")
    return fig
