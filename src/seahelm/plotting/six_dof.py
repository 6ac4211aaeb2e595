"""Standard figure of a 6-DOF craft's result: track, depth, attitude, actuators.

What a USV or AUV engineer looks at first: the track over ground (with the route of a guided
run), depth and pitch against time (the AUV's dive, the USV's trim), the attitude (roll, pitch,
heading) and the actuators — each propeller's shaft-speed command and response [rad/s], each
fin's command and angle [deg] — plus the guidance's cross-track error where there is one.
:func:`seahelm.plotting.timeseries.plot_result` draws this figure for any result with the
6-DOF states (``depth``, ``roll``, ``pitch``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["plot_six_dof", "is_six_dof"]

_MAX_LINES = 10


def is_six_dof(ds: Any) -> bool:
    """Whether a result dataset holds a 6-DOF craft (states ``depth``, ``roll``, ``pitch``).

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    bool
    """
    return all(n in ds and ds[n].attrs.get("kind") == "state" for n in ("depth", "roll", "pitch"))


def plot_six_dof(ds: Any, *, runs: Any = None, fig: Any = None, title: str = "",
                 draw_route: Any = None) -> Any:
    """Draw track, depth and pitch, attitude, shaft speeds and fin angles; returns the figure.

    Parameters
    ----------
    ds : xarray.Dataset
        A flat result dataset (dims ``(run, time)``).
    runs : sequence of int, optional
        Runs to draw (default: the first 10).
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one by default).
    title : str, optional
        The figure's title.
    draw_route : callable, optional
        ``draw_route(ax, run_dataset)`` draws a guided run's route under the track.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    if fig is None:
        fig = plt.figure(figsize=(13, 7.5))
        fig.subplots_adjust(left=0.06, right=0.985, bottom=0.07, top=0.9, wspace=0.28,
                            hspace=0.32)
    axes = fig.subplots(2, 3)
    ax_xy, ax_z, ax_att = axes[0]
    ax_n, ax_f, ax_e = axes[1]
    t = ds["time"].values
    run_ids = list(ds["run"].values)[:_MAX_LINES] if runs is None else list(runs)
    shafts = [str(n) for n in ds.data_vars if ds[n].attrs.get("kind") == "state"
              and str(n).endswith("_speed") and str(n) not in
              ("surge_speed", "sway_speed", "heave_speed")]
    fins = [str(n) for n in ds.data_vars if ds[n].attrs.get("kind") == "state"
            and str(n).endswith("_angle")]
    for k, i in enumerate(run_ids):
        sel = ds.sel(run=i)
        c = f"C{k % 10}"
        lab = f"run {i}" if len(run_ids) > 1 else None
        ax_xy.plot(sel["east"].values, sel["north"].values, color=c, label=lab)
        ax_z.plot(t, sel["depth"].values, color=c)
        ax_att.plot(t, np.degrees(sel["roll"].values), color=c, ls="-",
                    label="roll" if k == 0 else None)
        ax_att.plot(t, np.degrees(sel["pitch"].values), color=c, ls="--",
                    label="pitch" if k == 0 else None)
        ax_e.plot(t, np.degrees(np.unwrap(sel["heading"].values)), color=c,
                  label="heading" if k == 0 else None)
        for j, name in enumerate(shafts):
            ax_n.plot(t, sel[name].values, color=f"C{j}" if len(run_ids) == 1 else c,
                      label=name.replace("_", " ") if k == 0 else None)
            cmd = name + "_command"
            if cmd in ds and k == 0 and len(run_ids) == 1:
                ax_n.plot(t, sel[cmd].values, ":", color=f"C{j}", lw=1, label="command")
        for j, name in enumerate(fins):
            ax_f.plot(t, np.degrees(sel[name].values), color=f"C{j}" if len(run_ids) == 1 else c,
                      label=name.replace("_", " ") if k == 0 else None)
            cmd = name[: -len("_angle")] + "_command"
            if cmd in ds and k == 0 and len(run_ids) == 1:
                ax_f.plot(t, np.degrees(sel[cmd].values), ":", color=f"C{j}", lw=1,
                          label="command")
    guided = "cross_track_error" in ds
    if guided and draw_route is not None:
        draw_route(ax_xy, ds.sel(run=run_ids[0]))
    if not fins:  # a craft without fins: the panel shows the cross-track error, if any
        if guided:
            for k, i in enumerate(run_ids):
                ax_f.plot(t, ds.sel(run=i)["cross_track_error"].values, color=f"C{k % 10}")
        else:
            ax_f.text(0.5, 0.5, "no fins", ha="center", va="center", transform=ax_f.transAxes)
    if "heading_reference" in ds:
        h = np.unwrap(ds.sel(run=run_ids[0])["heading"].values)
        ref = ds.sel(run=run_ids[0])["heading_reference"].values
        ax_e.plot(t, np.degrees(h + (ref - h + np.pi) % (2 * np.pi) - np.pi), "k--", lw=1,
                  label="guidance ψ_d")
    ax_xy.set(xlabel="east [m]", ylabel="north [m]", title="Track")
    ax_xy.set_aspect("equal", adjustable="datalim")
    ax_z.set(xlabel="time [s]", ylabel="depth [m] (down)", title="Depth")
    ax_z.invert_yaxis()
    ax_att.set(xlabel="time [s]", ylabel="[deg]", title="Roll and pitch")
    ax_e.set(xlabel="time [s]", ylabel="heading [deg]", title="Heading")
    ax_n.set(xlabel="time [s]", ylabel="shaft speed [rad/s]", title="Propellers")
    if fins or not guided:
        ax_f.set(xlabel="time [s]", ylabel="fin angle [deg]", title="Fins")
    else:
        ax_f.set(xlabel="time [s]", ylabel="cross-track error [m]",
                 title="Cross-track error (+ starboard of the route)")
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize="small")
    fig.suptitle(title)
    return fig
