"""The report's sections of a batch of runs: the per-run table, the batch statistics with
their histograms, the inputs drawn for a Monte-Carlo batch, and a sweep store.

Every metric is labelled in words with its display unit and shown in it
(:mod:`seahelm.units`: angles in degrees, fractions in per cent), each angle once and no
filter's internal state; a metric no run reached is named under its table, not given an
empty column. No table is wider than the page at 1,280 px: the per-run table of a large
batch lists the runs drawn in the plots (at most
:data:`~seahelm.report.signals.MAX_RUNS_PLOTTED`: diverged runs first, the rest spread over
the batch) with their drawn values, and at most :data:`MAX_TABLE_COLUMNS` columns per table
(the further metrics in a table below it); the statistics cover every run. The values drawn
for a Monte-Carlo batch (``kind = "batch_values"``) get their own statistics and histograms.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..units import (label, metric_label, metric_unit, noted_unreached, shown_metrics,
                     to_display)
from .blocks import Section, escape, paragraph, section_id, subheading, table
from .figures import histogram_figure
from .inputs import ReportData, RunSet
from .signals import coordinate_text, plotted_runs, run_labels

__all__ = ["MAX_COLUMN_RUNS", "MAX_TABLE_COLUMNS", "MAX_STAT_GROUPS", "STATISTICS_MIN_RUNS",
           "MAX_SWEEP_HISTOGRAMS", "signal_units", "drawn_values", "drawn_blocks",
           "run_table_blocks", "row_tables", "statistics_blocks", "statistics_sections",
           "sweep_sections"]

#: Up to this many runs, the per-run table has a column per run (else a row per run).
MAX_COLUMN_RUNS = 6
#: Columns of one per-run table at most (its further metrics go to a table below it).
MAX_TABLE_COLUMNS = 12
#: Grid points of a grid × Monte-Carlo batch whose statistics are shown.
MAX_STAT_GROUPS = 6
#: A batch this large (or any Monte-Carlo batch) gets the statistics section.
STATISTICS_MIN_RUNS = 10
#: Metric columns of a sweep shown as histograms (the statistics table lists them all).
MAX_SWEEP_HISTOGRAMS = 12
#: Significant digits of the numbers in the batch tables.
DIGITS = 4


# ------------------------------------------------------------------------------------------
# what a batch holds
# ------------------------------------------------------------------------------------------
def signal_units(ds: Any) -> dict[str, str]:
    """The units of a result's signals and parameters by name (not of its metrics).

    Parameters
    ----------
    ds : xarray.Dataset
        A result or a sweep store.

    Returns
    -------
    dict of str to str
    """
    return {str(n): str(v.attrs["units"]) for n, v in ds.data_vars.items()
            if "units" in v.attrs and v.attrs.get("kind") != "metric"}


def drawn_values(ds: Any) -> dict[str, tuple[np.ndarray, str]]:
    """The values drawn per run of a Monte-Carlo batch (``kind = "batch_values"``), by their
    key path: ``(values, stored unit)``.

    Parameters
    ----------
    ds : xarray.Dataset
        A flat result (over ``run``), a sweep store or an ``imo-probabilities.nc``.

    Returns
    -------
    dict of str to (numpy.ndarray, str)
    """
    return {str(n): (np.asarray(v.values, dtype=float).reshape(-1), str(v.attrs.get("units",
                                                                                     "")))
            for n, v in ds.data_vars.items()
            if v.attrs.get("kind") == "batch_values" and v.ndim == 1
            and v.dtype.kind in "fiu"}


def _stat_header(qnames: list[str]) -> list[str]:
    return ["n", "mean", "std", "min", *qnames, "max"]


def _stat_cells(s: dict[str, Any], qnames: list[str], factor: float) -> list[Any]:
    """A statistics row's numbers (``None`` where there is none) in the display unit."""
    def scaled(v: Any) -> Any:
        return None if v is None else float(v) * factor

    return [s["n"], *(scaled(s[k]) for k in ("mean", "std", "min", *qnames, "max"))]


