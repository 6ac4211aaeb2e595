"""The HTML report (``seahelm report``, ``seahelm run --report``, ``seahelm demo``): what the
page holds, how a large batch is summarised, and bad input (exit 2, no HTML left behind).

The page in a real browser: tests/test_report_browser.py. The result files come from the
session fixtures of tests/conftest.py.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from conftest import one_error
from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.report import load_report_data, write_report
from seahelm.report.signals import (
    MAX_POINTS,
    MAX_RUNS_PLOTTED,
    decimated_index,
    find_signal,
    outline_interval,
    plotted_runs,
    ship_outlines,
)
from seahelm.results import load_result
from seahelm.units import metric_label

runner = CliRunner()

#: The first line of the inlined plotly.js bundle.
PLOTLY_BANNER = re.compile(r"\* plotly\.js v\d")


def self_contained(page: str) -> None:
    """plotly.js inlined exactly once, nothing loaded from anywhere."""
    assert len(PLOTLY_BANNER.findall(page)) == 1
    assert not re.search(r"<script[^>]*\bsrc\s*=", page)
    assert not re.search(r"""<(link|img|iframe)[^>]*\b(src|href)\s*=\s*["']?(https?:)?//""",
                         page)


# ------------------------------------------------------------------------------------------
# the demo, a batch with diverged runs, the IMO check
# ------------------------------------------------------------------------------------------
def test_demo_writes_the_report_beside_the_netcdf(report_demo_dir):
    page = (report_demo_dir / "report.html").read_text()
    self_contained(page)
    for sid in ("overview", "status", "metrics", "track", "timeseries"):
        assert f'<section id="{sid}">' in page
    assert page.count("Plotly.newPlot(") == 2  # track and time series
    assert "Mariner: 20 degree course change under PID" in page
    for text in ("integrator", "rk4", "seahelm version", "none (nothing random in the runs)",
                 "# The embedded default scenario", "1 run(s): 1 ok, 0 diverged",
                 "hull outlines every 50 s, L = 160.9 m"):
        assert text in page, text
    assert (report_demo_dir / "report.html").stat().st_size < 6e6


def test_report_command_default_path_and_json(report_demo_dir, tmp_path):
    src = tmp_path / "result.nc"
    src.write_bytes((report_demo_dir / "result.nc").read_bytes())
    res = runner.invoke(app, ["report", str(src), "--json"])
    assert res.exit_code == 0, res.stderr
    got = json.loads(res.stdout)
    assert got["report"] == str(tmp_path / "report.html") and got["n_runs"] == 1
    assert got["sections"] == ["overview", "status", "metrics", "track", "timeseries"]
    assert (tmp_path / "report.html").stat().st_size == got["bytes"]
    res = runner.invoke(app, ["report", str(src), "-o", str(tmp_path / "sub" / "r.html")])
    assert res.exit_code == 0 and "wrote" in res.stdout
    assert (tmp_path / "sub" / "r.html").is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html", "result.nc", "sub"]


def test_batch_report_lists_diverged_runs_and_statistics(report_batch_dir):
    page = (report_batch_dir / "report.html").read_text()
    self_contained(page)
    assert "10 run(s): 5 ok, 5 diverged" in page
    table = page[page.index('class="diverged"'):]
    table = table[:table.index("</table>")]
    assert table.count("<tr>") == 1 + 5  # header + every diverged run
    assert "state out of bounds" in table and "kp 4" in table
    assert '<section id="statistics">' in page
    assert "over the ok runs: kp 1 rad/rad: 5 ok of 5; kp 4 rad/rad: 0 ok of 5" in page
    assert "(no ok run: no metrics)" in page
    assert "dimension kp" in page and "controller.params.kp = 1, 4" in page
    assert "vessel.params.gain (normal)" in page
    # the drawn gain's and the metrics' histograms, track, time series
    assert page.count("Plotly.newPlot(") == 4


