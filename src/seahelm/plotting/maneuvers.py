"""Figures of the standard manoeuvres (:mod:`seahelm.analysis.maneuvers`).

Each function takes a :class:`~seahelm.analysis.maneuvers.ManeuverResult` and an optional
``ax`` (or ``fig``), draws every run of the batch, and returns what it drew into:

:func:`plot_turning`
    tracks in the frame of the original course (east across, north along, starting at the
    rudder order) with the advance, transfer and tactical diameter marked;
:func:`plot_zigzag`
    heading deviation and rudder angle against time, one panel per run, the triggers dashed
    and the overshoots marked at the heading extremes;
:func:`plot_spiral`
    the r–δ curve: the direct spiral's steady yaw rates on the descending and ascending legs
    and the reverse spiral's equilibria, with the hysteresis loop shaded;
:func:`plot_pullout`
    yaw rate against time after the rudder is returned to zero, both sides;
:func:`plot_stopping`
    stopping tracks in the frame of the original course with the dead-in-the-water points
    (dotted after them, going astern), and the surge speed, propeller rps and engine order
    against time, up to 1.5 times the latest time to dead in the water.

Angles are drawn in degrees.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from typing import Any

import numpy as np

__all__ = ["plot_turning", "plot_zigzag", "plot_spiral", "plot_pullout", "plot_stopping"]

_SIDE = {1: "starboard", -1: "port"}


def _runs(result: Any) -> Iterator[tuple[str, Any, Any]]:
    """(label, runs Dataset, metrics Dataset) of each run, C order over the batch dims."""
    metrics = result.metrics
    dims = list(metrics["complete"].dims)
    for idx in itertools.product(*(range(metrics.sizes[d]) for d in dims)):
        where = dict(zip(dims, idx))
        m = metrics.isel(where)
        runs = result.runs.isel(where) if result.runs is not None else None
        parts = []
        if len(result.ships) > 1:
            parts.append(str(m["ship_name"].item()))
        if "approach_speed" in dims:
            parts.append(f"U0 {float(m['approach_speed']):.4g} m/s")
        if "pair" in m.coords:
            parts.append(f"{math.degrees(float(m['rudder'])):.3g}/"
                         f"{math.degrees(float(m['trigger'])):.3g}")
        elif "rudder" in m.coords and "rudder" in dims:
            parts.append(f"{math.degrees(float(m['rudder'])):.3g} deg")
        if "side" in m.coords:
            parts.append(_SIDE[int(m["side"])])
        if "order" in dims:
            parts.append(f"order {float(m['order']):.3g}")
        yield ", ".join(parts) or m["ship_name"].item(), runs, m


def _new_axes(ax: Any, **kwargs: Any) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=kwargs.pop("figsize", (8, 7)), layout="constrained")
    return fig.add_subplot()


def plot_turning(result: Any, *, ax: Any = None) -> Any:
    """Turning-circle tracks with advance, transfer and tactical diameter marked.

    Parameters
    ----------
    result : ManeuverResult
        A turning-circle result (:func:`~seahelm.analysis.maneuvers.turning_circle`).
    ax : matplotlib Axes, optional
        Axes to draw into (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _new_axes(ax)
    for k, (label, run, m) in enumerate(_runs(result)):
        color = f"C{k % 10}"
        t = run["time"].values
        north, east = run["north"].values, run["east"].values
        # the original course is north (heading 0) in every manoeuvre; keep the general case
        psi0 = float(run["heading"].values[0])
        c, s = math.cos(psi0), math.sin(psi0)
        along = (north - north[0]) * c + (east - east[0]) * s
        across = -(north - north[0]) * s + (east - east[0]) * c
        keep = np.abs(run["heading"].values - psi0) <= 2.0 * math.pi + 1e-9
        ax.plot(across[keep], along[keep], color=color, lw=1.5, label=label)
        side = np.sign(across[np.argmax(np.abs(across))]) or 1.0
        adv, tr, td = (float(m[v]) for v in ("advance", "transfer", "tactical_diameter"))
        t90, t180 = float(m["time_90"]), float(m["time_180"])
        if math.isfinite(t90):
            x90 = side * tr
            ax.plot([x90], [adv], "o", color=color, ms=6)
            ax.annotate("", xy=(x90, adv), xytext=(x90, 0.0),
                        arrowprops=dict(arrowstyle="<->", color=color, lw=0.9))
            ax.text(x90, 0.5 * adv, f" advance\n {adv:.4g} m", color=color, fontsize=8,
                    ha="left" if side > 0 else "right", va="center")
            ax.annotate("", xy=(x90, adv), xytext=(0.0, adv),
                        arrowprops=dict(arrowstyle="<->", color=color, lw=0.9, ls="--"))
            ax.text(0.5 * x90, adv, f"transfer {tr:.4g} m", color=color, fontsize=8,
                    ha="center", va="bottom")
        if math.isfinite(t180):
            y180 = float(np.interp(t180, t, along))
            x180 = side * td
            ax.plot([x180], [y180], "s", color=color, ms=6)
            ax.annotate("", xy=(x180, y180), xytext=(0.0, y180),
                        arrowprops=dict(arrowstyle="<->", color=color, lw=0.9))
            ax.text(0.5 * x180, y180, f"tactical diameter {td:.4g} m", color=color,
                    fontsize=8, ha="center", va="top")
    ax.plot([0.0], [0.0], "k^", ms=7, label="rudder order")
    ax.axvline(0.0, color="0.6", lw=0.8, ls=":")
    rudder = result.metrics["rudder"]
    what = (f"{math.degrees(float(rudder)):.3g} deg rudder" if rudder.ndim == 0
            else "rudder " + ", ".join(f"{math.degrees(v):.3g}" for v in rudder.values) + " deg")
    ax.set(xlabel="across the original course (to starboard) [m]",
           ylabel="along the original course [m]",
           title=f"Turning circle: {', '.join(s.name for s in result.ships)}, {what} "
                 "(midship point)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize="small")
    return ax


def plot_zigzag(result: Any, *, fig: Any = None) -> Any:
    """Heading deviation and rudder angle of each zig-zag run, overshoots marked.

    Parameters
    ----------
    result : ManeuverResult
        A zig-zag result (:func:`~seahelm.analysis.maneuvers.zigzag`).
    fig : matplotlib Figure, optional
        Figure to draw into (default: a new one).

    Returns
    -------
    matplotlib Figure
    """
    import matplotlib.pyplot as plt

    runs = list(_runs(result))
    ncols = 2 if len(runs) > 1 else 1
    nrows = math.ceil(len(runs) / ncols)
    if fig is None:
        fig = plt.figure(figsize=(6.0 * ncols, 3.6 * nrows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).ravel()
    for ax, (label, run, m) in zip(axes, runs):
        t = run["time"].values
        psi = np.degrees(run["heading"].values - run["heading"].values[0])
        delta = np.degrees(run["rudder_angle"].values)
        trig = math.degrees(float(m["trigger"])) if "trigger" in m.coords else math.nan
        ax.plot(t, psi, color="C0", lw=1.5, label="heading change ψ − ψ0")
        ax.plot(t, delta, color="C1", lw=1.2, label="rudder angle δ")
        for level in (trig, -trig):
            ax.axhline(level, color="0.5", lw=0.8, ls="--")
        ax.axhline(0.0, color="0.7", lw=0.6)
        for j in range(m.sizes["n"]):
            tj = float(m["overshoot_time"].isel(n=j))
            if not math.isfinite(tj):
                continue
            yj = math.degrees(float(m["extreme_heading"].isel(n=j)))
            oj = math.degrees(float(m["overshoot"].isel(n=j)))
            ax.plot([tj], [yj], "v" if yj > 0 else "^", color="C3", ms=7)
            ax.annotate(f"o{j + 1} = {oj:.3g}°", (tj, yj), textcoords="offset points",
                        xytext=(0, 8 if yj > 0 else -14), ha="center", fontsize=8, color="C3")
        for j in range(m.sizes["n"]):
            te = float(m["execute_time"].isel(n=j))
            if math.isfinite(te):
                ax.axvline(te, color="C2", lw=0.6, alpha=0.6)
        ax.set(xlabel="time [s]", ylabel="[deg]", title=label)
        ax.margins(y=0.2)
        ax.grid(True, alpha=0.3)
        if not math.isfinite(float(m["period"])) or not bool(m["complete"]):
            ax.text(0.02, 0.02, str(m["message"].item()), transform=ax.transAxes, fontsize=7,
                    color="C3")
    for ax in axes[len(runs):]:
        ax.set_visible(False)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2, fontsize="small")
    fig.suptitle(f"Zig-zag: {', '.join(s.name for s in result.ships)} "
                 "(executes: green lines; overshoots: red marks)")
    return fig


def plot_spiral(direct: Any = None, reverse: Any = None, *, ax: Any = None) -> Any:
    """The r–δ curve of a direct and/or a reverse spiral (first ship and speed of each).

    Parameters
    ----------
    direct : ManeuverResult, optional
        A direct spiral (:func:`~seahelm.analysis.maneuvers.direct_spiral`).
    reverse : ManeuverResult, optional
        A reverse spiral (:func:`~seahelm.analysis.maneuvers.reverse_spiral`).
    ax : matplotlib Axes, optional
        Axes to draw into (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    if direct is None and reverse is None:
        raise ValueError("plot_spiral needs a direct or a reverse spiral result")
    ax = _new_axes(ax, figsize=(8, 6))
    title = []
    zoom = None
    if reverse is not None:
        m = _first(reverse.metrics)
        d = np.degrees(m["rudder_angle"].values)
        r = np.degrees(m["yaw_rate"].values)
        ok = np.isfinite(d) & np.isfinite(r)
        ax.plot(d[ok], r[ok], "-", color="C0", lw=1.5, label="reverse spiral (equilibria)")
        width = float(m["loop_width"])
        if width > 0:
            lo, hi = (math.degrees(float(m[v])) for v in ("loop_rudder_low", "loop_rudder_high"))
            ax.axvspan(lo, hi, color="C0", alpha=0.15,
                       label=f"loop: {lo:.3g} to {hi:.3g} deg (width {math.degrees(width):.3g})")
            # zoom on the loop: the part of the curve within a few loop widths of it
            pad = max(3.0 * (hi - lo), 0.5)
            near = ok & (d >= lo - pad) & (d <= hi + pad)
            if np.count_nonzero(near) >= 2:
                inset = ax.inset_axes((0.62, 0.08, 0.35, 0.35))
                inset.plot(d[near], r[near], "-", color="C0", lw=1.2)
                inset.axvspan(lo, hi, color="C0", alpha=0.15)
                inset.axhline(0.0, color="0.6", lw=0.6)
                inset.set_xlim(lo - pad, hi + pad)
                inset.tick_params(labelsize=7)
                inset.set_title("loop (zoom)", fontsize=8)
                inset.grid(True, alpha=0.3)
                zoom = inset
        title.append(reverse.ships[0].name)
    if direct is not None:
        m = _first(direct.metrics)
        d = np.degrees(m["step_rudder"].values)
        r = np.degrees(m["yaw_rate"].values)
        leg = m["leg"].values
        settled = m["settled"].values.astype(bool)
        for sign, marker, text in ((-1, "v", "direct, starboard → port"),
                                   (1, "^", "direct, port → starboard")):
            sel = leg == sign
            color = "C1" if sign < 0 else "C2"
            ax.plot(d[sel & settled], r[sel & settled], marker, color=color, ms=7, label=text)
            if np.any(sel & ~settled):
                ax.plot(d[sel & ~settled], r[sel & ~settled], marker, mfc="none", color=color,
                        ms=7, label=text + " (not settled)")
            if zoom is not None:
                lo_x, hi_x = zoom.get_xlim()
                near = sel & (d >= lo_x) & (d <= hi_x)
                zoom.plot(d[near & settled], r[near & settled], marker, color=color, ms=5)
                zoom.plot(d[near & ~settled], r[near & ~settled], marker, mfc="none",
                          color=color, ms=5)
        if not title:
            title.append(direct.ships[0].name)
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.axvline(0.0, color="0.6", lw=0.8)
    ax.set(xlabel="rudder angle δ [deg]", ylabel="steady yaw rate r [deg/s]",
           title=f"Spiral: {title[0]}")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize="small")
    return ax


def _first(metrics: Any) -> Any:
    """The first ship and speed of a metrics Dataset (its batch dims at index 0)."""
    return metrics.isel({d: 0 for d in metrics["complete"].dims})


def plot_pullout(result: Any, *, ax: Any = None) -> Any:
    """Yaw rate against time after the rudder is returned to zero.

    Parameters
    ----------
    result : ManeuverResult
        A pull-out result (:func:`~seahelm.analysis.maneuvers.pull_out`).
    ax : matplotlib Axes, optional
        Axes to draw into (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _new_axes(ax, figsize=(8, 5))
    for k, (label, run, m) in enumerate(_runs(result)):
        color = f"C{k % 10}"
        ax.plot(run["time"].values, np.degrees(run["yaw_rate"].values), color=color, label=label)
        ax.axhline(math.degrees(float(m["residual_yaw_rate"])), color=color, ls=":", lw=0.9)
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set(xlabel="time after the rudder order [s]", ylabel="yaw rate r [deg/s]",
           title=f"Pull-out: {', '.join(s.name for s in result.ships)} "
                 "(dotted: residual yaw rates)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    return ax


def plot_stopping(result: Any, *, fig: Any = None) -> Any:
    """Stopping tests: tracks (left) and surge speed, propeller rps, engine order (right).

    The track of each run is drawn in the frame of the original course (across to starboard,
    along ahead, from the position at the order) up to the end of the run, with the point where
    the ship is dead in the water marked and its head reach written; the time series show the
    reversal sequence (the windmilling shaft, the air start, the astern rps).

    Parameters
    ----------
    result : ManeuverResult
        A stopping result (:func:`~seahelm.analysis.maneuvers.crash_stop`).
    fig : matplotlib Figure, optional
        Figure to draw into (default: a new one).

    Returns
    -------
    matplotlib Figure
    """
    if fig is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(12.0, 7.0), layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=(1.0, 1.4))
    track = fig.add_subplot(grid[:, 0])
    series = [fig.add_subplot(grid[i, 1]) for i in range(3)]
    for ax in series[1:]:
        ax.sharex(series[0])
    dead = result.metrics["time_dead"].values
    shown = 1.5 * float(np.nanmax(dead)) if np.isfinite(dead).any() else math.inf
    for k, (label, run, m) in enumerate(_runs(result)):
        color = f"C{k % 10}"
        t = run["time"].values
        keep = t <= shown
        t_dead = float(m["time_dead"])
        ahead = t <= (t_dead if math.isfinite(t_dead) else math.inf)
        north, east = run["north"].values, run["east"].values
        psi0 = float(run["heading"].values[0])
        c, s = math.cos(psi0), math.sin(psi0)
        along = (north - north[0]) * c + (east - east[0]) * s
        across = -(north - north[0]) * s + (east - east[0]) * c
        head, lateral = float(m["head_reach"]), float(m["lateral_deviation"])
        track.plot(across[ahead], along[ahead], color=color, lw=1.5, label=label)
        track.plot(across[keep & ~ahead], along[keep & ~ahead], color=color, lw=0.7, ls=":")
        if math.isfinite(head):
            track.plot([lateral], [head], "o", color=color, ms=6)
            track.text(lateral, head, f"  head reach {head:.4g} m", color=color, fontsize=8,
                       va="center")
        series[0].plot(t[keep], run["surge_speed"].values[keep], color=color, lw=1.2,
                       label=label)
        series[1].plot(t[keep], run["propeller_rps"].values[keep], color=color, lw=1.2)
        series[2].plot(t[keep], run["engine_order"].values[keep], color=color, lw=1.2)
        for ax in series:
            if math.isfinite(t_dead):
                ax.axvline(t_dead, color=color, lw=0.8, ls="--")
    track.plot([0.0], [0.0], "k^", ms=7, label="full astern ordered")
    track.axvline(0.0, color="0.6", lw=0.8, ls=":")
    track.set(xlabel="across the original course (to starboard) [m]",
              ylabel="along the original course [m]", title="track")
    track.set_aspect("equal", adjustable="datalim")
    track.legend(fontsize="small", loc="lower right")
    for ax, ylabel in zip(series, ("surge speed u [m/s]", "propeller n [1/s]",
                                   "engine order [-]")):
        ax.axhline(0.0, color="0.6", lw=0.8, ls=":")
        ax.set_ylabel(ylabel)
    series[2].set_xlabel("time from the order [s] (dashed: dead in the water)")
    frac = result.metrics.attrs.get("dead_fraction", 0.05)
    fig.suptitle(f"Stopping test: {', '.join(s.name for s in result.ships)} "
                 f"(rudder amidships; dead in the water at u <= {frac:g} U0)")
    return fig
