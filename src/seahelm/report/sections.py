"""The sections of a report, each built from the Datasets of :class:`ReportData`.

A section is a title and a list of blocks: HTML text (tables, built here with every value
escaped) or a plotly figure specification (a dict of traces and layout, drawn by plotly.js in
the page; :mod:`seahelm.report.html` writes it). Each builder in
:data:`SECTIONS` takes the report data and returns its sections (none when the data has nothing
for it), so a new kind of result (e.g. the statistics of a sweep store) is one more builder.

Arrays go into the figures as plotly.js typed arrays (base64, single precision), which keeps a
page of many long runs small.
"""

from __future__ import annotations

import base64
import dataclasses
import html
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .inputs import ReportData, RunSet
from .signals import (
    TIME_SERIES,
    coordinate_text,
    decimated_index,
    find_signal,
    outline_interval,
    plotted_runs,
    run_labels,
    ship_breadth,
    ship_length,
    ship_outlines,
)

__all__ = ["Section", "SECTIONS", "build_sections", "MAX_STATUS_ROWS", "MAX_TABLE_RUNS"]

#: Diverged runs listed one per row (the counts cover all).
MAX_STATUS_ROWS = 500
#: Runs of the per-run summary table.
MAX_TABLE_RUNS = 200
#: Up to this many runs, the summary and metrics tables have a column per run (else a row per
#: run).
MAX_COLUMN_RUNS = 6
#: Histogram bins of the batch statistics at most (2 √n for n values, at least 5).
HISTOGRAM_BINS = 30
#: Grid points of a grid × Monte-Carlo batch whose statistics are shown.
MAX_STAT_GROUPS = 6
#: A batch this large (or any Monte-Carlo batch) gets the statistics section.
STATISTICS_MIN_RUNS = 10

#: Run metadata shown first, in this order (attribute, label, unit).
_METADATA = (("title", "title", ""), ("maneuver", "manoeuvre", ""),
             ("scenario_source", "scenario", ""), ("model", "vessel model", ""),
             ("actuator", "actuator", ""), ("controller", "controller", ""),
             ("integrator", "integrator", ""), ("dt", "step", "s"),
             ("controller_dt", "controller step", "s"), ("t_final", "duration", "s"),
             ("record_every", "recorded every", "steps"), ("seed", "seed", ""),
             ("seahelm_version", "seahelm version", ""), ("created", "created", ""),
             ("wall_time_s", "wall time", "s"), ("compile_time_s", "compile time", "s"))
_HIDDEN = ("scenario_text", "state_labels", "param_types")


@dataclasses.dataclass
class Section:
    """One section of the page.

    Attributes
    ----------
    id : str
        The HTML id (anchor) of the section.
    title : str
        Its heading.
    blocks : list
        HTML strings (already escaped) and plotly figure specifications (dicts), in order.
    """

    id: str
    title: str
    blocks: list[Any] = dataclasses.field(default_factory=list)


# ------------------------------------------------------------------------------------------
# HTML helpers
# ------------------------------------------------------------------------------------------
def _e(value: Any) -> str:
    return html.escape(str(value), quote=True)