def test_imo_report_has_the_criteria_and_both_manoeuvres(report_imo_dir):
    page = (report_imo_dir / "report.html").read_text()
    self_contained(page)
    assert "kvlcc2-l7 (L = 7 m" in page and "PASSES the evaluated criteria" in page
    table = page[page.index('class="imo"'):]
    table = table[:table.index("</table>")]
    assert table.count('<tr class="pass">') == 13  # stopping evaluated too
    assert table.count('<tr class="not-evaluated">') == 0
    for sid in ("imo", "track-turning-circle", "track-zigzag", "timeseries-zigzag",
                "track-stopping", "timeseries-stopping"):
        assert f'id="{sid}"' in page
    stopping = page[page.index('id="timeseries-stopping"'):]
    stopping = stopping[:stopping.index("</section>")]
    assert "propeller [1" in stopping  # the reversal shown (the order, constant, is not)
    # any file of the check gives the same report
    for name in ("zigzag-metrics.nc", "stopping-runs.nc"):
        data = load_report_data(report_imo_dir / name)
        assert [s.name for s in data.sets] == ["turning-circle", "zigzag", "stopping"]
    assert data.imo is not None and data.imo.sizes["row"] == 13


def test_a_manoeuvre_without_imo_report(report_imo_dir, tmp_path):
    for name in ("zigzag-runs.nc", "zigzag-metrics.nc"):
        (tmp_path / name).write_bytes((report_imo_dir / name).read_bytes())
    data = load_report_data(tmp_path / "zigzag-runs.nc")
    assert data.imo is None and [s.name for s in data.sets] == ["zigzag"]
    assert data.sets[0].metrics is not None and data.title == "zigzag, kvlcc2-l7"
    summary = write_report(data, tmp_path / "z.html")
    assert summary.sections == ("overview", "status", "metrics", "track", "timeseries")
    page = (tmp_path / "z.html").read_text()
    assert "overshoot 1 [deg]" in page and "pair 1, starboard, rudder 20°, trigger 20°" in page


# ------------------------------------------------------------------------------------------
# large batches are summarised
# ------------------------------------------------------------------------------------------
def test_a_10000_run_batch_gives_a_file_under_10_mb(report_demo_dir, tmp_path):
    """10,000 runs of a Monte-Carlo batch (the demo's result repeated with scattered
    headings and 300 diverged runs) through the same path as a file."""
    one = load_result(report_demo_dir / "result.nc").isel(time=slice(None, None, 30))
    keep = [n for n, v in one.data_vars.items() if v.attrs.get("kind") in ("state", "output",
                                                                            "reference")
            or "time" not in v.dims]
    one = one[keep]
    n = 10_000
    big = one.isel(run=np.zeros(n, dtype=int)).drop_vars("run").rename(run="sample")
    rng = np.random.default_rng(1)
    big["heading"] = big["heading"] * xr.DataArray(1 + 0.05 * rng.standard_normal(n),
                                                   dims="sample")
    status = np.zeros(n, dtype=np.int64)
    status[rng.choice(n, 300, replace=False)] = 2
    big["status"] = ("sample", status)
    big["failure_time"] = ("sample", np.where(status != 0, 42.0, np.nan))
    big["status_message"] = ("sample", np.where(status != 0, "diverged: state out of bounds "
                                                "at t = 42 s", "ok"))
    path = tmp_path / "big.html"
    summary = write_report(big, path)
    assert summary.n_runs == n
    assert path.stat().st_size < 10e6
    page = path.read_text()
    assert f"{MAX_RUNS_PLOTTED} of {n} runs drawn" in page and "of 9700 ok runs" in page
    assert "the band is the 5–95 % range over all ok runs" in page
    assert "10000 run(s): 9700 ok, 300 diverged" in page
    assert "first 500 of 300" not in page and page.count("state out of bounds") >= 300
    assert '<section id="statistics">' in page and "over the ok runs: 9700 ok of 10000" in page
    # the per-run table is summarised: the runs drawn in the plots, not 10,000 rows
    runs_table = page[page.index('class="summary"'):]
    runs_table = runs_table[:runs_table.index("</table>")]
    assert runs_table.count("<tr>") == 1 + MAX_RUNS_PLOTTED
    assert f"{MAX_RUNS_PLOTTED} of {n} runs: those drawn in the plots" in page


