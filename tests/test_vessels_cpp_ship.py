"""CPP ship model, Platonov & Platonova eq. (6)-(12)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.vessels.cpp_ship import (
    CPP_SHIP_CALM,
    CPP_SHIP_WAVES,
    CPPShipParams,
    calm_water_derivative,
    coefficient_case,
    emergence_factors,
    emergence_kinks,
    resistance_factor,
    rhs_calm,
    rhs_waves,
    waves_derivative,
)

# The paper's tables, typed in again here (independent of the module's copy).
TABLE = {
    1: dict(a1=1, b1=-0.60, c1=1.20, e1=-1.6, a2=1, b2=-0.65, c2=1.45, e2=-1.8),
    2: dict(a1=0.75, b1=-1.40, c1=2.05, e1=-1.6, a2=0.90, b2=-1.60, c2=2.30, e2=-1.8),
    3: dict(a1=0.75, b1=0.32, c1=1.6, e1=2.5, a2=0.90, b2=0.34, c2=1.8, e2=2.7),
}
K = 0.6  # default λ0/λmax (thrust and torque)
PE0 = 0.8 * (1 - 0.6 * K + 1.2 * K**2) - 1.6 * K**2  # eq. (8), hand-expanded
MC0 = 0.8 * (0.8 * (1 - 0.65 * K + 1.45 * K**2) - 1.8 * K**2)


def reference(v, w, phi, case, *, c1=1.0, c2=1.0, c10=1.0, c20=1.0, inv_a=1.0, n=1.0):
    """Eq. (10) (eq. (9) with all c = 1 and inv_a = 1), written out from the paper."""
    c = TABLE[case]
    chi = 1.0 if v >= 0 else -1.35
    dv = (phi * (c["a1"] * w * w + c["b1"] * K * v * w + c["c1"] * K * K * v * v)
          + c["e1"] * K * K * v * v) * c1 - chi * PE0 * c10 * v * v
    dw = n * (MC0 * c20 * 1.0 - phi * (phi * (c["a2"] * w * w + c["b2"] * K * v * w
                                              + c["c2"] * K * K * v * v)
                                       + c["e2"] * K * K * v * v) * c2)
    return np.array([dv, dw]) * inv_a


def test_initial_regime_eq8():
    p = CPPShipParams()
    assert p.initial_thrust == pytest.approx(0.2816, abs=1e-12)
    assert p.initial_torque == pytest.approx(0.20608, abs=1e-12)
    assert p.epsilon == pytest.approx(0.1)


def test_calm_equilibrium_at_initial_pitch():
    np.testing.assert_allclose(calm_water_derivative([1.0, 1.0], 0.8, CPPShipParams()),
                               [0.0, 0.0], atol=1e-14)


@pytest.mark.parametrize(
    "v, w, phi, case",
    [(0.9, 1.1, 0.7, 1), (0.5, 0.8, -0.6, 2), (-0.4, 0.7, -0.9, 3), (1.2, 1.0, 0.0, 1),
     (0.0, 1.0, -0.3, 2), (-0.3, 0.9, 0.5, 1)],
)
def test_calm_matches_paper_formula(v, w, phi, case):
    got = calm_water_derivative([v, w], phi, CPPShipParams())
    np.testing.assert_allclose(got, reference(v, w, phi, case), rtol=1e-13, atol=1e-14)


def test_coefficient_cases_and_boundaries():
    phi = np.array([0.0, 0.5, -0.5, -0.5, -1e-12, 0.0, 0.5])
    v = np.array([0.0, 0.5, 0.0, -1e-12, 0.5, -0.5, -0.5])
    np.testing.assert_array_equal(coefficient_case(phi, v), [1, 1, 2, 3, 2, 1, 1])
    np.testing.assert_array_equal(coefficient_case(phi, v, 3), [1, 1, 2, 3, 2, 3, 3])
    with pytest.raises(ParameterError, match="uncovered_case"):
        coefficient_case(phi, v, 2)


@pytest.mark.parametrize(
    "x_lo, x_hi, phi_lo, phi_hi",
    [((0.7, 1.0), (0.7, 1.0), -1e-12, 0.0),  # case 2 | case 1 across φ̄ = 0
     ((-1e-12, 0.9), (0.0, 0.9), -0.6, -0.6)],  # case 3 | case 2 across v̄ = 0
)
def test_rhs_continuous_across_case_boundaries(x_lo, x_hi, phi_lo, phi_hi):
    p = CPPShipParams()
    a = calm_water_derivative(x_lo, phi_lo, p)
    b = calm_water_derivative(x_hi, phi_hi, p)
    np.testing.assert_allclose(a, b, atol=1e-10)


def test_chi_switching():
    np.testing.assert_allclose(resistance_factor([0.0, 1e-9, -1e-9, -2.0], 2.0),
                               [2.0, 2.0, -2.7, -2.7])
    p = CPPShipParams()
    # φ̄ = 0, v̄ < 0 (uncovered -> case 1 by default): thrust e1 k² v² plus resistance +1.35 P v²
    v = -0.5
    got = calm_water_derivative([v, 1.0], 0.0, p)[0]
    assert got == pytest.approx(-1.6 * K**2 * v**2 + 1.35 * PE0 * v**2, rel=1e-13)
    got_pos = calm_water_derivative([-v, 1.0], 0.0, p)[0]
    assert got_pos == pytest.approx(-1.6 * K**2 * v**2 - PE0 * v**2, rel=1e-13)


def test_uncovered_case_policies():
    x, phi = [-0.4, 0.9], 0.5
    np.testing.assert_allclose(
        calm_water_derivative(x, phi, CPPShipParams(uncovered_case=3)),
        reference(-0.4, 0.9, phi, 3), rtol=1e-13)
    assert np.all(np.isnan(calm_water_derivative(x, phi, CPPShipParams(uncovered_case=0))))
    with pytest.raises(ParameterError, match="uncovered_case"):
        CPPShipParams(uncovered_case=2)


def test_emergence_factors_paper_case():
    # α = 0.5 − 0.4 sin τ: at τ = π/2, α = 0.1 -> c1 = 0.52, c2 = 0.6; at 3π/2 both 1
    c = emergence_factors([math.pi / 2, 3 * math.pi / 2, 0.0], 1.2, 0.96)
    np.testing.assert_allclose(c, [[0.52, 1.0, 1.0], [0.6, 1.0, 1.0]], atol=1e-14)
    np.testing.assert_allclose(emergence_kinks(1.2, 0.96), [0.0, math.pi], atol=1e-14)
    assert emergence_kinks(3.0, 0.5).size == 0


@pytest.mark.parametrize("tau", [0.3, math.pi / 2, 2.0, 4.0])
def test_waves_matches_paper_formula(tau):
    p = CPPShipParams()
    alpha = 0.5 - 0.4 * math.sin(tau)
    c1 = 0.4 + 1.2 * alpha if alpha <= 0.5 else 1.0
    c2 = 0.5 + alpha if alpha <= 0.5 else 1.0
    got = waves_derivative(tau, [0.95, 1.05], 0.7, p)
    want = reference(0.95, 1.05, 0.7, 1, c1=c1, c2=c2, c10=1 - 0.48 / math.pi,
                     c20=1 - 0.4 / math.pi, inv_a=0.1, n=1.0)
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-15)


def test_waves_reduce_to_calm():
    p = CPPShipParams(amplitude=0.0, immersion=2.0, thrust_emergence_initial=1.0,
                      torque_emergence_initial=1.0, wave_ratio=1.0)
    x = np.array([[0.9, 1.1], [0.4, 0.6]])
    u = np.array([0.3, -0.7])
    np.testing.assert_allclose(waves_derivative(1.234, x, u, p), calm_water_derivative(x, u, p),
                               rtol=1e-14)


def test_batched_equals_one_by_one_and_njit_signature():
    p = CPPShipParams()
    rng = np.random.default_rng(1)
    x = rng.uniform(0.2, 1.3, size=(4, 3, 2))
    u = rng.uniform(-1, 1, size=(4, 3))
    t = rng.uniform(0, 2 * math.pi, size=(4, 3))
    batch = waves_derivative(t, x, u, p)
    assert batch.shape == (4, 3, 2)
    parr = p.to_record()
    for i in range(4):
        for j in range(3):
            dx = np.empty(2)
            rhs_waves(t[i, j], x[i, j], u[i, j:j + 1], np.empty(0), parr, dx)
            np.testing.assert_allclose(batch[i, j], dx, rtol=1e-15)
            rhs_calm(0.0, x[i, j], u[i, j:j + 1], np.empty(0), parr, dx)
            np.testing.assert_allclose(calm_water_derivative(x[i, j], u[i, j], p), dx)


def test_broadcasting_or_not_compiles_one_batched_signature():
    """Inputs that broadcast to the batch (read-only views) and inputs that already have its
    shape reach the compiled _batched as the same types (issue 47 item 7: four signatures of
    _batched, rhs_calm and rhs_waves were compiled before), with the same numbers bit for bit."""
    from seahelm.vessels import cpp_ship

    p = CPPShipParams()
    x = np.array([[0.9, 1.1], [0.4, 0.6]])
    u = np.array([0.3, -0.7])
    full = calm_water_derivative(x, u, p)
    before = list(cpp_ship._batched.signatures)
    assert np.array_equal(calm_water_derivative(x, 0.3, p)[0], full[0])   # u broadcast
    assert np.array_equal(calm_water_derivative(x[1], u[1], p), full[1])  # one state
    assert np.array_equal(calm_water_derivative(np.array([0.9, 1.1]), u, p)[0], full[0])
    waves_derivative(np.zeros(2), x, u, p)
    waves_derivative(0.5, x[0], 0.3, [p])
    assert list(cpp_ship._batched.signatures) == before


def test_vessel_model_plugins_match():
    p = CPPShipParams()
    x = np.array([[0.9, 1.1], [0.5, 0.7]])
    u = np.array([[0.6], [-0.4]])
    # (VesselModel.derivative cannot reshape a zero-length disturbance yet: call the kernels)
    assert CPP_SHIP_WAVES.rhs is rhs_waves and CPP_SHIP_CALM.rhs is rhs_calm
    assert CPP_SHIP_WAVES.n_states == 2 and CPP_SHIP_WAVES.n_disturbances == 0
    y = CPP_SHIP_WAVES.outputs(0.0, x, u, p)
    np.testing.assert_allclose(y[:, 4], x[:, 0])


def test_balanced_parameters():
    p = CPPShipParams.balanced()
    assert p.thrust_emergence_initial == pytest.approx(1 - 0.48 / math.pi, abs=1e-12)
    assert p.torque_emergence_initial == pytest.approx(1 - 0.4 / math.pi, abs=1e-12)
    q = CPPShipParams.balanced(immersion=3.0)  # propeller never emerges
    assert q.thrust_emergence_initial == pytest.approx(1.0, abs=1e-14)


def test_bad_input_rejected():
    p = CPPShipParams()
    with pytest.raises(ParameterError, match=r"`pitch_ratio` must be in \[-1, 1\]"):
        calm_water_derivative([1.0, 1.0], 1.5, p)
    with pytest.raises(ParameterError, match="pitch_ratio"):
        waves_derivative(0.0, [1.0, 1.0], -1.01, p)
    with pytest.raises(ParameterError, match="c2"):
        CPPShipParams(immersion=0.0, amplitude=1.5)
    with pytest.raises(ParameterError, match="wave_ratio"):
        CPPShipParams(wave_ratio=0.0)
    with pytest.raises(ParameterError, match="initial_pitch"):
        CPPShipParams(initial_pitch=1.2)
    with pytest.raises(ParameterError, match="P_e0"):
        CPPShipParams(initial_pitch=0.3)
    with pytest.raises(ParameterError, match="2 states"):
        calm_water_derivative([1.0, 1.0, 1.0], 0.5, p)
    with pytest.warns(ValidityRangeWarning, match="c1"):
        CPPShipParams(immersion=0.0, amplitude=1.0)


def test_cpp_ship_runs_in_the_engine_and_matches_an_adaptive_reference():
    """The wave model in the compiled closed loop (open loop, constant pitch) against
    solve_ivp on the numpy right-hand side.

    Tolerance argument: the emergence factors c1(τ), c2(τ) have kinks (eq. (11)-(12); at
    τ = 0, π, 2π, … for the default immersion and amplitude). An adaptive solver stepping over
    a kink is far less accurate than its tolerance (1e-6 here, depending on where scipy's steps
    fall), so the reference restarts at every kink. Its own error, estimated against a solve
    100× tighter, must be below 1e-10; then the engine (RK4, dt = π/200, kinks on the grid)
    must agree with it to 1e-9, well above the reference's error and well below any modelling
    effect.
    """
    from seahelm.actuators.servo import DIRECT
    from seahelm.control.open_loop import OPEN_LOOP
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.integrators import solve_reference
    from seahelm.vessels.cpp_ship import CPPShipParams, waves_derivative

    p = CPPShipParams()
    x0 = np.array([0.9, 0.95])
    pitch = 0.7
    res = simulate(CPP_SHIP_WAVES, p, x0, t_final=20 * np.pi, dt=np.pi / 200, actuator=DIRECT,
                   controller=OPEN_LOOP, reference=[pitch], record_every=100)
    kinks = (emergence_kinks(p.immersion, p.amplitude)[:, None]
             + 2 * np.pi * np.arange(11)).ravel()
    ref = solve_reference(lambda t, x: waves_derivative(t, x, pitch, p), x0, res.time,
                          breakpoints=kinks)
    tighter = solve_reference(lambda t, x: waves_derivative(t, x, pitch, p), x0, res.time,
                              breakpoints=kinks, rtol=1e-12, atol=1e-14)
    assert np.abs(ref - tighter).max() < 1e-10  # the reference is fit to be ground truth
    np.testing.assert_allclose(res.state[0], ref, rtol=0, atol=1e-9)
    assert res.ok.all()
    np.testing.assert_allclose(res["surge_speed"][0], res["speed"][0])

