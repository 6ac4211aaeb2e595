"""The sections of a report, each built from the Datasets of :class:`ReportData`.

A section (:class:`~seahelm.report.blocks.Section`) is a title and a list of blocks: HTML text
(tables, built with every value escaped) or a plotly figure specification
(:mod:`seahelm.report.figures`). Each builder in :data:`SECTIONS` takes the report data and
returns its sections (none when the data has nothing for it), so a new kind of result (e.g. the
statistics of a sweep store) is one more builder. This module holds the tabular sections --
scenario and run metadata, per-run status, IMO criteria, metrics, batch statistics -- and the
page order.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .blocks import Section, escape, fmt, paragraph, run_attrs, section_id, set_title, table
from .figures import histogram_figure, timeseries_sections, track_sections
from .imo_ensemble import ensemble_sections
from .inputs import ReportData, RunSet
from .signals import coordinate_text, run_labels

__all__ = ["Section", "SECTIONS", "build_sections", "MAX_STATUS_ROWS", "MAX_TABLE_RUNS"]

#: Diverged runs listed one per row (the counts cover all).
MAX_STATUS_ROWS = 500
#: Runs of the per-run summary table.
MAX_TABLE_RUNS = 200
#: Up to this many runs, the summary and metrics tables have a column per run (else a row per
#: run).
MAX_COLUMN_RUNS = 6
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
        attrs = run_attrs(run_set)
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
        title = set_title(run_set, data)
        sec.blocks.append(table(["", title] if title else None,
                                [[k, str(v)] for k, v in rows], cls="meta"))
        text = attrs.get("scenario_text")
        if text:
            sec.blocks.append(f"<details><summary>scenario text ({len(str(text).splitlines())}"
                              f" lines)</summary><pre>{escape(text)}</pre></details>")
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
        sec.blocks.append(paragraph(f"{prefix}{n} run(s): {n - n_bad} ok, {n_bad} diverged",
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
    text = (f"{a['ship']} (L = {fmt(a['length_m'])} m, V = {fmt(a['speed_mps'], 4)} m/s, "
            f"L/V = {fmt(a['L_over_V_s'], 4)} s) {verdict} the evaluated criteria")
    sec.blocks.append(paragraph(text, cls="verdict " + ("good" if a["passed"] else "bad")))
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
        sec.blocks.append("<ul class='notes'>" + "".join(f"<li>{escape(n)}</li>" for n in notes)
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


def _grid_labels(shaped: Any, n_runs: int) -> list[str]:
    """Each run's grid point label of a Monte-Carlo batch (its batch dims other than
    ``sample``, by their coordinates); "" for every run otherwise."""
    from ..result_layout import batch_dims

    dims = batch_dims(shaped)
    others = [k for k, d in enumerate(dims) if d != "sample"] if "sample" in dims else []
    if not others:
        return [""] * n_runs
    index = np.unravel_index(np.arange(n_runs), [shaped.sizes[d] for d in dims])
    labels = []
    for i in range(n_runs):
        parts = []
        for k in others:
            d, j = dims[k], int(index[k][i])
            if d in shaped.coords and shaped[d].ndim == 1:
                c = shaped[d]
                parts.append(coordinate_text(d, c.values[j].item(), str(c.attrs.get("units", ""))))
            else:
                parts.append(f"{d} {j}")
        labels.append(", ".join(parts))
    return labels


def statistics_sections(data: ReportData) -> list[Section]:
    """Distribution of the summary metrics over the ok runs of a large or Monte-Carlo batch,
    per grid point of a grid × Monte-Carlo batch (the first :data:`MAX_STAT_GROUPS`):
    quantile tables and histograms (:func:`seahelm.analysis.statistics.batch_statistics`)."""
    from ..analysis.statistics import (
        DEFAULT_QUANTILES,
        batch_statistics,
        group_runs,
        numeric_keys,
        quantile_name,
    )

    sections = []
    for run_set in data.sets:
        if run_set.shaped is None or run_set.metrics is not None:
            continue
        if run_set.n_runs < STATISTICS_MIN_RUNS and "sample" not in run_set.shaped.dims:
            continue
        summary = run_set.summary
        status = np.asarray(run_set.runs["status"].values).reshape(-1)
        metrics = numeric_keys(summary[0], skip={"run"})
        groups = group_runs(_grid_labels(run_set.shaped, status.size))
        sec = Section(section_id("statistics", run_set, data), "Batch statistics")
        shown = dict(list(groups.items())[:MAX_STAT_GROUPS])
        qnames = [quantile_name(q) for q in DEFAULT_QUANTILES]
        columns = {m: np.array([float(row[m]) for row in summary]) for m in metrics}
        rows, values_by_group = [], {}
        counts = []
        for entry in batch_statistics(columns, ok=status == 0, groups=shown):
            label, ok = entry["key"], entry["ok_runs"]
            counts.append(f"{label + ': ' if label else ''}{entry['n_ok']} ok of "
                          f"{entry['n_runs']}")
            values_by_group[label] = {m: v[ok] for m, v in columns.items()}
            if not entry["n_ok"]:
                rows.append(([label] if label else []) + ["(no ok run: no metrics)"])
                continue
            for m, s in entry["metrics"].items():
                rows.append(([label] if label else []) + [m, s["n"], s["mean"], s["std"],
                                                          s["min"], *(s[q] for q in qnames),
                                                          s["max"]])
        note = "over the ok runs: " + "; ".join(counts)
        if len(groups) > len(shown):
            note += f" (first {len(shown)} of {len(groups)} grid points)"
        sec.blocks.append(paragraph(note))
        header = (["grid point"] if len(shown) > 1 or next(iter(shown)) else []) + [
            "metric", "n", "mean", "std", "min", *qnames, "max"]
        sec.blocks.append(table(header, rows, cls="statistics"))
        fig = histogram_figure(values_by_group)
        if fig is not None:
            sec.blocks.append(fig)
        sections.append(sec)
    return sections


#: Metric columns of a sweep shown as histograms (the statistics table lists them all).
MAX_SWEEP_HISTOGRAMS = 12


def sweep_sections(data: ReportData) -> list[Section]:
    """A sweep store: its state (chunks written), metadata and scenario text, the summary
    statistics of every metric over the runs (stored with a complete sweep, else computed
    from the chunks written) and their histograms."""
    import json

    ds = data.sweep
    if ds is None:
        return []
    from ..sweep.run import summary_statistics

    attrs = dict(ds.attrs)
    sec = Section("sweep", "Sweep")
    n_runs, n_chunks = int(ds.sizes["run"]), int(attrs.get("sweep_n_chunks", 0) or 0)
    if "complete" in ds:
        flags = np.asarray(ds["complete"].values).reshape(n_runs, -1).all(axis=1)
        state = f"incomplete: {int(flags.sum())} of {n_runs} runs written"
    else:
        flags = np.ones(n_runs, bool)
        state = "complete"
    rows = [["state", state], ["runs", n_runs],
            ["chunks", f"{n_chunks} of up to {attrs.get('sweep_chunk_size')} runs each"]]
    rows += [[k, v] for k, v in attrs.items() if not k.startswith("sweep_")
             and k not in _HIDDEN and k != "scenario_text" and len(str(v)) < 200]
    sec.blocks.append(table(None, [[k, str(v)] for k, v in rows], cls="meta"))
    if attrs.get("scenario_text"):
        text = str(attrs["scenario_text"])
        sec.blocks.append(f"<details><summary>scenario text ({len(text.splitlines())} lines)"
                          f"</summary><pre>{escape(text)}</pre></details>")
    summary = (json.loads(attrs["sweep_summary"]) if "sweep_summary" in attrs
               else summary_statistics(ds.isel(run=np.flatnonzero(flags))))
    if "n_ok" in summary:
        sec.blocks.append(paragraph(f"{summary['n_ok']} ok, {summary['n_failed']} failed of "
                                    f"{summary['n_runs']} runs"))
    qnames = sorted(k for k in (summary["metrics"][0] if summary["metrics"] else {})
                    if k.startswith("q") and k[1:].isdigit())
    header = ["metric", "where", "unit", "n", "mean", "std", "min", *qnames, "max"]
    sec.blocks.append(table(header, [[m["name"], m["where"], m.get("units", ""), m["n"],
                                      *(fmt(m[k]) for k in ("mean", "std", "min")),
                                      *(fmt(m[q]) for q in qnames), fmt(m["max"])]
                                     for m in summary["metrics"]], cls="statistics"))
    columns: dict[str, np.ndarray] = {}
    for name in sorted(ds.data_vars):
        var = ds[name]
        if var.attrs.get("kind") != "metric" or var.dims[:1] != ("run",):
            continue
        values = np.asarray(var.values, dtype=float)[flags]
        for idx in np.ndindex(*values.shape[1:]):
            where = ", ".join(f"{d}={_plain(ds[d].values[i]) if d in ds.coords else i}"
                              for d, i in zip(var.dims[1:], idx))
            columns[f"{name} ({where})" if where else name] = values[(slice(None), *idx)]
            if len(columns) == MAX_SWEEP_HISTOGRAMS:
                break
        if len(columns) == MAX_SWEEP_HISTOGRAMS:
            break
    fig = histogram_figure({"": columns}) if columns else None
    if fig is not None:
        sec.blocks.append(fig)
    return [sec]


#: The section builders, in page order.
SECTIONS: tuple[Callable[[ReportData], list[Section]], ...] = (
    overview_sections, sweep_sections, status_sections, imo_sections, ensemble_sections,
    metrics_sections, statistics_sections, track_sections, timeseries_sections)


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
