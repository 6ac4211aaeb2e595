"""Aggregate statistics of per-run metrics (Monte-Carlo batches)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.statistics import (
    batch_statistics,
    group_runs,
    metric_statistics,
    numeric_keys,
    quantile_name,
)
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


# ------------------------------------------------------------------------------------------
# the one computation of batch statistics (CLI, report, sweeps): analytic cases
# ------------------------------------------------------------------------------------------
def test_known_mean_std_and_quantiles():
    # 1..5: mean 3, sample std √2.5, population std √2; quantiles by linear interpolation
    s = metric_statistics({"x": [5.0, 1.0, 4.0, 2.0, 3.0]}, quantiles=(0.0, 0.25, 0.5, 0.75, 1.0))
    assert (s["x"]["n"], s["x"]["n_nan"], s["x"]["mean"]) == (5, 0, 3.0)
    assert s["x"]["std"] == pytest.approx(math.sqrt(2.5), rel=1e-15)
    assert [s["x"][k] for k in ("q00", "q25", "q50", "q75", "q100")] == [1.0, 2.0, 3.0, 4.0, 5.0]
    assert (s["x"]["min"], s["x"]["max"]) == (1.0, 5.0)
    population = metric_statistics({"x": [5.0, 1.0, 4.0, 2.0, 3.0]}, ddof=0)["x"]
    assert population["std"] == pytest.approx(math.sqrt(2.0), rel=1e-15)
    assert metric_statistics({"x": [7.0]}, ddof=0)["x"]["std"] == 0.0  # one value: no spread


def test_inf_is_left_out_like_nan():
    s = metric_statistics({"x": [1.0, np.inf, 3.0, -np.inf, np.nan]})["x"]
    assert (s["n"], s["n_nan"], s["mean"], s["min"], s["max"]) == (2, 3, 2.0, 1.0, 3.0)


def test_batch_statistics_leave_out_diverged_runs_and_nan_but_not_draws():
    # runs 0..5 in two grid points; run 1 diverged (its metric is a number, but not counted),
    # run 4 never settles (NaN): each group's metrics over its ok runs with a value
    metric = [1.0, 100.0, 3.0, 10.0, np.nan, 30.0]
    drawn = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
    ok = [True, False, True, True, True, True]
    groups = group_runs(["a", "a", "a", "b", "b", "b"])
    assert list(groups) == ["a", "b"]
    np.testing.assert_array_equal(groups["b"], [3, 4, 5])
    a, b = batch_statistics({"t": metric}, ok=ok, groups=groups, drawn={"gain": drawn})
    assert (a["key"], a["n_runs"], a["n_ok"]) == ("a", 3, 2)
    np.testing.assert_array_equal(a["ok_runs"], [0, 2])
    assert (a["metrics"]["t"]["n"], a["metrics"]["t"]["mean"]) == (2, 2.0)
    assert a["metrics"]["t"]["std"] == pytest.approx(math.sqrt(2.0))
    assert (a["drawn"]["gain"]["n"], a["drawn"]["gain"]["mean"]) == (3, pytest.approx(0.2))
    assert (b["n_ok"], b["metrics"]["t"]["n"], b["metrics"]["t"]["n_nan"]) == (3, 2, 1)
    assert b["metrics"]["t"]["mean"] == 20.0 and b["metrics"]["t"]["q50"] == 20.0


def test_batch_statistics_default_to_one_group_of_all_runs():
    (whole,) = batch_statistics({"t": [1.0, 2.0, 3.0]})
    assert (whole["key"], whole["n_runs"], whole["n_ok"]) == (None, 3, 3)
    assert whole["metrics"]["t"]["mean"] == 2.0 and whole["drawn"] == {}


def test_a_group_without_an_ok_run_has_no_numbers():
    (entry,) = batch_statistics({"t": [1.0, 2.0]}, ok=[False, False])
    assert entry["n_ok"] == 0 and entry["metrics"]["t"]["n"] == 0
    assert all(math.isnan(entry["metrics"]["t"][k]) for k in ("mean", "std", "q50", "max"))


def test_empty_batch():
    (entry,) = batch_statistics({"t": []}, ok=[])
    assert (entry["n_runs"], entry["n_ok"], entry["metrics"]["t"]["n"]) == (0, 0, 0)
    assert math.isnan(entry["metrics"]["t"]["mean"])
    (nothing,) = batch_statistics({})
    assert (nothing["n_runs"], nothing["runs"].size, nothing["metrics"]) == (0, 0, {})
    assert group_runs([]) == {} and metric_statistics({}) == {}


def test_summary_rows_name_their_numbers_not_flags_or_text():
    row = {"run": 0, "status": "ok", "settled": True, "n_steps": 3, "time_s": 93.8, "kp": 1.0}
    assert numeric_keys(row, skip={"run", "kp"}) == ["n_steps", "time_s"]


def test_batch_statistics_need_one_value_per_run():
    with pytest.raises(ParameterError, match="one value per run"):
        batch_statistics({"t": [1.0, 2.0]}, ok=[True])
    with pytest.raises(ParameterError, match="one value per run"):
        batch_statistics({"t": [1.0, 2.0]}, drawn={"gain": [0.1]})
