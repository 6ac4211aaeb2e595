"""`seahelm compensate` (the typer app of seahelm.cli.compensate)."""

from __future__ import annotations

import json
import math

import pytest
from typer.testing import CliRunner

from seahelm.cli.compensate import app
from seahelm.errors import ValidityRangeWarning

runner = CliRunner()

BASE = ["--length", "150", "--beam", "20", "--draft", "8", "--block-coefficient", "0.7",
        "--speed", "7", "--wind-speed", "15", "--wind-angle", "60", "--wave-height", "6.75",
        "--wave-angle", "60"]


def test_json_keys_and_values():
    r = runner.invoke(app, BASE + ["--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    for key in ("Cx", "Cy", "Cm", "X_w", "Y_w", "M_w", "arm", "delta_k_deg"):
        assert key in data
    # eq. (5)-(7) by hand for L/T = 18.75, B/T = 2.5, L/B = 7.5, δ = 0.7
    assert data["Cx"] == pytest.approx(0.155 - 0.159375 + 0.2296)
    assert data["Cy"] == pytest.approx(0.61725 + 2.56 * 8 / 150 + 0.44247)
    assert data["Cm"] == pytest.approx(0.105 + 0.09653 - 0.0699375)
    # eq. (9): λ = 1.55 (0.65·0.8·15)², V_n = −7 cos 60°, V_w = √(g λ/2π), A0 = 3.3, A1 = 1
    lam = 1.55 * (0.65 * 0.8 * 15) ** 2
    vw = math.sqrt(9.80665 * lam / (2 * math.pi))
    f = 1025 * 9.80665 * 150 * (6.75 / 2) ** 2 * math.exp(-3.3 * lam / 150) * (1 - 3.5 / vw)
    assert data["Y_w"] == pytest.approx(data["Cy"] * math.sin(math.radians(60)) * f, rel=1e-9)
    assert data["arm"] == pytest.approx(
        data["Cm"] / data["Cy"] * math.sin(math.radians(120)) / (2 - 1 / 3) * 150, rel=1e-9)
    assert data["delta_k_deg"] == pytest.approx(data["delta_k_wind_deg"] + data["delta_k_wave_deg"])
    assert data["warnings"] == []


def test_calm_gives_zero_delta_k():
    args = BASE.copy()
    args[args.index("--wind-speed") + 1] = "0"
    args[args.index("--wave-height") + 1] = "0"
    r = runner.invoke(app, args + ["--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert data["delta_k_deg"] == 0.0 and data["M_w"] == 0.0


def test_mirror_sea_flips_signs():
    mirror = BASE.copy()
    mirror[mirror.index("--wind-angle") + 1] = "-60"
    mirror[mirror.index("--wave-angle") + 1] = "-60"
    a = json.loads(runner.invoke(app, BASE + ["--json"]).stdout)
    b = json.loads(runner.invoke(app, mirror + ["--json"]).stdout)
    assert b["Y_w"] == pytest.approx(-a["Y_w"]) and b["X_w"] == pytest.approx(a["X_w"])
    assert b["delta_k_deg"] == pytest.approx(-a["delta_k_deg"])


def test_trim_moves_lateral_resistance_centre():
    r = runner.invoke(app, BASE + ["--draft-fore", "6", "--draft-aft", "9", "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["lateral_resistance_centre"] == pytest.approx(-1 / 30)
    r = runner.invoke(app, BASE + ["--draft-fore", "6"])
    assert r.exit_code == 2
    assert "--draft-aft" in r.output


def test_out_of_range_warns_or_fails_in_strict_mode():
    args = BASE.copy()
    args[args.index("--length") + 1] = "200"
    args[args.index("--beam") + 1] = "25"  # L/T = 25
    r = runner.invoke(app, args + ["--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert any("L/T = 25" in w and "10 < L/T < 23" in w for w in data["warnings"])
    r = runner.invoke(app, args + ["--strict"])
    assert r.exit_code == 2
    assert "L/T = 25 outside the published range 10 < L/T < 23" in r.output


def test_bad_input_exit_2_and_table_output():
    args = BASE.copy()
    args[args.index("--wave-height") + 1] = "-1"
    r = runner.invoke(app, args)
    assert r.exit_code == 2
    assert "`--wave-height`" in r.output
    r = runner.invoke(app, BASE)
    assert r.exit_code == 0, r.output
    assert "total δ_k" in r.output and "Cm" in r.output


def test_model_delta_k_beside_the_papers_and_which_one_the_autopilot_uses():
    from seahelm.studies import lvov2014 as lv

    args = ["--ship", "mariner", "--wind-speed", "15", "--wind-angle", "60", "--wave-height",
            "6.75", "--wave-angle", "60", "--json"]
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    case = lv.WindWaveCase("wind + waves", wind_speed=15.0, wind_angle=math.radians(60.0),
                           wave_height=6.75, wave_angle=math.radians(60.0))
    for method, key in (("model", "delta_k_model"), ("paper", "delta_k")):
        with pytest.warns(ValidityRangeWarning, match="block coefficient"):  # the Mariner's
            info = lv.wind_wave_scenario(case, t_final=60.0, delta_k_method=method)["info"]
        assert data[f"{key}_wind_deg"] == pytest.approx(math.degrees(info["delta_k_wind"]))
        assert data[f"{key}_wave_deg"] == pytest.approx(math.degrees(info["delta_k_wave"]))
        assert data[f"{key}_deg"] == pytest.approx(math.degrees(info["delta_k"]))
    # the README's table: the model needs about -9.6 deg, the printed formulas give +13.3
    assert data["delta_k_model_deg"] == pytest.approx(-9.57, abs=0.01)
    assert data["delta_k_deg"] == pytest.approx(13.31, abs=0.01)
    assert data["autopilot_delta_k"] == "model"
    human = " ".join(runner.invoke(app, args[:-1]).stdout.split())
    # the autopilot's δ_k first (the one that steers right), the paper's beside it
    assert "ship model (the autopilot's)" in human and "│ total δ_k │ -9.566 │ 13.31 │" in human
    assert "uses the ship model's δ_k" in human
    # an explicit particular overrides the named ship's
    longer = json.loads(runner.invoke(app, args + ["--length", "170"]).stdout)
    assert longer["delta_k_deg"] != data["delta_k_deg"]


def test_without_a_ship_model_the_model_delta_k_is_not_given():
    data = json.loads(runner.invoke(app, BASE + ["--json"]).stdout)
    assert data["delta_k_model_deg"] is None and data["autopilot_delta_k"] == "model"
    human = " ".join(runner.invoke(app, BASE).stdout.split())
    # no column of "needs --ship" cells: the paper's only, and the note says how
    assert "needs --ship" not in human and "ship model (the autopilot's)" not in human
    assert "The model's δ_k needs a ship model: --ship mariner" in human
    r = runner.invoke(app, BASE[2:])
    assert r.exit_code == 2
    assert "`--length` [m] is needed (or --ship mariner" in r.stderr


def test_a_sail_centre_off_the_ship_is_refused():
    r = runner.invoke(app, BASE + ["--sail-centre", "80"])
    assert r.exit_code == 2
    assert ("`--sail-centre` must lie on the ship, within ±L/2 = ±75 [m] of midships, got 80.0"
            in " ".join(r.stderr.split()))
    assert runner.invoke(app, BASE + ["--sail-centre", "-75", "--json"]).exit_code == 0


def test_windage_centres_off_the_ship_are_refused_by_the_library():
    from seahelm.environment.loads import LvovWindParams
    from seahelm.environment.wind import wind_moment_arm
    from seahelm.errors import ParameterError

    with pytest.raises(ParameterError, match=r"`windage_centre` must lie on the ship.*±50"):
        LvovWindParams(windage_lateral_area=900.0, windage_centre=60.0, windage_length=100.0)
    with pytest.raises(ParameterError, match=r"`sail_centre` must lie on the ship.*got -51"):
        wind_moment_arm(0.5, [0.0, -51.0], 100.0)
