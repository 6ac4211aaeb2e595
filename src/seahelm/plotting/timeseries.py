"""Standard figure of a simulation result: heading, actuator angle, yaw rate, xy track.

A guided run (a route followed by LOS/ILOS, :mod:`seahelm.control.guided`) shows the
cross-track error instead of the yaw rate, the heading reference of the guidance law on the
heading panel and the route (waypoints, acceptance circles) under the track.

Works on the :class:`xarray.Dataset` of :meth:`seahelm.results.SimResult.to_xarray` (or a
result file read back), so ``seahelm plot RESULT.nc`` draws the same figure. A batch with its
own dimensions (a grid ``kp × kd``, Monte-Carlo ``sample``) is drawn run by run in its flat
view (:func:`seahelm.result_layout.flatten_runs`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["plot_result"]

_MAX_LINES = 50


def _actuator_var(ds: Any) -> str | None:
    for name in ds.data_vars:
        if ds[name].attrs.get("kind") == "state" and name.endswith("_angle"):
            return str(name)
    return None


def plot_result(ds: Any, *, runs: Any = None, fig: Any = None) -> Any:
    """Draw heading, actuator angle, yaw rate and the track in a 2×2 figure; returns it.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset (dims ``(*batch_dims, time)``, e.g. ``(run, time)`` or
        ``(kp, kd, time)``).
    runs : sequence of int, optional
        Runs to draw, as flat run indices in C order over the batch dimensions (default: all,
        at most 50).
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one by default).
    """
    import matplotlib.pyplot as plt

    from ..result_layout import flatten_runs

    ds = flatten_runs(ds)
    batch_coords = [str(c) for c in ds.coords if c != "run" and ds[c].dims == ("run",)]
    if fig is None:
        # fixed margins: constrained layout measured every tick label twice and took half of
        # the time of `seahelm demo`'s plot (1.0 of 2.1 s)
        fig = plt.figure(figsize=(11, 7.5))
        fig.subplots_adjust(left=0.07, right=0.985, bottom=0.07, top=0.9, wspace=0.2,
                            hspace=0.32)
    axes = fig.subplots(2, 2)
    run_ids = list(ds["run"].values) if runs is None else list(runs)
    run_ids = run_ids[:_MAX_LINES]
    t = ds["time"].values
    alpha = 1.0 if len(run_ids) <= 3 else max(0.15, 3.0 / len(run_ids))
    act = _actuator_var(ds)
    guided = "cross_track_error" in ds
    ax_h, ax_d, ax_r, ax_xy = axes[0, 0], axes[0, 1], axes[1, 0], axes[1, 1]
    for k, i in enumerate(run_ids):
        sel = ds.sel(run=i)
        color = f"C{k % 10}" if len(run_ids) <= 10 else "C0"
        where = ", ".join(f"{c}={sel[c].item():.4g}" for c in batch_coords)
        heading = np.unwrap(sel["heading"].values)
        ax_h.plot(t, np.degrees(heading), color=color, alpha=alpha,
                  label=(f"run {i}" + (f" ({where})" if where else ""))
                  if len(run_ids) <= 5 else None)
        if "reference_heading" in ds:
            ax_h.plot(t, np.degrees(sel["reference_heading"].values), "k--", lw=1,
                      label="reference" if k == 0 else None)
        if "heading_reference" in ds and k == 0:  # the guidance law's ψ_d, on the same branch
            psi_d = heading + (sel["heading_reference"].values - heading + np.pi) % (
                2 * np.pi) - np.pi
            ax_h.plot(t, np.degrees(psi_d), "k--", lw=1, label="guidance ψ_d")
        if act is not None:
            ax_d.plot(t, np.degrees(sel[act].values), color=color, alpha=alpha)
        for name in ds.data_vars:
            # overlay angle commands (not rate commands) on the actuator-angle panel
            if (ds[name].attrs.get("kind") == "command" and str(name).endswith("_command")
                    and "rate" not in str(name) and k == 0 and len(run_ids) == 1):
                ax_d.plot(t, np.degrees(sel[name].values), ":", color="0.4", lw=1,
                          label=str(name))
        if guided:
            ax_r.plot(t, sel["cross_track_error"].values, color=color, alpha=alpha)
        else:
            ax_r.plot(t, np.degrees(sel["yaw_rate"].values), color=color, alpha=alpha)
        if "reference_yaw_rate" in ds and not guided:
            ax_r.plot(t, np.degrees(sel["reference_yaw_rate"].values), "k--", lw=1)
        ax_xy.plot(sel["east"].values, sel["north"].values, color=color, alpha=alpha)
    ax_h.set(xlabel="time [s]", ylabel="heading [deg]", title="Heading")
    ax_d.set(xlabel="time [s]", ylabel=f"{act or 'actuator'} [deg]",
             title=(act or "actuator").replace("_", " ").capitalize())
    if guided:
        ax_r.set(xlabel="time [s]", ylabel="cross-track error [m]",
                 title="Cross-track error (+ starboard of the route)")
        _draw_route(ax_xy, ds.sel(run=run_ids[0]))
    else:
        ax_r.set(xlabel="time [s]", ylabel="yaw rate [deg/s]", title="Yaw rate")
    ax_xy.set(xlabel="east [m]", ylabel="north [m]", title="Track")
    ax_xy.set_aspect("equal", adjustable="datalim")
    for ax in (ax_h, ax_d):
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize="small")
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
    title = ds.attrs.get("title") or f"{ds.attrs.get('model', '')} / {ds.attrs.get('controller', '')}"
    fig.suptitle(str(title))
    return fig


def _draw_route(ax: Any, sel: Any) -> None:
    """The route of a guided run: legs, waypoints and acceptance circles (its parameters)."""
    names = ("controller.route_north", "controller.route_east", "controller.n_waypoints")
    if not all(n in sel for n in names):
        return
    n = int(sel["controller.n_waypoints"].item())
    north = sel["controller.route_north"].values[:n]
    east = sel["controller.route_east"].values[:n]
    ax.plot(east, north, "k--", lw=1, marker="o", ms=4, label="route", zorder=1)
    if "controller.acceptance_radius" in sel:
        import matplotlib.patches as mpatches

        radius = float(sel["controller.acceptance_radius"].item())
        for e, nn in zip(east[1:], north[1:]):
            ax.add_patch(mpatches.Circle((e, nn), radius, fill=False, ls=":", lw=0.8,
                                         color="0.4"))
    ax.legend(loc="best", fontsize="small")
