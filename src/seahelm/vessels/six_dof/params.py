"""Parameters of a 6-DOF craft: mass properties, added mass, damping, restoring, thrusters, fins.

Matrices are flat row-major vectors of 36 numbers (``added_mass[6*i + j]`` is M_A,ij) in the
body frame about the body origin CO; vectors of thruster and fin data hold up to
:data:`MAX_THRUSTERS` / :data:`MAX_FINS` entries, of which the first ``thruster_count`` /
``fin_count`` are used (the rest are ignored; the ship file keeps them zero). SI units, radians;
a propeller's shaft speed is in rad/s.

What the right-hand side (:mod:`seahelm.vessels.six_dof.model`) does with each field is in the
field's doc; the equations are in :mod:`seahelm.vessels.six_dof.rigid_body` and the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...errors import ParameterError
from ...parameters import Params, param
from .rigid_body import rigid_body_mass_matrix

__all__ = ["SixDofParams", "MAX_THRUSTERS", "MAX_FINS", "FIN_RUDDER", "FIN_STERN_PLANE",
           "hoerner_cross_flow_coefficient", "mass_matrix"]

MAX_THRUSTERS = 4
MAX_FINS = 4
#: ``fin_kind`` values: a vertical fin (rudder: sway force, yaw moment) and a horizontal one
#: (stern plane: heave force, pitch moment).
FIN_RUDDER, FIN_STERN_PLANE = 0.0, 1.0

_Z36 = (0.0,) * 36
_ZT = (0.0,) * MAX_THRUSTERS
_ZF = (0.0,) * MAX_FINS
_BIG = 1.0e9


def _vec(n: int, value: float) -> tuple[float, ...]:
    return (float(value),) * n


@dataclass(frozen=True, kw_only=True)
class SixDofParams(Params):
    """A marine craft in 6 DOF (Fossen 2021, ch. 3, 4, 6, 7); see the module docstring.

    The defaults are a neutrally buoyant 1 m sphere-like body without damping or actuators
    (for tests); a craft's parameters come from its ship file.
    """

    mass: float = param(100.0, unit="kg", symbol="m", low=0.0, low_inclusive=False,
                        doc="rigid-body mass (including payload)")
    center_of_gravity: tuple = param((0.0, 0.0, 0.0), unit="m", symbol="r_g", size=3,
                                     doc="CG from the body origin CO (x fwd, y stbd, z down)")
    inertia_cg: tuple = param((10.0, 0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 10.0), unit="kg·m²",
                              symbol="I_g", size=9, doc="inertia dyadic about the CG (3×3)")
    added_mass: tuple = param(_Z36, unit="SI", symbol="M_A", size=36,
                              doc="added-mass matrix about CO (6×6, row-major)")
    added_mass_coriolis_mask: tuple = param(_vec(36, 1.0), unit="-", size=36, low=0.0, high=1.0,
                                            doc="1 keeps, 0 removes an element of C_A(ν_r)")
    linear_damping: tuple = param(_Z36, unit="SI", symbol="D", size=36,
                                  doc="linear damping matrix (6×6, row-major; force −D ν_r)")
    linear_damping_decay: float = param(0.0, unit="s/m", symbol="c_D", low=0.0,
                                        doc="D₁₁, D₂₂ scaled by exp(−c_D U_r) (0: constant)")
    quadratic_damping: tuple = param(_vec(6, 0.0), unit="SI", symbol="D_n", size=6, low=0.0,
                                     doc="diagonal quadratic damping: force −D_n,i |ν_r,i| ν_r,i")
    hydrostatic_stiffness: tuple = param(_Z36, unit="SI", symbol="G", size=36,
                                         doc="linear restoring −G η on (depth, roll, pitch)")
    weight: float = param(0.0, unit="N", symbol="W", low=0.0,
                          doc="weight in the submerged restoring forces (0: surface craft)")
    buoyancy: float = param(0.0, unit="N", symbol="B", low=0.0,
                            doc="buoyancy in the submerged restoring forces")
    center_of_buoyancy: tuple = param((0.0, 0.0, 0.0), unit="m", symbol="r_b", size=3,
                                      doc="CB from CO")
    payload_weight: float = param(0.0, unit="N", symbol="W_p", low=0.0,
                                  doc="point weight not in G (the Otter's payload)")
    payload_position: tuple = param((0.0, 0.0, 0.0), unit="m", symbol="r_p", size=3,
                                    doc="where the point weight acts, from CO")
    water_density: float = param(1026.0, unit="kg/m³", symbol="ρ", low=0.0, low_inclusive=False,
                                 doc="density in the cross-flow, lift, fin and propeller forces")
    cross_flow_length: float = param(0.0, unit="m", symbol="L", low=0.0,
                                     doc="hull length in the cross-flow drag (0: none)")
    cross_flow_draft: float = param(0.0, unit="m", symbol="T", low=0.0,
                                    doc="draft (AUV: diameter) in the cross-flow drag")
    cross_flow_coefficient: float = param(0.0, unit="-", symbol="C_d", low=0.0,
                                          doc="2-D cross-flow drag coefficient (Hoerner)")
    cross_flow_strips: float = param(20.0, unit="-", symbol="n", low=1.0,
                                     doc="strips in the cross-flow integral (n + 1 points)")
    hull_lift_span: float = param(0.0, unit="m", symbol="b", low=0.0,
                                  doc="span of the hull's lift/drag (AUV: diameter; 0: none)")
    hull_lift_area: float = param(0.0, unit="m²", symbol="S", low=0.0,
                                  doc="reference area of the hull's lift/drag")
    hull_drag_coefficient: float = param(0.0, unit="-", symbol="C_D0", low=0.0,
                                         doc="parasitic drag coefficient at zero lift")
    hull_lift_efficiency: float = param(0.7, unit="-", symbol="e", low=0.0, low_inclusive=False,
                                        doc="Oswald efficiency in the induced drag")
    quaternion_gain: float = param(1.0, unit="1/s", symbol="γ", low=0.0,
                                   doc="quaternion normalisation gain (RK4 needs γ h < 2.7)")
    # -- thrusters -------------------------------------------------------------------------
    thruster_count: float = param(0.0, unit="-", low=0.0, high=MAX_THRUSTERS,
                                  doc="thrusters used (the first of the thruster vectors)")
    thruster_x: tuple = param(_ZT, unit="m", size=MAX_THRUSTERS, doc="thruster position x")
    thruster_y: tuple = param(_ZT, unit="m", size=MAX_THRUSTERS, doc="thruster position y")
    thruster_z: tuple = param(_ZT, unit="m", size=MAX_THRUSTERS, doc="thruster position z")
    thruster_direction: tuple = param(_ZT, unit="rad", size=MAX_THRUSTERS,
                                      doc="thrust direction in the x-y plane (0: ahead)")
    thruster_azimuthing: tuple = param(_ZT, unit="-", size=MAX_THRUSTERS, low=0.0, high=1.0,
                                       doc="1: the direction is a state (azimuth thruster)")
    thruster_k_pos: tuple = param(_ZT, unit="N·s²", symbol="k_pos", size=MAX_THRUSTERS,
                                  low=0.0, doc="thrust k_pos n|n| for n > 0")
    thruster_k_neg: tuple = param(_ZT, unit="N·s²", symbol="k_neg", size=MAX_THRUSTERS,
                                  low=0.0, doc="thrust k_neg n|n| for n ≤ 0")
    thruster_k_advance: tuple = param(_ZT, unit="N·s²/m", symbol="k_J", size=MAX_THRUSTERS,
                                      doc="thrust + k_J V_a |n| for n > 0 (K_T linear in J)")
    thruster_torque_pos: tuple = param(_ZT, unit="N·m·s²", symbol="q_pos", size=MAX_THRUSTERS,
                                       doc="shaft moment on the hull q n|n| (about the axis)")
    thruster_torque_advance: tuple = param(_ZT, unit="N·m·s²/m", symbol="q_J",
                                           size=MAX_THRUSTERS, doc="moment + q_J V_a |n|, n > 0")
    thruster_wake: tuple = param(_ZT, unit="-", symbol="w", size=MAX_THRUSTERS, low=0.0,
                                 high=1.0, doc="wake fraction: V_a = (1 − w) U")
    thruster_deduction: tuple = param(_ZT, unit="-", symbol="t", size=MAX_THRUSTERS, low=0.0,
                                      high=1.0, doc="thrust deduction: force (1 − t) T")
    thruster_time_constant: tuple = param(_vec(MAX_THRUSTERS, 0.1), unit="s", symbol="T_n",
                                          size=MAX_THRUSTERS, low=0.0, low_inclusive=False,
                                          doc="first-order motor lag of the shaft speed")
    thruster_max_speed: tuple = param(_vec(MAX_THRUSTERS, 100.0), unit="rad/s",
                                      size=MAX_THRUSTERS, doc="shaft speed limit, ahead")
    thruster_min_speed: tuple = param(_vec(MAX_THRUSTERS, -100.0), unit="rad/s",
                                      size=MAX_THRUSTERS, doc="shaft speed limit, astern")
    thruster_max_acceleration: tuple = param(_vec(MAX_THRUSTERS, _BIG), unit="rad/s²",
                                             size=MAX_THRUSTERS, low=0.0, low_inclusive=False,
                                             doc="shaft acceleration limit")
    thruster_max_turn_rate: tuple = param(_vec(MAX_THRUSTERS, _BIG), unit="rad/s",
                                          size=MAX_THRUSTERS, low=0.0, low_inclusive=False,
                                          doc="azimuth turning-rate limit")
    thruster_turn_time_constant: tuple = param(_vec(MAX_THRUSTERS, 1.0), unit="s",
                                               size=MAX_THRUSTERS, low=0.0, low_inclusive=False,
                                               doc="first-order lag of the azimuth angle")
    # -- fins ------------------------------------------------------------------------------
    fin_count: float = param(0.0, unit="-", low=0.0, high=MAX_FINS, doc="fins used")
    fin_kind: tuple = param(_ZF, unit="-", size=MAX_FINS, low=0.0, high=1.0,
                            doc="0: rudder (sway force), 1: stern plane (heave force)")
    fin_x: tuple = param(_ZF, unit="m", size=MAX_FINS, doc="fin position x (lever arm)")
    fin_area: tuple = param(_ZF, unit="m²", size=MAX_FINS, low=0.0, doc="fin area A")
    fin_lift_slope: tuple = param(_ZF, unit="1/rad", symbol="C_Lδ", size=MAX_FINS, low=0.0,
                                  doc="lift coefficient per fin angle")
    fin_time_constant: tuple = param(_vec(MAX_FINS, 0.1), unit="s", size=MAX_FINS, low=0.0,
                                     low_inclusive=False, doc="first-order lag of the fin angle")
    fin_max_angle: tuple = param(_vec(MAX_FINS, 0.5), unit="rad", size=MAX_FINS, low=0.0,
                                 low_inclusive=False, doc="fin angle limit")
    fin_max_rate: tuple = param(_vec(MAX_FINS, _BIG), unit="rad/s", size=MAX_FINS, low=0.0,
                                low_inclusive=False, doc="fin rate limit")
    # -- extent, for the checks ------------------------------------------------------------
    hull_length: float = param(1.0, unit="m", low=0.0, low_inclusive=False,
                               doc="overall length (thrusters must lie within ±L/2)")
    hull_beam: float = param(1.0, unit="m", low=0.0, low_inclusive=False,
                             doc="overall beam (thrusters within ±B/2)")
    hull_height: float = param(1.0, unit="m", low=0.0, low_inclusive=False,
                               doc="overall height (thrusters within ±H of CO)")

    def validate(self) -> None:
        m = mass_matrix(self)
        if not np.allclose(m, m.T, rtol=1e-9, atol=1e-9 * np.abs(m).max()):
            i, j = np.unravel_index(np.argmax(np.abs(m - m.T)), m.shape)
            raise ParameterError(
                f"the mass matrix M_RB + M_A must be symmetric; element ({i}, {j}) is "
                f"{m[i, j]!r} but ({j}, {i}) is {m[j, i]!r} [SI]", field="added_mass",
                unit="SI", value=float(m[i, j]))
        eig = np.linalg.eigvalsh(0.5 * (m + m.T))
        if eig.min() <= 0.0:
            raise ParameterError(
                f"the mass matrix M_RB + M_A must be positive definite; its smallest "
                f"eigenvalue is {eig.min()!r} [SI]", field="added_mass", unit="SI",
                value=float(eig.min()))
        g = np.asarray(self.hydrostatic_stiffness).reshape(6, 6)
        if np.any(g[:, [0, 1, 5]] != 0.0):
            raise ParameterError(
                "`hydrostatic_stiffness` acts on depth, roll and pitch only: its columns 0, 1 "
                "and 5 (north, east, heading) must be zero", field="hydrostatic_stiffness")
        n = int(self.thruster_count)
        if n != self.thruster_count:
            raise ParameterError(f"`thruster_count` must be a whole number, got "
                                 f"{self.thruster_count!r}", field="thruster_count")
        for i in range(n):
            if self.thruster_k_pos[i] <= 0.0 or self.thruster_k_neg[i] <= 0.0:
                raise ParameterError(
                    f"thruster {i + 1}: `thruster_k_pos` and `thruster_k_neg` must be > 0 "
                    f"[N·s²], got {self.thruster_k_pos[i]!r}, {self.thruster_k_neg[i]!r}",
                    field=f"thruster_k_pos[{i}]", unit="N·s²", value=self.thruster_k_pos[i])
            for key, value, half in (("thruster_x", self.thruster_x[i], 0.5 * self.hull_length),
                                     ("thruster_y", self.thruster_y[i], 0.5 * self.hull_beam),
                                     ("thruster_z", self.thruster_z[i], self.hull_height)):
                if abs(value) > half:
                    raise ParameterError(
                        f"thruster {i + 1} is outside the hull: `{key}` = {value!r} [m], "
                        f"beyond ±{half!r} [m]", field=f"{key}[{i}]", unit="m", value=value)
            if self.thruster_min_speed[i] >= self.thruster_max_speed[i]:
                raise ParameterError(
                    f"thruster {i + 1}: `thruster_min_speed` {self.thruster_min_speed[i]!r} "
                    f"must be below `thruster_max_speed` {self.thruster_max_speed[i]!r} [rad/s]",
                    field=f"thruster_min_speed[{i}]", unit="rad/s",
                    value=self.thruster_min_speed[i])
        nf = int(self.fin_count)
        if nf != self.fin_count:
            raise ParameterError(f"`fin_count` must be a whole number, got {self.fin_count!r}",
                                 field="fin_count")
        if self.fin_kind != tuple(float(round(k)) for k in self.fin_kind):
            raise ParameterError("`fin_kind` entries must be 0 (rudder) or 1 (stern plane)",
                                 field="fin_kind")
        if self.layout is not None:
            n_t, azimuthing, n_f = self.layout
            flags = tuple(int(self.thruster_azimuthing[i]) for i in range(min(n, MAX_THRUSTERS)))
            if (n, flags, nf) != (n_t, tuple(azimuthing), n_f):
                raise ParameterError(
                    f"{type(self).__name__} has {n_t} thrusters (azimuthing: {list(azimuthing)}) "
                    f"and {n_f} fins; got `thruster_count` = {n}, `thruster_azimuthing` = "
                    f"{list(flags)}, `fin_count` = {nf}", field="thruster_count", value=n)
        if self.cross_flow_strips != round(self.cross_flow_strips):
            raise ParameterError(f"`cross_flow_strips` must be a whole number, got "
                                 f"{self.cross_flow_strips!r}", field="cross_flow_strips")

    # -- derived ---------------------------------------------------------------------------
    #: The craft's fixed layout (thrusters, azimuthing ones, fins), checked against the counts
    #: by a craft's subclass; None: any (the generic class, for tests and new crafts).
    layout: ClassVar[tuple[int, tuple[int, ...], int] | None] = None

    @property
    def rigid_body_mass_matrix(self) -> np.ndarray:
        """M_RB about CO [SI] (Fossen 2021, §3.3)."""
        return rigid_body_mass_matrix(self.mass, np.asarray(self.center_of_gravity),
                                      np.asarray(self.inertia_cg))

    @property
    def mass_matrix(self) -> np.ndarray:
        """M = M_RB + M_A [SI]."""
        return mass_matrix(self)


def mass_matrix(p: SixDofParams) -> np.ndarray:
    """M = M_RB + M_A (6 × 6) of a parameter set.

    Parameters
    ----------
    p : SixDofParams

    Returns
    -------
    numpy.ndarray, shape (6, 6)
    """
    return p.rigid_body_mass_matrix + np.asarray(p.added_mass).reshape(6, 6)


# Hoerner (1965), Fluid-Dynamic Drag, the 2-D cross-flow drag coefficient of a hull section
# against B/(2T), as digitised in Fossen's MSS (Hoerner.m) and PVS (gnc.Hoerner).
_HOERNER_B2T = (0.0109, 0.1766, 0.3530, 0.4519, 0.4728, 0.4929, 0.4933, 0.5585, 0.6464, 0.8336,
                0.9880, 1.3081, 1.6392, 1.8600, 2.3129, 2.6000, 3.0088, 3.4508, 3.7379, 4.0031)
_HOERNER_CD = (1.9661, 1.9657, 1.8976, 1.7872, 1.5837, 1.2786, 1.2108, 1.0836, 0.9986, 0.8796,
               0.8284, 0.7599, 0.6914, 0.6571, 0.6307, 0.5962, 0.5868, 0.5859, 0.5599, 0.5593)


def hoerner_cross_flow_coefficient(beam: float, draft: float) -> float:
    """Hoerner's 2-D cross-flow drag coefficient C_d(B/2T), linearly interpolated (clamped).

    Parameters
    ----------
    beam, draft : float
        Section beam B and draft T [m].

    Returns
    -------
    float
        C_d [-].

    References
    ----------
    Hoerner, S. F. (1965). Fluid-Dynamic Drag. Digitised as in Fossen (2021), §6.7.
    """
    if not (beam > 0.0 and draft > 0.0 and math.isfinite(beam) and math.isfinite(draft)):
        raise ParameterError(f"`beam` and `draft` must be > 0 [m], got {beam!r}, {draft!r}")
    return float(np.interp(beam / (2.0 * draft), _HOERNER_B2T, _HOERNER_CD))
