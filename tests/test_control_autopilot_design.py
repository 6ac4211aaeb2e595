"""Autopilot design: PID pole placement (exact poles), margins, the rudder-rate bound, LQ-integral
(against python-control's lqr), the controllers in the engine, `seahelm autopilot tune`."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.control.autopilot_design import (AutopilotDesignWarning, heading_loop_poles,
                                              loop_margins, lq_heading,
                                              natural_frequency_from_bandwidth,
                                              nomoto_pid_poles, pid_pole_placement)
from seahelm.control.lq_heading import LQ_HEADING, LQHeadingParams
from seahelm.control.pid import PID_HEADING, pid_gains_from_nomoto
from seahelm.errors import ParameterError
from seahelm.registry import get_controller

K, T = 0.185, 107.3


def sorted_roots(r):
    return np.array(sorted(np.asarray(r, complex), key=lambda z: (z.real, z.imag)))


@pytest.mark.parametrize("wn, zeta, ti", [(0.05, 0.8, None), (0.1, 1.0, 60.0),
                                          (0.03, 0.6, 500.0)])
def test_pole_placement_puts_the_poles_where_designed(wn, zeta, ti):
    d = pid_pole_placement(K, T, natural_frequency=wn, damping=zeta, integral_time=ti)
    Ti = 10 / wn if ti is None else ti
    want = np.roots(np.polymul([1, 2 * zeta * wn, wn * wn], [1, 1 / Ti]))
    np.testing.assert_allclose(sorted_roots(nomoto_pid_poles(K, T, d.params)),
                               sorted_roots(want), rtol=0, atol=1e-9)
    np.testing.assert_allclose(sorted_roots(d.poles), sorted_roots(want), rtol=0, atol=1e-9)
    assert d.integral_time == pytest.approx(Ti)


def test_without_integral_action_it_is_fossens_algorithm_15_1():
    d = pid_pole_placement(K, T, natural_frequency=0.05, damping=0.8, integral_time=math.inf)
    ref = pid_gains_from_nomoto(K, T, 0.05, 0.8)
    assert (d.params.kp, d.params.kd, d.params.ki) == pytest.approx((ref.kp, ref.kd, 0.0))


def test_bandwidth_to_natural_frequency():
    assert natural_frequency_from_bandwidth(0.1, 1 / math.sqrt(2)) == pytest.approx(0.1)
    d = pid_pole_placement(K, T, bandwidth=0.05, damping=0.8)
    assert d.natural_frequency == pytest.approx(natural_frequency_from_bandwidth(0.05, 0.8))
    assert d.bandwidth == pytest.approx(0.05)


@pytest.mark.parametrize("kwargs, match", [
    ({"bandwidth": 0.2, "max_rate": math.radians(5)}, r"`bandwidth` must be <= 0.1429"),
    ({"bandwidth": 0.001}, "negative derivative gain"),
    ({"bandwidth": -1.0}, "`bandwidth` must be > 0"),
    ({}, "give one of"),
    ({"bandwidth": 0.05, "damping": 0.0}, "`damping` must be > 0"),
])
def test_pid_design_validation(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        pid_pole_placement(K, T, **kwargs)


@pytest.mark.parametrize("gain, tc", [(0.0, 100.0), (0.1, -50.0)])
def test_a_pair_the_rudder_does_not_steer_is_refused(gain, tc):
    with pytest.raises(ParameterError, match="does not steer|differ in sign"):
        pid_pole_placement(gain, tc, bandwidth=0.05)


def test_a_design_below_the_minimum_margins_warns():
    with pytest.warns(AutopilotDesignWarning, match=r"gain margin .* phase margin"):
        d = pid_pole_placement(K, T, bandwidth=0.12, damping=0.4, servo_time_constant=15.0)
    assert d.gain_margin < 2 or math.degrees(d.phase_margin) < 30


def test_loop_margins_against_python_control():
    ct = pytest.importorskip("control")
    for k in (0.5, 1.2):
        L = ct.tf([k], [1, 2, 1, 0])  # k/(s(s+1)²): −180° at ω = 1, |L| = k/2
        gm, pm, wc = loop_margins(lambda w: np.asarray(L(1j * w)))
        gm_ref, pm_ref, _, wc_ref = ct.margin(L)
        assert gm == pytest.approx(2 / k, rel=1e-6) and gm == pytest.approx(gm_ref, rel=1e-6)
        assert math.degrees(pm) == pytest.approx(pm_ref, abs=1e-3)
        assert wc == pytest.approx(wc_ref, rel=1e-4)


@pytest.fixture(scope="module")
def mariner_block(mariner_linear):
    return mariner_linear.select(states=["sway_speed", "yaw_rate"], inputs=["rudder_angle"])


def test_lq_gains_equal_python_controls_lqr(mariner_block):
    ct = pytest.importorskip("control")
    A, b = mariner_block.A, mariner_block.B[:, 0]
    d = lq_heading(A, b, mariner_block.state_labels, max_heading_error=0.1)
    Aa = np.zeros((4, 4))
    Aa[0, 1] = 1.0
    Aa[1, 3] = 1.0
    Aa[2:, 2:] = A
    ba = np.concatenate([[0, 0], b])[:, None]
    Kref, _, poles = ct.lqr(Aa, ba, np.diag([1 / 10.0 ** 2, 1 / 0.1 ** 2, 0, 0]),
                            [[1 / math.radians(35) ** 2]])
    np.testing.assert_allclose(d.gain, np.asarray(Kref)[0], rtol=1e-8)
    np.testing.assert_allclose(sorted_roots(d.poles), sorted_roots(poles), rtol=1e-8)
    assert np.all(d.poles.real < 0)
    p = d.params
    assert (p.k_integral, p.k_heading, p.k_sway, p.k_yaw_rate) == pytest.approx(tuple(d.gain))
    # the same law through heading_loop_poles (ψ, r, v read from the block plus ψ, ∫ψ)
    A3 = np.zeros((3, 3))
    A3[:2, :2] = A
    A3[2, 1] = 1.0
    b3 = np.concatenate([b, [0.0]])
    poles3 = heading_loop_poles(A3, b3, [0, 0, 1], [0, 1, 0], c_sway=[1, 0, 0],
                                k_heading=p.k_heading, k_yaw_rate=p.k_yaw_rate,
                                k_integral=p.k_integral, k_sway=p.k_sway)
    np.testing.assert_allclose(sorted_roots(poles3), sorted_roots(d.poles), rtol=1e-8)


def test_lq_refuses_an_uncontrollable_pair():
    with pytest.raises(ParameterError, match="uncontrollable"):
        lq_heading(np.array([[-0.1]]), np.array([0.0]), ("yaw_rate",))
    with pytest.raises(ParameterError, match="yaw_rate"):
        lq_heading(np.array([[-0.1]]), np.array([1.0]), ("heading",))


def test_registered_and_run_batched_by_the_engine():
    """Both designs on the second-order Nomoto Mariner: a 10° course change, a batch of the two
    designs' gain sets equals the runs one by one."""
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2, Nomoto2Params

    assert get_controller("lq-heading") is LQ_HEADING
    p = Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7175, length=160.93)
    d = pid_pole_placement(0.185, 118 + 7.8 - 18.5, bandwidth=0.05, damping=0.8)
    lq = lq_heading(np.array([[-1 / 107.3]]), np.array([0.185 / 107.3]), ("yaw_rate",))
    ref = {"heading": math.radians(10.0)}
    runs = {}
    for ctl, params in ((PID_HEADING, d.params), (LQ_HEADING, lq.params)):
        res = simulate(NOMOTO2, p, NOMOTO2.initial_state(), t_final=1200.0, dt=0.1,
                       controller=ctl, controller_params=[params, params], reference=ref,
                       controller_dt=0.5)
        assert np.all(res.status == 0)
        assert res["heading"][0, -1] == pytest.approx(math.radians(10), abs=1e-4)
        one = simulate(NOMOTO2, p, NOMOTO2.initial_state(), t_final=1200.0, dt=0.1,
                       controller=ctl, controller_params=params, reference=ref,
                       controller_dt=0.5)
        np.testing.assert_allclose(res.state[1], one.state[0], rtol=0, atol=1e-12)
        runs[ctl.name] = res
    assert LQHeadingParams().k_sway == 0.0


