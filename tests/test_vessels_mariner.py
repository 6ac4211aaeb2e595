"""Mariner nonlinear model (Chislett & Strøm-Tejsen 1965): formulas by hand, linear steering
constants, sign convention, the Y_0/N_0 bias, engine runs (one kernel: Mariner + servo + open
loop)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR, MARINER_SERVO, MarinerParams

try:  # the catalog imports every vessel module; other models are mid-conversion on this branch
    from seahelm.ships import catalog as _catalog
    _CATALOG_ERROR = None
except Exception as exc:  # pragma: no cover - depends on the state of the other modules
    _catalog, _CATALOG_ERROR = None, exc

P = MARINER_NONLINEAR
L, U0 = 160.93, 7.7175


def mariner_by_hand(u, v, r, rudder, loads=(0.0, 0.0, 0.0)):
    """The tabulated equations, coefficients typed from the table (× 1e-5)."""
    e = 1e-5
    d = -rudder  # the table's δ: positive turns to port
    U = math.sqrt((U0 + u) ** 2 + v**2)
    u_, v_, r_ = u / U, v / U, r * L / U
    X = e * (-184 * u_ - 110 * u_**2 - 215 * u_**3 - 899 * v_**2 + 18 * r_**2 + 798 * r_ * v_
             - 95 * d**2 - 190 * u_ * d**2 + 93 * v_ * d + 93 * u_ * v_ * d)
    Y = e * (-1160 * v_ - 499 * r_ - 8078 * v_**3 + 15356 * v_**2 * r_ - 1160 * v_ * u_
             - 499 * r_ * u_ + 278 * d - 90 * d**3 + 556 * u_ * d + 278 * u_**2 * d
             - 4 * v_ * d**2 + 1190 * v_**2 * d + (-4 - 8 * u_ - 4 * u_**2))
    N = e * (-264 * v_ - 166 * r_ + 1636 * v_**3 - 5483 * v_**2 * r_ - 264 * v_ * u_
             - 166 * r_ * u_ - 139 * d + 45 * d**3 - 278 * u_ * d - 139 * u_**2 * d
             + 13 * v_ * d**2 - 489 * v_**2 * d + (3 + 6 * u_ + 3 * u_**2))
    m, Iz, xg = 798e-5, 39.2e-5, -0.023
    m11 = m + 42e-5
    m22, m23 = m + 748e-5, m * xg + 9.354e-5
    m32, m33 = m * xg - 4.646e-5, Iz + 43.8e-5
    det = m22 * m33 - m23 * m32
    udot = X * (U**2 / L) / m11
    vdot = -(-m33 * Y + m23 * N) * (U**2 / L) / det
    rdot = (-m32 * Y + m22 * N) * (U**2 / L**2) / det
    # dimensional loads on the dimensional mass matrix
    h = 0.5 * 1025.0
    M = np.array([[m11 * h * L**3, 0, 0], [0, m22 * h * L**3, m23 * h * L**4],
                  [0, m32 * h * L**4, m33 * h * L**5]])
    extra = np.linalg.solve(M, np.asarray(loads, dtype=float))
    return np.array([udot, vdot, rdot]) + extra


@pytest.mark.parametrize("state, rudder", [((-0.4, 0.3, 0.004), 0.15),
                                           ((0.2, -0.5, -0.006), -0.6),
                                           ((0.0, 0.0, 0.0), 0.0)])
def test_accelerations_by_hand(state, rudder):
    u, v, r = state
    psi = 0.3
    dx = MARINER.derivative(0.0, [u, v, r, 1.0, 2.0, psi], [rudder], P)
    np.testing.assert_allclose(dx[:3], mariner_by_hand(u, v, r, rudder), rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(dx[3:], [(U0 + u) * math.cos(psi) - v * math.sin(psi),
                                        (U0 + u) * math.sin(psi) + v * math.cos(psi), r],
                               rtol=1e-14)


def test_external_loads_are_dimensional():
    x = [-0.2, 0.1, 0.002, 0, 0, 0]
    loads = (2.0e5, -1.0e5, 3.0e7)  # [N, N, N·m]
    dx = MARINER.derivative(0.0, x, [0.1], P, loads)
    np.testing.assert_allclose(dx[:3], mariner_by_hand(-0.2, 0.1, 0.002, 0.1, loads),
                               rtol=1e-11)


def nomoto_from_jacobian(params):
    """K, T1, T2, T3 of r/δ = K(1 + T3 s)/((1 + T1 s)(1 + T2 s)) from the 2×2 sway–yaw
    linearisation of the model at the straight run (central finite differences)."""
    x0 = np.zeros(6)
    h = 1e-7

    def f(x, d):
        return MARINER.derivative(0.0, x, [d], params)[1:3]

    A = np.empty((2, 2))
    for j, k in enumerate((1, 2)):
        e = np.zeros(6)
        e[k] = h
        A[:, j] = (f(x0 + e, 0.0) - f(x0 - e, 0.0)) / (2 * h)
    b = (f(x0, h) - f(x0, -h)) / (2 * h)
    det = A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
    trace = A[0, 0] + A[1, 1]
    num0 = A[1, 0] * b[0] - A[0, 0] * b[1]  # r/δ = (b2 s + num0) / (s² − tr s + det)
    K = num0 / det
    T3 = b[1] / num0
    t_sum, t_prod = -trace / det, 1.0 / det
    disc = math.sqrt(t_sum**2 - 4 * t_prod)
    return K, (t_sum + disc) / 2, (t_sum - disc) / 2, T3


def test_linearised_model_gives_the_published_nomoto_constants():
    K, T1, T2, T3 = nomoto_from_jacobian(P)
    assert K == pytest.approx(0.185, rel=0.02)
    assert T1 == pytest.approx(118.0, rel=0.02)
    assert T2 == pytest.approx(7.8, rel=0.02)
    assert T3 == pytest.approx(18.5, rel=0.02)


def test_positive_rudder_turns_to_starboard():
    dx0 = MARINER.derivative(0.0, np.zeros(6), [0.0], P)
    dx = MARINER.derivative(0.0, np.zeros(6), [math.radians(10)], P)
    assert dx[2] - dx0[2] > 0
    assert nomoto_from_jacobian(P)[0] > 0  # K > 0: positive rudder, positive yaw rate


def test_zero_rudder_bias_yaws_slowly_to_starboard():
    """Y_0 < 0, N_0 > 0 (single screw): at zero rudder the ship starts to yaw to starboard."""
    dx = MARINER.derivative(0.0, np.zeros(6), [0.0], P)
    assert dx[2] > 0 and dx[1] < 0
    symmetric = P.replace(Y_0=0.0, Y_0u=0.0, Y_0uu=0.0, N_0=0.0, N_0u=0.0, N_0uu=0.0)
    np.testing.assert_array_equal(MARINER.derivative(0.0, np.zeros(6), [0.0], symmetric)[:3], 0)


def test_outputs():
    y = dict(zip(MARINER.output_labels,
                 MARINER.outputs(0.0, [-0.5, 0.4, 0.01, 3.0, 4.0, 1.0], [0.1], P)))
    assert y["surge_speed"] == pytest.approx(U0 - 0.5, rel=1e-15)
    assert y["speed"] == pytest.approx(math.hypot(U0 - 0.5, 0.4), rel=1e-15)
    assert y["drift_angle"] == pytest.approx(-math.atan(0.4 / (U0 - 0.5)), rel=1e-15)
    assert (y["north"], y["east"], y["heading"], y["yaw_rate"], y["sway_speed"]) == \
        (3.0, 4.0, 1.0, 0.01, 0.4)


def test_validation():
    with pytest.raises(ParameterError, match=r"`x_G` must be in \[-0.5, 0.5\] \[-\], got 0.7"):
        P.replace(x_G=0.7)
    with pytest.raises(ParameterError, match=r"`mass` − `X_udot` must be > 0"):
        P.replace(X_udot=0.01)
    with pytest.raises(ParameterError, match=r"mass matrix .* must be positive definite"):
        P.replace(N_rdot=1.0)


def test_servo_preset():
    assert MARINER_SERVO.max_angle == pytest.approx(math.radians(40.0))
    assert MARINER_SERVO.max_rate == pytest.approx(math.radians(5.0))


@pytest.mark.skipif(_CATALOG_ERROR is not None,
                    reason=f"seahelm.ships.catalog does not import on this branch: "
                           f"{_CATALOG_ERROR}")
def test_catalog_entry():
    entry = _catalog.get("mariner-nonlinear")
    assert entry.model.name == "mariner" and entry.params == MarinerParams()
    assert "Chislett" in entry.provenance and "MARINER_SERVO" in entry.provenance


def test_registry_name():
    from seahelm.registry import get_model

    assert get_model("mariner") is MARINER


# ------------------------------------------------------------------------------------------
# engine runs (Mariner + rudder servo + open loop)
# ------------------------------------------------------------------------------------------
def run(rudder, *, t_final, dt=0.1, params=P):
    rudder = np.atleast_1d(np.asarray(rudder, dtype=float))
    return simulate(MARINER, params, np.zeros(6), t_final=t_final, dt=dt, actuator=RUDDER_SERVO,
                    actuator_params=MARINER_SERVO, controller=OPEN_LOOP,
                    reference={"rudder_command": rudder.reshape(-1, 1, 1)})


@pytest.fixture(scope="module")
def turns():
    return run(np.radians([35.0, -35.0, 0.0]), t_final=800.0)


def test_turns_and_zero_rudder_drift(turns):
    res = turns
    assert np.all(res.status == 0)
    r = res["yaw_rate"][:, -1]
    # rate-limited servo: 5 °/s, so 17.5° after 3.5 s
    k = int(round(3.5 / 0.1))
    assert res["rudder_angle"][0, k] == pytest.approx(math.radians(17.5), abs=1e-3)
    assert r[0] > 0 > r[1]
    # not mirror images: the bias helps the starboard turn
    assert r[0] > 1.01 * -r[1]
    # zero rudder: a slow steady yaw to starboard, far below the 35° turn rate
    assert 0.0 < r[2] < 0.5 * r[0]
    assert res["heading"][2, -1] > math.radians(45)


def test_batched_equals_one_by_one(turns):
    one = run(math.radians(-35.0), t_final=800.0)
    np.testing.assert_allclose(turns.state[1], one.state[0], rtol=0, atol=1e-9)
