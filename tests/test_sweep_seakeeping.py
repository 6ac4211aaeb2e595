"""The polar seakeeping diagram from a time-domain sweep (seahelm.sweep.seakeeping)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.sweep import open_sweep, run_sweep
from seahelm.sweep.seakeeping import sweep_seakeeping

EXAMPLE = Path(__file__).parents[1] / "examples" / "container_seakeeping_sweep.toml"
#: Lvov's mean wave loads warn for the container's C_b 0.56 (< 0.6), as the example says
pytestmark = pytest.mark.filterwarnings("ignore:Lvov:seahelm.errors.ValidityRangeWarning")


def validation_text() -> str:
    """The example's ship and autopilot in a sea of Hs 1 m (the mean loads, ∝ Hs², hardly
    turn the ship: heading wander < 0.1 deg, speed within ±0.05 m/s), 3 headings (head, bow,
    beam seas) × 2 shaft speeds × 8 runs of 30 min."""
    text = EXAMPLE.read_text()
    for old, new in (("hs = 2.0 ", "hs = 1.0 "), ("[0, 45, 90, 135, 180]", "[0, 45, 90]"),
                     ("t_final = 900.0", "t_final = 1800.0"), ("runs = 6", "runs = 8")):
        assert old in text
        text = text.replace(old, new)
    return text


@pytest.fixture(scope="module")
def validation(tmp_path_factory):
    path = tmp_path_factory.mktemp("sk") / "v.toml"
    path.write_text(validation_text())
    store = path.with_suffix(".zarr")
    run_sweep(path, store, series=False)
    return store, sweep_seakeeping(store)


def test_the_cells_are_the_grid_at_the_ships_speed_and_heading(validation):
    _, p = validation
    assert p.dofs == ("heave", "pitch", "roll", "roll_total")
    assert p.heading_key == "environment.waves.direction_deg"
    assert p.speed_key == "controller.params.propeller_rps"
    np.testing.assert_array_equal(p.speed_values, [0.9, 1.2])
    np.testing.assert_array_equal(p.heading_values, [0, 45, 90])  # from ahead ... abeam
    # waves from 0, 45, 90 deg on a ship heading north: 180 (head), 225, 270 deg
    np.testing.assert_allclose(np.degrees(p.heading), [[180, 225, 270]] * 2, atol=0.1)
    np.testing.assert_array_equal(p.n_runs, 8)
    assert np.all(np.diff(p.row_speed) > 1.0)


def test_the_aggregation_against_the_stored_runs(validation):
    """m̂0 = mean of the runs' RMS², se = sample standard deviation / √R, from the store."""
    store, p = validation
    with open_sweep(store) as ds:
        cell = ds.sel(direction_deg=45).isel({"controller.params.propeller_rps": 1})
        x = np.radians(cell["rms_roll_wave_deg"].values) ** 2
        speed = cell["mean_surge_speed_mps"].values
    assert x.shape == (8,)
    j = 1  # the columns go 180, 225, 270 deg
    assert p.mean_square[2, 1, j] == pytest.approx(x.mean(), rel=1e-12)
    assert p.standard_error[2, 1, j] == pytest.approx(x.std(ddof=1) / math.sqrt(8), rel=1e-12)
    assert p.rms_standard_error("roll")[1, j] == pytest.approx(
        x.std(ddof=1) / math.sqrt(8) / (2 * math.sqrt(x.mean())), rel=1e-12)
    assert p.speed[1, j] == pytest.approx(speed.mean(), rel=1e-12)


