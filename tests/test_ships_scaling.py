"""Froude scaling of ships (seahelm.ships.scaling, Ship.scaled, `seahelm ship scale`)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.maneuvers import turning_circle
from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.parameters import Params, param
from seahelm.ships import CATALOG, Ship, get_ship, read_ship
from seahelm.ships.scaling import FROUDE_RULE, froude_exponents, froude_factor, scale_params
from seahelm.vessels.cpp_ship import CPPShipParams

runner = CliRunner()
LAMBDA = 320.0 / 7.0


@pytest.mark.parametrize("unit, exponents, factor", [
    ("m", (0, 1, 0), LAMBDA), ("m²", (0, 2, 0), LAMBDA ** 2), ("m³", (0, 3, 0), LAMBDA ** 3),
    ("s", (0, 0, 1), LAMBDA ** 0.5), ("m/s", (0, 1, -1), LAMBDA ** 0.5),
    ("1/s", (0, 0, -1), LAMBDA ** -0.5), ("rad/s", (0, 0, -1), LAMBDA ** -0.5),
    ("1/s²", (0, 0, -2), 1 / LAMBDA), ("s²", (0, 0, 2), LAMBDA), ("kg", (1, 0, 0), LAMBDA ** 3),
    ("N", (1, 1, -2), LAMBDA ** 3), ("kN", (1, 1, -2), LAMBDA ** 3),
    ("kg·m²", (1, 2, 0), LAMBDA ** 5), ("kg/m³", (1, -3, 0), 1.0),
    ("kN·s/m", (1, 0, -1), LAMBDA ** 2.5), ("kN·s²/m²", (1, -1, 0), LAMBDA ** 2),
    ("rad", (0, 0, 0), 1.0), ("-", (0, 0, 0), 1.0), ("1", (0, 0, 0), 1.0),
    ("m^2", (0, 2, 0), LAMBDA ** 2),
])
def test_the_rule_by_unit(unit, exponents, factor):
    assert froude_exponents(unit) == exponents
    assert froude_factor(unit, LAMBDA) == pytest.approx(factor, rel=1e-14)


def test_density_changes_masses_and_forces_only():
    assert froude_factor("N", 2.0, 1.025) == pytest.approx(8 * 1.025, rel=1e-15)
    assert froude_factor("kg/m³", 2.0, 1.025) == pytest.approx(1.025, rel=1e-15)
    assert froude_factor("m/s", 4.0, 1.025) == 2.0


@pytest.mark.parametrize("unit", ["", "furlong", "m/s/s", "kg·ft", "deg/s"])
def test_an_unknown_unit_names_the_field(unit):
    with pytest.raises(ParameterError, match=r"`params.x` has the unit .* which the Froude "
                       "scaling rule does not know") as err:
        froude_exponents(unit, field="params.x")
    assert (err.value.field, err.value.unit) == ("params.x", unit)


# the catalog's numbers as printed (Yasukawa & Yoshimura 2015): decimals of the L7 value and
# of the full-scale value, and the power of lambda of the unit
PRINTED = {"breadth": (2, 0, 1), "draft": (2, 1, 1), "displacement": (2, -2, 3),
           "x_G": (2, 1, 1), "propeller_diameter": (3, 2, 1), "rudder_span": (3, 1, 1),
           "rudder_area": (4, 1, 2), "approach_speed": (3, 6, 0.5)}


def test_kvlcc2_l7_scaled_to_320_m_is_the_full_scale_ship():
    l7, full = get_ship("kvlcc2-l7"), get_ship("kvlcc2-full")
    ship = l7.scaled(320.0, rho=1025.0)
    assert ship.params.length == 320.0 and ship.params.rho == 1025.0
    for info in full.params.info():
        got, want = getattr(ship.params, info.name), getattr(full.params, info.name)
        if info.name in PRINTED:
            d7, dfull, power = PRINTED[info.name]
            tol = 0.5 * 10.0 ** -d7 * LAMBDA ** power + 0.5 * 10.0 ** -dfull
            assert abs(got - want) <= tol, (info.name, got, want, tol)
        else:  # length, rho, and every non-dimensional coefficient: equal
            assert got == want, info.name
    gear, full_gear = ship.servo, full.servo
    assert gear.max_angle == full_gear.max_angle
    # 15.8 deg/s / sqrt(lambda) = 2.337 deg/s, printed 2.34
    assert math.degrees(gear.max_rate) == pytest.approx(math.degrees(full_gear.max_rate),
                                                        abs=0.05 / LAMBDA ** 0.5 + 0.005)
    # the catalog scales the lag by sqrt(45.7), the rounded scale
    assert gear.time_constant == pytest.approx(full_gear.time_constant, rel=2e-4)
    assert ship.test_speed == ship.params.approach_speed
    for name in ("length", "beam", "draft", "length_overall", "frontal_area", "lateral_area",
                 "windage_centre"):
        assert getattr(ship.particulars, name) == pytest.approx(
            getattr(full.particulars, name), rel=1e-14), name
    assert ship.provenance.startswith(
        "Froude-scaled from 'kvlcc2-l7' by lambda = 45.71428571 (L = 7 m -> 320 m); water "
        "density 1000 -> 1025 kg/m^3")
    assert FROUDE_RULE in ship.provenance and "Original: KVLCC2 tanker" in ship.provenance
    assert "Froude-scaled" in ship.steering_gear.provenance and ship.name == "kvlcc2-l7-L320"


def test_froude_similarity_of_the_turning_circle():
    """Same density: the scaled ship's track is the model's x lambda, in time x sqrt(lambda)."""
    l7 = get_ship("kvlcc2-l7")
    big = l7.scaled(320.0)
    dt, t_final = 0.05, 120.0
    rudders = np.radians([35.0, 10.0])
    a = turning_circle(l7, rudders, sides=(1, -1), dt=dt, t_final=t_final).metrics
    root = math.sqrt(LAMBDA)
    b = turning_circle(big, rudders, sides=(1, -1), dt=dt * root, t_final=t_final * root).metrics
    for name in ("advance", "transfer", "tactical_diameter", "distance_10", "steady_radius"):
        assert np.isfinite(a[name].values).all(), name
        np.testing.assert_allclose(b[name].values / 320.0, a[name].values / 7.0, rtol=1e-9,
                                   err_msg=name)
    for name in ("time_90", "time_180", "time_10"):
        np.testing.assert_allclose(b[name].values / root, a[name].values, rtol=1e-9)
    np.testing.assert_allclose(b["propeller_rps"].values * root, a["propeller_rps"].values,
                               rtol=1e-9)
    np.testing.assert_allclose(b["speed_loss"].values, a["speed_loss"].values, atol=1e-10)


def test_nomoto_k_and_t_scale_and_kt_stays():
    ship = get_ship("mariner-nomoto2")
    lam = 120.0 / ship.length
    small = ship.scaled(120.0)
    p, q = ship.params, small.params
    assert q.gain == pytest.approx(p.gain / math.sqrt(lam), rel=1e-14)
    for name in ("t1", "t2", "t3"):
        assert getattr(q, name) == pytest.approx(getattr(p, name) * math.sqrt(lam), rel=1e-14)
    assert q.gain * q.t1 == pytest.approx(p.gain * p.t1, rel=1e-14)
    assert q.gain * q.length / q.speed == pytest.approx(p.gain * p.length / p.speed, rel=1e-14)
    assert q.norrbin_n3 == pytest.approx(p.norrbin_n3 * lam, rel=1e-14)


@pytest.mark.parametrize("name", [n for n in CATALOG])
def test_there_and_back_is_the_identity(name):
    ship = get_ship(name)
    if math.isnan(ship.length):  # a 6-DOF craft's file gives no length: refused by name
        with pytest.raises(ParameterError, match="has no length to scale from"):
            ship.scaled(4.0)
        return
    back = ship.scaled(ship.length * 3.7).scaled(ship.length)
    for info in ship.params.info():
        np.testing.assert_allclose(getattr(back.params, info.name),
                                   getattr(ship.params, info.name), rtol=1e-14, err_msg=name)
    if ship.steering_gear is not None:
        for f in ship.servo.field_names():
            assert getattr(back.servo, f) == pytest.approx(getattr(ship.servo, f), rel=1e-14)
    if ship.particulars is not None:
        assert back.particulars.beam == pytest.approx(ship.particulars.beam, rel=1e-14)


@pytest.mark.parametrize("length", [0.0, -7.0, math.nan, math.inf, True, "320"])
def test_bad_length(length):
    with pytest.raises(ParameterError, match=r"`length` must be a finite number > 0 \[m\]") \
            as err:
        get_ship("kvlcc2-l7").scaled(length)
    assert (err.value.field, err.value.unit) == ("length", "m")


def test_bad_density_and_ships_that_cannot_scale():
    with pytest.raises(ParameterError, match=r"`rho` must be a finite number > 0 \[kg/m³\]"):
        get_ship("kvlcc2-l7").scaled(320.0, rho=-1.0)
    with pytest.raises(ParameterError, match=r"`rho`: model 'nomoto1' has no water density "):
        get_ship("mariner-nomoto1").scaled(120.0, rho=1025.0)
    cpp = Ship(name="cpp", model="cpp-ship-calm", params=CPPShipParams())
    with pytest.raises(ParameterError, match=r"`length`: ship 'cpp' has no length to scale "
                       r"from \(no parameter `length` in CPPShipParams and no particulars\)"):
        cpp.scaled(100.0)

    @dataclasses.dataclass(frozen=True, kw_only=True)
    class Odd(Params):
        length: float = param(10.0, unit="m")
        reach: float = param(1.0, unit="furlong")

    with pytest.raises(ParameterError, match=r"`params.reach` has the unit 'furlong'"):
        scale_params(Odd(), 2.0)


def test_cli_scale_prints_and_writes(tmp_path):
    res = runner.invoke(app, ["ship", "scale", "kvlcc2-l7", "--length", "320", "--rho", "1025"])
    assert res.exit_code == 0, res.stderr
    assert 'name = "kvlcc2-l7-L320"' in res.stdout and "rho = 1025.0" in res.stdout
    out = tmp_path / "big.toml"
    res = runner.invoke(app, ["ship", "scale", "mariner-nomoto1", "--length", "120", "--out",
                              str(out), "--name", "my-nomoto"])
    assert res.exit_code == 0, res.stderr
    assert "wrote" in res.stdout and "lambda = 0.745666" in res.stdout
    assert read_ship(out) == get_ship("mariner-nomoto1").scaled(120.0, name="my-nomoto")


@pytest.mark.parametrize("value, shown", [("-5", "-5.0"), ("0", "0.0"), ("nan", "nan")])
def test_cli_bad_length_exits_2_with_one_line(value, shown):
    res = runner.invoke(app, ["ship", "scale", "kvlcc2-l7", "--length", value])
    assert res.exit_code == 2
    lines = res.stderr.strip().splitlines()
    assert lines == [f"error: `--length` must be a finite number > 0 [m], got {shown}"]
