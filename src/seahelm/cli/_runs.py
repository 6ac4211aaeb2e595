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


def summary_table(summary: list[dict[str, Any]], title: str,
                  batch_keys: tuple[str, ...] = (), units: dict[str, str] | None = None
                  ) -> Table:
    """One run: a metric/value table (labels with their units, :func:`metric_label`; neither
    a filter's internal states nor an angle again in radians; the metrics the run did not
    reach named under it); a batch: one row per run (first :data:`MAX_ROWS`), with the run's
    grid coordinates and drawn values (``batch_keys``) as columns."""
    if len(summary) == 1:
        table = Table(title=title)
        table.add_column("metric")
        table.add_column("value", justify="right")
        row = summary[0]
        unreached = []
        for key, value in row.items():
            if key == "run" or _repeats_or_internal(key, row):
                continue
            if isinstance(value, float) and math.isnan(value):
                unreached.append(key)
                continue
            final = key.endswith("_deg") and f"final_{key[:-4]}" in row  # (the final value)
            table.add_row(escape(("final " if final else "") + metric_label(key, units)),
                          fmt(value))
        if unreached:
            table.caption = escape("not reached in this run: " + ", ".join(unreached)
                                   + " (every metric: --json)")
        return table
    table = Table(title=title)
    keys = ["run", *batch_keys, "status", "final_heading_rad", "final_yaw_rate",
            "settling_time_s"]
    for key in keys:
        name = key if key in batch_keys else key.replace("_", " ")
        table.add_column(escape(name), justify="left" if key == "status" else "right",
                         overflow="fold", no_wrap=key == "status")
    for row in summary[:MAX_ROWS]:
        table.add_row(*(escape(_short_status(row[k]) if k == "status" else fmt(row.get(k, "")))
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


def statistics_tables(stats: list[dict[str, Any]], what: str = "Monte-Carlo statistics"
                      ) -> list[Table]:
    """Tables of :func:`monte_carlo_statistics` (the first :data:`MAX_STAT_TABLES` points),
    titled ``what`` and the point."""
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
            names = list(entry[section])
            for name, s in entry[section].items():
                table.add_row(escape(name), str(s["n"]),
                              *(_num(s[k]) for k in ("mean", "std", *qnames)),
                              end_section=section == "drawn" and name == names[-1])
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
    prints them: the first ``max_rows`` metrics, without empty ``where``/``units`` columns.

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
        The table and the number of metrics left out.
    """
    table = Table(title=escape(title), title_justify="left")
    rows = summary["metrics"][:max_rows]
    labels = [c for c in ("where", "units") if any(r.get(c) for r in rows)]  # (no empty ones)
    table.add_column("metric", overflow="fold")
    for col in labels:
        table.add_column(col, no_wrap=True)
    for col in ("n", "mean", "std", "q05", "q50", "q95"):
        table.add_column(col, justify="right", no_wrap=True)
    for row in rows:
        table.add_row(escape(row["name"]), *(escape(str(row[c])) for c in labels),
                      str(row["n"]),
                      *(_stat(row[k]) for k in ("mean", "std", "q05", "q50", "q95")))
    return table, max(0, len(summary["metrics"]) - max_rows)


def _stat(value: Any) -> str:
    """A stored statistic (None or NaN where there is none: "–")."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    return f"{value:.4g}"


#: Units named by a metric's suffix (``settling_time_s``: s).
_SUFFIX_UNITS = {"_deg": "deg", "_degps": "deg/s", "_s": "s", "_m": "m", "_mps": "m/s",
                 "_rad": "rad", "_pct": "%", "_L": "L"}


def metric_label(key: str, units: dict[str, str] | None = None) -> str:
    """A summary metric's label with its unit: ``settling_time_s`` → ``settling time [s]``,
    ``final_north`` → ``final north [m]`` (the unit of the state ``north`` in ``units``).

    Parameters
    ----------
    key : str
        The metric's key.
    units : dict of str to str, optional
        Units of the result's signals by name.

    Returns
    -------
    str
    """
    for suffix, unit in _SUFFIX_UNITS.items():
        if key.endswith(suffix):
            return f"{key[:-len(suffix)].replace('_', ' ')} [{unit}]"
    if key.startswith("final_") and units and units.get(key[len("final_"):]):
        return f"{key.replace('_', ' ')} [{units[key[len('final_'):]]}]"
    return key.replace("_", " ")


def _repeats_or_internal(key: str, row: dict[str, Any]) -> bool:
    """A filter's internal state (``final_yaw_aux``), or an angle also given in degrees
    (``final_heading`` beside ``heading_deg``; ``final_heading_rad``)."""
    if key.endswith("_aux") or "_aux_" in key:
        return True
    if key.startswith("final_"):
        name = key[len("final_"):].removesuffix("_rad")
        return f"{name}_deg" in row
    return False
