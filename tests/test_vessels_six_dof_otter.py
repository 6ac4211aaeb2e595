"""The Otter USV in the engine against PythonVehicleSimulator (PVS), quoted.

The constants below were obtained by running PVS's own Otter model (``vehicles/otter.py``,
``lib/gnc.py``, ``lib/control.py`` of cybergalactic/PythonVehicleSimulator, commit
c717e073d7a839dcb5956cf20c595132f1fa249a) on identical inputs: its ``dynamics`` evaluated as a
right-hand side (``sampleTime = 1``: ν[k+1] − ν[k] = ν̇) and integrated with the classical RK4
at h = 0.02 s, the controller (``headingAutopilot``) sampled once per step — the integration
seahelm does — from rest at the origin. The script is described on the docs page "Marine craft
in 6 DOF"; seahelm agrees with it to 1e-14 relative over whole runs. A test that runs PVS itself
(skipped without the snapshot) is ``test_vessels_six_dof_pvs.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.vessels.six_dof.otter import OTTER_QUATERNION, otter_params

P = otter_params()
NMAX = P.thruster_max_speed[0]
DT = 0.02

# PVS c717e07, RK4 at 0.02 s (module docstring)
PVS_FULL_THRUST_U_10S = 3.218862517085284      # surge speed at t = 10 s [m/s]
PVS_FULL_THRUST_NORTH_30S = 92.42365274925537  # north at t = 30 s [m]
PVS_FULL_THRUST_PITCH_30S_DEG = -2.4166286531126615
PVS_HEADING_STEP_PSI_20S_DEG = 99.43910582632297   # ψ_ref = 100°, τ_X = 120 N
PVS_HEADING_STEP_PSI_60S_DEG = 99.99999274873505
PVS_TURN_YAW_RATE_200S_DEG = 15.895253992959482   # n = (100, 50) rad/s, r at t = 200 s [°/s]


def run(t_final, controller="open-loop", reference=None):
    problem = Problem(ship="otter", x0=np.zeros(14), t_final=t_final, dt=DT,
                      controller=controller, actuator="direct", reference=reference,
                      integrator="rk4")
    return simulate(problem).to_xarray()


def at(ds, name, t):
    return float(ds[name].sel(time=t, method="nearest").values[0])


def test_full_thrust_acceleration_equals_pvs():
    ds = run(30.0, reference={"propeller_port_speed_command": NMAX,
                              "propeller_starboard_speed_command": NMAX})
    assert at(ds, "surge_speed", 10.0) == pytest.approx(PVS_FULL_THRUST_U_10S, rel=1e-9)
    assert at(ds, "north", 30.0) == pytest.approx(PVS_FULL_THRUST_NORTH_30S, rel=1e-9)
    assert math.degrees(at(ds, "pitch", 30.0)) == pytest.approx(PVS_FULL_THRUST_PITCH_30S_DEG,
                                                                rel=1e-9)


def test_heading_step_under_the_autopilot_equals_pvs():
    ds = run(60.0, controller="thrust-heading",
             reference={"heading": math.radians(100.0), "surge_force": 120.0})
    assert math.degrees(at(ds, "heading", 20.0)) == pytest.approx(PVS_HEADING_STEP_PSI_20S_DEG,
                                                                  rel=1e-9)
    assert math.degrees(at(ds, "heading", 60.0)) == pytest.approx(PVS_HEADING_STEP_PSI_60S_DEG,
                                                                  rel=1e-9)


def test_turning_circle_equals_pvs():
    ds = run(200.0, reference={"propeller_port_speed_command": 100.0,
                               "propeller_starboard_speed_command": 50.0})
    assert math.degrees(at(ds, "yaw_rate", 200.0)) == pytest.approx(PVS_TURN_YAW_RATE_200S_DEG,
                                                                    rel=1e-9)


def test_a_quaternion_that_is_not_normalised_is_refused():
    x0 = np.zeros(15)
    x0[3] = 0.9  # |q| = 0.9
    with pytest.raises(ParameterError,
                       match=r"`x0` must hold a unit quaternion .*got length 0\.9 \[-\]") as exc:
        Problem(model=OTTER_QUATERNION, params=P, x0=x0, t_final=1.0, dt=DT, actuator="direct")
    assert exc.value.field == "x0"
