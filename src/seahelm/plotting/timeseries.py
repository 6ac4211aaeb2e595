"""Standard figure of a simulation result: heading, actuator angle, yaw rate, xy track.

A guided run (a route followed by LOS/ILOS, :mod:`seahelm.control.guided`) shows the
cross-track error instead of the yaw rate, the heading reference of the guidance law on the
heading panel and the route (waypoints, acceptance circles) under the track.

Works on the :class:`xarray.Dataset` of :meth:`seahelm.results.SimResult.to_xarray` (or a
result file read back), so ``seahelm plot RESULT.nc`` draws the same figure. A batch with its
own dimensions (a grid ``kp × kd``, Monte-Carlo ``sample``) is drawn run by run in its flat
view (:func:`seahelm.result_layout.flatten_runs`). Above :data:`BAND_RUNS` runs (a Monte-Carlo
batch), the time series are drawn as the band between the 5 % and 95 % points over the runs
that did not diverge, with their median and a few runs spread over the batch, and the tracks
of at most 20 runs, not every run over every other. A diverged run is marked with an x where
its record ends, and the figure says how many diverged.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["plot_result"]

_MAX_LINES = 50
#: Runs above which the time series are drawn as a band (5-95 %) with their median.
BAND_RUNS = 20
#: Runs drawn one by one over a band.
_BAND_LINES = 5


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
    from .six_dof import is_six_dof, plot_six_dof

    if is_six_dof(ds):  # a USV or AUV: track, depth, attitude, propellers, fins
        return plot_six_dof(ds, runs=runs, fig=fig, title=_title(ds), draw_route=_draw_route)
    batch_coords = [str(c) for c in ds.coords if c != "run" and ds[c].dims == ("run",)]
    if fig is None:
        # fixed margins: constrained layout measured every tick label twice and took half of
        # the time of `seahelm demo`'s plot (1.0 of 2.1 s)
        fig = plt.figure(figsize=(11, 7.5))
        fig.subplots_adjust(left=0.07, right=0.985, bottom=0.07, top=0.9, wspace=0.2,
                            hspace=0.32)
    axes = fig.subplots(2, 2)
    run_ids = list(ds["run"].values) if runs is None else list(runs)
    status = (np.asarray(ds["status"].values).reshape(-1) if "status" in ds
              else np.zeros(ds.sizes["run"], dtype=int))
    banded = runs is None and len(run_ids) > BAND_RUNS
    if banded:  # a few runs spread over the batch, and the diverged ones (marked)
        spread = np.unique(np.linspace(0, len(run_ids) - 1, _BAND_LINES).round().astype(int))
        run_ids = sorted({*(run_ids[j] for j in spread),
                          *np.flatnonzero(status != 0)[:_BAND_LINES].tolist()})
    run_ids = run_ids[:_MAX_LINES]
    t = ds["time"].values
    alpha = 1.0 if len(run_ids) <= 3 else max(0.15, 3.0 / len(run_ids))
    act = _actuator_var(ds)
    guided = "cross_track_error" in ds
    ax_h, ax_d, ax_r, ax_xy = axes[0, 0], axes[0, 1], axes[1, 0], axes[1, 1]
    if banded:
        alpha = 0.5
        ok = status == 0
        heading_all = np.degrees(np.unwrap(ds["heading"].values, axis=-1))
        _band(ax_h, t, heading_all[ok], "heading")
        if act is not None:
            _band(ax_d, t, np.degrees(ds[act].values)[ok], None)
        _band(ax_r, t, (ds["cross_track_error"].values if guided
                        else np.degrees(ds["yaw_rate"].values))[ok], None)
    for k, i in enumerate(run_ids):
        sel = ds.sel(run=i)
        color = "0.35" if banded else f"C{k % 10}" if len(run_ids) <= 10 else "C0"
        where = ", ".join(_coordinate_text(c, sel[c].item(), ds[c].attrs.get("units"))
                          for c in batch_coords)
        heading = np.unwrap(sel["heading"].values)
        label = (f"run {i}" + (f" ({where})" if where else "")) if len(run_ids) <= 5 else None
        if banded:
            label = f"{len(run_ids)} runs spread over the batch" if k == 0 else None
        ax_h.plot(t, np.degrees(heading), color=color, alpha=alpha,
                  lw=0.7 if banded else None, label=label)
        if "reference_heading" in ds:
            ax_h.plot(t, np.degrees(sel["reference_heading"].values), "k--", lw=1,
                      label="reference" if k == 0 else None)
        if "heading_reference" in ds and k == 0:  # the guidance law's ψ_d, on the same branch
            psi_d = heading + (sel["heading_reference"].values - heading + np.pi) % (
                2 * np.pi) - np.pi
            ax_h.plot(t, np.degrees(psi_d), "k--", lw=1, label="guidance ψ_d")
        if act is not None:
            ax_d.plot(t, np.degrees(sel[act].values), color=color, alpha=alpha,
                      lw=0.7 if banded else None)
        for name in ds.data_vars:
            # overlay angle commands (not rate commands) on the actuator-angle panel
            if (ds[name].attrs.get("kind") == "command" and str(name).endswith("_command")
                    and "rate" not in str(name) and k == 0 and len(run_ids) == 1):
                ax_d.plot(t, np.degrees(sel[name].values), ":", color="0.4", lw=1,
                          label=str(name).replace("_", " "))
        width = 0.7 if banded else None
        if guided:
            ax_r.plot(t, sel["cross_track_error"].values, color=color, alpha=alpha, lw=width)
        else:
            ax_r.plot(t, np.degrees(sel["yaw_rate"].values), color=color, alpha=alpha,
                      lw=width)
        if "reference_yaw_rate" in ds and not guided:
            ax_r.plot(t, np.degrees(sel["reference_yaw_rate"].values), "k--", lw=1)
        ax_xy.plot(sel["east"].values, sel["north"].values, color=color, alpha=alpha)
        if status[int(i)] != 0:  # diverged: an x where its record ends
            _mark_divergence(ax_h, t, np.degrees(heading))
            _mark_divergence(ax_xy, sel["east"].values, sel["north"].values)
    if banded:  # the tracks of at most 20 runs spread over the batch
        for i in np.unique(np.linspace(0, ds.sizes["run"] - 1, 20).round().astype(int)):
            sel = ds.isel(run=int(i))
            ax_xy.plot(sel["east"].values, sel["north"].values, color="C0", alpha=0.3, lw=0.8)
    ax_h.set(xlabel="time [s]", ylabel="heading [deg]", title="Heading")
    ax_d.set(xlabel="time [s]", ylabel=f"{(act or 'actuator').replace('_', ' ')} [deg]",
             title=(act or "actuator").replace("_", " ").capitalize()
             + (" (positive turns to starboard)" if act == "rudder_angle" else ""))
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
    for ax in (ax_h, ax_d, ax_r):  # short tick labels (×10ⁿ above the axis) fit the margins
        ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 4), useMathText=True)
    title = _title(ds)
    notes = []
    if banded:
        notes.append(f"{ds.sizes['run']:,} runs: 5-95 % band and median of the "
                     f"{int((status == 0).sum()):,} that did not diverge, {len(run_ids)} runs "
                     "drawn, 20 tracks")
    if (status != 0).any():
        notes.append(f"{int((status != 0).sum()):,} diverged (x: where the record ends)")
    fig.suptitle(title + ("\n" + "; ".join(notes) if notes else ""),
                 fontsize="medium" if notes else None)
    return fig


def _title(ds: Any) -> str:
    """The figure's title: the scenario's; a manoeuvre and its ship ("Turning circle:
    kvlcc2-l7 (mmg)", it was "mmg / open-loop"); else the model and the controller."""
    if ds.attrs.get("title"):
        return str(ds.attrs["title"])
    model = str(ds.attrs.get("model", ""))
    maneuver = ds.attrs.get("maneuver")
    if maneuver:
        what = str(maneuver).replace("-", " ").replace("zigzag", "zig-zag").capitalize()
        ship = ds["ship_name"] if "ship_name" in ds.coords else None
        ship_text = (str(ship.item()) if ship is not None and ship.ndim == 0 else
                     ", ".join(dict.fromkeys(str(v) for v in np.ravel(ship.values)))
                     if ship is not None else "")
        return f"{what}: {ship_text} ({model})" if ship_text else f"{what} ({model})"
    return f"{model} / {ds.attrs.get('controller', '')}"


def _coordinate_text(name: str, value: Any, unit: str | None = None) -> str:
    """A run's coordinate in a legend: a manoeuvre's side as "starboard"/"port" (it was
    "side=1"/"side=-1"), a name as itself, an angle in degrees ("rudder=20°", it was
    "rudder=0.3491"), another number as ``name=value``."""
    if name == "side" and value in (1, -1):
        return "starboard" if value == 1 else "port"
    if isinstance(value, str):
        return value
    if unit == "rad":
        return f"{name}={np.degrees(value):.4g}°"
    return f"{name}={value:.4g}"


def _band(ax: Any, t: np.ndarray, values: np.ndarray, label: str | None) -> None:
    """The 5-95 % band and the median over the runs (rows) of ``values``."""
    if not values.size:
        return
    import warnings

    with warnings.catch_warnings():  # (a time where every run is NaN: no band there)
        warnings.simplefilter("ignore", RuntimeWarning)
        lo, mid, hi = np.nanquantile(values, [0.05, 0.5, 0.95], axis=0)
    ax.fill_between(t, lo, hi, color="C0", alpha=0.25, lw=0,
                    label="5-95 % of the runs" if label else None)
    ax.plot(t, mid, color="C0", lw=1.8, label="median" if label else None, zorder=3)


def _mark_divergence(ax: Any, x: np.ndarray, y: np.ndarray) -> None:
    """An x at the last finite sample of a diverged run."""
    finite = np.flatnonzero(np.isfinite(x) & np.isfinite(y))
    if finite.size:
        ax.plot([x[finite[-1]]], [y[finite[-1]]], "x", color="C3", ms=9, mew=2)


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