def fmt(value: Any, digits: int = 5) -> str:
    """A number in ``digits`` significant digits (— for NaN); anything else as text."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (float, np.floating)):
        return "—" if not math.isfinite(float(value)) else f"{float(value):.{digits}g}"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return str(value)


def table(header: Sequence[str] | None, rows: Sequence[Sequence[Any]], *, cls: str = "",
          row_classes: Sequence[str] | None = None, caption: str = "") -> str:
    """An HTML table, every cell escaped (numbers formatted by :func:`fmt`); no header row if
    ``header`` is None."""
    head = "".join(f"<th>{_e(h)}</th>" for h in header or ())
    body = []
    for i, row in enumerate(rows):
        rc = f' class="{_e(row_classes[i])}"' if row_classes and row_classes[i] else ""
        cells = "".join(
            f'<td class="num">{_e(fmt(v))}</td>' if isinstance(v, (int, float, np.number))
            and not isinstance(v, (bool, np.bool_)) else f"<td>{_e(fmt(v))}</td>" for v in row)
        body.append(f"<tr{rc}>{cells}</tr>")
    cap = f"<caption>{_e(caption)}</caption>" if caption else ""
    klass = f' class="{_e(cls)}"' if cls else ""
    thead = f"<thead><tr>{head}</tr></thead>" if header is not None else ""
    return (f'<div class="table"><table{klass}>{cap}{thead}'
            f"<tbody>{''.join(body)}</tbody></table></div>")


def _p(text: str, cls: str = "") -> str:
    klass = f' class="{_e(cls)}"' if cls else ""
    return f"<p{klass}>{_e(text)}</p>"


def _set_title(run_set: RunSet, data: ReportData) -> str:
    return run_set.name if len(data.sets) > 1 else ""


def _sid(prefix: str, run_set: RunSet, data: ReportData) -> str:
    return prefix if len(data.sets) == 1 else f"{prefix}-{run_set.name}"


def _attrs(run_set: RunSet) -> dict[str, Any]:
    ds = run_set.shaped if run_set.shaped is not None else run_set.metrics
    return {} if ds is None else {str(k): (v.item() if hasattr(v, "item") else v)
                                  for k, v in ds.attrs.items()}


# ------------------------------------------------------------------------------------------
# metadata and status
# ------------------------------------------------------------------------------------------
def overview_sections(data: ReportData) -> list[Section]:
    """Files, run metadata (version, integrator, step, seeds, ...), batch dims and the
    scenario text."""
    sec = Section("overview", "Scenario and run")
    if data.sources:
        sec.blocks.append(table(["file read"], [[s] for s in data.sources], cls="meta"))
    for run_set in data.sets:
        attrs = _attrs(run_set)
        rows: list[list[Any]] = []
        shown = set()
        for key, label, unit in _METADATA:
            if key in attrs:
                value = attrs[key]
                if key == "seed" and str(value) == "-1":
                    value = "none (nothing random in the runs)"
                elif unit:
                    value = f"{fmt(_number(value), 6)} {unit}"
                rows.append([label, value])
                shown.add(key)
        for key, value in attrs.items():
            if key not in shown and key not in _HIDDEN:
                rows.append([key, value])
        if run_set.shaped is not None:
            from ..result_layout import batch_dims

            dims = batch_dims(run_set.shaped)
            sizes = " × ".join(f"{d}={run_set.shaped.sizes[d]}" for d in dims) or "1 run"
            time = np.asarray(run_set.runs["time"].values)
            rows.append(["runs", f"{run_set.n_runs} ({sizes}), {time.size} time samples over "
                                 f"{fmt(float(time[-1] - time[0]), 6)} s"])
            rows.extend(_batch_rows(run_set.shaped, dims))
        title = _set_title(run_set, data)
        sec.blocks.append(table(["", title] if title else None,
                                [[k, str(v)] for k, v in rows], cls="meta"))
        text = attrs.get("scenario_text")
        if text:
            sec.blocks.append(f"<details><summary>scenario text ({len(str(text).splitlines())}"
                              f" lines)</summary><pre>{_e(text)}</pre></details>")
    return [sec]


def _number(value: Any) -> Any:
    try:
        return float(value)
    except (TypeError, ValueError):
        return value


def _batch_rows(ds: Any, dims: tuple[str, ...]) -> list[list[Any]]:
    rows = []
    for dim in dims:
        if dim == "run":  # a plain batch: its runs are numbered, nothing varies by name
            continue
        if dim in ds.coords and ds[dim].ndim == 1:
            c = ds[dim]
            units = str(c.attrs.get("units", ""))
            values = np.asarray(c.values)
            if units == "rad":
                values, units = np.degrees(values), "deg"
            key = c.attrs.get("key", "")
            text = ", ".join(fmt(v) for v in values.tolist()[:50])
            if values.size > 50:
                text += f", … ({values.size} values)"
            rows.append([f"dimension {dim}", (f"{key} = " if key else "") + text
                         + (f" [{units}]" if units else "")])
    for name, var in ds.data_vars.items():
        if var.attrs.get("kind") == "batch_values":
            what = var.attrs.get("distribution", "")
            rows.append(["drawn", f"{name}" + (f" ({what})" if what else "")
                         + (f" [{var.attrs['units']}]" if var.attrs.get("units") else "")])
    return rows


def status_sections(data: ReportData) -> list[Section]:
    """Per-run status: counts by status and every diverged run with its time and reason."""
    sec = Section("status", "Run status")
    for run_set in data.sets:
        if run_set.runs is None:
            continue
        runs = run_set.runs
        status = np.asarray(runs["status"].values).reshape(-1)
        n = status.size
        n_bad = int((status != 0).sum())
        prefix = f"{run_set.name}: " if len(data.sets) > 1 else ""
        sec.blocks.append(_p(f"{prefix}{n} run(s): {n - n_bad} ok, {n_bad} diverged",
                             cls="status-line " + ("bad" if n_bad else "good")))
        if not n_bad:
            continue
        times = (np.asarray(runs["failure_time"].values, float).reshape(-1)
                 if "failure_time" in runs else np.full(n, np.nan))
        reasons = _reasons(runs, status)
        labels = run_labels(runs)
        bad = np.flatnonzero(status != 0)
        counts: dict[str, int] = {}
        for i in bad:
            counts[reasons[i]] = counts.get(reasons[i], 0) + 1
        sec.blocks.append(table(["reason", "runs"], [[k, v] for k, v in counts.items()],
                                cls="status-counts"))
        shown = bad[:MAX_STATUS_ROWS]
        caption = "" if bad.size <= MAX_STATUS_ROWS else (
            f"first {MAX_STATUS_ROWS} of {bad.size} diverged runs (all are in the result "
            "file: seahelm inspect --json)")
        sec.blocks.append(table(["run", "diverged at [s]", "reason"],
                                [[labels[i], float(times[i]), reasons[i]] for i in shown],
                                cls="diverged", caption=caption))
    return [sec] if sec.blocks else []


def _reasons(runs: Any, status: np.ndarray) -> list[str]:
    if "status_message" in runs:
        messages = [str(m) for m in np.asarray(runs["status_message"].values).reshape(-1)]
    else:
        messages = ["ok" if s == 0 else f"status {s}" for s in status]
    return [m.split(" at t = ")[0].removeprefix("diverged: ") for m in messages]


# ------------------------------------------------------------------------------------------
# IMO and manoeuvre metrics
# ------------------------------------------------------------------------------------------
def imo_sections(data: ReportData) -> list[Section]:
    """The IMO MSC.137(76) criteria: value, limit, margin and pass/fail per side."""
    imo = data.imo
    if imo is None:
        return []
    a = imo.attrs
    verdict = "PASSES" if a["passed"] else "FAILS"
    sec = Section("imo", "IMO MSC.137(76) criteria")
    sec.blocks.append(_p(f"{a['ship']} (L = {fmt(a['length_m'])} m, V = {fmt(a['speed_mps'], 4)}"
                         f" m/s, L/V = {fmt(a['L_over_V_s'], 4)} s) {verdict} the evaluated "
                         "criteria", cls="verdict " + ("good" if a["passed"] else "bad")))
    rows, classes = [], []
    for i in range(imo.sizes["row"]):
        r = {k: imo[k].values[i].item() for k in imo.data_vars}
        unit = r["unit"]
        values = [r["value"], r["limit"], r["margin"]]
        if unit == "rad":
            values, unit = [math.degrees(v) for v in values], "deg"
        rows.append([r["ability"], r["criterion"], r["side"], *values, unit, r["status"],
                     r["note"]])
        classes.append({"pass": "pass", "fail": "fail"}.get(r["status"], "not-evaluated"))
    sec.blocks.append(table(["ability", "criterion", "side", "value", "limit", "margin", "unit",
                             "status", "note"], rows, cls="imo", row_classes=classes))
    notes = [n for n in str(a.get("notes", "")).splitlines() if n]
    if notes:
        sec.blocks.append("<ul class='notes'>" + "".join(f"<li>{_e(n)}</li>" for n in notes)
                          + "</ul>")
    return [sec]


def metrics_sections(data: ReportData) -> list[Section]:
    """A manoeuvre's metrics (one column per run) or a simulation's per-run summary."""
    sec = Section("metrics", "Metrics")
    for run_set in data.sets:
        if run_set.metrics is not None:
            sec.blocks.extend(_maneuver_metrics(run_set, data))
        elif run_set.shaped is not None:
            sec.blocks.extend(_summary_metrics(run_set))
    return [sec] if sec.blocks else []


def _maneuver_metrics(run_set: RunSet, data: ReportData) -> list[str]:
    from ..analysis.maneuvers import metrics_rows

    m = run_set.metrics
    rows = metrics_rows(m)
    if not rows:
        return []
    batch = list(m["complete"].dims)
    labels = []
    for row in rows:
        parts = [_coord_label(k, row.get(k), m) for k in batch]
        for extra in ("rudder", "trigger"):
            if extra in row and extra not in batch and "pair" in batch:
                parts.append(_coord_label(extra, row[extra], m))
        labels.append(", ".join(parts) or "run")
    skip = set(batch) | {"rudder", "trigger", "ship", "n"}
    long_tables, long_vars = _long_dim_tables(m, batch) if len(rows) == 1 else ([], set())
    out_rows = []
    for key in rows[0]:
        if key in skip:
            continue
        base = key.rsplit("_", 1)[0] if key not in m.variables else key
        if base in long_vars:
            continue
        units = str(m[base].attrs.get("units", "")) if base in m.variables else ""
        values = [row.get(key) for row in rows]
        if units in ("rad", "rad/s"):
            values = [math.degrees(v) if isinstance(v, float) else v for v in values]
            units = {"rad": "deg", "rad/s": "deg/s"}[units]
        if key == "complete":
            values = [bool(v) for v in values]
        out_rows.append([f"{key} [{units}]" if units else key, *values])
    caption = f"{run_set.name}: {len(rows)} run(s)"
    if len(rows) <= MAX_COLUMN_RUNS:  # metrics down, runs across
        return [table(["metric", *labels], out_rows, cls="metrics", caption=caption),
                *long_tables]
    shown = min(len(rows), MAX_TABLE_RUNS)  # runs down (a spiral's steps, a large batch)
    if shown < len(rows):
        caption += f"; the first {shown} shown"
    return [table(["run", *(r[0] for r in out_rows)],
                  [[labels[j], *(r[j + 1] for r in out_rows)] for j in range(shown)],
                  cls="metrics", caption=caption)]


def _display(var: Any) -> tuple[str, np.ndarray]:
    """A variable's values and units for a table (radians in degrees)."""
    units = str(var.attrs.get("units", ""))
    values = np.asarray(var.values)
    if units in ("rad", "rad/s") and values.dtype.kind == "f":
        return units.replace("rad", "deg"), np.degrees(values)
    return units, values


