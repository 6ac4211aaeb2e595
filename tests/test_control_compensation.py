"""Compensating rudder angle, controllability monitor, course setter and the closed loop of
Lvov (2014), eq. (12)-(14), Fig. 1."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.control import compensation as cp
from seahelm.control.pid import PID_HEADING, PIDHeadingParams, pid_gains_from_nomoto
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.registry import get_controller
from seahelm.simulation.engine import simulate

RHO = 1025.0
HULL = dict(length=150.0, draft=8.0, block_coefficient=0.7, rudder_area=20.0,
            rudder_aspect_ratio=1.5, windage_area=1200.0, underwater_area=1200.0)


def c_hull(alpha_deg):
    """(0.23 sin α + 1.09 sin²α)/(2.1 δ − 7 T/L)², δ = 0.7, T = 8, L = 150, by hand."""
    s = math.sin(math.radians(alpha_deg))
    return (0.23 * s + 1.09 * s * s) / (2.1 * 0.7 - 7 * 8 / 150) ** 2


def test_lateral_resistance_centre_eq13():
    assert float(cp.lateral_resistance_centre(7.0, 7.0)) == pytest.approx(0.0, abs=1e-15)
    # T_f/T_a = 2/3: (1 + 4/3)/(3·5/3) − 0.5 = 7/15 − 1/2 = −1/30 (trim by the stern: aft)
    assert float(cp.lateral_resistance_centre(6.0, 9.0)) == pytest.approx(-1.0 / 30.0, rel=1e-12)
    assert float(cp.lateral_resistance_centre(9.0, 6.0)) > 0
    with pytest.raises(ParameterError, match=r"`draft_aft` must be > 0 \[m\]"):
        cp.lateral_resistance_centre(6.0, 0.0)


def test_hull_drift_coefficient_and_drift_angle():
    assert float(cp.hull_drift_coefficient(math.radians(5), 0.7, 8.0, 150.0)) == pytest.approx(
        c_hull(5.0), rel=1e-12)
    assert c_hull(5.0) == pytest.approx(0.023552, rel=1e-4)
    assert float(cp.hull_drift_coefficient(-math.radians(5), 0.7, 8.0, 150.0)) == pytest.approx(
        -c_hull(5.0), rel=1e-12)
    force = c_hull(4.0) * RHO * 1200.0 * 8.0**2
    alpha = cp.drift_angle([force, -force, 0.0], speed=8.0, underwater_area=1200.0,
                           block_coefficient=0.7, draft=8.0, length=150.0)
    np.testing.assert_allclose(alpha, np.radians([4.0, -4.0, 0.0]), rtol=1e-10, atol=1e-15)


def test_wind_compensation_eq12_hand_computed():
    l_lr = -1.0 / 30.0
    factor = (1 + 2 / 1.5) / (20.0 * RHO)
    wind = (0.25 + 5 / 150 - 60 / 360) * 0.37 * math.sin(math.radians(60)) * 1.225 * 1200 * 400 / 64
    hull = (0.5 + l_lr - 3 / 180) * c_hull(3.0) * RHO * 1200
    hand = factor * (wind + hull)
    got = cp.wind_compensation(wind_speed=20.0, wind_angle=math.radians(60), drift=math.radians(3),
                               speed=8.0, sail_centre=5.0, resistance_centre=l_lr, **HULL)
    assert float(got) == pytest.approx(hand, rel=1e-12)
    # odd in the angles (mirror image for wind from port)
    mirror = cp.wind_compensation(wind_speed=20.0, wind_angle=-math.radians(60),
                                  drift=-math.radians(3), speed=8.0, sail_centre=5.0,
                                  resistance_centre=l_lr, **HULL)
    assert float(mirror) == pytest.approx(-hand, rel=1e-12)


def test_wave_term_and_eq14():
    # (1 + 2/λ_p)/(S_p ρ) · M_w/(V² L)
    hand = (1 + 2 / 1.5) / (20.0 * RHO) * 1.0e7 / (64.0 * 150.0)
    got = cp.wave_compensation(1.0e7, speed=8.0, length=150.0, rudder_area=20.0,
                               rudder_aspect_ratio=1.5)
    assert float(got) == pytest.approx(hand, rel=1e-12)
    wind_kw = dict(wind_speed=20.0, wind_angle=math.radians(60), drift=math.radians(3),
                   speed=8.0, **HULL)
    total = cp.compensating_rudder_angle(wave_moment=1.0e7, **wind_kw)
    assert float(total) == pytest.approx(float(cp.wind_compensation(**wind_kw)) + hand, rel=1e-12)


def test_delta_k_zero_without_wind_and_waves():
    dk = cp.compensating_rudder_angle(wind_speed=0.0, wind_angle=0.9, drift=0.0, speed=8.0,
                                      wave_moment=0.0, **HULL)
    assert float(dk) == 0.0
    ship = cp.ShipParticulars(length=150.0, beam=20.0, draft=8.0, block_coefficient=0.7, speed=8.0)
    s = cp.compensation_summary(ship, wind_speed=0.0, wind_angle=0.4, wave_height=0.0,
                                wave_angle=0.4)
    assert s.delta_k == 0.0 and s.sway == 0.0 and s.yaw == 0.0 and s.wind_moment == 0.0


def test_summary_matches_pieces():
    ship = cp.ShipParticulars(length=150.0, beam=20.0, draft=8.0, block_coefficient=0.7,
                              speed=7.0, draft_fore=7.0, draft_aft=9.0)
    s = cp.compensation_summary(ship, wind_speed=15.0, wind_angle=math.radians(60),
                                wave_height=6.75, wave_angle=math.radians(60))
    assert s.wave_length == pytest.approx(1.55 * (0.65 * 0.8 * 15) ** 2)
    assert s.resistance_centre == pytest.approx((1 + 2 * 7 / 9) / (3 * (1 + 7 / 9)) - 0.5)
    assert s.delta_k == pytest.approx(s.delta_k_wind + s.delta_k_wave)
    assert s.delta_k_wave > 0 and s.yaw > 0  # bow seas from starboard: paper-positive


def test_monitor_synthetic():
    dt = 0.5
    t = np.arange(0, 600, dt)
    wiggle = np.radians(10.0) * np.sin(2 * np.pi * t / 40.0)
    dk = np.radians([[20.0], [30.0]])
    rep = cp.controllability_monitor(dk + wiggle, dk, dt=dt, window=60.0)
    assert rep.activity.shape == (2, t.size)
    assert np.degrees(rep.activity[:, -1]) == pytest.approx([10.0, 10.0], abs=0.05)
    assert rep.lost.tolist() == [False, True]  # 20 + 10 < 35 < 30 + 10
    assert np.isnan(rep.first_time[0]) and rep.first_time[1] > 0
    late = cp.controllability_monitor(dk + wiggle, dk, dt=dt, window=60.0, start=599.0)
    assert late.first_time[1] >= 599.0
    with pytest.raises(ParameterError, match="time axis"):
        cp.controllability_monitor(0.1, 0.0, dt=0.1)


def test_great_circle_course_and_course_to_steer():
    r = math.radians
    assert float(cp.initial_great_circle_course(0, 0, 0, r(10))) == pytest.approx(r(90))
    assert float(cp.initial_great_circle_course(0, 0, r(10), 0)) == pytest.approx(0.0)
    assert float(cp.initial_great_circle_course(r(10), 0, 0, 0)) == pytest.approx(r(180))
    # φ1 = 0, φ2 = 45°, Δλ = 90°: tan C = cos 45°/sin 45° = 1
    assert float(cp.initial_great_circle_course(0, 0, r(45), r(90))) == pytest.approx(r(45))
    assert float(cp.course_to_steer(r(10), r(2), r(1))) == pytest.approx(r(13))
    assert float(cp.course_to_steer(r(359), r(2))) == pytest.approx(r(1))
    with pytest.raises(ParameterError, match="lat_arrival"):
        cp.initial_great_circle_course(0, 0, 2.0, 0)


def test_heading_metrics_synthetic():
    dt = 0.1
    t = np.arange(0, 60 + dt / 2, dt)
    e = np.full_like(t, math.radians(0.5))
    rud = np.radians(5.0) * np.sin(2 * np.pi * t / 10.0)
    m = cp.heading_metrics(e, rud, dt=dt)
    assert float(m["mean_abs_error"]) == pytest.approx(math.radians(0.5))
    assert float(m["iae"]) == pytest.approx(math.radians(0.5) * 60.0)
    # the rudder first moves up; it turns at 2.5, 7.5, …, 57.5 s: 12 reversals in one minute
    assert float(m["reversals_per_min"]) == pytest.approx(12.0)
    assert float(m["settling_time"]) == 0.0


# --------------------------------------------------------------------------------------
# closed loop of Fig. 1 on the Voitkunsky Mariner
# --------------------------------------------------------------------------------------
GAINS = pid_gains_from_nomoto(0.185, 107.3, 0.05, 0.8)


def run_case(case, *, t_final=600.0, method="model"):
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):  # Mariner δ = 0.542
        sc = cp.wind_wave_scenario(case, t_final=t_final, delta_k_method=method)
    info = sc.pop("info")
    ctrl = [cp.CompensatedPIDParams(kp=GAINS.kp, ki=GAINS.ki, kd=GAINS.kd, wind_gain=g,
                                    wave_gain=g, feedforward_time_constant=15.0) for g in (0.0, 1.0)]
    res = simulate(controller_params=ctrl, **sc)
    assert res.ok.all()
    return sc, info, res


def test_controller_is_registered_and_zero_gain_is_pid():
    assert get_controller("compensated-pid") is cp.COMPENSATED_PID
    case = cp.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    sc, info, res = run_case(case, t_final=200.0)
    pid = simulate(sc["model"], sc["params"], sc["x0"], t_final=200.0, dt=sc["dt"],
                   controller=PID_HEADING, actuator=sc["actuator"], controller_dt=1.0,
                   controller_params=PIDHeadingParams(kp=GAINS.kp, ki=GAINS.ki, kd=GAINS.kd),
                   reference=sc["reference"][:, :1], disturbance=sc["disturbance"])
    np.testing.assert_allclose(res["heading"][0], pid["heading"][0], rtol=0, atol=1e-12)


def test_compensation_beats_pid_in_steady_wind_and_waves():
    case = cp.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    sc, info, res = run_case(case)
    e = sc["reference"][:, 0] - res["heading"]
    m = cp.heading_metrics(e, res["rudder_angle"], dt=sc["dt"], delta_k=info["steady_rudder"],
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
    case = cp.WindWaveCase("storm", 15.0, math.radians(120), 6.75, math.radians(120),
                           irregular=True)
    sc, info, res = run_case(case)
    assert abs(info["delta_k"]) > math.radians(20)
    dk = res["reference_delta_k_wind"] + res["reference_delta_k_wave"]
    rep = cp.controllability_monitor(res["rudder_angle"], dk, dt=sc["dt"], start=case.onset + 120)
    assert rep.lost.all()
    assert np.all(rep.first_time >= case.onset + 120)


def test_scenario_validation():
    case = cp.WindWaveCase("calm")
    with pytest.raises(ValueError, match="unknown delta_k_method 'x'; valid: model, paper"):
        cp.wind_wave_scenario(case, delta_k_method="x")


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
    case = cp.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):
        sc = cp.wind_wave_scenario(case, t_final=100.0)
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
    case = cp.WindWaveCase("wind+waves", 15.0, math.radians(60), 6.75, math.radians(60))
    sc, info, res = run_case(case, method="paper")
    assert np.sign(info["delta_k"]) != np.sign(info["steady_rudder"])
    e = sc["reference"][:, 0] - res["heading"]
    m = cp.heading_metrics(e, res["rudder_angle"], dt=sc["dt"], delta_k=info["steady_rudder"],
                           start=case.onset)
    pid, paper = 0, 1
    assert m["mean_abs_error"][paper] > m["mean_abs_error"][pid]