def drawn_blocks(drawn: dict[str, tuple[np.ndarray, str]], what: str) -> list[Any]:
    """The statistics table and the histograms of a Monte-Carlo batch's drawn inputs (each
    labelled with its display unit and shown in it).

    Parameters
    ----------
    drawn : dict
        :func:`drawn_values` (of the runs to count).
    what : str
        Which runs they are, for the caption ("all 200 runs").

    Returns
    -------
    list
        HTML and a figure; empty without drawn values.
    """
    from ..analysis.statistics import DEFAULT_QUANTILES, metric_statistics, quantile_name

    if not drawn:
        return []
    qnames = [quantile_name(q) for q in DEFAULT_QUANTILES]
    rows, columns = [], {}
    for name, (values, unit) in drawn.items():
        shown, unit_shown = to_display(values, unit, name)
        s = metric_statistics({name: shown}, quantiles=DEFAULT_QUANTILES)[name]
        rows.append([label(name, unit_shown), *_stat_cells(s, qnames, 1.0)])
        columns[label(name, unit_shown)] = np.asarray(shown, dtype=float)
    out: list[Any] = [subheading("Drawn inputs"),
                      table(["drawn input", *_stat_header(qnames)], rows,
                            cls="statistics drawn", caption=f"the values drawn for {what}",
                            digits=DIGITS)]
    fig = histogram_figure({"": columns})
    if fig is not None:
        out.append(fig)
    return out


# ------------------------------------------------------------------------------------------
# the per-run table
# ------------------------------------------------------------------------------------------
def _short_status(message: str) -> str:
    if " at t = " in message:
        return f"diverged at {message.split(' at t = ')[1]}"
    return message


def run_table_blocks(run_set: RunSet) -> list[str]:
    """A simulation's per-run summary metrics (:func:`seahelm.analysis.maneuvers.summarize`)
    with each run's drawn values: a column per run up to :data:`MAX_COLUMN_RUNS` runs, else a
    row per run drawn in the plots (module docstring).

    Parameters
    ----------
    run_set : RunSet
        A simulation's runs.

    Returns
    -------
    list of str
        The table(s).
    """
    summary = run_set.summary
    if not summary:
        return []
    runs = run_set.runs
    units = signal_units(runs)
    every = shown_metrics(k for k in summary[0] if k not in ("run", "status"))
    values = {k: np.array([float(row[k]) for row in summary]) for k in every}
    keys = [k for k in every if np.isfinite(values[k]).any()]
    unreached = noted_unreached([k for k in every if k not in keys], every)
    metric_cols = []
    for key in keys:
        unit = metric_unit(key, units)
        metric_cols.append((metric_label(key, unit), to_display(values[key], unit, key)[0]))
    drawn_cols = [(label(n, to_display(None, u, n)[1]), to_display(v, u, n)[0])
                  for n, (v, u) in drawn_values(runs).items()]
    status = np.asarray(runs["status"].values).reshape(-1)
    messages = ([str(m) for m in np.asarray(runs["status_message"].values).reshape(-1)]
                if "status_message" in runs else
                ["ok" if s == 0 else f"status {s}" for s in status])
    labels = run_labels(runs)
    n = len(summary)
    note = ("not reached in any run: " + ", ".join(unreached)) if unreached else ""
    if n <= MAX_COLUMN_RUNS:  # metrics down, runs across
        rows = [["status", *(_short_status(m) for m in messages[:n])]]
        rows += [[name, *(float(v) for v in col)] for name, col in drawn_cols + metric_cols]
        return [table(["metric", *labels[:n]], rows, cls="summary", caption=note,
                      digits=DIGITS + 1)]
    shown = plotted_runs(status)
    lead: list[tuple[str, Any]] = [("run", labels), *drawn_cols]
    if (status != 0).any():
        lead.append(("status", [_short_status(m) for m in messages]))
    caption = (f"{shown.size} of {n} runs: those drawn in the plots (diverged runs first, the "
               f"rest spread over the batch); the statistics below cover all {n}; every run's "
               "values: seahelm inspect RESULT --json" + (f"; {note}" if note else ""))
    return row_tables(lead, metric_cols, shown, caption, cls="summary")


