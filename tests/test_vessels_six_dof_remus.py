"""The REMUS 100 under its depth and heading autopilots against PythonVehicleSimulator, quoted.

Constants from PVS's own REMUS 100 (``vehicles/remus100.py`` and ``lib/control.py`` of
cybergalactic/PythonVehicleSimulator, commit c717e073d7a839dcb5956cf20c595132f1fa249a) run on
identical inputs: ``dynamics`` as a right-hand side (``sampleTime = 1``), RK4 at h = 0.02 s,
``depthHeadingAutopilot`` sampled once per step, from rest at the surface, 1525 rpm
(159.7 rad/s). seahelm agrees with it to 4e-13 relative over the whole runs (docs page
"Marine craft in 6 DOF").
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.vessels.six_dof.remus100 import RPM

DT = 0.02
PVS_DIVE_DEPTH_100S = 26.199960701957675      # z_ref = 30 m, ψ_ref = 0: depth at 100 s [m]
PVS_DIVE_NORTH_200S = 503.962479891           # north at 200 s [m] (printed to 1e-9)
PVS_TURN_HEADING_50S_DEG = 51.75166927634584  # z_ref = 0, ψ_ref = 60°: heading at 50 s


def run(t_final, depth, heading_deg):
    problem = Problem(ship="remus100", x0=np.zeros(15), t_final=t_final, dt=DT,
                      actuator="direct", controller="auv-depth-heading", integrator="rk4",
                      reference={"depth": depth, "heading": math.radians(heading_deg),
                                 "propeller_speed": 1525.0 * RPM})
    return simulate(problem).to_xarray()


def at(ds, name, t):
    return float(ds[name].sel(time=t, method="nearest").values[0])


def test_depth_change_equals_pvs():
    ds = run(200.0, 30.0, 0.0)
    assert at(ds, "depth", 100.0) == pytest.approx(PVS_DIVE_DEPTH_100S, rel=1e-9)
    assert at(ds, "north", 200.0) == pytest.approx(PVS_DIVE_NORTH_200S, abs=1e-8)


def test_heading_step_equals_pvs():
    ds = run(50.0, 0.0, 60.0)
    assert math.degrees(at(ds, "heading", 50.0)) == pytest.approx(PVS_TURN_HEADING_50S_DEG,
                                                                  rel=1e-9)


def test_an_auv_above_the_surface_is_refused():
    x0 = np.zeros(15)
    x0[2] = -1.0
    with pytest.raises(ParameterError, match=r"`depth` must be >= 0 \[m\].*got -1\.0"):
        Problem(ship="remus100", x0=x0, t_final=1.0, dt=DT, actuator="direct")
