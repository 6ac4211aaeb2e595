"""The sections of a report, each built from the Datasets of :class:`ReportData`.

A section (:class:`~seahelm.report.blocks.Section`) is a title and a list of blocks: HTML text
(tables, built with every value escaped) or a plotly figure specification
(:mod:`seahelm.report.figures`). Each builder in :data:`SECTIONS` takes the report data and
returns its sections (none when the data has nothing for it), so a new kind of result (e.g. the
statistics of a sweep store) is one more builder. This module holds the tabular sections --
scenario and run metadata, per-run status, IMO criteria, a manoeuvre's metrics -- and the page
order; a batch's per-run table and statistics and a sweep store's section are in
:mod:`~seahelm.report.batch`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..units import metric_label, to_display
from .batch import (
    MAX_COLUMN_RUNS,
    row_tables,
    run_table_blocks,
    statistics_blocks,
    statistics_sections,
    sweep_sections,
)
from .blocks import Section, escape, fmt, paragraph, run_attrs, set_title, subheading, table
from .figures import timeseries_sections, track_sections
from .imo_ensemble import ensemble_sections
from .encounters import encounter_sections
from .dp_capability import dp_capability_sections
from .replay import replay_sections
from .seakeeping import seakeeping_sections
from .seakeeping_sweep import sweep_seakeeping_sections
from .inputs import ReportData, RunSet
from .signals import run_labels

__all__ = ["Section", "SECTIONS", "build_sections", "MAX_STATUS_ROWS", "MAX_TABLE_RUNS",
           "statistics_sections", "sweep_sections"]

#: Diverged runs listed one per row (the counts cover all).
MAX_STATUS_ROWS = 500
#: Runs of a manoeuvre's metrics table with a row per run (a spiral's steps, a batch).
MAX_TABLE_RUNS = 200
#: A manoeuvre batch of more runs is listed in part (its first :data:`MAX_LISTED_OF_MANY`
#: runs) with the statistics of all.
MAX_LISTED = 50
MAX_LISTED_OF_MANY = 20

#: Run metadata shown first, in this order (attribute, label, unit).
_METADATA = (("title", "title", ""), ("maneuver", "manoeuvre", ""),
             ("scenario_source", "scenario", ""), ("model", "vessel model", ""),
             ("actuator", "actuator", ""), ("controller", "controller", ""),
             ("integrator", "integrator", ""), ("dt", "step", "s"),
             ("controller_dt", "controller step", "s"), ("t_final", "duration", "s"),
             ("record_every", "recorded every", "steps"), ("seed", "seed", ""),
             ("seahelm_version", "seahelm version", ""), ("created", "created", ""),
             ("wall_time_s", "wall time", "s"), ("compile_time_s", "compile time", "s"),
             ("actuator_step", "actuator step", ""), ("execution", "loop", ""),
             ("seahelm_checksums", "checksums", ""))
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
        for key, value in attrs.items():  # (words, not attribute names: "first order")
            if key not in shown and key not in _HIDDEN:
                rows.append([str(key).replace("_", " "), value])
        if run_set.shaped is not None:
            from ..result_layout import batch_dims

            dims = batch_dims(run_set.shaped)
            sizes = " × ".join(f"{d}={run_set.shaped.sizes[d]}" for d in dims) or "1 run"
            time = np.asarray(run_set.runs["time"].values)
            rows.append(["runs", f"{run_set.n_runs} ({sizes}), {time.size} time samples over "
                                 f"{fmt(float(time[-1] - time[0]), 6)} s"])
            rows.extend(_batch_rows(run_set.shaped, dims))
        title = set_title(run_set, data)
        if rows:  # (a sweep's runs: their metadata is the store's, in its own section)
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
            values, units = to_display(np.asarray(c.values), units, dim)
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
    """Per-run status: counts by status and every diverged run with its time and reason (of
    every run written to a sweep store, not only of those read for the plots)."""
    sec = Section("status", "Run status")
    sources = [(s.name, s.runs) for s in data.sets if s.runs is not None]
    sweep = data.sweep
    if sweep is not None and "status" in sweep:
        written = (np.asarray(sweep["complete"].values).reshape(sweep.sizes["run"], -1)
                   .all(axis=1) if "complete" in sweep else np.ones(sweep.sizes["run"], bool))
        sources = [("store", sweep.isel(run=np.flatnonzero(written)))]
    for name, runs in sources:
        status = np.asarray(runs["status"].values).reshape(-1)
        n = status.size
        n_bad = int((status != 0).sum())
        prefix = f"{name}: " if len(sources) > 1 else ""
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
    from ..results import STATUS_TEXT

    if "status_message" in runs:
        messages = [str(m) for m in np.asarray(runs["status_message"].values).reshape(-1)]
    else:  # (a sweep store keeps the codes)
        messages = [STATUS_TEXT.get(int(s), f"status {s}") for s in status]
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
        shown = [to_display(r[k], unit) for k in ("value", "limit", "margin")]
        values, unit = [v for v, _ in shown], shown[0][1]
        rows.append([r["ability"], r["criterion"], r["side"], *values, unit, r["status"],
                     r["note"]])
        classes.append({"pass": "pass", "fail": "fail"}.get(r["status"], "not-evaluated"))
    header = ["ability", "criterion", "side", "value", "limit", "margin", "unit", "status",
              "note"]
    if not any(str(r[-1]).strip() for r in rows):  # (no column of blanks)
        header, rows = header[:-1], [r[:-1] for r in rows]
    sec.blocks.append(table(header, rows, cls="imo", row_classes=classes))
    notes = [n for n in str(a.get("notes", "")).splitlines() if n]
    if notes:
        sec.blocks.append("<ul class='notes'>" + "".join(f"<li>{escape(n)}</li>" for n in notes)
                          + "</ul>")
    return [sec]


def metrics_sections(data: ReportData) -> list[Section]:
    """A manoeuvre's metrics (one column per run; a row per run in a large batch, with their
    statistics) or a simulation's per-run summary (:func:`~seahelm.report.batch.
    run_table_blocks`); every metric labelled with its display unit and shown in it."""
    sec = Section("metrics", "Metrics")
    for run_set in data.sets:
        if run_set.metrics is not None:
            blocks = _maneuver_metrics(run_set, data)
        elif run_set.shaped is not None:
            blocks = run_table_blocks(run_set)
        else:
            continue
        if blocks and len(data.sets) > 1 and run_set.metrics is None:
            sec.blocks.append(subheading(run_set.name))  # (a manoeuvre's caption names it)
        sec.blocks.extend(blocks)
    return [sec] if sec.blocks else []


def _maneuver_metrics(run_set: RunSet, data: ReportData) -> list[Any]:
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
        values = [to_display(row.get(key), units, key)[0] for row in rows]
        if key == "complete":
            values = [bool(v) for v in values]
        out_rows.append([metric_label(key, units), *values])
    caption = f"{run_set.name}: {len(rows)} run(s)"
    if len(rows) <= MAX_COLUMN_RUNS:  # metrics down, runs across
        return [table(["metric", *labels], out_rows, cls="metrics", caption=caption),
                *long_tables]
    # runs down (a spiral's steps, a batch): a large batch's first runs and its statistics
    many = len(rows) > MAX_LISTED
    shown = min(len(rows), MAX_LISTED_OF_MANY if many else MAX_TABLE_RUNS)
    if shown < len(rows):
        caption += f"; the first {shown} shown, the statistics below cover all"
    out: list[Any] = row_tables([("run", labels)], [(r[0], r[1:]) for r in out_rows],
                                range(shown), caption, cls="metrics")
    numeric = {r[0]: np.asarray(r[1:], dtype=float) for r in out_rows
               if r[0] != "complete" and all(isinstance(v, (int, float))
                                             and not isinstance(v, bool) for v in r[1:])}
    if many and numeric:
        ok = np.array([bool(row.get("complete", True)) for row in rows])
        out.extend(statistics_blocks(numeric, ok, f"the {int(ok.sum())} complete of "
                                                  f"{len(rows)} runs"))
    return out


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
            units = str(var.attrs.get("units", ""))
            header.append(metric_label(name, units))
            data.append(to_display(np.asarray(var.values), units, name)[0])
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
        return f"{key} {to_display(value, units)[0]:.4g}°"
    return f"{key} {fmt(value, 4)}"


#: The section builders, in page order: an IMO check's verdict (and an ensemble's
#: probabilities) first, before the metadata tables it sat below.
SECTIONS: tuple[Callable[[ReportData], list[Section]], ...] = (
    imo_sections, ensemble_sections, overview_sections, sweep_sections, status_sections,
    seakeeping_sections, sweep_seakeeping_sections, replay_sections, encounter_sections,
    dp_capability_sections,
    metrics_sections, statistics_sections,
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
