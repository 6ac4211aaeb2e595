"""The low-speed 3-DOF model of a dynamically positioned vessel: M ν̇_r + D ν_r = τ + τ_env.

The linear DP model of Fossen (2021), *Handbook of Marine Craft Hydrodynamics and Motion
Control*, 2nd ed., §6.7 (the linear low-speed model, Coriolis and nonlinear damping left out
at station-keeping speeds) and §11.2 (the supply vessel example)::

    η̇ = R(ψ) ν_r + V_c          (η = (x_N, y_E, ψ), V_c the current over ground)
    M ν̇_r + D ν_r = τ + τ_env   (ν_r = (u, v, r) through the water)

with M (rigid body plus added mass) and D (linear damping) constant 3 × 3 matrices about the
body origin, τ the thrusters' generalized force (the model's inputs ``thrust_surge`` [N],
``thrust_sway`` [N], ``thrust_yaw`` [N·m] — what an allocation gives, B f, see
:mod:`seahelm.control.dp_pid`) and τ_env the environment's loads on the disturbance channels
``force_x``, ``force_y``, ``moment_z``. M need not be symmetric nor D (Fossen's supply vessel
has D₂₃ ≠ D₃₂); M must be invertible.

The matrices' elements are parameters (m11 … m33, d11 … d33, SI units): a ship file gives
them with their source.

**Range**: the model is the station-keeping one — linear damping, no Coriolis or nonlinear
terms — identified from a supply vessel under DP (Fossen, Sagatun & Sørensen 1996, Control
Engineering Practice 4(3), 369–376) and stated by Fossen (2021, §6.7) for low-speed
applications (station keeping and low-speed manoeuvring), without a number that was reachable
here. seahelm's limit is :data:`MAX_SPEED` = 2 m/s through the water (Froude number
U/√(gL) = 0.073 for the supply vessel's 76.2 m): a run faster than that warns
(:class:`~seahelm.errors.ValidityRangeWarning`, an error in strict mode) after it is done
(``check_result``), naming the run, the speed and the limit.
The catalog's ``supply`` is Fossen's supply vessel in this model.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from ..errors import ParameterError, warn_validity
from ..parameters import Params, param, signal_indices
from .base import NAV_OUTPUT_UNITS, NAV_OUTPUTS, VesselModel
from .rigid_body import horizontal_velocity

__all__ = ["DpThreeDofParams", "DP_3DOF", "STATES", "INPUTS", "MAX_SPEED", "check_result"]

STATES: tuple[str, ...] = ("north", "east", "heading", "surge_speed", "sway_speed", "yaw_rate")
INPUTS: tuple[str, ...] = ("thrust_surge", "thrust_sway", "thrust_yaw")
DISTURBANCES: tuple[str, ...] = ("force_x", "force_y", "moment_z", "current_north",
                                 "current_east")
OUTPUTS: tuple[str, ...] = NAV_OUTPUTS + ("speed",)

_X = signal_indices(STATES)
_U = signal_indices(INPUTS)
_D = signal_indices(DISTURBANCES)
_Y = signal_indices(OUTPUTS)


@dataclass(frozen=True, kw_only=True)
class DpThreeDofParams(Params):
    """Mass and damping of the low-speed 3-DOF DP model (Fossen 2021, §6.7, §11.2): the
    elements M_ij and D_ij of M = M_RB + M_A and of the linear damping D in (u, v, r) (force
    −D ν_r)."""

    m11: float = param(unit="kg", symbol="M_11", low=0.0, low_inclusive=False,
                       doc="mass (with added mass), row u, column u")
    m12: float = param(0.0, unit="kg", symbol="M_12",
                       doc="mass (with added mass), row u, column v")
    m13: float = param(0.0, unit="kg·m", symbol="M_13",
                       doc="mass (with added mass), row u, column r")
    m21: float = param(0.0, unit="kg", symbol="M_21",
                       doc="mass (with added mass), row v, column u")
    m22: float = param(unit="kg", symbol="M_22", low=0.0, low_inclusive=False,
                       doc="mass (with added mass), row v, column v")
    m23: float = param(0.0, unit="kg·m", symbol="M_23",
                       doc="mass (with added mass), row v, column r")
    m31: float = param(0.0, unit="kg·m", symbol="M_31",
                       doc="mass (with added mass), row r, column u")
    m32: float = param(0.0, unit="kg·m", symbol="M_32",
                       doc="mass (with added mass), row r, column v")
    m33: float = param(unit="kg·m²", symbol="M_33", low=0.0, low_inclusive=False,
                       doc="mass (with added mass), row r, column r")
    d11: float = param(unit="kg/s", symbol="D_11", low=0.0,
                       doc="linear damping, row u, column u")
    d12: float = param(0.0, unit="kg/s", symbol="D_12",
                       doc="linear damping, row u, column v")
    d13: float = param(0.0, unit="kg·m/s", symbol="D_13",
                       doc="linear damping, row u, column r")
    d21: float = param(0.0, unit="kg/s", symbol="D_21",
                       doc="linear damping, row v, column u")
    d22: float = param(unit="kg/s", symbol="D_22", low=0.0,
                       doc="linear damping, row v, column v")
    d23: float = param(0.0, unit="kg·m/s", symbol="D_23",
                       doc="linear damping, row v, column r")
    d31: float = param(0.0, unit="kg·m/s", symbol="D_31",
                       doc="linear damping, row r, column u")
    d32: float = param(0.0, unit="kg·m/s", symbol="D_32",
                       doc="linear damping, row r, column v")
    d33: float = param(unit="kg·m²/s", symbol="D_33", low=0.0,
                       doc="linear damping, row r, column r")

    def __post_init__(self) -> None:
        super().__post_init__()
        if abs(np.linalg.det(self.mass_matrix())) <= 1e-12 * abs(self.m11 * self.m22 * self.m33):
            raise ParameterError("must be invertible [kg, kg·m, kg·m²], got a singular M = "
                                 f"{self.mass_matrix().tolist()}", field="m11", unit="kg")

    def mass_matrix(self) -> np.ndarray:
        """M (3 × 3) [kg, kg·m, kg·m²]."""
        return np.array([[self.m11, self.m12, self.m13], [self.m21, self.m22, self.m23],
                         [self.m31, self.m32, self.m33]], dtype=float)

    def damping_matrix(self) -> np.ndarray:
        """D (3 × 3) [kg/s, kg·m/s, kg·m²/s]."""
        return np.array([[self.d11, self.d12, self.d13], [self.d21, self.d22, self.d23],
                         [self.d31, self.d32, self.d33]], dtype=float)


@njit(cache=True)
def _solve3(p, b0, b1, b2):  # pragma: no cover - compiled
    """x of M x = b for the model's M (Cramer's rule)."""
    a, b, c, d, e, f, g, h, i = p.m11, p.m12, p.m13, p.m21, p.m22, p.m23, p.m31, p.m32, p.m33
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    x0 = (b0 * (e * i - f * h) - b * (b1 * i - f * b2) + c * (b1 * h - e * b2)) / det
    x1 = (a * (b1 * i - f * b2) - b0 * (d * i - f * g) + c * (d * b2 - b1 * g)) / det
    x2 = (a * (e * b2 - b1 * h) - b * (d * b2 - b1 * g) + b0 * (d * h - e * g)) / det
    return x0, x1, x2


@njit(cache=True)
def dp_3dof_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    su, sv, sr = x[_X.surge_speed], x[_X.sway_speed], x[_X.yaw_rate]
    fx = u[_U.thrust_surge] + d[_D.force_x] - (p.d11 * su + p.d12 * sv + p.d13 * sr)
    fy = u[_U.thrust_sway] + d[_D.force_y] - (p.d21 * su + p.d22 * sv + p.d23 * sr)
    mz = u[_U.thrust_yaw] + d[_D.moment_z] - (p.d31 * su + p.d32 * sv + p.d33 * sr)
    a0, a1, a2 = _solve3(p, fx, fy, mz)
    north, east = horizontal_velocity(su, sv, x[_X.heading], d[_D.current_north],
                                      d[_D.current_east])
    dx[_X.north] = north
    dx[_X.east] = east
    dx[_X.heading] = sr
    dx[_X.surge_speed] = a0
    dx[_X.sway_speed] = a1
    dx[_X.yaw_rate] = a2


@njit(cache=True)
def dp_3dof_output(t, x, u, p, y):  # pragma: no cover - compiled
    y[_Y.north] = x[_X.north]
    y[_Y.east] = x[_X.east]
    y[_Y.heading] = x[_X.heading]
    y[_Y.yaw_rate] = x[_X.yaw_rate]
    y[_Y.surge_speed] = x[_X.surge_speed]
    y[_Y.sway_speed] = x[_X.sway_speed]
    y[_Y.speed] = np.sqrt(x[_X.surge_speed] ** 2 + x[_X.sway_speed] ** 2)


#: Speed through the water [m/s] above which a run warns (the module's Range: seahelm's).
MAX_SPEED = 2.0


def check_result(result: Any) -> None:
    """Warn if a run's speed through the water exceeded :data:`MAX_SPEED` (module docstring).

    Parameters
    ----------
    result : SimResult
        Runs of the model, finished (:func:`~seahelm.simulation.engine.simulate`) or as far as
        they were stepped (:meth:`~seahelm.simulation.stepping.Simulator.result`; the records
        not reached yet are not looked at, nor are diverged runs).
    """
    u, v = np.asarray(result["surge_speed"]), np.asarray(result["sway_speed"])
    speed = np.sqrt(u * u + v * v)
    # (diverged runs and the records a stepped result has not reached yet, NaN, count as 0)
    speed = np.where((np.asarray(result.status)[:, None] == 0) & np.isfinite(speed), speed, 0.0)
    peak = speed.max(axis=1) if speed.size else np.zeros(0)
    over = np.flatnonzero(peak > MAX_SPEED)
    if over.size:
        i = int(over[np.argmax(peak[over])])
        warn_validity(
            f"dp-3dof (the low-speed DP model, Fossen 2021 §6.7) used outside its range: "
            f"{over.size} run(s) faster than {MAX_SPEED:g} m/s through the water, run {i} "
            f"at {peak[i]:.3g} m/s (seahelm's limit for station keeping and low-speed "
            "manoeuvring)")


@njit(cache=True)
def dp_3dof_motion(x, p):  # pragma: no cover - compiled
    return x[_X.surge_speed], x[_X.sway_speed], x[_X.heading]


DP_3DOF = VesselModel(
    name="dp-3dof",
    description="low-speed 3-DOF DP model M ν̇ + D ν = τ (Fossen 2021, §6.7, §11.2), inputs "
    "the thrusters' generalized force",
    params_type=DpThreeDofParams,
    state_labels=STATES,
    state_units=("m", "m", "rad", "m/s", "m/s", "rad/s"),
    input_labels=INPUTS,
    input_units=("N", "N", "N·m"),
    disturbance_labels=DISTURBANCES,
    disturbance_units=("N", "N", "N·m", "m/s", "m/s"),
    rhs=dp_3dof_rhs,
    output=dp_3dof_output,
    output_labels=OUTPUTS,
    output_units=NAV_OUTPUT_UNITS + ("m/s",),
    motion=dp_3dof_motion,
    check_result=check_result,
)
