"""Which runs of a manoeuvre batch a figure draws, grouped into what is drawn together.

A batch of up to :data:`MAX_RUNS_DRAWN` runs is drawn run by run, every run its own group (as
it always was). A bigger batch (a Monte-Carlo of ships: thousands of runs) is drawn by
**representatives**: within each group of runs that share every batch coordinate but the ship
(a side, a rudder angle, a zig-zag pair), the runs at the 0, 5, 25, 50, 75, 95 and 100 %
points of one metric (the tactical diameter of a turning circle, the first overshoot of a
zig-zag, ...) — the median one drawn bold and measured, the others thin — and up to two runs
that did not complete (diverged, or an event not reached), marked as such. So a figure of
10,000 runs has at most a few dozen artists and says what it shows.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["MAX_RUNS_DRAWN", "REPRESENTATIVE_QUANTILES", "DrawnRun", "RunGroup",
           "drawn_groups", "representatives_note", "ship_names"]

#: Runs drawn one by one at most; a bigger batch is drawn by representatives.
MAX_RUNS_DRAWN = 20
#: Quantiles of the metric at which a big batch's representative runs are chosen.
REPRESENTATIVE_QUANTILES = (0.0, 0.05, 0.25, 0.5, 0.75, 0.95, 1.0)
#: Runs that did not complete drawn per group at most (a big batch).
MAX_FAILED_DRAWN = 2

_SIDE = {1: "starboard", -1: "port"}


@dataclasses.dataclass(frozen=True)
class DrawnRun:
    """One run a figure draws.

    Attributes
    ----------
    label : str
        What the run is (its ship, side, rudder...; in a big batch its quantile).
    runs : xarray.Dataset or None
        Its time series.
    metrics : xarray.Dataset
        Its metrics.
    role : str
        ``"run"`` (a batch drawn run by run), ``"median"`` (a big batch's measured run),
        ``"quantile"`` (another representative) or ``"failed"`` (a run that did not complete).
    """

    label: str
    runs: Any
    metrics: Any
    role: str = "run"

    @property
    def measured(self) -> bool:
        """Whether the figure marks this run's metrics (not for a big batch's thin runs)."""
        return self.role in ("run", "median")


@dataclasses.dataclass(frozen=True)
class RunGroup:
    """Runs drawn together: one run (a small batch), or a big batch's representatives of one
    side/rudder/pair.

    Attributes
    ----------
    label : str
        The group's coordinates (or the run's label).
    runs : tuple of DrawnRun
    size : int
        Runs in the group in the batch (more than drawn in a big batch).
    """

    label: str
    runs: tuple[DrawnRun, ...]
    size: int


def ship_names(names: Sequence[str]) -> str:
    """The ships of a batch in a few words: all of up to three, else the first and last.

    Parameters
    ----------
    names : sequence of str

    Returns
    -------
    str
    """
    if len(names) <= 3:
        return ", ".join(names)
    return f"{names[0]} … {names[-1]} ({len(names):,} ships)"


def _label(result: Any, m: Any, dims: Sequence[str], *, ship: bool = True) -> str:
    parts = []
    if ship and len(result.ships) > 1:
        parts.append(str(m["ship_name"].item()))
    if "approach_speed" in dims:
        parts.append(f"U0 {float(m['approach_speed']):.4g} m/s")
    if "pair" in m.coords:
        parts.append(f"{math.degrees(float(m['rudder'])):.3g}/"
                     f"{math.degrees(float(m['trigger'])):.3g}")
    elif "rudder" in m.coords and "rudder" in dims:
        parts.append(f"{math.degrees(float(m['rudder'])):.3g} deg")
    if "side" in m.coords:
        parts.append(_SIDE[int(m["side"])])
    if "order" in dims:
        parts.append(f"order {float(m['order']):.3g}")
    return ", ".join(parts) or str(m["ship_name"].item())


def _select(result: Any, where: dict[str, int]) -> tuple[Any, Any]:
    m = result.metrics.isel(where)
    return m, (result.runs.isel(where) if result.runs is not None else None)


def drawn_groups(result: Any, by: str | None = None, *, index: int | None = None
                 ) -> list[RunGroup]:
    """The runs a figure of ``result`` draws, grouped (module docstring).

    Parameters
    ----------
    result : ManeuverResult
        Any manoeuvre result with runs.
    by : str, optional
        The metric whose quantiles choose a big batch's representatives (e.g.
        ``"tactical_diameter"``); without it, or for a batch of at most
        :data:`MAX_RUNS_DRAWN` runs, every run is drawn.
    index : int, optional
        Index along the metric's extra dimension (e.g. ``0`` for the first overshoot).

    Returns
    -------
    list of RunGroup
    """
    metrics = result.metrics
    dims = list(metrics["complete"].dims)
    n = int(np.prod([metrics.sizes[d] for d in dims], dtype=np.int64))
    if by is None or n <= MAX_RUNS_DRAWN or "ship" not in dims:
        groups = []
        for idx in itertools.product(*(range(metrics.sizes[d]) for d in dims)):
            m, runs = _select(result, dict(zip(dims, idx)))
            label = _label(result, m, dims)
            groups.append(RunGroup(label, (DrawnRun(label, runs, m),), 1))
        return groups
    others = [d for d in dims if d != "ship"]
    values = metrics[by]
    extra = [d for d in values.dims if d not in dims]
    if extra:
        values = values.isel({extra[0]: index or 0})
    complete = np.asarray(metrics["complete"].transpose("ship", *others).values)
    values = np.asarray(np.abs(values.transpose("ship", *others).values), dtype=float)
    groups = []
    for idx in itertools.product(*(range(metrics.sizes[d]) for d in others)):
        where = dict(zip(others, idx))
        v, done = values[(slice(None), *idx)], complete[(slice(None), *idx)]
        chosen: dict[int, str] = {}
        finite = np.flatnonzero(np.isfinite(v))
        if finite.size:
            for q, at in zip(REPRESENTATIVE_QUANTILES,
                             np.quantile(v[finite], REPRESENTATIVE_QUANTILES,
                                         method="nearest")):
                ship = int(finite[np.argmin(np.abs(v[finite] - at))])
                chosen.setdefault(ship, "median" if q == 0.5 else f"q{100 * q:02.0f}")
        for ship in np.flatnonzero(~done)[:MAX_FAILED_DRAWN].tolist():
            chosen[int(ship)] = "failed"
        runs = []
        for ship, tag in sorted(chosen.items(), key=lambda item: item[1] == "median"):
            m, series = _select(result, {**where, "ship": ship})
            role = tag if tag in ("median", "failed") else "quantile"
            runs.append(DrawnRun(f"{m['ship_name'].item()} ({tag})", series, m, role))
        m0 = metrics.isel({**where, "ship": 0})
        groups.append(RunGroup(_label(result, m0, dims, ship=False), tuple(runs),
                               metrics.sizes["ship"]))
    return groups


def representatives_note(groups: Sequence[RunGroup], what: str) -> str:
    """A figure's note on what a big batch's drawing shows ("" for a batch drawn run by run).

    Parameters
    ----------
    groups : sequence of RunGroup
        :func:`drawn_groups`.
    what : str
        The metric that chose them, in words (e.g. "tactical diameter").

    Returns
    -------
    str
    """
    if all(g.size == 1 for g in groups):
        return ""
    n = sum(g.size for g in groups)
    failed = sum(r.role == "failed" for g in groups for r in g.runs)
    return (f"{n:,} runs; drawn per group: the runs at the 0, 5, 25, 50, 75, 95, 100 % "
            f"points of the {what} (thin) and the median (bold, measured)"
            + (f"; {failed} incomplete runs dashed, x where they ended" if failed else ""))
