"""Plots of catamaran runs as in Shushlyapin et al. (2017): yaw rate with its reference,
thruster angle, trajectory (matplotlib is imported inside the functions).

Every function takes a :class:`~seahelm.results.SimResult` of the ``catamaran`` model, an
optional ``ax=`` and the runs to draw, and returns the axes it drew on.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["plot_yaw_rate", "plot_thruster_angle", "plot_trajectory", "plot_overview"]


def _axes(ax: Any) -> Any:
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


def _runs(result: Any, runs: Sequence[int] | None) -> list[int]:
    return list(range(result.n_runs)) if runs is None else list(runs)


def plot_yaw_rate(result: Any, *, ax: Any = None, runs: Sequence[int] | None = None) -> Any:
    """Yaw rate ω [rad/s] (solid) and, if the controller has one, its reference (dashed).

    Parameters
    ----------
    result : SimResult
        Result of a catamaran run.
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).
    runs : sequence of int, optional
        Runs to draw (default: all).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for i in _runs(result, runs):
        (line,) = ax.plot(result.time, result["yaw_rate"][i], label=f"ω, run {i}")
        if "yaw_rate" in result.reference_labels:
            ax.plot(result.time, result["reference_yaw_rate"][i], "--", color=line.get_color(),
                    label=f"ω*, run {i}")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("yaw rate [rad/s]")
    ax.legend(fontsize="small")
    return ax


def plot_thruster_angle(result: Any, *, ax: Any = None, runs: Sequence[int] | None = None
                        ) -> Any:
    """Thruster angle δ in degrees (degrees only at this edge).

    Parameters
    ----------
    result : SimResult
        Result of a catamaran run.
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).
    runs : sequence of int, optional
        Runs to draw (default: all).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for i in _runs(result, runs):
        ax.plot(result.time, np.degrees(result["thruster_angle"][i]), label=f"run {i}")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("thruster angle δ [deg]")
    return ax


def plot_trajectory(result: Any, *, ax: Any = None, runs: Sequence[int] | None = None) -> Any:
    """Track: east [m] horizontally, north [m] vertically, equal axes.

    Parameters
    ----------
    result : SimResult
        Result of a catamaran run.
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).
    runs : sequence of int, optional
        Runs to draw (default: all).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for i in _runs(result, runs):
        ax.plot(result["east"][i], result["north"][i], label=f"run {i}")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_aspect("equal", adjustable="datalim")
    return ax


def plot_overview(result: Any, *, fig: Any = None, runs: Sequence[int] | None = None) -> Any:
    """The three panels of the paper's figures (yaw rate, thruster angle, trajectory).

    Parameters
    ----------
    result : SimResult
        Result of a catamaran run.
    fig : matplotlib Figure, optional
        Figure to draw into (default: a new one).
    runs : sequence of int, optional
        Runs to draw (default: all).

    Returns
    -------
    matplotlib Figure
    """
    if fig is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(11, 7))
    gs = fig.add_gridspec(2, 2)
    plot_yaw_rate(result, ax=fig.add_subplot(gs[0, 0]), runs=runs)
    plot_thruster_angle(result, ax=fig.add_subplot(gs[1, 0]), runs=runs)
    plot_trajectory(result, ax=fig.add_subplot(gs[:, 1]), runs=runs)
    title = result.metadata.get("title")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig
