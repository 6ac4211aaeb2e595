"""Bad input to ``seahelm replay`` found by this round's campaign (issue 43): each was an exit 2
with a misleading line, an option silently dropped, or a numpy warning, before.

The records are the synthetic FRT-DS-ESSO-header records of ``tests/test_replay.py``.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from seahelm.identification.records import read_records
from seahelm.analysis.replay.simulate import manoeuvre_metrics
from seahelm.errors import ParameterError

from conftest import one_error
from test_replay import SHIP, _simulated_turn, _write


@pytest.fixture(scope="module")
def turn_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("rec") / "turn.csv"
    return _write(path, *_simulated_turn())


def _lines(path):
    header, *rows = path.read_text().splitlines()
    return header, rows


def test_a_header_without_data_rows_is_named(tmp_path, turn_csv):
    # was: 'error: zero-size array to reduction operation fmax which has no identity'
    header, _ = _lines(turn_csv)
    bad = tmp_path / "header-only.csv"
    bad.write_text(header + "\n")
    line = one_error(["replay", str(bad), "--ship", SHIP])
    assert line == f"error: {bad}: a header and no data rows (a record needs its samples)"


def test_a_column_twice_in_the_header_is_named(tmp_path, turn_csv):
    # was: "column `heading` has shape (6002,), time (3001,)" (the two columns read as one)
    header, rows = _lines(turn_csv)
    bad = tmp_path / "twice.csv"
    bad.write_text("\n".join([header + ",psi_hat [rad]", *(r + ",0.0" for r in rows)]) + "\n")
    line = one_error(["replay", str(bad), "--ship", SHIP])
    assert line == (f"error: {bad}: column `psi_hat [rad]` appears twice in the header "
                    "(columns 6 and 12; row 1)")


def _generic(tmp_path, turn_csv):
    header, rows = _lines(turn_csv)
    names = ["time", "N", "U", "E", "V", "PSI", "R", "RPS", "DELTA", "W", "WD"]
    other = tmp_path / "other.csv"
    other.write_text("\n".join([",".join(names), *rows]) + "\n")
    return other


def test_a_column_mapped_to_an_unknown_channel_is_refused(tmp_path, turn_csv):
    # was: the column dropped without a word ('a replay needs column(s) x')
    other = _generic(tmp_path, turn_csv)
    line = one_error(["replay", str(other), "--ship", SHIP, "--angles", "rad",
                      "--column", "time=time", "--column", "DELTA=rudder_angle",
                      "--column", "PSI=heading", "--column", "N=north"])
    assert line.startswith(f"error: `--column` {other}: column `N` mapped to an unknown "
                           "channel `north`; valid: time, rudder_angle, heading"), line


def test_two_columns_mapped_to_one_channel_are_refused(tmp_path, turn_csv):
    # was: the last one read, the first dropped without a word
    other = _generic(tmp_path, turn_csv)
    with pytest.raises(ParameterError, match="columns `PSI` and `R` both mapped to `heading`"):
        read_records(other, angles="rad", columns={"time": "time", "DELTA": "rudder_angle",
                                                   "PSI": "heading", "R": "heading"})


def test_a_header_mapped_twice_is_refused(tmp_path, turn_csv):
    # was: the second mapping replaced the first ('missing column `time`')
    other = _generic(tmp_path, turn_csv)
    line = one_error(["replay", str(other), "--ship", SHIP, "--angles", "rad",
                      "--column", "time=time", "--column", "time=rudder_angle"])
    assert line == "error: `--column` maps header 'time' twice (time and rudder_angle)"


def test_a_check_angle_for_a_turn_is_refused(turn_csv):
    # was: accepted, ignored, and shown in the title ('turning, check angle 10 deg')
    line = one_error(["replay", str(turn_csv), "--ship", SHIP, "--check-angle", "10"])
    assert line == (f"error: `--check-angle` {turn_csv}: a check angle is a zig-zag's; this "
                    "record is 'turning' (drop it, or give kind 'zigzag')")


def test_a_turn_replayed_as_a_zigzag_says_the_check_angle_is_not_in_the_record(turn_csv):
    # was: 'a zig-zag needs its check angle [rad] (a record with a heading)' of a record that
    # has a heading
    line = one_error(["replay", str(turn_csv), "--ship", SHIP, "--kind", "zigzag"])
    assert line == (f"error: `--check-angle` {turn_csv}: the rudder does not switch between "
                    "two sides at a constant angle, so the check angle cannot be read from "
                    "the record; give it explicitly")


def test_a_turn_from_rest_has_no_speed_loss_and_no_warning():
    # was: 'RuntimeWarning: invalid value encountered in scalar divide' on the terminal
    t = np.linspace(0.0, 100.0, 1001)
    rudder = np.where(t > 1.0, math.radians(35.0), 0.0)
    psi = np.where(t > 1.0, 0.05 * (t - 1.0), 0.0)
    track = {"north": 10.0 * np.sin(psi), "east": 10.0 * (1.0 - np.cos(psi)), "heading": psi,
             "speed": np.zeros_like(t)}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m = manoeuvre_metrics("turning", t, track, rudder)
    assert math.isnan(m["speed_loss"])


def test_the_files_of_a_record_in_parts_are_checked_before_the_work(tmp_path, turn_csv):
    # a file of two records writes replay-1.* and replay-2.*; a user's replay-1.nc was found
    # only after the work, in the library's words ("`path` ... pass force=True"), and
    # --force did not exist
    header, rows = _lines(turn_csv)
    later = [",".join([repr(float(r.split(",")[0]) + 1000.0), *r.split(",")[1:]]) for r in rows]
    two = tmp_path / "two.csv"
    two.write_text("\n".join([header, *rows, *later]) + "\n")
    out = tmp_path / "out"
    out.mkdir()
    mine = out / "replay-1.nc"
    mine.write_text("a user's file\n")
    line = one_error(["replay", str(two), "--ship", SHIP, "--out", str(out)])
    assert line == (f"error: `--out` {mine} exists (a file seahelm did not write); this writes "
                    "a NetCDF file there: pass --force to replace it, or choose another path")
    assert mine.read_text() == "a user's file\n"
    from test_replay import run_cli

    res = run_cli(["replay", str(two), "--ship", SHIP, "--out", str(out), "--force"])
    assert res.exit_code == 0, res.stderr
    assert sorted(p.name for p in out.iterdir()) == ["replay-1.nc", "replay-1.png",
                                                     "replay-2.nc", "replay-2.png"]


def test_too_much_work_is_said_in_the_replays_words(turn_csv, monkeypatch):
    # was: "`t_final`: 1 run(s) x 3e+03 steps ... a shorter `t_final`, a larger `--dt` or
    # fewer runs" (replay has no t_final: the record's duration is the run's)
    monkeypatch.setenv("SEAHELM_WORK_BUDGET", "5")
    line = one_error(["replay", str(turn_csv), "--ship", SHIP])
    assert line.startswith(f"error: `--dt` = 0.05 s: the replay of {turn_csv} (150 s) takes "
                           "3,000 steps: 1 run(s) x 3e+03 steps"), line
    assert line.endswith("a larger step (the record's interval is 0.05 s) (or set "
                         "SEAHELM_WORK_BUDGET=1e+04 to run it anyway)"), line
    assert "t_final" not in line


def test_a_recording_too_large_names_the_step(turn_csv):
    # was: "`record_every`: the recorded time series would need 312 GB ..." (no such option)
    line = one_error(["replay", str(turn_csv), "--ship", SHIP, "--dt", "1e-7"])
    assert line.startswith(f"error: `--dt` = 1e-07 s: the replay of {turn_csv} (150 s) takes "
                           "1,500,000,000 steps: it would record 312 GB"), line
    assert "record_every" not in line


def test_a_replay_result_shows_a_summary_not_its_arrays(turn_csv):
    # was the dataclass's repr: 4.3 kB of the record's and both tracks' arrays
    from seahelm.analysis.replay.simulate import replay

    rec, = read_records(turn_csv)
    text = repr(replay(rec, SHIP))
    lines = text.splitlines()
    assert lines[0] == f"ReplayResult: {turn_csv} with {SHIP}"
    assert lines[1].split(None, 1) == ["kind", "turning (measured rudder; wind none)"]
    assert lines[2].split(None, 1) == ["record", "3001 samples, t = 0 … 150 s; dt 0.05 s"]
    assert lines[4].startswith("  metrics    advance, transfer, tactical_diameter")
    assert len(lines) == 5 and "array(" not in text


def test_replays_own_netcdf_is_named_when_given_as_a_record(tmp_path, turn_csv):
    # was: "not a seahelm simulation result ...; `seahelm plot` draws a result.nc ..." (said by
    # replay and identify nomoto too, of seahelm replay's own output)
    from test_replay import run_cli

    out = tmp_path / "out"
    assert run_cli(["replay", str(turn_csv), "--ship", SHIP, "--out", str(out)]).exit_code == 0
    nc = out / "replay.nc"
    for args in (["replay", str(nc), "--ship", SHIP], ["plot", str(nc)]):
        assert one_error(args) == (
            f"error: {nc}: a `seahelm replay` file (a measured and a simulated track, not runs) "
            "(no `status` over runs and `time`); a simulation result is a result.nc of "
            "`seahelm run --out` or a manoeuvre's *-runs.nc"), args


@pytest.mark.parametrize("column, value, message", [
    # was: "the replay with ship kvlcc2-l7 failed: diverged: non-finite state", blaming --ship
    (9, "1e300", "column `wind_velo_true [m/s]` row 42 is 1e+300 m/s, beyond ±150 m/s"),
    # was: exit 0, a wind from the direction of cos/sin(1e300)
    (10, "1e300", "column `true_wind_direction` row 42 is 1e+300 rad, beyond ±6283.19 rad"),
    # was: "column `x` row 42" in a file whose column is x_position_mid [m]
    (1, "1e300", "column `x_position_mid [m]` row 42 is 1e+300 m, beyond ±1e+08 m"),
])
def test_a_damaged_value_is_named_under_its_column(tmp_path, turn_csv, column, value, message):
    header, rows = _lines(turn_csv)
    cells = rows[40].split(",")
    cells[column] = value
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join([header, *rows[:40], ",".join(cells), *rows[41:]]) + "\n")
    line = one_error(["replay", str(bad), "--ship", SHIP, "--wind", "measured"])
    assert message in line and str(bad) in line, line


def test_angles_in_degrees_under_channel_names_are_limited_in_radians(tmp_path, turn_csv):
    # a header named as its channel, mapped, in degrees: its 35 deg rudder is not a
    # "1.5708 rad" limit's breach (the limits apply after --angles)
    header, rows = _lines(turn_csv)
    names = ["time", "x", "surge_speed", "y", "sway_speed", "heading", "yaw_rate",
             "propeller_rps", "rudder_angle", "W", "WD"]
    deg = [",".join(repr(math.degrees(float(c))) if k in (5, 6, 8) else c
                    for k, c in enumerate(r.split(","))) for r in rows]
    other = tmp_path / "deg.csv"
    other.write_text("\n".join([",".join(names), *deg]) + "\n")
    rec, = read_records(other, columns={n: n for n in names[:9]})
    assert max(abs(rec.rudder_angle)) == pytest.approx(math.radians(35.0))
