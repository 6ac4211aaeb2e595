"""LQ-integral cross-track control: the design against python-control's lqr on the linearised
Mariner (poles = eig(A − BK)), the sampled closed loop on a linear (Nomoto) ship against
python-control's discrete-time simulation, convergence on the nonlinear Mariner beside ILOS,
the law, batches, scenarios, `seahelm autopilot tune --design lq-cross-track`, bad input."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from seahelm.control.lq_cross_track import (LQ_CROSS_TRACK, LQCrossTrackParams,
                                            LQCrossTrackRpsParams, lq_cross_track)
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate

K, T, U = 0.185, 107.3, 7.7175  # the Mariner's first-order Nomoto model
NORTH = [[0.0, 0.0], [100000.0, 0.0]]  # a route due north: y_e = east


def sorted_roots(r):
    return np.array(sorted(np.asarray(r, complex), key=lambda z: (z.real, z.imag)))


@pytest.fixture(scope="module")
def mariner_route_block(mariner_linear):
    lin = mariner_linear
    assert lin.x0[lin.state_labels.index("heading")] == 0.0  # the route is due north
    return lin.select(states=["sway_speed", "yaw_rate", "heading", "east"],
                      inputs=["rudder_angle"])


def test_the_design_is_python_controls_lqr_of_the_linearised_ship(mariner_route_block):
    """The augmented model assembled from the linearised Mariner's own sway, yaw, heading and
    east rows (east = y_e on a route due north) plus ∫east: python-control's lqr gives the
    design's gains (1e-8) and its closed-loop eigenvalues are the design's poles (1e-9)."""
    ct = pytest.importorskip("control")
    idx = {s: i for i, s in enumerate(mariner_route_block.state_labels)}
    speed = mariner_route_block.A[idx["east"], idx["heading"]]
    block = mariner_route_block.select(states=["sway_speed", "yaw_rate"])
    d = lq_cross_track(block.A, block.B[:, 0], block.state_labels, speed, max_cross_track=50.0,
                       max_heading_error=math.radians(20.0), max_rudder=math.radians(40.0))
    assert d.states == ("cross_track_error_integral", "cross_track_error", "heading_error",
                        "sway_speed", "yaw_rate")
    order = [idx[s] for s in ("east", "heading", "sway_speed", "yaw_rate")]
    A = np.zeros((5, 5))
    A[0, 1] = 1.0
    A[1:, 1:] = mariner_route_block.A[np.ix_(order, order)]
    B = np.concatenate([[0.0], mariner_route_block.B[order, 0]])[:, None]
    Q = np.diag([1 / 5000.0 ** 2, 1 / 50.0 ** 2, 1 / math.radians(20.0) ** 2, 0.0, 0.0])
    R = np.array([[1 / math.radians(40.0) ** 2]])
    k_ref, _, poles_ref = ct.lqr(A, B, Q, R)
    np.testing.assert_allclose(d.gain, np.asarray(k_ref)[0], rtol=1e-8)
    np.testing.assert_allclose(sorted_roots(d.poles), sorted_roots(poles_ref), rtol=1e-9)
    np.testing.assert_allclose(sorted_roots(d.poles),
                               sorted_roots(np.linalg.eigvals(A - B @ d.gain[None, :])),
                               rtol=1e-9)
    assert np.all(d.poles.real < 0)
    assert d.gains == {"k_integral": d.gain[0], "k_cross_track": d.gain[1],
                       "k_heading": d.gain[2], "k_sway": d.gain[3], "k_yaw_rate": d.gain[4]}


def _nomoto_design(**kw):
    return lq_cross_track([[-1 / T]], [K / T], ("yaw_rate",), U, max_cross_track=20.0,
                          max_heading_error=math.radians(20.0), **kw)


def _nomoto_run(params, east0, *, t_final=600.0):
    from seahelm.actuators.servo import RUDDER_SERVO, ServoParams
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    x0 = np.zeros((len(east0), NOMOTO1.n_states))
    x0[:, NOMOTO1.state_labels.index("east")] = east0
    return simulate(NOMOTO1, Nomoto1Params(gain=K, time_constant=T, speed=U), x0,
                    t_final=t_final, dt=0.1, controller=LQ_CROSS_TRACK,
                    controller_params=params, controller_dt=0.5, actuator=RUDDER_SERVO,
                    actuator_params=ServoParams(max_angle=math.radians(40.0),
                                                max_rate=math.radians(5.0), time_constant=1.0),
                    record_every=5)


def test_on_a_linear_ship_the_offset_decays_as_the_sampled_linear_loop_predicts():
    """The first-order Nomoto ship with its rudder servo, 1 cm to starboard of a route due north:
    the cross-track error at every controller sample equals python-control's simulation of the
    sampled closed loop (the ship sampled by zero-order hold, ∫y_e by Euler at the controller
    period, as the controller integrates) to 1e-8 of the offset (measured 7e-10; the
    kinematics' sin ψ ≈ ψ adds 2.4e-6 of a 1 m offset, growing with its square)."""
    ct = pytest.importorskip("control")
    d = _nomoto_design()
    td, y0 = 0.5, 0.01
    res = _nomoto_run(d.params(NORTH), [y0])
    assert res.ok.all()
    ship = ct.ss([[0, U, 0, 0], [0, 0, 1, 0], [0, 0, -1 / T, K / T], [0, 0, 0, -1.0]],
                 [[0], [0], [0], [1.0]], np.eye(4), np.zeros((4, 1)))  # y_e, ψ, r, δ
    shipd = ship.sample(td, method="zoh")
    g = d.gains
    k = np.array([g["k_cross_track"], g["k_heading"], g["k_yaw_rate"], 0.0])
    acl = np.zeros((5, 5))  # (∫y_e, y_e, ψ, r, δ)
    acl[0, 0], acl[0, 1] = 1.0, td
    acl[1:, 1:] = shipd.A - shipd.B @ k[None, :]
    acl[1:, 0] = -shipd.B[:, 0] * g["k_integral"]
    loop = ct.ss(acl, np.zeros((5, 1)), [[0, 1, 0, 0, 0]], [[0]], td)
    t = np.arange(0.0, 600.0 + td / 2, td)
    predicted = ct.initial_response(loop, T=t, X0=[0, y0, 0, 0, 0]).outputs
    got = res["cross_track_error"][0]
    assert got.shape == predicted.shape
    assert np.abs(predicted).max() == pytest.approx(y0) and abs(predicted[-1]) < 0.02 * y0
    # (the record at t_final repeats the last sample's: the controller does not step there)
    np.testing.assert_allclose(got[:-1], predicted[:-1], rtol=0, atol=1e-8 * y0)
    assert np.all(np.abs(np.linalg.eigvals(acl)) < 1)


def test_the_law_is_the_state_feedback_and_approaches_at_the_largest_angle():
    """One step of the compiled law: δ_c = −(k_i ∫y_e + k_y y_e + k_ψ ψ̃ + k_r r + k_v v) near the
    line (by numpy); far from it the heading reference is π_k − χ_max."""
    from seahelm.parameters import as_records

    p = LQCrossTrackParams(route_north=(0.0, 1000.0) + (0.0,) * 30,
                           route_east=(0.0, 1000.0) + (0.0,) * 30, k_integral=1e-4,
                           k_cross_track=0.02, k_heading=5.0, k_yaw_rate=30.0, k_sway=0.1,
                           max_approach_angle=math.radians(30.0))
    rec = as_records(p.to_array()[None, :], LQCrossTrackParams)[0]
    pi_k = math.pi / 4
    for y_e, psi_off, r, v in ((3.0, 0.02, 0.001, 0.05), (-2.0, -0.05, -0.002, 0.0)):
        north = 100.0 * math.cos(pi_k) - y_e * math.sin(pi_k)
        east = 100.0 * math.sin(pi_k) + y_e * math.cos(pi_k)
        y = np.array([north, east, pi_k + psi_off, r, v])
        cs = np.zeros(3)
        cs[1] = 50.0  # ∫y_e [m·s]
        cmd = np.zeros(5)
        LQ_CROSS_TRACK.step(0.0, 0.5, np.zeros(1), y, np.zeros(0), rec, cs, cmd)
        expected = -(1e-4 * 50.0 + 0.02 * y_e + 5.0 * psi_off + 30.0 * r + 0.1 * v)
        assert cmd[0] == pytest.approx(expected, rel=1e-12)
        assert cmd[2] == pytest.approx(y_e, abs=1e-9) and cmd[3] == pytest.approx(100.0)
        assert cs[1] == pytest.approx(50.0 + 0.5 * y_e)  # integrated
    y = np.array([-1000.0, 1000.0, pi_k, 0.0, 0.0])  # 1414 m to starboard, abreast of p_0
    cmd = np.zeros(5)
    LQ_CROSS_TRACK.step(0.0, 0.5, np.zeros(1), y, np.zeros(0), rec, np.zeros(3), cmd)
    assert cmd[1] == pytest.approx(pi_k - math.radians(30.0))  # far to starboard: χ_max


def test_a_batch_of_designs_equals_the_runs_one_by_one():
    routes = [NORTH, [[0.0, 0.0], [70000.0, 70000.0]]]
    params = [_nomoto_design().params(routes[0]),
              lq_cross_track([[-1 / T]], [K / T], ("yaw_rate",), U, max_cross_track=60.0,
                             integral=False).params(routes[1])]
    assert params[1].k_integral == 0.0
    batch = _nomoto_run(params, [30.0, -20.0], t_final=300.0)
    for i, p in enumerate(params):
        one = _nomoto_run(p, [[30.0, -20.0][i]], t_final=300.0)
        np.testing.assert_allclose(batch.state[i], one.state[0], rtol=0, atol=1e-12)


@pytest.mark.slow
def test_on_the_nonlinear_mariner_it_converges_and_beside_ilos():
    """The Mariner (nonlinear, its steering gear: 40°, 5°/s) on a straight route, 200 m off it in
    calm water, and on it in a 1 m/s cross current: the LQ-integral design (50 m, 20°) ends on
    the line in both; in the current it holds it closer than ILOS (Δ = 800 m, κ = U/4, PID
    kp 3, kd 60) — the figures of docs/guide/control-design.rst."""
    from seahelm.analysis.equilibria.equilibrium import approach_state
    from seahelm.analysis.equilibria.linearisation import linearize
    from seahelm.control.guided import guided
    from seahelm.control.path_following import ILOS, route_params
    from seahelm.control.pid import PID_HEADING
    from seahelm.ships import get_ship

    ship = get_ship("mariner-nonlinear")
    lin = linearize(ship, actuator=False)
    block = lin.select(states=["sway_speed", "yaw_rate"], inputs=["rudder_angle"])
    speed = lin.A[lin.state_labels.index("east"), lin.state_labels.index("heading")]
    d = lq_cross_track(block.A, block.B[:, 0], block.state_labels, speed, max_cross_track=50.0,
                       max_heading_error=math.radians(20.0), max_rudder=ship.max_rudder)
    start = approach_state(ship, trim=True)
    x0 = np.tile(start.state, (2, 1))
    x0[0, ship.model.state_labels.index("east")] = 200.0
    current = np.zeros((2, 1, 1))
    current[1] = 1.0
    ilos = guided(ILOS, PID_HEADING)
    cases = {"lq": (LQ_CROSS_TRACK, d.params(NORTH)),
             "ilos": (ilos, ilos.params_type(**route_params(
                 NORTH, law=ILOS, lookahead=800.0, kappa=ship.test_speed / 4).as_dict(),
                 kp=3.0, ki=0.0, kd=60.0))}
    out = {}
    for name, (ctl, params) in cases.items():
        res = simulate(ship=ship, x0=x0, actuator_x0=[start.inputs["rudder_angle"]],
                       t_final=2000.0, dt=0.1, controller=ctl, controller_params=params,
                       controller_dt=0.5, record_every=5, disturbance={"current_east": current})
        assert res.ok.all()
        out[name] = res["cross_track_error"]
    lq, il = out["lq"], out["ilos"]
    assert np.abs(lq[:, -1]).max() < 0.05
    rms = {k: np.sqrt(np.mean(v ** 2, axis=1)) for k, v in out.items()}
    assert rms["lq"][1] < 0.5 * rms["ilos"][1]  # the current: 7.8 m vs 37.9 m
    assert np.abs(lq[1]).max() < 0.5 * np.abs(il[1]).max()  # 36 m vs 94 m
    assert lq[0].min() > -40.0  # the overshoot from 200 m (25 m; ILOS 33 m)


SCENARIO = """
title = "Mariner: LQ cross-track"
[vessel]
ship = "mariner-nonlinear"
[vessel.initial]
east = 50.0
[controller]
model = "lq-cross-track"
[controller.params]
k_integral = 0.0001
k_cross_track = 0.0187
k_heading = 5.38
k_yaw_rate = 34.4
k_sway = 0.044
max_command_deg = 40.0
[guidance]
waypoints = [[0.0, 0.0], [30000.0, 0.0]]
acceptance_radius = 500.0
[simulation]
t_final = 1000.0
dt = 0.1
record_every = 5
"""


def test_runs_from_a_scenario_with_a_route_and_refuses_a_guidance_law():
    from seahelm.analysis.maneuvers import summarize
    from seahelm.scenario import ScenarioError, parse_scenario, run_scenario

    res = run_scenario(parse_scenario(SCENARIO))
    assert res.ok.all()
    row = summarize(res)[0]
    assert row["max_abs_cross_track_error_m"] == pytest.approx(50.0, abs=0.5)
    assert abs(row["final_cross_track_error_m"]) < 0.5
    for key, line in (("law", 'law = "ilos"'), ("lookahead", "lookahead = 800.0"),
                      ("kappa", "kappa = 2.0")):
        with pytest.raises(ScenarioError, match=rf"guidance\.{key}.*follows the route itself"):
            parse_scenario(SCENARIO.replace("acceptance_radius = 500.0",
                                            f"acceptance_radius = 500.0\n{line}"))


def test_cli_tune_cross_track_writes_a_route_scenario_that_settles(tmp_path):
    """`seahelm autopilot tune --design lq-cross-track`: the gains are lq_cross_track's at the
    reported weights, and the scenario (the ship L off a straight route) ends on the line;
    KVLCC2 L7 gets the ``-rps`` variant holding the self-propulsion rps."""
    from typer.testing import CliRunner

    from seahelm.analysis.equilibria.linearisation import linearize
    from seahelm.cli.main import app

    runner = CliRunner()
    for ship, controller in (("mariner-nonlinear", "lq-cross-track"),
                             ("kvlcc2-l7", "lq-cross-track-rps")):
        out = tmp_path / f"{ship}.toml"
        res = runner.invoke(app, ["autopilot", "tune", ship, "--design", "lq-cross-track",
                                  "--out", str(out), "--json"])
        assert res.exit_code == 0, res.output
        payload = json.loads(res.stdout)
        assert payload["controller"] == controller
        lin = linearize(ship, actuator=False)
        block = lin.select(states=["sway_speed", "yaw_rate"], inputs=["rudder_angle"])
        d = lq_cross_track(block.A, block.B[:, 0], block.state_labels, payload["surge_speed"],
                           max_cross_track=payload["max_cross_track_m"],
                           max_heading_error=math.radians(payload["max_heading_error_deg"]),
                           max_rudder=payload["gains"]["max_command"])
        for key, value in d.gains.items():
            assert payload["gains"][key] == pytest.approx(value, rel=1e-12)
        assert ("propeller_rps" in payload["gains"]) == (controller.endswith("-rps"))
        assert all(p[0] < 0 for p in payload["poles_with_ship_and_steering_gear"])
        run = runner.invoke(app, ["run", str(out), "--json"])
        assert run.exit_code == 0, run.output
        summary = json.loads(run.stdout)
        assert summary["max_abs_cross_track_error_m"] >= lin.length  # it started L off
        assert abs(summary["final_cross_track_error_m"]) < 0.01 * lin.length


@pytest.mark.parametrize("args, kwargs, field, match", [
    ((("heading",),), {}, "states", "must be yaw_rate"),
    ((("yaw_rate",),), {"speed": 0.0}, "speed", "must be > 0"),
    ((("yaw_rate",),), {"max_cross_track": -1.0}, "max_cross_track", "must be > 0"),
    ((("yaw_rate",),), {"b": [0.0]}, "A", "uncontrollable"),
    ((("yaw_rate", "sway_speed"),), {}, "A", r"A must be \(2, 2\)"),
])
def test_bad_design_input(args, kwargs, field, match):
    values = {"A": [[-1 / T]], "b": [K / T], "speed": U, "max_cross_track": 20.0, **kwargs}
    with pytest.raises(ParameterError, match=match) as exc:
        lq_cross_track(values.pop("A"), values.pop("b"), *args, values.pop("speed"), **values)
    assert exc.value.field == field


def test_bad_parameters():
    with pytest.raises(ParameterError, match="k_heading"):
        LQCrossTrackParams(k_heading=0.0)
    with pytest.raises(ParameterError, match="max_approach_angle"):
        LQCrossTrackParams(max_approach_angle=2.0)
    with pytest.raises(ParameterError, match="propeller_rps"):
        _nomoto_design().params(NORTH, propeller_rps=-1.0)
    assert isinstance(_nomoto_design().params(NORTH, propeller_rps=1.0), LQCrossTrackRpsParams)
    with pytest.raises(ParameterError, match="acceptance_radius"):
        _nomoto_design().params([[0.0, 0.0], [50.0, 0.0]], acceptance_radius=100.0)