def row_tables(lead: list[tuple[str, Any]], columns: list[tuple[str, Any]], rows: Any,
               caption: str, *, cls: str) -> list[str]:
    """Tables of the runs ``rows``, a row each: the ``lead`` columns (the run's label, its
    drawn values, ...) and as many of ``columns`` as keep a table within
    :data:`MAX_TABLE_COLUMNS` columns; the further columns in tables below it, each led by
    the first lead column (the run's label).

    Parameters
    ----------
    lead : list of (str, sequence)
        Heading and values (one per run of the batch) of the leading columns.
    columns : list of (str, sequence)
        Heading and values of the other columns.
    rows : array_like of int
        The runs shown, in order.
    caption : str
        Under the last table.
    cls : str
        The tables' CSS class.

    Returns
    -------
    list of str
    """
    rows = [int(i) for i in np.asarray(rows).reshape(-1)]
    budget = max(2, MAX_TABLE_COLUMNS - len(lead))
    n_tables = max(1, -(-len(columns) // budget))
    size = -(-len(columns) // n_tables)  # (the columns shared evenly between the tables)
    chunks = [columns[k:k + size] for k in range(0, len(columns), size)] or [[]]
    out = []
    for k, chunk in enumerate(chunks):
        cols = (lead if k == 0 else lead[:1]) + chunk
        body = [[_cell(values[i]) for _, values in cols] for i in rows]
        out.append(table([c[0] for c in cols], body, cls=cls, digits=DIGITS,
                         caption=caption if len(chunks) == 1 else ""))
    if len(chunks) > 1 and caption:
        out.append(paragraph(caption, cls="caption"))
    return out


def _cell(value: Any) -> Any:
    """A table cell: a numpy number as a plain one."""
    if isinstance(value, (np.floating, np.integer, np.bool_)):
        return value.item()
    return value


# ------------------------------------------------------------------------------------------
# batch statistics
# ------------------------------------------------------------------------------------------
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
                parts.append(coordinate_text(d, c.values[j].item(),
                                             str(c.attrs.get("units", ""))))
            else:
                parts.append(f"{d} {j}")
        labels.append(", ".join(parts))
    return labels


def statistics_blocks(columns: dict[str, np.ndarray], ok: np.ndarray, what: str) -> list[Any]:
    """The statistics table and histograms of a batch's metric columns (already labelled and
    in their display units) over its ``ok`` runs.

    Parameters
    ----------
    columns : dict of str to numpy.ndarray
        Label → one value per run (NaN where a run has none).
    ok : numpy.ndarray of bool
        The runs counted.
    what : str
        Which runs they are, for the caption.

    Returns
    -------
    list
        HTML and a figure.
    """
    from ..analysis.statistics import DEFAULT_QUANTILES, metric_statistics, quantile_name

    qnames = [quantile_name(q) for q in DEFAULT_QUANTILES]
    counted = {k: np.asarray(v, dtype=float)[ok] for k, v in columns.items()}
    stats = metric_statistics(counted, quantiles=DEFAULT_QUANTILES)
    rows = [[k, *_stat_cells(s, qnames, 1.0)] for k, s in stats.items() if s["n"]]
    unreached = noted_unreached([k for k, s in stats.items() if not s["n"]], stats)
    caption = f"over {what}" + ("; not reached in any: " + ", ".join(unreached)
                                if unreached else "")
    out: list[Any] = [table(["metric", *_stat_header(qnames)], rows, cls="statistics",
                            caption=caption, digits=DIGITS)]
    fig = histogram_figure({"": {k: v for k, v in counted.items() if np.isfinite(v).any()}})
    if fig is not None:
        out.append(fig)
    return out


def statistics_sections(data: ReportData) -> list[Section]:
    """Distribution of the summary metrics over the ok runs of a large or Monte-Carlo batch,
    per grid point of a grid × Monte-Carlo batch (the first :data:`MAX_STAT_GROUPS`):
    quantile tables and histograms (:func:`seahelm.analysis.statistics.batch_statistics`);
    and the drawn inputs' (:func:`drawn_blocks`).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    from ..analysis.statistics import DEFAULT_QUANTILES, batch_statistics, group_runs, \
        quantile_name

    sections = []
    for run_set in data.sets:
        if run_set.shaped is None or run_set.metrics is not None:
            continue
        if run_set.n_runs < STATISTICS_MIN_RUNS and "sample" not in run_set.shaped.dims:
            continue
        summary = run_set.summary
        status = np.asarray(run_set.runs["status"].values).reshape(-1)
        units = signal_units(run_set.runs)
        metrics = [k for k in shown_metrics(summary[0]) if k not in ("run", "status")]
        groups = group_runs(_grid_labels(run_set.shaped, status.size))
        sec = Section(section_id("statistics", run_set, data), "Batch statistics"
                      + (f": {run_set.name}" if len(data.sets) > 1 else ""))
        shown = dict(list(groups.items())[:MAX_STAT_GROUPS])
        qnames = [quantile_name(q) for q in DEFAULT_QUANTILES]
        columns = {m: np.array([float(row[m]) for row in summary]) for m in metrics}
        rows, values_by_group, counts, unreached = [], {}, [], set(metrics)
        for entry in batch_statistics(columns, ok=status == 0, groups=shown):
            key, ok = entry["key"], entry["ok_runs"]
            counts.append(f"{key + ': ' if key else ''}{entry['n_ok']} ok of "
                          f"{entry['n_runs']}")
            group: dict[str, np.ndarray] = {}
            if not entry["n_ok"]:
                rows.append(([key] if key else []) + ["(no ok run: no metrics)"])
            for m, s in entry["metrics"].items():
                if not s["n"]:
                    continue
                unreached.discard(m)
                unit = metric_unit(m, units)
                name = metric_label(m, unit)
                factor = to_display(1.0, unit, m)[0]
                group[name] = columns[m][ok] * factor
                rows.append(([key] if key else []) + [name, *_stat_cells(s, qnames, factor)])
            values_by_group[key] = group
        note = "over the ok runs: " + "; ".join(counts)
        if len(groups) > len(shown):
            note += f" (first {len(shown)} of {len(groups)} grid points)"
        unreached = set(noted_unreached(unreached, metrics))
        if unreached:
            note += "; not reached in any ok run: " + ", ".join(
                m for m in metrics if m in unreached)
        sec.blocks.extend(drawn_blocks(drawn_values(run_set.runs),
                                       f"all {status.size} runs (ok or not)"))
        sec.blocks.append(subheading("Metrics"))
        sec.blocks.append(paragraph(note))
        header = (["grid point"] if len(shown) > 1 or next(iter(shown)) else []) + [
            "metric", *_stat_header(qnames)]
        sec.blocks.append(table(header, rows, cls="statistics", digits=DIGITS))
        names = [n for n in dict.fromkeys(k for g in values_by_group.values() for k in g)]
        fig = histogram_figure({k: {n: g.get(n, np.array([])) for n in names}
                                for k, g in values_by_group.items()}) if names else None
        if fig is not None:
            sec.blocks.append(fig)
        sections.append(sec)
    return sections


# ------------------------------------------------------------------------------------------
# a sweep store
# ------------------------------------------------------------------------------------------
_HIDDEN = ("scenario_text", "state_labels", "param_types")


def sweep_sections(data: ReportData) -> list[Section]:
    """A sweep store: its state (chunks written), metadata and scenario text, the summary
    statistics of every metric over the runs (stored with a complete sweep, else computed
    from the chunks written) and their histograms, and the drawn inputs'.

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    import json

    ds = data.sweep
    if ds is None:
        return []
    from ..sweep.run import fill_summary_units, summary_statistics

    attrs = dict(ds.attrs)
    sec = Section("sweep", "Sweep")
    n_runs, n_chunks = int(ds.sizes["run"]), int(attrs.get("sweep_n_chunks", 0) or 0)
    if "complete" in ds:
        flags = np.asarray(ds["complete"].values).reshape(n_runs, -1).all(axis=1)
        state = f"incomplete: {int(flags.sum())} of {n_runs} runs written"
    else:
        flags = np.ones(n_runs, bool)
        state = "complete"
    rows = [["state", state], ["runs", f"{n_runs}"],
            ["chunks", f"{n_chunks} of up to {attrs.get('sweep_chunk_size')} runs each"]]
    rows += [[k, v] for k, v in attrs.items() if not k.startswith("sweep_")
             and k not in _HIDDEN and len(str(v)) < 200]
    sec.blocks.append(table(None, [[k, str(v)] for k, v in rows], cls="meta"))
    if attrs.get("scenario_text"):
        text = str(attrs["scenario_text"])
        sec.blocks.append(f"<details><summary>scenario text ({len(text.splitlines())} lines)"
                          f"</summary><pre>{escape(text)}</pre></details>")
    summary = fill_summary_units(
        json.loads(attrs["sweep_summary"]) if "sweep_summary" in attrs
        else summary_statistics(ds.isel(run=np.flatnonzero(flags))), ds)
    drawn = {n: (v[flags], u) for n, (v, u) in sorted(drawn_values(ds).items())}
    sec.blocks.extend(drawn_blocks(drawn, f"the {int(flags.sum())} runs written"))
    sec.blocks.append(subheading("Metrics"))
    if "n_ok" in summary:
        sec.blocks.append(paragraph(f"{summary['n_ok']} ok, {summary['n_failed']} failed "
                                    f"of {summary['n_runs']} runs"))
    metrics = summary["metrics"]
    names = set(shown_metrics(dict.fromkeys(m["name"] for m in metrics)))
    shown = [m for m in metrics if m["name"] in names and m["n"]]
    noted = set(noted_unreached([m["name"] for m in metrics if not m["n"]], names))
    unreached = [m["name"] + (f" ({m['where']})" if m["where"] else "") for m in metrics
                 if m["name"] in names and not m["n"] and m["name"] in noted]
    qnames = sorted(k for k in (metrics[0] if metrics else {})
                    if k.startswith("q") and k[1:].isdigit())
    where = any(m["where"] for m in shown)
    body = []
    for m in shown:
        unit = m.get("units") or metric_unit(m["name"])
        factor = to_display(1.0, unit, m["name"])[0]
        body.append([metric_label(m["name"], unit), *([m["where"]] if where else []),
                     *_stat_cells(m, qnames, factor)])
    caption = "not reached in any run: " + ", ".join(unreached) if unreached else ""
    sec.blocks.append(table(["metric", *(["where"] if where else []), *_stat_header(qnames)],
                            body, cls="statistics", caption=caption, digits=DIGITS))
    columns: dict[str, np.ndarray] = {}
    units = {m["name"]: m.get("units") or "" for m in metrics}
    for name in sorted(ds.data_vars):
        var = ds[name]
        if var.attrs.get("kind") != "metric" or var.dims[:1] != ("run",) or name not in names:
            continue
        unit = units.get(name, "")
        values = to_display(np.asarray(var.values, dtype=float)[flags], unit, name)[0]
        for idx in np.ndindex(*values.shape[1:]):
            at = ", ".join(f"{d}={_plain(ds[d].values[i]) if d in ds.coords else i}"
                           for d, i in zip(var.dims[1:], idx))
            text = metric_label(name, unit)
            columns[f"{text} ({at})" if at else text] = values[(slice(None), *idx)]
            if len(columns) == MAX_SWEEP_HISTOGRAMS:
                break
        if len(columns) == MAX_SWEEP_HISTOGRAMS:
            break
    fig = histogram_figure({"": columns}) if columns else None
    if fig is not None:
        sec.blocks.append(fig)
    return [sec]


def _plain(value: Any) -> Any:
    return value.item() if hasattr(value, "item") else value
