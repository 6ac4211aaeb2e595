"""Nonlinear manoeuvring model of the Mariner-class cargo ship (Chislett & Strøm-Tejsen 1965).

Surge, sway and yaw of the 160.93 m Mariner at a nominal speed U_0 = 15 kn from the planar
motion mechanism tests of Chislett & Strøm-Tejsen (1965), as tabulated in Fossen's Marine
Systems Simulator (``mariner.m``). No propeller input: the surge state is the perturbation u
about U_0 (total surge speed U_0 + u), and the hydrodynamic polynomials balance the thrust at
u = 0.

Non-dimensional quantities use the instantaneous speed U = √((U_0 + u)² + v²): u' = u/U,
v' = v/U, r' = r L/U, δ in radians; forces over ½ρL²U², moments over ½ρL³U², masses over ½ρL³,
inertia over ½ρL⁵. The forces (Chislett & Strøm-Tejsen 1965, PMM polynomial model)::

    X' = X_u u' + X_uu u'² + X_uuu u'³ + X_vv v'² + X_rr r'² + X_rv r'v' + X_δδ δ²
         + X_uδδ u'δ² + X_vδ v'δ + X_uvδ u'v'δ
    Y' = Y_v v' + Y_r r' + Y_vvv v'³ + Y_vvr v'² r' + Y_vu v'u' + Y_ru r'u' + Y_δ δ
         + Y_δδδ δ³ + Y_uδ u'δ + Y_uuδ u'²δ + Y_vδδ v'δ² + Y_vvδ v'²δ + (Y_0 + Y_0u u' + Y_0uu u'²)
    N' = the same terms with the N coefficients

and the equations of motion (the rigid-body Coriolis terms are contained in the coefficients,
as in the tabulation)::

    m11 L u̇ = X' U² + X_ext/(½ρL²),            m11 = m' − X'_u̇
    [m22 m23; m32 m33] [L v̇; L² ṙ] = [Y' U² + Y_ext/(½ρL²); N' U² + N_ext/(½ρL³)]
    m22 = m' − Y'_v̇, m23 = m' x'_G − Y'_ṙ, m32 = m' x'_G − N'_v̇, m33 = I'_z − N'_ṙ

which is the tabulated u̇ = X' (U²/L)/m11, v̇ = −(−m33 Y' + m23 N')(U²/L)/det,
ṙ = (−m32 Y' + m22 N')(U²/L²)/det with the external loads ``force_x``, ``force_y`` [N] and
``moment_z`` [N·m] made non-dimensional consistently (with ρ = ``rho``). Kinematics:
ẋ_N = (U_0 + u) cos ψ − v sin ψ, ẏ_E = (U_0 + u) sin ψ + v cos ψ, ψ̇ = r (heading continuous,
not wrapped).

Sign convention
    In the original data a positive rudder angle gives a negative yaw rate. Here, as in the MSS
    file, the model's input ``rudder_angle`` is the negated tabulated δ, so **a positive
    rudder angle gives a positive (starboard) yaw rate**, heading ψ clockwise from north
    (north-east-down). Only the rudder sign is flipped: the body axes, the coefficients and
    the asymmetry terms Y_0, N_0 (single screw) are as tabulated, so with zero rudder the ship
    turns slowly to starboard, and ±δ turns are not mirror images.
    The drift angle output is β = atan2(−v, U_0 + u), positive when the ship moves to port
    of its heading (as in a steady turn to starboard).

Current
    ``current_north``, ``current_east`` [m/s] are the velocity of a uniform current over
    ground. The velocity states (u, v, r) are then relative to the water, so the hydrodynamic
    forces see the velocity through the water, and the position moves with the current:
    ẋ_N += V_c,N, ẏ_E += V_c,E. For a current constant in time this is exact: the rigid-body
    inertial and Coriolis forces written in relative velocities equal those in absolute ones for
    an irrotational, constant current (Fossen 2021, *Handbook of Marine Craft Hydrodynamics and
    Motion Control*, 2nd ed., §10.3, Property 10.1). A current that changes in time would add the
    inertia force of its acceleration, which is left out (so it is a slowly varying current).

Low speed
    The non-dimensional velocities use U_f = max(U, Fn_min √(g L)) (``min_froude_number``);
    the forces keep the factor U² of the actual speed. The model is a perturbation model about
    15 kn and is not meant for large speed losses beyond those of a turning circle.

Rudder
    The steering gear (±40°, 5 °/s in the original data, a first-order lag of 1 s as in MSS)
    is an actuator: simulate with ``actuator=RUDDER_SERVO, actuator_params=MARINER_SERVO``.

References
----------
Chislett, M. S., Strøm-Tejsen, J. (1965). Planar motion mechanism tests and full-scale steering
and manoeuvring predictions for a Mariner class vessel. Technical Report Hy-5, Hydro- and
Aerodynamics Laboratory, Lyngby, Denmark.
Fossen, T. I. Marine Systems Simulator (MSS), ``mariner.m`` (coefficient table).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..actuators.servo import ServoParams
from ..constants import GRAVITY
from ..errors import ParameterError
from ..parameters import Params, param, signal_indices
from .base import VesselModel
from .rigid_body import (PLANAR_OUTPUT_UNITS, PLANAR_OUTPUTS, cramer_2x2, horizontal_velocity,
                         write_planar_outputs)

__all__ = [
    "MarinerParams",
    "MARINER",
    "MARINER_NONLINEAR",
    "MARINER_NONLINEAR_PROVENANCE",
    "MARINER_SERVO",
    "STATES",
    "INPUTS",
    "DISTURBANCES",
    "OUTPUTS",
]

STATES = ("surge_perturbation", "sway_speed", "yaw_rate", "north", "east", "heading")
STATE_UNITS = ("m/s", "m/s", "rad/s", "m", "m", "rad")
INPUTS = ("rudder_angle",)
INPUT_UNITS = ("rad",)
DISTURBANCES = ("force_x", "force_y", "moment_z", "current_north", "current_east")
DISTURBANCE_UNITS = ("N", "N", "N·m", "m/s", "m/s")
OUTPUTS = PLANAR_OUTPUTS
OUTPUT_UNITS = PLANAR_OUTPUT_UNITS

S = signal_indices(STATES)
U = signal_indices(INPUTS)
D = signal_indices(DISTURBANCES)
Y = signal_indices(OUTPUTS)

_E5 = 1e-5


def _c(value: float, symbol: str, doc: str) -> float:
    return param(value * _E5, unit="-", symbol=symbol, doc=doc)


@dataclass(frozen=True, kw_only=True)
class MarinerParams(Params):
    """Parameters of the Mariner nonlinear model (Chislett & Strøm-Tejsen 1965).

    Defaults are the Mariner values (the coefficient table × 10⁻⁵, non-dimensional as in the
    module docstring); δ in the polynomials is the tabulated rudder angle (the negated
    ``rudder_angle`` input).
    """

    length: float = param(160.93, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="length between perpendiculars")
    nominal_speed: float = param(7.7175, unit="m/s", symbol="U_0", low=0.0,
                                 low_inclusive=False,
                                 doc="speed about which surge is perturbed: 15 kn, as tabulated "
                                     "7.7175 m/s (15 × 0.5145)")
    rho: float = param(1025.0, unit="kg/m³", symbol="ρ", low=0.0, low_inclusive=False,
                       doc="water density (scales the external loads only)")
    min_froude_number: float = param(1e-3, unit="-", symbol="Fn_min", low=0.0,
                                     low_inclusive=False, high=0.1,
                                     doc="speed floor Fn_min √(g L) in u', v', r' (U → 0 guard)")
    mass: float = param(798e-5, unit="-", symbol="m'", low=0.0, low_inclusive=False,
                        doc="mass over ½ρL³")
    inertia: float = param(39.2e-5, unit="-", symbol="I'_z", low=0.0, low_inclusive=False,
                           doc="yaw moment of inertia over ½ρL⁵")
    x_G: float = param(-0.023, unit="-", symbol="x'_G", low=-0.5, high=0.5,
                       doc="centre of gravity forward of the origin, over L")
    # surge
    X_udot: float = _c(-42.0, "X'_u̇", "surge added mass")
    X_u: float = _c(-184.0, "X'_u", "surge force per u'")
    X_uu: float = _c(-110.0, "X'_uu", "surge force per u'²")
    X_uuu: float = _c(-215.0, "X'_uuu", "surge force per u'³")
    X_vv: float = _c(-899.0, "X'_vv", "surge force per v'²")
    X_rr: float = _c(18.0, "X'_rr", "surge force per r'²")
    X_dd: float = _c(-95.0, "X'_δδ", "surge force per δ²")
    X_udd: float = _c(-190.0, "X'_uδδ", "surge force per u'δ²")
    X_rv: float = _c(798.0, "X'_rv", "surge force per r'v'")
    X_vd: float = _c(93.0, "X'_vδ", "surge force per v'δ")
    X_uvd: float = _c(93.0, "X'_uvδ", "surge force per u'v'δ")
    # sway
    Y_vdot: float = _c(-748.0, "Y'_v̇", "sway added mass")
    Y_rdot: float = _c(-9.354, "Y'_ṙ", "sway force per ṙ'")
    Y_v: float = _c(-1160.0, "Y'_v", "sway force per v'")
    Y_r: float = _c(-499.0, "Y'_r", "sway force per r'")
    Y_vvv: float = _c(-8078.0, "Y'_vvv", "sway force per v'³")
    Y_vvr: float = _c(15356.0, "Y'_vvr", "sway force per v'² r'")
    Y_vu: float = _c(-1160.0, "Y'_vu", "sway force per v'u'")
    Y_ru: float = _c(-499.0, "Y'_ru", "sway force per r'u'")
    Y_d: float = _c(278.0, "Y'_δ", "sway force per δ")
    Y_ddd: float = _c(-90.0, "Y'_δδδ", "sway force per δ³")
    Y_ud: float = _c(556.0, "Y'_uδ", "sway force per u'δ")
    Y_uud: float = _c(278.0, "Y'_uuδ", "sway force per u'²δ")
    Y_vdd: float = _c(-4.0, "Y'_vδδ", "sway force per v'δ²")
    Y_vvd: float = _c(1190.0, "Y'_vvδ", "sway force per v'²δ")
    Y_0: float = _c(-4.0, "Y'_0", "sway force bias (single screw)")
    Y_0u: float = _c(-8.0, "Y'_0u", "sway force bias per u'")
    Y_0uu: float = _c(-4.0, "Y'_0uu", "sway force bias per u'²")
    # yaw
    N_vdot: float = _c(4.646, "N'_v̇", "yaw moment per v̇'")
    N_rdot: float = _c(-43.8, "N'_ṙ", "yaw added inertia")
    N_v: float = _c(-264.0, "N'_v", "yaw moment per v'")
    N_r: float = _c(-166.0, "N'_r", "yaw moment per r'")
    N_vvv: float = _c(1636.0, "N'_vvv", "yaw moment per v'³")
    N_vvr: float = _c(-5483.0, "N'_vvr", "yaw moment per v'² r'")
    N_vu: float = _c(-264.0, "N'_vu", "yaw moment per v'u'")
    N_ru: float = _c(-166.0, "N'_ru", "yaw moment per r'u'")
    N_d: float = _c(-139.0, "N'_δ", "yaw moment per δ")
    N_ddd: float = _c(45.0, "N'_δδδ", "yaw moment per δ³")
    N_ud: float = _c(-278.0, "N'_uδ", "yaw moment per u'δ")
    N_uud: float = _c(-139.0, "N'_uuδ", "yaw moment per u'²δ")
    N_vdd: float = _c(13.0, "N'_vδδ", "yaw moment per v'δ²")
    N_vvd: float = _c(-489.0, "N'_vvδ", "yaw moment per v'²δ")
    N_0: float = _c(3.0, "N'_0", "yaw moment bias (single screw)")
    N_0u: float = _c(6.0, "N'_0u", "yaw moment bias per u'")
    N_0uu: float = _c(3.0, "N'_0uu", "yaw moment bias per u'²")

    def validate(self) -> None:
        """Cross-field checks: positive effective masses and a regular sway–yaw mass matrix."""
        m11 = self.mass - self.X_udot
        m22 = self.mass - self.Y_vdot
        m23 = self.mass * self.x_G - self.Y_rdot
        m32 = self.mass * self.x_G - self.N_vdot
        m33 = self.inertia - self.N_rdot
        if m11 <= 0.0:
            raise ParameterError(f"`mass` − `X_udot` must be > 0 [-], got {m11!r}")
        if m22 * m33 - m23 * m32 <= 0.0 or m22 <= 0.0:
            raise ParameterError(
                "the sway–yaw mass matrix [m' − Y'_v̇, m'x'_G − Y'_ṙ; m'x'_G − N'_v̇, "
                f"I'_z − N'_ṙ] must be positive definite [-], got det {m22 * m33 - m23 * m32!r}")


@njit(cache=True)
def mariner_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of the Mariner model for one run (module docstring)."""
    L = p.length
    U0 = p.nominal_speed
    du = x[S.surge_perturbation]
    v = x[S.sway_speed]
    r = x[S.yaw_rate]
    psi = x[S.heading]
    delta = -u[U.rudder_angle]  # tabulated sign: positive δ turns to port
    surge = U0 + du
    speed2 = surge * surge + v * v
    u_nd = max(math.sqrt(speed2), p.min_froude_number * math.sqrt(GRAVITY * L))
    un = du / u_nd
    vn = v / u_nd
    rn = r * L / u_nd
    d2 = delta * delta
    Xh = (p.X_u * un + p.X_uu * un * un + p.X_uuu * un * un * un + p.X_vv * vn * vn
          + p.X_rr * rn * rn + p.X_rv * rn * vn + p.X_dd * d2 + p.X_udd * un * d2
          + p.X_vd * vn * delta + p.X_uvd * un * vn * delta)
    Yh = (p.Y_v * vn + p.Y_r * rn + p.Y_vvv * vn * vn * vn + p.Y_vvr * vn * vn * rn
          + p.Y_vu * vn * un + p.Y_ru * rn * un + p.Y_d * delta + p.Y_ddd * d2 * delta
          + p.Y_ud * un * delta + p.Y_uud * un * un * delta + p.Y_vdd * vn * d2
          + p.Y_vvd * vn * vn * delta + (p.Y_0 + p.Y_0u * un + p.Y_0uu * un * un))
    Nh = (p.N_v * vn + p.N_r * rn + p.N_vvv * vn * vn * vn + p.N_vvr * vn * vn * rn
          + p.N_vu * vn * un + p.N_ru * rn * un + p.N_d * delta + p.N_ddd * d2 * delta
          + p.N_ud * un * delta + p.N_uud * un * un * delta + p.N_vdd * vn * d2
          + p.N_vvd * vn * vn * delta + (p.N_0 + p.N_0u * un + p.N_0uu * un * un))
    half_rho_l2 = 0.5 * p.rho * L * L
    fx = Xh * speed2 + d[D.force_x] / half_rho_l2
    fy = Yh * speed2 + d[D.force_y] / half_rho_l2
    mz = Nh * speed2 + d[D.moment_z] / (half_rho_l2 * L)
    m11 = p.mass - p.X_udot
    m22 = p.mass - p.Y_vdot
    m23 = p.mass * p.x_G - p.Y_rdot
    m32 = p.mass * p.x_G - p.N_vdot
    m33 = p.inertia - p.N_rdot
    # [[m22, m23], [m32, m33]] [L v̇, L² ṙ] = [fy, mz]
    d1, d2, det = cramer_2x2(m22, m23, m32, m33, fy, mz)
    dx[S.surge_perturbation] = fx / (m11 * L)
    dx[S.sway_speed] = d1 / (det * L)
    dx[S.yaw_rate] = d2 / (det * L * L)
    # velocities through the water; the position moves with the current as well
    north, east = horizontal_velocity(surge, v, psi, d[D.current_north], d[D.current_east])
    dx[S.north] = north
    dx[S.east] = east
    dx[S.heading] = r