def test_plotted_runs_spread_and_diverged_first():
    status = np.zeros(1000, dtype=int)
    status[[3, 500, 998]] = 2
    shown = plotted_runs(status)
    assert shown.size == MAX_RUNS_PLOTTED and {3, 500, 998} <= set(shown.tolist())
    assert shown[0] == 0 and shown[-1] == 999
    assert plotted_runs(np.zeros(5)).tolist() == [0, 1, 2, 3, 4]


@pytest.mark.parametrize("n", [10, 2000, 2001, 6001, 100_000])
def test_decimation_keeps_the_ends(n):
    idx = decimated_index(n)
    assert idx.size <= MAX_POINTS and idx[0] == 0 and idx[-1] == n - 1
    assert np.all(np.diff(idx) > 0)


def test_outline_interval_is_1_2_5():
    assert outline_interval(600.0) == 50.0
    assert outline_interval(108.0) == 10.0
    assert outline_interval(30.0) == 5.0


def test_hull_outline_points_along_the_heading():
    t = np.array([0.0, 1.0])
    east, north = ship_outlines(t, np.zeros(2), np.zeros(2), np.array([90.0, 90.0]),
                                length=100.0, breadth=20.0, interval=10.0)
    assert np.isnan(east[-1]) and east.size == 7  # one polygon (t = 0) and its break
    assert east[0] == pytest.approx(50.0) and north[0] == pytest.approx(0.0, abs=1e-9)
    assert np.nanmin(east) == pytest.approx(-50.0) and np.nanmax(north) == pytest.approx(10.0)


def test_signals_found_by_name_in_other_spellings():
    ds = xr.Dataset({"x": (("run", "time"), np.ones((1, 3)), {"units": "m"}),
                     "psi": (("run", "time"), np.full((1, 3), math.pi), {"units": "rad"}),
                     "u": (("run", "time"), np.full((1, 3), 3.0), {"units": "m/s"}),
                     "v": (("run", "time"), np.full((1, 3), 4.0), {"units": "m/s"})})
    assert find_signal(ds, "north").name == "x"
    heading = find_signal(ds, "heading")
    assert heading.units == "deg" and heading.values[0, 0] == pytest.approx(180.0)
    assert find_signal(ds, "speed").values[0, 0] == pytest.approx(5.0)
    assert find_signal(ds, "rudder") is None


# ------------------------------------------------------------------------------------------
# bad input: exit 2, one line, no HTML under the final name
# ------------------------------------------------------------------------------------------
def test_a_netcdf_not_written_by_seahelm(tmp_path):
    path = tmp_path / "other.nc"
    xr.Dataset({"a": ("x", np.arange(3.0))}).to_netcdf(path, engine="h5netcdf")
    assert "not a seahelm result file" in one_error(["report", str(path)])
    text = tmp_path / "notes.nc"
    text.write_text("hello")
    assert "not a NetCDF-4/HDF5 file" in one_error(["report", str(text)])
    assert not list(tmp_path.glob("*.html")) and not list(tmp_path.glob(".*"))


def test_a_result_without_runs(report_demo_dir, tmp_path):
    empty = load_result(report_demo_dir / "result.nc").isel(run=slice(0, 0))
    path = tmp_path / "empty.nc"
    empty.to_netcdf(path, engine="h5netcdf")
    assert "holds no runs" in one_error(["report", str(path)])
    assert not (tmp_path / "empty.html").exists()


@pytest.mark.parametrize("store", ["missing.zarr", "empty.zarr/"])
def test_a_missing_or_empty_store_is_refused(tmp_path, store):
    path = tmp_path / store
    if store.endswith("/"):
        path.mkdir()
    message = one_error(["report", str(path)])
    assert "no such sweep store" in message or "not a sweep store" in message
    with pytest.raises(ParameterError, match="not a sweep store"):
        load_report_data(tmp_path / "empty.zarr")
    assert not list(tmp_path.rglob("*.html"))


def test_missing_input_and_unwritable_output(report_demo_dir, tmp_path):
    src = report_demo_dir / "result.nc"
    assert "no such file" in one_error(["report", str(tmp_path / "nope.nc")])
    afile = tmp_path / "afile"
    afile.write_text("x")
    assert "is a file, not a directory" in one_error(
        ["report", str(src), "-o", str(afile / "r.html")])
    assert "must be a file name" in one_error(["report", str(src), "-o", str(tmp_path)])
    assert "cannot write in" in one_error(["report", str(src), "-o", "/proc/r.html"])
    assert "is a file this command reads: writing it would destroy it" in one_error(
        ["report", str(src), "-o", str(src)])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile"]


