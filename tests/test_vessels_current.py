"""A uniform current on the 3-DOF models (Mariner, MMG) and on Nomoto's kinematics: the
velocity states are relative to the water, so with a constant current the velocities are those of calm water and the track is
the calm-water track carried by the current, x(t) = x_0(t) + V_c t (Fossen 2021, Property 10.1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.maneuvers.common import steady_approach
from seahelm.simulation.engine import simulate
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR, MARINER_SERVO
from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO, MMG
from seahelm.ships import catalog
from seahelm.vessels.nomoto import NOMOTO2


@pytest.mark.parametrize("model, params, servo, speed", [
    (MARINER, MARINER_NONLINEAR, MARINER_SERVO, 7.7175),
    (MMG, KVLCC2_L7, KVLCC2_L7_SERVO, 1.179),
], ids=["mariner", "kvlcc2-l7"])
def test_constant_current_carries_the_calm_water_track(model, params, servo, speed):
    app = steady_approach(model, params, speed)
    ref = {"rudder_command": math.radians(20.0)}
    if app.rps is not None:
        ref["propeller_rps"] = app.rps
    current = np.array([[0.0, 0.0], [0.3 * speed, -0.2 * speed], [-0.5 * speed, 0.4 * speed]])
    dist = np.zeros((3, 1, 5))
    dist[:, 0, 3:] = current  # current_north, current_east
    res = simulate(model, params, app.state, t_final=200.0, dt=0.1, actuator=RUDDER_SERVO,
                   actuator_params=servo, actuator_x0=[app.rudder], reference=ref,
                   disturbance=dist)
    assert res.ok.all()
    labels = list(res.state_labels)
    vel = [labels.index(n) for n in model.state_labels[:3]]
    np.testing.assert_array_equal(res.state[1:, :, vel], np.broadcast_to(
        res.state[:1, :, vel], res.state[1:, :, vel].shape))  # velocities through the water
    t = res.time
    for i in (1, 2):
        for k, name in enumerate(("north", "east")):
            j = labels.index(name)
            drift = res.state[i, :, j] - res.state[0, :, j]
            np.testing.assert_allclose(drift, current[i, k] * t, rtol=1e-9, atol=1e-9 * speed)
    # and the heading turns as in calm water: the current changes the track, not the turn
    j = labels.index("heading")
    np.testing.assert_array_equal(res.state[2, :, j], res.state[0, :, j])


def test_constant_current_carries_the_nomoto_track():
    """Nomoto with kinematics: the yaw dynamics are untouched, the position drifts by V_c t."""
    params = catalog.get("mariner-nomoto2").params
    current = np.array([[0.0, 0.0], [1.5, -0.7], [-2.0, 2.5]])
    dist = np.zeros((3, 1, 4))
    dist[:, 0, 2:] = current
    res = simulate(NOMOTO2, params, np.zeros(5), t_final=300.0, dt=0.1, actuator=RUDDER_SERVO,
                   reference={"rudder_command": math.radians(15.0)}, disturbance=dist)
    assert res.ok.all()
    labels = list(res.state_labels)
    for name in ("heading", "yaw_rate", "yaw_aux", "rudder_angle"):
        j = labels.index(name)
        np.testing.assert_array_equal(res.state[1:, :, j], np.broadcast_to(
            res.state[:1, :, j], res.state[1:, :, j].shape))
    for i in (1, 2):
        for k, name in enumerate(("north", "east")):
            j = labels.index(name)
            np.testing.assert_allclose(res.state[i, :, j] - res.state[0, :, j],
                                       current[i, k] * res.time, rtol=1e-9, atol=1e-8)


def test_current_channels_are_declared_with_units():
    for model in (MARINER, MMG, NOMOTO2):
        d = dict(zip(model.disturbance_labels, model.disturbance_units))
        assert d["current_north"] == "m/s" and d["current_east"] == "m/s"