@njit(cache=True)
def mariner_output(t, x, u, p, y):  # pragma: no cover - compiled
    """Outputs of the Mariner model (``OUTPUTS`` order) for one run."""
    surge = p.nominal_speed + x[S.surge_perturbation]
    v = x[S.sway_speed]
    write_planar_outputs(y, x[S.north], x[S.east], x[S.heading], x[S.yaw_rate], surge, v,
                         math.sqrt(surge * surge + v * v), math.atan2(-v, surge))


@njit(cache=True)
def mariner_motion(x, p):  # pragma: no cover - compiled
    """Surge U_0 + u and sway speed through the water [m/s] and heading [rad] (for the loads)."""
    return p.nominal_speed + x[S.surge_perturbation], x[S.sway_speed], x[S.heading]


MARINER = VesselModel(
    name="mariner",
    description="Mariner-class cargo ship, nonlinear 3-DOF PMM model (surge perturbed about "
    "15 kn), Chislett & Strøm-Tejsen (1965); positive rudder turns to starboard",
    params_type=MarinerParams,
    state_labels=STATES,
    state_units=STATE_UNITS,
    input_labels=INPUTS,
    input_units=INPUT_UNITS,
    disturbance_labels=DISTURBANCES,
    disturbance_units=DISTURBANCE_UNITS,
    rhs=mariner_rhs,
    output=mariner_output,
    output_labels=OUTPUTS,
    output_units=OUTPUT_UNITS,
    motion=mariner_motion,
)

