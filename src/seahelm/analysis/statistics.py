"""Aggregate statistics of per-run metrics over a batch (e.g. the samples of a Monte-Carlo run).

The one place where the statistics of a batch are computed: ``seahelm run``/``inspect`` (the
Monte-Carlo tables and JSON), the HTML report (the batch statistics section) and the sweeps
(the summary stored with a sweep) all call it.

:func:`metric_statistics` takes the metrics by name (one value per run) and gives, for each,
the number of finite values, mean, standard deviation, extremes and quantiles. NaN values (a
metric a run does not reach, e.g. a settling time of a run that never settles) are left out
and counted apart, so a statistic describes the runs that have the metric.
:func:`batch_statistics` does so per group of runs (the grid points of a grid × Monte-Carlo
batch, :func:`group_runs`), over the ok runs only (a diverged run's metrics describe no
finished run) and, for the drawn values of a Monte-Carlo batch, over all runs.
:func:`numeric_keys` names the numeric entries of a per-run summary row.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ParameterError

__all__ = ["DEFAULT_QUANTILES", "metric_statistics", "quantile_name", "batch_statistics",
           "group_runs", "numeric_keys"]

#: Quantiles reported by default: the 5 %, 50 % (median) and 95 % points.
DEFAULT_QUANTILES: tuple[float, ...] = (0.05, 0.5, 0.95)


def quantile_name(q: float) -> str:
    """The key of quantile ``q`` in :func:`metric_statistics`: ``q05``, ``q50``, ``q95``, ``q99.9``.

    Parameters
    ----------
    q : float
        Quantile in [0, 1].

    Returns
    -------
    str
    """
    pct = 100.0 * q
    return f"q{pct:02.0f}" if abs(pct - round(pct)) < 1e-9 else f"q{pct:g}"


def metric_statistics(
    metrics: Mapping[str, ArrayLike],
    *,
    quantiles: Sequence[float] = DEFAULT_QUANTILES,
    ddof: int = 1,
) -> dict[str, dict[str, float]]:
    """Count, mean, standard deviation, min, quantiles and max of each metric over the runs.

    Parameters
    ----------
    metrics : mapping of str to array_like
        Metric name → one value per run (all of equal length).
    quantiles : sequence of float, optional
        Quantiles to report, each in [0, 1] (default 0.05, 0.5, 0.95); keys named by
        :func:`quantile_name`.
    ddof : int, optional
        Delta degrees of freedom of the standard deviation: 1 (default) the sample standard
        deviation, 0 the population one (the sweeps' stored summaries use 0).

    Returns
    -------
    dict
        Per metric: ``n`` (finite values), ``n_nan`` (left out), ``mean``, ``std`` (NaN with
        no more than ``ddof`` values), ``min``, the quantiles (linear interpolation, numpy's
        default) and ``max``; NaN where no value is finite.

    Raises
    ------
    ParameterError
        If a quantile is outside [0, 1] or the metrics have different lengths.

    Notes
    -----
    std = √(Σ (x_i − x̄)² / (n − ddof)) over the n finite values x_i.
    """
    qs = [float(q) for q in quantiles]
    bad = [q for q in qs if not 0.0 <= q <= 1.0]
    if bad:
        raise ParameterError(f"`quantiles` must be in [0, 1] [-], got {bad[0]!r}")
    sizes = {name: np.size(values) for name, values in metrics.items()}
    if len(set(sizes.values())) > 1:
        raise ParameterError(f"every metric needs one value per run; lengths: {sizes}")
    out: dict[str, dict[str, float]] = {}
    for name, values in metrics.items():
        arr = np.asarray(values, dtype=float).reshape(-1)
        finite = arr[np.isfinite(arr)]
        n = int(finite.size)
        stats: dict[str, float] = {"n": n, "n_nan": int(arr.size - n)}
        if n:
            stats["mean"] = float(finite.mean())
            stats["std"] = float(finite.std(ddof=ddof)) if n > ddof else float("nan")
            stats["min"] = float(finite.min())
            for q, v in zip(qs, np.quantile(finite, qs)):
                stats[quantile_name(q)] = float(v)
            stats["max"] = float(finite.max())
        else:
            for key in ("mean", "std", "min", *map(quantile_name, qs), "max"):
                stats[key] = float("nan")
        out[name] = stats
    return out


def numeric_keys(row: Mapping[str, Any], skip: Iterable[str] = ()) -> list[str]:
    """The names of the numeric entries of a per-run summary row (not booleans), in its order.

    Parameters
    ----------
    row : mapping of str to value
        One run's summary (e.g. ``{"run": 0, "status": "ok", "settling_time_s": 93.8}``).
    skip : iterable of str, optional
        Names to leave out (e.g. ``run``, the batch dimensions, the drawn values).

    Returns
    -------
    list of str
    """
    skip = set(skip)
    return [k for k, v in row.items()
            if k not in skip and isinstance(v, (int, float)) and not isinstance(v, bool)]


def group_runs(keys: Iterable[Hashable]) -> dict[Hashable, np.ndarray]:
    """The runs of a batch grouped by a key per run, in the order the keys first appear.

    Parameters
    ----------
    keys : iterable of hashable
        One key per run (e.g. the coordinates of a run's grid point, without ``sample``).

    Returns
    -------
    dict
        Key → indices of its runs (increasing, int arrays).
    """
    groups: dict[Hashable, list[int]] = {}
    for i, key in enumerate(keys):
        groups.setdefault(key, []).append(i)
    return {key: np.asarray(runs, dtype=int) for key, runs in groups.items()}


def batch_statistics(
    metrics: Mapping[str, ArrayLike],
    *,
    ok: ArrayLike | None = None,
    groups: Mapping[Hashable, ArrayLike] | None = None,
    drawn: Mapping[str, ArrayLike] | None = None,
    quantiles: Sequence[float] = DEFAULT_QUANTILES,
    ddof: int = 1,
) -> list[dict[str, Any]]:
    """The statistics of a batch's metrics over its ok runs, per group of runs.

    Parameters
    ----------
    metrics : mapping of str to array_like
        Metric name → one value per run (NaN where a run has no value).
    ok : array_like of bool, optional
        Which runs count (e.g. ``status == 0``: a diverged run is left out); default all.
    groups : mapping of hashable to array_like of int, optional
        Group key → indices of its runs (:func:`group_runs`); default one group of all runs,
        key ``None``.
    drawn : mapping of str to array_like, optional
        Values drawn per run (a Monte-Carlo batch's inputs), summarised over all the runs of a
        group, ok or not (default none).
    quantiles : sequence of float, optional
        As :func:`metric_statistics`.
    ddof : int, optional
        As :func:`metric_statistics` (default 1).

    Returns
    -------
    list of dict
        One entry per group, in the order of ``groups``: ``key``, ``runs`` and ``ok_runs``
        (indices), ``n_runs``, ``n_ok``, ``metrics`` (:func:`metric_statistics` of the metrics
        over the ok runs) and ``drawn`` (of the drawn values over all runs).

    Raises
    ------
    ParameterError
        If the metrics, drawn values and ``ok`` differ in length, or as
        :func:`metric_statistics`.
    """
    columns = {name: np.asarray(v, dtype=float).reshape(-1) for name, v in metrics.items()}
    draws = {name: np.asarray(v, dtype=float).reshape(-1) for name, v in (drawn or {}).items()}
    sizes = {name: v.size for name, v in {**columns, **draws}.items()}
    if ok is not None:
        ok = np.asarray(ok, dtype=bool).reshape(-1)
        sizes["ok"] = ok.size
    if len(set(sizes.values())) > 1:
        raise ParameterError(f"every metric needs one value per run; lengths: {sizes}")
    n_runs = next(iter(sizes.values()), None)
    if n_runs is None:  # (nothing per run given: the groups say how many runs)
        n_runs = 1 + max((int(np.max(r)) for r in (groups or {}).values() if np.size(r)),
                         default=-1)
    if ok is None:
        ok = np.ones(n_runs, dtype=bool)
    if groups is None:
        groups = {None: np.arange(n_runs)}
    out = []
    for key, runs in groups.items():
        runs = np.asarray(runs, dtype=int).reshape(-1)
        good = runs[ok[runs]]
        out.append({
            "key": key, "runs": runs, "ok_runs": good,
            "n_runs": int(runs.size), "n_ok": int(good.size),
            "metrics": metric_statistics({m: v[good] for m, v in columns.items()},
                                         quantiles=quantiles, ddof=ddof),
            "drawn": metric_statistics({d: v[runs] for d, v in draws.items()},
                                       quantiles=quantiles, ddof=ddof),
        })
    return out
