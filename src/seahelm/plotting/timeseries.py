"""Standard figure of a simulation result: heading, actuator angle, yaw rate, xy track.

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
    ax_h, ax_d, ax_r, ax_xy = axes[0, 0], axes[0, 1], axes[1, 0], axes[1, 1]
    for k, i in enumerate(run_ids):
        sel = ds.sel(run=i)
        color = f"C{k % 10}" if len(run_ids) <= 10 else "C0"
        where = ", ".join(f"{c}={sel[c].item():.4g}" for c in batch_coords)
        ax_h.plot(t, np.degrees(np.unwrap(sel["heading"].values)), color=color, alpha=alpha,
                  label=(f"run {i}" + (f" ({where})" if where else ""))
                  if len(run_ids) <= 5 else None)
        if "reference_heading" in ds:
            ax_h.plot(t, np.degrees(sel["reference_heading"].values), "k--", lw=1,
                      label="reference" if k == 0 else None)
        if act is not None:
            ax_d.plot(t, np.degrees(sel[act].values), color=color, alpha=alpha)
        for name in ds.data_vars:
            # overlay angle commands (not rate commands) on the actuator-angle panel
            if (ds[name].attrs.get("kind") == "command" and "rate" not in str(name)
                    and k == 0 and len(run_ids) == 1):
                ax_d.plot(t, np.degrees(sel[name].values), ":", color="0.4", lw=1,
                          label=str(name))
        ax_r.plot(t, np.degrees(sel["yaw_rate"].values), color=color, alpha=alpha)
        if "reference_yaw_rate" in ds:
            ax_r.plot(t, np.degrees(sel["reference_yaw_rate"].values), "k--", lw=1)
        ax_xy.plot(sel["east"].values, sel["north"].values, color=color, alpha=alpha)
    ax_h.set(xlabel="time [s]", ylabel="heading [deg]", title="Heading")
    ax_d.set(xlabel="time [s]", ylabel=f"{act or 'actuator'} [deg]",
             title=(act or "actuator").replace("_", " ").capitalize())
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
