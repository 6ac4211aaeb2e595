"""The reproduction of Lvov (2014): ship data, the paper's chain, the two ways of computing δ_k
and the closed loop of Fig. 1 (seahelm.studies.lvov2014)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.maneuvers import course_keeping as ck
from seahelm.control import compensation as cp
from seahelm.control.pid import PID_HEADING, PIDHeadingParams, pid_gains_from_nomoto
from seahelm.errors import ValidityRangeWarning
from seahelm.registry import get_controller
from seahelm.simulation.engine import simulate
from seahelm.studies import lvov2014 as lv

HULL = dict(length=150.0, draft=8.0, block_coefficient=0.7, rudder_area=20.0,
            rudder_aspect_ratio=1.5, windage_area=1200.0, underwater_area=1200.0)


def test_delta_k_zero_without_wind_and_waves():
    dk = cp.compensating_rudder_angle(wind_speed=0.0, wind_angle=0.9, drift=0.0, speed=8.0,
                                      wave_moment=0.0, **HULL)
    assert float(dk) == 0.0
    ship = lv.ShipParticulars(length=150.0, beam=20.0, draft=8.0, block_coefficient=0.7, speed=8.0)
    s = lv.compensation_summary(ship, wind_speed=0.0, wind_angle=0.4, wave_height=0.0,
                                wave_angle=0.4)
    assert s.delta_k == 0.0 and s.sway == 0.0 and s.yaw == 0.0 and s.wind_moment == 0.0


def test_summary_matches_pieces():
    ship = lv.ShipParticulars(length=150.0, beam=20.0, draft=8.0, block_coefficient=0.7,
                              speed=7.0, draft_fore=7.0, draft_aft=9.0)
    s = lv.compensation_summary(ship, wind_speed=15.0, wind_angle=math.radians(60),
                                wave_height=6.75, wave_angle=math.radians(60))
    assert s.wave_length == pytest.approx(1.55 * (0.65 * 0.8 * 15) ** 2)
    assert s.resistance_centre == pytest.approx((1 + 2 * 7 / 9) / (3 * (1 + 7 / 9)) - 0.5)
    assert s.delta_k == pytest.approx(s.delta_k_wind + s.delta_k_wave)
    assert s.delta_k_wave > 0 and s.yaw > 0  # bow seas from starboard: paper-positive


# --------------------------------------------------------------------------------------
# closed loop of Fig. 1 on the Voitkunsky Mariner
# --------------------------------------------------------------------------------------
GAINS = pid_gains_from_nomoto(0.185, 107.3, 0.05, 0.8)


def run_case(case, *, t_final=600.0, method="model"):
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):  # Mariner δ = 0.542
        sc = lv.wind_wave_scenario(case, t_final=t_final, delta_k_method=method)
    info = sc.pop("info")
    ctrl = [cp.CompensatedPIDParams(kp=GAINS.kp, ki=GAINS.ki, kd=GAINS.kd, wind_gain=g,
                                    wave_gain=g, feedforward_time_constant=15.0) for g in (0.0, 1.0)]
    res = simulate(controller_params=ctrl, **sc)
    assert res.ok.all()
    return sc, info, res


def test_controller_is_registered_and_zero_gain_is_pid():
    assert get_controller("compensated-pid") is cp.COMPENSATED_PID
    case = lv.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    sc, info, res = run_case(case, t_final=200.0)
    pid = simulate(sc["model"], sc["params"], sc["x0"], t_final=200.0, dt=sc["dt"],
                   controller=PID_HEADING, actuator=sc["actuator"], controller_dt=1.0,
                   controller_params=PIDHeadingParams(kp=GAINS.kp, ki=GAINS.ki, kd=GAINS.kd),
                   reference=sc["reference"][:, :1], disturbance=sc["disturbance"])
    np.testing.assert_allclose(res["heading"][0], pid["heading"][0], rtol=0, atol=1e-12)


def test_compensation_beats_pid_in_steady_wind_and_waves():
    case = lv.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    sc, info, res = run_case(case)
    e = sc["reference"][:, 0] - res["heading"]
    m = ck.heading_metrics(e, res["rudder_angle"], dt=sc["dt"], delta_k=info["steady_rudder"],
                           start=case.onset)
    pid, comp = 0, 1
    assert m["mean_abs_error"][comp] < 0.5 * m["mean_abs_error"][pid]
    assert m["max_abs_error"][comp] < m["max_abs_error"][pid]
    assert m["mean_activity"][comp] < m["mean_activity"][pid]
    assert m["reversals_per_min"][comp] < m["reversals_per_min"][pid]
    # the feed-forward is the model's steady rudder: the PID has (almost) nothing left to do
    assert res["rudder_angle"][comp, -1] == pytest.approx(info["delta_k"], abs=math.radians(0.2))
    dk = res["reference_delta_k_wind"] + res["reference_delta_k_wave"]
    assert not cp.controllability_monitor(res["rudder_angle"], dk, dt=sc["dt"],
                                          start=case.onset + 120).lost.any()


def test_storm_triggers_loss_of_controllability():
    case = lv.WindWaveCase("storm", 15.0, math.radians(120), 6.75, math.radians(120),
                           irregular=True)
    sc, info, res = run_case(case)
    assert abs(info["delta_k"]) > math.radians(20)
    dk = res["reference_delta_k_wind"] + res["reference_delta_k_wave"]
    rep = cp.controllability_monitor(res["rudder_angle"], dk, dt=sc["dt"], start=case.onset + 120)
    assert rep.lost.all()
    assert np.all(rep.first_time >= case.onset + 120)


def test_scenario_validation():
    case = lv.WindWaveCase("calm")
    with pytest.raises(ValueError, match="unknown delta_k_method 'x'; valid: model, paper"):
        lv.wind_wave_scenario(case, delta_k_method="x")


def test_example_table_script_runs_the_hand_written_scenarios():
    import importlib.util
    from pathlib import Path

    examples = Path(__file__).resolve().parents[1] / "examples"
    spec = importlib.util.spec_from_file_location("compensation_table", examples / "compensation_table.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    rows = mod.run_case("windwaves", t_final=300.0)
    assert [r["controller"] for r in rows] == ["PID", "PID + δ_k", "PID + δ_k (12)/(14)"]
    assert rows[1]["mean"] < 0.2 * rows[0]["mean"]  # the model's δ_k helps
    assert rows[2]["mean"] > rows[0]["mean"]  # the printed formula's sign hurts
    # the scenario files describe the weather; the engine computes the loads (none written in)
    for key in mod.CASES:
        for kind in ("pid", "compensated"):
            text = (examples / f"compensation_{key}_{kind}.toml").read_text()
            assert "[environment.disturbance]" not in text and "Generated" not in text
            assert ("\n[environment.wind]\n" in text) == (key != "calm")


def _steady_rudder_by_root_finding(p, yaw_moment, sway_force):
    """Course keeping (ω = 0) of eq. (1) with the disturbance channels, solved independently:
    0 = −q31 β − s31 α + m_d,  0 = −q21 β − h2 β|β| − s21 α − f_d."""
    from scipy.optimize import brentq

    def residual(alpha):
        beta = (yaw_moment - p.s31 * alpha) / p.q31
        return -p.q21 * beta - p.h2 * beta * abs(beta) - p.s21 * alpha - sway_force

    return brentq(residual, -0.7, 0.7, xtol=1e-14)


def test_model_delta_k_is_the_steady_rudder_of_the_disturbed_ship():
    case = lv.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):
        sc = lv.wind_wave_scenario(case, t_final=100.0)
    info = sc["info"]
    labels = sc["model"].disturbance_labels
    last = sc["disturbance"].reshape(-1, len(labels))[-1]
    md, fd = last[labels.index("yaw_moment")], last[labels.index("sway_force")]
    expected = _steady_rudder_by_root_finding(sc["params"], md, fd)
    assert info["steady_rudder"] == pytest.approx(expected, rel=1e-9)
    assert info["delta_k"] == pytest.approx(expected, rel=1e-6)


def test_paper_delta_k_has_the_wrong_sign_for_the_mariner_and_hurts():
    """Erratum kept visible: eq. (12)/(14) as printed add the hull-drift moment with the wind
    moment's sign; for this ship they oppose, so the printed δ_k points the wrong way and
    feeding it forward makes course keeping worse than the PID alone."""
    case = lv.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    sc, info, res = run_case(case, method="paper")
    assert np.sign(info["delta_k"]) != np.sign(info["steady_rudder"])
    e = sc["reference"][:, 0] - res["heading"]
    m = ck.heading_metrics(e, res["rudder_angle"], dt=sc["dt"], delta_k=info["steady_rudder"],
                           start=case.onset)
    pid, paper = 0, 1
    assert m["mean_abs_error"][paper] > m["mean_abs_error"][pid]


def test_delta_k_methods_are_registry_objects():
    assert lv.get_delta_k_method("model") is lv.MODEL_BALANCE
    assert lv.get_delta_k_method("paper") is lv.PRINTED_EQ14
    assert lv.get_delta_k_method(lv.PRINTED_EQ14) is lv.PRINTED_EQ14
    assert sorted(lv.DELTA_K_METHODS) == ["model", "paper"]
    case = lv.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):
        by_name = lv.wind_wave_scenario(case, t_final=10.0, delta_k_method="paper")["info"]
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):
        by_object = lv.wind_wave_scenario(case, t_final=10.0,
                                          delta_k_method=lv.PRINTED_EQ14)["info"]
    assert by_object["delta_k"] == by_name["delta_k"]
    assert by_object["drift"] == by_name["drift"]
    summ = by_name["summary"]
    assert by_name["delta_k_wind"] == summ.delta_k_wind
    assert by_name["drift"] == summ.wind_drift + summ.wave_drift