def _long_dim_tables(m: Any, batch: list[str]) -> tuple[list[str], set[str]]:
    """Metrics of one run along a dimension of their own longer than 4 (a spiral's steps): a
    table with a row per index (its coordinates first); and the names of those variables."""
    out, names = [], set()
    for dim in [d for d in m.dims if d not in batch and m.sizes[d] > 4]:
        columns = [(str(n), v) for n, v in m.coords.items() if v.dims == (dim,) and n != dim]
        columns += [(str(n), v) for n, v in m.data_vars.items() if v.dims == (dim,)]
        if not columns:
            continue
        header, data = [dim], [np.arange(m.sizes[dim])]
        for name, var in columns:
            units, values = _display(var)
            header.append(f"{name} [{units}]" if units else name)
            data.append(values)
            names.add(name)
        out.append(table(header, [[_plain(col[i]) for col in data]
                                  for i in range(m.sizes[dim])],
                         cls="metrics", caption=f"per {dim}"))
    return out, names


def _plain(value: Any) -> Any:
    return value.item() if hasattr(value, "item") else value


def _coord_label(key: str, value: Any, ds: Any) -> str:
    units = str(ds[key].attrs.get("units", "")) if key in ds.variables else ""
    if key == "side" and value in (1, -1):
        return "starboard" if value == 1 else "port"
    if units == "rad" and isinstance(value, float):
        return f"{key} {math.degrees(value):.4g}°"
    return f"{key} {fmt(value, 4)}"


