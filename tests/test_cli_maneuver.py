"""``seahelm maneuver turning|zigzag|spiral|pullout`` and ``seahelm imo MODEL`` (CliRunner).

Uses the MMG kernels (open loop, zigzag-rps) and the Mariner open-loop kernel only.
"""

from __future__ import annotations

import json
import math
import os

import pytest
import xarray as xr
from typer.testing import CliRunner

from seahelm.analysis.maneuvers import turning_circle
from seahelm.cli.main import app

runner = CliRunner()


def run_json(*args: str) -> dict:
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)  # exactly one JSON object on stdout


def test_turning_json_matches_the_library():
    out = run_json("maneuver", "turning", "--catalog", "kvlcc2-l7", "--rudder", "35",
                   "--t-final", "60")
    assert out["maneuver"] == "turning-circle" and out["ship"] == "kvlcc2-l7"
    assert out["length_m"] == 7.0 and out["approach_speed_mps"] == 1.179
    assert [r["side"] for r in out["runs"]] == ["starboard", "port"]
    lib = turning_circle("kvlcc2-l7", math.radians(35.0), t_final=60.0).metrics
    for row, side in zip(out["runs"], (1, -1)):
        m = lib.sel(side=side)
        assert row["advance_m"] == pytest.approx(float(m["advance"]), rel=1e-12)
        assert row["tactical_diameter_L"] == pytest.approx(float(m["tactical_diameter"]) / 7.0,
                                                           rel=1e-12)
        assert row["drift_angle_deg"] == pytest.approx(
            math.degrees(float(m["steady_drift_angle"])), rel=1e-12)
        assert row["rudder_deg"] == pytest.approx(35.0)


def test_turning_of_a_model_with_roll_shows_the_heel():
    """The 4-DOF container ship's table and JSON carry the maximum and steady heel (the
    library's metrics, in degrees); a ship without roll has no such rows."""
    args = ("maneuver", "turning", "--catalog", "son-nomoto-container", "--rudder", "20",
            "--side", "starboard", "--t-final", "600")
    out = run_json(*args)
    lib = turning_circle("son-nomoto-container", math.radians(20.0), sides=1,
                         t_final=600.0).metrics
    row = out["runs"][0]
    assert row["max_heel_deg"] == pytest.approx(math.degrees(float(lib["max_heel_angle"])),
                                                rel=1e-12)
    assert row["steady_heel_deg"] == pytest.approx(
        math.degrees(float(lib["steady_heel_angle"])), rel=1e-12)
    assert row["steady_heel_deg"] < 0.0  # a turn to starboard heels to port, outward
    table = runner.invoke(app, list(args))
    assert table.exit_code == 0 and "maximum heel [deg]" in table.stdout
    assert "heel" not in json.dumps(run_json("maneuver", "turning", "--t-final", "60"))


def test_turning_not_reaching_180_is_a_result_not_an_error():
    out = run_json("maneuver", "turning", "--side", "starboard", "--t-final", "30")
    (row,) = out["runs"]
    assert row["tactical_diameter_m"] is None  # NaN -> null
    assert row["complete"] is False and "180 deg heading change not reached" in row["message"]