MARINER_NONLINEAR_PROVENANCE = (
    "Mariner-class cargo ship (L = 160.93 m, U0 = 15 kn = 7.7175 m/s): nonlinear PMM model of "
    "Chislett & Strom-Tejsen (1965), Tech. Report Hy-5, Hydro- and Aerodynamics Laboratory, "
    "Lyngby, as tabulated in Fossen's Marine Systems Simulator (mariner.m): m' = 798e-5, "
    "I'_z = 39.2e-5, x'_G = -0.023 and the X, Y, N coefficients x 1e-5. Rudder sign flipped "
    "as in MSS (positive rudder -> positive yaw rate). Steering gear +-40 deg, 5 deg/s: "
    "seahelm.vessels.mariner.MARINER_SERVO for the rudder-servo actuator. Linear steering "
    "constants at U0: K = 0.185 1/s, T1 = 118 s, T2 = 7.8 s, T3 = 18.5 s ('mariner-nomoto2')."
)

#: The Mariner parameter set (the :class:`MarinerParams` defaults).
MARINER_NONLINEAR = MarinerParams()

#: Mariner steering gear for ``RUDDER_SERVO``: ±40°, 5 °/s, first-order lag 1 s (as in MSS).
MARINER_SERVO = ServoParams(max_angle=math.radians(40.0), max_rate=math.radians(5.0),
                            time_constant=1.0)