def _summary_metrics(run_set: RunSet) -> list[str]:
    summary = run_set.summary
    if not summary:
        return []
    labels = run_labels(run_set.runs)
    keys = [k for k in summary[0] if k != "run"]
    if len(summary) <= MAX_COLUMN_RUNS:  # metrics down, runs across
        return [table(["metric", *labels[:len(summary)]],
                      [[k.replace("_", " "), *(row.get(k, "") for row in summary)]
                       for k in keys], cls="summary")]
    shown = summary[:MAX_TABLE_RUNS]
    caption = "" if len(summary) <= MAX_TABLE_RUNS else (
        f"first {MAX_TABLE_RUNS} of {len(summary)} runs (the statistics below cover all)")
    return [table(["run", *(k.replace("_", " ") for k in keys)],
                  [[labels[i], *(row.get(k, "") for k in keys)] for i, row in enumerate(shown)],
                  cls="summary", caption=caption)]


def _grid_groups(shaped: Any, n_runs: int) -> dict[str, np.ndarray]:
    """The runs of each grid point of a Monte-Carlo batch (its batch dims other than
    ``sample``), labelled by the point's coordinates; one group of all runs otherwise."""
    from ..result_layout import batch_dims

    dims = batch_dims(shaped)
    others = [k for k, d in enumerate(dims) if d != "sample"] if "sample" in dims else []
    if not others:
        return {"": np.arange(n_runs)}
    index = np.unravel_index(np.arange(n_runs), [shaped.sizes[d] for d in dims])
    groups: dict[str, list[int]] = {}
    for i in range(n_runs):
        parts = []
        for k in others:
            d, j = dims[k], int(index[k][i])
            if d in shaped.coords and shaped[d].ndim == 1:
                c = shaped[d]
                parts.append(coordinate_text(d, c.values[j].item(), str(c.attrs.get("units", ""))))
            else:
                parts.append(f"{d} {j}")
        groups.setdefault(", ".join(parts), []).append(i)
    return {k: np.asarray(v) for k, v in groups.items()}


