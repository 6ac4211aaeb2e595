"""``seahelm seakeeping``: the table, --json against the library, the NetCDF and the polar PNG
written together, an RAO file, the polar diagram's axes, bad input (exit 2, one line naming
the option and its unit)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from seahelm.analysis.seakeeping.frequency_domain import closed_form_moments
from seahelm.cli.main import app
from seahelm.environment.rao import closed_form_rao
from seahelm.environment.rao_io import write_rao_table
from seahelm.environment.spectra import Jonswap
from seahelm.ships import get_ship

runner = CliRunner()
SHIP = "son-nomoto-container"


def run_json(*args: str) -> dict:
    res = runner.invoke(app, ["seakeeping", *args, "--json"])
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def test_json_agrees_with_the_library():
    out = run_json(SHIP, "--hs", "4", "--tp", "10", "--speeds", "0,7", "--headings", "0:180:5",
                   "--exceed", "5", "--duration", "1800", "--both-sides")
    m = closed_form_moments(get_ship(SHIP), Jonswap(significant_height=4.0, peak_period=10.0),
                            [0.0, 7.0], np.radians(np.linspace(0, 180, 5)),
                            metacentric_height=0.3)  # the ship's GM
    rms = np.degrees(m.rms("roll")).ravel()
    prob = m.exceedance_probability("roll", math.radians(5), 1800.0, both_sides=True).ravel()
    assert out["unit"] == "deg" and len(out["cells"]) == 10
    for cell, r, p in zip(out["cells"], rms, prob):
        assert cell["rms_deg"] == pytest.approx(r, rel=1e-12)
        assert cell["significant_amplitude_deg"] == pytest.approx(2 * r, rel=1e-12)
        assert cell["exceedance_probability"] == pytest.approx(p, rel=1e-12, abs=1e-300)
    mpm = np.degrees(m.most_probable_maximum("roll", 1800.0)).ravel()
    assert [c["most_probable_maximum_deg"] for c in out["cells"]] == [
        None if not np.isfinite(v) else pytest.approx(v, rel=1e-12) for v in mpm]
    assert out["cells"][2]["heading_deg"] == pytest.approx(90.0)


def test_files_table_and_polar_diagram(tmp_path):
    res = runner.invoke(app, ["seakeeping", SHIP, "--hs", "4", "--tp", "10", "--speeds",
                              "0:7:4", "--headings", "0:350:36", "--limit", "2", "--out",
                              str(tmp_path)])
    assert res.exit_code == 0, res.stderr
    assert "per speed over 144 cells" in res.stdout  # a summary, not 144 rows
    assert "rms roll above 2 deg:" in res.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["seakeeping-roll.png", "seakeeping.nc"]
    assert (tmp_path / "seakeeping-roll.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with xr.open_dataset(tmp_path / "seakeeping.nc") as ds:
        assert dict(ds.sizes) == {"dof": 3, "speed": 4, "heading": 36}
        assert ds.attrs["ship"] == SHIP and ds["heading"].attrs["units"] == "rad"
        roll = ds["rms"].sel(dof="roll").values
    # port and starboard: ε and 360° − ε
    np.testing.assert_allclose(roll[:, 1:18], roll[:, 35:18:-1], rtol=1e-12)


def test_polar_diagram_axes():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from seahelm.plotting.seakeeping import plot_polar_diagram

    eps = np.radians(np.arange(0, 360, 30.0))
    ax = plot_polar_diagram([0, 4, 8], eps, np.outer([1, 2, 3], np.ones(12)), label="RMS roll",
                            unit="deg", limit=2.5)
    try:
        assert ax.name == "polar" and ax.get_theta_direction() == -1
        assert ax.get_theta_offset() % (2 * math.pi) == pytest.approx(1.5 * math.pi)  # 0 at the bottom
        bar = ax.figure.axes[1]
        assert bar.get_ylabel() == "RMS roll [deg]"
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["limit 2.5 deg"]
        ax2 = plot_polar_diagram([5.0], eps, np.ones((1, 12)), label="RMS roll", unit="deg",
                                 limit=9.0)
        assert "at 5 m/s" in ax2.get_legend().get_texts()[0].get_text()
        plt.close(ax2.figure)
    finally:
        plt.close(ax.figure)


def test_rao_file(tmp_path):
    w = np.linspace(0.05, 4.0, 200)
    rao = closed_form_rao(get_ship(SHIP), 5.0, frequency=w, metacentric_height=0.3)
    path = tmp_path / "rao.csv"
    write_rao_table(rao, path)
    out = run_json("--rao", str(path), "--hs", "3", "--tp", "9", "--headings", "90")
    assert [c["speed_mps"] for c in out["cells"]] == [5.0]
    m = closed_form_moments(get_ship(SHIP), Jonswap(significant_height=3.0, peak_period=9.0),
                            [5.0], [math.pi / 2], metacentric_height=0.3)
    # the table's interpolation on 200 frequencies against the exact closed form
    assert out["cells"][0]["rms_deg"] == pytest.approx(math.degrees(m.rms("roll")[0, 0]),
                                                       rel=2e-3)


@pytest.mark.parametrize("args, message", [
    ([SHIP, "--hs", "0", "--tp", "10"], "`--hs` must be in (0, 100] [m], got 0.0"),
    ([SHIP, "--hs", "-2", "--tp", "10"], "`--hs` must be in (0, 100] [m]"),
    ([SHIP, "--hs", "nan", "--tp", "10"], "`--hs` must be in (0, 100] [m], got nan"),
    # overflowed (exit 1, OverflowError) or gave NaN moments named `values`/`m0` before
    ([SHIP, "--hs", "1e300", "--tp", "10"], "`--hs` must be in (0, 100] [m], got 1e+300"),
    ([SHIP, "--hs", "4", "--tp", "1e300"], "`--tp` must be in [0.1, 1000] [s], got 1e+300"),
    ([SHIP, "--hs", "4", "--tp", "1e-300"], "`--tp` must be in [0.1, 1000] [s], got 1e-300"),
    ([SHIP, "--hs", "4", "--tp", "10", "--gamma", "1e300"], "`--gamma` must be in [1, 20] [-]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", "1e300"], "`--speeds` must be in [0, 100] "
                                                             "[m/s], got '1e300'"),
    ([SHIP, "--hs", "4", "--tp", "10", "--headings", "1e300"], "`--headings` must be within "
                                                               "±360 [deg], got '1e300'"),
    ([SHIP, "--hs", "4", "--tp", "10", "--spreading", "cos-2s", "--spreading-s", "1e300"],
     "`--spreading-s` must be in (0, 1000] [-], got 1e+300"),
    ([SHIP, "--hs", "4", "--tp", "10", "--spreading", "cos2", "--directions", "100000000000"],
     "`--directions` must be in [1, 10000] [-], got 100000000000"),
    ([SHIP, "--tp", "10"], "`--hs` is required [m]"),
    ([SHIP, "--hs", "4", "--tp", "0"], "`--tp` must be in [0.1, 1000] [s]"),
    ([SHIP, "--hs", "4"], "`--tp` is required for jonswap [s]"),
    ([SHIP, "--hs", "4", "--tp", "8", "--spectrum", "pierson-moskowitz"], "`--tp` is not taken"),
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", ""], "`--speeds` must hold at least one value [m/s]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", "0:8"], "`--speeds` must be START:STOP:N"),
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", "-1,2"], "`--speeds` must be in [0, 100] [m/s]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--headings", "0,nan"], "`--headings` must be finite [deg]"),
    # a MemoryError (exit 1); a numpy warning line before the error
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", "0:1:100000000000"],
     "`--speeds` needs N <= 100000 [m/s], got '0:1:100000000000'"),
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", "0:inf:3"],
     "`--speeds` must be finite [m/s], got '0:inf:3'"),
    ([SHIP, "--hs", "4", "--tp", "10", "--speeds", "0:1:0"],
     "`--speeds` needs N >= 1 (N = 1 only with START = STOP) [m/s], got '0:1:0'"),
    ([SHIP, "--hs", "4", "--tp", "10", "--headings", "90,10"], "`--headings` must be strictly increasing [deg]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--limit", "0"], "`--limit` must be > 0 [deg]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--dof", "heave", "--exceed", "-1"], "`--exceed` must be > 0 [m]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--exceed", "3", "--duration", "0"], "`--duration` must be > 0 [s]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--gm", "-0.3"], "`--gm` must be > 0 [m]"),
    ([SHIP, "--hs", "4", "--tp", "10", "--roll-damping", "0"], "`--roll-damping` must be in (0, 1] [-]"),
    (["kvlcc2-l7", "--hs", "4", "--tp", "10"], "`--gm` is not known for ship kvlcc2-l7 [m]"),
    (["shushlyapin2017-listing", "--hs", "4", "--tp", "10", "--dof", "heave"],
     "has no [particulars] (length, beam, draft, block_coefficient)"),
    (["--hs", "4", "--tp", "10"], "give a SHIP or `--rao FILE`"),
    (["no-such-ship", "--hs", "4", "--tp", "10"], "no-such-ship"),
])
def test_bad_input_exits_2_with_one_line(args, message):
    res = runner.invoke(app, ["seakeeping", *args])
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and message in lines[0], lines


def test_report_of_a_seakeeping_file(tmp_path):
    res = runner.invoke(app, ["seakeeping", SHIP, "--hs", "3", "--tp", "9", "--speeds", "0:6:3",
                              "--headings", "0:330:12", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.stderr
    nc = tmp_path / "seakeeping.nc"
    res = runner.invoke(app, ["report", str(nc), "--json"])
    assert res.exit_code == 0, res.stderr
    out = json.loads(res.stdout)
    assert out["sections"] == ["overview", "seakeeping"] and out["n_runs"] == 0
    page = (tmp_path / "report.html").read_text()
    for text in ('"barpolar"', "RMS roll [deg]", "RMS heave [m]", "max RMS pitch [deg]",
                 "significant amplitude = 2√m0"):
        assert text in page
    # the table's largest roll per speed is the file's, in degrees
    with xr.open_dataset(nc) as ds:
        top = float(np.degrees(ds["rms"].sel(dof="roll").isel(speed=2).max()))
    assert f"<td>{top:.4g}</td>" in page
    # reported alone
    other = tmp_path / "copy.nc"
    other.write_bytes(nc.read_bytes())
    res = runner.invoke(app, ["report", str(nc), str(other)])
    assert res.exit_code == 2 and "is reported alone" in res.stderr


def test_roll_excitation_full_slope_selectable():
    """``--roll-excitation slope`` is the library's full-slope roll; in quartering seas at speed
    the averaged slope removes the short waves of the second encounter branch that drove the
    34 s roll resonance (measured 3.74° against 0.073° RMS at 7 m/s, ε = 45°: asserted > 20×)."""
    args = (SHIP, "--hs", "4", "--tp", "10", "--speeds", "7", "--headings", "45")
    slope = run_json(*args, "--roll-excitation", "slope")
    averaged = run_json(*args)
    m = closed_form_moments(get_ship(SHIP), Jonswap(significant_height=4.0, peak_period=10.0),
                            [7.0], [math.radians(45.0)], metacentric_height=0.3,
                            roll_excitation="slope")
    rms_slope, rms_avg = slope["cells"][0]["rms_deg"], averaged["cells"][0]["rms_deg"]
    assert rms_slope == pytest.approx(math.degrees(float(m.rms("roll").ravel()[0])), rel=1e-9)
    assert rms_slope > 20 * rms_avg
    res = runner.invoke(app, ["seakeeping", *args, "--roll-excitation", "full"])
    assert res.exit_code == 2 and "--roll-excitation" in res.stderr


@pytest.mark.parametrize("args, named", [
    (["--stat", "significant", "--limit", "1"], "--stat"),
    (["--exceed", "1"], "--exceed"),
    (["--roll-excitation", "slope"], "--roll-excitation"),
    (["--headings", "0:90:3", "--gm", "1"], "--headings, --gm"),
    (["kvlcc2-l7", "--hs", "2"], "SHIP, --hs"),
])
def test_sweep_refuses_every_option_it_would_ignore(tmp_path, args, named):
    """``--sweep`` takes only --dof, --limit, --out and --json: ``--stat significant --limit 1``
    counted the cells' RMS above 1 (not their significant amplitude) and --exceed, --headings,
    --gm, --roll-excitation ... were dropped without a word. The refusal comes before the store
    is read (here there is none)."""
    res = runner.invoke(app, ["seakeeping", "--sweep", str(tmp_path / "none.zarr"), *args])
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        f"error: `--sweep` takes the sea, the ship and the speeds from the sweep's scenario; "
        f"give no {named} with it"), lines
    assert res.stdout == ""
