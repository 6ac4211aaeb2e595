"""Fixed-step integrators: Butcher tableaus, their orders against closed-form solutions (numpy and
the compiled engine), batched == one by one, and the tableau validation."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.linalg import expm

from seahelm.actuators.servo import DIRECT, RUDDER_SERVO
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.simulation.engine import compile_closed_loop, simulate
from seahelm.simulation.integrators import (
    INTEGRATORS,
    ORDERS,
    ButcherTableau,
    get_integrator,
    integrate,
    rk_step,
    solve_reference,
)
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

METHODS = list(INTEGRATORS)

# a method that is in no registry: the engine and rk_step take the tableau itself
# (the one-parameter family of second-order methods with c_2 = 3/4; Butcher (2016), sec. 231)
CUSTOM = ButcherTableau(
    name="rk2-three-quarters",
    a=[[0.0, 0.0], [0.75, 0.0]],
    b=[1 / 3, 2 / 3],
    c=[0.0, 0.75],
    order=2,
)


def _id(method) -> str:
    return getattr(method, "name", method)


def _log2_ratio(coarse: float, fine: float) -> float:
    return math.log2(coarse / fine)


# --- the registry ---------------------------------------------------------------------------
def test_published_orders_and_stages():
    expected = {"euler": (1, 1), "midpoint": (2, 2), "heun": (2, 2), "ralston": (2, 2),
                "bosh3": (3, 3), "ssprk3": (3, 3), "kutta3": (3, 3), "rk4": (4, 4),
                "rk38": (4, 4)}
    for name, (order, stages) in expected.items():
        assert INTEGRATORS[name].order == order
        assert INTEGRATORS[name].stages == stages
        assert INTEGRATORS[name].name == name
    assert ORDERS == {name: tab.order for name, tab in INTEGRATORS.items()}


def test_get_integrator_takes_a_name_or_a_tableau():
    assert get_integrator("rk4") is INTEGRATORS["rk4"]
    assert get_integrator(CUSTOM) is CUSTOM
    with pytest.raises(ValueError, match="unknown integrator 'rk5'; valid: euler, midpoint, "
                       "heun, ralston, bosh3, ssprk3, kutta3, rk4, rk38"):
        get_integrator("rk5")
    with pytest.raises(TypeError, match="integrator must be a name"):
        get_integrator(4)


# --- validation -------------------------------------------------------------------------------
_GOOD = dict(name="t", a=[[0.0, 0.0], [1.0, 0.0]], b=[0.5, 0.5], c=[0.0, 1.0], order=2)


@pytest.mark.parametrize(
    ("change", "match"),
    [
        ({"c": [0.0, 0.9]}, r"`c` of tableau 't' must equal the row sums of `a` .*c\[1\] = 0.9, "
                            r"row sum 1.0"),
        ({"a": [[0.0, 0.0], [1.0, 0.5]], "c": [0.0, 1.5]},
         r"`a` of tableau 't' must be strictly lower triangular .*a\[1\]\[1\] = 0.5"),
        ({"a": [[0.5, 0.0], [1.0, 0.0]], "c": [0.5, 1.0]},
         r"strictly lower triangular .*a\[0\]\[0\] = 0.5"),
        ({"a": [[0.0, 0.5], [1.0, 0.0]], "c": [0.5, 1.0]}, r"a\[0\]\[1\] = 0.5"),
        ({"b": [0.5, 0.6]}, r"`b` of tableau 't' must sum to 1, got sum 1.1"),
        ({"b": [1.0]}, r"`b` of tableau 't' must have shape \(2,\)"),
        ({"c": [0.0, 1.0, 2.0]}, r"`c` of tableau 't' must have shape \(2,\)"),
        ({"a": [[0.0, 0.0]]}, r"`a` of tableau 't' must be a square \(s, s\) array"),
        ({"a": [[0.0], [1.0, 0.0]]}, r"`a` of tableau 't' must be a numeric array"),
        ({"b": [float("nan"), 0.5]}, r"`b` of tableau 't' must be finite"),
        ({"order": 0}, r"`order` of tableau 't' must be a whole number >= 1, got 0"),
        ({"order": 2.5}, r"`order` of tableau 't' must be a whole number >= 1, got 2.5"),
        ({"name": ""}, r"`name` of a tableau must be a non-empty string"),
    ],
)
def test_tableau_validation(change, match):
    with pytest.raises(ParameterError, match=match):
        ButcherTableau(**{**_GOOD, **change})


def test_tableau_allows_round_off_in_the_consistency_checks():
    # 1/3 + 1/3 + 1/3 and -1/3 + 1 are not exactly 1 and 2/3 in binary floating point
    tab = ButcherTableau(name="thirds", a=[[0, 0, 0], [2 / 3, 0, 0], [-1 / 3, 1, 0]],
                         b=[1 / 3, 1 / 3, 1 / 3], c=[0, 2 / 3, 2 / 3], order=1)
    assert tab.stages == 3
    assert tab.a[2] == (-1 / 3, 1.0, 0.0)  # stored as tuples of floats, hashable
    assert hash(tab) == hash(dataclasses.replace(tab))


# --- numpy: observed order == declared order --------------------------------------------------
# a forced damped oscillator x' = A x + B g(t), g = (cos ωt, sin ωt), batched over 3 initial
# states; exact solution from the matrix exponential of the augmented system with g' = Ω g
A = np.array([[0.0, 1.0], [-4.0, -0.4]])
B = np.array([[0.0, 0.5], [1.0, 0.0]])
OMEGA = 1.3
X0 = np.array([[1.0, 0.0], [0.0, 1.0], [0.5, -0.5]])


def _forced(t, x):
    g = np.array([math.cos(OMEGA * t), math.sin(OMEGA * t)])
    return x @ A.T + g @ B.T


def _forced_exact(t_end: float) -> np.ndarray:
    M = np.zeros((4, 4))
    M[:2, :2], M[:2, 2:], M[2:, 2:] = A, B, [[0.0, -OMEGA], [OMEGA, 0.0]]
    z0 = np.concatenate([X0, np.tile([1.0, 0.0], (len(X0), 1))], axis=1)
    return (z0 @ expm(M * t_end).T)[:, :2]


def _grid(t_end: float, h: float) -> np.ndarray:
    return np.linspace(0.0, t_end, int(round(t_end / h)) + 1)


def _forced_error(method, h: float) -> float:
    xs = integrate(_forced, X0, _grid(4.0, h), method=method)
    return float(np.max(np.abs(xs[-1] - _forced_exact(4.0))))


# the Riccati equation x' = 1 + x² (nonlinear): x(t) = tan(t + arctan x0)
R0 = np.array([[0.0], [0.3], [-0.5]])


def _riccati_error(method, h: float) -> float:
    xs = integrate(lambda t, x: 1.0 + x * x, R0, _grid(0.5, h), method=method)
    return float(np.max(np.abs(xs[-1] - np.tan(0.5 + np.arctan(R0)))))


@pytest.mark.parametrize("method", METHODS + [CUSTOM], ids=_id)
def test_numpy_order_on_a_forced_linear_system(method):
    tab = get_integrator(method)
    observed = _log2_ratio(_forced_error(method, 0.025), _forced_error(method, 0.0125))
    assert observed == pytest.approx(tab.order, abs=0.3)


@pytest.mark.parametrize("method", METHODS + [CUSTOM], ids=_id)
def test_numpy_order_on_a_nonlinear_equation(method):
    tab = get_integrator(method)
    observed = _log2_ratio(_riccati_error(method, 0.025), _riccati_error(method, 0.0125))
    assert observed == pytest.approx(tab.order, abs=0.3)


def test_rk_step_evaluates_the_stages_at_their_nodes():
    # x' = t² from 0: one step of any method of order >= 3 is exact (h³/3); Simpson's rule
    # for rk4, i.e. the mid-step stages really are at t + h/2
    for name in ("bosh3", "ssprk3", "kutta3", "rk4", "rk38"):
        x = rk_step(name, lambda t, x: np.full_like(x, t * t), 1.0, np.zeros((2, 1)), 0.5)
        np.testing.assert_allclose(x, (1.5 ** 3 - 1.0) / 3.0, rtol=1e-15)
    # Euler samples the start only
    x = rk_step("euler", lambda t, x: np.full_like(x, t * t), 1.0, np.zeros(1), 0.5)
    np.testing.assert_array_equal(x, [0.5])


def test_solve_reference_matches_closed_form():
    t = np.linspace(0.0, 5.0, 11)
    xs = solve_reference(lambda tt, x: A @ x, X0[0], t)
    exact = np.array([expm(A * tt) @ X0[0] for tt in t])
    np.testing.assert_allclose(xs, exact, atol=1e-9)


def test_integrate_rejects_bad_grid():
    with pytest.raises(ParameterError, match="time step"):
        integrate(_forced, X0, [0.0, 1.0, 0.5])
    with pytest.raises(ValueError, match="unknown integrator 'rk5'; valid: euler, midpoint"):
        integrate(_forced, X0, [0.0, 1.0], method="rk5")


# --- the compiled closed-loop kernel --------------------------------------------------------
# Nomoto-1, T ṙ + r = K (δ + δ_d(t)), rudder δ constant (direct actuator, open loop) and a
# rudder disturbance linear in time, δ_d = α + β t, given on the grid (so the kernel's linear
# interpolation to the stage times is exact). From rest, with a = K (δ + α) − T K β, b = K β:
#   r(t) = a + b t − a e^{−t/T},   ψ(t) = a t + b t²/2 − a T (1 − e^{−t/T})
K, T, DELTA = 0.185, 107.3, math.radians(10.0)
ALPHA, BETA = 0.02, -0.0005
P1 = Nomoto1Params(gain=K, time_constant=T, speed=7.7)
T_FINAL = 200.0


def _heading_exact(t: float) -> float:
    a, b = K * (DELTA + ALPHA) - T * K * BETA, K * BETA
    return a * t + b * t * t / 2.0 - a * T * (1.0 - math.exp(-t / T))


def _kernel_error(method, dt: float) -> float:
    t = np.arange(int(round(T_FINAL / dt)) + 1) * dt
    z = np.zeros_like(t)  # (no sway velocity, no current)
    dist = np.stack([ALPHA + BETA * t, z, z, z], axis=1)
    res = simulate(NOMOTO1, P1, np.zeros(4), t_final=T_FINAL, dt=dt, actuator=DIRECT,
                   reference=[DELTA], disturbance=dist, integrator=method)
    return abs(res["heading"][0, -1] - _heading_exact(T_FINAL))


@pytest.mark.parametrize("method", METHODS)
def test_kernel_order_with_a_time_varying_disturbance(method):
    # large steps so that round-off does not mask the truncation error of the 4th-order methods
    observed = _log2_ratio(_kernel_error(method, 10.0), _kernel_error(method, 5.0))
    assert observed == pytest.approx(INTEGRATORS[method].order, abs=0.3)


# the same loop with the nonlinear Norrbin term, a sway disturbance and a rudder disturbance
# that is not linear in time, run by the kernel and by rk_step on the same equations
P_NONLINEAR = Nomoto1Params(gain=K, time_constant=T, speed=7.7, norrbin_n3=2000.0)
DT, N_STEPS = 2.0, 60


def _nonlinear_disturbance(phase: float) -> np.ndarray:
    t = np.arange(N_STEPS + 1) * DT
    z = np.zeros_like(t)  # (no current)
    return np.stack([0.03 * np.sin(0.05 * t + phase), 0.4 * np.cos(0.03 * t + phase), z, z],
                    axis=1)


def _nomoto1_numpy(t, x, p, grid, dist):
    d = np.array([np.interp(t, grid, dist[:, j]) for j in range(2)])
    psi, r = x[2], x[3]
    return np.array([
        p.speed * math.cos(psi) - d[1] * math.sin(psi),
        p.speed * math.sin(psi) + d[1] * math.cos(psi),
        r,
        (p.gain * (DELTA + d[0]) - (r + p.norrbin_n3 * r ** 3)) / p.time_constant,
    ])


@pytest.mark.parametrize("method", METHODS + [CUSTOM], ids=_id)
def test_kernel_step_equals_the_numpy_step(method):
    dist = _nonlinear_disturbance(0.3)
    x0 = np.array([0.0, 0.0, 0.1, 0.002])
    res = simulate(NOMOTO1, P_NONLINEAR, x0, t_final=N_STEPS * DT, dt=DT, actuator=DIRECT,
                   reference=[DELTA], disturbance=dist, integrator=method)
    grid = np.arange(N_STEPS + 1) * DT
    xs = integrate(_nomoto1_numpy, x0, grid, P_NONLINEAR, grid, dist, method=method)
    assert res.ok.all()
    assert res.metadata["integrator"] == get_integrator(method).name
    np.testing.assert_allclose(res.state[0], xs, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("method", METHODS)
def test_kernel_batched_equals_one_by_one(method):
    params = [Nomoto1Params(gain=0.1 + 0.05 * i, time_constant=60.0 + 30.0 * i, speed=5.0 + i,
                            norrbin_n3=500.0 * i) for i in range(4)]
    x0 = np.array([[0.0, 0.0, 0.1 * i, 0.001 * (i - 1)] for i in range(4)])
    dist = np.stack([_nonlinear_disturbance(0.5 * i) for i in range(4)])
    kw = dict(t_final=N_STEPS * DT, dt=DT, actuator=DIRECT, reference=[DELTA],
              integrator=method)
    batch = simulate(NOMOTO1, params, x0, disturbance=dist, **kw)
    for i in range(4):
        one = simulate(NOMOTO1, params[i], x0[i], disturbance=dist[i], **kw)
        np.testing.assert_array_equal(batch.state[i], one.state[0])
        np.testing.assert_array_equal(batch.output[i], one.output[0])


def test_engine_takes_a_tableau_and_keys_its_kernel_on_the_coefficients():
    heun = INTEGRATORS["heun"]
    same = ButcherTableau(name="heun", a=heun.a, b=heun.b, c=heun.c, order=heun.order)
    kw = dict(t_final=N_STEPS * DT, dt=DT, actuator=DIRECT, reference=[DELTA],
              disturbance=_nonlinear_disturbance(0.0))
    by_name = simulate(NOMOTO1, P_NONLINEAR, np.zeros(4), integrator="heun", **kw)
    by_object = simulate(NOMOTO1, P_NONLINEAR, np.zeros(4), integrator=same, **kw)
    np.testing.assert_array_equal(by_name.state, by_object.state)
    names = {compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, m).__name__
             for m in METHODS + [CUSTOM]}
    assert len(names) == len(METHODS) + 1
    with pytest.raises(ValueError, match="unknown integrator 'rk45'; valid: euler, midpoint"):
        simulate(NOMOTO1, P1, np.zeros(4), integrator="rk45", **kw)


# --- the step as a loop over the stages (heavy models) ----------------------------------------
@pytest.fixture
def stage_loop_everywhere(monkeypatch):
    """Every kernel built in the test loops over its stages (threshold below any model)."""
    from seahelm.simulation import closed_loop as engine  # (where the threshold is read)

    monkeypatch.setattr(engine, "STAGE_LOOP_ABOVE", -1)
    engine.compile_closed_loop.cache_clear()
    yield
    engine.compile_closed_loop.cache_clear()


# nodes 0 only, 2/3, 1/2 and 1, 1/3 and 2/3 and 1, 3/4, a repeated 1/2 (rk4), 1 before 1/2
# (ssprk3): every branch of the stage disturbance
@pytest.mark.parametrize("method", ["euler", "ralston", "kutta3", "rk38", "rk4", "ssprk3", CUSTOM],
                         ids=_id)
def test_looped_kernel_step_equals_the_numpy_step(method, stage_loop_everywhere):
    dist = _nonlinear_disturbance(0.3)
    x0 = np.array([0.0, 0.0, 0.1, 0.002])
    kernel = compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, method)
    assert kernel.RK_A.shape == (get_integrator(method).stages,) * 2  # (the looped form)
    res = simulate(NOMOTO1, P_NONLINEAR, x0, t_final=N_STEPS * DT, dt=DT, actuator=DIRECT,
                   reference=[DELTA], disturbance=dist, integrator=method)
    grid = np.arange(N_STEPS + 1) * DT
    xs = integrate(_nomoto1_numpy, x0, grid, P_NONLINEAR, grid, dist, method=method)
    assert res.ok.all()
    np.testing.assert_allclose(res.state[0], xs, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("exact", [True, False], ids=["closed-form servo", "integrated servo"])
def test_looped_and_written_out_steps_agree_with_actuator_states_and_a_controller(exact):
    """Nomoto-2 + rudder servo (an actuator state: from its closed-form step, or integrated with
    the tableau through ka/ta) + PID, RK4, a time-varying rudder disturbance: the two forms of
    the step give the same run to rounding."""
    from seahelm.control.pid import PID_HEADING, PIDHeadingParams
    from seahelm.simulation import engine
    from seahelm.ships import get_ship
    from seahelm.vessels.nomoto import NOMOTO2

    servo = RUDDER_SERVO if exact else dataclasses.replace(RUDDER_SERVO, advance=None)
    p = get_ship("mariner-nomoto2").params
    t = np.arange(301) * 0.5
    dist = np.zeros((301, NOMOTO2.n_disturbances))
    dist[:, 0] = 0.02 * np.sin(0.05 * t)
    kw = dict(t_final=150.0, dt=0.5, actuator=servo, controller=PID_HEADING,
              controller_params=PIDHeadingParams(kp=3.0, ki=0.001, kd=90.0),
              reference=[math.radians(20.0)], disturbance=dist)
    x0 = np.array([0.0, 0.0, 0.05, 0.001, 0.0])
    written = simulate(NOMOTO2, p, x0, **kw)
    looped_kernel = compile_closed_loop(NOMOTO2, servo, PID_HEADING, "rk4", stage_loop=True)
    assert hasattr(looped_kernel, "RK_A") and looped_kernel.EXACT_ACTUATOR == exact
    old = engine.STAGE_LOOP_ABOVE
    engine.compile_closed_loop.cache_clear()
    try:
        engine.STAGE_LOOP_ABOVE = -1
        looped = simulate(NOMOTO2, p, x0, **kw)
    finally:
        engine.STAGE_LOOP_ABOVE = old
        engine.compile_closed_loop.cache_clear()
    assert written.ok.all() and looped.ok.all()
    assert np.ptp(written.state[0, :, -1]) > 0.1  # the servo moved
    np.testing.assert_allclose(looped.state, written.state, rtol=1e-12, atol=1e-12)


def test_heavy_models_loop_over_the_stages_and_light_ones_write_them_out():
    from seahelm.actuators.servo import RUDDER_PROPELLER, RUDDER_SERVO
    from seahelm.control.pid import PID_HEADING
    from seahelm.simulation.engine import STAGE_LOOP_ABOVE, _stage_code_size
    from seahelm.vessels.catamaran import CATAMARAN
    from seahelm.vessels.mariner import MARINER
    from seahelm.vessels.mmg import MMG
    from seahelm.vessels.nomoto import NOMOTO2

    rk4, euler = get_integrator("rk4"), get_integrator("euler")

    def looped(model, actuator, tab):
        return _stage_code_size(model, actuator, tab) > STAGE_LOOP_ABOVE

    assert looped(MMG, RUDDER_PROPELLER, rk4) and looped(MARINER, RUDDER_SERVO, rk4)
    assert not looped(NOMOTO2, RUDDER_SERVO, rk4) and not looped(CATAMARAN, DIRECT, rk4)
    assert not looped(MMG, RUDDER_PROPELLER, euler)  # one stage: one copy either way
    # the size counts what the right-hand side calls, each function once
    assert _stage_code_size(MMG, DIRECT, rk4) > 4 * 500
    assert hasattr(compile_closed_loop(MMG, RUDDER_PROPELLER, OPEN_LOOP, "rk4"), "RK_A")
    assert not hasattr(compile_closed_loop(NOMOTO2, RUDDER_SERVO, PID_HEADING, "rk4"), "RK_A")
    # the environment's loads count (compiled in the same go): Voitkunsky's model with Lvov's
    # loads loops, without them it stays written out
    import warnings
    from pathlib import Path

    from seahelm.scenario import load_scenario

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (the example ship is outside Lvov's hull range)
        job = load_scenario(Path(__file__).resolve().parents[1] / "examples"
                            / "compensation_storm_compensated.toml")
    assert job.environment is not None and job.model.name == "voitkunsky"
    from seahelm.simulation.stages import stages_of

    stages = stages_of(job)  # (the environment's stage)
    assert [stage.name for stage in stages] == ["environment"]
    with_loads = _stage_code_size(job.model, job.actuator, rk4, stages, True)
    without = _stage_code_size(job.model, job.actuator, rk4, (), True)
    assert without < STAGE_LOOP_ABOVE < with_loads


# --- actuators with a closed-form step --------------------------------------------------------
def _kvlcc2_circle(actuator, dt: float, method: str = "rk4"):
    """60 s of a 35 deg starboard turn of the KVLCC2 L7 model from a straight run at the
    self-propulsion rps, the rudder through its steering gear (15.8 deg/s, 0.1 s lag)."""
    from seahelm.analysis.equilibria.equilibrium import self_propulsion_rps
    from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO, MMG

    rps = float(self_propulsion_rps(KVLCC2_L7, 1.179))
    return simulate(MMG, KVLCC2_L7, np.array([1.179, 0.0, 0.0, 0.0, 0.0, 0.0]), t_final=60.0,
                    dt=dt, actuator=actuator, actuator_params=KVLCC2_L7_SERVO,
                    integrator=method,
                    reference={"rudder_command": math.radians(35.0), "propeller_rps": rps})


def test_a_closed_form_servo_frees_the_step_from_the_servo_lag():
    """The 0.1 s steering-gear lag makes RK4 unstable for the servo beyond 0.28 s (the rate
    limit then bounds a rudder chatter): integrated, a 0.5 s step is 0.7 % off in heading
    after 60 s; with the closed-form servo 0.5 s and 1 s steps stay within 0.005 % of a
    0.05 s run, and at 0.05 s the two agree to 1e-7 (the integrated servo's error)."""
    integrated = dataclasses.replace(RUDDER_SERVO, advance=None)
    fine = _kvlcc2_circle(RUDDER_SERVO, 0.05)
    psi = fine["heading"][0, -1]
    assert psi > 3.0  # (well into the turn)
    assert _kvlcc2_circle(integrated, 0.05)["heading"][0, -1] == pytest.approx(psi, rel=1e-7)
    for dt in (0.5, 1.0):
        run = _kvlcc2_circle(RUDDER_SERVO, dt)
        assert run.ok.all()
        assert run["heading"][0, -1] == pytest.approx(psi, rel=5e-5)
        assert run.state[0, -1, 3] == pytest.approx(fine.state[0, -1, 3], rel=1e-3)  # north
    coarse = _kvlcc2_circle(integrated, 0.5)
    assert abs(coarse["heading"][0, -1] / psi - 1.0) > 3e-3
    assert fine.metadata["actuator_step"] == "closed-form"
    assert coarse.metadata["actuator_step"] == "integrated"


def test_simulate_integrates_the_servo_on_request():
    """``exact_actuator=False`` is the integrated servo (the behaviour before the closed form),
    the same run as an actuator without ``advance``; ``True`` needs a closed form."""
    from seahelm.analysis.equilibria.equilibrium import self_propulsion_rps
    from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO, MMG

    rps = float(self_propulsion_rps(KVLCC2_L7, 1.179))
    kw = dict(t_final=30.0, dt=0.2, actuator_params=KVLCC2_L7_SERVO,
              reference={"rudder_command": math.radians(35.0), "propeller_rps": rps})
    x0 = np.array([1.179, 0.0, 0.0, 0.0, 0.0, 0.0])
    asked = simulate(MMG, KVLCC2_L7, x0, actuator=RUDDER_SERVO, exact_actuator=False, **kw)
    bare = simulate(MMG, KVLCC2_L7, x0, actuator=dataclasses.replace(RUDDER_SERVO, advance=None),
                    **kw)
    np.testing.assert_array_equal(asked.state, bare.state)
    assert asked.metadata["actuator_step"] == "integrated"
    exact = simulate(MMG, KVLCC2_L7, x0, actuator=RUDDER_SERVO, **kw)
    assert np.max(np.abs(exact.state - asked.state)) > 0  # (a different step)
    with pytest.raises(ParameterError, match="`exact_actuator`: the actuator 'direct' has no"):
        simulate(NOMOTO1, P1, np.zeros(4), t_final=10.0, dt=1.0, actuator=DIRECT,
                 reference=[0.1], exact_actuator=True)
    for bad in ("no", 0, 1.0):  # (a string or a number is not a choice: "no" would be truthy)
        with pytest.raises(ParameterError, match="`exact_actuator` must be True, False or None"):
            simulate(MMG, KVLCC2_L7, x0, actuator=RUDDER_SERVO, exact_actuator=bad, **kw)


@pytest.mark.parametrize("method", ["euler", "ssprk3", CUSTOM], ids=_id)
def test_closed_form_servo_written_out_and_looped_for_any_nodes(method):
    """Nodes 0 only (the step ends advancing the servo by h), 1 before 1/2, a last node that
    is not 1: written out and looped agree, and the servo's state at every step is its closed
    form (a 20 deg order at 5 deg/s, T = 1 s: a ramp for 3 s, then the lag)."""
    from seahelm.actuators.servo import RUDDER_SERVO, ServoParams
    from seahelm.simulation import engine
    from seahelm.ships import get_ship
    from seahelm.vessels.nomoto import NOMOTO2

    kw = dict(t_final=20.0, dt=0.25, actuator=RUDDER_SERVO, integrator=method,
              actuator_params=ServoParams(max_rate=math.radians(5.0), time_constant=1.0),
              reference=[math.radians(20.0)])
    p, x0 = get_ship("mariner-nomoto2").params, np.zeros(5)
    old = engine.STAGE_LOOP_ABOVE
    engine.compile_closed_loop.cache_clear()
    try:
        engine.STAGE_LOOP_ABOVE = 10 ** 9
        written = simulate(NOMOTO2, p, x0, **kw)
        engine.compile_closed_loop.cache_clear()
        engine.STAGE_LOOP_ABOVE = -1
        looped = simulate(NOMOTO2, p, x0, **kw)
        assert compile_closed_loop(NOMOTO2, RUDDER_SERVO, OPEN_LOOP, method).EXACT_ACTUATOR
    finally:
        engine.STAGE_LOOP_ABOVE = old
        engine.compile_closed_loop.cache_clear()
    assert written.ok.all() and looped.ok.all()
    np.testing.assert_allclose(looped.state, written.state, rtol=1e-12, atol=1e-12)
    t = np.arange(81) * 0.25
    want = np.where(t <= 3.0, 5.0 * t, 20.0 - 5.0 * np.exp(-(t - 3.0)))
    np.testing.assert_allclose(np.degrees(written.state[0, :, -1]), want, rtol=0, atol=1e-9)
    assert np.ptp(written.state[0, :, 2]) > 0.1  # (and the ship turned)


def test_exact_actuator_needs_a_closed_form_step():
    with pytest.raises(ValueError, match="exact_actuator: the actuator 'direct' has no"):
        compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, "rk4", exact_actuator=True)
