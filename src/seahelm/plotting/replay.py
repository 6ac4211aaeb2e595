"""Overlay of a replayed record: the measured and the simulated track, heading, speed, inputs."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["plot_replay"]


def plot_replay(result: Any, *, fig: Any = None) -> Any:
    """Measured (black) and simulated (colour) track, heading, speed and the measured inputs.

    Parameters
    ----------
    result : ReplayResult
        A replay (:func:`~seahelm.analysis.replay.simulate.replay`).
    fig : matplotlib Figure, optional
        Figure to draw into (default: a new one).

    Returns
    -------
    matplotlib Figure
    """
    from .maneuvers import track_and_series_axes

    fig, track, series = track_and_series_axes(fig, (12.0, 7.5), 1.3)
    t = result.time - result.time[0]
    m, s = result.measured, result.simulated
    sim = f"simulated ({result.ship})"
    track.plot(m["east"], m["north"], "k-", lw=1.6, label="measured")
    track.plot(s["east"], s["north"], "C0--", lw=1.4, label=sim)
    track.plot([m["east"][0]], [m["north"][0]], "k^", ms=7, label="start")
    track.set(xlabel="east y [m]", ylabel="north x [m]",
              title=f"track (RMS error {result.rms_error_window:.3g} L over 60 s, "
                    f"{result.rms_error:.3g} L in all)")
    track.set_aspect("equal", adjustable="datalim")
    track.legend(fontsize="small", loc="best")
    series[0].plot(t, np.degrees(m["heading"]), "k-", label="measured")
    series[0].plot(t, np.degrees(s["heading"]), "C0--", label=sim)
    series[0].set(ylabel="heading ψ [deg]")
    series[0].legend(fontsize="small", loc="best")
    series[1].plot(t, m["speed"], "k-", label="measured U")
    series[1].plot(t, s["speed"], "C0--", label="simulated U")
    series[1].plot(t, m["surge_speed"], "k:", lw=0.9, label="measured u")
    series[1].plot(t, s["surge_speed"], "C0:", lw=0.9, label="simulated u")
    series[1].set(ylabel="speed [m/s]")
    series[1].legend(fontsize="small", loc="best", ncols=2)
    series[2].plot(t, np.degrees(m["rudder_angle"]), "C3-", label="measured rudder δ")
    if result.closed_loop:
        series[2].plot(t, np.degrees(s["rudder_angle"]), "C0--",
                       label="simulated rudder δ (closed loop)")
    series[2].set(ylabel="rudder δ [deg]", xlabel="time from the first sample [s]")
    handles, labels = series[2].get_legend_handles_labels()
    if "propeller_rps" in m:
        rps = series[2].twinx()
        rps.plot(t, m["propeller_rps"], "C2-", label="measured propeller n")
        rps.set(ylabel="propeller n [1/s]")
        rps.ticklabel_format(axis="y", useOffset=False)
        more = rps.get_legend_handles_labels()
        handles, labels = handles + more[0], labels + more[1]
    series[2].legend(handles, labels, fontsize="small", loc="lower center", ncols=3,
                     bbox_to_anchor=(0.5, 1.0), frameon=False)
    inputs = "rudder closed loop" if result.closed_loop else "measured inputs"
    series[0].set_title(f"{result.record.name}: {result.kind} replay, {inputs}"
                        + (f", check angle {math.degrees(result.check_angle):.0f} deg"
                           if result.check_angle is not None else ""), fontsize="medium")
    return fig
