"""Encounters: tracks with ship domains and time marks, CPA and range over time, and a rose of
outcomes by the target's relative bearing at the start
(:class:`~seahelm.encounters.result.EncounterResult`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["plot_encounter_tracks", "plot_cpa", "plot_outcome_rose", "initial_bearing"]


def _plt() -> Any:
    from .._optional import optional_import
    return optional_import("matplotlib.pyplot", extra="plot", purpose="encounter plots")


def initial_bearing(result: Any) -> np.ndarray:
    """The first target's relative bearing from the own bow at the start [rad] (encounters,).

    Parameters
    ----------
    result : EncounterResult
    """
    from ..encounters.geometry import relative_bearing

    tr = result.tracks
    own = np.stack([tr["north"][:, 0, 0], tr["east"][:, 0, 0]], -1)
    tgt = np.stack([tr["north"][:, 1, 0], tr["east"][:, 1, 0]], -1)
    return relative_bearing(own, tr["heading"][:, 0, 0], tgt)


def plot_encounter_tracks(result: Any, encounter: int = 0, *, marks: float = 120.0,
                          domain: bool = True, ax: Any = None) -> Any:
    """Tracks of one encounter's vessels, with their positions and the own ship's domain
    (Fujii & Tanaka 1971 ellipse) every ``marks`` seconds, labelled with the time.

    Parameters
    ----------
    result : EncounterResult
    encounter : int
        Which encounter.
    marks : float
        Time between marks [s].
    domain : bool
        Draw the own ship's domain at the marks (and the closest approach).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    plt = _plt()
    if ax is None:
        _, ax = plt.subplots(figsize=(8.0, 8.0))
    tr, t = result.tracks, result.time
    nv = tr["north"].shape[1]
    step = max(1, int(round(marks / max(t[1] - t[0], 1e-9)))) if t.size > 1 else 1
    along, across = result.domain_axes
    for v in range(nv):
        n, e = tr["north"][encounter, v], tr["east"][encounter, v]
        ax.plot(e, n, color=f"C{v}", lw=1.5, label=result.names[v])
        ax.plot(e[::step], n[::step], "o", color=f"C{v}", ms=3)
        ax.plot(e[:1], n[:1], "^", color=f"C{v}", ms=8)
        for k in range(0, t.size, step):
            ax.annotate(f"{t[k] / 60:.0f}", (e[k], n[k]), fontsize=7, color=f"C{v}",
                        xytext=(3, 3), textcoords="offset points")
    if domain:
        L = result.lengths[0]
        s = np.linspace(0, 2 * math.pi, 73)
        k_min = int(np.nanargmin(result.pair["range"][encounter, 0])) if nv > 1 else 0
        for k in sorted(set(range(0, t.size, step)) | {k_min}):
            psi = tr["heading"][encounter, 0, k]
            x, y = along * L * np.cos(s), across * L * np.sin(s)
            dn = x * math.cos(psi) - y * math.sin(psi)
            de = x * math.sin(psi) + y * math.cos(psi)
            ax.plot(tr["east"][encounter, 0, k] + de, tr["north"][encounter, 0, k] + dn,
                    color="C0", lw=1.2 if k == k_min else 0.5, alpha=0.9 if k == k_min else 0.4)
    title = f"encounter {encounter}"
    if nv > 1:
        title += (f": least range {result.min_range[encounter, 0]:.0f} m at "
                  f"{result.t_min_range[encounter, 0] / 60:.1f} min"
                  f"{' (COLLISION)' if result.collision[encounter, 0] else ''}"
                  f"{' (near miss: inside the domain)' if result.near_miss[encounter, 0] else ''}")
    ax.set(xlabel="east [m]", ylabel="north [m]", title=title)
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize="small", loc="best", title="marks: minutes")
    return ax


def plot_cpa(result: Any, encounters: Any = None, *, ax: Any = None) -> Any:
    """Range and DCPA to the first target over time, and the least range.

    Parameters
    ----------
    result : EncounterResult
    encounters : sequence of int, optional
        Which encounters (default the first five).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    plt = _plt()
    if ax is None:
        _, ax = plt.subplots(figsize=(9.0, 5.0))
    if encounters is None:
        encounters = range(min(5, result.n_encounters))
    t = result.time / 60.0
    for c, e in enumerate(encounters):
        ax.plot(t, result.pair["range"][e, 0], color=f"C{c}", lw=1.4, label=f"{e}: range")
        dcpa = np.where(result.pair["tcpa"][e, 0] > 0, result.pair["dcpa"][e, 0], np.nan)
        ax.plot(t, dcpa, "--", color=f"C{c}", lw=1.0, label=f"{e}: DCPA (ahead)")
    touch = 0.5 * (result.lengths[0] + result.lengths[1])
    ax.axhline(touch, color="k", lw=0.8, ls=":", label="collision (half lengths)")
    ax.set(xlabel="time [min]", ylabel="distance [m]", title="range and CPA over time",
           yscale="log")
    ax.legend(fontsize="small", ncol=2)
    return ax


def plot_outcome_rose(result: Any, *, sectors: int = 16, ax: Any = None) -> Any:
    """Outcomes by the target's relative bearing at the start: stacked bars of collisions,
    domain intrusions and clear passings per sector (north up: ahead).

    Parameters
    ----------
    result : EncounterResult
    sectors : int
        Bearing sectors (default 16, 22.5° each).
    ax : matplotlib polar Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    plt = _plt()
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 7.0), subplot_kw={"projection": "polar"})
    beta = initial_bearing(result)
    width = 2 * math.pi / sectors
    k = np.floor(((beta + width / 2) % (2 * math.pi)) / width).astype(int) % sectors
    centre = np.arange(sectors) * width
    coll = np.bincount(k[result.collision[:, 0]], minlength=sectors)
    near = np.bincount(k[result.near_miss[:, 0]], minlength=sectors)
    clear = np.bincount(k[~(result.collision[:, 0] | result.near_miss[:, 0])],
                        minlength=sectors)
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.bar(centre, clear, width=width * 0.9, color="C2", label="clear")
    ax.bar(centre, near, width=width * 0.9, bottom=clear, color="C1",
           label="near miss (domain, no collision)")
    ax.bar(centre, coll, width=width * 0.9, bottom=clear + near, color="C3", label="collision")
    ax.set_title("outcomes by the target's relative bearing at the start")
    ax.legend(fontsize="small", loc="lower left", bbox_to_anchor=(-0.1, -0.1))
    return ax
