"""The rigid-body part of the 3-DOF models, written once: kinematics, the mass-matrix solve and
the outputs they begin with (:data:`PLANAR_OUTPUTS`, :func:`write_planar_outputs`).

Every surface-ship model in the horizontal plane moves its reference point the same way, and
every model with a coupled sway–yaw mass matrix solves the same 2×2 system; the models
(:mod:`~seahelm.vessels.mmg`, :mod:`~seahelm.vessels.mmg_four_quadrant`,
:mod:`~seahelm.vessels.mariner`, :mod:`~seahelm.vessels.container`,
:mod:`~seahelm.vessels.nomoto`) call these functions instead of each writing them out.

Kinematics (north-east-down axes, heading ψ clockwise from north; the 3-DOF kinematics of
Fossen 2021, *Handbook of Marine Craft Hydrodynamics and Motion Control*, 2nd ed., ch. 2)::

    ẋ_N = u cos ψ − v sin ψ + V_c,N,     ẏ_E = u sin ψ + v cos ψ + V_c,E

with (u, v) the velocity through the water of the reference point in body axes and
(V_c,N, V_c,E) a uniform current over ground (zero when there is none).

Equations of motion about a midship origin with the centre of gravity at x_G (Yasukawa &
Yoshimura 2015, "motion equations")::

    (m + m_x) u̇ − (m + m_y) v r − x_G m r²     = X
    (m + m_y) v̇ + (m + m_x) u r + x_G m ṙ       = Y
    (I_zG + x_G² m + J_z) ṙ + x_G m (v̇ + u r)   = N

solved exactly: the surge equation directly, the sway–yaw coupling by Cramer's rule
(:func:`cramer_2x2`).

Each function performs the floating-point operations of the code it replaced, in the same
order, so the models' numbers are unchanged, bit for bit (``tests/test_vessels_rigid_body.py``;
the crash-stop and IMO outputs compared before and after).

References
----------
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed. Wiley.
"""
from __future__ import annotations

import math

from numba import njit

from ..parameters import signal_indices

__all__ = ["horizontal_velocity", "cramer_2x2", "midship_accelerations", "PLANAR_OUTPUTS",
           "PLANAR_OUTPUT_UNITS", "write_planar_outputs"]

#: The outputs a 3-DOF surface model with sway begins with (``mmg`` and its family, ``mariner``,
#: ``container``), in this order: :func:`write_planar_outputs` writes them.
PLANAR_OUTPUTS: tuple[str, ...] = ("north", "east", "heading", "yaw_rate", "surge_speed",
                                   "sway_speed", "speed", "drift_angle")
PLANAR_OUTPUT_UNITS: tuple[str, ...] = ("m", "m", "rad", "rad/s", "m/s", "m/s", "m/s", "rad")
_Y = signal_indices(PLANAR_OUTPUTS)


@njit(cache=True)
def horizontal_velocity(u, v, psi, current_north, current_east):  # pragma: no cover - compiled
    """Velocity over ground (ẋ_N, ẏ_E) [m/s] of a point moving at (u, v) through the water.

    Parameters
    ----------
    u, v : float
        Surge and sway velocity through the water in body axes [m/s].
    psi : float
        Heading ψ [rad], clockwise from north.
    current_north, current_east : float
        Uniform current over ground [m/s].

    Returns
    -------
    (float, float)
        ẋ_N = u cos ψ − v sin ψ + V_c,N and ẏ_E = u sin ψ + v cos ψ + V_c,E [m/s].
    """
    c = math.cos(psi)
    s = math.sin(psi)
    return u * c - v * s + current_north, u * s + v * c + current_east


@njit(cache=True)
def cramer_2x2(a11, a12, a21, a22, b1, b2):  # pragma: no cover - compiled
    """Cramer's rule for [[a11, a12], [a21, a22]] [x1, x2] = [b1, b2].

    Parameters
    ----------
    a11, a12, a21, a22 : float
        The matrix (a mass matrix: its determinant is not zero).
    b1, b2 : float
        The right-hand side.

    Returns
    -------
    (float, float, float)
        Δ_1 = a22 b1 − a12 b2, Δ_2 = a11 b2 − a21 b1 and Δ = a11 a22 − a12 a21, so that
        x1 = Δ_1/Δ and x2 = Δ_2/Δ (a model that scales the solution divides once, by Δ
        times its scale).
    """
    return a22 * b1 - a12 * b2, a11 * b2 - a21 * b1, a11 * a22 - a12 * a21


@njit(cache=True)
def midship_accelerations(X, Y, N, u, v, r, m, m_x, m_y, I_zG, J_z, x_G):  # pragma: no cover
    """(u̇, v̇, ṙ) of the midship-origin equations of motion (module docstring).

    Parameters
    ----------
    X, Y : float
        Surge and sway force [N] (everything but the rigid-body and added-mass inertia).
    N : float
        Yaw moment about midship [N·m].
    u, v, r : float
        Surge and sway velocity of the midship point [m/s], yaw rate [rad/s].
    m, m_x, m_y : float
        Mass and the added masses in surge and sway [kg].
    I_zG, J_z : float
        Yaw moment of inertia about the centre of gravity and added moment of inertia [kg·m²].
    x_G : float
        Longitudinal position of the centre of gravity from midship [m].

    Returns
    -------
    (float, float, float)
        u̇ [m/s²], v̇ [m/s²], ṙ [rad/s²].
    """
    du = (X + (m + m_y) * v * r + x_G * m * r * r) / (m + m_x)
    # [[m + m_y, x_G m], [x_G m, I_zG + x_G² m + J_z]] [v̇, ṙ] = [b1, b2]
    a12 = x_G * m
    d1, d2, det = cramer_2x2(m + m_y, a12, a12, I_zG + x_G * x_G * m + J_z,
                             Y - (m + m_x) * u * r, N - x_G * m * u * r)
    return du, d1 / det, d2 / det


@njit(cache=True)
def write_planar_outputs(y, north, east, heading, yaw_rate, surge_speed, sway_speed, speed,
                         drift_angle):  # pragma: no cover - compiled
    """Write the :data:`PLANAR_OUTPUTS` (the first eight outputs) of one run into ``y``.

    Parameters
    ----------
    y : numpy.ndarray
        The run's outputs; its first eight entries are written.
    north, east : float
        Position [m].
    heading : float
        Heading ψ [rad].
    yaw_rate : float
        Yaw rate r [rad/s].
    surge_speed, sway_speed, speed : float
        u, v and U through the water [m/s].
    drift_angle : float
        Drift angle β [rad].
    """
    y[_Y.north] = north
    y[_Y.east] = east
    y[_Y.heading] = heading
    y[_Y.yaw_rate] = yaw_rate
    y[_Y.surge_speed] = surge_speed
    y[_Y.sway_speed] = sway_speed
    y[_Y.speed] = speed
    y[_Y.drift_angle] = drift_angle
