"""How the runs of a simulation batch are shown: the per-run summary table with each run's
batch coordinates and drawn values, the status of diverged runs, and the aggregate statistics
of a Monte-Carlo batch. Shared by ``seahelm run``/``demo`` (a result in memory) and
``seahelm inspect`` (a result read back from its file), so both show a batch the same way.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from rich import box
from rich.markup import escape
from rich.table import Table

from ..analysis.statistics import (
    DEFAULT_QUANTILES,
    batch_statistics,
    group_runs,
    numeric_keys,
    quantile_name,
)
from ..units import label, metric_label, metric_unit, noted_unreached, shown_metrics, to_display

#: Rows shown in the per-run table of a batch (the JSON output has every run).
MAX_ROWS = 20
#: Grid points whose Monte-Carlo statistics are shown as tables (the JSON output has all).
MAX_STAT_TABLES = 4


def fmt(v: Any) -> str:
    """A number in 5 significant digits; anything else as text."""
    return f"{v:.5g}" if isinstance(v, float) else str(v)


def batch_columns(result: Any, summary: list[dict[str, Any]]) -> tuple[str, ...]:
    """Put each run's batch coordinates and drawn values after ``run`` in its summary row.

    Returns the table's extra columns: the batch dimensions (a scenario's grid keys, a
    manoeuvre's side or rudder angle; not the ``sample`` index of a Monte-Carlo batch) and the
    drawn values of a Monte-Carlo batch (named by their key path).
    """
    layout = result.layout
    if layout is None or layout.is_flat:
        return ()
    values = {v.name: v.values for v in layout.values}
    for i, row in enumerate(summary):
        extra = {**layout.point(i), **{k: float(v[i]) for k, v in values.items()}}
        rest = {k: v for k, v in row.items() if k != "run"}
        row.clear()
        row.update({"run": i, **extra, **rest})
    return tuple(a.name for a in layout.axes if a.name != "sample") + tuple(values)


def run_units(result: Any, summary: list[dict[str, Any]]) -> dict[str, str]:
    """The stored unit of every column of a batch's summary rows: the summary metrics'
    (:func:`seahelm.analysis.maneuvers.summary_units`), the grid coordinates' and the drawn
    values' (as the batch layout declares them).

    Parameters
    ----------
    result : SimResult
        The runs.
    summary : list of dict
        Their summary rows (:func:`seahelm.analysis.maneuvers.summarize`).

    Returns
    -------
    dict of str to str
    """
    units = result.units()
    out = {k: metric_unit(k, units) for k in summary[0] if k not in ("run", "status")}
    layout = result.layout
    if layout is not None:
        out.update({a.name: a.units for a in layout.axes})
        out.update({v.name: v.units for v in layout.values})
    return out


#: A settling time that was never reached, in a table (one line: its column is this wide).
NOT_SETTLED = "not\u00a0settled"


def _shown(value: Any, unit: str, name: str) -> str:
    """A value in its display unit (:func:`seahelm.units.to_display`), formatted; a run that
    never settles says "not settled" (it printed ``nan``)."""
    if name == "settling_time_s" and isinstance(value, float) and math.isnan(value):
        return NOT_SETTLED
    return fmt(to_display(value, unit, name)[0]) if isinstance(value, float) else fmt(value)


def summary_table(summary: list[dict[str, Any]], title: str,
                  batch_keys: tuple[str, ...] = (), units: dict[str, str] | None = None
                  ) -> Table:
    """One run: a metric/value table (labels with their display units and values in them,
    :mod:`seahelm.units`; neither a filter's internal states nor an angle again; the metrics
    the run did not reach named under it); a batch: one row per run (first
    :data:`MAX_ROWS`), with the run's grid coordinates and drawn values (``batch_keys``) as
    columns.

    Parameters
    ----------
    summary : list of dict
        The runs' summary rows.
    title : str
        The table's title.
    batch_keys : tuple of str, optional
        The batch coordinates and drawn values in the rows (:func:`batch_columns`).
    units : dict of str to str, optional
        The stored unit of each column (:func:`run_units`).

    Returns
    -------
    rich.table.Table
    """
    units = units or {}
    if len(summary) == 1:
        table = Table(title=title)
        table.add_column("metric")
        table.add_column("value", justify="right")
        row = summary[0]
        unreached = []
        for key in shown_metrics(k for k in row if k != "run"):
            value = row[key]
            if isinstance(value, float) and math.isnan(value):
                unreached.append(key)
                continue
            unit = units.get(key, metric_unit(key))
            table.add_row(escape(metric_label(key, unit) if key != "status" else key),
                          _shown(value, unit, key))
        unreached = noted_unreached(unreached, row)
        if unreached:
            table.caption = escape("not reached in this run: " + ", ".join(unreached)
                                   + " (every metric: --json)")
        return table
    table = Table(title=title)
    keys = ["run", *batch_keys, "status", "final_heading_rad", "final_yaw_rate",
            "settling_time_s"]
    for key in keys:
        unit = units.get(key, metric_unit(key))
        if key in batch_keys:
            name = label(key, to_display(None, unit, key)[1])
        elif key in ("run", "status"):
            name = key
        else:
            name = metric_label(key, unit)
        table.add_column(escape(name), justify="left" if key == "status" else "right",
                         overflow="fold", no_wrap=key == "status",
                         min_width=len(NOT_SETTLED) if key == "settling_time_s" else None)
    for row in summary[:MAX_ROWS]:
        table.add_row(*(escape(_short_status(row[k]) if k == "status"
                               else _shown(row.get(k, ""), units.get(k, metric_unit(k)), k))
                        for k in keys))
    if len(summary) > MAX_ROWS:
        table.caption = f"first {MAX_ROWS} of {len(summary)} runs"
    return table


def _short_status(message: str) -> str:
    """'diverged: state out of bounds at t = 11.5 s' -> 'diverged at 11.5 s' (the diverged
    runs' table gives the reason)."""
    if " at t = " in message:
        return f"diverged at {message.split(' at t = ')[1]}"
    return message


def status_counts(status: np.ndarray) -> dict[str, int]:
    """``n_runs``, ``n_ok`` and ``n_diverged`` of a batch's status codes (0 = ok)."""
    status = np.asarray(status).reshape(-1)
    return {"n_runs": int(status.size), "n_ok": int((status == 0).sum()),
            "n_diverged": int((status != 0).sum())}


def diverged_runs(result: Any) -> list[dict[str, Any]]:
    """The runs that diverged: flat run index, batch coordinates, time [s] and reason."""
    out = []
    layout = result.layout
    for i in np.flatnonzero(np.asarray(result.status) != 0):
        i = int(i)
        row: dict[str, Any] = {"run": i}
        if layout is not None and not layout.is_flat:
            row.update(layout.point(i))
        row["time_s"] = float(result.failure_time[i])
        row["reason"] = result.messages()[i].split(" at t = ")[0].removeprefix("diverged: ")
        out.append(row)
    return out


def diverged_table(rows: list[dict[str, Any]]) -> Table:
    """The diverged runs (first :data:`MAX_ROWS`): run, coordinates, time, reason."""
    keys = list(rows[0]) if rows else ["run", "time_s", "reason"]
    table = Table(title="diverged runs", title_justify="left")
    for key in keys:
        table.add_column(escape("time [s]") if key == "time_s" else escape(key),
                         justify="left" if key == "reason" else "right")
    for row in rows[:MAX_ROWS]:
        table.add_row(*(escape(fmt(row[k])) for k in keys))
    if len(rows) > MAX_ROWS:
        table.caption = f"first {MAX_ROWS} of {len(rows)} diverged runs"
    return table


def monte_carlo_statistics(result: Any, summary: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Aggregate statistics of the metrics over the samples of a Monte-Carlo batch
    (:func:`seahelm.analysis.statistics.batch_statistics`).

    One entry per grid point (a Monte-Carlo batch without a grid has one): the point's
    coordinates, its run and ok counts, the statistics of every numeric metric over its ok
    runs, and those of the drawn values over all its runs. Empty for a batch without a
    ``sample`` dimension.
    """
    layout = result.layout
    if layout is None or "sample" not in layout.dims:
        return []
    drawn = [v.name for v in layout.values]
    metrics = numeric_keys(summary[0], skip={"run", *layout.dims, *drawn})
    others = [d for d in layout.dims if d != "sample"]
    points = [layout.point(i) for i in range(len(summary))]
    groups = group_runs(tuple(point[d] for d in others) for point in points)
    stats = batch_statistics(
        {m: [row[m] for row in summary] for m in metrics},
        drawn={d: [row[d] for row in summary] for d in drawn},
        ok=np.asarray(result.status).reshape(-1) == 0, groups=groups)
    return [{"point": dict(zip(others, entry["key"])), "n_runs": entry["n_runs"],
             "n_ok": entry["n_ok"], "metrics": entry["metrics"], "drawn": entry["drawn"]}
            for entry in stats]


def statistics_tables(stats: list[dict[str, Any]], what: str = "Monte-Carlo statistics",
                      units: dict[str, str] | None = None) -> list[Table]:
    """Tables of :func:`monte_carlo_statistics` (the first :data:`MAX_STAT_TABLES` points),
    titled ``what`` and the point.

    Parameters
    ----------
    stats : list of dict
        The statistics per grid point.
    what : str, optional
        The tables' title.
    units : dict of str to str, optional
        The stored unit of each metric and drawn value (:func:`run_units`): the rows are
        labelled with their display units and the statistics shown in them; without it the
        names are shown as given (already labels).

    Returns
    -------
    list of rich.table.Table
    """
    tables = []
    qnames = [quantile_name(q) for q in DEFAULT_QUANTILES]
    for entry in stats[:MAX_STAT_TABLES]:
        where = ", ".join(f"{k}={fmt(v)}" for k, v in entry["point"].items())
        title = (f"{what}{' at ' + where if where else ''}: "
                 + (f"drawn values over all {entry['n_runs']} samples, " if entry["drawn"]
                    else "") + f"metrics over the {entry['n_ok']} ok of {entry['n_runs']} runs")
        table = Table(title=escape(title), title_justify="left", box=box.SIMPLE_HEAD,
                      pad_edge=False)
        table.add_column("metric", no_wrap=True)
        for col in ("n", "mean", "std", *qnames):
            table.add_column(col, justify="right", overflow="fold")
        for section in ("drawn", "metrics"):
            if section == "metrics" and not entry["n_ok"]:
                table.add_row("(no ok run: no metrics)")
                continue
            items = list(entry[section].items())
            if section == "metrics" and units is not None:
                items = [(k, entry[section][k]) for k in shown_metrics(entry[section])]
            for name, s in items:
                shown = name
                factor = 1.0
                if units is not None:
                    unit = units.get(name, metric_unit(name))
                    shown_unit = to_display(None, unit, name)[1]
                    factor = to_display(1.0, unit, name)[0]
                    shown = (label(name, shown_unit) if section == "drawn"
                             else metric_label(name, unit))
                table.add_row(escape(shown), str(s["n"]),
                              *(_num(s[k] * factor) for k in ("mean", "std", *qnames)),
                              end_section=section == "drawn" and name == items[-1][0])
        table.caption = "min, max and more digits: --json"
        tables.append(table)
    if len(stats) > MAX_STAT_TABLES:
        tables[-1].caption = (f"first {MAX_STAT_TABLES} of {len(stats)} grid points; all, "
                              "with min, max and more digits: --json")
    return tables


def _num(v: float) -> str:
    return "" if isinstance(v, float) and math.isnan(v) else f"{v:.4g}"


def sweep_summary_table(title: str, summary: dict[str, Any], max_rows: int = MAX_ROWS
                        ) -> tuple[Table, int]:
    """The statistics of a sweep store's metrics (its ``sweep_summary``) as ``seahelm sweep``
    prints them: the first ``max_rows`` metrics (:func:`seahelm.units.shown_metrics`, each
    labelled with its display unit and its statistics in it), without an empty ``where``
    column.

    Parameters
    ----------
    title : str
        The table's title.
    summary : dict
        :func:`seahelm.sweep.run.summary_statistics` of the store.
    max_rows : int, optional
        Metrics shown at most (default :data:`MAX_ROWS`).

    Returns
    -------
    (rich.table.Table, int)
        The table and the number of metrics left out (beyond ``max_rows``).
    """
    table = Table(title=escape(title), title_justify="left")
    every = shown_metrics(dict.fromkeys(r["name"] for r in summary["metrics"]))
    rows = [r for r in summary["metrics"] if r["name"] in set(every)]
    left = len(rows) - max_rows
    rows = rows[:max_rows]
    where = any(r.get("where") for r in rows)  # (no empty column)
    table.add_column("metric", overflow="fold")
    if where:
        table.add_column("where", no_wrap=True)
    for col in ("n", "mean", "std", "q05", "q50", "q95"):
        table.add_column(col, justify="right", no_wrap=True)
    for row in rows:
        unit = row.get("units") or metric_unit(row["name"])
        factor = to_display(1.0, unit, row["name"])[0]
        table.add_row(escape(metric_label(row["name"], unit)),
                      *([escape(str(row["where"]))] if where else []), str(row["n"]),
                      *(_stat(row[k], factor) for k in ("mean", "std", "q05", "q50", "q95")))
    return table, max(0, left)


def _stat(value: Any, factor: float = 1.0) -> str:
    """A stored statistic times ``factor`` (None or NaN where there is none: "–")."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    return f"{value * factor:.4g}"
