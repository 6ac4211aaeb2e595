"""The report section of a replay (``replay.nc`` of ``seahelm replay --out``,
:meth:`seahelm.analysis.replay.simulate.ReplayResult.to_xarray`): the replay's settings, the
measured and simulated metrics side by side with the RMS position errors (as ``seahelm replay``
printed them), the two tracks in the horizontal plane and the heading, yaw rate and rudder
angle of both over time.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..units import metric_label, to_display
from .blocks import Section, fmt, paragraph, table
from .figures import LEGEND, typed_array
from .inputs import ReportData
from .signals import decimated_index

__all__ = ["replay_sections"]

#: The file's attributes shown, in this order (attribute, label, unit).
_SHOWN = (("record", "record", ""), ("ship", "ship", ""), ("kind", "manoeuvre", ""),
          ("rudder", "rudder", ""), ("wind_kind", "wind", ""), ("dt_s", "step", "s"),
          ("length_m", "ship length L", "m"))
#: Time series drawn against time (those in the file).
_SIGNALS = ("heading", "yaw_rate", "rudder_angle", "speed")
#: Track colours: measured, simulated.
_COLORS = ("#222222", "#d62728")


def replay_sections(data: ReportData) -> list[Section]:
    """The replay's sections (none for other inputs).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    from ..analysis.replay.dataset import replay_metrics

    ds = data.replay
    if ds is None:
        return []
    a = ds.attrs
    sec = Section("replay", "Replay of a measured record")
    sec.blocks.append(table(None, [[label, f"{fmt(a[k], 6)} {unit}".strip()]
                                   for k, label, unit in _SHOWN if k in a], cls="meta"))
    rows = []
    for key, (m, s, unit) in replay_metrics(ds).items():
        (m_shown, shown), (s_shown, _) = (to_display(v, unit, key) for v in (m, s))
        rows.append([metric_label(key, shown), fmt(m_shown, 5), fmt(s_shown, 5)])
    for key, label in (("rms_error_60s_L", "RMS position error, first 60 s [L]"),
                       ("rms_error_L", "RMS position error, whole record [L]")):
        if key in a:
            rows.append([label, "", fmt(float(a[key]), 4)])
    sec.blocks.append(table(["metric", "measured", "simulated"], rows, cls="metrics",
                            caption="the same metrics computed from both tracks"))
    tracks = [str(t) for t in ds["track"].values]
    time = np.asarray(ds["time"].values, dtype=float)
    idx = decimated_index(time.size)
    if "north" in ds and "east" in ds:
        traces = [{"type": "scatter", "mode": "lines", "name": name,
                   "x": typed_array(ds["east"].values[i, idx]),
                   "y": typed_array(ds["north"].values[i, idx]),
                   "line": {"color": _COLORS[i % 2], "width": 1.5,
                            "dash": "solid" if i == 0 else "dash"}}
                  for i, name in enumerate(tracks)]
        sec.blocks.append(paragraph("track: east right, north up, equal scales",
                                    cls="caption"))
        sec.blocks.append({"data": traces, "layout": {
            "xaxis": {"title": {"text": "east [m]"}},
            "yaxis": {"title": {"text": "north [m]"}, "scaleanchor": "x", "scaleratio": 1},
            "height": 520, "margin": dict(l=60, r=20, t=20, b=50), "legend": LEGEND}})
    for name in [n for n in _SIGNALS if n in ds]:
        unit = str(ds[name].attrs.get("units", ""))
        values, shown = to_display(np.asarray(ds[name].values, dtype=float), unit, name)
        traces: list[dict[str, Any]] = [
            {"type": "scatter", "mode": "lines", "name": track,
             "x": typed_array(time[idx]), "y": typed_array(values[i, idx]),
             "line": {"color": _COLORS[i % 2], "width": 1.5,
                      "dash": "solid" if i == 0 else "dash"}}
            for i, track in enumerate(tracks)]
        sec.blocks.append({"data": traces, "layout": {
            "xaxis": {"title": {"text": "time [s]"}},
            "yaxis": {"title": {"text": f"{name.replace('_', ' ')} [{shown}]"}},
            "height": 270, "margin": dict(l=60, r=20, t=30, b=40), "legend": LEGEND}})
    return [sec]
