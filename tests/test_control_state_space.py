"""python-control systems as seahelm controllers: the closed loop in seahelm's batched engine
equals python-control's own closed-loop simulation (the plant sampled by zero-order hold, which
is exact for the held command), a batch of designs equals the runs one by one, the generated
controller keeps the component contract, and bad systems are refused naming the argument."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

ct = pytest.importorskip("control")

from seahelm.actuators.servo import DIRECT  # noqa: E402
from seahelm.control.state_space import (SAMPLING_METHODS, StateSpaceController,  # noqa: E402
                                         state_space_controller)
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.simulation.engine import simulate  # noqa: E402
from seahelm.vessels.nomoto import NOMOTO1, NOMOTO2, Nomoto1Params, Nomoto2Params  # noqa: E402

K, T, U = 0.185, 107.3, 7.7175  # the Mariner's first-order Nomoto model
T1, T2, T3 = 118.0, 7.8, 18.5
DT, DTC, TF = 0.1, 0.5, 300.0  # integration step, controller period, duration [s]


def nomoto1_plant():
    """ψ/δ = K/(s (T s + 1)) with outputs heading and yaw rate (states r, ψ)."""
    return ct.ss([[-1 / T, 0.0], [1.0, 0.0]], [[K / T], [0.0]], [[0.0, 1.0], [1.0, 0.0]],
                 [[0.0], [0.0]], inputs="rudder_angle", outputs=["heading", "yaw_rate"],
                 name="ship")


def nomoto2_plant():
    """r/δ = K (1 + T3 s)/((1 + T1 s)(1 + T2 s)), ψ = r/s."""
    r = ct.tf([K * T3, K], np.polymul([T1, 1.0], [T2, 1.0]))
    g = ct.ss(ct.tf([1.0], [1.0, 0.0]) * r)  # heading
    both = ct.ss(ct.append(g, ct.ss(r)))  # (δ, δ) -> (ψ, r): join the inputs
    both = both * ct.ss([], [], [], [[1.0], [1.0]])
    return ct.ss(both, inputs="rudder_angle", outputs=["heading", "yaw_rate"], name="ship")


def pid_discrete():
    """A PID with a filtered derivative, designed directly in discrete time (period DTC)."""
    pid = ct.tf([60.0, 3.0, 0.01], [1.0, 0.0]) * ct.tf([1.0], [4.0, 1.0])
    return ct.ss(pid.sample(DTC, method="tustin"), inputs="heading_error",
                 outputs="rudder_angle", name="pid")


def grid(t_end=TF, step=DTC):
    return np.arange(0.0, t_end + step / 2, step)


def samples(res, t):
    return np.rint(t / DT).astype(int)


def test_a_discrete_siso_controller_closes_the_loop_as_python_control_does():
    """A 10° course change of the linear first-order Nomoto ship: heading and rudder at every
    controller sample equal python-control's closed loop ``feedback(Gd C, 1)`` and
    ``feedback(C, Gd)`` (Gd the ship sampled by zero-order hold) to 1e-9 (RK4's error on
    the held command)."""
    ctl = state_space_controller(pid_discrete())
    assert isinstance(ctl, StateSpaceController) and ctl.sample_period == DTC
    assert ctl.reference_labels == ("heading",) and ctl.measurement_labels == ("heading",)
    ref = math.radians(10.0)
    p = Nomoto1Params(gain=K, time_constant=T, speed=U)
    res = simulate(NOMOTO1, p, NOMOTO1.initial_state(), t_final=TF, dt=DT, controller=ctl,
                   actuator=DIRECT, reference={"heading": ref})  # controller_dt: its period
    assert res.status[0] == 0
    gd = nomoto1_plant()[0, 0].sample(DTC)
    c = pid_discrete()
    t = grid()
    heading = ct.forced_response(ct.feedback(gd * c, 1), T=t, U=np.full(t.size, ref)).outputs
    rudder = ct.forced_response(ct.feedback(c, gd), T=t, U=np.full(t.size, ref)).outputs
    k = samples(res, t)
    assert np.abs(heading).max() > 0.1  # it turned
    np.testing.assert_allclose(res["heading"][0, k], heading, rtol=0, atol=1e-9)
    # (the command recorded at t_final is the one held over the last interval)
    np.testing.assert_allclose(res["rudder_angle"][0, k[:-1]], rudder[:-1], rtol=0, atol=1e-9)


@pytest.mark.parametrize("method", ["zoh", "tustin"])
def test_a_continuous_mimo_design_sampled_in_the_wrapper(method):
    """A continuous two-input controller (on the heading error and the yaw rate, with integral
    action) on the second-order Nomoto ship started 5° off course, sampled by the wrapper;
    the closed loop equals python-control's ``interconnect`` of the zero-order-hold ship and
    the controller sampled with the same method, by signal name, to 1e-9."""
    kp, ki, kd, tf = 1.5, 0.005, 40.0, 2.0  # ∫e, filtered r
    c = ct.ss([[0.0, 0.0], [0.0, -1 / tf]], [[1.0, 0.0], [0.0, 1 / tf]], [[ki, -kd]],
              [[kp, 0.0]], inputs=["heading_error", "yaw_rate"], outputs="rudder_angle",
              name="pd-i")
    ctl = state_space_controller(c, DTC, method=method)
    assert ctl.method == method and ctl.measurement_labels == ("heading", "yaw_rate")
    p = Nomoto2Params(gain=K, t1=T1, t2=T2, t3=T3, speed=U)
    x0 = NOMOTO2.initial_state()
    psi0 = math.radians(5.0)
    x0[NOMOTO2.state_labels.index("heading")] = psi0
    res = simulate(NOMOTO2, p, x0, t_final=TF, dt=DT, controller=ctl, actuator=DIRECT,
                   reference={"heading": 0.0})
    assert res.status[0] == 0
    ship = nomoto2_plant().sample(DTC)
    cd = c.sample(DTC, method=method)
    error = ct.summing_junction(inputs=["heading_reference", "-heading"],
                                outputs="heading_error", dt=DTC)
    loop = ct.interconnect([ship, cd, error], inputs="heading_reference",
                           outputs=["heading", "rudder_angle"])
    t = grid()
    # the ship at rest 5° off course: the eigenvector of its integrator (pole z = 1)
    w, v = np.linalg.eig(ship.A)
    x_ship = np.real(v[:, np.argmin(np.abs(w - 1.0))])
    x_ship *= psi0 / (ship.C[0] @ x_ship)
    resp = ct.forced_response(loop, T=t, U=np.zeros(t.size),
                              X0=np.concatenate([x_ship, np.zeros(cd.nstates)]))
    k = samples(res, t)
    np.testing.assert_allclose(res["heading"][0, k], resp.outputs[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(res["rudder_angle"][0, k[:-1]], resp.outputs[1][:-1], rtol=0,
                               atol=1e-9)
    assert abs(res["heading"][0, -1]) < 0.1 * psi0  # it came back


def test_the_sampled_matrices_are_scipys_zero_order_hold():
    from scipy.signal import cont2discrete

    c = ct.ss([[-0.2, 0.1], [0.0, -0.05]], [[1.0], [0.5]], [[0.3, -0.7]], [[2.0]],
              inputs="heading_error", outputs="rudder_command")
    ctl = state_space_controller(c, 0.5)
    a, b, cc, d, _ = cont2discrete((c.A, c.B, c.C, c.D), 0.5, method="zoh")
    p = ctl.params_type()
    np.testing.assert_allclose(np.reshape(p.a, (2, 2)), a, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(np.reshape(p.b, (2, 1)), b, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(p.c, cc.ravel(), rtol=1e-15)
    assert p.d == (2.0,) and ctl.sample_period == 0.5


def test_a_batch_of_designs_equals_the_runs_one_by_one_and_the_python_loop():
    c = pid_discrete()
    ctl = state_space_controller(c)
    designs = [ctl.params_for(c), ctl.params_for(_two_state_pid(1.5, 0.005, 30.0))]
    p = Nomoto1Params(gain=K, time_constant=T, speed=U)
    ref = {"heading": math.radians(10.0)}
    batch = simulate(NOMOTO1, p, NOMOTO1.initial_state(), t_final=TF, dt=DT, controller=ctl,
                     controller_params=designs, actuator=DIRECT, reference=ref)
    assert np.all(batch.status == 0)
    assert not np.allclose(batch["heading"][0], batch["heading"][1])
    for i, d in enumerate(designs):
        one = simulate(NOMOTO1, p, NOMOTO1.initial_state(), t_final=TF, dt=DT, controller=ctl,
                       controller_params=d, actuator=DIRECT, reference=ref)
        np.testing.assert_allclose(batch.state[i], one.state[0], rtol=0, atol=1e-12)
    python = simulate(NOMOTO1, p, NOMOTO1.initial_state(), t_final=20.0, dt=DT, controller=ctl,
                      controller_params=designs[1], actuator=DIRECT, reference=ref, jit=False)
    np.testing.assert_allclose(python.state[0], batch.state[1, :python.state.shape[1]],
                               rtol=0, atol=1e-12)


def _two_state_pid(kp, ki, kd):
    pid = ct.tf([kd, kp, ki], [1.0, 0.0]) * ct.tf([1.0], [4.0, 1.0])
    return ct.ss(pid.sample(DTC, method="tustin"), inputs="heading_error",
                 outputs="rudder_angle")


def test_a_static_gain_offsets_and_the_wrapped_heading_error():
    """u = u₀ + D (w − w₀), at any controller period; heading_error wrapped to [−π, π)."""
    gain = ct.ss([], [], [], [[2.0, -40.0]], inputs=["heading_error", "yaw_rate"],
                 outputs="rudder_angle")
    ctl = state_space_controller(gain, input_offset=[0.0, 0.001], output_offset=[0.01])
    assert ctl.sample_period is None and ctl.n_system_states == 0
    p = Nomoto1Params(gain=K, time_constant=T, speed=U)
    x0 = NOMOTO1.initial_state()
    x0[NOMOTO1.state_labels.index("heading")] = 3.0
    res = simulate(NOMOTO1, p, x0, t_final=1.0, dt=DT, controller=ctl, actuator=DIRECT,
                   reference={"heading": -3.0})
    wrapped = (-3.0 - 3.0) + 2 * math.pi
    assert res["rudder_angle"][0, 0] == pytest.approx(0.01 + 2.0 * wrapped - 40.0 * (-0.001),
                                                      rel=1e-14)


def test_the_generated_controller_keeps_the_component_contract():
    from test_components_contract import (BARE_INDEX, POSITIONAL_PARAM, _code,
                                          _seahelm_dispatchers_called)

    for sys in (pid_discrete(), ct.ss([], [], [], [[1.0]], inputs="heading_error",
                                      outputs="rudder_command")):
        ctl = state_space_controller(sys)
        seen = {}
        for f in (ctl.init, ctl.step):
            _seahelm_dispatchers_called(f, seen)
        assert "seahelm.control.state_space.state_space_inputs" in seen
        for key, f in seen.items():
            code = _code(f)
            assert not POSITIONAL_PARAM.search(code), key
            assert not BARE_INDEX.search(code), key
        p = ctl.params_type()
        for bad in (math.nan, math.inf):
            with pytest.raises(ParameterError, match="must be finite"):
                ctl.params_type(**{**p.as_dict(), "d": (bad,)})


def _nonlinear():
    return ct.nlsys(lambda t, x, u, params: -x + u, lambda t, x, u, params: x, states=1,
                    inputs="heading_error", outputs="rudder_command", name="nl")


@pytest.mark.parametrize("make, kwargs, field, match", [
    (lambda: np.eye(2), {}, "sys", "must be a python-control StateSpace or TransferFunction"),
    (_nonlinear, {}, "sys", "NonlinearIOSystem: its update and output functions are Python"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), {"dt": 0.5}, "sys",
     r"has input 'u\[0\]', which is no signal seahelm can route"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="depth_error",
                   outputs="rudder_command"), {"dt": 0.5}, "sys", "input 'depth_error'"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading"), {"dt": 0.5}, "sys",
     "distinct outputs named after commands"),
    (lambda: ct.ss([[np.nan]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": 0.5}, "sys", "non-finite entries in its A"),
    (lambda: ct.ss([[1.2]], [[1.0]], [[1.0]], [[0.0]], 0.5, inputs="heading",
                   outputs="rudder_command"), {}, "sys", "unstable controller.*1.2"),
    (lambda: ct.ss([[0.1]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": 1.0}, "sys", "unstable controller"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {}, "dt", "is needed to sample a continuous"),
    (lambda: ct.ss([[0.5]], [[1.0]], [[1.0]], [[0.0]], 0.5, inputs="heading",
                   outputs="rudder_command"), {"dt": 1.0}, "dt", "discrete system's sample"),
    (lambda: ct.ss([[0.5]], [[1.0]], [[1.0]], [[0.0]], True, inputs="heading",
                   outputs="rudder_command"), {}, "dt", "does not say its sample period"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": -1.0}, "dt", "must be > 0"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": 0.5, "method": "matched"}, "method",
     "must be one of zoh"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": 0.5, "input_offset": [1.0, 2.0]},
     "input_offset", "must have 1 values"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": 0.5, "initial_state": [0.0, 0.0]},
     "initial_state", "must have 1 values"),
    (lambda: ct.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs="heading",
                   outputs="rudder_command"), {"dt": 0.5, "output_offset": [math.nan]},
     "output_offset", "must be finite"),
])
def test_bad_systems_are_refused_naming_the_argument(make, kwargs, field, match):
    with pytest.raises(ParameterError, match=match) as exc:
        state_space_controller(make(), **kwargs)
    assert exc.value.field == field


def test_what_unstable_and_other_outputs_need():
    sys = ct.ss([[1.2]], [[1.0]], [[1.0]], [[0.0]], 0.5, inputs="drift_angle",
                outputs="rudder_command")
    with pytest.raises(ParameterError, match="drift_angle"):
        state_space_controller(sys, allow_unstable=True)
    from seahelm.vessels.mariner import MARINER

    ctl = state_space_controller(sys, allow_unstable=True, model=MARINER)
    assert ctl.measurement_labels == ("drift_angle",)
    err = ct.ss([[0.5]], [[1.0]], [[1.0]], [[0.0]], 0.5, inputs="speed_error",
                outputs="propeller_rps")
    ctl = state_space_controller(err, model=MARINER)
    assert ctl.reference_labels == ("speed",) and ctl.reference_units == ("m/s",)


def test_params_for_and_the_controller_period_are_checked():
    ctl = state_space_controller(pid_discrete())
    with pytest.raises(ParameterError, match="must have the structure") as exc:
        ctl.params_for(ct.ss([[0.5]], [[1.0]], [[1.0]], [[0.0]], DTC, inputs="heading_error",
                             outputs="rudder_angle"))
    assert exc.value.field == "sys"
    c = pid_discrete()
    with pytest.raises(ParameterError, match="sample period 1.0 s"):
        ctl.params_for(ct.ss(c.A, c.B, c.C, c.D, 1.0, inputs="heading_error",
                             outputs="rudder_angle"))
    p = Nomoto1Params(gain=K, time_constant=T, speed=U)
    with pytest.raises(ParameterError, match=re.escape("`controller_dt` must be 0.5 s")):
        simulate(NOMOTO1, p, NOMOTO1.initial_state(), t_final=10.0, dt=DT, controller=ctl,
                 actuator=DIRECT, controller_dt=1.0)
    assert set(SAMPLING_METHODS) >= {"zoh", "tustin"}
