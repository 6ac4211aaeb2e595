"""Encounters in chunks (seahelm.encounters.chunked): chunk by chunk in this process and on a
local dask cluster, the result equals the whole batch run at once, bit for bit (avoidance
on); `seahelm encounter --workers/--chunk-size` prints the same table."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.encounters import Encounter
from seahelm.encounters.chunked import concat_results, run_chunked, split_encounter
from seahelm.encounters.monte_carlo import monte_carlo_vessels
from seahelm.errors import ParameterError

runner = CliRunner()


def _encounter():
    vessels, _ = monte_carlo_vessels(7, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                     seed=3, detection_range=(3000.0, 3500.0),
                                     tcpa=(100.0, 300.0), overtaking=0.3,
                                     overtaking_range=(1200.0, 1600.0))
    return Encounter(vessels, t_final=360.0, avoidance="velocity-obstacles", record_every=5)


def _same(a, b):
    for name in a.tracks:
        assert np.array_equal(a.tracks[name], b.tracks[name], equal_nan=True), name
    for name in a.pair:
        assert np.array_equal(a.pair[name], b.pair[name], equal_nan=True), name
    for name in a.verdicts:
        assert np.array_equal(a.verdicts[name], b.verdicts[name], equal_nan=True), name
    for name in ("status", "min_range", "t_min_range", "min_domain_distance", "situation",
                 "collision", "near_miss"):
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name
    assert a.summary() == b.summary()


@pytest.fixture(scope="module")
def whole():
    return _encounter().run()


def test_chunks_in_process_equal_the_whole_batch(whole):
    enc = _encounter()
    assert [len(np.atleast_1d(c[0][1].north)) for c in split_encounter(enc, 3)] == [3, 3, 1]
    res = run_chunked(enc, chunk_size=3)
    _same(res, whole)
    assert np.ptp(whole.tracks["heading"][:, 0], axis=-1).max() > 0.2  # (it avoided)


def test_chunks_on_a_local_dask_cluster_equal_the_whole_batch(whole):
    pytest.importorskip("distributed")
    _same(run_chunked(_encounter(), chunk_size=2, workers=2), whole)


def test_bad_chunking():
    enc = _encounter()
    with pytest.raises(ParameterError, match="chunk_size"):
        split_encounter(enc, 0)
    with pytest.raises(ParameterError, match="workers"):
        run_chunked(enc, workers=0)
    vessels = list(enc.vessels)
    with pytest.raises(ParameterError, match="joined"):
        short = Encounter(vessels, t_final=60.0).run()
        concat_results([short, Encounter(vessels, t_final=30.0).run()])


def test_cli_chunked_prints_the_same_table():
    args = ["encounter", "--monte-carlo", "6", "--t-final", "600", "--detection", "4000",
            "--seed", "8", "--avoidance", "rule-based", "--json"]
    one = runner.invoke(app, args)
    two = runner.invoke(app, [*args, "--chunk-size", "4"])
    assert one.exit_code == 0 and two.exit_code == 0, (one.output, two.output)
    a, b = json.loads(one.output)["methods"], json.loads(two.output)["methods"]
    assert a == b
    bad = runner.invoke(app, [*args, "--workers", "0"])
    assert bad.exit_code == 2 and "--workers" in bad.output
