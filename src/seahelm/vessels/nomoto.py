"""Nomoto steering models, first and second order, with Norrbin's nonlinear manoeuvring term.

First order (Nomoto et al., 1957)::

    T ṙ + H_N(r) = K (δ + δ_d)

Second order::

    T1 T2 r̈ + (T1 + T2) ṙ + H_N(r) = K (δ + δ_d) + K T3 δ̇

with Norrbin's (1963) manoeuvring characteristic H_N(r) = r + n3 r³ (n3 = 0 gives the linear
models; n3 > 0 makes the steady turning rate saturate as |δ| grows). The second-order model is
realised without the rudder rate δ̇ through the auxiliary state ξ = ṙ − a δ, a = K T3/(T1 T2)::

    ṙ = ξ + a δ
    ξ̇ = [K (δ + δ_d) − (T1 + T2) ṙ − H_N(r)] / (T1 T2)

so that any rudder signal, also a discontinuous one, can drive it.

Kinematics at constant forward speed U with a sway velocity v_d (e.g. a wind or current drift)::

    ẋ_N = U cos ψ − v_d sin ψ,   ẏ_E = U sin ψ + v_d cos ψ,   ψ̇ = r

Disturbances (sampled on the simulation grid): the equivalent rudder angle δ_d [rad] — the
steady rudder angle that would cancel the wind and wave yaw moments (Fossen, 2021, §7.1; Lvov,
2014, eq. (12)-(14), there called δ_k) — and the sway drift velocity v_d [m/s].

References
----------
Nomoto, K., Taguchi, T., Honda, K., Hirano, S. (1957). On the steering qualities of ships.
Norrbin, N. H. (1963). On the design and analysis of the zig-zag test on base of quasi-linear
frequency response. Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion
Control, 2nd ed., §7.1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import Params, param
from .base import VesselModel

__all__ = ["Nomoto1Params", "Nomoto2Params", "NOMOTO1", "NOMOTO2"]


@dataclass(frozen=True, kw_only=True)
class Nomoto1Params(Params):
    """First-order Nomoto model with Norrbin term (SI units)."""

    gain: float = param(unit="1/s", symbol="K", low=0.0, low_inclusive=False,
                        doc="Nomoto gain: steady yaw rate per rudder angle")
    time_constant: float = param(unit="s", symbol="T", low=0.0, low_inclusive=False,
                                 doc="Nomoto time constant")
    speed: float = param(unit="m/s", symbol="U", low=0.0, doc="forward speed")
    length: float = param(100.0, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="length between perpendiculars (for plots and scaling)")
    norrbin_n3: float = param(0.0, unit="s²", symbol="n3", low=0.0,
                              doc="Norrbin cubic coefficient in H_N(r) = r + n3 r³")


@dataclass(frozen=True, kw_only=True)
class Nomoto2Params(Params):
    """Second-order Nomoto model with Norrbin term (SI units)."""

    gain: float = param(unit="1/s", symbol="K", low=0.0, low_inclusive=False,
                        doc="Nomoto gain: steady yaw rate per rudder angle")
    t1: float = param(unit="s", symbol="T1", low=0.0, low_inclusive=False, doc="time constant T1")
    t2: float = param(unit="s", symbol="T2", low=0.0, low_inclusive=False, doc="time constant T2")
    t3: float = param(unit="s", symbol="T3", low=0.0, doc="zero time constant T3")
    speed: float = param(unit="m/s", symbol="U", low=0.0, doc="forward speed")
    length: float = param(100.0, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="length between perpendiculars (for plots and scaling)")
    norrbin_n3: float = param(0.0, unit="s²", symbol="n3", low=0.0,
                              doc="Norrbin cubic coefficient in H_N(r) = r + n3 r³")

    def equivalent_first_order(self) -> Nomoto1Params:
        """The first-order model with T = T1 + T2 − T3 (Nomoto's approximation)."""
        return Nomoto1Params(
            gain=self.gain,
            time_constant=self.t1 + self.t2 - self.t3,
            speed=self.speed,
            length=self.length,
            norrbin_n3=self.norrbin_n3,
        )


@njit(cache=True)
def nomoto1_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    gain, tc, speed, n3 = p[0], p[1], p[2], p[4]
    psi = x[2]
    r = x[3]
    delta_d = d[0] if d.shape[0] > 0 else 0.0
    v = d[1] if d.shape[0] > 1 else 0.0
    c = math.cos(psi)
    s = math.sin(psi)
    dx[0] = speed * c - v * s
    dx[1] = speed * s + v * c
    dx[2] = r
    dx[3] = (gain * (u[0] + delta_d) - (r + n3 * r * r * r)) / tc


@njit(cache=True)
def nomoto1_output(t, x, u, p, y):  # pragma: no cover - compiled
    y[0] = x[0]
    y[1] = x[1]
    y[2] = x[2]
    y[3] = x[3]
    y[4] = p[2]
    y[5] = 0.0


@njit(cache=True)
def nomoto2_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    gain, t1, t2, t3, speed, n3 = p[0], p[1], p[2], p[3], p[4], p[6]
    psi = x[2]
    r = x[3]
    xi = x[4]
    delta = u[0]
    delta_d = d[0] if d.shape[0] > 0 else 0.0
    v = d[1] if d.shape[0] > 1 else 0.0
    c = math.cos(psi)
    s = math.sin(psi)
    t12 = t1 * t2
    rdot = xi + gain * t3 / t12 * delta
    dx[0] = speed * c - v * s
    dx[1] = speed * s + v * c
    dx[2] = r
    dx[3] = rdot
    dx[4] = (gain * (delta + delta_d) - (t1 + t2) * rdot - (r + n3 * r * r * r)) / t12


@njit(cache=True)
def nomoto2_output(t, x, u, p, y):  # pragma: no cover - compiled
    y[0] = x[0]
    y[1] = x[1]
    y[2] = x[2]
    y[3] = x[3]
    y[4] = p[4]
    y[5] = 0.0


_DIST = ("rudder_disturbance", "sway_velocity")
_DIST_UNITS = ("rad", "m/s")

NOMOTO1 = VesselModel(
    name="nomoto1",
    description="first-order Nomoto steering model with Norrbin term, constant speed",
    params_type=Nomoto1Params,
    state_labels=("north", "east", "heading", "yaw_rate"),
    state_units=("m", "m", "rad", "rad/s"),
    input_labels=("rudder_angle",),
    input_units=("rad",),
    disturbance_labels=_DIST,
    disturbance_units=_DIST_UNITS,
    rhs=nomoto1_rhs,
    output=nomoto1_output,
)

NOMOTO2 = VesselModel(
    name="nomoto2",
    description="second-order Nomoto steering model with Norrbin term, constant speed",
    params_type=Nomoto2Params,
    state_labels=("north", "east", "heading", "yaw_rate", "yaw_aux"),
    state_units=("m", "m", "rad", "rad/s", "rad/s"),
    input_labels=("rudder_angle",),
    input_units=("rad",),
    disturbance_labels=_DIST,
    disturbance_units=_DIST_UNITS,
    rhs=nomoto2_rhs,
    output=nomoto2_output,
)
