"""The figures of a report: plotly figure specifications (dicts of traces and layout, drawn by
plotly.js in the page), with the arrays as plotly.js typed arrays (base64, single precision),
which keeps a page of many long runs small.

The track in the horizontal plane with hull outlines, the time series (heading, rudder angle,
yaw rate, speed) on a shared time axis with the 5-95 % band of a large batch, and the
histograms of the batch statistics (binned here: the page holds counts, not values).
"""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np

from .blocks import Section, paragraph, section_id
from .inputs import ReportData, RunSet
from .signals import (
    TIME_SERIES,
    decimated_index,
    find_signal,
    outline_interval,
    plotted_runs,
    run_labels,
    ship_breadth,
    ship_length,
    ship_outlines,
)

__all__ = ["HISTOGRAM_BINS", "LEGEND_HINT", "histogram_figure", "run_colors",
           "timeseries_sections", "track_sections", "typed_array"]

#: Histogram bins of the batch statistics at most (2 √n for n values, at least 5).
HISTOGRAM_BINS = 30


def histogram_figure(groups: dict[str, dict[str, np.ndarray]]) -> dict[str, Any] | None:
    """Histograms (binned here: the page holds the counts, not the values) of the metrics
    with more than one distinct finite value, one subplot per metric on plotly's grid, the
    grid points overlaid with common bins.

    Parameters
    ----------
    groups : dict
        Grid point label ("" for a batch without grid) → metric name → values.

    Returns
    -------
    dict or None
        The figure specification; None if no metric varies.
    """
    first = next(iter(groups.values()))
    names = [m for m in first
             if np.unique(np.concatenate([g[m][np.isfinite(g[m])] for g in groups.values()])
                          ).size > 1]
    if not names:
        return None
    cols = min(3, len(names))
    nrows = math.ceil(len(names) / cols)
    colors = run_colors(len(groups))
    data, layout = [], {}
    for k, name in enumerate(names):
        every = np.concatenate([g[name][np.isfinite(g[name])] for g in groups.values()])
        bins = int(np.clip(2 * math.sqrt(every.size), 5, HISTOGRAM_BINS))
        edges = np.histogram_bin_edges(every, bins=bins)
        suffix = "" if k == 0 else str(k + 1)
        for color, (label, values) in zip(colors, groups.items()):
            v = values[name][np.isfinite(values[name])]
            counts, _ = np.histogram(v, bins=edges)
            data.append({"type": "bar", "x": typed_array(0.5 * (edges[:-1] + edges[1:])),
                         "y": typed_array(counts), "width": float(edges[1] - edges[0]),
                         "name": label or name, "legendgroup": label,
                         "showlegend": bool(label) and k == 0, "opacity": 0.7,
                         "marker": {"color": color}, "xaxis": f"x{suffix}",
                         "yaxis": f"y{suffix}"})
        layout[f"xaxis{suffix}"] = {"title": {"text": name, "font": {"size": 11}}}
        layout[f"yaxis{suffix}"] = {"title": {"text": "runs" if k % cols == 0 else ""}}
    layout.update(grid={"rows": nrows, "columns": cols, "pattern": "independent",
                        "ygap": 0.45, "xgap": 0.12}, barmode="overlay",
                  height=240 * nrows + 40, bargap=0.02, margin=dict(l=50, r=20, t=20, b=40),
                  legend=LEGEND)
    return {"data": data, "layout": layout}


# ------------------------------------------------------------------------------------------
# plots: plotly figure specifications (dicts), drawn by plotly.js in the page
# ------------------------------------------------------------------------------------------
def run_colors(n: int) -> list[str]:
    """Run colours: plotly's 24-colour "Dark24" qualitative palette, repeated as needed.

    Parameters
    ----------
    n : int
        Colours wanted.

    Returns
    -------
    list of str
    """
    from plotly.colors import qualitative

    palette = qualitative.Dark24
    return [palette[i % len(palette)] for i in range(n)]


def typed_array(values: Any) -> dict[str, str]:
    """An array as plotly.js's typed-array spec (``dtype`` and base64 ``bdata``): floats in
    single precision (a plot needs no more; a third of the size of JSON text), integers as
    int32. NaN stays NaN (a break in a line).

    Parameters
    ----------
    values : array_like
        Numbers.

    Returns
    -------
    dict
        ``{"dtype": "f4" or "i4", "bdata": base64 text}``.
    """
    arr = np.asarray(values)
    if np.issubdtype(arr.dtype, np.integer):
        arr, dtype = arr.astype("<i4"), "i4"
    else:
        arr, dtype = arr.astype("<f4"), "f4"
    return {"dtype": dtype, "bdata": base64.b64encode(np.ascontiguousarray(arr).tobytes())
            .decode("ascii")}


