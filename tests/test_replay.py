"""``seahelm replay``: a measured record simulated with its measured inputs.

No measured data are used: the records are synthetic, made by simulating a catalog ship
(``kvlcc2-l7``) with known inputs and written as CSV files with the header of the FRT-DS-ESSO
free-running tests (Osaka University; the header names only, no data of the set).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from seahelm.identification.records import RECORD_FORMATS, read_records
from seahelm.analysis.replay.simulate import classify, replay
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.simulation.signals import Samples, make_signal

from conftest import one_error

HEADER = list(RECORD_FORMATS["FRT-DS-ESSO"][0])
SHIP = "kvlcc2-l7"
DT = 0.05  # [s]: the records' interval, and the replay's default step for this ship (L/100U)


def _write(path, time, track, rudder, rps):
    cols = {"t [s]": time, "x_position_mid [m]": track["north"],
            "u_velo [m/s]": track["surge_speed"], "y_position_mid [m]": track["east"],
            "vm_velo [m/s]": track["sway_speed"], "psi_hat [rad]": track["heading"],
            "r_angvelo [rad/s]": track["yaw_rate"], "n_prop [rps]": rps,
            "delta_rudder [rad]": rudder, "wind_velo_true [m/s]": np.zeros_like(time),
            "wind_dir_true [rad]": np.zeros_like(time)}
    with open(path, "w") as fh:
        fh.write(",".join(HEADER) + "\n")
        for i in range(time.size):
            fh.write(",".join(repr(float(cols[h][i])) for h in HEADER) + "\n")
    return path


def _simulated_turn(t_final=150.0, rudder=math.radians(35.0)):
    """A turn of the KVLCC2 L7 model: the rudder ramped at 15.8 deg/s from t = 1 s (2.32
    deg/s at full scale, Froude-scaled) to ``rudder``, 10.4 rps, from a non-zero origin."""
    ship = get_ship(SHIP)
    knots = np.arange(0.0, t_final + DT / 2, DT)
    delta = np.clip((knots - 1.0) * math.radians(15.8), 0.0, rudder)
    x0 = ship.model.initial_state(surge_speed=1.179, north=3.0, east=-2.0, heading=0.4)
    res = simulate(Problem(t_final=t_final, dt=DT, ship=ship, actuator="direct", x0=x0,
                           reference={"rudder_angle": Samples(tuple(knots), tuple(delta)),
                                      "propeller_rps": 10.4}))
    track = {k: res[k][0] for k in ("north", "east", "heading", "surge_speed", "sway_speed",
                                    "yaw_rate")}
    return res.time, track, res["rudder_angle"][0], res["propeller_rps"][0]


@pytest.fixture(scope="module")
def turn_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("rec") / "turn.csv"
    return _write(path, *_simulated_turn())


@pytest.fixture(scope="module")
def zigzag_csv(tmp_path_factory):
    """A 20/20 zig-zag of seahelm's own manoeuvre (steering gear in the loop): its rudder and
    track written as a record."""
    from seahelm.analysis.maneuvers import zigzag

    z = zigzag(SHIP, math.radians(20.0), sides=1, dt=DT)
    sim = z.simulation
    track = {k: sim[k][0] for k in ("north", "east", "heading", "surge_speed", "sway_speed",
                                    "yaw_rate")}
    path = tmp_path_factory.mktemp("rec") / "zigzag.csv"
    return _write(path, sim.time, track, sim["rudder_angle"][0], sim["propeller_rps"][0]), z


def test_samples_signal_is_a_first_order_hold():
    sig = make_signal({"kind": "samples", "times": [0.0, 1.0, 3.0], "values": [0.0, 2.0, -2.0]})
    np.testing.assert_allclose(sig(np.array([-1.0, 0.5, 1.0, 2.0, 3.0, 9.0])),
                               [0.0, 1.0, 2.0, 0.0, -2.0, -2.0])
    with pytest.raises(ParameterError, match="must increase.*1.0 then 1.0 at index 2"):
        Samples((0.0, 1.0, 1.0), (0.0, 1.0, 2.0))


def test_the_frt_ds_esso_header_is_read_as_it_is(turn_csv):
    rec, = read_records(turn_csv)
    assert set(rec.channels) >= {"x", "y", "surge_speed", "sway_speed", "propeller_rps",
                                 "true_wind_speed", "true_wind_direction"}
    assert rec.heading[0] == pytest.approx(0.4)  # radians, as the header says (not degrees)
    assert rec.channels["x"][0] == pytest.approx(3.0)


def test_replay_with_the_same_ship_reproduces_the_record(turn_csv):
    rec, = read_records(turn_csv)
    res = replay(rec, SHIP)
    assert res.kind == "turning" and res.dt == pytest.approx(DT)
    assert res.rms_error_window < 1e-6 and res.rms_error < 1e-6
    for name, (measured, simulated) in res.metrics.items():
        assert math.isfinite(measured), name
        assert simulated == pytest.approx(measured, rel=1e-9, abs=1e-9), name
    # the measured metrics are the record's own: TD and advance of the turn at 35 deg, in L
    assert 2.5 < res.metrics["tactical_diameter"][0] / res.length < 4.0
    assert res.metrics["steady_diameter"][0] < res.metrics["tactical_diameter"][0]


def test_replay_with_a_perturbed_ship_drifts_away(turn_csv):
    rec, = read_records(turn_csv)
    ship = get_ship(SHIP)
    worse = ship.replace(params={"N_r": 1.3 * ship.params.N_r})
    res = replay(rec, worse)
    assert res.rms_error > 0.05 and res.rms_error > res.rms_error_window > 1e-3
    measured, simulated = res.metrics["tactical_diameter"]
    assert abs(simulated - measured) > 0.02 * measured  # a stiffer yaw damping: a wider turn
    assert simulated > measured


def test_zigzag_record_metrics_match_the_manoeuvre_and_the_replay(zigzag_csv):
    path, z = zigzag_csv
    rec, = read_records(path)
    kind, angle = classify(rec)
    assert kind == "zigzag" and math.degrees(angle) == pytest.approx(20.0)
    res = replay(rec, SHIP)
    overshoot = np.asarray(z.metrics["overshoot"]).reshape(-1, 3)[0, 0]
    assert res.metrics["overshoot_1"][0] == pytest.approx(overshoot, abs=1e-9)
    # measured rudder replayed through the first-order hold (the steering gear's lag between
    # samples is not replayed): the same zig-zag to a few hundredths of a degree
    for j in (1, 2, 3):
        m, s = res.metrics[f"overshoot_{j}"]
        assert math.isfinite(m) and abs(math.degrees(s - m)) < 0.05, j
    assert res.rms_error < 5e-3  # 1.2 cm of a 7 m model: the servo moved within steps


def run_cli(args):
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    return CliRunner().invoke(app, args)


def _rows(path):
    return path.read_text().splitlines()


@pytest.mark.parametrize("edit, message", [
    (lambda h, r: (h.replace("delta_rudder [rad],", ""), [",".join(
        c for k, c in enumerate(x.split(",")) if k != 8) for x in r]),
     "without column(s) `delta_rudder [rad]` (row 1, the header)"),
    (lambda h, r: (h.replace("psi_hat [rad]", "psi [rad]"), r),
     "without column(s) `psi_hat [rad]`"),
    (lambda h, r: (h, r[:40] + [r[40].replace(r[40].split(",")[5], "nan", 1)] + r[41:]),
     "column `psi_hat [rad]` row 42 is not a finite number (nan)"),
    (lambda h, r: (h, r[:30] + [r[31], r[30]] + r[32:]),
     "column `t [s]` row 33 does not increase (1.55 then 1.5)"),
    (lambda h, r: (h, [",".join(c if k != 8 else repr(math.degrees(float(c)))
                                for k, c in enumerate(x.split(","))) for x in r]),
     "column `delta_rudder [rad]` row 24 is 1.58 rad (more than 90°) with angles in radians: "
     "are they degrees? (this file's format is in radians)"),
    (lambda h, r: (h, r[:600]), "column `psi_hat [rad]` row 601: the record ends at a heading "
     "change of 93.08 deg; a turning circle needs 180 deg (shorter than the manoeuvre needs)"),
])
def test_bad_records_exit_2_with_one_line(tmp_path, turn_csv, edit, message):
    header, *rows = _rows(turn_csv)
    header, rows = edit(header, rows)
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join([header, *rows]) + "\n")
    line = one_error(["replay", str(bad), "--ship", SHIP])
    assert message in line and str(bad) in line, line


def test_cli_end_to_end(tmp_path, turn_csv):
    out = tmp_path / "out"
    res = run_cli(["replay", str(turn_csv), "--ship", SHIP, "--json", "--out", str(out)])
    assert res.exit_code == 0, res.stderr
    payload = json.loads(res.stdout)
    rep, = payload["replays"]
    assert rep["kind"] == "turning" and rep["rms_position_error_L"] < 1e-6
    td = rep["metrics"]["tactical_diameter"]
    assert td["simulated"] == pytest.approx(td["measured"]) and td["unit"] == "m"
    import xarray as xr

    with xr.open_dataset(out / "replay.nc") as ds:
        assert list(ds["track"].values) == ["measured", "simulated"]
        np.testing.assert_allclose(ds["north"].sel(track="simulated"),
                                   ds["north"].sel(track="measured"), atol=1e-9)
    assert (out / "replay.png").stat().st_size > 10_000
    table = run_cli(["replay", str(turn_csv), "--ship", SHIP])
    assert table.exit_code == 0 and "tactical diameter [m]" in table.stdout


def test_a_column_mapping_reads_another_header(tmp_path, turn_csv):
    header, *rows = _rows(turn_csv)
    other = tmp_path / "other.csv"
    names = ["time", "N", "U", "E", "V", "PSI", "R", "RPS", "DELTA", "W", "WD"]
    other.write_text("\n".join([",".join(names), *rows]) + "\n")
    cols = {"time": "time", "N": "x", "U": "surge_speed", "E": "y", "V": "sway_speed",
            "PSI": "heading", "R": "yaw_rate", "RPS": "propeller_rps", "DELTA": "rudder_angle"}
    rec, = read_records(other, angles="rad", columns=cols)
    assert replay(rec, SHIP).rms_error < 1e-6
    args = [a for h, c in cols.items() for a in ("--column", f"{h}={c}")]
    res = run_cli(["replay", str(other), "--ship", SHIP, "--angles", "rad", *args])
    assert res.exit_code == 0, res.stderr
    line = one_error(["replay", str(other), "--ship", SHIP, "--angles", "rad",
                      "--column", "time=time", "--column", "DELTA=rudder_angle"])
    assert "missing column `heading` or `yaw_rate`" in line and str(other) in line, line


def test_closed_loop_zigzag_reproduces_the_manoeuvre(zigzag_csv):
    """seahelm's zig-zag replayed closed loop with the same ship: the same controller, servo and
    step from the same state, so the same run (the open-loop replay differs by the servo's
    motion within steps, test above)."""
    path, z = zigzag_csv
    rec, = read_records(path)
    res = replay(rec, SHIP, closed_loop=True)
    assert res.closed_loop and res.rms_error < 1e-6
    for name, (measured, simulated) in res.metrics.items():
        assert simulated == pytest.approx(measured, abs=1e-6), name
    worse = get_ship(SHIP).replace(params={"N_r": 1.3 * get_ship(SHIP).params.N_r})
    res = replay(rec, worse, closed_loop=True)
    m, s = res.metrics["overshoot_1"]
    assert s < m - math.radians(0.2)  # more yaw damping: a smaller first overshoot


def test_closed_loop_is_for_a_zigzag(turn_csv):
    line = one_error(["replay", str(turn_csv), "--ship", SHIP, "--closed-loop"])
    assert "a closed-loop replay is for a zig-zag; this record is 'turning'" in line


def test_measured_wind_is_replayed(tmp_path):
    """A turn simulated in a steady 4 m/s wind from 60 deg (the wind a parameter), written
    with that wind in the record's true-wind columns: replayed with the measured wind (the
    speed then comes in as a time series) it is the same run; in still air it is not."""
    from seahelm.environment.loads import environment, ship_load_params

    ship = get_ship(SHIP)
    env = environment(wind="blendermann")
    direction = math.radians(60.0)
    params = ship_load_params(ship, env, wind_speed=4.0, wind_direction=direction)
    t_final = 60.0
    knots = np.arange(0.0, t_final + DT / 2, DT)
    delta = np.clip((knots - 1.0) * math.radians(15.8), 0.0, math.radians(35.0))
    x0 = ship.model.initial_state(surge_speed=1.179)
    res = simulate(Problem(t_final=t_final, dt=DT, ship=ship, actuator="direct", x0=x0,
                           environment=env, environment_params=params,
                           reference={"rudder_angle": Samples(tuple(knots), tuple(delta)),
                                      "propeller_rps": 10.4}))
    track = {k: res[k][0] for k in ("north", "east", "heading", "surge_speed", "sway_speed",
                                    "yaw_rate")}
    path = _write(tmp_path / "windy.csv", res.time, track, res["rudder_angle"][0],
                  res["propeller_rps"][0])
    header, *rows = _rows(path)
    rows = [",".join([*r.split(",")[:-2], "4.0", repr(direction)]) for r in rows]
    path.write_text("\n".join([header, *rows]) + "\n")
    rec, = read_records(path)
    windy = replay(rec, SHIP, kind="none", wind="measured")
    assert windy.rms_error < 1e-6
    assert windy.wind["direction"] == pytest.approx(direction)
    assert windy.wind["mean_speed"] == pytest.approx(4.0)
    still = replay(rec, SHIP, kind="none")
    assert still.rms_error > 1e-3
    rows = [",".join([*r.split(",")[:-2], "-1.0", "0.0"]) if k == 9 else r
            for k, r in enumerate(rows)]
    path.write_text("\n".join([header, *rows]) + "\n")
    line = one_error(["replay", str(path), "--ship", SHIP, "--wind", "measured"])
    assert "column `wind_velo_true [m/s]` row 11 is -1.0 [m/s] (< 0)" in line, line


def test_a_turn_that_ends_with_the_rudder_eased_counts_until_then(tmp_path, turn_csv):
    """Speed loss and steady diameter are taken while the rudder is held: the record's last
    20 s with the rudder amidships (the ship straightening up) change neither."""
    header, *rows = _rows(turn_csv)
    rec, = read_records(turn_csv)
    held = replay(rec, SHIP)
    eased = [",".join([*r.split(",")[:8], "0.0", *r.split(",")[9:]]) if k >= len(rows) - 400
             else r for k, r in enumerate(rows)]
    path = tmp_path / "eased.csv"
    path.write_text("\n".join([header, *eased]) + "\n")
    rec, = read_records(path)
    res = replay(rec, SHIP)
    # (the measured track is the held turn's, so only the simulated one straightens up)
    assert res.rms_error_window < 1e-6 < 1e-3 < res.rms_error
    end = len(rows) - 401
    u, v = rec.channels["surge_speed"], rec.channels["sway_speed"]
    k0 = int(np.flatnonzero(rec.rudder_angle > 0)[0]) - 1
    expected = 1.0 - math.hypot(u[end], v[end]) / math.hypot(u[k0], v[k0])
    assert res.metrics["speed_loss"][0] == pytest.approx(expected, rel=1e-12)
    assert res.metrics["speed_loss"][0] != pytest.approx(held.metrics["speed_loss"][0],
                                                          rel=1e-6)


def test_a_zigzag_cut_before_its_third_execute_is_too_short(tmp_path, zigzag_csv):
    path, _ = zigzag_csv
    header, *rows = _rows(path)
    short = tmp_path / "short.csv"
    short.write_text("\n".join([header, *rows[:700]]) + "\n")  # 35 s: past the 2nd execute
    line = one_error(["replay", str(short), "--ship", SHIP, "--kind", "zigzag",
                      "--check-angle", "20"])
    assert ("column `psi_hat [rad]` row 701: the record ends before the zig-zag's third "
            "execute (shorter than the manoeuvre needs)") in line, line
