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

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .maneuver_runs import DrawnRun, drawn_groups, representatives_note, ship_names

__all__ = ["plot_turning", "plot_zigzag", "plot_spiral", "plot_pullout", "plot_stopping"]



def _style(run: DrawnRun, color: str) -> dict[str, Any]:
    """Line style of a drawn run: bold measured, thin representative, dashed incomplete."""
    if run.role == "quantile":
        return dict(color=color, lw=0.7, alpha=0.6)
    if run.role == "failed":
        return dict(color=color, lw=0.9, ls="--", alpha=0.8)
    return dict(color=color, lw=1.8 if run.role == "median" else 1.5)


def _mark_end(ax: Any, run: DrawnRun, x: Any, y: Any, color: str) -> None:
    """An x at the end of an incomplete run (a big batch's 'failed' run, or any run that did
    not complete), where it stopped."""
    if (run.role == "failed" or not bool(run.metrics["complete"])) and len(x):
        ax.plot([x[-1]], [y[-1]], "x", color=color, ms=8, mew=2)


def _note(fig: Any, text: str) -> None:
    if text:  # (a figure-level label: the layout engine makes room for it)
        fig.supxlabel(text, fontsize=7, color="0.3", wrap=True)


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
    groups = drawn_groups(result, "tactical_diameter")
    # the values are written beside the arrows of a lone measured run; with several, in the
    # legend (written beside each, they overlap where the circles meet)
    measured = sum(drawn.measured for group in groups for drawn in group.runs)
    for k, group in enumerate(groups):
        color = f"C{k % 10}"
        for drawn in group.runs:
            _turning_run(ax, drawn, color, group.label if group.size > 1 else drawn.label,
                         written=measured == 1)
    ax.plot([0.0], [0.0], "k^", ms=7, label="rudder order")
    ax.axvline(0.0, color="0.6", lw=0.8, ls=":")
    rudder = result.metrics["rudder"]
    what = (f"{math.degrees(float(rudder)):.3g} deg rudder" if rudder.ndim == 0
            else "rudder " + ", ".join(f"{math.degrees(v):.3g}" for v in rudder.values) + " deg")
    ax.set(xlabel="across the original course (to starboard) [m]",
           ylabel="along the original course [m]",
           title=f"Turning circle: {ship_names([s.name for s in result.ships])}, {what} "
                 "(midship point)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    _note(ax.figure, representatives_note(groups, "tactical diameter"))
    return ax


def _turning_run(ax: Any, drawn: DrawnRun, color: str, group_label: str, *,
                 written: bool) -> None:
    """One turning circle's track; a measured run's advance, transfer and tactical diameter
    marked by arrows, their values ``written`` beside them or else in the legend."""
    run, m = drawn.runs, drawn.metrics
    adv, tr, td = (float(m[v]) for v in ("advance", "transfer", "tactical_diameter"))
    t = run["time"].values
    north, east = run["north"].values, run["east"].values
    # the original course is north (heading 0) in every manoeuvre; keep the general case
    psi0 = float(run["heading"].values[0])
    c, s = math.cos(psi0), math.sin(psi0)
    along = (north - north[0]) * c + (east - east[0]) * s
    across = -(north - north[0]) * s + (east - east[0]) * c
    keep = np.abs(run["heading"].values - psi0) <= 2.0 * math.pi + 1e-9
    label = group_label if drawn.measured else None
    if label is not None and not written:
        label += "".join(f", {name} {v:.4g} m" for name, v in (
            ("advance", adv), ("transfer", tr), ("tactical diameter", td)) if math.isfinite(v))
    ax.plot(across[keep], along[keep], label=label, **_style(drawn, color))
    _mark_end(ax, drawn, across[keep], along[keep], color)
    if not drawn.measured:
        return
    side = np.sign(across[np.argmax(np.abs(across))]) or 1.0
    t90, t180 = float(m["time_90"]), float(m["time_180"])
    if math.isfinite(t90):
        x90 = side * tr
        ax.plot([x90], [adv], "o", color=color, ms=6)
        ax.annotate("", xy=(x90, adv), xytext=(x90, 0.0),
                    arrowprops=dict(arrowstyle="<->", color=color, lw=0.9))
        if written:
            ax.text(x90, 0.5 * adv, f" advance\n {adv:.4g} m", color=color, fontsize=8,
                    ha="left" if side > 0 else "right", va="center")
        ax.annotate("", xy=(x90, adv), xytext=(0.0, adv),
                    arrowprops=dict(arrowstyle="<->", color=color, lw=0.9, ls="--"))
        if written:
            ax.text(0.5 * x90, adv, f"transfer {tr:.4g} m", color=color, fontsize=8,
                    ha="center", va="bottom")
    if math.isfinite(t180):
        y180 = float(np.interp(t180, t, along))
        x180 = side * td
        ax.plot([x180], [y180], "s", color=color, ms=6)
        ax.annotate("", xy=(x180, y180), xytext=(0.0, y180),
                    arrowprops=dict(arrowstyle="<->", color=color, lw=0.9))
        if written:
            ax.text(0.5 * x180, y180, f"tactical diameter {td:.4g} m", color=color,
                    fontsize=8, ha="center", va="top")


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

    groups = drawn_groups(result, "overshoot", index=0)
    ncols = 2 if len(groups) > 1 else 1
    nrows = math.ceil(len(groups) / ncols)
    if fig is None:
        fig = plt.figure(figsize=(6.0 * ncols, 3.6 * nrows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).ravel()
    for ax, group in zip(axes, groups):
        for drawn in group.runs:
            _zigzag_run(ax, drawn)
        m = group.runs[-1].metrics
        trig = math.degrees(float(m["trigger"])) if "trigger" in m.coords else math.nan
        for level in (trig, -trig):
            ax.axhline(level, color="0.5", lw=0.8, ls="--")
        ax.axhline(0.0, color="0.7", lw=0.6)
        title = group.label if group.size == 1 else (
            f"{group.label} ({len(group.runs)} of {group.size:,} runs)")
        ax.set(xlabel="time [s]", ylabel="heading change, rudder angle [deg]", title=title)
        ax.margins(y=0.2)
        ax.grid(True, alpha=0.3)
        if group.size == 1 and (not math.isfinite(float(m["period"]))
                                or not bool(m["complete"])):
            ax.text(0.02, 0.02, str(m["message"].item()), transform=ax.transAxes, fontsize=7,
                    color="C3")
    for ax in axes[len(groups):]:
        ax.set_visible(False)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2, fontsize="small")
    fig.suptitle(f"Zig-zag: {ship_names([s.name for s in result.ships])} "
                 "(executes: green lines; overshoots: red marks)")
    _note(fig, representatives_note(groups, "first overshoot"))
    return fig


def _zigzag_run(ax: Any, drawn: DrawnRun) -> None:
    """One zig-zag run's heading change and rudder angle; a measured run's overshoots and
    executes."""
    run, m = drawn.runs, drawn.metrics
    t = run["time"].values
    psi = np.degrees(run["heading"].values - run["heading"].values[0])
    measured = drawn.measured
    ax.plot(t, psi, label="heading change ψ − ψ0" if measured else None,
            **_style(drawn, "C0"))
    _mark_end(ax, drawn, t, psi, "C0")
    if not measured:
        return
    ax.plot(t, np.degrees(run["rudder_angle"].values), color="C1", lw=1.2,
            label="rudder angle δ (positive turns to starboard)")
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
    groups = drawn_groups(result, "residual_yaw_rate")
    for k, group in enumerate(groups):
        color = f"C{k % 10}"
        for drawn in group.runs:
            run, m = drawn.runs, drawn.metrics
            t, r = run["time"].values, np.degrees(run["yaw_rate"].values)
            ax.plot(t, r, label=group.label if drawn.measured else None,
                    **_style(drawn, color))
            _mark_end(ax, drawn, t, r, color)
            if drawn.measured:
                ax.axhline(math.degrees(float(m["residual_yaw_rate"])), color=color, ls=":",
                           lw=0.9)
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set(xlabel="time after the rudder order [s]", ylabel="yaw rate r [deg/s]",
           title=f"Pull-out: {ship_names([s.name for s in result.ships])} "
                 "(dotted: residual yaw rates)")
    _note(ax.figure, representatives_note(groups, "residual yaw rate"))
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    return ax



def track_and_series_axes(fig: Any, figsize: tuple[float, float], series_width: float
                          ) -> tuple[Any, Any, list[Any]]:
    """A figure with the track on the left (all rows) and three time series on the right
    sharing their time axis (the stopping and replay figures).

    Parameters
    ----------
    fig : matplotlib Figure or None
        Figure to draw into (None: a new one of ``figsize``, constrained layout).
    figsize : (float, float)
        Size of a new figure [in].
    series_width : float
        Width of the series column relative to the track's.

    Returns
    -------
    (Figure, Axes, list of Axes)
        The figure, the track's axes and the three series' axes, top to bottom.
    """
    if fig is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=figsize, layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=(1.0, series_width))
    track = fig.add_subplot(grid[:, 0])
    series = [fig.add_subplot(grid[i, 1]) for i in range(3)]
    for ax in series[1:]:
        ax.sharex(series[0])
    return fig, track, series

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
    fig, track, series = track_and_series_axes(fig, (12.0, 7.0), 1.4)
    dead = result.metrics["time_dead"].values
    shown = 1.5 * float(np.nanmax(dead)) if np.isfinite(dead).any() else math.inf
    groups = drawn_groups(result, "track_reach")
    for k, group in enumerate(groups):
        for drawn in group.runs:
            _stopping_run(track, series, drawn, f"C{k % 10}", shown,
                          group.label if group.size > 1 else drawn.label)
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
    fig.suptitle(f"Stopping test: {ship_names([s.name for s in result.ships])} "
                 f"(rudder amidships; dead in the water at u <= {frac:g} U0)")
    _note(fig, representatives_note(groups, "track reach"))
    return fig


def _stopping_run(track: Any, series: Sequence[Any], drawn: DrawnRun, color: str,
                  shown: float, label: str) -> None:
    """One stopping run: its track (dotted astern), surge speed, rps and engine order; a
    measured run's head reach and time dead in the water."""
    run, m = drawn.runs, drawn.metrics
    style = _style(drawn, color)
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
    label = label if drawn.measured else None
    track.plot(across[ahead], along[ahead], label=label, **style)
    track.plot(across[keep & ~ahead], along[keep & ~ahead], color=color, lw=0.7, ls=":")
    _mark_end(track, drawn, across[ahead], along[ahead], color)
    for ax, name in zip(series, ("surge_speed", "propeller_rps", "engine_order")):
        ax.plot(t[keep], run[name].values[keep], label=label if name == "surge_speed" else None,
                **{**style, "lw": min(style["lw"], 1.2)})
    if not drawn.measured:
        return
    if math.isfinite(head):
        track.plot([lateral], [head], "o", color=color, ms=6)
        track.text(lateral, head, f"  head reach {head:.4g} m", color=color, fontsize=8,
                   va="center")
    for ax in series:
        if math.isfinite(t_dead):
            ax.axvline(t_dead, color=color, lw=0.8, ls="--")
