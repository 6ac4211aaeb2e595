"""seahelm's Otter beside PythonVehicleSimulator itself (skipped without a PVS snapshot).

Set ``SEAHELM_PVS_SOURCE`` to a directory holding the package ``python_vehicle_simulator``
(cybergalactic/PythonVehicleSimulator, ``src/``). PVS's ``dynamics`` is evaluated as a
right-hand side (``sampleTime = 1``) and integrated here with RK4 at the step seahelm takes;
nothing of PVS is copied into seahelm.
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
from python_vehicle_simulator.vehicles.otter import otter  # noqa: E402

from seahelm.simulation.engine import simulate  # noqa: E402
from seahelm.simulation.problem import Problem  # noqa: E402
from seahelm.vessels.six_dof.otter import OTTER, otter_params  # noqa: E402

P = otter_params()
DT = 0.02


def pvs_rhs(vehicle, x, command):
    eta, nu, n = x[:6].copy(), x[6:12].copy(), x[12:14].copy()
    nu1, n1 = vehicle.dynamics(eta.copy(), nu.copy(), n.copy(), np.asarray(command, float), 1.0)
    return np.concatenate([attitudeEuler(eta.copy(), nu, 1.0) - eta, nu1 - nu, n1 - n])


def pvs_rk4(vehicle, t_final, control):
    x = np.zeros(14)
    out = [x]
    for k in range(int(round(t_final / DT))):
        u = control(x)
        k1 = pvs_rhs(vehicle, x, u)
        k2 = pvs_rhs(vehicle, x + 0.5 * DT * k1, u)
        k3 = pvs_rhs(vehicle, x + 0.5 * DT * k2, u)
        k4 = pvs_rhs(vehicle, x + DT * k3, u)
        x = x + DT / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        out.append(x)
    return np.array(out)


def seahelm_run(t_final, **kw):
    ds = simulate(Problem(ship="otter", x0=np.zeros(14), t_final=t_final, dt=DT,
                          actuator="direct", integrator="rk4", **kw)).to_xarray()
    return np.stack([ds[k].values[0] for k in OTTER.state_labels], axis=1)


def test_the_derivative_equals_pvs_at_random_states():
    rng = np.random.default_rng(0)
    vehicle = otter()
    for _ in range(20):
        x = np.concatenate([rng.normal(size=6) * [5, 5, 0.05, 0.1, 0.1, 2],
                            rng.normal(size=6) * [1, 0.3, 0.1, 0.2, 0.2, 0.3],
                            rng.uniform(-90, 100, size=2)])
        want = pvs_rhs(vehicle, x, x[12:])
        got = OTTER.derivative(0.0, x, x[12:], P)
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("case", ["full thrust", "heading step", "turn"])
def test_runs_equal_pvs(case):
    nmax = P.thruster_max_speed[0]
    if case == "full thrust":
        want = pvs_rk4(otter(), 30.0, lambda x: [nmax, nmax])
        got = seahelm_run(30.0, reference={"propeller_port_speed_command": nmax,
                                           "propeller_starboard_speed_command": nmax})
    elif case == "heading step":
        vehicle = otter("headingAutopilot", 100.0, 0.0, 0.0, 120.0)
        want = pvs_rk4(vehicle, 60.0, lambda x: vehicle.headingAutopilot(x[:6], x[6:12], DT))
        got = seahelm_run(60.0, controller="thrust-heading",
                          reference={"heading": math.radians(100.0), "surge_force": 120.0})
    else:
        want = pvs_rk4(otter(), 200.0, lambda x: [100.0, 50.0])
        got = seahelm_run(200.0, reference={"propeller_port_speed_command": 100.0,
                                            "propeller_starboard_speed_command": 50.0})
    scale = np.maximum(np.abs(want).max(axis=0), 1e-9)
    assert (np.abs(got - want).max(axis=0) / scale).max() < 1e-6
