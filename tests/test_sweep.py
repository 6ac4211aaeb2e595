"""Sweeps in this process: chunks equal one batch, resumable stores, seeds, draws, bad input.

The scenario is the demo's closed loop (Nomoto 2 + rudder servo + PID heading, compiled by the
suite already), 60 s long, over a grid of two gains × 7 Monte-Carlo samples with a truncated
normal and a correlated pair of draws. The reference is what the engine gives for the whole
batch in one call (``run_scenario``), never values computed by the sweep itself.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.numerics.sampling import CorrelatedNormal, TruncatedNormal, draw_samples, \
    get_distribution, sample_generator
from seahelm.scenario import ScenarioError, parse_scenario, run_scenario
from seahelm.sweep import open_sweep, run_sweep
from seahelm.sweep.store import MARKERS

SCENARIO = """
title = "sweep test: PID gains x uncertain Nomoto model"
[vessel]
model = "nomoto2"
catalog = "mariner-nomoto2"
[actuator]
model = "rudder-servo"
[actuator.params]
max_angle_deg = 35.0
max_rate_deg = 2.33
time_constant = 1.0
[controller]
model = "pid-heading"
dt = 0.5
[controller.params]
kp = 4.0
ki = 0.0002
kd = 110.0
max_command_deg = 35.0
[controller.reference]
heading_deg = 20.0
[simulation]
t_final = 60.0
dt = 0.1
record_every = 10
[batch.grid]
"controller.params.kp" = [2.0, 4.0]
[batch.monte_carlo]
runs = 7
seed = 5
[batch.monte_carlo.draws]
"vessel.params.gain" = { distribution = "truncnormal", mean = 0.185, std = 0.02, low = 0.16 }
[[batch.monte_carlo.correlated]]
keys = ["vessel.params.t1", "controller.params.kd"]
mean = [118.0, 110.0]
covariance = [[25.0, 5.0], [5.0, 16.0]]
"""
N_RUNS = 14


@pytest.fixture
def scenario(tmp_path: Path) -> Path:
    path = tmp_path / "study.toml"
    path.write_text(SCENARIO)
    return path


def _load(store: Path, flat: bool = True):
    return open_sweep(store, flat=flat).load()


def _same_store(a, b) -> bool:
    """Identical stores (values, dims, coordinates, attributes) but for the scenario's path."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        ds.attrs.pop("scenario_source")
    return a.identical(b)


def _equal_arrays(a, b) -> bool:
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind == "f")


@pytest.fixture(scope="module")
def reference():
    """The whole batch in one engine call."""
    return run_scenario(parse_scenario(SCENARIO, source="study.toml")).to_xarray()


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    base = tmp_path_factory.mktemp("sweep")
    (base / "study.toml").write_text(SCENARIO)
    store = base / "study.zarr"
    report = run_sweep(base / "study.toml", store, chunk_size=4)
    return store, report


# -- draws --------------------------------------------------------------------------------
def test_a_sample_depends_on_its_index_only():
    marg = {"a": get_distribution("normal", mean=1.0, std=2.0),
            "b": get_distribution("truncnormal", mean=0.0, std=1.0, low=0.5)}
    block = [CorrelatedNormal(("c", "d"), [0.0, 1.0], [[1.0, 0.3], [0.3, 2.0]])]
    whole = draw_samples(marg, 11, np.arange(50), block)
    part = draw_samples(marg, 11, [37, 3, 20], block)
    for key in whole:
        assert np.array_equal(part[key], whole[key][[37, 3, 20]])
    # the generator of sample i is the i-th child of SeedSequence(seed).spawn(n)
    child = np.random.SeedSequence(11).spawn(50)[37]
    assert sample_generator(11, 37).normal() == np.random.default_rng(child).normal()


def test_correlated_draws_have_the_covariance():
    cov = np.array([[4.0, -1.2], [-1.2, 1.0]])
    block = CorrelatedNormal(("x", "y"), [10.0, -3.0], cov)
    draws = draw_samples({}, 3, np.arange(4000), [block])
    sample = np.cov(np.vstack([draws["x"], draws["y"]]))
    assert np.allclose(sample, cov, rtol=0.1, atol=0.05)
    assert abs(draws["x"].mean() - 10.0) < 0.1


@pytest.mark.parametrize("low, high", [(0.5, np.inf), (-np.inf, -1.0), (3.0, 4.0), (-1.0, 2.0)])
def test_truncated_normal_stays_in_its_range_with_the_truncated_mean(low, high):
    from scipy.stats import truncnorm

    d = TruncatedNormal(mean=2.0, std=0.5, low=2.0 + 0.5 * low, high=2.0 + 0.5 * high)
    rng = np.random.default_rng(0)
    x = np.array([d.sample(rng) for _ in range(4000)])
    assert x.min() >= d.low and x.max() <= d.high
    expected = 2.0 + 0.5 * truncnorm.mean(low, high)
    assert abs(x.mean() - expected) < 4 * 0.5 * truncnorm.std(low, high) / np.sqrt(x.size)


