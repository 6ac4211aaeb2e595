"""Aggregate statistics of per-run metrics over a batch (e.g. the samples of a Monte-Carlo run).

:func:`metric_statistics` takes the metrics by name (one value per run) and gives, for each,
the number of finite values, mean, sample standard deviation, extremes and quantiles. NaN
values (a metric a run does not reach, e.g. a settling time of a run that never settles) are
left out and counted apart, so a statistic describes the runs that have the metric.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ParameterError

__all__ = ["DEFAULT_QUANTILES", "metric_statistics", "quantile_name"]

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
) -> dict[str, dict[str, float]]:
    """Count, mean, standard deviation, min, quantiles and max of each metric over the runs.

    Parameters
    ----------
    metrics : mapping of str to array_like
        Metric name → one value per run (all of equal length).
    quantiles : sequence of float, optional
        Quantiles to report, each in [0, 1] (default 0.05, 0.5, 0.95); keys named by
        :func:`quantile_name`.

    Returns
    -------
    dict
        Per metric: ``n`` (finite values), ``n_nan`` (left out), ``mean``, ``std`` (sample
        standard deviation, ``ddof=1``; NaN below two values), ``min``, the quantiles (linear
        interpolation, numpy's default) and ``max``; NaN where no value is finite.

    Raises
    ------
    ParameterError
        If a quantile is outside [0, 1] or the metrics have different lengths.
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
            stats["std"] = float(finite.std(ddof=1)) if n > 1 else float("nan")
            stats["min"] = float(finite.min())
            for q, v in zip(qs, np.quantile(finite, qs)):
                stats[quantile_name(q)] = float(v)
            stats["max"] = float(finite.max())
        else:
            for key in ("mean", "std", "min", *map(quantile_name, qs), "max"):
                stats[key] = float("nan")
        out[name] = stats
    return out