def _note_for(run_set: RunSet, shown: np.ndarray, stride_note: str, *, band: bool) -> str:
    n = run_set.n_runs
    parts = []
    if run_set.n_source:  # (a sweep store: the runs read for the plots, not all)
        parts.append(f"{shown.size} of the first {n} of {run_set.n_source} runs drawn (the "
                     "runs read from the store for the plots; spread over them, diverged runs "
                     "first)" + (f"; the band is the 5–95 % range over those {n} runs' ok ones"
                                 if band else ""))
    elif shown.size < n:
        parts.append(f"{shown.size} of {n} runs drawn (spread over the batch, diverged runs "
                     "first)" + ("; the band is the 5–95 % range over all ok runs"
                                 if band else ""))
    if stride_note:
        parts.append(stride_note)
    return "; ".join(parts)


def _stride_note(idx: np.ndarray, n_time: int) -> str:
    if idx.size == n_time:
        return ""
    return f"{idx.size} of {n_time} samples drawn (every {idx[1] - idx[0]}th)"


LEGEND = {"font": {"size": 10}}
#: How the runs are selected (plotly's legend does it).
LEGEND_HINT = ("click a run in the legend to hide or show it in every panel, double-click to "
               "show it alone")


def track_sections(data: ReportData) -> list[Section]:
    """The track in the horizontal plane (east right, north up, equal scales) with hull
    outlines every few seconds; the legend toggles a run.

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
        One per batch with a track (``north``/``east`` or ``x``/``y``).
    """
    sections = []
    for run_set in data.sets:
        runs = run_set.runs
        if runs is None:
            continue
        north, east = find_signal(runs, "north"), find_signal(runs, "east")
        heading = find_signal(runs, "heading")
        if north is None or east is None:
            continue
        time = np.asarray(runs["time"].values, dtype=float)
        status = np.asarray(runs["status"].values).reshape(-1)
        shown = plotted_runs(status)
        idx = decimated_index(time.size)
        labels = run_labels(runs)
        colors = run_colors(shown.size)
        length = ship_length(runs, run_set.metrics)
        note = ""
        if length is None:
            n_vals, e_vals = north.values[shown], east.values[shown]
            extent = float(np.nanmax([np.nanmax(n_vals) - np.nanmin(n_vals),
                                      np.nanmax(e_vals) - np.nanmin(e_vals), 1.0]))
            length = extent / 15.0
            note = (f"ship length not in the file: outlines drawn {length:.3g} m long "
                    "(1/15 of the track's extent)")
        breadth = ship_breadth(runs) or length / 6.5
        interval = outline_interval(float(time[-1] - time[0]))
        traces: list[dict[str, Any]] = []
        for color, i in zip(colors, shown):
            traces.append({"type": "scatter", "mode": "lines", "name": labels[i],
                           "x": typed_array(east.values[i, idx]),
                           "y": typed_array(north.values[i, idx]),
                           "legendgroup": str(i), "line": {"color": color, "width": 1.5}})
            if heading is not None:
                ox, oy = ship_outlines(time, north.values[i], east.values[i], heading.values[i],
                                       length, breadth, interval)
                traces.append({"type": "scatter", "mode": "lines", "name": labels[i] + " hull",
                               "x": typed_array(ox), "y": typed_array(oy),
                               "legendgroup": str(i), "showlegend": False, "hoverinfo": "skip",
                               "line": {"color": color, "width": 1}})
        layout = {"xaxis": {"title": {"text": f"east [{east.units}]"}},
                  "yaxis": {"title": {"text": f"north [{north.units}]"}, "scaleanchor": "x",
                            "scaleratio": 1},
                  "height": 560, "margin": dict(l=60, r=20, t=20, b=50), "legend": LEGEND}
        title = "Track" + (f": {run_set.name}" if len(data.sets) > 1 else "")
        sec = Section(section_id("track", run_set, data), title)
        caption = (f"hull outlines every {interval:g} s, L = {length:.4g} m"
                   + (f"; {note}" if note else ""))
        extra = _note_for(run_set, shown, _stride_note(idx, time.size), band=False)
        sec.blocks.append(paragraph(caption + (f"; {extra}" if extra else ""), cls="caption"))
        sec.blocks.append({"data": traces, "layout": layout})
        sections.append(sec)
    return sections


