"""seahelm's supply vessel on DP beside PythonVehicleSimulator's (skipped without a PVS snapshot).

Set ``SEAHELM_PVS_SOURCE`` to a directory holding the package ``python_vehicle_simulator``
(cybergalactic/PythonVehicleSimulator). PVS's ``supply.dynamics`` is evaluated as a
right-hand side (``sampleTime = 1``, the shaft speeds as commanded: no lag) and integrated here
with RK4 at seahelm's step; its ``DPcontrol`` (nonlinear PID by pole placement, first-order
reference filters, pseudo-inverse allocation) runs at the same control step. seahelm runs
``dp-pid`` with no shaft lag and power weights w = n_max⁴ (so that its minimum of
Σ w (f/T_max)² is PVS's minimum of Σ (n abs(n))²: both the least-norm allocation while no
thruster saturates). Nothing of PVS is copied into seahelm.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

SOURCE = os.environ.get("SEAHELM_PVS_SOURCE", "")
if not SOURCE or not os.path.isdir(os.path.join(SOURCE, "python_vehicle_simulator")):
    pytest.skip("no PythonVehicleSimulator snapshot (set SEAHELM_PVS_SOURCE)",
                allow_module_level=True)
sys.path.insert(0, SOURCE)

from python_vehicle_simulator.lib.gnc import attitudeEuler  # noqa: E402
from python_vehicle_simulator.vehicles.supply import supply  # noqa: E402

from seahelm.control.dp_pid import dp_pid_params  # noqa: E402
from seahelm.ships import get_ship  # noqa: E402
from seahelm.simulation.engine import simulate  # noqa: E402
from seahelm.simulation.problem import Problem  # noqa: E402

SHIP = get_ship("supply")
DT = 0.1


def pvs_rhs(vehicle, x, n):
    """(η̇, ν̇) of PVS's supply vessel, 6-DOF vectors, for shaft speeds n [rpm] held."""
    eta, nu = x[:6].copy(), x[6:].copy()
    nu1, _ = vehicle.dynamics(eta.copy(), nu.copy(), np.asarray(n, float).copy(),
                              np.asarray(n, float).copy(), 1.0)
    return np.concatenate([attitudeEuler(eta.copy(), nu, 1.0) - eta, nu1 - nu])


def _to3(x6):
    return x6[[0, 1, 5, 6, 7, 11]]


def test_the_model_equals_pvs_for_the_same_forces():
    """Open loop, same thrusts: ν̇ and η̇ equal PVS's at random states and shaft speeds to
    1e-9 (relative)."""
    rng = np.random.default_rng(0)
    vehicle = supply()
    lay = SHIP.thrusters
    k = np.array([3.2] * 4 + [31.2] * 2)            # PVS's thrust coefficients
    for _ in range(30):
        x6 = np.zeros(12)
        x6[[0, 1, 5]] = rng.normal(size=3) * [50, 50, 1]
        x6[[6, 7, 11]] = rng.normal(size=3) * [1, 0.5, 0.01]
        n = rng.uniform(-250, 250, size=6)
        n[4:] = rng.uniform(-160, 160, size=2)
        want = _to3(pvs_rhs(vehicle, x6, n))
        f = k * n * np.abs(n)
        tau = [np.sum(f * np.cos(lay.direction)), np.sum(f * np.sin(lay.direction)),
               np.sum(np.asarray(lay.x) * f * np.sin(lay.direction)
                      - np.asarray(lay.y) * f * np.cos(lay.direction))]
        got = SHIP.model.derivative(0.0, _to3(x6), tau, SHIP.params)
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("step", [(10.0, 0.0, 0.0), (0.0, 10.0, 0.0), (0.0, 0.0, 10.0),
                                  (4.0, 4.0, 50.0)])
def test_dp_step_responses_equal_pvs(step):
    """Set-point steps (x_d [m], y_d [m], ψ_d [deg]) from rest, 150 s: positions within 1e-6 m
    and heading within 1e-8 rad of PVS's (the allocation's slack, here ρ = 1e9, is what
    differs: with the default ρ = 1e6 the difference is about 1e-4 m on a 10 m step)."""
    vehicle = supply("DPcontrol", *step, 0.0, 0.0)
    x = np.zeros(12)
    rows = [_to3(x)]
    for _ in range(int(round(150.0 / DT))):
        n = vehicle.DPcontrol(x[:6].copy(), x[6:].copy(), DT)
        k1 = pvs_rhs(vehicle, x, n)
        k2 = pvs_rhs(vehicle, x + 0.5 * DT * k1, n)
        k3 = pvs_rhs(vehicle, x + 0.5 * DT * k2, n)
        k4 = pvs_rhs(vehicle, x + DT * k3, n)
        x = x + DT / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        rows.append(_to3(x))
    want = np.array(rows)
    nmax = np.array([250.0] * 4 + [160.0] * 2 + [1.0] * 2)
    params = dp_pid_params(SHIP, thruster_weight=tuple((nmax / 160.0) ** 4), slack_weight=1e9)
    res = simulate(Problem(ship="supply", x0=np.zeros(6), t_final=150.0, dt=DT,
                           controller="dp-pid", controller_params=params, actuator="direct",
                           reference={"north": step[0], "east": step[1],
                                      "heading": math.radians(step[2]), "wind_force_x": 0.0,
                                      "wind_force_y": 0.0, "wind_moment_z": 0.0}))
    got = np.stack([res[k][0] for k in SHIP.model.state_labels], axis=1)
    err_pos = np.max(np.abs(got[:, :2] - want[:, :2]))
    err_psi = np.max(np.abs(got[:, 2] - want[:, 2]))
    print(f"step {step}: max position difference {err_pos:.3g} m, heading {err_psi:.3g} rad")
    assert err_pos < 1e-6 and err_psi < 1e-8
    # and the steps were taken: the set-point is reached within 2 % by 150 s
    assert np.allclose(got[-1, :2], step[:2], atol=0.2) \
        and abs(math.degrees(got[-1, 2]) - step[2]) < 0.02 * max(step[2], 1.0)