def test_a_failure_while_writing_leaves_no_partial_html(report_demo_dir, tmp_path,
                                                        monkeypatch):
    target = tmp_path / "r.html"
    target.write_text("the previous report")

    def broken(*args, **kwargs):
        raise RuntimeError("disk full")

    monkeypatch.setattr("plotly.offline.get_plotlyjs", broken)
    # (--force: the file is not a seahelm report, which the output policy keeps without it)
    res = runner.invoke(app, ["report", str(report_demo_dir / "result.nc"), "-o", str(target),
                              "--force"])
    assert res.exit_code == 1 and "disk full" in res.stderr
    assert target.read_text() == "the previous report"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.html"]


def test_run_report_needs_out():
    scenario = Path(__file__).resolve().parents[1] / "examples" / "mariner_course_change.toml"
    assert "`--report` writes report.html" in one_error(["run", str(scenario), "--report"])


def test_run_report_of_a_maneuver_scenario(tmp_path):
    """A [maneuver] scenario (the KVLCC2 turning circles, the kernel of `seahelm imo`'s
    turning): report.html beside the manoeuvre's files."""
    scenario = Path(__file__).resolve().parents[1] / "examples" / "kvlcc2_turning_circles.toml"
    res = runner.invoke(app, ["run", str(scenario), "--out", str(tmp_path), "--no-plot",
                              "--report"])
    assert res.exit_code == 0, res.stderr
    assert "report:" in res.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "report.html", "turning-circle-metrics.nc", "turning-circle-runs.nc"]
    page = (tmp_path / "report.html").read_text()
    assert "tactical diameter [m]" in page and "rudder 20°, starboard" in page
    assert page.count("Plotly.newPlot(") == 2