def statistics_sections(data: ReportData) -> list[Section]:
    """Distribution of the summary metrics over the ok runs of a large or Monte-Carlo batch,
    per grid point of a grid × Monte-Carlo batch (the first :data:`MAX_STAT_GROUPS`):
    quantile tables and histograms."""
    from ..analysis.statistics import DEFAULT_QUANTILES, metric_statistics, quantile_name

    sections = []
    for run_set in data.sets:
        if run_set.shaped is None or run_set.metrics is not None:
            continue
        if run_set.n_runs < STATISTICS_MIN_RUNS and "sample" not in run_set.shaped.dims:
            continue
        summary = run_set.summary
        status = np.asarray(run_set.runs["status"].values).reshape(-1)
        metrics = [k for k, v in summary[0].items() if k != "run"
                   and isinstance(v, (int, float)) and not isinstance(v, bool)]
        groups = _grid_groups(run_set.shaped, status.size)
        sec = Section(_sid("statistics", run_set, data), "Batch statistics")
        shown = list(groups.items())[:MAX_STAT_GROUPS]
        qnames = [quantile_name(q) for q in DEFAULT_QUANTILES]
        rows, values_by_group = [], {}
        counts = []
        for label, runs in shown:
            ok = runs[status[runs] == 0]
            counts.append(f"{label + ': ' if label else ''}{ok.size} ok of {runs.size}")
            values = {m: np.array([float(summary[i][m]) for i in ok]) for m in metrics}
            values_by_group[label] = values
            if not ok.size:
                rows.append(([label] if label else []) + ["(no ok run: no metrics)"])
                continue
            for m, s in metric_statistics(values).items():
                rows.append(([label] if label else []) + [m, s["n"], s["mean"], s["std"],
                                                          s["min"], *(s[q] for q in qnames),
                                                          s["max"]])
        note = "over the ok runs: " + "; ".join(counts)
        if len(groups) > len(shown):
            note += f" (first {len(shown)} of {len(groups)} grid points)"
        sec.blocks.append(_p(note))
        header = (["grid point"] if len(shown) > 1 or shown[0][0] else []) + [
            "metric", "n", "mean", "std", "min", *qnames, "max"]
        sec.blocks.append(table(header, rows, cls="statistics"))
        fig = _histograms(values_by_group)
        if fig is not None:
            sec.blocks.append(fig)
        sections.append(sec)
    return sections


