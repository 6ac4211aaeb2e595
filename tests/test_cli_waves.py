"""``seahelm waves`` (table, spectrum, sample) and the wave plots behind ``--plot``."""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.waves import app

runner = CliRunner()


def run_json(*args: str) -> dict:
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)  # exactly one JSON object on stdout


def test_table_json():
    out = run_json("table")
    assert [g["roman"] for g in out["table1"]] == ["I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX"]
    assert out["table1"][8] == {"grade": 9, "roman": "IX", "h3_min": 11.0, "h3_max": None}
    rows = out["table2"]["rows"]
    assert len(rows) == 10 and rows[3]["h3"] == 4.0
    assert rows[3]["lambda_mean"] == 0.867 and rows[0]["mu_min"] == 0.188
    printed = run_json("table", "--table", "printed")["table2"]["rows"]
    assert printed[3]["lambda_mean"] == 0.667 and printed[0]["mu_min"] == 0.138


def test_table_human():
    res = runner.invoke(app, ["table"])
    assert res.exit_code == 0
    assert "VIII" in res.stdout and "0.867" in res.stdout


def test_spectrum_json():
    out = run_json("spectrum", "--h3", "3")
    dr = 0.143 * 1.5**2
    assert out["D_r"] == pytest.approx(dr)
    assert (out["mu"], out["lambda"]) == (0.214, 1.003)
    assert out["m0"] == pytest.approx(dr, rel=1e-6)
    assert out["peak_frequency"] == pytest.approx(math.sqrt(1.003**2 - 0.214**2), rel=1e-6)
    pm = run_json("spectrum", "--h3", "3", "--model", "pierson-moskowitz")
    assert pm["m0"] == pytest.approx(dr, rel=1e-6)  # Hs = 4√D_r


def test_spectrum_plot(tmp_path):
    png = tmp_path / "s.png"
    out = run_json("spectrum", "--h3", "4.5", "--model", "rakhmanin-firsov-1", "--plot", str(png))
    assert out["plot"] == str(png)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(os.listdir(tmp_path)) == ["s.png"]  # no temporary files left


@pytest.mark.parametrize(
    "args,match",
    [
        (["spectrum", "--h3", "-1"], "h3"),
        (["spectrum", "--h3", "0"], "h3"),
        (["spectrum", "--h3", "nan"], "h3"),
        (["spectrum", "--h3", "12"], "h3"),
        (["spectrum", "--h3", "3", "--model", "nope"],
         "Invalid value for '--model': 'nope' is not one of 'rakhmanin-firsov-1',"),
        (["table", "--table", "misprinted"],
         "Invalid value for '--table': 'misprinted' is not one of 'corrected', 'printed'"),
        (["sample", "--h3", "3", "--duration", "10", "--dt", "0", "--seed", "1"], "dt"),
        (["sample", "--h3", "3", "--duration", "10", "--dt", "-0.1", "--seed", "1"], "dt"),
        (["sample", "--h3", "3", "--duration", "-10", "--dt", "0.1", "--seed", "1"], "duration"),
        (["sample", "--h3", "-3", "--duration", "10", "--dt", "0.1", "--seed", "1"], "h3"),
        (["sample", "--h3", "3", "--duration", "10", "--dt", "0.1", "--seed", "1", "--runs", "0"], "runs"),
        # no shaping filter: sampling takes the rational (Rakhmanin–Firsov) spectra only
        (["sample", "--h3", "3", "--duration", "10", "--dt", "0.1", "--seed", "1", "--model", "jonswap"],
         "Invalid value for '--model': 'jonswap' is not one of 'rakhmanin-firsov-1',"),
    ],
)
def test_bad_input_exits_2(args, match):
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 2
    err = res.stderr.strip()
    assert "\n" not in err and match in err
    assert json.loads(res.stdout) == {"error": err.removeprefix("error: "), "exit_code": 2}


@pytest.mark.parametrize("command", [["spectrum"], ["sample", "--duration", "10", "--dt", "0.5",
                                                   "--seed", "1"]])
def test_height_outside_table2_names_the_cli_option_not_a_python_keyword(command):
    res = runner.invoke(app, [*command, "--h3", "12"])
    assert res.exit_code == 2
    err = res.stderr.strip()
    assert err.startswith("error: `--h3` must be in [1, 10] [m]") and "\n" not in err
    assert "--extrapolate" in err and "extrapolate=True" not in err
    out = run_json(*command, "--h3", "12", "--extrapolate")
    assert out["h3"] == 12


