"""Propeller reversals found in records and their stops replayed (issue 48 item 4).

No measured data: the records are synthetic — the catalog ship ``esso-osaka-3m`` simulated with
known rps and rudder and written in the FRT-DS-ESSO header (names only, no data of the set).
The expected stops are read from the dense simulated track with numpy, not by the code under
test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.identification.records import RECORD_FORMATS, read_records, record_from_arrays
from seahelm.analysis.replay.reversals import (
    REVERSAL_RULE,
    find_reversals,
    replay_stop,
    slice_record,
)
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.simulation.signals import Samples

HEADER = list(RECORD_FORMATS["FRT-DS-ESSO"][0])
SHIP = "esso-osaka-3m"
DT = 0.1  # [s]: the data set's interval


def _simulate(rps_knots, t_final, dt=0.02):
    ship = get_ship(SHIP)
    knots = np.arange(0.0, t_final + dt / 2, DT)
    rps = np.interp(knots, *rps_knots)
    delta = math.radians(2.0) * np.sin(0.3 * knots)
    x0 = ship.model.initial_state(surge_speed=0.3, north=1.0, east=2.0, heading=0.3)
    res = simulate(Problem(t_final=t_final, dt=dt, ship=ship, actuator="direct", x0=x0,
                           reference={"rudder_angle": Samples(tuple(knots), tuple(delta)),
                                      "propeller_rps": Samples(tuple(knots), tuple(rps))}))
    return res


def _write(path, res, every):
    t = res.time[::every]
    cols = {"t [s]": t, "x_position_mid [m]": res["north"][0][::every],
            "u_velo [m/s]": res["surge_speed"][0][::every],
            "y_position_mid [m]": res["east"][0][::every],
            "vm_velo [m/s]": res["sway_speed"][0][::every],
            "psi_hat [rad]": res["heading"][0][::every],
            "r_angvelo [rad/s]": res["yaw_rate"][0][::every],
            "n_prop [rps]": res["propeller_rps"][0][::every],
            "delta_rudder [rad]": res["rudder_angle"][0][::every],
            "wind_velo_true [m/s]": np.zeros_like(t), "wind_dir_true [rad]": np.zeros_like(t)}
    with open(path, "w") as fh:
        fh.write(",".join(HEADER) + "\n")
        for i in range(t.size):
            fh.write(",".join(repr(float(cols[h][i])) for h in HEADER) + "\n")
    return read_records(path)[0]


@pytest.fixture(scope="module")
def crash_stop(tmp_path_factory):
    """Ahead at 10 rps, reversed to -10 rps between 20.0 and 20.5 s, held."""
    res = _simulate(([0.0, 20.0, 20.5, 200.0], [10.0, 10.0, -10.0, -10.0]), 120.0)
    return res, _write(tmp_path_factory.mktemp("rev") / "crash.csv", res, 5)


def _truth(res, t_start):
    """Time and head reach to u = 0 from the dense simulated track (numpy only)."""
    t, u = res.time, res["surge_speed"][0]
    k = int(np.flatnonzero((t >= t_start) & (u <= 0))[0])
    t0 = t[k - 1] + (t[k] - t[k - 1]) * u[k - 1] / (u[k - 1] - u[k])
    i = int(np.argmin(np.abs(t - t_start)))
    psi = res["heading"][0][i]
    dn = np.interp(t0, t, res["north"][0]) - res["north"][0][i]
    de = np.interp(t0, t, res["east"][0]) - res["east"][0][i]
    return t0 - t_start, dn * math.cos(psi) + de * math.sin(psi)


def test_a_crash_stop_is_found_with_its_time_and_reach(crash_stop):
    res, record = crash_stop
    found = find_reversals(record)
    assert len(found) == 1
    rev = found[0]
    n = record.channels["propeller_rps"]
    assert n[rev.start] > 0 and n[rev.start + 1] <= 0 and rev.astern_rps == pytest.approx(-10)
    assert record.channels["surge_speed"][rev.stop] <= 0 < record.channels["surge_speed"][
        rev.stop - 1]
    t_stop, reach = _truth(res, rev.start_time)
    assert rev.time_to_stop == pytest.approx(t_stop, abs=0.01)  # linear interpolation at 0.1 s
    assert rev.head_reach == pytest.approx(reach, rel=1e-3)
    assert 5.0 < t_stop < 100.0 and reach > 0.3  # a real stop, not a trivial one


def test_the_replayed_stop_of_the_same_ship_agrees(crash_stop):
    _res, record = crash_stop
    rev = find_reversals(record)[0]
    got = replay_stop(record, rev, SHIP)
    assert abs(got.time_error) < 0.02 and abs(got.reach_error) < 0.02
    assert got.wind == "none"


def test_the_rule_rejects_unclean_stops(tmp_path):
    # the rps comes back ahead before the ship stops: not clean
    res = _simulate(([0.0, 10.0, 10.5, 14.0, 14.5, 80.0], [10.0, 10.0, -10.0, -10.0, 8.0, 8.0]),
                    60.0)
    assert find_reversals(_write(tmp_path / "back.csv", res, 5)) == []
    # a stopped propeller (n = 0): a coasting stop, found only when asked for (a made-up
    # record: u falls linearly through 0 at t = 30 s with n = 0 from t = 10 s)
    t = np.arange(0.0, 40.0, DT)
    u = np.clip(0.2 - 0.01 * np.maximum(t - 10.0, 0.0), -0.05, None)
    record = record_from_arrays("coast", t, 0.01 * np.sin(t), heading=np.zeros_like(t),
                                yaw_rate=np.zeros_like(t), surge_speed=u,
                                sway_speed=np.zeros_like(t), x=np.cumsum(u) * DT,
                                y=np.zeros_like(t), propeller_rps=np.where(t < 10.0, 8.0, 0.0))[0]
    assert find_reversals(record) == []
    coast = find_reversals(record, coasting=True)
    assert len(coast) == 1 and coast[0].coasting and coast[0].astern_rps == 0.0
    assert coast[0].time_to_stop == pytest.approx(30.0 - t[coast[0].start], abs=1e-9)
    # too slow at the reversal
    assert find_reversals(_write(tmp_path / "back2.csv", _simulate(
        ([0.0, 10.0, 10.5, 200.0], [10.0, 10.0, -10.0, -10.0]), 80.0), 5),
        min_speed=0.5) == []


def test_a_record_without_rps_is_an_error(crash_stop):
    _res, record = crash_stop
    bare = slice_record(record, 0, 50)
    bare = type(bare)(name="bare.csv", time=bare.time, rudder_angle=bare.rudder_angle,
                      heading=bare.heading, channels={k: v for k, v in bare.channels.items()
                                                      if k != "propeller_rps"})
    with pytest.raises(ParameterError, match="bare.csv: finding propeller reversals needs "
                                             "column\\(s\\) propeller_rps"):
        find_reversals(bare)


def test_slice_and_rule_text(crash_stop):
    _res, record = crash_stop
    part = slice_record(record, 10, 30)
    assert part.time[0] == record.time[10] and len(part.time) == 20
    assert part.channels["x"][0] == record.channels["x"][10]
    assert "n[k-1] > 0 and n[k] <= 0" in REVERSAL_RULE


def test_the_measured_wind_uses_the_ships_own_wind_model(crash_stop):
    """esso-osaka-3m has Fujiwara's windage data: the replay's default loads are Fujiwara's;
    a ship without them keeps Blendermann's."""
    from seahelm.analysis.replay.simulate import _default_wind_loads

    assert _default_wind_loads(get_ship(SHIP)) == "fujiwara"
    assert _default_wind_loads(get_ship("kvlcc2-l7")) == "blendermann"
    from seahelm.analysis.replay.simulate import replay

    _res, record = crash_stop
    got = replay(slice_record(record, 0, 100), SHIP, kind="none", wind="measured")
    assert got.wind["load_model"] == "fujiwara"