def _histograms(groups: dict[str, dict[str, np.ndarray]]) -> dict[str, Any] | None:
    """Histograms (binned here: the page holds the counts, not the values) of the metrics
    with more than one distinct finite value, one subplot per metric on plotly's grid, the
    grid points overlaid with common bins."""
    first = next(iter(groups.values()))
    names = [m for m in first
             if np.unique(np.concatenate([g[m][np.isfinite(g[m])] for g in groups.values()])
                          ).size > 1]
    if not names:
        return None
    cols = min(3, len(names))
    nrows = math.ceil(len(names) / cols)
    colors = _colors(len(groups))
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
                  legend=_LEGEND)
    return {"data": data, "layout": layout}


# ------------------------------------------------------------------------------------------
# plots: plotly figure specifications (dicts), drawn by plotly.js in the page
# ------------------------------------------------------------------------------------------
def _colors(n: int) -> list[str]:
    """Run colours: plotly's 24-colour "Dark24" qualitative palette."""
    from plotly.colors import qualitative

    palette = qualitative.Dark24
    return [palette[i % len(palette)] for i in range(n)]


def typed_array(values: Any) -> dict[str, str]:
    """An array as plotly.js's typed-array spec (``dtype`` and base64 ``bdata``): floats in
    single precision (a plot needs no more; a third of the size of JSON text), integers as
    int32. NaN stays NaN (a break in a line)."""
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
    if shown.size < n:
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


_LEGEND = {"font": {"size": 10}}
#: How the runs are selected (plotly's legend does it).
LEGEND_HINT = ("click a run in the legend to hide or show it in every panel, double-click to "
               "show it alone")


def track_sections(data: ReportData) -> list[Section]:
    """The track in the horizontal plane (east right, north up, equal scales) with hull
    outlines every few seconds; the legend toggles a run."""
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
        colors = _colors(shown.size)
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
                  "height": 560, "margin": dict(l=60, r=20, t=20, b=50), "legend": _LEGEND}
        title = "Track" + (f": {run_set.name}" if len(data.sets) > 1 else "")
        sec = Section(_sid("track", run_set, data), title)
        caption = (f"hull outlines every {interval:g} s, L = {length:.4g} m"
                   + (f"; {note}" if note else ""))
        extra = _note_for(run_set, shown, _stride_note(idx, time.size), band=False)
        sec.blocks.append(_p(caption + (f"; {extra}" if extra else ""), cls="caption"))
        sec.blocks.append({"data": traces, "layout": layout})
        sections.append(sec)
    return sections


def timeseries_sections(data: ReportData) -> list[Section]:
    """Heading, rudder angle, yaw rate and speed over time (the signals the result has), one
    panel each on a shared time axis; the legend toggles a run in every panel."""
    sections = []
    for run_set in data.sets:
        runs = run_set.runs
        if runs is None:
            continue
        panels = [(label, sig) for role, label in TIME_SERIES
                  if (sig := find_signal(runs, role)) is not None]
        if not panels:
            continue
        time = np.asarray(runs["time"].values, dtype=float)
        status = np.asarray(runs["status"].values).reshape(-1)
        shown = plotted_runs(status)
        idx = decimated_index(time.size)
        labels = run_labels(runs)
        colors = _colors(shown.size)
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
                      legend=_LEGEND, hovermode="x")
        title = "Time series" + (f": {run_set.name}" if len(data.sets) > 1 else "")
        sec = Section(_sid("timeseries", run_set, data), title)
        note = _note_for(run_set, shown, _stride_note(idx, time.size), band=band)
        hint = LEGEND_HINT if shown.size > 1 else ""
        if note or hint:
            sec.blocks.append(_p("; ".join(x for x in (note, hint) if x), cls="caption"))
        sec.blocks.append({"data": traces, "layout": layout})
        sections.append(sec)
    return sections


#: The section builders, in page order.
SECTIONS: tuple[Callable[[ReportData], list[Section]], ...] = (
    overview_sections, status_sections, imo_sections, metrics_sections, statistics_sections,
    track_sections, timeseries_sections)


def build_sections(data: ReportData) -> list[Section]:
    """Every section of the report, in page order (:data:`SECTIONS`).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    return [s for builder in SECTIONS for s in builder(data)]
