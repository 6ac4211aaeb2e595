"""A big batch of manoeuvre runs shown as statistics, not as one column per run.

``seahelm run`` of a Monte-Carlo ``[maneuver]`` scenario (and any manoeuvre batch of more than
:data:`SUMMARY_RUNS` runs) prints, per group of runs that share their side, rudder angle or
zig-zag pair, the statistics of every metric over the group's runs and of the values drawn
per ship (:func:`seahelm.analysis.statistics.batch_statistics`, shown as the statistics of a
simulation batch are: :func:`seahelm.cli._runs.statistics_tables`), and the runs' notes each
said once with the number of runs it applies to ("1,974 of 2,000 runs: ok; the turn was not
yet steady …"). ``--json`` keeps every run and adds the statistics.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from rich.markup import escape

from ..analysis.statistics import batch_statistics, group_runs
from ._common import console

__all__ = ["SUMMARY_RUNS", "aggregate_notes", "note_lines", "maneuver_statistics",
           "print_statistics"]

#: Runs above which a manoeuvre batch is summarised (a table of runs up to this many).
SUMMARY_RUNS = 10

#: Notes listed at most (the most frequent first); the JSON output has every run's.
MAX_NOTES = 8

_NUMBER = re.compile(r"[-+]?(?:\d[\d,_]*(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?")
#: Coordinates of a run that make a group (the ship is what varies within one).
_GROUP_KEYS = ("side", "rudder_deg", "heading_trigger_deg")


def aggregate_notes(labels: Sequence[str], messages: Sequence[str],
                    skip: Sequence[str] = ("ok",)) -> list[dict[str, Any]]:
    """The runs' notes, each kind once: notes that differ only in their numbers are one kind.

    Parameters
    ----------
    labels : sequence of str
        Each run's label (as in the tables).
    messages : sequence of str
        Each run's note.
    skip : sequence of str, optional
        Notes not listed (default: ``"ok"``).

    Returns
    -------
    list of dict
        Most frequent first: ``count``, ``example`` (the first run's note of that kind),
        ``runs`` (the labels of its first three runs) and ``same`` (whether every note of
        the kind is the example word for word).
    """
    kinds: dict[str, dict[str, Any]] = {}
    for label, message in zip(labels, messages):
        if message in skip:
            continue
        entry = kinds.setdefault(_NUMBER.sub("#", message),
                                 {"count": 0, "example": message, "runs": [],
                                  "same": True})
        entry["count"] += 1
        entry["same"] &= message == entry["example"]
        if len(entry["runs"]) < 3:
            entry["runs"].append(label)
    return sorted(kinds.values(), key=lambda e: -e["count"])


def note_lines(notes: Sequence[Mapping[str, Any]], n_runs: int) -> list[str]:
    """Lines of :func:`aggregate_notes` (at most :data:`MAX_NOTES` kinds).

    Parameters
    ----------
    notes : sequence of mapping
        :func:`aggregate_notes`.
    n_runs : int
        Runs in the batch.

    Returns
    -------
    list of str
    """
    lines = []
    for entry in notes[:MAX_NOTES]:
        if entry["count"] == 1:
            lines.append(f"{entry['runs'][0]}: {entry['example']}")
            continue
        where = "" if entry.get("same", False) else f" (as in {entry['runs'][0]})"
        lines.append(f"{entry['count']:,} of {n_runs:,} runs{where}: {entry['example']}")
    if len(notes) > MAX_NOTES:
        rest = sum(e["count"] for e in notes[MAX_NOTES:])
        lines.append(f"{rest:,} more runs with {len(notes) - MAX_NOTES} other kinds of note "
                     "(each run's note: --json)")
    return lines


def maneuver_statistics(rows: Sequence[Mapping[str, Any]], keys: Sequence[str],
                        drawn: Mapping[str, np.ndarray] | None = None
                        ) -> list[dict[str, Any]]:
    """Statistics of a manoeuvre batch's metrics per group of runs (same side, rudder, pair).

    Parameters
    ----------
    rows : sequence of mapping
        The runs in command-line units (``cli.maneuver.display_rows``), each with its
        ``message`` and, in a batch of several ships, its ``ship`` index.
    keys : sequence of str
        The numeric metrics to summarise (keys of the rows).
    drawn : mapping of str to ndarray, optional
        Values drawn per ship (a Monte-Carlo scenario's draws, by key path), indexed by the
        rows' ``ship``.

    Returns
    -------
    list of dict
        One entry per group: ``point`` (the group's coordinates), ``n_runs``, ``n_ok`` (runs
        that did not diverge), ``metrics`` and ``drawn`` (statistics as
        :func:`seahelm.analysis.statistics.metric_statistics`).
    """
    present = [k for k in _GROUP_KEYS if any(k in row for row in rows)]
    groups = group_runs(tuple(row.get(k) for k in present) for row in rows)
    ok = np.array(["diverged" not in str(row.get("message", "")) for row in rows])
    metrics = {k: [_number(row.get(k)) for row in rows] for k in keys}
    per_run: dict[str, list[float]] = {}
    if drawn:
        ships = np.array([int(row.get("ship", 0)) for row in rows])
        per_run = {name: np.asarray(values, dtype=float)[ships].tolist()
                   for name, values in drawn.items()}
    stats = batch_statistics(metrics, ok=ok, groups=groups, drawn=per_run)
    return [{"point": dict(zip(present, entry["key"])), "n_runs": entry["n_runs"],
             "n_ok": entry["n_ok"], "metrics": entry["metrics"], "drawn": entry["drawn"]}
            for entry in stats]


def _number(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return math.nan
    return float(value)


def print_statistics(title: str, stats: Sequence[Mapping[str, Any]],
                     rows: Sequence[Mapping[str, Any]], labels: Mapping[str, str]) -> None:
    """Print a big batch: its statistics tables per group of runs, then its notes counted.

    Parameters
    ----------
    title : str
        What ran (e.g. "Turning circle, kvlcc2-l7, 35 deg rudder").
    stats : sequence of mapping
        :func:`maneuver_statistics`.
    rows : sequence of mapping
        The runs (with ``run`` labels and ``message`` notes).
    labels : mapping of str to str
        Metric key → the label shown (with its unit).
    """
    from ._runs import statistics_tables

    console.print(escape(f"{title}: {len(rows):,} runs"), highlight=False)
    shown = [{**e, "metrics": {labels.get(k, k): v for k, v in e["metrics"].items()}}
             for e in stats]
    for table in statistics_tables(shown, what="statistics"):
        console.print(table)
    for line in note_lines(aggregate_notes([r["run"] for r in rows],
                                           [r["message"] for r in rows]), len(rows)):
        console.print(f"  {escape(line)}", highlight=False)
