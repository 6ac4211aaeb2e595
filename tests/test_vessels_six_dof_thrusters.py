"""Thruster configuration and allocation by weighted pseudo-inverse (seahelm.vessels.six_dof)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.vessels.six_dof.otter import otter_params
from seahelm.vessels.six_dof.params import SixDofParams
from seahelm.vessels.six_dof.thrusters import Allocation, allocate, configuration_matrix

OTTER = otter_params()


def test_otter_allocation_is_the_published_two_by_two_inverse():
    # Fossen's Otter: [τ_X, τ_N] = k_pos [[1, 1], [−y₁, −y₂]] (n₁|n₁|, n₂|n₂|), y = ∓0.395 m
    k, y1, y2 = 0.02216 / 2, -0.395, 0.395
    binv = np.linalg.inv(k * np.array([[1.0, 1.0], [-y1, -y2]]))
    for tau in ([120.0, 5.0], [60.0, -12.0], [100.0, 0.0]):
        u = binv @ tau
        want = np.sign(u) * np.sqrt(np.abs(u))
        np.testing.assert_allclose(allocate(OTTER, tau, ("surge", "yaw")), want, rtol=1e-12)


def three_thrusters():
    return SixDofParams(thruster_count=3.0, thruster_x=(-0.4, -0.4, 0.45, 0.0),
                        thruster_y=(-0.3, 0.3, 0.0, 0.0),
                        thruster_direction=(0.0, 0.0, math.pi / 2, 0.0),
                        thruster_k_pos=(0.01, 0.01, 0.005, 0.0),
                        thruster_k_neg=(0.008, 0.008, 0.005, 0.0),
                        thruster_max_speed=(200.0, 200.0, 200.0, 100.0),
                        thruster_min_speed=(-200.0, -200.0, -200.0, -100.0))


def test_configuration_matrix_of_a_tunnel_thruster():
    b = configuration_matrix(three_thrusters())
    # a tunnel thruster at x = 0.45 m pointing to starboard: sway force 1, yaw moment 0.45
    np.testing.assert_allclose(b[:, 2], [0.0, 1.0, 0.0, 0.0, 0.0, 0.45], atol=1e-15)
    np.testing.assert_allclose(b[:, 0], [1.0, 0.0, 0.0, 0.0, 0.0, 0.3], atol=1e-15)


def test_weighted_pseudo_inverse_meets_the_forces_at_least_weighted_cost():
    p = three_thrusters()
    w = np.array([1.0, 2.0, 4.0])
    alloc = Allocation(p, ("surge", "sway", "yaw"), weights=w)
    tau = np.array([3.0, 0.5, 0.2])
    f = alloc.thrusts(tau)
    np.testing.assert_allclose(alloc.matrix @ f, tau, atol=1e-12)
    # two DOF with three thrusters: f is the least f^T W f among all solutions
    alloc2 = Allocation(p, ("surge", "yaw"), weights=w)
    f2 = alloc2.thrusts(tau[[0, 2]])
    null = np.linalg.svd(alloc2.matrix)[2][-1]
    for step in (1e-3, -1e-3, 0.1):
        g = f2 + step * null
        np.testing.assert_allclose(alloc2.matrix @ g, tau[[0, 2]], atol=1e-12)
        assert g @ (w * g) > f2 @ (w * f2)


def test_allocation_saturates_each_shaft_speed():
    n = allocate(OTTER, [1.0e4, 0.0], ("surge", "yaw"))
    np.testing.assert_allclose(n, [OTTER.thruster_max_speed[0]] * 2)


def test_fewer_effective_thrusters_than_dof_is_refused():
    with pytest.raises(ParameterError, match=r"needs 3 effective thrusters, the craft has 2"):
        Allocation(OTTER, ("surge", "sway", "yaw"))


@pytest.mark.parametrize("kw, match", [({"dofs": ("surge", "warp")}, "`dofs` must name"),
                                       ({"dofs": ("surge",), "weights": [1.0, 0.0]},
                                        r"`weights` must be 2 numbers > 0")])
def test_bad_allocation_input(kw, match):
    with pytest.raises(ParameterError, match=match):
        Allocation(OTTER, **kw)


def azimuth_craft():
    return SixDofParams(mass=100.0, thruster_count=1.0, thruster_x=(-0.4, 0.0, 0.0, 0.0),
                        thruster_azimuthing=(1.0, 0.0, 0.0, 0.0),
                        thruster_k_pos=(0.01, 0.0, 0.0, 0.0), thruster_k_neg=(0.01, 0.0, 0.0, 0.0),
                        thruster_max_turn_rate=(0.5, 1e9, 1e9, 1e9),
                        thruster_turn_time_constant=(0.2, 1.0, 1.0, 1.0),
                        thruster_max_acceleration=(30.0, 1e9, 1e9, 1e9))


def test_an_azimuth_thruster_pushes_along_its_angle_state_with_limited_turn_rate():
    from seahelm.vessels.six_dof.model import six_dof_model

    p = azimuth_craft()
    model = six_dof_model("azimuth-test", "one azimuth thruster", SixDofParams,
                          thrusters=("pod",), azimuthing=("pod",))
    assert model.state_labels[12:] == ("pod_speed", "pod_angle")
    assert model.input_labels == ("pod_speed_command", "pod_angle_command")
    x = model.initial_state(pod_speed=50.0, pod_angle=math.pi / 2)
    dx = model.derivative(0.0, x, [50.0, math.pi / 2], p)
    thrust = 0.01 * 50.0**2
    # pointing to starboard at x = −0.4 m: sway force T, yaw moment −0.4 T
    tau = np.array([0.0, thrust, 0.0, 0.0, 0.0, -0.4 * thrust])
    np.testing.assert_allclose(dx[6:12], np.linalg.solve(p.mass_matrix, tau), atol=1e-12)
    # the angle follows its command at most at 0.5 rad/s, the shaft at most 30 rad/s²
    dx = model.derivative(0.0, x, [100.0, -math.pi / 2], p)
    assert dx[13] == pytest.approx(-0.5)
    assert dx[12] == pytest.approx(30.0)