def test_time_domain_agrees_with_the_frequency_domain_within_three_standard_errors(
        validation):
    """|m̂0 − m0| <= 3 σ̂/√R in every cell where the response does not vanish at the exact
    heading; m0 of seahelm.analysis.seakeeping.frequency_domain.response_moments (the same RAO
    tables, sea and band, at the cell's mean speed and heading). Where it vanishes (pitch in beam seas,
    roll in head seas) the autopilot's heading wander alone gives the time domain its
    value: small against the same response elsewhere."""
    _, p = validation
    fd = p.frequency_domain
    assert fd is not None and np.all(np.isnan(fd[3]))  # (the total roll has none)
    checked = 0
    for k, dof in enumerate(("heave", "pitch", "roll")):
        z = p.deviation(dof)
        for i, j in np.ndindex(*z.shape):
            if (dof, j) in (("pitch", 2), ("roll", 0)):
                continue
            assert abs(z[i, j]) <= 3.0, (dof, i, j, z[i, j])
            assert p.rms(dof)[i, j] == pytest.approx(p.frequency_domain_rms(dof)[i, j],
                                                     rel=0.05)
            checked += 1
    assert checked == 14
    assert np.all(p.rms("pitch")[:, 2] < 0.05 * p.rms("pitch")[:, 0])
    assert np.all(p.rms("roll")[:, 0] < 1e-3 * p.rms("roll")[:, 2])


def test_the_figure_side_by_side_on_one_scale(validation):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from seahelm.plotting.seakeeping import plot_sweep_polar

    fig = plot_sweep_polar(validation[1], "heave")
    try:
        polar = [ax for ax in fig.axes if ax.name == "polar"]
        bars = [ax for ax in fig.axes if ax.name != "polar"]
        assert len(polar) == 2 and len(bars) == 2
        assert "time domain" in polar[0].get_title() and "frequency" in polar[1].get_title()
        assert list(bars[0].get_ylim()) == list(bars[1].get_ylim())
    finally:
        plt.close(fig)
    fig = plot_sweep_polar(validation[1], "roll_total")  # no frequency domain: one panel
    try:
        assert len([ax for ax in fig.axes if ax.name == "polar"]) == 1
    finally:
        plt.close(fig)


def test_the_report_section(validation, tmp_path):
    from seahelm.report import write_report

    summary = write_report(validation[0], tmp_path / "r.html")
    assert "seakeeping-sweep" in summary.sections
    html = (tmp_path / "r.html").read_text()
    assert "Seakeeping from the time-domain sweep" in html
    assert "frequency domain, same cells" in html and "polar2" in html


def _flat(store: Path):
    return open_sweep(store, flat=True).load()


@pytest.mark.parametrize("change, field, match", [
    ("no-motions", "environment.waves.first_order_motions", "first_order_motions = true"),
    ("one-sample", "batch.monte_carlo.runs", "2 or more seeded runs per cell"),
    ("one-heading", "batch.grid.environment.waves.direction_deg", "2 or more wave headings"),
    ("no-heading", "batch.grid", "must vary the wave heading"),
    ("incomplete", "store", "not complete"),
])
def test_a_sweep_that_cannot_make_a_polar_diagram_is_named(validation, change, field, match):
    ds = _flat(validation[0])
    dims = json.loads(ds.attrs["sweep_dims"])
    if change == "no-motions":
        ds = ds.drop_vars([v for v in ds.data_vars if str(v).startswith("rms_")])
    elif change == "one-sample":
        ds = ds.isel(run=ds["sample"].values == 0)
        dims[2][1] = 1
    elif change == "one-heading":
        ds = ds.isel(run=ds["direction_deg"].values == 45)
        dims[0][1] = 1
    elif change == "no-heading":
        ds["direction_deg"].attrs["key"] = "environment.waves.height"
    else:
        ds["complete"] = ("run", np.ones(ds.sizes["run"], bool))
    ds.attrs["sweep_dims"] = json.dumps(dims)
    with pytest.raises(ParameterError, match=match) as info:
        sweep_seakeeping(ds, frequency_domain=False)
    assert info.value.field == field