def test_the_report_target_is_checked_before_anything_runs(tmp_path, monkeypatch):
    import seahelm.scenario as scenario

    def tripwire(*args, **kwargs):
        raise AssertionError("ran before the output path was checked")

    monkeypatch.setattr(scenario, "run_scenario", tripwire)
    (tmp_path / "report.html").mkdir()
    assert "report.html is a directory" in one_error(["demo", "--out", str(tmp_path)])
    example = Path(__file__).resolve().parents[1] / "examples" / "mariner_course_change.toml"
    assert "report.html is a directory" in one_error(
        ["run", str(example), "--out", str(tmp_path), "--report"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html"]


def test_metrics_along_a_dimension_of_their_own_get_a_table(tmp_path):
    """A direct spiral's metrics: one run, values per step (here synthetic, no time series)."""
    from seahelm.report import ReportData, RunSet

    steps = np.arange(6)
    metrics = xr.Dataset(
        {"yaw_rate": ("step", np.radians(np.linspace(2, -2, 6)), {"units": "rad/s"}),
         "loop_width": ((), 0.01, {"units": "rad"}), "complete": ((), np.int8(1)),
         "message": ((), "ok")},
        coords={"step": steps, "step_rudder": ("step", np.radians(np.linspace(10, -10, 6)),
                                               {"units": "rad"})},
        attrs={"maneuver": "direct-spiral"})
    data = ReportData("spiral", (RunSet("direct-spiral", None, metrics),))
    summary = write_report(data, tmp_path / "s.html")
    assert summary.sections == ("overview", "metrics") and summary.n_runs == 0
    page = (tmp_path / "s.html").read_text()
    assert "step rudder [deg]" in page and "yaw rate [deg/s]" in page and "per step" in page
    assert "yaw rate 1" not in page and "loop width [deg]" in page


def test_a_sweep_store_report(report_sweep_dir):
    """The sweep section: state, statistics as stored with the sweep, histograms."""
    import json

    from seahelm.report.sections import sweep_sections
    from seahelm.sweep.store import store_attrs

    data = load_report_data(report_sweep_dir / "sweep.zarr")
    assert data.sweep is not None and data.sweep.sizes["run"] == 10
    [sec] = sweep_sections(data)
    html_text = "".join(b for b in sec.blocks if isinstance(b, str))
    stored = json.loads(store_attrs(report_sweep_dir / "sweep.zarr")["sweep_summary"])
    assert f"{stored['n_ok']} ok, {stored['n_failed']} failed of 10 runs" in html_text
    assert stored["n_failed"] == 5  # kp = 4 leaves the bounds in every sample
    for m in stored["metrics"][:3]:  # (labelled in words, with the display unit)
        assert f"<td>{metric_label(m['name'], m['units'])}</td>" in html_text
    assert any(isinstance(b, dict) for b in sec.blocks)  # the histograms
    assert (report_sweep_dir / "report.html").stat().st_size < 10e6
    # a directory that is not a sweep store: a clear error, exit 2, nothing written
    (report_sweep_dir / "other").mkdir(exist_ok=True)
    assert "not a sweep store" in one_error(["report", str(report_sweep_dir / "other")])
    assert not (report_sweep_dir / "other.html").exists()


# ------------------------------------------------------------------------------------------
# what a person sees (issue 36): counts, units, drawn inputs, no empty column
# ------------------------------------------------------------------------------------------
def _tables(page: str, cls: str) -> list[tuple[list[str], list[list[str]]]]:
    """The header and body cells of every table of class ``cls`` in a page (tags removed)."""
    out = []
    for match in re.finditer(rf'<table class="{cls}">(.*?)</table>', page, re.S):
        body = match.group(1)
        head = [re.sub(r"<[^>]+>", "", h) for h in re.findall(r"<th>(.*?)</th>", body)]
        rows = [[re.sub(r"<[^>]+>", "", c) for c in re.findall(r"<td[^>]*>(.*?)</td>", r)]
                for r in re.findall(r"<tr[^>]*>(.*?)</tr>", body.split("<tbody>")[1])]
        out.append((head, rows))
    return out


def test_the_per_run_table_shows_drawn_values_and_display_units(report_batch_dir):
    """A grid × Monte-Carlo batch: each run's drawn gain beside its metrics, every metric
    labelled with its display unit (angles in degrees), an angle once, no column that is
    blank in every row."""
    page = (report_batch_dir / "report.html").read_text()
    ds = load_result(report_batch_dir / "result.nc")
    gains = np.asarray(ds["vessel.params.gain"].values).reshape(-1)
    heading = np.degrees(np.asarray(ds["heading"].values)[..., -1].reshape(-1))
    [(head, rows)] = _tables(page, "summary")
    assert head[:2] == ["run", "vessel.params.gain [1/s]"] and "status" in head
    assert "final heading [deg]" in head and "final yaw rate [deg/s]" in head
    for hidden in ("heading [deg]", "final heading rad", "final yaw aux", "final heading [rad]"):
        assert hidden not in head, hidden
    assert len(rows) == gains.size == 10
    col = head.index("final heading [deg]")
    for row in rows:
        i = int(row[0].split()[1])
        assert float(row[1]) == pytest.approx(gains[i], rel=1e-3)
        if row[head.index("status")] == "ok":
            assert float(row[col]) == pytest.approx(heading[i], rel=1e-3)
    for k, name in enumerate(head):
        assert any(r[k].strip() not in ("", "—") for r in rows), name  # filled, or omitted
    # a course change never turns a circle: its turning diameter is neither a column of
    # dashes nor a "not reached" note (issue 44: the note was under every course change)
    assert "turning diameter" not in head and "turning_diameter" not in page
    # the drawn inputs: their statistics (over all runs, ok or not) and their histogram
    [(drawn_head, drawn_rows)] = _tables(page, "statistics drawn")
    assert drawn_head[0] == "drawn input" and drawn_rows[0][0] == "vessel.params.gain [1/s]"
    assert drawn_rows[0][1] == "10" and float(drawn_rows[0][2]) == pytest.approx(
        gains.mean(), rel=1e-3)
    stats = page[page.index('<section id="statistics">'):]
    stats = stats[:stats.index("</section>")]
    assert stats.count("Plotly.newPlot(") == 2  # the drawn inputs' and the metrics'


def test_a_store_report_counts_every_run_of_the_store(report_sweep_dir, monkeypatch):
    """The runs read for the plots are not the store's runs ("Run status: 200 run(s)" was
    shown for a 10,000-run store): the counts are the store's, the notes say what is drawn."""
    import seahelm.report.inputs as inputs
    from seahelm.report import report_html

    monkeypatch.setattr(inputs, "MAX_SWEEP_RUNS", 4)
    data = load_report_data(report_sweep_dir / "sweep.zarr")
    assert data.sets[0].n_runs == 4 and data.sets[0].n_source == 10 and data.n_runs == 10
    page, _ = report_html(data)
    assert "10 run(s): 5 ok, 5 diverged" in page
    assert "of the first 4 of 10 runs drawn (the runs read from the store" in page
    diverged = _tables(page, "diverged")[0][1]
    assert len(diverged) == 5 and all(r[0].startswith("run ") for r in diverged)
    assert {int(r[0].split()[1]) for r in diverged} == {5, 6, 7, 8, 9}  # (the store's indices)


def test_a_store_report_shows_units_and_drawn_inputs(report_sweep_dir):
    """The sweep's statistics: unit in each label (the unit column was empty), values in the
    display unit, no empty "where" column; the drawn gain's statistics and histogram."""
    page = (report_sweep_dir / "report.html").read_text()
    stored = json.loads(load_report_data(report_sweep_dir / "sweep.zarr").sweep
                        .attrs["sweep_summary"])
    tables = _tables(page, "statistics")
    head, rows = tables[0]
    assert head[:3] == ["metric", "n", "mean"] and "where" not in head and "unit" not in head
    by_label = {r[0]: r for r in rows}
    heading = next(m for m in stored["metrics"] if m["name"] == "final_heading")
    assert heading["units"] == "rad"
    assert float(by_label["final heading [deg]"][2]) == pytest.approx(
        math.degrees(heading["mean"]), rel=1e-3)
    assert not any(k.startswith(("heading [deg]", "final heading [rad]")) for k in by_label)
    [(drawn_head, drawn_rows)] = _tables(page, "statistics drawn")
    assert drawn_rows[0][0] == "vessel.params.gain [1/s]" and drawn_rows[0][1] == "10"


def test_a_combined_report_of_several_results(report_demo_dir, report_batch_dir, tmp_path):
    """`seahelm report A.nc B.nc`: one page, each file's runs named by the file."""
    from seahelm.report import combined_report_data

    demo, batch = report_demo_dir / "result.nc", report_batch_dir / "result.nc"
    data = combined_report_data([demo, batch])
    names = [s.name for s in data.sets]
    assert names == [f"{demo.parent.name}/result", f"{batch.parent.name}/result"]
    assert data.n_runs == 1 + 10 and data.sources == (str(demo), str(batch))
    target = tmp_path / "both.html"
    res = runner.invoke(app, ["report", str(demo), str(batch), "-o", str(target), "--json"])
    assert res.exit_code == 0, res.stderr
    got = json.loads(res.stdout)
    assert got["files"] == [str(demo), str(batch)] and got["n_runs"] == 11
    ids = [re.sub(r"[^A-Za-z0-9_-]+", "-", n) for n in names]
    for sid in (f"track-{ids[0]}", f"track-{ids[1]}", f"statistics-{ids[1]}"):
        assert sid in got["sections"], sid
    page = target.read_text()
    assert f"{names[0]}: 1 run(s): 1 ok" in page and f"{names[1]}: 10 run(s): 5 ok" in page
    # refused, exit 2, nothing written: a file twice, a sweep store with a result
    assert "are the same result" in one_error(["report", str(demo), str(demo), "-o",
                                               str(tmp_path / "x.html")])
    store = tmp_path / "fake.zarr"
    assert not (tmp_path / "x.html").exists()
    assert "no such sweep store" in one_error(["report", str(demo), str(store)])


def test_a_sweep_store_is_reported_alone(report_demo_dir, report_sweep_dir):
    assert "is reported alone" in one_error(["report", str(report_demo_dir / "result.nc"),
                                             str(report_sweep_dir / "sweep.zarr")])