# -- CLI ---------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def runner():
    return CliRunner()


def test_cli_tune_writes_a_scenario_that_seahelm_run_accepts(runner, tmp_path):
    from seahelm.cli.main import app

    out = tmp_path / "autopilot.toml"
    res = runner.invoke(app, ["autopilot", "tune", "mariner-nonlinear", "--bandwidth", "0.05",
                              "--damping", "0.8", "--out", str(out), "--json"])
    assert res.exit_code == 0, res.output
    payload = json.loads(res.stdout)
    assert payload["controller"] == "pid-heading" and payload["gains"]["kp"] > 0
    assert all(p[0] < 0 for p in payload["poles_with_ship_and_steering_gear"])
    assert "[controller]" in out.read_text()
    run = runner.invoke(app, ["run", str(out), "--json"])
    assert run.exit_code == 0, run.output
    summary = json.loads(run.stdout)
    assert summary["n_ok"] == 1
    assert summary["heading_deg"] == pytest.approx(10.0, abs=0.05)


def test_cli_tune_lq_prints_gains_and_poles(runner):
    from seahelm.cli.main import app

    res = runner.invoke(app, ["autopilot", "tune", "mariner-nonlinear", "--design", "lq"])
    assert res.exit_code == 0, res.output
    assert "k_sway" in res.stdout and "designed poles" in res.stdout


