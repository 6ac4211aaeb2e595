"""The autopilot design workflow as a library call (issue 47 item 4:
:mod:`seahelm.analysis.steering.autopilot_tuning`, what ``seahelm autopilot tune`` did inside the
CLI):
the cross-track loop's poles against the characteristic polynomial worked by hand, the
scenario's duration rule, the scenario written as TOML by tomlkit and read back by the
scenario loader, the design equal to the control building blocks', errors naming the
argument."""

from __future__ import annotations

import math
import tomllib
from types import SimpleNamespace

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.steering.autopilot_tuning import (
    cross_track_loop_poles,
    poles_text,
    scenario_duration,
    scenario_toml,
    settling_time,
    tune_autopilot,
)
from seahelm.errors import ParameterError


def test_cross_track_poles_are_the_roots_of_the_hand_worked_polynomial():
    """east' = U ψ, ψ' = r, r' = −a r + b δ, ξ' = east (the integral), under
    δ = −(k_i ξ + k_y y + k_ψ ψ + k_r r): s⁴ + (a + b k_r) s³ + b k_ψ s² + b k_y U s + b k_i U."""
    U, a, b = 5.0, 0.2, 0.05
    gains = dict(k_integral=0.001, k_cross_track=0.05, k_heading=2.0, k_yaw_rate=20.0,
                 k_sway=0.0)
    A = np.array([[0.0, U, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -a]])
    B = np.array([[0.0], [0.0], [b]])
    linear = SimpleNamespace(A=A, B=B, state_labels=("east", "heading", "yaw_rate"),
                             input_labels=("rudder_command",))
    got = np.sort_complex(cross_track_loop_poles(linear, gains))
    want = np.sort_complex(np.roots([1.0, a + b * gains["k_yaw_rate"], b * gains["k_heading"],
                                     b * gains["k_cross_track"] * U,
                                     b * gains["k_integral"] * U]))
    np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("poles, duration, settle", [
    ([-0.01, -1.0], 500.0, 1000.0),         # 5 τ = 500 s
    ([-0.1 + 0.2j, -0.1 - 0.2j], 300.0, 100.0),  # at least 300 s
    ([0.01, -0.0], 300.0, 300.0),           # nothing stable
    ([-0.0067], 800.0, 10 / 0.0067),        # the Mariner PID's slowest pole: 746 s -> 800 s
])
def test_the_scenario_duration_rule(poles, duration, settle):
    assert scenario_duration(np.array(poles)) == duration
    assert settling_time(np.array(poles)) == pytest.approx(settle, rel=1e-12)


def test_poles_text_sorted_and_short():
    assert poles_text([-0.5 + 0.1j, -1.0, -0.5 - 0.1j]) == ["-1", "-0.5-0.1j", "-0.5+0.1j"]


def test_scenario_toml_reads_back_as_the_mapping():
    doc = {"title": 'a "quoted" \\ title', "vessel": {"ship": "../ships/a b.toml",
                                                      "initial": {"surge_speed": 1.179}},
           "controller": {"model": "pid-heading", "dt": 0.5,
                          "params": {"kp": 0.1234567890123456789, "max_command_deg": 35.0}},
           "guidance": {"waypoints": [[0.0, 0.0], [707.4, 0.0]]}}
    text = scenario_toml(doc, "first line\nsecond: K = 1")
    assert text.startswith("# first line\n# second: K = 1\n")
    assert tomllib.loads(text) == doc


@pytest.fixture(scope="module")
def mariner():
    from seahelm.ships import get_ship

    return get_ship("mariner-nonlinear")


def test_pid_design_is_the_pole_placement_of_the_ship_nomoto(mariner):
    from seahelm.analysis.equilibria.linearisation import linearize
    from seahelm.analysis.steering.indices import steering_indices
    from seahelm.control.autopilot_design import pid_pole_placement

    tuning = tune_autopilot(mariner, design="pid", bandwidth=0.05, damping=0.8)
    nomoto = steering_indices(linearize(mariner, actuator=False)).nomoto
    servo = mariner.servo
    direct = pid_pole_placement(nomoto.gain, nomoto.time_constant, bandwidth=0.05, damping=0.8,
                                max_command=float(servo.max_angle),
                                max_rate=float(servo.max_rate))
    assert tuning.controller == "pid-heading"  # (no propeller: no -rps)
    assert tuning.gains == dict(direct.params.as_dict())
    np.testing.assert_array_equal(np.sort_complex(tuning.result.poles),
                                  np.sort_complex(direct.poles))
    assert all(p.real < 0 for p in tuning.poles)
    payload = tuning.as_dict()
    assert payload["nomoto"]["K_per_s"] == nomoto.gain and payload["bandwidth"] == 0.05


def test_the_scenario_runs_the_design(mariner, tmp_path):
    from seahelm.scenario import parse_scenario, run_scenario

    tuning = tune_autopilot(mariner, design="lq")
    doc = tuning.scenario(heading_step=10.0)
    assert doc["controller"]["params"]["max_command_deg"] == pytest.approx(
        math.degrees(tuning.gains["max_command"]), rel=1e-15)
    assert doc["simulation"]["t_final"] == scenario_duration(tuning.poles)
    text = scenario_toml(doc, tuning.comment())
    assert tomllib.loads(text) == doc
    result = run_scenario(parse_scenario(text))
    heading = np.degrees(np.asarray(result["heading"])[0, -1])
    assert heading == pytest.approx(10.0, abs=0.05)


@pytest.mark.parametrize("kwargs, field", [
    ({"design": "lqr"}, "design"),
    ({"bandwidth": -1.0}, "bandwidth"),
    ({"damping": math.nan}, "damping"),
    ({"dt": 0.0}, "dt"),
    ({"design": "pid", "max_cross_track": 5.0}, "max_cross_track"),
    ({"design": "lq", "offset": 5.0}, "offset"),
    ({"integral_time": -3.0}, "integral_time"),
    ({"dt": 1000.0}, "dt"),
])
def test_bad_arguments_are_named(mariner, kwargs, field):
    with pytest.raises(ParameterError) as info:
        tune_autopilot(mariner, **kwargs)
    assert info.value.field == field


def test_a_bad_heading_step_is_named(mariner):
    tuning = tune_autopilot(mariner, design="pid")
    with pytest.raises(ParameterError, match="course change") as info:
        tuning.scenario(heading_step=0.0)
    assert info.value.field == "heading_step"


def test_the_command_is_the_library_call(mariner, tmp_path):
    """`seahelm autopilot tune --json` prints the library's result; --out writes its scenario."""
    import json

    from seahelm.cli.main import app

    out = tmp_path / "pid.toml"
    res = CliRunner().invoke(app, ["autopilot", "tune", "mariner-nonlinear", "--heading-step",
                                   "20", "--out", str(out), "--json"])
    assert res.exit_code == 0, res.output
    payload = json.loads(res.stdout)
    tuning = tune_autopilot(mariner)
    want = tuning.as_dict()
    assert payload["gains"] == want["gains"] and payload["nomoto"] == want["nomoto"]
    assert payload["poles_with_ship_and_steering_gear"] == want[
        "poles_with_ship_and_steering_gear"]
    assert tomllib.loads(out.read_text()) == tuning.scenario(ship="mariner-nonlinear",
                                                             heading_step=20.0)
