"""Aggregate statistics of per-run metrics (Monte-Carlo batches)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.statistics import metric_statistics, quantile_name
from seahelm.errors import ParameterError


def test_statistics_equal_numpy_and_leave_out_nan():
    rng = np.random.default_rng(1)
    x = rng.normal(2.0, 0.5, 101)
    with_nan = np.concatenate([x, [np.nan, np.nan]])
    s = metric_statistics({"x": with_nan, "none": np.full(103, np.nan)})["x"]
    assert (s["n"], s["n_nan"]) == (101, 2)
    assert s["mean"] == pytest.approx(x.mean())
    assert s["std"] == pytest.approx(x.std(ddof=1))
    assert (s["min"], s["max"]) == (x.min(), x.max())
    for q in (0.05, 0.5, 0.95):
        assert s[quantile_name(q)] == pytest.approx(np.quantile(x, q))
    none = metric_statistics({"none": [np.nan]})["none"]
    assert none["n"] == 0 and math.isnan(none["mean"]) and math.isnan(none["q50"])


def test_one_value_has_no_spread_and_quantiles_are_named():
    s = metric_statistics({"x": [3.0]}, quantiles=(0.25, 0.999))["x"]
    assert s["mean"] == s["q25"] == s["q99.9"] == 3.0 and math.isnan(s["std"])
    assert [quantile_name(q) for q in (0.0, 0.05, 0.5, 1.0)] == ["q00", "q05", "q50", "q100"]


@pytest.mark.parametrize("metrics, quantiles, match", [
    ({"x": [1.0]}, (1.5,), r"`quantiles` must be in \[0, 1\] \[-\], got 1.5"),
    ({"x": [1.0], "y": [1.0, 2.0]}, (0.5,), "one value per run"),
])
def test_bad_input_is_named(metrics, quantiles, match):
    with pytest.raises(ParameterError, match=match):
        metric_statistics(metrics, quantiles=quantiles)