@pytest.mark.parametrize("args, match", [
    (["--bandwidth", "0.3"], "--bandwidth"),
    (["--bandwidth", "-1"], "--bandwidth"),
    (["--damping", "0"], "--damping"),
])
def test_cli_tune_bad_input_exits_2(runner, args, match):
    from seahelm.cli.main import app

    res = runner.invoke(app, ["autopilot", "tune", "mariner-nonlinear", *args])
    assert res.exit_code == 2, res.output
    assert match in res.output


def test_cli_tune_lq_for_a_ship_with_a_propeller(runner, tmp_path):
    """KVLCC2 L7 (MMG, propeller): linearised at the self-propelled straight run, the design is
    ``lq-heading-rps`` holding the self-propulsion rps; the scenario starts at the approach
    speed and `seahelm run` (with the ship's steering gear) settles the 10° course change."""
    from seahelm.analysis.equilibria.equilibrium import approach_state
    from seahelm.cli.main import app
    from seahelm.control.lq_heading import LQ_HEADING_RPS

    assert get_controller("lq-heading-rps") is LQ_HEADING_RPS
    out = tmp_path / "lq.toml"
    res = runner.invoke(app, ["autopilot", "tune", "kvlcc2-l7", "--design", "lq", "--out",
                              str(out), "--json"])
    assert res.exit_code == 0, res.output
    payload = json.loads(res.stdout)
    assert payload["controller"] == "lq-heading-rps"
    point = approach_state("kvlcc2-l7", trim=True)
    assert payload["gains"]["propeller_rps"] == pytest.approx(point.inputs["propeller_rps"],
                                                              rel=1e-9)
    assert payload["max_heading_error_deg"] == 5.0
    text = out.read_text()
    assert "[vessel.initial]" in text and "surge_speed = 1.179" in text
    run = runner.invoke(app, ["run", str(out), "--json"])
    assert run.exit_code == 0, run.output
    summary = json.loads(run.stdout)
    assert summary["n_ok"] == 1
    assert summary["heading_deg"] == pytest.approx(10.0, abs=0.05)
    assert summary["overshoot_deg"] < 1.0  # (0.60 deg with the ship's 15.8 deg/s gear)