@pytest.mark.parametrize("cov, match", [
    ([[1.0, 2.0], [2.0, 1.0]], "positive definite; its smallest eigenvalue is -1"),
    ([[1.0, 0.5], [0.4, 1.0]], "symmetric"),
    ([[1.0]], "must be 2 x 2"),
])
def test_bad_covariance(cov, match):
    with pytest.raises(ParameterError, match=match):
        CorrelatedNormal(("a", "b"), [0.0, 0.0], cov)


def test_unknown_distribution_lists_the_valid_ones():
    with pytest.raises(ParameterError, match="unknown distribution 'gamma'; valid: normal, "
                                             "uniform, lognormal, truncnormal"):
        get_distribution("gamma", mean=1.0)


@pytest.mark.parametrize("edit, match", [
    (('"truncnormal"', '"weibull"'), "truncnormal"),
    (("[[25.0, 5.0], [5.0, 16.0]]", "[[25.0, 30.0], [30.0, 16.0]]"), "positive definite"),
    (("mean = [118.0, 110.0]", "mean = [118.0]"), "needs 2 values"),
    (('keys = ["vessel.params.t1"', 'keys = ["vessel.params.gain"'), "drawn twice"),
    ((", low = 0.16 }", " }"), "truncnormal draw needs `low` and/or `high`"),
])
def test_bad_monte_carlo_sections_name_the_problem(edit, match):
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(SCENARIO.replace(*edit))


# -- the sweep ----------------------------------------------------------------------------
def test_sweep_equals_the_batch_run_at_once(uninterrupted, reference):
    store, report = uninterrupted
    assert (report.n_runs, report.n_chunks, report.computed, report.skipped) == (N_RUNS, 4, 4, 0)
    shaped = _load(store, flat=False)
    assert dict(shaped["status"].sizes) == {"kp": 2, "sample": 7}
    compared = 0
    for name, var in reference.data_vars.items():
        if name == "status_message":
            continue
        assert _equal_arrays(shaped[name].transpose(*var.dims).values, var.values), name
        compared += 1
    assert compared > 20
    for key in ("vessel.params.gain", "vessel.params.t1", "controller.params.kd"):
        assert _equal_arrays(shaped[key].values, reference[key].values)
    flat = _load(store)
    assert np.array_equal(flat["run"].values, np.arange(N_RUNS))
    assert sorted(p.name for p in (store / MARKERS).iterdir()) == \
        ["000000", "000001", "000002", "000003", "init"]


def test_the_chunk_size_changes_nothing_but_the_chunking(uninterrupted, scenario, tmp_path):
    store, _ = uninterrupted
    other = tmp_path / "one.zarr"
    run_sweep(scenario, other, chunk_size=N_RUNS)
    a, b = _load(store), _load(other)
    for name in a.variables:
        assert _equal_arrays(a[name].values, b[name].values), name


def test_the_store_holds_the_scenario_and_the_statistics(uninterrupted, reference):
    store, report = uninterrupted
    attrs = _load(store).attrs
    assert attrs["scenario_text"] == SCENARIO
    assert attrs["seed"] == 5
    summary = json.loads(attrs["sweep_summary"])
    assert summary == json.loads(json.dumps(report.summary))
    assert summary["n_ok"] + summary["n_failed"] == N_RUNS
    assert summary["n_ok"] == int((reference["status"] == 0).sum())
    row = next(r for r in summary["metrics"] if r["name"] == "final_heading_rad")
    final = reference["heading"].isel(time=-1).values.ravel()
    assert row["n"] == N_RUNS
    assert row["mean"] == pytest.approx(final.mean(), rel=1e-12)
    assert row["q50"] == pytest.approx(np.median(final), rel=1e-12)


def test_an_interrupted_sweep_resumes_to_the_same_store(uninterrupted, scenario, tmp_path):
    store = tmp_path / "study.zarr"
    seen = []

    def stop_after_two(done: int, total: int) -> None:
        seen.append(done)
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(scenario, store, chunk_size=4, progress=stop_after_two)
    assert len(list((store / MARKERS).glob("0*"))) == 2
    partial = open_sweep(store)
    assert int(partial["complete"].sum()) == 8
    report = run_sweep(scenario, store)  # the same command: the store's chunk size
    assert (report.computed, report.skipped, report.chunk_size) == (2, 2, 4)
    assert _same_store(_load(store), _load(uninterrupted[0]))


def test_a_chunk_written_without_its_marker_is_written_again(uninterrupted, scenario, tmp_path):
    store = tmp_path / "copy.zarr"
    shutil.copytree(uninterrupted[0], store)
    (store / MARKERS / "000002").unlink()  # died between the region write and the marker
    for path in (store / "heading").rglob("*"):  # and left the region half-written
        if path.is_file() and path.name != "zarr.json" and "/2" in str(path.relative_to(store)):
            path.write_bytes(b"garbage")
    report = run_sweep(scenario, store)
    assert (report.computed, report.skipped) == (1, 3)
    assert _same_store(_load(store), _load(uninterrupted[0]))


