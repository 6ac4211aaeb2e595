"""Course-unstable Nomoto ships (T1 < 0, K < 0; Fossen 2021, §7.1): the parameters admit them,
``seahelm ship estimate --model nomoto2`` writes them, flagged (issue 45, item 4)."""

from __future__ import annotations

import math

import pytest
from typer.testing import CliRunner

from seahelm.analysis.equilibria.linearisation import linearize
from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.ships import read_ship
from seahelm.vessels.nomoto import Nomoto1Params, Nomoto2Params

runner = CliRunner()
# the particulars of MSS's SIMclarke83.m (L 100 m, B 20 m, T 10 m, C_b 0.8, x_G -3 m) and of
# the KVLCC2 at full scale (L 320 m, B 58 m, T 20.8 m, C_b 0.8098, 15.5 kn)
SIMCLARKE83 = ["--length", "100", "--beam", "20", "--draft", "10", "--cb", "0.8", "--x-g", "-3",
               "--speed", "5"]
KVLCC2 = ["--length", "320", "--beam", "58", "--draft", "20.8", "--cb", "0.8098",
          "--speed", "7.97"]


@pytest.mark.parametrize("particulars", [SIMCLARKE83, KVLCC2], ids=["simclarke83", "kvlcc2"])
@pytest.mark.parametrize("order", ["nomoto2", "nomoto1"])
def test_estimate_writes_a_course_unstable_ship_flagged(tmp_path, particulars, order):
    path = tmp_path / "ship.toml"
    res = runner.invoke(app, ["ship", "estimate", *particulars, "--model", order, "--name", "x",
                              "-o", str(path)])
    assert res.exit_code == 0, res.output
    assert "course-unstable" in res.stdout
    ship = read_ship(path)
    time = ship.params.t1 if order == "nomoto2" else ship.params.time_constant
    assert time < 0 and ship.params.gain < 0 and ship.params.course_unstable
    assert any(v.startswith("course-unstable") for v in ship.validity)
    assert "course-unstable" in ship.description


def test_estimate_to_stdout_notes_it_on_stderr():
    res = runner.invoke(app, ["ship", "estimate", *SIMCLARKE83, "--model", "nomoto2"])
    assert res.exit_code == 0, res.output
    assert 'validity = [' in res.stdout and "course-unstable: T1 = " in res.stdout
    assert "note: course-unstable" in res.stderr


def test_a_course_unstable_nomoto_ship_has_the_positive_pole_minus_one_over_t1():
    p = Nomoto2Params(gain=-0.056, t1=-83.3, t2=7.77, t3=14.5, speed=5.0, length=100.0)
    lin = linearize(p, actuator=False)
    poles = sorted(lin.select(states=("yaw_rate", "yaw_aux")).poles.real)
    assert poles[-1] == pytest.approx(1 / 83.3, rel=1e-9)
    assert poles[0] == pytest.approx(-1 / 7.77, rel=1e-9)


@pytest.mark.parametrize("kwargs, field", [
    ({"gain": -0.05, "t1": 80.0}, "gain"),          # K < 0 with a stable T1: a sign error
    ({"gain": 0.05, "t1": -80.0}, "gain"),
    ({"gain": 0.05, "t1": 0.0}, "t1"),
    ({"gain": 0.0, "t1": 80.0}, "gain"),
    ({"gain": -0.05, "t1": -80.0, "norrbin_n3": 10.0}, "norrbin_n3"),
])
def test_nomoto2_sign_rules(kwargs, field):
    with pytest.raises(ParameterError, match=field) as info:
        Nomoto2Params(**{"t2": 7.0, "t3": 14.0, "speed": 5.0, **kwargs})
    assert info.value.field == field


def test_nomoto1_sign_rules():
    assert Nomoto1Params(gain=-0.2, time_constant=-100.0, speed=5.0).course_unstable
    assert not Nomoto1Params(gain=0.2, time_constant=100.0, speed=5.0).course_unstable
    with pytest.raises(ParameterError, match="gain"):
        Nomoto1Params(gain=0.2, time_constant=-100.0, speed=5.0)
    with pytest.raises(ParameterError, match="time_constant"):
        Nomoto1Params(gain=0.2, time_constant=0.0, speed=5.0)
    assert not math.isnan(Nomoto2Params(gain=0.1, t1=50.0, t2=5.0, t3=8.0, speed=5.0).t1)
