"""Regular roll and pitch, mount-point kinematics and the disturbance moment.

Sushchenko & Lutsko (2010), "regular rolling" section: for a deterministic study the roll
(and pitch) angle is a harmonic x = ϑ sin ω_x t, felt by the stabilised platform through its
rate ẋ = ϑ ω_x cos ω_x t. A platform mounted at a distance l from the centre of rolling moves
with the tangential velocity v = θ ω l cos ωt and acceleration v̇ = −θ ω² l sin ωt; its total
velocity is V + v (longitudinal motion only). The disturbance moment on the platform is
M = M_st + M_op sign(ω_o), ω_o the external angular rate.

All functions broadcast: parameters of shape (batch,) against times of shape (n_t,) give
arrays of shape (batch, n_t) when called with ``amplitude[:, None]`` etc.; batch axes lead.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative

__all__ = [
    "HarmonicMotion",
    "harmonic_motion",
    "mount_point_kinematics",
    "mount_point_velocity",
    "disturbance_moment",
]


@dataclasses.dataclass(frozen=True)
class HarmonicMotion:
    """Angle, rate and acceleration of a regular roll or pitch motion.

    Attributes
    ----------
    angle : numpy.ndarray
        θ(t) = Θ sin(ωt + φ) [rad].
    rate : numpy.ndarray
        θ̇(t) = Θω cos(ωt + φ) [rad/s].
    acceleration : numpy.ndarray
        θ̈(t) = −Θω² sin(ωt + φ) [rad/s²].
    """

    angle: np.ndarray
    rate: np.ndarray
    acceleration: np.ndarray


def harmonic_motion(
    t: ArrayLike, amplitude: ArrayLike, frequency: ArrayLike, phase: ArrayLike = 0.0
) -> HarmonicMotion:
    """Regular roll or pitch θ = Θ sin(ωt + φ) with its rate and acceleration.

    Sushchenko & Lutsko (2010): x_b = ϑ sin ω_x t (roll), x_k = γ sin ω_x t (pitch) and the
    rates ϑω_x cos ω_x t, γω_x cos ω_x t that act on the stabilisation system.

    Parameters
    ----------
    t : array_like
        Time [s].
    amplitude : array_like
        Θ (ϑ for roll, γ for pitch) [rad], ≥ 0.
    frequency : array_like
        ω_x [rad/s], ≥ 0.
    phase : array_like
        φ [rad].

    Returns
    -------
    HarmonicMotion
        Arrays broadcast over the inputs.

    Raises
    ------
    ParameterError
        If an input is not finite or ``amplitude``/``frequency`` is negative.
    """
    tt = as_float_array("t", t, "s")
    amp = as_float_array("amplitude", amplitude, "rad")
    check_nonnegative("amplitude", amp, "rad")
    w = as_float_array("frequency", frequency, "rad/s")
    check_nonnegative("frequency", w, "rad/s")
    ph = as_float_array("phase", phase, "rad")
    arg = w * tt + ph
    s, c = np.sin(arg), np.cos(arg)
    return HarmonicMotion(angle=amp * s, rate=amp * w * c, acceleration=-amp * w**2 * s)


def mount_point_velocity(rate: ArrayLike, lever_arm: ArrayLike) -> np.ndarray:
    """Tangential velocity v = l θ̇ [m/s] of a point at distance l from the centre of rolling.

    Works for any angular-rate signal (regular or from a shaping filter).

    Parameters
    ----------
    rate : array_like
        θ̇ [rad/s].
    lever_arm : array_like
        l [m], ≥ 0.
    """
    r = as_float_array("rate", rate, "rad/s")
    arm = as_float_array("lever_arm", lever_arm, "m")
    check_nonnegative("lever_arm", arm, "m")
    return arm * r


def mount_point_kinematics(
    t: ArrayLike,
    amplitude: ArrayLike,
    frequency: ArrayLike,
    lever_arm: ArrayLike,
    *,
    ship_speed: ArrayLike = 0.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Velocity and acceleration of a mount point under regular roll.

    v = θ ω l cos ωt, v̇ = −θ ω² l sin ωt and the total velocity V + v
    (Sushchenko & Lutsko (2010), mount-point equations; tangential components only).

    Parameters
    ----------
    t : array_like
        Time [s].
    amplitude : array_like
        Roll amplitude θ [rad], ≥ 0.
    frequency : array_like
        Roll frequency ω [rad/s], ≥ 0.
    lever_arm : array_like
        l, distance from the centre of rolling [m], ≥ 0.
    ship_speed : array_like
        V, speed of the ship [m/s].

    Returns
    -------
    velocity, acceleration, total_velocity : numpy.ndarray
        v [m/s], v̇ [m/s²], V + v [m/s].
    """
    motion = harmonic_motion(t, amplitude, frequency)
    arm = as_float_array("lever_arm", lever_arm, "m")
    check_nonnegative("lever_arm", arm, "m")
    speed = as_float_array("ship_speed", ship_speed, "m/s")
    v = arm * motion.rate
    return v, arm * motion.acceleration, speed + v


def disturbance_moment(
    angular_rate: ArrayLike, steady_moment: ArrayLike, friction_moment: ArrayLike
) -> np.ndarray:
    """Disturbance moment M = M_st + M_op sign(ω_o) [N·m] on the stabilised platform.

    Sushchenko & Lutsko (2010), M_зб = M_ст + M_оп sign ω_o; sign(0) = 0.

    Parameters
    ----------
    angular_rate : array_like
        ω_o, external angular rate acting on the platform (from rolling) [rad/s].
    steady_moment : array_like
        M_st, constant moment [N·m].
    friction_moment : array_like
        M_op, resistance moment of the stabilisation motors [N·m], ≥ 0.
    """
    w = as_float_array("angular_rate", angular_rate, "rad/s")
    m_st = as_float_array("steady_moment", steady_moment, "N m")
    m_op = as_float_array("friction_moment", friction_moment, "N m")
    check_nonnegative("friction_moment", m_op, "N m")
    return m_st + m_op * np.sign(w)
