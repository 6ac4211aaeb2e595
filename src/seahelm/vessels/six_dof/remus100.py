"""The REMUS 100 AUV: Fossen's 6-DOF model of the vehicle (Prestero 2001; Allen et al. 2000), as
data on the rigid-body model.

A 1.6 m × 0.19 m torpedo-shaped vehicle (spheroid mass 4/3 π ρ a b² ≈ 31.9 kg, neutrally
buoyant, CG 0.02 m below the CB), steered by a tail rudder and stern planes, driven by one
propeller. The numbers and the way the matrices follow from them are those of Fossen (2021),
§8.4.2, as implemented in Fossen's MSS (``remus100.m``) and PythonVehicleSimulator
(``vehicles/remus100.py``):

* rigid body of a prolate spheroid with semi-axes a = L/2, b = D/2: I_x = (2/5) m b²,
  I_y = I_z = (1/5) m (a² + b²); r_g = (0, 0, 0.02) m, r_b = 0; W = B = m g;
* added mass from Lamb's k-factors (k₁, k₂, k′ of the spheroid's eccentricity), roll
  A₄₄ = 0.3 I_x; in C_A the pitch and yaw Munk terms (elements (5,1), (1,5), (5,3), (3,5),
  (6,1), (1,6), (6,2), (2,6)) are removed, as published;
* linear damping from time constants (surge, sway, heave 20 s, yaw 1 s) and relative damping
  in roll (0.3) and pitch (0.8) at the natural frequencies; surge and sway fading as
  exp(−3 U_r); hull lift and drag (C_D0 = 0.42 π b²/S, S = 0.7 L D); cross-flow drag with
  Hoerner's C_d(D/2D);
* fins (area 2 × 0.00665 m² each pair, at x = −a): rudder C_Lδ = 0.5, stern planes 0.7,
  ±15°, T = 0.1 s;
* propeller D = 0.14 m, K_T linear in J from the Wageningen B-series (K_T0 = 0.4566,
  K_T(J = 0.6632) = 0.1798; K_Q0 = 0.0700, K_Q = 0.0312), wake V_a = 0.944 U, thrust
  deduction 0.1, the shaft moment scaled by 1/10 "to match experimental results", ≤ 1525 rpm,
  T_n = 1 s. seahelm takes the shaft speed in rad/s (PVS: rpm).

References
----------
Prestero, T. (2001). Verification of a six-degree of freedom simulation model for the REMUS
autonomous underwater vehicle. MSc thesis, MIT/WHOI.
Allen, B., Vorus, W. S., Prestero, T. (2000). Propulsion system performance enhancements on
REMUS AUVs. OCEANS 2000, 1869-1873.
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.,
§8.4.2. PythonVehicleSimulator ``vehicles/remus100.py`` (commit c717e07).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .model import six_dof_model
from .params import FIN_RUDDER, FIN_STERN_PLANE, SixDofParams, hoerner_cross_flow_coefficient

__all__ = ["REMUS100", "Remus100Params", "remus100_params", "REMUS100_PROVENANCE",
           "RPM"]

#: 1 rpm in rad/s.
RPM = 2.0 * math.pi / 60.0


@dataclass(frozen=True, kw_only=True)
class Remus100Params(SixDofParams):
    """:class:`SixDofParams` of a craft laid out as the REMUS 100: one propeller, two fins
    (rudder, stern planes)."""

    layout: ClassVar[tuple[int, tuple[int, ...], int] | None] = (1, (0,), 2)


REMUS100_PROVENANCE = (
    "Fossen (2021), Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed., 8.4.2, "
    "the REMUS 100 AUV after Prestero (2001) and Allen et al. (2000), as in MSS remus100.m and "
    "PythonVehicleSimulator vehicles/remus100.py (commit c717e07): L = 1.6 m, D = 0.19 m, "
    "spheroid mass and inertia, Lamb's k-factors, r_g = (0, 0, 0.02) m, fins 2 x 0.00665 m^2 "
    "(C_L 0.5 rudder, 0.7 stern planes), propeller 0.14 m with linear K_T(J); matrices computed "
    "by seahelm.vessels.six_dof.remus100.remus100_params."
)


def remus100_params(**changes: Any) -> Remus100Params:
    """The REMUS 100's parameters from its published data (module docstring).

    Parameters
    ----------
    **changes
        Any :class:`SixDofParams` field, set after the computation.

    Returns
    -------
    Remus100Params
    """
    rho, g = 1026.0, 9.81
    length, diam = 1.6, 0.19
    area = 0.7 * length * diam
    a, b = length / 2.0, diam / 2.0
    m = 4.0 / 3.0 * math.pi * rho * a * b * b
    ix = 0.4 * m * b * b
    iy = 0.2 * m * (a * a + b * b)
    zg = 0.02
    e = math.sqrt(1.0 - (b / a) ** 2)
    log = math.log((1.0 + e) / (1.0 - e))
    alpha0 = 2.0 * (1.0 - e * e) / e**3 * (0.5 * log - e)
    beta0 = 1.0 / e**2 - (1.0 - e * e) / (2.0 * e**3) * log
    k1 = alpha0 / (2.0 - alpha0)
    k2 = beta0 / (2.0 - beta0)
    kp = e**4 * (beta0 - alpha0) / ((2.0 - e * e)
                                    * (2.0 * e * e - (2.0 - e * e) * (beta0 - alpha0)))
    added = np.diag([m * k1, m * k2, m * k2, 0.3 * ix, kp * iy, kp * iy])
    # M = M_RB + M_A about CO (M_RB of the spheroid moved by r_g)
    p0 = Remus100Params(mass=m, center_of_gravity=(0.0, 0.0, zg),
                        inertia_cg=(ix, 0.0, 0.0, 0.0, iy, 0.0, 0.0, 0.0, iy),
                        added_mass=tuple(added.ravel()), thruster_count=1.0,
                        thruster_k_pos=(1.0, 0.0, 0.0, 0.0), thruster_k_neg=(1.0, 0.0, 0.0, 0.0),
                        fin_count=2.0, hull_length=length, hull_beam=diam, hull_height=diam)
    mm = p0.mass_matrix
    w = m * g
    w_roll = math.sqrt(w * zg / mm[3, 3])
    w_pitch = math.sqrt(w * zg / mm[4, 4])
    damping = np.diag([mm[0, 0] / 20.0, mm[1, 1] / 20.0, mm[2, 2] / 20.0,
                       mm[3, 3] * 2.0 * 0.3 * w_roll, mm[4, 4] * 2.0 * 0.8 * w_pitch,
                       mm[5, 5] / 1.0])
    mask = np.ones((6, 6))
    for i, j in ((4, 0), (4, 2), (5, 0), (5, 1)):
        mask[i, j] = mask[j, i] = 0.0
    # propeller: K_T = K_T0 + (K_Tmax − K_T0)/J_max J with n in rps; here n in rad/s
    d_p, j_max = 0.14, 0.6632
    kt0, kt_max, kq0, kq_max = 0.4566, 0.1798, 0.0700, 0.0312
    two_pi = 2.0 * math.pi
    k_pos = rho * d_p**4 * kt0 / two_pi**2
    k_adv = rho * d_p**3 * (kt_max - kt0) / j_max / two_pi
    q_pos = rho * d_p**5 * kq0 / two_pi**2 / 10.0
    q_adv = rho * d_p**4 * (kq_max - kq0) / j_max / two_pi / 10.0
    s_fin = 0.00665
    n_max = 1525.0 * RPM
    values: dict[str, Any] = dict(
        linear_damping=tuple(damping.ravel()),
        linear_damping_decay=3.0,
        added_mass_coriolis_mask=tuple(mask.ravel()),
        weight=w, buoyancy=w, center_of_buoyancy=(0.0, 0.0, 0.0),
        water_density=rho,
        cross_flow_length=length, cross_flow_draft=diam,
        cross_flow_coefficient=hoerner_cross_flow_coefficient(diam, diam),
        cross_flow_strips=20.0,
        hull_lift_span=diam, hull_lift_area=area,
        hull_drag_coefficient=0.42 * math.pi * b * b / area, hull_lift_efficiency=0.7,
        thruster_x=(-a, 0.0, 0.0, 0.0),
        thruster_k_pos=(k_pos, 0.0, 0.0, 0.0), thruster_k_neg=(k_pos, 0.0, 0.0, 0.0),
        thruster_k_advance=(k_adv, 0.0, 0.0, 0.0),
        thruster_torque_pos=(q_pos, 0.0, 0.0, 0.0),
        thruster_torque_advance=(q_adv, 0.0, 0.0, 0.0),
        thruster_wake=(1.0 - 0.944, 0.0, 0.0, 0.0),
        thruster_deduction=(0.1, 0.0, 0.0, 0.0),
        thruster_time_constant=(1.0, 0.1, 0.1, 0.1),
        thruster_max_speed=(n_max, 100.0, 100.0, 100.0),
        thruster_min_speed=(-n_max, -100.0, -100.0, -100.0),
        fin_kind=(FIN_RUDDER, FIN_STERN_PLANE, 0.0, 0.0),
        fin_x=(-a, -a, 0.0, 0.0),
        fin_area=(2.0 * s_fin, 2.0 * s_fin, 0.0, 0.0),
        fin_lift_slope=(0.5, 0.7, 0.0, 0.0),
        fin_time_constant=(0.1, 0.1, 0.1, 0.1),
        fin_max_angle=(math.radians(15.0), math.radians(15.0), 0.5, 0.5),
    )
    values.update(changes)
    return p0.replace(**values)


REMUS100 = six_dof_model(
    "remus100", "REMUS 100 AUV, 6 DOF with Euler angles: propeller, tail rudder, stern planes "
    "(Fossen 2021 after Prestero 2001; MSS/PVS remus100)", Remus100Params,
    thrusters=("propeller",), fins=("rudder", "stern_plane"), submerged=True)
