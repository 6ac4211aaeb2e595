"""`seahelm averaging cpp` (the typer app of seahelm.cli.averaging)."""

from __future__ import annotations

import json

import matplotlib
import pytest
from typer.testing import CliRunner

from seahelm.cli.averaging import app

matplotlib.use("Agg")

runner = CliRunner()


def test_json_output():
    r = runner.invoke(app, ["cpp", "--grid", "40", "--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    for key in ("beta1", "beta2", "beta3", "hausdorff_V_Y", "hausdorff_V_Y_printed",
                "grid_points"):
        assert key in data
    assert round(data["beta1"], 5) == 0.82419
    assert round(data["beta2"], 4) == 0.8472
    assert round(data["beta3"], 4) == 0.8727
    assert data["grid_points"] == 40 * 20
    assert data["hausdorff_V_Y"] < data["hausdorff_V_Y_printed"]


def test_other_waves_change_betas():
    r = runner.invoke(app, ["cpp", "--grid", "20", "--json", "--immersion", "1.2",
                            "--amplitude", "0.48"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    # α = 0.5 − 0.2 sin τ: c2 = 1 − 0.2 sin τ on [0, π] -> β3 = 1 − 0.2/π
    assert data["beta3"] == pytest.approx(1 - 0.2 / 3.141592653589793, abs=1e-12)


def test_text_output():
    r = runner.invoke(app, ["cpp", "--grid", "20"])
    assert r.exit_code == 0, r.output
    assert "β1" in r.stdout and "0.82419" in r.stdout


def test_plot(tmp_path):
    out = tmp_path / "sets.png"
    r = runner.invoke(app, ["cpp", "--grid", "20", "--plot", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert out.stat().st_size > 1000
    assert json.loads(r.stdout)["plot"] == str(out)


@pytest.mark.parametrize(
    "args, message",
    [(["--immersion", "0", "--amplitude", "1.5"], "c2"),
     (["--grid", "2"], "grid"),
     (["--amplitude", "-1"], "amplitude")],
)
def test_bad_input_exit_2(args, message):
    r = runner.invoke(app, ["cpp", "--json", *args])
    assert r.exit_code == 2
    assert message in r.stderr
    assert json.loads(r.stdout)["exit_code"] == 2  # --json: the error as one JSON object
