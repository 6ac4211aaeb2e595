"""The Otter USV (Maritime Robotics): Fossen's published 6-DOF model, as data.

A 2.0 m × 1.08 m catamaran of 55 kg with a 25 kg payload, driven by two fixed propellers on
the pontoons (differential thrust steers it). The numbers and the way the matrices follow
from them are those of Fossen (2021), §8.x Otter example, as implemented in Fossen's MSS
(``otter.m``) and PythonVehicleSimulator (``vehicles/otter.py``):

* mass m = 55 kg (hull), payload m_p = 25 kg at r_p = (0.05, 0, −0.35) m; hull CG at
  (0.2, 0, −0.2) m, the CG r_g is the mass-weighted mean; radii of gyration R44 = 0.4 B,
  R55 = R66 = 0.25 L; the inertia dyadic used about the CG is
  I_g = m diag(R44², R55², R66²) − m S(r_g)² − m_p S(r_p)² (as published; MSS PR #78
  discusses it), M_RB = H(r_g)ᵀ diag((m + m_p) I₃, I_g) H(r_g);
* added mass X_u̇ = −0.1 m, Y_v̇ = −1.5 m, Z_ẇ = −m, K_ṗ = −0.2 I_g,11, M_q̇ = −0.8 I_g,22,
  N_ṙ = −1.7 I_g,33 (diagonal);
* hydrostatics of two pontoons (B_p = 0.25 m, y_p = ±0.395 m, C_w = 0.75, C_b = 0.4):
  ∇ = (m + m_p)/ρ, draft T = ∇/(2 C_b B_p L), G33 = 2 ρ g A_w, G44 = ρ g ∇ GM_T,
  G55 = ρ g ∇ GM_L, moved from the centre of flotation x = −0.2 m to CO by H;
* linear damping X_u = −24.4 g/U_max (U_max = 6 kn), Y_v = −M22/T_sway, N_r = −M66/T_yaw
  (T = 1 s), Z_w, K_p, M_q from relative damping 0.3, 0.2, 0.4 at the natural frequencies;
  quadratic yaw damping 10 |D66| |r| r; cross-flow drag with Hoerner's C_d(B_p/2T);
* propellers at y = ∓0.395 m (port, starboard), k_pos = 0.02216/2, k_neg = 0.01289/2 N·s²
  (bollard pull 24.4 kg ahead, 13.6 kg astern for both), n_max = √(½ 24.4 g/k_pos),
  n_min = −√(½ 13.6 g/k_neg) [rad/s], motor lag T_n = 0.1 s; ρ = 1025 kg/m³ in the
  hydrostatics, 1026 kg/m³ in the cross-flow drag (as published).

:func:`otter_params` computes these; the catalog ship file ``otter.toml`` holds the result.

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley. Chapters 3, 4, 6 (the model), 8 (the Otter USV example).
Fossen, T. I. PythonVehicleSimulator, ``vehicles/otter.py`` (commit c717e07).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .model import six_dof_model
from .params import SixDofParams, hoerner_cross_flow_coefficient
from .rigid_body import skew, system_transformation

__all__ = ["OTTER", "OTTER_QUATERNION", "OtterParams", "otter_params", "OTTER_PROVENANCE",
           "OTTER_THRUSTERS",
           "OTTER_YAW_INERTIA"]

OTTER_THRUSTERS = ("propeller_port", "propeller_starboard")

#: Moment of inertia in yaw including added mass used by the published heading autopilot
#: [kg·m²] (PVS ``headingAutopilot``: m = 41.4, a Nomoto model with T = 1 s).
OTTER_YAW_INERTIA = 41.4


@dataclass(frozen=True, kw_only=True)
class OtterParams(SixDofParams):
    """:class:`SixDofParams` of a craft laid out as the Otter: two fixed propellers, no fins."""

    layout: ClassVar[tuple[int, tuple[int, ...], int] | None] = (2, (0, 0), 0)


OTTER_PROVENANCE = (
    "Fossen (2021), Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed., the "
    "Otter USV (Maritime Robotics) example, as in MSS otter.m and PythonVehicleSimulator "
    "vehicles/otter.py (commit c717e07): m = 55 kg, payload 25 kg at (0.05, 0, -0.35) m, hull "
    "CG (0.2, 0, -0.2) m, L = 2.0 m, B = 1.08 m, pontoons B = 0.25 m at y = +-0.395 m, "
    "Cw = 0.75, Cb = 0.4, added mass and damping by the published rules of thumb, "
    "k_pos = 0.01108, k_neg = 0.006445 N s^2 per propeller, T_n = 0.1 s; matrices computed by "
    "seahelm.vessels.six_dof.otter.otter_params."
)


def otter_params(*, mass: float = 55.0, payload: float = 25.0,
                 payload_position: tuple[float, float, float] = (0.05, 0.0, -0.35),
                 **changes: Any) -> OtterParams:
    """The Otter's parameters from its published data (module docstring).

    Parameters
    ----------
    mass : float, optional
        Hull mass m [kg] (default 55).
    payload : float, optional
        Payload m_p [kg] (default 25).
    payload_position : tuple of float, optional
        Where the payload sits, from CO [m] (default (0.05, 0, −0.35)).
    **changes
        Any :class:`SixDofParams` field, set after the computation.

    Returns
    -------
    OtterParams
    """
    rho, g = 1025.0, 9.81  # as published (Fossen's models take g = 9.81 m/s²)
    length, beam = 2.0, 1.08
    m, mp = float(mass), float(payload)
    rp = np.asarray(payload_position, dtype=float)
    rg = (m * np.array([0.2, 0.0, -0.2]) + mp * rp) / (m + mp)
    radii = np.array([0.4 * beam, 0.25 * length, 0.25 * length])
    s_rg, s_rp = skew(rg), skew(rp)
    inertia = m * np.diag(radii**2) - m * s_rg @ s_rg - mp * s_rp @ s_rp
    m_cg = np.zeros((6, 6))
    m_cg[0:3, 0:3] = (m + mp) * np.eye(3)
    m_cg[3:6, 3:6] = inertia
    h = system_transformation(rg)
    m_rb = h.T @ m_cg @ h
    added = np.diag([0.1 * m, 1.5 * m, 1.0 * m, 0.2 * inertia[0, 0], 0.8 * inertia[1, 1],
                     1.7 * inertia[2, 2]])
    mtot = m_rb + added
    # hydrostatics of the two pontoons
    b_p, y_p, cw, cb = 0.25, 0.395, 0.75, 0.4
    volume = (m + mp) / rho
    draft = volume / (2.0 * cb * b_p * length)
    a_w = cw * length * b_p
    i_t = (2.0 / 12.0 * length * b_p**3 * (6.0 * cw**3 / ((1.0 + cw) * (1.0 + 2.0 * cw)))
           + 2.0 * a_w * y_p**2)
    i_l = 0.8 * 2.0 / 12.0 * b_p * length**3
    kb = (2.5 * draft - 0.5 * volume / (length * b_p)) / 3.0
    kg = draft - rg[2]
    gm_t = kb + i_t / volume - kg
    gm_l = kb + i_l / volume - kg
    g33 = rho * g * 2.0 * a_w
    g44 = rho * g * volume * gm_t
    g55 = rho * g * volume * gm_l
    h_cf = system_transformation(np.array([-0.2, 0.0, 0.0]))
    stiffness = h_cf.T @ np.diag([0.0, 0.0, g33, g44, g55, 0.0]) @ h_cf
    w3 = math.sqrt(g33 / mtot[2, 2])
    w4 = math.sqrt(g44 / mtot[3, 3])
    w5 = math.sqrt(g55 / mtot[4, 4])
    u_max = 6.0 * 0.5144
    damping = np.diag([24.4 * g / u_max, mtot[1, 1] / 1.0, 2.0 * 0.3 * w3 * mtot[2, 2],
                       2.0 * 0.2 * w4 * mtot[3, 3], 2.0 * 0.4 * w5 * mtot[4, 4],
                       mtot[5, 5] / 1.0])
    k_pos, k_neg = 0.02216 / 2.0, 0.01289 / 2.0
    n_max = math.sqrt(0.5 * 24.4 * g / k_pos)
    n_min = -math.sqrt(0.5 * 13.6 * g / k_neg)
    values: dict[str, Any] = dict(
        mass=m + mp,
        center_of_gravity=tuple(rg),
        inertia_cg=tuple(inertia.ravel()),
        added_mass=tuple(added.ravel()),
        linear_damping=tuple(damping.ravel()),
        quadratic_damping=(0.0, 0.0, 0.0, 0.0, 0.0, 10.0 * damping[5, 5]),
        hydrostatic_stiffness=tuple(stiffness.ravel()),
        payload_weight=mp * g,
        payload_position=tuple(rp),
        water_density=1026.0,
        cross_flow_length=length,
        cross_flow_draft=draft,
        cross_flow_coefficient=hoerner_cross_flow_coefficient(b_p, draft),
        cross_flow_strips=20.0,
        thruster_count=2.0,
        thruster_x=(0.0, 0.0, 0.0, 0.0),
        thruster_y=(-y_p, y_p, 0.0, 0.0),
        thruster_z=(0.0, 0.0, 0.0, 0.0),
        thruster_k_pos=(k_pos, k_pos, 0.0, 0.0),
        thruster_k_neg=(k_neg, k_neg, 0.0, 0.0),
        thruster_time_constant=(0.1, 0.1, 0.1, 0.1),
        thruster_max_speed=(n_max, n_max, 100.0, 100.0),
        thruster_min_speed=(n_min, n_min, -100.0, -100.0),
        hull_length=length,
        hull_beam=beam,
        hull_height=1.0,
    )
    values.update(changes)
    return OtterParams(**values)


OTTER = six_dof_model(
    "otter", "Otter USV (Maritime Robotics), 6 DOF with Euler angles, two propellers "
    "(Fossen 2021; MSS/PVS otter)", OtterParams, thrusters=OTTER_THRUSTERS)
OTTER_QUATERNION = six_dof_model(
    "otter-quaternion", "Otter USV, 6 DOF with a unit quaternion (13 rigid-body states)",
    OtterParams, thrusters=OTTER_THRUSTERS, kinematics="quaternion")
