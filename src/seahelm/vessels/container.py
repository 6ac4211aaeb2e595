"""4-DOF (surge, sway, roll, yaw) manoeuvring model of the Son & Nomoto (1981, 1982) container ship.

The high-speed single-screw container ship (L = 175 m, B = 25.4 m, d = 8.5 m, ∇ = 21,222 m³,
GM = 0.3 m) whose coupled steering and rolling Son & Nomoto (1981, 1982) modelled from captive
tests, as tabulated in Fossen's Marine Systems Simulator (``container.m``, Lauvdal 1994, revised
by Fossen 2001–2024; the model of Fossen 2021, *Handbook of Marine Craft Hydrodynamics and Motion
Control*, 2nd ed., §7.5.3 / Appendix D). It is the manoeuvring model with roll: a turn heels the
ship, and the heel feeds back into the sway force and yaw moment.

Non-dimensional quantities use the speed U = √(u² + v²) and L: u' = u/U, v' = v/U, r' = rL/U,
p' = pL/U, n' = nL/U; forces over ½ρL²U², moments over ½ρL³U², masses over ½ρL³, inertias over
½ρL⁵. Equations (Son & Nomoto 1982, eqs. (1)–(4), in the form of ``container.m``), with the
Coriolis terms on the right-hand side::

    (m' + m'_x) u̇' = X' = X'_uu u'² + (1 − t) T' + X'_vr v'r' + X'_vv v'² + X'_rr r'² + X'_φφ φ²
                         + c_RX F'_N sin δ + (m' + m'_y) v'r'
    (m' + m'_y) v̇' − m'_y l'_y ṗ' + m'_y α_y ṙ' = Y' = Y_hull + (1 + a_H) F'_N cos δ
                                                      − (m' + m'_x) u'r'
    −m'_y l'_y v̇' + (I'_x + J'_x) ṗ' = K' = K_hull − (1 + a_H) z'_R F'_N cos δ + m'_x l'_x u'r'
                                             − W' GM' φ
    m'_y α_y v̇' + (I'_z + J'_z) ṙ' = N' = N_hull + (x'_R + a_H x'_H) F'_N cos δ

with the hull polynomials (Y, K and N alike)::

    Y_hull = Y_v v' + Y_r r' + Y_p p' + Y_φ φ + Y_vvv v'³ + Y_rrr r'³ + Y_vvr v'²r' + Y_vrr v'r'²
             + Y_vvφ v'²φ + Y_vφφ v'φ² + Y_rrφ r'²φ + Y_rφφ r'φ²

W' GM' φ = ρg∇ GM φ /(½ρL³U²). Propeller and rudder::

    u'_P = u' [(1 − w_p) + τ ((v' + x'_p r')² + c_pv v' + c_pr r')]
    J = u_P/(nD),  K_T = 0.527 − 0.455 J,  T = ρ D⁴ K_T n|n|
    u_R = ε u_P √(1 + 8 k K_T/(π J²)),  v'_R = γ v' + c_Rr r' + c_Rrrr r'³ + c_Rrrv r'² v'
    α_R = δ + atan(v_R/u_R),  F'_N = −(6.13 Λ/(Λ + 2.25)) (A_R/L²) (u'_R² + v'_R²) sin α_R

and the kinematics ẋ_N = u cos ψ − v cos φ sin ψ, ẏ_E = u sin ψ + v cos φ cos ψ, ψ̇ = r cos φ,
φ̇ = p (``container.m``; pitch neglected).

Sign conventions
    Body axes x forward, y to starboard, z down; ψ clockwise from north; roll φ positive with the
    starboard side down. A **positive rudder angle gives a positive (starboard) yaw rate**, as in
    ``container.m`` itself (there F_N < 0 for δ > 0 and x'_R + a_H x'_H < 0, so N > 0): no sign
    is flipped. In a steady turn to starboard the ship heels to port (φ < 0), outwards.

Exact rewritings (the same equations, finite where the printed form divides by zero)
    ``container.m`` stops at U = 0 or n ≤ 0. Here the thrust is T = ρD²(0.527 D² n|n| −
    0.455 D u_P |n|) (= ρD⁴K_T n|n| for n > 0, finite at n = 0) and the rudder inflow
    u_R = ε √max(0, u_P² + (8k/π)(0.527 n²D² − 0.455 u_P |n| D)) (= ε u_P √(1 + 8kK_T/(πJ²))
    for u_P > 0), α_R = δ + atan2(v_R, u_R). The non-dimensional velocities use
    U_f = max(U, Fn_min √(gL)) (``min_froude_number``) and every force keeps the factor U² of
    the actual speed; the Coriolis terms are written dimensionally. The restoring moment uses
    seahelm's g = 9.80665 m/s² (``container.m``: 9.81, 0.03 % stiffer). The model is for ahead
    motion (u > 0); a roll angle beyond ±90° (capsize) marks a run diverged.

External loads ``force_x``, ``force_y`` [N], ``moment_x`` (roll, K) and ``moment_z`` (yaw, N)
[N·m] add to X, Y, K, N; the current (``current_north``, ``current_east``) is handled as in the
MMG model (:mod:`seahelm.vessels.mmg`): the velocity states are relative to the water, and the
position moves with the current.

Actuators
    The steering gear of ``container.m`` (±10°, 5 °/s, δ̇ = δ_c − δ: a first-order lag of 1 s) is
    the ``rudder-servo`` actuator with :data:`CONTAINER_MSS_SERVO`; the catalog ship
    (``son-nomoto-container``) has the same rate and lag with ±35° (:data:`CONTAINER_SERVO`). The input ``propeller_rps`` is the
    actual shaft speed n [1/s] (MSS: rpm; 80 rpm = 4/3 1/s, limit 160 rpm); ``container.m``'s
    shaft lag (T_m = 5.65/n s) is not part of the model: at a constant shaft speed it does
    nothing.

References
----------
Son, K. H., Nomoto, K. (1981). On the coupled motion of steering and rolling of a high speed
container ship. J. Soc. Nav. Arch. Japan 150, 232–244. (English: Naval Architecture and Ocean
Engineering 20 (1982), 73–83.)
Fossen, T. I. Marine Systems Simulator (MSS), ``container.m`` (coefficient table), and Fossen
(2021), *Handbook of Marine Craft Hydrodynamics and Motion Control*, 2nd ed., Wiley.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..actuators.servo import ServoParams
from ..constants import GRAVITY
from ..errors import ParameterError
from ..parameters import Params, param, signal_indices
from .base import VesselModel
from .rigid_body import (PLANAR_OUTPUT_UNITS, PLANAR_OUTPUTS, horizontal_velocity,
                         write_planar_outputs)

__all__ = ["ContainerParams", "CONTAINER", "CONTAINER_SHIP", "CONTAINER_SERVO",
           "CONTAINER_MSS_SERVO", "CONTAINER_PROVENANCE", "STATES", "INPUTS", "DISTURBANCES", "OUTPUTS"]

STATES = ("surge_speed", "sway_speed", "yaw_rate", "north", "east", "heading", "roll_rate",
          "roll_angle")
STATE_UNITS = ("m/s", "m/s", "rad/s", "m", "m", "rad", "rad/s", "rad")
INPUTS = ("rudder_angle", "propeller_rps")
INPUT_UNITS = ("rad", "1/s")
DISTURBANCES = ("force_x", "force_y", "moment_x", "moment_z", "current_north", "current_east")
DISTURBANCE_UNITS = ("N", "N", "N·m", "N·m", "m/s", "m/s")
OUTPUTS = PLANAR_OUTPUTS + ("roll_angle", "roll_rate", "thrust", "rudder_normal_force")
OUTPUT_UNITS = PLANAR_OUTPUT_UNITS + ("rad", "rad/s", "N", "N")

S = signal_indices(STATES)
U = signal_indices(INPUTS)
D = signal_indices(DISTURBANCES)
Y = signal_indices(OUTPUTS)


def _c(value: float, symbol: str, doc: str) -> float:
    return param(value, unit="-", symbol=symbol, doc=doc)


def _pos(value: float, unit: str, symbol: str, doc: str) -> float:
    return param(value, unit=unit, symbol=symbol, low=0.0, low_inclusive=False, doc=doc)


@dataclass(frozen=True, kw_only=True)
class ContainerParams(Params):
    """Parameters of the Son & Nomoto (1982) container-ship model (``container.m`` values).

    Non-dimensional as in the module docstring; the main dimensions in SI units.
    """

    length: float = _pos(175.0, "m", "L", "length between perpendiculars")
    beam: float = _pos(25.4, "m", "B", "breadth (for reference; not in the equations)")
    draft: float = _pos(8.5, "m", "d", "mean draught (fore 8.0 m, aft 9.0 m; for reference)")
    displacement: float = _pos(21222.0, "m³", "∇", "displacement volume (restoring moment)")
    metacentric_height: float = _pos(0.3, "m", "GM", "transverse metacentric height")
    propeller_diameter: float = _pos(6.533, "m", "D", "propeller diameter")
    rudder_area: float = _pos(33.0376, "m²", "A_R", "rudder area")
    rudder_aspect_ratio: float = _pos(1.8219, "-", "Λ", "rudder aspect ratio")
    rho: float = _pos(1025.0, "kg/m³", "ρ", "water density (thrust and external loads)")
    approach_speed: float = _pos(7.0, "m/s", "U_0", "service speed (MSS: 7.0 m/s); not in "
                                 "the equations, default of the equilibrium helpers")
    min_froude_number: float = param(1e-3, unit="-", symbol="Fn_min", low=0.0,
                                     low_inclusive=False, high=0.1,
                                     doc="speed floor Fn_min √(g L) in u', v', r', p' (U → 0)")
    # masses and inertias
    mass: float = _pos(0.00792, "-", "m'", "mass over ½ρL³")
    m_x: float = _c(0.000238, "m'_x", "surge added mass")
    m_y: float = _c(0.007049, "m'_y", "sway added mass (MSS 2001 revision: 0.007049)")
    I_x: float = _pos(0.0000176, "-", "I'_x", "roll moment of inertia over ½ρL⁵")
    J_x: float = _c(0.0000034, "J'_x", "roll added inertia")
    I_z: float = _pos(0.000456, "-", "I'_z", "yaw moment of inertia over ½ρL⁵")
    J_z: float = _c(0.000419, "J'_z", "yaw added inertia")
    alpha_y: float = _c(0.05, "α_y", "x-position of the sway added mass, over L")
    l_x: float = _c(0.0313, "l'_x", "z-position of the surge added mass, over L")
    l_y: float = _c(0.0313, "l'_y", "z-position of the sway added mass, over L")
    # surge
    X_uu: float = _c(-0.0004226, "X'_uu", "surge resistance per u'²")
    X_vr: float = _c(-0.00311, "X'_vr", "surge force per v'r'")
    X_rr: float = _c(0.00020, "X'_rr", "surge force per r'²")
    X_phiphi: float = _c(-0.00020, "X'_φφ", "surge force per φ²")
    X_vv: float = _c(-0.00386, "X'_vv", "surge force per v'²")
    # roll
    K_v: float = _c(0.0003026, "K'_v", "roll moment per v'")
    K_r: float = _c(-0.000063, "K'_r", "roll moment per r'")
    K_p: float = _c(-0.0000075, "K'_p", "roll damping per p'")
    K_phi: float = _c(-0.000021, "K'_φ", "roll moment per φ")
    K_vvv: float = _c(0.002843, "K'_vvv", "roll moment per v'³")
    K_rrr: float = _c(-0.0000462, "K'_rrr", "roll moment per r'³")
    K_vvr: float = _c(-0.000588, "K'_vvr", "roll moment per v'²r'")
    K_vrr: float = _c(0.0010565, "K'_vrr", "roll moment per v'r'²")
    K_vvphi: float = _c(-0.0012012, "K'_vvφ", "roll moment per v'²φ")
    K_vphiphi: float = _c(-0.0000793, "K'_vφφ", "roll moment per v'φ²")
    K_rrphi: float = _c(-0.000243, "K'_rrφ", "roll moment per r'²φ")
    K_rphiphi: float = _c(0.00003569, "K'_rφφ", "roll moment per r'φ²")
    # sway
    Y_v: float = _c(-0.0116, "Y'_v", "sway force per v'")
    Y_r: float = _c(0.00242, "Y'_r", "sway force per r'")
    Y_p: float = _c(0.0, "Y'_p", "sway force per p'")
    Y_phi: float = _c(-0.000063, "Y'_φ", "sway force per φ")
    Y_vvv: float = _c(-0.109, "Y'_vvv", "sway force per v'³")
    Y_rrr: float = _c(0.00177, "Y'_rrr", "sway force per r'³")
    Y_vvr: float = _c(0.0214, "Y'_vvr", "sway force per v'²r'")
    Y_vrr: float = _c(-0.0405, "Y'_vrr", "sway force per v'r'²")
    Y_vvphi: float = _c(0.04605, "Y'_vvφ", "sway force per v'²φ")
    Y_vphiphi: float = _c(0.00304, "Y'_vφφ", "sway force per v'φ²")
    Y_rrphi: float = _c(0.009325, "Y'_rrφ", "sway force per r'²φ")
    Y_rphiphi: float = _c(-0.001368, "Y'_rφφ", "sway force per r'φ²")
    # yaw
    N_v: float = _c(-0.0038545, "N'_v", "yaw moment per v'")
    N_r: float = _c(-0.00222, "N'_r", "yaw moment per r'")
    N_p: float = _c(0.000213, "N'_p", "yaw moment per p'")
    N_phi: float = _c(-0.0001424, "N'_φ", "yaw moment per φ")
    N_vvv: float = _c(0.001492, "N'_vvv", "yaw moment per v'³")
    N_rrr: float = _c(-0.00229, "N'_rrr", "yaw moment per r'³")
    N_vvr: float = _c(-0.0424, "N'_vvr", "yaw moment per v'²r'")
    N_vrr: float = _c(0.00156, "N'_vrr", "yaw moment per v'r'²")
    N_vvphi: float = _c(-0.019058, "N'_vvφ", "yaw moment per v'²φ")
    N_vphiphi: float = _c(-0.0053766, "N'_vφφ", "yaw moment per v'φ²")
    N_rrphi: float = _c(-0.0038592, "N'_rrφ", "yaw moment per r'²φ")
    N_rphiphi: float = _c(0.0024195, "N'_rφφ", "yaw moment per r'φ²")
    # propeller and rudder
    thrust_deduction: float = param(0.175, unit="-", symbol="t", low=0.0, high=1.0,
                                    doc="thrust deduction factor")
    wake_fraction: float = param(0.184, unit="-", symbol="w_p", low=0.0, high=1.0,
                                 low_inclusive=True, doc="wake fraction in straight motion")
    k_0: float = _c(0.527, "k_0", "K_T = k_0 + k_1 J, constant term")
    k_1: float = _c(-0.455, "k_1", "K_T = k_0 + k_1 J, linear term")
    tau: float = _c(1.09, "τ", "wake change with (v' + x'_p r')²")
    x_p: float = _c(-0.526, "x'_p", "propeller position over L")
    c_pv: float = _c(0.0, "c_pv", "wake change per v'")
    c_pr: float = _c(0.0, "c_pr", "wake change per r'")
    kappa: float = _c(0.631, "k", "propeller slipstream factor at the rudder")
    epsilon: float = _c(0.921, "ε", "rudder-to-propeller inflow ratio")
    gamma: float = _c(0.088, "γ", "flow straightening of v' at the rudder")
    c_Rr: float = _c(-0.156, "c_Rr", "rudder inflow per r'")
    c_Rrrr: float = _c(-0.275, "c_Rrrr", "rudder inflow per r'³")
    c_Rrrv: float = _c(1.96, "c_Rrrv", "rudder inflow per r'²v'")
    c_RX: float = _c(0.71, "c_RX", "rudder drag factor")
    a_H: float = _c(0.237, "a_H", "hull force induced by the rudder")
    x_R: float = _c(-0.5, "x'_R", "rudder position over L")
    x_H: float = _c(-0.48, "x'_H", "position of the induced hull force over L")
    z_R: float = _c(0.033, "z'_R", "rudder force height over L (roll arm)")

    def validate(self) -> None:
        """Cross-field check: a positive definite sway–roll–yaw mass matrix."""
        m = self.mass_matrix()
        if not np.all(np.linalg.eigvalsh(m) > 0.0) or self.mass + self.m_x <= 0.0:
            raise ParameterError(
                "the mass matrix [m'+m'_y, −m'_y l'_y, m'_y α_y; −m'_y l'_y, I'_x+J'_x, 0; "
                "m'_y α_y, 0, I'_z+J'_z] (and m'+m'_x) must be positive definite [-]",
                field="mass", unit="-", value=self.mass)

    def mass_matrix(self) -> np.ndarray:
        """The sway–roll–yaw mass matrix (v̇', ṗ', ṙ' order) [-]."""
        m32, m42 = -self.m_y * self.l_y, self.m_y * self.alpha_y
        return np.array([[self.mass + self.m_y, m32, m42], [m32, self.I_x + self.J_x, 0.0],
                         [m42, 0.0, self.I_z + self.J_z]])

    def roll_period(self) -> float:
        """Undamped natural roll period 2π √((I'_x + J'_x) ½ρL⁵/(ρg∇ GM)) [s] (29.3 s)."""
        inertia = (self.I_x + self.J_x) * 0.5 * self.length ** 5
        return 2.0 * math.pi * math.sqrt(
            inertia / (GRAVITY * self.displacement * self.metacentric_height))


@njit(cache=True)
def _forces(uu, v, r, pr, phi, delta, n, p):  # pragma: no cover - compiled
    """(X', Y', K', N') × U² (without the external loads), thrust [N], F_N [N], U [m/s]."""
    L = p.length
    speed = math.sqrt(uu * uu + v * v)
    uf = max(speed, p.min_froude_number * math.sqrt(GRAVITY * L))
    un = uu / uf
    vn = v / uf
    rn = r * L / uf
    pn = pr * L / uf
    U2 = speed * speed
    # propeller: thrust and the rudder inflow in forms finite at n = 0 (module docstring)
    Dp = p.propeller_diameter
    wake = (1.0 - p.wake_fraction) + p.tau * ((vn + p.x_p * rn) ** 2 + p.c_pv * vn
                                               + p.c_pr * rn)
    u_P = uu * wake  # [m/s]
    an = abs(n)
    thrust = p.rho * Dp * Dp * (p.k_0 * Dp * Dp * n * an + p.k_1 * Dp * u_P * an)
    slip = u_P * u_P + 8.0 * p.kappa / math.pi * (p.k_0 * n * n * Dp * Dp
                                                  + p.k_1 * u_P * an * Dp)
    u_R = p.epsilon * math.sqrt(max(slip, 0.0))  # [m/s]
    v_R = uf * (p.gamma * vn + p.c_Rr * rn + p.c_Rrrr * rn * rn * rn
                + p.c_Rrrv * rn * rn * vn)  # [m/s]
    alpha_R = delta + math.atan2(v_R, u_R)
    lam = p.rudder_aspect_ratio
    # F'_N U² (force over ½ρL²)
    fn = -(6.13 * lam / (lam + 2.25)) * (p.rudder_area / (L * L)) * (u_R * u_R + v_R * v_R) \
        * math.sin(alpha_R)
    half_rho_l2 = 0.5 * p.rho * L * L
    cd = math.cos(delta)
    X = ((p.X_uu * un * un + p.X_vr * vn * rn + p.X_vv * vn * vn + p.X_rr * rn * rn
          + p.X_phiphi * phi * phi) * U2 + (1.0 - p.thrust_deduction) * thrust / half_rho_l2
         + p.c_RX * fn * math.sin(delta) + (p.mass + p.m_y) * v * r * L)
    vv = vn * vn
    rr = rn * rn
    ph2 = phi * phi
    Yh = (p.Y_v * vn + p.Y_r * rn + p.Y_p * pn + p.Y_phi * phi + p.Y_vvv * vv * vn
          + p.Y_rrr * rr * rn + p.Y_vvr * vv * rn + p.Y_vrr * vn * rr + p.Y_vvphi * vv * phi
          + p.Y_vphiphi * vn * ph2 + p.Y_rrphi * rr * phi + p.Y_rphiphi * rn * ph2)
    Kh = (p.K_v * vn + p.K_r * rn + p.K_p * pn + p.K_phi * phi + p.K_vvv * vv * vn
          + p.K_rrr * rr * rn + p.K_vvr * vv * rn + p.K_vrr * vn * rr + p.K_vvphi * vv * phi
          + p.K_vphiphi * vn * ph2 + p.K_rrphi * rr * phi + p.K_rphiphi * rn * ph2)
    Nh = (p.N_v * vn + p.N_r * rn + p.N_p * pn + p.N_phi * phi + p.N_vvv * vv * vn
          + p.N_rrr * rr * rn + p.N_vvr * vv * rn + p.N_vrr * vn * rr + p.N_vvphi * vv * phi
          + p.N_vphiphi * vn * ph2 + p.N_rrphi * rr * phi + p.N_rphiphi * rn * ph2)
    restoring = GRAVITY * p.displacement * p.metacentric_height / (0.5 * L * L * L)
    Yf = Yh * U2 + (1.0 + p.a_H) * fn * cd - (p.mass + p.m_x) * uu * r * L
    K = (Kh * U2 - (1.0 + p.a_H) * p.z_R * fn * cd + p.m_x * p.l_x * uu * r * L
         - restoring * phi)
    N = Nh * U2 + (p.x_R + p.a_H * p.x_H) * fn * cd
    return X, Yf, K, N, thrust, fn * half_rho_l2, speed


@njit(cache=True)
def container_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of the container-ship model for one run (module docstring)."""
    uu = x[S.surge_speed]
    v = x[S.sway_speed]
    r = x[S.yaw_rate]
    pr = x[S.roll_rate]
    phi = x[S.roll_angle]
    psi = x[S.heading]
    X, Yf, K, N, _T, _F, _U = _forces(uu, v, r, pr, phi, u[U.rudder_angle],
                                      u[U.propeller_rps], p)
    L = p.length
    half_rho_l2 = 0.5 * p.rho * L * L
    X = X + d[D.force_x] / half_rho_l2
    Yf = Yf + d[D.force_y] / half_rho_l2
    K = K + d[D.moment_x] / (half_rho_l2 * L)
    N = N + d[D.moment_z] / (half_rho_l2 * L)
    m22 = p.mass + p.m_y
    m32 = -p.m_y * p.l_y
    m42 = p.m_y * p.alpha_y
    m33 = p.I_x + p.J_x
    m44 = p.I_z + p.J_z
    det = m22 * m33 * m44 - m32 * m32 * m44 - m42 * m42 * m33
    # [m22 m32 m42; m32 m33 0; m42 0 m44] [L v̇, L² ṗ, L² ṙ] = [Y', K', N'] U² (exact inverse)
    dx[S.surge_speed] = X / ((p.mass + p.m_x) * L)
    dx[S.sway_speed] = (m33 * m44 * Yf - m32 * m44 * K - m42 * m33 * N) / (det * L)
    dx[S.roll_rate] = (-m32 * m44 * Yf + (m22 * m44 - m42 * m42) * K + m32 * m42 * N) \
        / (det * L * L)
    dx[S.yaw_rate] = (-m42 * m33 * Yf + m32 * m42 * K + (m22 * m33 - m32 * m32) * N) \
        / (det * L * L)
    # the sway velocity projected on the horizontal plane (roll φ)
    north, east = horizontal_velocity(uu, v * math.cos(phi), psi, d[D.current_north],
                                      d[D.current_east])
    dx[S.north] = north
    dx[S.east] = east
    dx[S.heading] = r * math.cos(phi)
    dx[S.roll_angle] = pr


@njit(cache=True)
def container_output(t, x, u, p, y):  # pragma: no cover - compiled
    """Outputs of the container-ship model (``OUTPUTS`` order) for one run."""
    uu = x[S.surge_speed]
    v = x[S.sway_speed]
    _X, _Y, _K, _N, thrust, F_N, speed = _forces(
        uu, v, x[S.yaw_rate], x[S.roll_rate], x[S.roll_angle], u[U.rudder_angle],
        u[U.propeller_rps], p)
    write_planar_outputs(y, x[S.north], x[S.east], x[S.heading], x[S.yaw_rate], uu, v, speed,
                         math.atan2(-v, uu))
    y[Y.roll_angle] = x[S.roll_angle]
    y[Y.roll_rate] = x[S.roll_rate]
    y[Y.thrust] = thrust
    y[Y.rudder_normal_force] = F_N


@njit(cache=True)
def container_motion(x, p):  # pragma: no cover - compiled
    """Surge and sway speed through the water [m/s] and heading [rad] (for the loads)."""
    return x[S.surge_speed], x[S.sway_speed], x[S.heading]


_HALF_PI = 0.5 * math.pi

CONTAINER = VesselModel(
    name="container",
    description="Son & Nomoto (1982) container ship, nonlinear 4-DOF model with roll (surge, "
    "sway, roll, yaw; rudder and shaft speed), as in Fossen's MSS container.m",
    params_type=ContainerParams,
    state_labels=STATES,
    state_units=STATE_UNITS,
    input_labels=INPUTS,
    input_units=INPUT_UNITS,
    disturbance_labels=DISTURBANCES,
    disturbance_units=DISTURBANCE_UNITS,
    rhs=container_rhs,
    output=container_output,
    output_labels=OUTPUTS,
    output_units=OUTPUT_UNITS,
    # ahead motion only; a heel beyond 90 deg is a capsize: both mark a run diverged
    state_lower=(0.0, -np.inf, -np.inf, -np.inf, -np.inf, -np.inf, -np.inf, -_HALF_PI),
    state_upper=(np.inf,) * 7 + (_HALF_PI,),
    motion=container_motion,
)

CONTAINER_PROVENANCE = (
    "High-speed container ship of Son & Nomoto (1981), J. Soc. Nav. Arch. Japan 150, and "
    "(1982), Naval Architecture and Ocean Engineering 20:73-83: nonlinear 4-DOF (surge, sway, "
    "roll, yaw) model as tabulated in Fossen's Marine Systems Simulator (container.m, Lauvdal "
    "1994; m'_y = 0.007049 per the 2001 revision; u_P = u (...) per the 2022 correction). "
    "L 175 m, B 25.4 m, d 8.5 m, displacement 21,222 m^3, GM 0.3 m, D 6.533 m, A_R 33.04 m^2. "
    "Rudder sign as in container.m (positive rudder -> positive yaw rate). Shaft speed in 1/s "
    "(MSS: rpm, limit 160 rpm); container.m's shaft lag is not modelled.")

#: The container-ship parameter set (the :class:`ContainerParams` defaults).
CONTAINER_SHIP = ContainerParams()

#: The steering gear of ``container.m`` for ``RUDDER_SERVO``: ±10°, 5 °/s, lag 1 s (MSS's
#: conditions, the validation's).
CONTAINER_MSS_SERVO = ServoParams(max_angle=math.radians(10.0), max_rate=math.radians(5.0),
                                  time_constant=1.0)

#: The catalog ship's steering gear: ``container.m``'s rate (5 °/s) and lag (1 s) with the usual
#: hard-over angle of ±35° (SOLAS II-1/29) instead of MSS's ±10°, so that the IMO check's 35°
#: turning circles and 20°/20° zig-zags can run (rudder angles beyond 10° extrapolate the model).
CONTAINER_SERVO = ServoParams(max_angle=math.radians(35.0), max_rate=math.radians(5.0),
                              time_constant=1.0)
