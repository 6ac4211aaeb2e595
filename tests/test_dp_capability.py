"""DP capability level 1: the static balance and the capability against hand computations,
the environment's load models, and ``seahelm dp capability``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.dp.level1 import (
    BEAUFORT_WIND,
    DpVessel,
    environment_loads,
    level1_capability,
    sea_from_wind,
)
from seahelm.cli.main import app
from seahelm.control.dp_allocation import ConstrainedAllocation, ThrusterLayout
from seahelm.environment.blendermann import blendermann_wind_loads

# a surge thruster at the origin and two tunnel thrusters 20 m fore and aft: B is square,
# B = [[1, 0, 0], [0, 1, 1], [0, 20, -20]], so the thrusts are B⁻¹ τ, written out below
SURGE_MAX, TUNNEL_MAX = 1e5, 5e4
LAYOUT = ThrusterLayout(("main", "bow", "stern"), (0.0, 20.0, -20.0), (0.0, 0.0, 0.0),
                        (0.0, math.pi / 2, math.pi / 2), (False, False, False),
                        (SURGE_MAX, TUNNEL_MAX, TUNNEL_MAX))
VESSEL = DpVessel("square", LAYOUT, 60.0, 14.0, 5.0, frontal_area=200.0, lateral_area=600.0,
                  lateral_centre=3.0, wind_type="offshore-supply-vessel")


def _hand_thrusts(tau):
    tx, ty, tn = tau
    return np.array([tx, 0.5 * (ty + tn / 20.0), 0.5 * (ty - tn / 20.0)])


def _wind(u, theta):
    w = blendermann_wind_loads(u, theta, "offshore-supply-vessel", frontal_area=200.0,
                               lateral_area=600.0, length_overall=60.0, lateral_centre=3.0)
    return np.array([float(w[0]), float(w[1]), float(w[2])])


def test_static_balance_matches_the_hand_computation():
    alloc = ConstrainedAllocation(LAYOUT)
    theta = np.radians([0.0, 30.0, 90.0, 135.0, 200.0, 300.0])
    u = 6.0
    tau = -environment_loads(VESSEL, u, theta, 0.0, waves=False)
    res = alloc.capacity(tau)
    for k, th in enumerate(theta):
        hand = _hand_thrusts(-_wind(u, th))
        np.testing.assert_allclose(res.thrust[k], hand, rtol=1e-9, atol=1e-9 * SURGE_MAX)
    assert np.all(np.abs(res.unmet) < 1e-6)


def test_capability_matches_the_hand_computation():
    """Wind only (loads ∝ U²): U* = min_i √(T_max,i / |f_i(U = 1)|), capped at Beaufort 11."""
    res = level1_capability(VESSEL, headings=36, failures="none", current_speed=0.0,
                            waves=False)
    tmax = np.array([SURGE_MAX, TUNNEL_MAX, TUNNEL_MAX])
    for k, th in enumerate(res.directions):
        f1 = np.abs(_hand_thrusts(-_wind(1.0, th)))
        hand = min(math.sqrt(t / f) if f > 0 else math.inf for t, f in zip(tmax, f1))
        hand = min(hand, BEAUFORT_WIND[-1])
        assert res.wind_speed[0, k] == pytest.approx(hand, rel=1e-9), math.degrees(th)


def test_failures_of_a_layout_without_redundancy_hold_nothing():
    res = level1_capability(VESSEL, headings=8, current_speed=0.0, waves=False)
    assert res.cases == ("intact", "without main", "without bow", "without stern")
    assert np.all(res.wind_speed[0] > 5.0)
    np.testing.assert_array_equal(res.wind_speed[1:], 0.0)   # rank 2: not even calm


def test_wave_drift_and_current_load_models():
    # PM sea: Hs = 0.21 U19.5²/g, U19.5 = U·1.95^(1/7); wall bound ρ g Hs²/16 per metre
    u = 15.0
    u195 = u * 1.95 ** (1 / 7)
    hs = 0.21 * u195**2 / 9.80665
    assert sea_from_wind(u)[0] == pytest.approx(hs, rel=1e-12)
    head = environment_loads(VESSEL, u, 0.0, 0.0) - environment_loads(VESSEL, u, 0.0, 0.0,
                                                                       waves=False)
    assert head[0] == pytest.approx(-1025.0 * 9.80665 * hs**2 / 16 * 14.0, rel=1e-12)
    assert head[1] == pytest.approx(0.0, abs=1e-6) and head[2] == 0.0
    # beam current from starboard: Y = −½ ρ v² L T C_y
    beam = environment_loads(VESSEL, 0.0, math.pi / 2, 1.2, waves=False)
    assert beam[1] == pytest.approx(-0.5 * 1025.0 * 1.2**2 * 60.0 * 5.0 * 1.0, rel=1e-12)


runner = CliRunner()


def test_cli_capability_writes_json_netcdf_and_plot(tmp_path):
    import xarray as xr

    nc, js, png = tmp_path / "cap.nc", tmp_path / "cap.json", tmp_path / "cap.png"
    res = runner.invoke(app, ["dp", "capability", "shushlyapin2017-dp", "--headings", "12", "--out",
                              str(nc), "--json-out", str(js), "--plot", str(png), "--json"])
    assert res.exit_code == 0, res.stderr
    out = json.loads(res.stdout)
    assert out["cases"] == ["intact", "without azimuth-port", "without azimuth-starboard"]
    assert len(out["directions_deg"]) == 12
    assert min(out["wind_speed_m_s"]["intact"]) > 0
    assert any("Beaufort" in a for a in out["assumptions"])
    assert json.loads(js.read_text())["wind_speed_m_s"] == out["wind_speed_m_s"]
    with xr.open_dataset(nc) as ds:
        np.testing.assert_allclose(ds["wind_speed"].sel(case="intact").values,
                                   out["wind_speed_m_s"]["intact"])
    assert png.stat().st_size > 0


@pytest.mark.parametrize("args, words", [
    (["otter"], ["SHIP", "otter"]),
    (["shushlyapin2017-dp", "--headings", "0"], ["--headings", "[-]", "0"]),
    (["shushlyapin2017-dp", "--failures", "bow"], ["--failures", "bow"]),
    (["shushlyapin2017-dp", "--current", "5"], ["--current", "m/s", "5"]),
])
def test_cli_bad_input_exits_2_with_one_line(args, words):
    res = runner.invoke(app, ["dp", "capability", *args])
    assert res.exit_code == 2
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    for w in words:
        assert w in lines[0]


def test_supply_vessel_layout_and_capability():
    """Fossen's supply vessel: six thrusters; head-on wind alone is held by the two main
    propellers up to U* = √(2 · 31.2 · 160² / |X(U = 1)|) (no side force or moment head-on);
    losing a thruster never holds more wind, in any direction."""
    from seahelm.analysis.dp.level1 import dp_vessel

    ship = dp_vessel("supply")
    assert ship.layout.count == 6
    assert ship.layout.max_thrust[0] == pytest.approx(200e3) and \
        ship.layout.max_thrust[4] == pytest.approx(798.72e3)
    res = level1_capability(ship, headings=4, failures="none", current_speed=0.0,
                            waves=False)
    x1 = blendermann_wind_loads(1.0, 0.0, "offshore-supply-vessel", frontal_area=300.0,
                                lateral_area=900.0, length_overall=76.2)[0]
    hand = min(math.sqrt(2 * 31.2 * 160.0**2 / abs(float(x1))), BEAUFORT_WIND[-1])
    assert res.wind_speed[0, 0] == pytest.approx(hand, rel=1e-9)
    full = level1_capability(ship, headings=36)
    assert np.all(full.wind_speed[1:] <= full.wind_speed[0] + 1e-9)
    assert np.all(full.wind_speed[0] > 10.0)