def test_turning_table_and_out(tmp_path):
    res = runner.invoke(app, ["maneuver", "turning", "--t-final", "60", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.stderr
    assert "tactical diameter [L]" in res.stdout and "starboard" in res.stdout
    files = sorted(os.listdir(tmp_path))
    assert files == ["turning-circle-metrics.nc", "turning-circle-runs.nc", "turning.png"]
    assert (tmp_path / "turning.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with xr.open_dataset(tmp_path / "turning-circle-metrics.nc", engine="h5netcdf") as ds:
        assert ds["advance"].dims == ("side",) and ds["advance"].attrs["units"] == "m"
        assert ds["complete"].values.tolist() == [1, 1]  # booleans stored as int8 flags
        assert all(str(msg).startswith("ok") for msg in ds["message"].values)
    with xr.open_dataset(tmp_path / "turning-circle-runs.nc", engine="h5netcdf") as ds:
        assert ds["heading"].dims == ("side", "time")


@pytest.mark.parametrize("args, text", [
    (["maneuver", "turning", "--rudder", "40"],
     "`--rudder` must be in (0, 35] [deg] (steering gear limit of 'kvlcc2-l7'), got 40.0"),
    (["maneuver", "turning", "--rudder", "0"], "`--rudder` must be in (0, 35] [deg]"),
    (["maneuver", "turning", "--speed", "-1"], "`--speed` must be > 0 [m/s], got -1.0"),
    (["maneuver", "turning", "--rps", "0"], "`--rps` must be > 0 [1/s], got 0.0"),
    (["maneuver", "turning", "--catalog", "mariner-nonlinear", "--rps", "2"],
     "`--rps`: 'mariner-nonlinear' (model mariner) has no propeller input, got 2.0 [1/s]"),
    (["maneuver", "turning", "--catalog", "kvlcc9"],
     "unknown ship 'kvlcc9'; catalog ships with a steering gear: esso-osaka-3m, kvlcc2-full, kvlcc2-l7, "
     "kvlcc2-l7-wp0-0.35, kvlcc2-l7-xp-0.5, mariner-nonlinear, son-nomoto-container (or the "
     "path of a ship file"),
    (["maneuver", "turning", "--catalog", "mariner-nomoto2"],  # in the catalog, no steering gear
     "ship 'mariner-nomoto2' has no steering gear"),
    (["maneuver", "turning", "--side", "middle"],
     "Invalid value for '--side': 'middle' is not one of 'both', 'starboard', 'port'"),
    (["maneuver", "zigzag", "--side", "left"], "Invalid value for '--side': 'left' is not one of"),
    (["maneuver", "turning", "--dt", "-0.1"], "`--dt` must be > 0 [s], got -0.1"),
    (["maneuver", "zigzag", "--heading", "200"], "`--heading` must be in (0, 180) [deg], got "
                                                 "200.0"),
    (["maneuver", "zigzag", "--rudder", "10", "--heading", "60", "--t-final", "20"],
     "`--heading` trigger 60 deg is not reached within `--t-final` = 20.0 [s]"),
    # library messages name the command's options (the user typed `--t-final`, not t_final)
    (["maneuver", "zigzag", "--rps", "0.001"], "GB (a peak of about 2.5x that), more than 80% of the"),
    (["maneuver", "pullout", "--rps", "0.001"],
     "give a faster approach (`--speed` or `--rps`) or a shorter `--t-final`"),
    (["maneuver", "pullout", "--rudder", "-5"], "`--rudder` must be in (0, 35] [deg]"),
    (["maneuver", "spiral", "--max-rudder", "36"], "`--max-rudder` must be in (0, 35] [deg]"),
    (["maneuver", "spiral", "--hold", "0"], "`--hold` must be > 0 [s], got 0.0"),
    (["imo", "nope"], "unknown ship 'nope'; catalog ships with a steering gear: esso-osaka-3m, kvlcc2-full, "),
    (["imo", "mariner-nomoto2"], "ship 'mariner-nomoto2' has no steering gear"),
    (["imo", "kvlcc2-l7", "--speed", "0"], "`--speed` must be > 0 [m/s], got 0.0"),
    (["maneuver", "stopping", "--ship", "mariner-nonlinear"],
     "`--ship`: ship 'mariner-nonlinear' has no propeller"),
    (["maneuver", "stopping", "--order", "0.5"], "`--order` must be in [-1, 0) [-]"),
    (["maneuver", "stopping", "--reversal-delay", "-3"],
     "`--reversal-delay` must be >= 0 [s], got -3.0"),
    (["maneuver", "stopping", "--dead-fraction", "1"], "`--dead-fraction` must be in [0, 1)"),
    (["maneuver", "stopping", "--hull", "yoshimura"],
     "`--hull` must be one of cross-flow, mirror, got 'yoshimura'"),
])
def test_bad_input_exits_2_with_one_line(args, text):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    assert res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert text in " ".join(res.stderr.split())


def test_zigzag_json_and_out(tmp_path):
    out = run_json("maneuver", "zigzag", "--rudder", "10", "--heading", "10", "--out",
                   str(tmp_path))
    assert out["rudder_deg"] == 10.0 and out["heading_trigger_deg"] == 10.0
    for row in out["runs"]:
        assert row["complete"] is True
        assert 0.0 < row["overshoot_1_deg"] < 10.0
        assert row["period_s"] > row["initial_turning_time_s"] > 0.0
    assert sorted(os.listdir(tmp_path)) == ["zigzag-metrics.nc", "zigzag-runs.nc", "zigzag.png"]
    assert set(out["files"]) == {"zigzag-metrics", "zigzag-runs", "plot"}


def test_pullout_json():
    out = run_json("maneuver", "pullout", "--catalog", "mariner-nonlinear", "--rudder", "20")
    assert [r["side"] for r in out["runs"]] == ["starboard", "port"]
    residuals = [r["residual_yaw_rate_degps"] for r in out["runs"]]
    assert residuals[0] == pytest.approx(residuals[1], rel=1e-3) and residuals[0] > 0.1
    assert abs(out["residual_gap_degps"]) < 1e-3


def test_spiral_json(tmp_path):
    out = run_json("maneuver", "spiral", "--catalog", "kvlcc2-l7", "--max-rudder", "10",
                   "--out", str(tmp_path))
    assert out["maneuver"] == "spiral"
    assert len(out["direct"]) == 33 and out["direct"][0]["rudder_deg"] == pytest.approx(10.0)
    assert 0.3 < out["reverse_loop_width_deg"] < 0.5
    assert out["reverse_loop_rudder_low_deg"] == pytest.approx(0.0, abs=1e-6)
    assert sorted(os.listdir(tmp_path)) == ["direct-spiral-metrics.nc", "direct-spiral-runs.nc",
                                            "reverse-spiral-metrics.nc", "spiral.png"]


def test_imo_json_and_table(tmp_path):
    out = run_json("imo", "kvlcc2-l7", "--out", str(tmp_path))
    assert out["ship"] == "kvlcc2-l7" and out["passed"] is True
    assert out["L_over_V_s"] == pytest.approx(7.0 / 1.179)
    crit = {(c["ability"], c["criterion"], c["side"]): c for c in out["criteria"]}
    first = crit[("10/10 zig-zag", "first overshoot", "starboard")]
    assert first["unit"] == "deg" and first["limit"] == pytest.approx(10.0)
    stop = crit[("stopping", "track reach (full astern)", "-")]
    assert stop["status"] == "pass" and 5.0 < stop["value"] < 9.0 and stop["limit"] == 15.0
    report = json.loads((tmp_path / "imo-report.json").read_text())
    assert report["criteria"] == out["criteria"]
    assert {"imo-turning.png", "imo-zigzag.png", "turning-circle-metrics.nc",
            "zigzag-metrics.nc", "stopping-metrics.nc", "stopping-runs.nc",
            "imo-stopping.png"} <= set(os.listdir(tmp_path))
    res = runner.invoke(app, ["imo", "kvlcc2-l7"])
    assert res.exit_code == 0
    text = " ".join(res.stdout.split())
    assert "PASSES" in text and "the engine is an estimate" in text
    mariner = run_json("imo", "mariner-nonlinear")
    stop = {(c["ability"], c["side"]): c for c in mariner["criteria"]}[("stopping", "-")]
    assert stop["status"] == "not evaluated" and "no propeller" in stop["note"]


def test_stopping_json_and_out(tmp_path):
    out = run_json("maneuver", "stopping", "--ship", "kvlcc2-l7", "--reversal-delay", "5",
                   "--out", str(tmp_path))
    assert out["maneuver"] == "stopping" and out["engine_order"] == -1.0
    (run,) = out["runs"]
    assert run["complete"] and run["reversal_delay_s"] == 5.0
    assert out["hull"] == "cross-flow"
    assert 5.0 < run["time_astern_s"] < 7.0
    assert run["head_reach_L"] == pytest.approx(run["head_reach_m"] / 7.0)
    assert run["head_reach_m"] <= run["track_reach_m"]
    assert sorted(os.listdir(tmp_path)) == ["stopping-metrics.nc", "stopping-runs.nc",
                                            "stopping.png"]


def test_no_steady_turn_names_the_option_that_avoids_it():
    """60 m/s (51 x the parameter set's speed): a validity warning, then one error line naming
    `--t-final` (which skips the duration estimate that needs the steady turn)."""
    res = runner.invoke(app, ["maneuver", "turning", "--speed", "60"])
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert [line.split(":")[0] for line in lines] == ["warning", "error"]
    assert lines[1].startswith("error: `--t-final`: no steady turn of 'kvlcc2-l7' at rudder 35, "
                               "-35 deg from the approach at 60 m/s")
    assert lines[1].endswith("identified near 1.179 m/s; give `--t-final` to skip the estimate")
    assert "t_final" not in lines[1]


def test_library_messages_keep_python_names_outside_the_cli():
    """The equilibrium failure names the keyword that avoids it (`t_final`), in degrees."""
    from seahelm.analysis.equilibria.equilibrium import EquilibriumError

    with pytest.raises(EquilibriumError, match=r"^`t_final`: no steady turn of 'kvlcc2-l7' at "
                                               r"rudder 35 deg .*\(35 deg\).*give `t_final`"):
        with pytest.warns(Warning):  # 60 m/s is far above the parameter set's speed
            turning_circle("kvlcc2-l7", sides=1, speed=60.0)


def test_scenario_maneuver_equilibrium_failure_names_file_and_key(tmp_path):
    path = tmp_path / "fast.toml"
    path.write_text('[vessel]\ncatalog = "kvlcc2-l7"\n\n[maneuver]\nkind = "turning"\n'
                    'speed = 60.0\n')
    res = runner.invoke(app, ["run", str(path)])
    assert res.exit_code == 2, (res.stdout, res.stderr)
    line = res.stderr.strip().splitlines()[-1]  # (after the validity warning)
    assert line.startswith(f"error: {path}: [maneuver] `t_final`: no steady turn")



def test_spiral_table_shows_the_reverse_spirals_curve():
    """The reverse spiral appeared only as its loop width: its r-delta points are a table
    too, each the JSON's point (at most 15 shown)."""
    res = runner.invoke(app, ["maneuver", "spiral", "--catalog", "kvlcc2-l7", "--max-rudder",
                              "10"], env={"COLUMNS": "120"})
    assert res.exit_code == 0, res.output
    text = " ".join(res.stdout.split())
    assert "Reverse spiral (equilibria)" in text
    points = run_json("maneuver", "spiral", "--catalog", "kvlcc2-l7", "--max-rudder",
                      "10")["reverse"]
    shown = points[::max(1, math.ceil(len(points) / 15))]
    assert f"{len(shown)} of {len(points)} points" in text
    for row in shown:
        assert f"{row['rudder_deg']:.4g}" in text


def test_stopping_hull_option_selects_the_mirrored_hull():
    """--hull mirror: the earlier approximation; the L7's crash stop is the same to dead in the
    water (it leaves the MMG range only at the end), the option is echoed."""
    a = run_json("maneuver", "stopping", "--ship", "kvlcc2-l7", "--hull", "mirror")
    b = run_json("maneuver", "stopping", "--ship", "kvlcc2-l7", "--hull", "cross-flow")
    assert (a["hull"], b["hull"]) == ("mirror", "cross-flow")
    assert a["runs"][0]["head_reach_m"] == pytest.approx(b["runs"][0]["head_reach_m"], rel=1e-4)