def test_sample_json_and_netcdf(tmp_path):
    xr = pytest.importorskip("xarray")
    nc = tmp_path / "waves.nc"
    out = run_json("sample", "--h3", "3", "--duration", "2000", "--dt", "0.5", "--seed", "4",
                   "--runs", "8", "--out", str(nc))
    dr = 0.143 * 1.5**2
    assert out["variance_expected"] == pytest.approx(dr, rel=1e-10)
    assert out["samples"] == 8 * 4001
    # R = 8 runs of T = 2000 s: σ(v̂)/D ≈ √(2∫K²dτ/(RT))/D < 0.05 (∫K² ≤ D²(1/μ)); 5σ ≈ 0.25
    assert abs(out["variance_sample"] / dr - 1) < 0.25
    assert out["slope_variance_expected"] == pytest.approx(dr * (0.214**2 + 1.003**2) / 9.80665**2, rel=1e-10)
    with xr.open_dataset(nc, engine="h5netcdf") as ds:
        assert ds["ordinate"].shape == (8, 4001)
        assert ds.attrs["h3"] == 3.0 and int(ds.attrs["seed"]) == 4
        assert float((ds["ordinate"] ** 2).mean()) == pytest.approx(out["variance_sample"], rel=1e-12)
    assert sorted(os.listdir(tmp_path)) == ["waves.nc"]
    again = run_json("sample", "--h3", "3", "--duration", "2000", "--dt", "0.5", "--seed", "4", "--runs", "8")
    assert again["variance_sample"] == out["variance_sample"]


def test_sample_human():
    res = runner.invoke(app, ["sample", "--h3", "2", "--duration", "50", "--dt", "1", "--seed", "0"])
    assert res.exit_code == 0 and "variance_expected" in res.stdout


def test_sample_out_creates_directory_and_leaves_no_temp(tmp_path):
    out = tmp_path / "new" / "x.nc"
    res = runner.invoke(app, ["sample", "--h3", "2", "--duration", "5", "--dt", "1", "--seed", "0",
                              "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert out.is_file()
    assert [p.name for p in out.parent.iterdir()] == ["x.nc"]


def test_plotting_functions():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from seahelm.environment.shaping import shaping_filter
    from seahelm.environment.spectra import spectrum_from_wave_height
    from seahelm.plotting import waves as pw
    from seahelm.studies.sushchenko2010 import plot_paper_figure

    assert pw.grade_wave_height(3) == 1.0 and pw.grade_wave_height(6) == 4.75 and pw.grade_wave_height(9) == 10.0
    fig, ax = plt.subplots()
    assert pw.plot_sea_state_spectra("rakhmanin-firsov-2", (3, 6, 9), ax=ax) is ax
    assert len(ax.lines) == 3
    x, y = ax.lines[0].get_xdata(), ax.lines[0].get_ydata()  # sea state 3 → h3% = 1 m
    d, mu, lam = 0.143 * 0.25, 0.374, 1.745
    a2 = mu**2 + lam**2
    np.testing.assert_allclose(y, 4 * d * mu / np.pi * a2 / ((a2 + x**2) ** 2 - 4 * lam**2 * x**2), rtol=1e-12)
    spec = spectrum_from_wave_height("rakhmanin-firsov-2", 3.0)
    samples = shaping_filter(spec).sample(duration=20, dt=0.5, seed=0, runs=2)
    ax2 = pw.plot_realisations(samples, runs=(0, 1), ax=fig.add_subplot(2, 1, 2))
    np.testing.assert_array_equal(ax2.lines[1].get_ydata(), samples["ordinate"][1])
    plt.close(fig)
    f = plot_paper_figure(duration=20.0, dt=0.5)
    assert len(f.axes) == 6
    plt.close(f)


def test_figure_command_writes_the_paper_figure(tmp_path):
    out = tmp_path / "fig.png"
    res = runner.invoke(app, ["figure", "--out", str(out), "--duration", "20"])
    assert res.exit_code == 0, res.output
    assert out.stat().st_size > 20_000
    bad = runner.invoke(app, ["figure", "--out", str(out), "--duration", "-1"])
    assert bad.exit_code == 2 and "`--duration` must be in (0, 100000] [s]" in bad.stderr
