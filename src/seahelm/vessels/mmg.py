"""MMG standard 3-DOF manoeuvring model (Yasukawa & Yoshimura 2015): hull, propeller, rudder.

The model of the Japanese Maneuvering Modeling Group in the standard form of Yasukawa &
Yoshimura (2015): a single-screw, single-rudder ship in calm deep water, surge, sway and yaw,
with the origin at **midship** (``v`` is the sway velocity of the midship point, v_m).

Equations of motion with the origin at midship (Yasukawa & Yoshimura 2015, "motion
equations")::

    (m + m_x) u̇ − (m + m_y) v_m r − x_G m r²          = X = X_H + X_P + X_R + X_ext
    (m + m_y) v̇_m + (m + m_x) u r + x_G m ṙ            = Y = Y_H + Y_R + Y_ext
    (I_zG + x_G² m + J_z) ṙ + x_G m (v̇_m + u r)        = N = N_H + N_R + N_ext

solved exactly for (u̇, v̇_m, ṙ): the surge equation directly, the 2×2 sway–yaw mass coupling
by its determinant (:func:`~seahelm.vessels.rigid_body.midship_accelerations`, the rigid-body
code the 3-DOF models share). Kinematics of the midship point in north-east-down axes, heading ψ
clockwise from north: ẋ_N = u cos ψ − v_m sin ψ, ẏ_E = u sin ψ + v_m cos ψ, ψ̇ = r. The
heading state and output are the integrated yaw angle (continuous, not wrapped to ±π), so a
turning circle's 90° and 180° heading changes can be read off directly.

Hydrodynamic forces ("hull forces", "propeller force", "rudder forces" of the paper), with
U = √(u² + v_m²), v'_m = v_m/U, r' = r L_pp/U, β = atan2(−v_m, u)::

    X_H = ½ρ L_pp d U² (−R'_0 + X'_vv v'² + X'_vr v' r' + X'_rr r'² + X'_vvvv v'⁴)
    Y_H = ½ρ L_pp d U² (Y'_v v' + Y'_r r' + Y'_vvv v'³ + Y'_vvr v'² r' + Y'_vrr v' r'² + Y'_rrr r'³)
    N_H = ½ρ L_pp² d U² (N'_v v' + ... the same terms with N')

    X_P = (1 − t_P) T,   T = ρ n² D_P⁴ K_T(J_P),   K_T = k_0 + k_1 J_P + k_2 J_P²,
    J_P = u (1 − w_P) / (n D_P),
    1 − w_P = (1 − w_P0) [1 + (1 − exp(−C_1 |β_P|)) (C_2 − 1)],   β_P = β − x'_P r'
              (C_2 for β_P > 0 or β_P < 0: :func:`wake_fraction`)

    X_R = −(1 − t_R) F_N sin δ,   Y_R = −(1 + a_H) F_N cos δ,   N_R = −(x_R + a_H x_H) F_N cos δ
    F_N = ½ρ A_R U_R² f_α sin α_R,   U_R² = u_R² + v_R²,   α_R = δ − atan(v_R / u_R)
    u_R = ε u (1 − w_P) √(η {1 + κ (√(1 + 8 K_T/(π J_P²)) − 1)}² + (1 − η)),   η = D_P / H_R
    v_R = U γ_R β_R,   β_R = β − l'_R r'     (γ_R for β_R < 0 or β_R > 0)

with x_R = x'_R L_pp and x_H = x'_H L_pp **in metres** in N_R (one open implementation used the
non-dimensional x'_R there, a known bug).

Sign conventions
    Body axes x forward, y to starboard, z down; ψ clockwise from north. A **positive rudder
    angle δ gives a positive (starboard) yaw rate**: in a straight run α_R = δ, so δ > 0 gives
    F_N > 0, Y_R < 0 (the stern is pushed to port) and N_R = −(x_R + a_H x_H) F_N > 0 because
    x_R + a_H x_H < 0. The drift angle β = atan2(−v_m, u) is positive when the midship point
    moves to port of the heading, as in a steady turn to starboard.

Low speed
    The non-dimensional velocities divide by U. The model uses U_f = max(U, Fn_min √(g L_pp))
    (``min_froude_number``) in v'_m, r' only; every force keeps the factor U² of the actual
    speed, so the hull forces vanish at rest and the model starts from rest without NaN. The
    propeller thrust is evaluated as T = ρ D_P² (k_0 n² D_P² + k_1 n D_P u_P + k_2 u_P²),
    u_P = u (1 − w_P), which equals ρ n² D_P⁴ K_T(J_P) for n ≠ 0 and is finite for n = 0; the
    rudder inflow as u_R = ε √(η ((1 − κ) u_P + κ √(u_P² + 8T/(πρD_P²)))² + (1 − η) u_P²),
    algebraically the paper's formula for u_P ≥ 0 and finite at u → 0 (bollard pull). The
    MMG standard method covers ahead motion only: the surge speed has the declared lower
    bound 0, so a run that goes astern is recorded as diverged (out of bounds), not continued
    outside the model's validity.

External loads ``force_x``, ``force_y`` [N] and ``moment_z`` [N·m] (about midship) are added to
X, Y, N; they are zero when not given.

Current: ``current_north``, ``current_east`` [m/s] are the velocity of a uniform current over
ground. The velocity states (u, v, r) are then relative to the water, so the hull, propeller
and rudder forces see the velocity through the water, and the position moves with the current:
ẋ_N += V_c,N, ẏ_E += V_c,E. For a current constant in time this is exact: the rigid-body
inertial and Coriolis forces written in relative velocities equal those in absolute ones for
an irrotational, constant current (Fossen 2021, *Handbook of Marine Craft Hydrodynamics and
Motion Control*, 2nd ed., §10.3, Property 10.1). A current that changes in time would add the
inertia force of its acceleration, which is left out (so it is a slowly varying current).

References
----------
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52. doi:10.1007/s00773-014-0293-y.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numba import njit

from ..actuators.servo import ServoParams
from ..constants import GRAVITY, KNOT
from ..errors import ParameterError
from ..parameters import Params, param, signal_indices
from .base import VesselModel
from .rigid_body import (PLANAR_OUTPUT_UNITS, PLANAR_OUTPUTS, horizontal_velocity,
                         midship_accelerations, write_planar_outputs)

__all__ = [
    "MMGParams",
    "MMG",
    "MMGForces",
    "mmg_accelerations",
    "wake_fraction",
    "force_components",
    "KVLCC2_FULL",
    "KVLCC2_L7",
    "KVLCC2_FULL_PROVENANCE",
    "KVLCC2_L7_PROVENANCE",
    "KVLCC2_L7_WP0_035",
    "KVLCC2_L7_XP_050",
    "KVLCC2_L7_SERVO",
    "KVLCC2_FULL_SERVO",
    "STATES",
    "INPUTS",
    "DISTURBANCES",
    "OUTPUTS",
]

STATES = ("surge_speed", "sway_speed", "yaw_rate", "north", "east", "heading")
STATE_UNITS = ("m/s", "m/s", "rad/s", "m", "m", "rad")
INPUTS = ("rudder_angle", "propeller_rps")
INPUT_UNITS = ("rad", "1/s")
DISTURBANCES = ("force_x", "force_y", "moment_z", "current_north", "current_east")
DISTURBANCE_UNITS = ("N", "N", "N·m", "m/s", "m/s")
OUTPUTS = PLANAR_OUTPUTS + ("thrust", "rudder_normal_force", "rudder_inflow_angle")
OUTPUT_UNITS = PLANAR_OUTPUT_UNITS + ("N", "N", "rad")

S = signal_indices(STATES)
U = signal_indices(INPUTS)
D = signal_indices(DISTURBANCES)
Y = signal_indices(OUTPUTS)

_POS = dict(low=0.0, low_inclusive=False)


@dataclass(frozen=True, kw_only=True)
class MMGParams(Params):
    """Parameters of the MMG standard model (Yasukawa & Yoshimura 2015).

    Principal particulars are dimensional (SI); the hydrodynamic coefficients are the paper's
    non-dimensional (primed) ones, with forces made non-dimensional by ½ρ L_pp d U², moments by
    ½ρ L_pp² d U², masses by ½ρ L_pp² d and the added yaw inertia by ½ρ L_pp⁴ d. The defaults
    are the full-scale KVLCC2 tanker (:data:`KVLCC2_FULL`).
    """

    # -- principal particulars (dimensional) ---------------------------------------------
    length: float = param(320.0, unit="m", symbol="L_pp", **_POS,
                          doc="length between perpendiculars")
    breadth: float = param(58.0, unit="m", symbol="B", **_POS,
                           doc="moulded breadth (for reference; not in the equations)")
    draft: float = param(20.8, unit="m", symbol="d", **_POS, doc="draught (even keel)")
    displacement: float = param(312_600.0, unit="m³", symbol="∇", **_POS,
                                doc="displacement volume; mass m = ρ∇")
    x_G: float = param(11.2, unit="m", symbol="x_G",
                       doc="centre of gravity forward of midship (dimensional)")
    gyration_radius: float = param(0.25, unit="-", symbol="k_zz/L_pp", **_POS, high=1.0,
                                   doc="yaw radius of gyration over L_pp; I_zG = m (k_zz)²")
    propeller_diameter: float = param(9.86, unit="m", symbol="D_P", **_POS,
                                      doc="propeller diameter")
    rudder_span: float = param(15.8, unit="m", symbol="H_R", **_POS,
                               doc="rudder span; η = D_P/H_R")
    rudder_area: float = param(112.5, unit="m²", symbol="A_R", **_POS,
                               doc="profile area of the movable rudder")
    rho: float = param(1025.0, unit="kg/m³", symbol="ρ", **_POS,
                       doc="water density (1025 sea water; 1000 for fresh-water model tests)")
    approach_speed: float = param(15.5 * KNOT, unit="m/s", symbol="U_0", **_POS,
                                  doc="test (approach) speed of the parameter set; not used by "
                                      "the equations, default of the equilibrium helpers")
    min_froude_number: float = param(1e-3, unit="-", symbol="Fn_min", **_POS, high=0.1,
                                     doc="speed floor Fn_min √(g L_pp) for the "
                                         "non-dimensional velocities v'_m, r' (U → 0 guard)")
    # -- hull (non-dimensional) ----------------------------------------------------------
    R_0: float = param(0.022, unit="-", symbol="R'_0", low=0.0,
                       doc="straight-run resistance coefficient")
    X_vv: float = param(-0.040, unit="-", symbol="X'_vv", doc="surge force per v'²")
    X_vr: float = param(0.002, unit="-", symbol="X'_vr", doc="surge force per v' r'")
    X_rr: float = param(0.011, unit="-", symbol="X'_rr", doc="surge force per r'²")
    X_vvvv: float = param(0.771, unit="-", symbol="X'_vvvv", doc="surge force per v'⁴")
    Y_v: float = param(-0.315, unit="-", symbol="Y'_v", doc="sway force per v'")
    Y_r: float = param(0.083, unit="-", symbol="Y'_R", doc="sway force per r'")
    Y_vvv: float = param(-1.607, unit="-", symbol="Y'_vvv", doc="sway force per v'³")
    Y_vvr: float = param(0.379, unit="-", symbol="Y'_vvr", doc="sway force per v'² r'")
    Y_vrr: float = param(-0.391, unit="-", symbol="Y'_vrr", doc="sway force per v' r'²")
    Y_rrr: float = param(0.008, unit="-", symbol="Y'_rrr", doc="sway force per r'³")
    N_v: float = param(-0.137, unit="-", symbol="N'_v", doc="yaw moment per v'")
    N_r: float = param(-0.049, unit="-", symbol="N'_R", doc="yaw moment per r'")
    N_vvv: float = param(-0.030, unit="-", symbol="N'_vvv", doc="yaw moment per v'³")
    N_vvr: float = param(-0.294, unit="-", symbol="N'_vvr", doc="yaw moment per v'² r'")
    N_vrr: float = param(0.055, unit="-", symbol="N'_vrr", doc="yaw moment per v' r'²")
    N_rrr: float = param(-0.013, unit="-", symbol="N'_rrr", doc="yaw moment per r'³")
    m_x: float = param(0.022, unit="-", symbol="m'_x", low=0.0, doc="added mass in surge")
    m_y: float = param(0.223, unit="-", symbol="m'_y", low=0.0, doc="added mass in sway")
    J_z: float = param(0.011, unit="-", symbol="J'_z", low=0.0,
                       doc="added moment of inertia in yaw")
    # -- propeller ----------------------------------------------------------------------
    t_P: float = param(0.220, unit="-", symbol="t_P", low=0.0, high=0.99,
                       doc="thrust deduction factor")
    w_P0: float = param(0.40, unit="-", symbol="w_P0", low=0.0, high=0.99,
                        doc="wake fraction at the propeller in straight motion")
    k_0: float = param(0.2931, unit="-", symbol="k_0", doc="K_T polynomial, constant term")
    k_1: float = param(-0.2753, unit="-", symbol="k_1", doc="K_T polynomial, linear term")
    k_2: float = param(-0.1385, unit="-", symbol="k_2", doc="K_T polynomial, quadratic term")
    x_P: float = param(-0.48, unit="-", symbol="x'_P", low=-1.0, high=1.0,
                       doc="effective longitudinal position of the propeller in β_P")
    C_1: float = param(2.0, unit="-", symbol="C_1", low=0.0, doc="wake-change rate with β_P")
    C_2_plus: float = param(1.6, unit="-", symbol="C_2 (β_P > 0)", **_POS,
                            doc="wake-change factor for β_P > 0")
    C_2_minus: float = param(1.1, unit="-", symbol="C_2 (β_P < 0)", **_POS,
                             doc="wake-change factor for β_P < 0")
    # -- rudder -------------------------------------------------------------------------
    t_R: float = param(0.387, unit="-", symbol="t_R", low=0.0, high=0.99,
                       doc="steering resistance deduction factor")
    a_H: float = param(0.312, unit="-", symbol="a_H", low=0.0,
                       doc="rudder force increase factor (hull lateral force induced by steering)")
    x_H: float = param(-0.464, unit="-", symbol="x'_H", low=-1.0, high=1.0,
                       doc="position of the additional lateral force over L_pp")
    x_R: float = param(-0.5, unit="-", symbol="x'_R", low=-1.0, high=1.0,
                       doc="rudder position over L_pp (x_R = x'_R L_pp [m] in N_R)")
    gamma_R_minus: float = param(0.395, unit="-", symbol="γ_R (β_R < 0)", low=0.0,
                                 doc="flow straightening coefficient for β_R < 0")
    gamma_R_plus: float = param(0.640, unit="-", symbol="γ_R (β_R > 0)", low=0.0,
                                doc="flow straightening coefficient for β_R > 0")
    l_R: float = param(-0.710, unit="-", symbol="l'_R", low=-2.0, high=2.0,
                       doc="effective longitudinal rudder position in β_R")
    epsilon: float = param(1.09, unit="-", symbol="ε", **_POS,
                           doc="ratio of wake fractions at rudder and propeller, (1−w_R)/(1−w_P)")
    kappa: float = param(0.50, unit="-", symbol="κ", low=0.0,
                         doc="propeller slipstream correction at the rudder")
    f_alpha: float = param(2.747, unit="-", symbol="f_α", **_POS,
                           doc="rudder lift gradient coefficient")

    def validate(self) -> None:
        """Cross-field checks: CoG inside the ship, propeller no larger than the rudder span."""
        if abs(self.x_G) >= 0.5 * self.length:
            raise ParameterError(
                f"`x_G` must lie within ±L_pp/2 = ±{0.5 * self.length:g} [m], got {self.x_G!r}")
        if self.propeller_diameter > self.rudder_span:
            raise ParameterError(
                "`propeller_diameter` must not exceed `rudder_span` (η = D_P/H_R ≤ 1) [m], got "
                f"D_P = {self.propeller_diameter!r}, H_R = {self.rudder_span!r}")


@njit(cache=True)
def wake_fraction(beta_P, w_P0, C_1, C_2_plus, C_2_minus):  # pragma: no cover - compiled
    """Effective wake fraction at the propeller in manoeuvring, w_P(β_P).

    Yasukawa & Yoshimura (2015), propeller force: 1 − w_P = (1 − w_P0) [1 + (1 − exp(−C_1
    |β_P|)) (C_2 − 1)], with C_2 = ``C_2_plus`` for β_P > 0 and ``C_2_minus`` for β_P < 0.
    At β_P = 0 the bracket is 1 and w_P = w_P0 exactly. Compiled (numba); call it with floats.

    Parameters
    ----------
    beta_P : float
        Geometrical inflow angle to the propeller β_P = β − x'_P r' [rad].
    w_P0 : float
        Wake fraction in straight motion [-].
    C_1 : float
        Rate of change of the wake with |β_P| [-].
    C_2_plus, C_2_minus : float
        C_2 for β_P > 0 and β_P < 0 [-].

    Returns
    -------
    float
        w_P [-].
    """
    C_2 = C_2_plus if beta_P > 0.0 else C_2_minus
    return 1.0 - (1.0 - w_P0) * (1.0 + (1.0 - math.exp(-C_1 * abs(beta_P))) * (C_2 - 1.0))


@njit(cache=True)
def _forces(u, v, r, delta, n, p):  # pragma: no cover - compiled
    """Hull, propeller and rudder forces for one state; see the module docstring."""
    L = p.length
    rho = p.rho
    speed = math.sqrt(u * u + v * v)
    u_floor = p.min_froude_number * math.sqrt(GRAVITY * L)
    u_nd = max(speed, u_floor)
    vn = v / u_nd
    rn = r * L / u_nd
    beta = math.atan2(-v, u)
    q = 0.5 * rho * L * p.draft * speed * speed
    vn2 = vn * vn
    rn2 = rn * rn
    # hull (polynomials in v'_m, r')
    X_H = q * (-p.R_0 + p.X_vv * vn2 + p.X_vr * vn * rn + p.X_rr * rn2 + p.X_vvvv * vn2 * vn2)
    Y_H = q * (p.Y_v * vn + p.Y_r * rn + p.Y_vvv * vn2 * vn + p.Y_vvr * vn2 * rn
               + p.Y_vrr * vn * rn2 + p.Y_rrr * rn2 * rn)
    N_H = q * L * (p.N_v * vn + p.N_r * rn + p.N_vvv * vn2 * vn + p.N_vvr * vn2 * rn
                   + p.N_vrr * vn * rn2 + p.N_rrr * rn2 * rn)
    # propeller: T = ρ n² D⁴ K_T(J_P) written without dividing by n
    beta_P = beta - p.x_P * rn
    w_P = wake_fraction(beta_P, p.w_P0, p.C_1, p.C_2_plus, p.C_2_minus)
    u_P = u * (1.0 - w_P)
    dp = p.propeller_diameter
    thrust = rho * dp * dp * (p.k_0 * n * n * dp * dp + p.k_1 * n * dp * u_P + p.k_2 * u_P * u_P)
    X_P = (1.0 - p.t_P) * thrust
    X_R, Y_R, F_N, cos_d, u_R, v_R = mmg_rudder_forces(u_P, thrust, beta, rn, speed, delta, p)
    x_R = p.x_R * L  # metres
    x_H = p.x_H * L
    N_R = -(x_R + p.a_H * x_H) * F_N * cos_d
    return (X_H, Y_H, N_H, X_P, X_R, Y_R, N_R, thrust, F_N, w_P, u_R, v_R, speed, beta)


@njit(cache=True)
def mmg_rudder_forces(u_P, thrust, beta, rn, speed, delta, p):  # pragma: no cover - compiled
    """The MMG rudder's surge and sway forces (Yasukawa & Yoshimura 2015, rudder force),
    for every model of the MMG family that has its rudder (``mmg``, ``mmg-4q``).

    Parameters
    ----------
    u_P : float
        Propeller inflow speed u (1 − w_P) [m/s].
    thrust : float
        Propeller thrust T [N].
    beta, rn : float
        Drift angle β [rad] and non-dimensional yaw rate r' [-] at the midship point.
    speed : float
        Speed U through the water [m/s].
    delta : float
        Rudder angle δ [rad].
    p : parameters
        The model's parameters (ρ, D_P, H_R, κ, ε, l'_R, γ_R±, A_R, f_α, t_R, a_H).

    Returns
    -------
    (float, float, float, float, float, float)
        X_R = −(1 − t_R) F_N sin δ and Y_R = −(1 + a_H) F_N cos δ [N], F_N [N], cos δ (for the
        model's yaw moment N_R = −(x_R + a_H x_H) F_N cos δ), u_R and v_R [m/s].
    """
    rho = p.rho
    dp = p.propeller_diameter
    # rudder inflow: u_P (1 + κ(√(1 + 8K_T/(πJ²)) − 1)) = (1 − κ) u_P + κ √(u_P² + 8T/(πρD²))
    eta = dp / p.rudder_span
    slip = u_P * u_P + 8.0 * thrust / (math.pi * rho * dp * dp)
    a_P = abs(u_P)
    jet = (1.0 - p.kappa) * a_P + p.kappa * math.sqrt(max(slip, 0.0))
    u_R = p.epsilon * math.sqrt(eta * jet * jet + (1.0 - eta) * a_P * a_P)
    if u_P < 0.0:
        u_R = -u_R
    beta_R = beta - p.l_R * rn
    gamma_R = p.gamma_R_minus if beta_R < 0.0 else p.gamma_R_plus
    v_R = speed * gamma_R * beta_R
    # F_N = ½ρ A_R U_R² f_α sin α_R with α_R = δ − atan2(v_R, u_R), U_R = √(u_R² + v_R²):
    # U_R² sin α_R = U_R (u_R sin δ − v_R cos δ), without the arctangent (α_R: rudder_inflow_angle)
    sin_d = math.sin(delta)
    cos_d = math.cos(delta)
    U_R = math.sqrt(u_R * u_R + v_R * v_R)
    F_N = 0.5 * rho * p.rudder_area * p.f_alpha * U_R * (u_R * sin_d - v_R * cos_d)
    X_R = -(1.0 - p.t_R) * F_N * sin_d
    Y_R = -(1.0 + p.a_H) * F_N * cos_d
    return X_R, Y_R, F_N, cos_d, u_R, v_R


@njit(cache=True)
def rudder_inflow_angle(delta, u_R, v_R):  # pragma: no cover - compiled
    """Effective rudder inflow angle α_R = δ − atan2(v_R, u_R) [rad] (Yasukawa & Yoshimura 2015)."""
    return delta - math.atan2(v_R, u_R)


@njit(cache=True)
def mmg_accelerations(X, Y, N, u, v, r, p):  # pragma: no cover - compiled
    """(u̇, v̇_m, ṙ) of the motion equations (module docstring) under the forces (X, Y, N)
    [N, N, N·m]: :func:`~seahelm.vessels.rigid_body.midship_accelerations` with the mass
    m = ρ∇, the added masses m_x = m'_x ½ρL²d, m_y = m'_y ½ρL²d, J_z = J'_z ½ρL⁴d and
    I_zG = m (k_zz L)² of the parameters ``p``."""
    L = p.length
    m = p.rho * p.displacement
    scale = 0.5 * p.rho * L * L * p.draft
    k = p.gyration_radius * L
    return midship_accelerations(X, Y, N, u, v, r, m, p.m_x * scale, p.m_y * scale, m * k * k,
                                 p.J_z * scale * L * L, p.x_G)


@njit(cache=True)
def mmg_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of the MMG standard model for one run (module docstring)."""
    uu = x[S.surge_speed]
    v = x[S.sway_speed]
    r = x[S.yaw_rate]
    X_H, Y_H, N_H, X_P, X_R, Y_R, N_R, _T, _F_N, _w_P, _u_R, _v_R, _U, _b = _forces(
        uu, v, r, u[U.rudder_angle], u[U.propeller_rps], p)
    X = X_H + X_P + X_R + d[D.force_x]
    Yf = Y_H + Y_R + d[D.force_y]
    N = N_H + N_R + d[D.moment_z]
    du, dv, dr = mmg_accelerations(X, Yf, N, uu, v, r, p)
    write_mmg_rates(x, d, dx, du, dv, dr)


@njit(cache=True)
def write_mmg_rates(x, d, dx, du, dv, dr):  # pragma: no cover - compiled
    """The rates of the states every model of the MMG family has (:data:`STATES`, the first
    of ``mmg-4q``'s and ``mmg-ls``'s; their disturbances are :data:`DISTURBANCES`): the
    accelerations (u̇, v̇_m, ṙ) the model computed, and the kinematics
    (:func:`~seahelm.vessels.rigid_body.horizontal_velocity`): the velocities are through the
    water, the position moves with the current as well."""
    dx[S.surge_speed] = du
    dx[S.sway_speed] = dv
    dx[S.yaw_rate] = dr
    north, east = horizontal_velocity(x[S.surge_speed], x[S.sway_speed], x[S.heading],
                                      d[D.current_north], d[D.current_east])
    dx[S.north] = north
    dx[S.east] = east
    dx[S.heading] = x[S.yaw_rate]


@njit(cache=True)
def mmg_output(t, x, u, p, y):  # pragma: no cover - compiled
    """Outputs of the MMG model (``OUTPUTS`` order) for one run."""
    delta = u[U.rudder_angle]
    (_X_H, _Y_H, _N_H, _X_P, _X_R, _Y_R, _N_R, thrust, F_N, _w_P, u_R, v_R, speed,
     beta) = _forces(x[S.surge_speed], x[S.sway_speed], x[S.yaw_rate], delta,
                     u[U.propeller_rps], p)
    write_mmg_outputs(x, y, speed, beta, thrust, F_N, rudder_inflow_angle(delta, u_R, v_R))


@njit(cache=True)
def write_mmg_outputs(x, y, speed, beta, thrust, F_N, inflow_angle):  # pragma: no cover
    """The outputs every model of the MMG family has (:data:`OUTPUTS`, the first entries of
    ``mmg-4q``'s and ``mmg-ls``'s; their states begin with :data:`STATES`): the state's
    position, heading, rates and speeds, then ``speed``, ``drift_angle``, ``thrust``,
    ``rudder_normal_force`` and ``rudder_inflow_angle`` as the model computed them."""
    write_planar_outputs(y, x[S.north], x[S.east], x[S.heading], x[S.yaw_rate],
                         x[S.surge_speed], x[S.sway_speed], speed, beta)
    y[Y.thrust] = thrust
    y[Y.rudder_normal_force] = F_N
    y[Y.rudder_inflow_angle] = inflow_angle


@njit(cache=True)
def mmg_motion(x, p):  # pragma: no cover - compiled
    """Surge and sway speed through the water [m/s] and heading [rad] (for the loads), of
    every model of the MMG family (their states begin with :data:`STATES`)."""
    return x[S.surge_speed], x[S.sway_speed], x[S.heading]


MMG = VesselModel(
    name="mmg",
    description="MMG standard 3-DOF manoeuvring model (hull, propeller, rudder; midship "
    "origin), Yasukawa & Yoshimura (2015)",
    params_type=MMGParams,
    state_labels=STATES,
    state_units=STATE_UNITS,
    input_labels=INPUTS,
    input_units=INPUT_UNITS,
    disturbance_labels=DISTURBANCES,
    disturbance_units=DISTURBANCE_UNITS,
    rhs=mmg_rhs,
    output=mmg_output,
    output_labels=OUTPUTS,
    output_units=OUTPUT_UNITS,
    # the MMG standard method covers ahead motion: going astern marks the run diverged
    state_lower=(0.0, -np.inf, -np.inf, -np.inf, -np.inf, -np.inf),
    motion=mmg_motion,
    capabilities=frozenset({"shallow-water", "hull-identification", "engine-estimate",
                            "closed-form-self-propulsion"}),
)


class MMGForces(NamedTuple):
    """Force components of the MMG model for one state (SI units; moments about midship)."""

    X_H: float
    Y_H: float
    N_H: float
    X_P: float
    X_R: float
    Y_R: float
    N_R: float
    thrust: float
    rudder_normal_force: float
    rudder_inflow_angle: float
    wake_fraction: float
    rudder_inflow_u: float
    rudder_inflow_v: float
    speed: float
    drift_angle: float

    @property
    def X(self) -> float:
        """Total surge force X_H + X_P + X_R [N] (without external loads)."""
        return self.X_H + self.X_P + self.X_R

    @property
    def Y(self) -> float:
        """Total sway force Y_H + Y_R [N] (without external loads)."""
        return self.Y_H + self.Y_R

    @property
    def N(self) -> float:
        """Total yaw moment about midship N_H + N_R [N·m] (without external loads)."""
        return self.N_H + self.N_R


def force_components(params: MMGParams, state: Any, inputs: Any) -> MMGForces:
    """The hull, propeller and rudder forces of the MMG model for one state (diagnostics).

    Parameters
    ----------
    params : MMGParams
        Ship parameters.
    state : array_like, shape (6,)
        State (surge speed [m/s], midship sway speed [m/s], yaw rate [rad/s], north [m],
        east [m], heading [rad]); only the first three matter.
    inputs : array_like, shape (2,)
        Rudder angle [rad] and propeller rps [1/s].

    Returns
    -------
    MMGForces
        X_H, Y_H, N_H, X_P, X_R, Y_R, N_R [N, N·m], thrust T [N], rudder normal force F_N [N],
        effective rudder inflow angle α_R [rad], wake fraction w_P [-], rudder inflow
        velocities u_R, v_R [m/s], speed U [m/s] and drift angle β [rad].
    """
    if not isinstance(params, MMGParams):
        raise ParameterError(f"`params` must be MMGParams, got {type(params).__name__}")
    x = np.asarray(state, dtype=float)
    uin = np.asarray(inputs, dtype=float)
    if x.shape != (len(STATES),) or uin.shape != (len(INPUTS),):
        raise ParameterError(
            f"`state` must have shape ({len(STATES)},) and `inputs` ({len(INPUTS)},), got "
            f"{x.shape} and {uin.shape}")
    delta = float(uin[0])
    f = [float(v) for v in _forces(float(x[0]), float(x[1]), float(x[2]), delta,
                                   float(uin[1]), params.to_record())]
    alpha_R = float(rudder_inflow_angle(delta, f[10], f[11]))
    return MMGForces(*f[:9], alpha_R, *f[9:])


# ------------------------------------------------------------------------------------------
# KVLCC2 parameter sets (Yasukawa & Yoshimura 2015, KVLCC2 tables)
# ------------------------------------------------------------------------------------------
_KVLCC2_COMMON = (
    "KVLCC2 tanker, MMG standard method: Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol. "
    "20:37-52, tables of principal particulars and of the hydrodynamic coefficients "
    "(midship origin). Values cross-checked across independent open transcriptions of the "
    "paper; where they disagree the value used by every transcription of the L7 table is "
    "taken: w_P0 = 0.40 (0.35 appears in one tool, labelled assumed there: catalog entry "
    "'kvlcc2-l7-wp0-0.35'), k_2 = -0.1385 (-0.1359 elsewhere, negligible), x'_P = -0.48 "
    "(-0.65/-0.69 in tools with a different wake formula; -0.5 as the geometric propeller "
    "position: catalog entry 'kvlcc2-l7-xp-0.5'). I_zG = m (0.25 L_pp)^2; eta = D_P/H_R. "
    "x_R = x'_R L_pp in metres in N_R. Deep water."
)

KVLCC2_FULL_PROVENANCE = (
    _KVLCC2_COMMON + " Full scale: L_pp 320 m, B 58 m, d 20.8 m, displacement 312,600 m^3, "
    "x_G 11.2 m, D_P 9.86 m, H_R 15.8 m, A_R 112.5 m^2, sea water rho 1025 kg/m^3; test "
    "speed 15.5 kn (Fn 0.142). Rudder rate 2.34 deg/s (KVLCC2_FULL_SERVO)."
)
KVLCC2_L7_PROVENANCE = (
    _KVLCC2_COMMON + " L7 model (scale 1/45.7): L_pp 7.00 m, B 1.27 m, d 0.46 m, "
    "displacement 3.27 m^3, x_G 0.25 m, D_P 0.216 m, H_R 0.345 m, A_R 0.0539 m^2; fresh "
    "water rho 1000 kg/m^3 (model tests); test speed 1.179 m/s (Fn 0.142). Rudder rate "
    "15.8 deg/s (KVLCC2_L7_SERVO)."
)

#: KVLCC2 full scale (the :class:`MMGParams` defaults), sea water.
KVLCC2_FULL = MMGParams()

#: KVLCC2 L7 model (1/45.7), fresh water.
KVLCC2_L7 = MMGParams(
    length=7.00, breadth=1.27, draft=0.46, displacement=3.27, x_G=0.25,
    propeller_diameter=0.216, rudder_span=0.345, rudder_area=0.0539, rho=1000.0,
    approach_speed=1.179,
)

#: KVLCC2 L7 with the disputed w_P0 = 0.35 of one open tool (labelled "assumed" there).
KVLCC2_L7_WP0_035 = KVLCC2_L7.replace(w_P0=0.35)

#: KVLCC2 L7 with x'_P = −0.5, the geometric propeller position, in the same wake formula.
KVLCC2_L7_XP_050 = KVLCC2_L7.replace(x_P=-0.5)

#: Steering gear of the L7 free-running tests: ±35°, 15.8 °/s; a short lag (0.1 s) so that
#: the rate limit governs, as in the tests.
KVLCC2_L7_SERVO = ServoParams(max_angle=math.radians(35.0), max_rate=math.radians(15.8),
                              time_constant=0.1)

#: Full-scale steering gear: ±35°, 2.34 °/s; lag 0.1 s × √45.7 (Froude-scaled from the L7).
KVLCC2_FULL_SERVO = ServoParams(max_angle=math.radians(35.0), max_rate=math.radians(2.34),
                                time_constant=0.1 * math.sqrt(45.7))

