"""`seahelm report encounters.nc`: the file `seahelm encounter --out` writes gives a page with
the outcome table by COLREG situation (rates with Wilson intervals), the tracks with domains,
range/CPA over time and the outcome rose; the file round-trips to an EncounterResult; bad
files are exit 2 with one line."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app

runner = CliRunner()


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("enc") / "study"
    res = runner.invoke(app, ["encounter", "--monte-carlo", "8", "--t-final", "300",
                              "--detection", "2600", "--seed", "2", "--overtaking", "0",
                              "--avoidance", "rule-based", "--out", str(out), "--json"])
    assert res.exit_code == 0, res.output
    return out, json.loads(res.output)["methods"]["rule-based"]


def test_the_file_round_trips_to_the_same_summary(study):
    import xarray as xr

    from seahelm.encounters.result import EncounterResult

    out, printed = study
    with xr.open_dataset(out / "encounters.nc") as ds:
        ds = ds.load()
    assert ds.attrs["avoidance"] == "rule-based"
    back = EncounterResult.from_xarray(ds)
    assert json.loads(json.dumps(back.summary())) == printed  # as printed, from the file
    assert back.lengths.tolist() == [320.0, 320.0]
    assert back.collision.dtype == bool and back.verdicts["acted"].dtype == bool


def test_report_of_an_encounter_study(study):
    import xarray as xr

    from seahelm.report import load_report_data
    from seahelm.report.encounters import ROSE_SECTORS, rose_counts
    from seahelm.report.sections import build_sections

    out, printed = study
    res = runner.invoke(app, ["report", str(out / "encounters.nc")])
    assert res.exit_code == 0, res.output
    assert "8 encounter(s)" in " ".join(res.output.split())
    page = (out / "report.html").read_text()
    assert "Ships meeting ships" in page and "rule-based" in page
    with xr.open_dataset(out / "encounters.nc") as ds:
        ds = ds.load()
    # the table's rows, counted here from the file's arrays (not by summary())
    sit = ds["situation"].values[:, 0]
    coll = ds["collision"].values[:, 0].astype(bool)
    from seahelm.encounters import Situation
    flat = page.replace("\n", "")
    shown = 0
    for code in Situation:
        name = code.name.lower().replace("_", "-")
        n = int((sit == code).sum())
        if n:
            shown += 1
            assert (f"<td>{name}</td><td>{n}</td><td>{100 * coll[sit == code].mean():.1f} % ["
                    in flat)
    assert shown >= 2 and f"<td>all</td><td>8</td><td>{100 * coll.mean():.1f} % [" in flat
    data = load_report_data(out / "encounters.nc")
    secs = {s.id: s for s in build_sections(data)}
    assert "encounters" in secs and data.n_runs == 8
    figures = [b for b in secs["encounters"].blocks if isinstance(b, dict)]
    kinds = [f["data"][0]["type"] for f in figures]
    assert kinds.count("barpolar") == 1 and kinds.count("scatter") >= 2
    # the rose: every encounter once, in the sector of its bearing at the start (drawn
    # geometry: own ship heading north at the origin)
    counts = rose_counts(data_result(ds))
    assert sum(int(c.sum()) for c in counts.values()) == 8
    beta = np.arctan2(ds["east"].values[:, 1, 0], ds["north"].values[:, 1, 0]) % (2 * math.pi)
    width = 2 * math.pi / ROSE_SECTORS
    expect = np.bincount(np.floor((beta + width / 2) / width).astype(int) % ROSE_SECTORS,
                         minlength=ROSE_SECTORS)
    assert (sum(counts.values()) == expect).all()


def data_result(ds):
    from seahelm.encounters.result import EncounterResult
    return EncounterResult.from_xarray(ds)


def test_an_encounter_file_is_reported_alone_and_a_damaged_one_named(study, tmp_path):
    import xarray as xr

    from seahelm.results import write_netcdf

    out, _ = study
    res = runner.invoke(app, ["report", str(out / "encounters.nc"), str(out / "encounters.nc"),
                              "-o", str(tmp_path / "r.html")])
    assert res.exit_code == 2 and "reported alone" in res.output
    with xr.open_dataset(out / "encounters.nc") as ds:
        ds = ds.load()
    write_netcdf(ds.drop_vars("pair_dcpa"), tmp_path / "bad.nc")
    res = runner.invoke(app, ["report", str(tmp_path / "bad.nc")])
    assert res.exit_code == 2 and "pair_dcpa" in res.output
    assert len(res.output.strip().splitlines()) == 1
