"""``seahelm imo SHIP --monte-carlo N`` (issue 44 item 7 leftovers, issue 47 item 4): ``--out``
writes the distribution figure next to ``imo-probabilities.nc``; the output names the drawn
parameters with their units; a progress bar shows under a pseudo-terminal; the command is
one library call (:func:`seahelm.analysis.imo.monte_carlo.imo_monte_carlo`) whose numbers are
the command's.

Sizes are small (one KVLCC2 L7 sample's IMO check costs about 0.3 s).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.results import open_result_file

runner = CliRunner()
N = 12


@pytest.fixture(scope="module")
def checked(tmp_path_factory):
    out = tmp_path_factory.mktemp("mc")
    res = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", str(N), "--seed", "3",
                              "--out", str(out), "--json"])
    assert res.exit_code == 0, (res.stdout, res.stderr)
    return out, json.loads(res.stdout)


def test_out_writes_the_distribution_figure(checked):
    out, payload = checked
    png = out / "imo-probabilities.png"
    assert payload["files"]["plot"] == str(png)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert (out / "imo-probabilities.nc").is_file()


def test_the_figure_has_a_panel_per_quantity_with_its_limit(checked):
    import matplotlib.pyplot as plt

    from seahelm.plotting.imo_ensemble import plot_imo_ensemble

    out, _ = checked
    ds = open_result_file(out / "imo-probabilities.nc")
    fig = plot_imo_ensemble(ds)
    shown = [ax for ax in fig.axes if ax.get_visible()]
    quantities = {(a, q) for a, q in zip(ds["ability"].values, ds["quantity"].values)}
    assert len(shown) == len(quantities) == 7  # 6 criteria x 2 sides + stopping
    for ax in shown:
        limits = [line.get_xdata()[0] for line in ax.get_lines()]
        assert len(limits) == 1 and float(limits[0]) in set(ds["limit"].values.tolist())
    plt.close(fig)


def test_the_figure_refuses_another_dataset():
    import xarray as xr

    from seahelm.plotting.imo_ensemble import plot_imo_ensemble

    with pytest.raises(ValueError, match="not the Dataset of an IMO ensemble"):
        plot_imo_ensemble(xr.Dataset())


def test_the_drawn_parameters_are_named_with_their_units(checked):
    out, payload = checked
    ds = open_result_file(out / "imo-probabilities.nc")
    rows = {r["parameter"]: r for r in payload["drawn_parameters"]}
    assert sorted(rows) == sorted(f"vessel.params.{k}" for k in ("Y_v", "Y_r", "N_v", "N_r"))
    for key, row in rows.items():
        values = ds[key].values
        assert row["distribution"] == "normal" and row["units"] == "-"
        assert row["mean"] == pytest.approx(values.mean(), rel=1e-12)
        assert row["std"] == pytest.approx(values.std(ddof=1), rel=1e-12)
        assert (row["min"], row["max"]) == (values.min(), values.max())


def test_the_table_shows_the_drawn_parameters():
    res = runner.invoke(app, ["imo", "kvlcc2-l7", "--monte-carlo", "4"], env={"COLUMNS": "160"})
    assert res.exit_code == 0, res.stderr
    text = res.stdout
    assert "drawn parameters" in text
    for key in ("Y_v", "Y_r", "N_v", "N_r"):
        line = next(line for line in text.splitlines() if f"vessel.params.{key} " in line)
        assert "normal" in line and " - " in line


def test_one_library_call_gives_the_commands_numbers(checked):
    from seahelm.analysis.imo.monte_carlo import imo_monte_carlo
    from seahelm.ships import get_ship

    _, payload = checked
    calls = []
    ensemble = imo_monte_carlo(get_ship("kvlcc2-l7"), N, seed=3,
                               progress=lambda done, total: calls.append((done, total)))
    got = ensemble.probabilities.as_dict()
    assert got["criteria"] == payload["criteria"] and got["probability"] == payload["probability"]
    assert ensemble.metadata == {"ship": "kvlcc2-l7", "samples": N, "seed": 3,
                                 "draws": "default", "uncertainty": 0.10}
    # the progress: the reference, then turning, initial turning, 10/10, 20/20 and stopping
    assert calls == [(k, 6) for k in range(1, 7)]
    ds = ensemble.dataset()
    assert ds.attrs["title"] == ensemble.title and ds.sizes["sample"] == N


def test_ships_of_samples_names_the_column(tmp_path):
    from seahelm.analysis.imo.monte_carlo import ships_of_samples
    from seahelm.identification.samples_file import read_samples
    from seahelm.errors import ParameterError
    from seahelm.ships import get_ship

    path = tmp_path / "s.csv"
    path.write_text("vessel.params.Y_v,vessel.params.bogus\n-0.3,1\n")
    with pytest.raises(ParameterError, match=r"column `vessel.params.bogus`: not a parameter"):
        ships_of_samples(get_ship("kvlcc2-l7"), read_samples(path))
    path.write_text("vessel.params.Y_v\n-0.3\n-0.31\n")
    ships = ships_of_samples(get_ship("kvlcc2-l7"), read_samples(path))
    assert [s.params.Y_v for s in ships] == [-0.3, -0.31]
    assert [s.name for s in ships] == ["kvlcc2-l7 #0", "kvlcc2-l7 #1"]


def test_a_progress_bar_under_a_pseudo_terminal():
    """On a terminal the check shows a (transient) progress bar on stderr; it showed none.
    (``SEAHELM_PROGRESS_DELAY=0``: on a fast machine with the kernels cached the 40 samples took
    less than the bar's default 1 s delay, and no bar was drawn, correctly.)"""
    pty = pytest.importorskip("pty")
    master, slave = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "seahelm", "imo", "kvlcc2-l7",
                             "--monte-carlo", "40"], stdin=slave, stdout=slave, stderr=slave,
                            env={**os.environ, "COLUMNS": "120",
                                     "SEAHELM_PROGRESS_DELAY": "0"}, close_fds=True)
    os.close(slave)
    data = b""
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # (the child closed the terminal)
            break
        if not chunk:
            break
        data += chunk
    os.close(master)
    assert proc.wait(timeout=120) == 0, data.decode(errors="replace")[-2000:]
    assert b"checking 40 sample(s)" in data and b"%" in data