def test_same_seed_same_store_other_seed_other_draws(uninterrupted, tmp_path):
    again = tmp_path / "again.toml"
    again.write_text(SCENARIO)
    run_sweep(again, tmp_path / "again.zarr", chunk_size=4)
    a, b = _load(uninterrupted[0]), _load(tmp_path / "again.zarr")
    assert _same_store(a, b)
    other = tmp_path / "other.toml"
    other.write_text(SCENARIO.replace("seed = 5", "seed = 6"))
    run_sweep(other, tmp_path / "other.zarr", chunk_size=4)
    c = _load(tmp_path / "other.zarr")
    for key in ("vessel.params.gain", "vessel.params.t1", "controller.params.kd"):
        assert not np.any(a[key].values == c[key].values), key
    assert np.array_equal(a["kp"].values, c["kp"].values)


@pytest.mark.parametrize("chunk", [0, -3, 2.5, True])
def test_bad_chunk_size(scenario, tmp_path, chunk):
    with pytest.raises(ParameterError, match="`chunk_size` must be a whole number >= 1"):
        run_sweep(scenario, tmp_path / "s.zarr", chunk_size=chunk)
    assert not (tmp_path / "s.zarr").exists()


def test_another_scenarios_store_is_refused_unless_overwrite(uninterrupted, tmp_path):
    store = tmp_path / "copy.zarr"
    shutil.copytree(uninterrupted[0], store)
    other = tmp_path / "other.toml"
    other.write_text(SCENARIO.replace("t_final = 60.0", "t_final = 30.0"))
    before = sorted(p.name for p in store.rglob("*"))
    with pytest.raises(ParameterError, match="holds the sweep of another scenario"):
        run_sweep(other, store)
    assert sorted(p.name for p in store.rglob("*")) == before
    with pytest.raises(ParameterError, match="in chunks of 4 runs, not 5"):
        run_sweep(tmp_path / "s.toml", store, text=SCENARIO, chunk_size=5)
    with pytest.raises(ParameterError, match="with the time series; resume without "
                                             "--no-series"):
        run_sweep(tmp_path / "s.toml", store, text=SCENARIO, series=False)
    report = run_sweep(other, store, overwrite=True, chunk_size=N_RUNS)
    assert report.computed == 1
    assert _load(store)["time"].values[-1] == 30.0


def test_a_path_that_is_not_a_store_is_never_deleted(scenario, tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "precious.txt").write_text("x")
    for overwrite in (False, True):
        with pytest.raises(ParameterError, match="exists and is not a sweep store"):
            run_sweep(scenario, tmp_path / "data", overwrite=overwrite)
    assert (tmp_path / "data" / "precious.txt").read_text() == "x"
    with pytest.raises(ParameterError, match="is a file"):
        run_sweep(scenario, tmp_path / "data" / "precious.txt")


def test_scheduler_and_workers_are_checked_before_any_run(scenario, tmp_path):
    with pytest.raises(ParameterError, match="not both"):
        run_sweep(scenario, tmp_path / "s.zarr", workers=2, scheduler="tcp://127.0.0.1:1")
    with pytest.raises(ParameterError, match="`workers` must be a whole number >= 1"):
        run_sweep(scenario, tmp_path / "s.zarr", workers=0)
    with pytest.raises(ParameterError, match="address such as tcp://HOST:PORT"):
        run_sweep(scenario, tmp_path / "s.zarr", scheduler="localhost")
    assert not (tmp_path / "s.zarr").exists()


def test_an_interrupted_initialisation_leaves_no_half_store(scenario, tmp_path, monkeypatch):
    import seahelm.sweep.store as store_module

    real = store_module._build

    def build_then_die(*args, **kwargs):
        real(*args, **kwargs)
        raise KeyboardInterrupt

    monkeypatch.setattr(store_module, "_build", build_then_die)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(scenario, tmp_path / "s.zarr", chunk_size=7)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.toml"]
    monkeypatch.setattr(store_module, "_build", real)
    report = run_sweep(scenario, tmp_path / "s.zarr", chunk_size=7)
    assert (report.computed, report.skipped) == (2, 0)


def test_writing_a_chunk_again_writes_the_same_bytes(uninterrupted, tmp_path):
    from seahelm.sweep import compute_chunk
    from seahelm.sweep.chunks import SweepSpec
    from seahelm.sweep.store import write_chunk

    store = tmp_path / "copy.zarr"
    shutil.copytree(uninterrupted[0], store)
    attrs = json.loads((store / "zarr.json").read_text())["attributes"]
    spec = SweepSpec(text=SCENARIO, source=attrs["scenario_source"],
                     chunk_size=attrs["sweep_chunk_size"], n_runs=attrs["sweep_n_runs"])
    assert spec.fingerprint == attrs["sweep_fingerprint"]

    def files(root):
        return {p.relative_to(root): p.read_bytes() for p in root.rglob("*")
                if p.is_file() and MARKERS not in p.parts}

    before = files(store)
    write_chunk(store, spec, 1, compute_chunk(spec, 1))
    assert files(store) == before
