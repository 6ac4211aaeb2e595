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

Course-unstable ships have a positive real pole: T1 < 0 and K < 0 (Nomoto's form holds, with
K/T1 > 0 so that a positive rudder still gives a positive yaw acceleration; Fossen 2021, §7.1,
"a negative T1 implies that the ship is course unstable"). The parameters admit them: K and T1
(T of the first-order model) may be negative, but not zero, and of the same sign. Norrbin's
term as written (H_N = r + n3 r³) is the stable ship's; for T1 < 0 it would destabilise the
turn instead of saturating it, so n3 > 0 with T1 < 0 is refused (the unstable ship's
characteristic, n1 = −1 in Fossen's H_N = n3 r³ + n1 r, is not implemented).

Kinematics at constant forward speed U with a sway velocity v_d (e.g. a wind or current drift)::

    ẋ_N = U cos ψ − v_d sin ψ,   ẏ_E = U sin ψ + v_d cos ψ,   ψ̇ = r

Disturbances (sampled on the simulation grid): the equivalent rudder angle δ_d [rad] — the
steady rudder angle that would cancel the wind and wave yaw moments (Fossen, 2021, §7.1; Lvov,
2014, eq. (12)-(14), there called δ_k) — and the sway drift velocity v_d [m/s].

Outputs: the navigation outputs (:data:`~seahelm.vessels.base.NAV_OUTPUTS`; surge speed U, sway
speed 0 — the drift v_d is an input, not reported) and ``speed`` U.

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

from ..errors import ParameterError
from ..parameters import Params, param, signal_indices
from .base import NAV_OUTPUT_UNITS, NAV_OUTPUTS, VesselModel
from .rigid_body import horizontal_velocity

__all__ = ["Nomoto1Params", "Nomoto2Params", "NOMOTO1", "NOMOTO2"]


def _check_signs(p: Params, time: str) -> None:
    """Course-unstable (T < 0, K < 0) is admitted; zero, or K and T of opposite sign, not."""
    t, k = getattr(p, time), p.gain
    if t == 0.0:
        raise ParameterError(f"must not be 0 [s] (< 0 for a course-unstable ship), got {t!r}",
                             field=time, unit="s", value=t)
    if k == 0.0 or (k > 0) != (t > 0):
        raise ParameterError(
            f"must be nonzero and of the sign of {time} ({t:.6g} s): K/T > 0 (a positive rudder "
            f"gives a positive yaw acceleration; K < 0 with T < 0 for a course-unstable ship), "
            f"got {k!r}", field="gain", unit="1/s", value=k)
    if t < 0 and p.norrbin_n3 > 0:
        raise ParameterError(
            f"must be 0 for a course-unstable ship ({time} = {t:.6g} s < 0): the term r + n3 r³ "
            "is the stable ship's", field="norrbin_n3", unit="s²", value=p.norrbin_n3)


@dataclass(frozen=True, kw_only=True)
class Nomoto1Params(Params):
    """First-order Nomoto model with Norrbin term (SI units)."""

    gain: float = param(unit="1/s", symbol="K",
                        doc="Nomoto gain: steady yaw rate per rudder angle (< 0 with T < 0: "
                            "course-unstable)")
    time_constant: float = param(unit="s", symbol="T",
                                 doc="Nomoto time constant (< 0: course-unstable)")
    speed: float = param(unit="m/s", symbol="U", low=0.0, low_inclusive=False,
                         doc="forward speed (> 0: K and T hold at this U; at rest the rudder "
                             "turns nothing)")
    length: float = param(100.0, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="length between perpendiculars (for plots and scaling)")
    norrbin_n3: float = param(0.0, unit="s²", symbol="n3", low=0.0,
                              doc="Norrbin cubic coefficient in H_N(r) = r + n3 r³")

    def validate(self) -> None:
        """K and T nonzero and of one sign; Norrbin's n3 only for T > 0 (module docstring)."""
        _check_signs(self, "time_constant")

    @property
    def course_unstable(self) -> bool:
        """T < 0: a positive real pole (Fossen 2021, §7.1)."""
        return self.time_constant < 0


@dataclass(frozen=True, kw_only=True)
class Nomoto2Params(Params):
    """Second-order Nomoto model with Norrbin term (SI units)."""

    gain: float = param(unit="1/s", symbol="K",
                        doc="Nomoto gain: steady yaw rate per rudder angle (< 0 with T1 < 0: "
                            "course-unstable)")
    t1: float = param(unit="s", symbol="T1", doc="time constant T1 (< 0: course-unstable)")
    t2: float = param(unit="s", symbol="T2", low=0.0, low_inclusive=False, doc="time constant T2")
    t3: float = param(unit="s", symbol="T3", low=0.0, doc="zero time constant T3")
    speed: float = param(unit="m/s", symbol="U", low=0.0, low_inclusive=False,
                         doc="forward speed (> 0: K and T hold at this U; at rest the rudder "
                             "turns nothing)")
    length: float = param(100.0, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="length between perpendiculars (for plots and scaling)")
    norrbin_n3: float = param(0.0, unit="s²", symbol="n3", low=0.0,
                              doc="Norrbin cubic coefficient in H_N(r) = r + n3 r³")

    def validate(self) -> None:
        """K and T1 nonzero and of one sign; Norrbin's n3 only for T1 > 0 (module docstring)."""
        _check_signs(self, "t1")

    @property
    def course_unstable(self) -> bool:
        """T1 < 0: a positive real pole (Fossen 2021, §7.1)."""
        return self.t1 < 0

    def equivalent_first_order(self) -> Nomoto1Params:
        """The first-order model with T = T1 + T2 − T3 (Nomoto's approximation)."""
        return Nomoto1Params(
            gain=self.gain,
            time_constant=self.t1 + self.t2 - self.t3,
            speed=self.speed,
            length=self.length,
            norrbin_n3=self.norrbin_n3,
        )


NOMOTO1_STATES: tuple[str, ...] = ("north", "east", "heading", "yaw_rate")
NOMOTO2_STATES: tuple[str, ...] = NOMOTO1_STATES + ("yaw_aux",)
INPUTS: tuple[str, ...] = ("rudder_angle",)
#: Rudder-equivalent disturbance, sway velocity through the water, and a uniform current over
#: ground (north, east): the yaw dynamics see the water, the position moves with the current
#: (Fossen 2021, §10.3, Property 10.1: exact for a constant, irrotational current).
DISTURBANCES: tuple[str, ...] = ("rudder_disturbance", "sway_velocity", "current_north",
                                 "current_east")
#: The navigation outputs plus the speed U [m/s] of the ship.
OUTPUTS: tuple[str, ...] = NAV_OUTPUTS + ("speed",)

_X1 = signal_indices(NOMOTO1_STATES)
_X2 = signal_indices(NOMOTO2_STATES)
_U = signal_indices(INPUTS)
_D = signal_indices(DISTURBANCES)
_Y = signal_indices(OUTPUTS)


@njit(cache=True)
def nomoto1_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    gain, tc, speed, n3 = p.gain, p.time_constant, p.speed, p.norrbin_n3
    psi = x[_X1.heading]
    r = x[_X1.yaw_rate]
    delta_d = d[_D.rudder_disturbance] if d.shape[0] > _D.rudder_disturbance else 0.0
    v = d[_D.sway_velocity] if d.shape[0] > _D.sway_velocity else 0.0
    cn = d[_D.current_north] if d.shape[0] > _D.current_north else 0.0
    ce = d[_D.current_east] if d.shape[0] > _D.current_east else 0.0
    north, east = horizontal_velocity(speed, v, psi, cn, ce)
    dx[_X1.north] = north
    dx[_X1.east] = east
    dx[_X1.heading] = r
    dx[_X1.yaw_rate] = (gain * (u[_U.rudder_angle] + delta_d) - (r + n3 * r * r * r)) / tc


@njit(cache=True)
def nomoto1_output(t, x, u, p, y):  # pragma: no cover - compiled
    y[_Y.north] = x[_X1.north]
    y[_Y.east] = x[_X1.east]
    y[_Y.heading] = x[_X1.heading]
    y[_Y.yaw_rate] = x[_X1.yaw_rate]
    y[_Y.surge_speed] = p.speed
    y[_Y.sway_speed] = 0.0
    y[_Y.speed] = p.speed


@njit(cache=True)
def nomoto2_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    gain, t1, t2, t3, speed, n3 = p.gain, p.t1, p.t2, p.t3, p.speed, p.norrbin_n3
    psi = x[_X2.heading]
    r = x[_X2.yaw_rate]
    xi = x[_X2.yaw_aux]
    delta = u[_U.rudder_angle]
    delta_d = d[_D.rudder_disturbance] if d.shape[0] > _D.rudder_disturbance else 0.0
    v = d[_D.sway_velocity] if d.shape[0] > _D.sway_velocity else 0.0
    cn = d[_D.current_north] if d.shape[0] > _D.current_north else 0.0
    ce = d[_D.current_east] if d.shape[0] > _D.current_east else 0.0
    t12 = t1 * t2
    rdot = xi + gain * t3 / t12 * delta
    north, east = horizontal_velocity(speed, v, psi, cn, ce)
    dx[_X2.north] = north
    dx[_X2.east] = east
    dx[_X2.heading] = r
    dx[_X2.yaw_rate] = rdot
    dx[_X2.yaw_aux] = (gain * (delta + delta_d) - (t1 + t2) * rdot - (r + n3 * r * r * r)) / t12


@njit(cache=True)
def nomoto2_output(t, x, u, p, y):  # pragma: no cover - compiled
    y[_Y.north] = x[_X2.north]
    y[_Y.east] = x[_X2.east]
    y[_Y.heading] = x[_X2.heading]
    y[_Y.yaw_rate] = x[_X2.yaw_rate]
    y[_Y.surge_speed] = p.speed
    y[_Y.sway_speed] = 0.0
    y[_Y.speed] = p.speed


_DIST_UNITS = ("rad", "m/s", "m/s", "m/s")
_OUTPUT_UNITS = NAV_OUTPUT_UNITS + ("m/s",)

NOMOTO1 = VesselModel(
    name="nomoto1",
    description="first-order Nomoto steering model with Norrbin term, constant speed",
    params_type=Nomoto1Params,
    state_labels=NOMOTO1_STATES,
    state_units=("m", "m", "rad", "rad/s"),
    input_labels=INPUTS,
    input_units=("rad",),
    disturbance_labels=DISTURBANCES,
    disturbance_units=_DIST_UNITS,
    rhs=nomoto1_rhs,
    output=nomoto1_output,
    output_labels=OUTPUTS,
    output_units=_OUTPUT_UNITS,
)

NOMOTO2 = VesselModel(
    name="nomoto2",
    description="second-order Nomoto steering model with Norrbin term, constant speed",
    params_type=Nomoto2Params,
    state_labels=NOMOTO2_STATES,
    state_units=("m", "m", "rad", "rad/s", "rad/s"),
    input_labels=INPUTS,
    input_units=("rad",),
    disturbance_labels=DISTURBANCES,
    disturbance_units=_DIST_UNITS,
    rhs=nomoto2_rhs,
    output=nomoto2_output,
    output_labels=OUTPUTS,
    output_units=_OUTPUT_UNITS,
)