def test_the_example(tmp_path):
    """examples/container_seakeeping_sweep.toml: 5 headings x 2 shaft speeds x 6 runs; every
    cell computed, the report has the section."""
    from seahelm.report import write_report

    store = tmp_path / "example.zarr"
    report = run_sweep(EXAMPLE, store, series=False)
    assert report.n_runs == 60 and report.summary["n_failed"] == 0
    p = sweep_seakeeping(store)
    assert p.speed.shape == (2, 5)
    # the columns from head seas round the starboard side to following seas
    np.testing.assert_allclose(np.degrees(p.column_heading), [180, 225, 270, 315, 360],
                               atol=0.5)
    assert np.all(np.isfinite(p.frequency_domain[:3]))
    assert "seakeeping-sweep" in write_report(store, tmp_path / "r.html").sections


def test_the_command(validation, tmp_path):
    """seahelm seakeeping --sweep STORE: the cells as the library gives them, the files."""
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    store, p = validation
    res = CliRunner().invoke(app, ["seakeeping", "--sweep", str(store), "--dof", "heave",
                                   "--out", str(tmp_path / "out"), "--json"])
    assert res.exit_code == 0, res.stderr
    out = json.loads(res.stdout)
    assert [c["runs"] for c in out["cells"]] == [8] * 6
    np.testing.assert_allclose([c["rms_m"] for c in out["cells"]], p.rms("heave").ravel(),
                               rtol=1e-12)
    np.testing.assert_allclose([c["z"] for c in out["cells"]], p.deviation("heave").ravel(),
                               rtol=1e-12)
    assert sorted(x.name for x in (tmp_path / "out").iterdir()) == [
        "seakeeping-sweep-heave.png", "seakeeping-sweep.nc"]


@pytest.mark.parametrize("args, message", [
    (["--hs", "3"], "`--sweep` takes the sea, the ship and the speeds from the sweep's "
                    "scenario; give no --hs with it"),
    (["--limit", "-1"], "`--limit` must be > 0 [deg], got -1.0"),
    (["--dof", "sway"], "Invalid value for '--dof'"),
])
def test_the_command_refuses(validation, args, message):
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, ["seakeeping", "--sweep", str(validation[0]), *args])
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert message in res.stderr and (len(lines) == 1 or "Usage" in res.stderr), lines


def test_the_command_on_a_sweep_without_motions(tmp_path):
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    text = (Path(__file__).parents[1] / "examples" / "mariner_pid_sweep.toml").read_text()
    text = text.replace("t_final = 600.0", "t_final = 10.0")
    path = tmp_path / "pid.toml"
    path.write_text(text)
    run_sweep(path, tmp_path / "pid.zarr", series=False)
    res = CliRunner().invoke(app, ["seakeeping", "--sweep", str(tmp_path / "pid.zarr")])
    assert res.exit_code == 2
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: `environment.waves.first_order_"
                                                   "motions`") and "first_order_motions = true" \
        in lines[0], lines
    res = CliRunner().invoke(app, ["seakeeping", "--sweep", str(tmp_path / "none.zarr")])
    assert res.exit_code == 2 and "no such sweep store" in res.stderr


def test_one_speed_is_one_row(validation):
    """A grid over the heading alone (the other key's one value here): one row, no speed key's
    values, drawn as a curve."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from seahelm.plotting.seakeeping import plot_sweep_polar

    ds = _flat(validation[0])
    ds = ds.isel(run=ds["controller.params.propeller_rps"].values == 1.2)
    ds = ds.drop_vars("controller.params.propeller_rps")
    ds.attrs["sweep_dims"] = json.dumps([["direction_deg", 3], ["sample", 8]])
    p = sweep_seakeeping(ds, frequency_domain=False)
    full = validation[1]
    assert p.speed_key is None and p.speed.shape == (1, 3)
    np.testing.assert_array_equal(p.mean_square, full.mean_square[:, 1:])
    fig = plot_sweep_polar(p, "roll")
    try:
        assert len([ax for ax in fig.axes if ax.name == "polar"]) == 1  # no frequency domain
    finally:
        plt.close(fig)