#: Time-series panels drawn only where the signal changes (a zig-zag's constant rps is none).
_WHEN_VARYING = ("propeller", "engine_order")


def _varies(values: np.ndarray) -> bool:
    finite = values[np.isfinite(values)]
    return finite.size > 0 and float(finite.max() - finite.min()) > 0.0


def timeseries_sections(data: ReportData) -> list[Section]:
    """Heading, rudder angle, yaw rate and speed over time (the signals the result has; the
    propeller rps and engine order where they change, as in a stopping test), one panel each
    on a shared time axis; the legend toggles a run in every panel.

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
        One per batch with time series.
    """
    sections = []
    for run_set in data.sets:
        runs = run_set.runs
        if runs is None:
            continue
        panels = [(label, sig) for role, label in TIME_SERIES
                  if (sig := find_signal(runs, role)) is not None
                  and (role not in _WHEN_VARYING or _varies(sig.values))]
        if not panels:
            continue
        time = np.asarray(runs["time"].values, dtype=float)
        status = np.asarray(runs["status"].values).reshape(-1)
        shown = plotted_runs(status)
        idx = decimated_index(time.size)
        labels = run_labels(runs)
        colors = run_colors(shown.size)
        ok = status == 0
        band = shown.size < run_set.n_runs and bool(ok.any())
        t = typed_array(time[idx])
        traces: list[dict[str, Any]] = []
        layout: dict[str, Any] = {}
        for row, (label, sig) in enumerate(panels, start=1):
            axis = "" if row == 1 else str(row)
            on = {"xaxis": "x", "yaxis": f"y{axis}"}
            if band:
                lo, hi = np.nanquantile(sig.values[ok][:, idx], [0.05, 0.95], axis=0)
                traces.append({"type": "scatter", "mode": "lines", "x": t, "y": typed_array(lo),
                               "line": {"width": 0}, "legendgroup": "band",
                               "showlegend": False, "hoverinfo": "skip", "name": "5 %", **on})
                traces.append({"type": "scatter", "mode": "lines", "x": t, "y": typed_array(hi),
                               "line": {"width": 0}, "fill": "tonexty",
                               "fillcolor": "rgba(120,120,120,0.25)", "legendgroup": "band",
                               "showlegend": row == 1, "hoverinfo": "skip",
                               "name": f"5–95 % of {int(ok.sum())} ok runs", **on})
            for color, i in zip(colors, shown):
                traces.append({"type": "scatter", "mode": "lines", "name": labels[i], "x": t,
                               "y": typed_array(sig.values[i, idx]), "legendgroup": str(i),
                               "showlegend": row == 1, "line": {"color": color, "width": 1.3},
                               **on})
            if label == "heading" and "reference_heading" in runs:
                ref = np.degrees(np.asarray(runs["reference_heading"].values, float))
                traces.append({"type": "scatter", "mode": "lines", "x": t,
                               "y": typed_array(ref[shown[0], idx]),
                               "name": "reference heading",
                               "line": {"color": "black", "dash": "dot", "width": 1}, **on})
            layout[f"yaxis{axis}"] = {"title": {"text": f"{label} [{sig.units}]"}}
        layout["xaxis"] = {"title": {"text": "time [s]"}}
        layout.update(grid={"rows": len(panels), "columns": 1, "pattern": "coupled",
                            "ygap": 0.08},
                      height=220 * len(panels) + 80, margin=dict(l=70, r=20, t=20, b=50),
                      legend=LEGEND, hovermode="x")
        title = "Time series" + (f": {run_set.name}" if len(data.sets) > 1 else "")
        sec = Section(section_id("timeseries", run_set, data), title)
        note = _note_for(run_set, shown, _stride_note(idx, time.size), band=band)
        hint = LEGEND_HINT if shown.size > 1 else ""
        if note or hint:
            sec.blocks.append(paragraph("; ".join(x for x in (note, hint) if x), cls="caption"))
        sec.blocks.append({"data": traces, "layout": layout})
        sections.append(sec)
    return sections
