"""The closed-loop engine: batch equals one by one, divergence, ZOH, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT, RUDDER_SERVO, ServoParams
from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.errors import ParameterError, SimulationDiverged
from seahelm.simulation.engine import RunStatus, simulate
from seahelm.vessels.nomoto import NOMOTO1, NOMOTO2, Nomoto1Params

GAINS = PIDHeadingParams(kp=3.0, ki=0.001, kd=90.0)


def test_batch_equals_runs_one_by_one(mariner2):
    rng = np.random.default_rng(7)
    n = 6
    params = [mariner2.replace(gain=g) for g in rng.uniform(0.1, 0.3, n)]
    gains = [GAINS.replace(kp=k) for k in rng.uniform(1.0, 4.0, n)]
    x0 = np.zeros((n, 5))
    x0[:, 2] = rng.uniform(-0.2, 0.2, n)
    ref = rng.uniform(-0.5, 0.5, (n, 1, 1))
    dist = np.zeros((n, 3001, 4))  # rudder disturbance, sway velocity, current north/east
    dist[:, :, 0] = 0.01 * np.sin(np.arange(3001) * 0.1 * 0.05)[None] * np.arange(1, n + 1)[:, None]
    kw = dict(t_final=300.0, dt=0.1, controller=PID_HEADING, controller_dt=0.5)
    batch = simulate(NOMOTO2, params, x0, controller_params=gains, reference=ref,
                     disturbance=dist, **kw)
    for i in range(n):
        one = simulate(NOMOTO2, params[i], x0[i], controller_params=gains[i],
                       reference=ref[i, 0], disturbance=dist[i], **kw)
        np.testing.assert_allclose(batch.state[i], one.state[0], rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(batch.command[i], one.command[0], rtol=1e-13, atol=1e-13)


def test_out_of_bounds_is_detected_at_the_right_time():
    p = Nomoto1Params(gain=0.2, time_constant=20.0, speed=5.0)
    delta = 0.1
    bound = 0.015  # r(t) = K δ (1 − e^{−t/T}) crosses it at t* = −T ln(1 − bound/(K δ))
    t_star = -p.time_constant * math.log(1.0 - bound / (p.gain * delta))
    dt = 0.05
    res = simulate(NOMOTO1, p, np.zeros(4), t_final=100.0, dt=dt, actuator=DIRECT,
                   reference=np.array([[[delta]], [[0.5 * delta]]]),
                   bounds={"yaw_rate": (-1.0, bound)})
    assert res.status[0] == RunStatus.OUT_OF_BOUNDS
    assert t_star <= res.failure_time[0] < t_star + dt + 1e-12
    assert res.status[1] == RunStatus.OK  # the other run goes on (its r stays at 0.01)
    assert np.isfinite(res.state[1, -1]).all()
    # records after the failure are NaN, before it finite
    k_fail = int(round(res.failure_time[0] / dt))
    assert np.isnan(res.state[0, k_fail + 1:]).all()
    assert np.isfinite(res.state[0, :k_fail]).all()


def _euler_blowup_step() -> int:
    """First Euler step at which r of T ṙ = −(r + n3 r³) overflows (computed independently)."""
    r, k = 1.0, 0
    with np.errstate(over="ignore", invalid="ignore"):
        while np.isfinite(r):
            r = np.float64(r) + 1.0 * (-(r + 1000.0 * r**3) / 10.0)
            k += 1
    return k


def test_nonfinite_state_is_detected_and_throw_raises():
    stiff = Nomoto1Params(gain=0.1, time_constant=10.0, speed=1.0, norrbin_n3=1000.0)
    calm = stiff.replace(norrbin_n3=0.0)
    x0 = np.array([0.0, 0.0, 0.0, 1.0])
    kw = dict(t_final=50.0, dt=1.0, actuator=DIRECT, reference=[0.0], integrator="euler")
    res = simulate(NOMOTO1, [stiff, calm], x0, **kw)
    assert list(res.status) == [RunStatus.NONFINITE, RunStatus.OK]
    k = _euler_blowup_step()
    assert res.failure_time[0] == pytest.approx(k * 1.0)
    assert f"diverged: non-finite state at t = {k:g} s" in res.messages()[0]
    assert np.isfinite(res.state[1]).all()
    with pytest.raises(SimulationDiverged, match=rf"run 0 diverged at t = {k:g} s") as info:
        simulate(NOMOTO1, [stiff, calm], x0, throw=True, **kw)
    assert info.value.time == pytest.approx(k)
    assert info.value.run == 0
    assert not np.isfinite(info.value.state).all()


def test_nan_inputs_are_rejected(mariner1):
    dist = np.zeros((11, 2))
    dist[5, 0] = np.nan
    with pytest.raises(ParameterError, match="`disturbance` must be finite"):
        simulate(NOMOTO1, mariner1, np.zeros(4), t_final=1.0, dt=0.1, disturbance=dist)


def test_controller_is_sampled_with_zero_order_hold(mariner2):
    res = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=60.0, dt=0.1, controller=PID_HEADING,
                   controller_params=GAINS, reference=[0.3], controller_dt=2.0)
    cmd = res["rudder_command"][0]
    blocks = cmd[:600].reshape(30, 20)  # 20 steps of 0.1 s per 2-s sample
    assert np.all(blocks == blocks[:, :1])
    assert np.any(np.diff(blocks[:, 0]) != 0)


def test_servo_limits_angle_and_rate(mariner2):
    servo = ServoParams(max_angle=math.radians(20.0), max_rate=math.radians(3.0),
                        time_constant=0.5)
    res = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=120.0, dt=0.05,
                   controller=PID_HEADING, controller_params=GAINS, actuator=RUDDER_SERVO,
                   actuator_params=servo, reference=[math.radians(60.0)])
    delta = res["rudder_angle"][0]
    assert np.max(np.abs(delta)) <= servo.max_angle + 1e-12
    assert np.max(np.abs(delta)) == pytest.approx(servo.max_angle, rel=1e-6)
    assert np.max(np.abs(np.diff(delta))) / 0.05 <= servo.max_rate * (1 + 1e-9)


def test_progress_callback_and_record_every(mariner2):
    calls = []
    res = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=100.0, dt=0.1, reference=[0.0],
                   record_every=7, progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (1000, 1000)
    # every 7th step and the final state (1000 is not a multiple of 7: a shorter last interval)
    np.testing.assert_allclose(res.time, np.append(np.arange(0, 1001, 7), 1000) * 0.1)
    every = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=100.0, dt=0.1, reference=[0.0],
                     record_every=1)
    np.testing.assert_array_equal(res.state[:, -1], every.state[:, -1])  # the final state
    np.testing.assert_array_equal(res.state[:, :-1], every.state[:, ::7])
    np.testing.assert_array_equal(res.output[:, -1], every.output[:, -1])
    # chunked (a progress callback) and in one go record the same samples
    whole = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=100.0, dt=0.1, reference=[0.0],
                     record_every=7)
    np.testing.assert_array_equal(whole.state, res.state)


@pytest.mark.parametrize(
    ("kwargs", "exc", "match"),
    [
        ({"dt": 0.0}, ParameterError, r"`dt` must be > 0 \[s\], got 0.0"),
        ({"t_final": 10.05}, ParameterError, "`t_final` must be a positive whole multiple of `dt`"),
        ({"controller_dt": 0.25}, ParameterError, "`controller_dt` must be a positive whole"),
        ({"integrator": "rk45"}, ValueError,
         "unknown integrator 'rk45'; valid: euler, midpoint, heun, ralston, bosh3"),
        ({"x0": np.zeros(4)}, ParameterError, r"`x0` must have 5 states"),
        ({"x0": np.zeros((3, 5)), "params_n": 2}, ParameterError, "batch sizes do not broadcast"),
        ({"record_every": 0}, ParameterError, "`record_every` must be a whole number >= 1"),
        # more than the number of steps: only t = 0 would be recorded, and every "final"
        # metric would silently be the initial value
        ({"record_every": 101}, ParameterError,
         r"`record_every` = 101 exceeds the number of steps \(100 = t_final/dt\)"),
        ({"reference": np.zeros((7, 1))}, ParameterError, "needs 101 rows"),
        ({"bounds": {"speed": (0, 1)}}, ParameterError, "`bounds.speed` is an unknown state; states: "),
        ({"disturbance": [0.0]}, ParameterError, "`disturbance` must have 4 channel"),
    ],
)
def test_bad_input_is_rejected_before_running(mariner2, kwargs, exc, match):
    kw = dict(t_final=10.0, dt=0.1, x0=np.zeros(5), reference=[0.0])
    n = kwargs.pop("params_n", 1)
    kw.update(kwargs)
    with pytest.raises(exc, match=match):
        simulate(NOMOTO2, [mariner2] * n, **kw)


def test_initial_state_outside_bounds_is_rejected(mariner2):
    with pytest.raises(ParameterError, match="the initial state of run 0"):
        simulate(NOMOTO2, mariner2, [0, 0, 0, 0.5, 0], t_final=1.0, dt=0.1,
                 bounds={"yaw_rate": (-0.1, 0.1)})


@pytest.mark.parametrize("tau", [1.0, 2.0])
def test_servo_is_a_first_order_lag_below_its_limits(mariner1, tau):
    """A 1° step well inside the rate limit: δ(t) = δ_c (1 − e^{−t/T})."""
    from seahelm.control.open_loop import OPEN_LOOP

    step = math.radians(1.0)
    servo = ServoParams(max_rate=math.radians(10.0), time_constant=tau)
    res = simulate(NOMOTO1, mariner1, np.zeros(4), t_final=10.0, dt=0.01, controller=OPEN_LOOP,
                   actuator=RUDDER_SERVO, actuator_params=servo, reference=[step])
    np.testing.assert_allclose(res["rudder_angle"][0], step * (1.0 - np.exp(-res.time / tau)),
                               atol=1e-10)


def test_disturbance_is_aligned_with_the_grid():
    """A ramp disturbance δ_d = a t on the first-order Nomoto model from rest, no rudder:
    r(t) = K a (t − T (1 − e^{−t/T})). An off-by-one in the grid indexing shifts it by dt."""
    p = Nomoto1Params(gain=0.2, time_constant=20.0, speed=5.0)
    a = 1e-3
    t_grid = np.arange(0, 1001) * 0.1
    z = np.zeros_like(t_grid)
    dist = np.stack([a * t_grid, z, z, z], axis=1)
    res = simulate(NOMOTO1, p, np.zeros(4), t_final=100.0, dt=0.1, actuator=DIRECT,
                   reference=[0.0], disturbance=dist)
    t = res.time
    expected = p.gain * a * (t - p.time_constant * (1.0 - np.exp(-t / p.time_constant)))
    np.testing.assert_allclose(res["yaw_rate"][0], expected, atol=1e-12)


def _module_from_text(tmp_path, name, text):
    import importlib.util
    import sys

    path = tmp_path / f"{name}.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


def test_kernel_fingerprint_follows_code_in_memory_and_its_dependencies(tmp_path):
    """A kernel is named after the bytecode of its components *and* of the numba functions
    they call, as loaded: an edit of a helper in another module must give another kernel
    (a stale on-disk numba cache was once served after such an edit)."""
    from seahelm.simulation.engine import code_fingerprint

    body = ("from numba import njit\n\n@njit\ndef helper(x):\n    return x + {k}\n\n"
            "SCALE = {s}\n\n@njit\ndef component(x):\n    return helper(x) * SCALE\n")
    a = _module_from_text(tmp_path, "fp_a", body.format(k=1, s=2.0))
    b = _module_from_text(tmp_path, "fp_b", body.format(k=1, s=2.0))
    c = _module_from_text(tmp_path, "fp_c", body.format(k=2, s=2.0))
    d = _module_from_text(tmp_path, "fp_d", body.format(k=1, s=3.0))
    fa, fb, fc, fd = (code_fingerprint(m.component.py_func) for m in (a, b, c, d))
    assert fa.replace(b"fp_a", b"") == fb.replace(b"fp_b", b"")  # same code, same print
    assert fc.replace(b"fp_c", b"") != fa.replace(b"fp_a", b"")  # helper changed
    assert fd.replace(b"fp_d", b"") != fa.replace(b"fp_a", b"")  # frozen global changed


def test_one_run_and_a_batch_share_one_compiled_loop(mariner2, monkeypatch):
    """A single run's inputs are broadcast views (read-only); numba types those apart from
    writable arrays, so without care the same loop compiled twice (15-80 s each): every
    array the kernel receives is writable, for one run as for a batch."""
    import seahelm.simulation.engine as engine

    seen = []

    class Recording(engine._Slices):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            seen.append([(a.dtype, a.ndim, a.flags.writeable) for a in self.arrays])

    monkeypatch.setattr(engine, "_Slices", Recording)
    kw = dict(t_final=2.0, dt=0.1, controller=PID_HEADING, controller_params=GAINS,
              actuator=RUDDER_SERVO, actuator_params=ServoParams())
    for n in (1, 3):
        res = simulate(NOMOTO2, mariner2, np.zeros((n, 5)), reference={"heading": 0.1}, **kw)
        assert res.ok.all()
    assert seen[0] == seen[1]  # the same types: one specialisation of the loop
    assert all(writable for _, _, writable in seen[0])
