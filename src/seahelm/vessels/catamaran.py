"""Research catamaran with two azimuth thrusters (Shushlyapin, Karapetyan, Bezuglaya & Afonina,
2017).

The 22.3 m, 155 t research catamaran "Pioneer-M" steered by two azimuth thrusters (ВРК) that
turn together by the angle δ at equal thrust T_v each. State (the paper's z, eq. (1)-(4))::

    z = (V_x, V_y, ω, x, y, K, δ)

surge and sway speed of the centre of mass in body axes [m/s], yaw rate ω [rad/s], position
[m], heading (course) K [rad] and thruster angle δ [rad]. The control is the thruster rate
u = dδ/dt (eq. (2)), so the system is control-affine, dz/dt = Φ(z) + B u with B = e_7::

    dV_x/dt = (2 T_v cos δ − R_x − m_y ω V_y) / m_x
    dV_y/dt = (2 T_v sin δ − s_y R_y − m_x ω V_x) / m_y
    dω/dt   = (L T_v sin δ + M_K + M_D − V_x V_y (m_x − m_y)) / J_ω
    dx/dt   = V cos(K − β) = V_x cos K + V_y sin K
    dy/dt   = V sin(K − β) = V_x sin K − V_y cos K
    dK/dt   = ω
    dδ/dt   = u

with (eq. (5)-(11) as in the MathCAD listing of Table 1)::

    V = √(V_x² + V_y²),  β = atan2(V_y, V_x)                 (the paper: atan(V_y/V_x))
    R_K(V) = c0 + c1 V + c2 V²                    [kN, one hull, OpenFOAM fit]
    R_x = 2000 R_K(V) Vⁿ cos β,   R_y = 2000 R_K(V) Vⁿ sin β  [N, two hulls, kN → N]
    M_K = 0.4 L (0.5 − β/π_l) R_y                 (π_l = 3.14 in the listing)
    M_D = −C_d V (ρ/2) A_Ls L² ω,  C_d = (0.739 + 8.7 T_m/L)(1.611σ² − 2.873σ + 1.33),
    A_Ls = L T_m σ
    m_x = (1 + k11) D,  m_y = (1 + k22) D,  J_ω = (1 + k66) J_zz

The yaw moment L·T_v·sin δ is that of two thrusters at L/2 from the centre of mass
(2 · T_v sin δ · L/2); the listing also defines the thrusters' lateral offset r_VRK = 3 m and
the slant distance d_n = √(r_VRK² + L²/4), which do not enter the equations.

Errata and the printed variants (``/work/shared/seeds/README.md``; the listing is the model
that produced the paper's figures)
    * The printed sway equation (3) omits the lateral resistance −R_y; with it omitted the
      thrusters' side force is resisted by nothing but the centripetal term and
      ω* = 0.08 rad/s cannot be reached. ``sway_resistance`` = 1 (default) includes it,
      0 gives the printed eq. (3).
    * Printed eq. (6)-(7) carry an extra factor V (R = 2000 R_K V cos β); the listing does not.
      ``resistance_speed_power`` n = 0 (default) is the listing, n = 1 the printed equations
      (then the straight-run speed drops from 4.42 m/s to 3.13 m/s, ω* = 0.08 rad/s needs
      only δ ≈ 45°, and the resistance is no longer the OpenFOAM fit in kN).
    * With the printed sway equation the steady turn saturates at ω ≈ 0.071 rad/s as δ → 90°.
    * The drift angle is computed with atan2 (the listing's atan(V_y/V_x) is singular at
      V_x = 0 and flips the kinematics for V_x < 0); at V = 0 it is taken as 0, so the
      resistance is R_x = 2000 R_K(0) = 16.2 kN at rest (the polynomial fit is meant for
      cruising speeds; the thrust 40.8 kN still accelerates the ship from rest).
    * The kinematics use cos(K − β): β is positive for a velocity to port of the bow, so the
      paper's V_y points to port. The navigation outputs therefore report the sway speed
      v = −V_y (starboard positive, ẏ_E = U sin ψ + v cos ψ, :mod:`seahelm.vessels.base`);
      the state keeps the paper's V_y under the label ``sway_speed_port``. The model also
      outputs ``speed`` V, ``drift_angle`` β (the paper's, port positive) and
      ``thruster_angle`` δ.

Two parameter sets (registered in :mod:`seahelm.ships.catalog`)
    ``shushlyapin2017-listing`` (:func:`paper_params`): every constant of the listing —
    D = 155000 kg, L = 22.3 m, σ = 0.697, T_m = 1.55 m (missing from the paper; it reproduces
    both constants of eq. (10), C_d = 0.148 and A_Ls = 24.092 m²), T_v = 20400 N per thruster,
    k11 = 0.05, k22 = 0.7, k66 = 0.6, ρ = 1.025 ("rov", t/m³), J_zz = 0.05/1000 · ρ · D · L²
    = 3950 kg·m² and π_l = 3.14. This J_zz is about 1200 times below the physical value and
    M_D, computed with ρ in t/m³, is in kN·m while every other moment is in N·m: the yaw
    equation has a time constant of about 1.6 s and the strong oscillations the paper shows
    at constant δ (angular accelerations up to 10 rad/s²) come from this.

    ``shushlyapin2017-consistent`` (:func:`consistent_params`): the same ship with
    J_zz = D (0.25 L)² = 4.82e6 kg·m² (radius of gyration a quarter of the length, the usual
    value; the listing's formula read with D in tonnes gives 3.95e6, the same order),
    ρ = 1025 kg/m³ (M_D in N·m) and π_l = π. The yaw dynamics then take tens of seconds
    instead of one; the final-state controllers need T_u·h scaled by the ratio of the J_ω
    values (about 1220) for the same closed-loop time constant.

References
----------
Shushlyapin, E. A., Karapetyan, V. A., Bezuglaya, A. E., Afonina, A. A. (2017). Nonlinear
regulators for keeping a ship on a given trajectory in "strong" manoeuvres. SPIIRAS
Proceedings 4(53), 179-196, eq. (1)-(11), (22) and Table 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from .._validate import as_float_array
from ..errors import ParameterError
from ..parameters import Params, as_records, param, signal_indices, stack_params
from .base import NAV_OUTPUT_UNITS, NAV_OUTPUTS, VesselModel

__all__ = [
    "CatamaranParams",
    "CatamaranServoParams",
    "CATAMARAN",
    "CATAMARAN_SERVO",
    "paper_params",
    "consistent_params",
    "jacobian",
    "drift",
    "steady_turn",
    "PAPER_PROVENANCE",
    "CONSISTENT_PROVENANCE",
    "N_CATAMARAN_PARAMS",
    "STATES",
    "OUTPUTS",
]

_LISTING_JZZ = 0.05 / 1000.0 * 1.025 * 155000.0 * 22.3**2


@dataclass(frozen=True, kw_only=True)
class CatamaranParams(Params):
    """Parameters of the twin-thruster catamaran (SI units; defaults: the paper's listing).

    See the module docstring for the equations, the two named sets and why they differ.
    """

    displacement: float = param(155000.0, unit="kg", symbol="D", low=0.0, low_inclusive=False,
                                doc="mass (weight displacement) of the ship")
    length: float = param(22.3, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="ship length (yaw-moment arm of the thruster pair)")
    mean_draft: float = param(1.55, unit="m", symbol="T_m", low=0.0, low_inclusive=False,
                              doc="mean draft (damping moment only; not printed in the paper)")
    block_coefficient: float = param(0.697, unit="-", symbol="σ", low=0.0, low_inclusive=False,
                                     high=1.0, doc="hull block coefficient")
    thrust: float = param(20400.0, unit="N", symbol="T_v", low=0.0, low_inclusive=False,
                          doc="thrust of one azimuth thruster (both equal)")
    k11: float = param(0.05, unit="-", symbol="k11", low=0.0, doc="surge added-mass coefficient")
    k22: float = param(0.7, unit="-", symbol="k22", low=0.0, doc="sway added-mass coefficient")
    k66: float = param(0.6, unit="-", symbol="k66", low=0.0,
                       doc="yaw added-moment-of-inertia coefficient")
    yaw_inertia: float = param(_LISTING_JZZ, unit="kg·m²", symbol="J_zz", low=0.0,
                               low_inclusive=False,
                               doc="moment of inertia of the ship (listing: 3950, ~1200x small)")
    water_density: float = param(1.025, unit="kg/m³", symbol="ρ", low=0.0, low_inclusive=False,
                                 doc="density in the damping moment (listing: 1.025, i.e. t/m³)")
    resistance_c0: float = param(8.1, unit="kN", symbol="c0",
                                 doc="hull resistance fit R_K = c0 + c1 V + c2 V² (one hull)")
    resistance_c1: float = param(-8.436, unit="kN·s/m", symbol="c1", doc="resistance fit, linear")
    resistance_c2: float = param(2.536, unit="kN·s²/m²", symbol="c2",
                                 doc="resistance fit, quadratic")
    lever_pi: float = param(3.14, unit="-", symbol="π_l", low=0.0, low_inclusive=False,
                            doc="the π in the lever l_K = 0.4 L (0.5 − β/π) (listing: 3.14)")
    sway_resistance: float = param(1.0, unit="-", symbol="s_y", low=0.0, high=1.0,
                                   doc="1: −R_y in the sway equation (errata); 0: printed eq. (3)")
    resistance_speed_power: float = param(0.0, unit="-", symbol="n", low=0.0, high=1.0,
                                          doc="0: listing R = 2000 R_K cos β; 1: eq. (6)-(7)")

    def validate(self) -> None:
        # the straight-run resistance must be able to balance the thrust at some speed,
        # otherwise the ship accelerates without bound
        if self.resistance_c2 <= 0.0:
            raise ParameterError(
                f"`resistance_c2` must be > 0 [kN·s²/m²] (resistance must grow with speed), "
                f"got {self.resistance_c2!r}"
            )

    # -- derived quantities ---------------------------------------------------------------
    @property
    def surge_mass(self) -> float:
        """m_x = (1 + k11) D [kg], eq. (11)."""
        return (1.0 + self.k11) * self.displacement

    @property
    def sway_mass(self) -> float:
        """m_y = (1 + k22) D [kg], eq. (11)."""
        return (1.0 + self.k22) * self.displacement

    @property
    def yaw_moment_of_inertia(self) -> float:
        """J_ω = (1 + k66) J_zz [kg·m²], eq. (11)."""
        return (1.0 + self.k66) * self.yaw_inertia

    @property
    def damping_coefficient(self) -> float:
        """C_d = (0.739 + 8.7 T_m/L)(1.611σ² − 2.873σ + 1.33) [-] (0.148 for the listing)."""
        s = self.block_coefficient
        return (0.739 + 8.7 * self.mean_draft / self.length) * (1.611 * s * s - 2.873 * s + 1.33)

    @property
    def lateral_area(self) -> float:
        """A_Ls = L T_m σ [m²] (24.092 for the listing)."""
        return self.length * self.mean_draft * self.block_coefficient

    def straight_speed(self) -> float:
        """Steady straight-run speed [m/s] at δ = 0: 2 T_v = 2000 R_K(V) Vⁿ (bisection)."""
        lo, hi = 0.0, 1.0
        f = lambda v: 2.0 * self.thrust - 2000.0 * (  # noqa: E731
            self.resistance_c0 + self.resistance_c1 * v + self.resistance_c2 * v * v
        ) * v**self.resistance_speed_power
        while f(hi) > 0.0:
            hi *= 2.0
            if hi > 1e4:
                raise ParameterError("no straight-run speed below 1e4 m/s: thrust too high")
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) > 0.0 else (lo, mid)
        return 0.5 * (lo + hi)


N_CATAMARAN_PARAMS = len(CatamaranParams.field_names())


@dataclass(frozen=True, kw_only=True)
class CatamaranServoParams(CatamaranParams):
    """Catamaran with the thruster servo of eq. (22): dδ/dt = (−δ + k_δ v)/T_δ."""

    servo_time_constant: float = param(1.0, unit="s", symbol="T_δ", low=0.0, low_inclusive=False,
                                       doc="time constant of the thruster drive, eq. (22)")
    servo_gain: float = param(1.0, unit="-", symbol="k_δ", low=0.0, low_inclusive=False,
                              doc="gain of the thruster drive, eq. (22)")


PAPER_PROVENANCE = (
    "Shushlyapin, Karapetyan, Bezuglaya & Afonina (2017), SPIIRAS Proceedings 4(53), Table 1 "
    "(MathCAD listing): research catamaran 'Pioneer-M', D = 155000 kg, L = 22.3 m, sigma = 0.697, "
    "Tv = 20400 N per thruster, k11 = 0.05, k22 = 0.7, k66 = 0.6, rov = 1.025, "
    "Jzz = 0.05/1000*rov*D*L^2 = 3950 kg m^2 (about 1200x below physical), pi = 3.14 in l_K; "
    "mean draft Tm = 1.55 m (not printed; reproduces C_d = 0.148 and A_Ls = 24.092 m^2 of "
    "eq. (10)). Reproduces the paper's figures."
)
CONSISTENT_PROVENANCE = (
    "The listing's ship (Shushlyapin et al., 2017) with a physical moment of inertia "
    "Jzz = D (0.25 L)^2 = 4.82e6 kg m^2, water density 1025 kg/m^3 so that the damping moment "
    "is in N m like the other moments, and pi in l_K."
)


def paper_params(**changes: Any) -> CatamaranParams:
    """The listing's parameter set (Table 1; T_m = 1.55 m) — reproduces the paper's figures."""
    return CatamaranParams().replace(**changes) if changes else CatamaranParams()


def consistent_params(**changes: Any) -> CatamaranParams:
    """The physically consistent set: J_zz = D (L/4)², ρ = 1025 kg/m³, π_l = π."""
    d, length = 155000.0, 22.3
    p = CatamaranParams(
        yaw_inertia=d * (0.25 * length) ** 2, water_density=1025.0, lever_pi=math.pi
    )
    return p.replace(**changes) if changes else p


# ------------------------------------------------------------------------------------------
# signals
# ------------------------------------------------------------------------------------------
#: The paper's z = (V_x, V_y, ω, x, y, K, δ); V_y points to port (see the module docstring).
STATES: tuple[str, ...] = ("surge_speed", "sway_speed_port", "yaw_rate", "north", "east",
                           "heading", "thruster_angle")
_UNITS = ("m/s", "m/s", "rad/s", "m", "m", "rad", "rad")
#: The navigation outputs (sway speed v = −V_y, starboard positive), then the speed V [m/s],
#: the drift angle β = atan2(V_y, V_x) [rad] (port positive, 0 at rest) and the thruster angle
#: δ [rad].
OUTPUTS: tuple[str, ...] = NAV_OUTPUTS + ("speed", "drift_angle", "thruster_angle")
_OUTPUT_UNITS = NAV_OUTPUT_UNITS + ("m/s", "rad", "rad")

#: Inputs: the thruster rate u = dδ/dt of eq. (2), or with the drive of eq. (22) its input v.
INPUTS: tuple[str, ...] = ("thruster_rate",)
SERVO_INPUTS: tuple[str, ...] = ("thruster_command",)

_X = signal_indices(STATES)
_U = signal_indices(INPUTS)
_US = signal_indices(SERVO_INPUTS)
_Y = signal_indices(OUTPUTS)


# ------------------------------------------------------------------------------------------
# compiled right-hand side, drift Φ and Jacobian ∂Φ/∂z
# ------------------------------------------------------------------------------------------
@njit(cache=True)
def catamaran_drift(x, p, f):  # pragma: no cover - compiled
    """Φ(z) of eq. (3) (the uncontrolled part; dδ/dt = 0) for one run.

    Arranged for speed (two divisions instead of seven; the same equations): the damping
    constant C_d (ρ/2) A_Ls L² is written without L in a denominator, β/π_l and the three
    mass divisions share one reciprocal. ``p`` is a record with the
    :class:`CatamaranParams` fields (also of a subclass, e.g. a controller's parameters).
    """
    D = p.displacement
    L = p.length
    tm = p.mean_draft
    sig = p.block_coefficient
    tv = p.thrust
    mx = (1.0 + p.k11) * D
    my = (1.0 + p.k22) * D
    pil = p.lever_pi
    jwp = (1.0 + p.k66) * p.yaw_inertia * pil
    rho = p.water_density
    c0 = p.resistance_c0
    c1 = p.resistance_c1
    c2 = p.resistance_c2
    sy = p.sway_resistance
    npow = p.resistance_speed_power
    a = x[_X.surge_speed]
    b = x[_X.sway_speed_port]
    w = x[_X.yaw_rate]
    K = x[_X.heading]
    d = x[_X.thruster_angle]
    V = math.sqrt(a * a + b * b)
    if V > 0.0:
        iv = 1.0 / V
        cb = a * iv
        sb = b * iv
        beta = math.atan2(b, a)
    else:
        cb = 1.0
        sb = 0.0
        beta = 0.0
    F = 2000.0 * (c0 + (c1 + c2 * V) * V)
    if npow != 0.0:
        F *= V**npow
    rx = F * cb
    ry = F * sb
    # C_d (ρ/2) A_Ls L² with C_d = (0.739 + 8.7 T_m/L)(1.611σ² − 2.873σ + 1.33), A_Ls = L T_m σ
    cm = (0.739 * L + 8.7 * tm) * ((1.611 * sig - 2.873) * sig + 1.33) * 0.5 * rho * tm * sig
    cm *= L * L
    sd = math.sin(d)
    cdl = math.cos(d)
    cK = math.cos(K)
    sK = math.sin(K)
    r = 1.0 / (mx * my * jwp)
    f[_X.surge_speed] = (2.0 * tv * cdl - rx - my * w * b) * (my * jwp * r)
    f[_X.sway_speed_port] = (2.0 * tv * sd - sy * ry - mx * w * a) * (mx * jwp * r)
    # (L T_v sin δ + M_K + M_D − V_x V_y (m_x − m_y)) / J_ω, M_K = 0.4 L (0.5 − β/π_l) R_y
    f[_X.yaw_rate] = (pil * (L * tv * sd - cm * V * w - a * b * (mx - my))
                      + 0.4 * L * (0.5 * pil - beta) * ry) * (mx * my * r)
    f[_X.north] = a * cK + b * sK
    f[_X.east] = a * sK - b * cK
    f[_X.heading] = w
    f[_X.thruster_angle] = 0.0


@njit(cache=True)
def catamaran_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """dz/dt = Φ(z) + e_7 u: the input u is the thruster rate dδ/dt [rad/s] (eq. (2))."""
    catamaran_drift(x, p, dx)
    dx[_X.thruster_angle] = u[_U.thruster_rate]


@njit(cache=True)
def catamaran_servo_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """Eq. (3) with the thruster drive eq. (22): dδ/dt = (−δ + k_δ v)/T_δ, input v [rad]."""
    catamaran_drift(x, p, dx)
    dx[_X.thruster_angle] = (p.servo_gain * u[_US.thruster_command]
                             - x[_X.thruster_angle]) / p.servo_time_constant


@njit(cache=True)
def catamaran_output(t, x, u, p, y):  # pragma: no cover - compiled
    a = x[_X.surge_speed]
    b = x[_X.sway_speed_port]
    y[_Y.north] = x[_X.north]
    y[_Y.east] = x[_X.east]
    y[_Y.heading] = x[_X.heading]
    y[_Y.yaw_rate] = x[_X.yaw_rate]
    y[_Y.surge_speed] = a
    y[_Y.sway_speed] = -b
    V = math.sqrt(a * a + b * b)
    y[_Y.speed] = V
    y[_Y.drift_angle] = math.atan2(b, a) if V > 0.0 else 0.0
    y[_Y.thruster_angle] = x[_X.thruster_angle]


@njit(cache=True)
def catamaran_yaw_acceleration(x, p):  # pragma: no cover - compiled
    """Φ_3(z) [rad/s²], eq. (18) — the yaw row of eq. (3) alone (for the controller eq. (20))."""
    D = p.displacement
    L = p.length
    tm = p.mean_draft
    sig = p.block_coefficient
    mx = (1.0 + p.k11) * D
    my = (1.0 + p.k22) * D
    jw = (1.0 + p.k66) * p.yaw_inertia
    a = x[_X.surge_speed]
    b = x[_X.sway_speed_port]
    V = math.sqrt(a * a + b * b)
    if V > 0.0:
        sb = b / V
        beta = math.atan2(b, a)
    else:
        sb = 0.0
        beta = 0.0
    F = 2000.0 * (p.resistance_c0 + (p.resistance_c1 + p.resistance_c2 * V) * V)
    if p.resistance_speed_power != 0.0:
        F *= V ** p.resistance_speed_power
    cd = (0.739 + 8.7 * tm / L) * ((1.611 * sig - 2.873) * sig + 1.33)
    cm = cd * 0.5 * p.water_density * (L * tm * sig) * L * L
    mk = 0.4 * L * (0.5 - beta / p.lever_pi) * F * sb
    return (L * p.thrust * math.sin(x[_X.thruster_angle]) + mk - cm * V * x[_X.yaw_rate]
            - a * b * (mx - my)) / jw


@njit(cache=True)
def catamaran_jacobian(x, p, J):  # pragma: no cover - compiled
    """Analytic ∂Φ/∂z (7 × 7) of eq. (3) at ``x`` (the control enters only through B = e_7).

    At V = 0 the drift angle is not differentiable; the derivative is taken along V_x > 0.
    """
    D = p.displacement
    L = p.length
    tm = p.mean_draft
    sig = p.block_coefficient
    tv = p.thrust
    mx = (1.0 + p.k11) * D
    my = (1.0 + p.k22) * D
    jw = (1.0 + p.k66) * p.yaw_inertia
    rho = p.water_density
    c0 = p.resistance_c0
    c1 = p.resistance_c1
    c2 = p.resistance_c2
    pil = p.lever_pi
    sy = p.sway_resistance
    npow = p.resistance_speed_power
    a = x[_X.surge_speed]
    b = x[_X.sway_speed_port]
    w = x[_X.yaw_rate]
    K = x[_X.heading]
    d = x[_X.thruster_angle]
    for i in range(J.shape[0]):
        for j in range(J.shape[1]):
            J[i, j] = 0.0
    V = math.sqrt(a * a + b * b)
    if V > 1e-12:
        cb = a / V
        sb = b / V
        beta = math.atan2(b, a)
        iv = 1.0 / V
    else:
        V = 0.0
        cb = 1.0
        sb = 0.0
        beta = 0.0
        iv = 0.0  # one-sided along V_x > 0 for the V-dependent factors below
    rk = c0 + (c1 + c2 * V) * V
    drk = c1 + 2.0 * c2 * V
    if npow != 0.0:
        vn = V**npow
        dvn = npow * V ** (npow - 1.0) if V > 0.0 else 0.0
    else:
        vn = 1.0
        dvn = 0.0
    F = 2000.0 * rk * vn
    dF = 2000.0 * (drk * vn + rk * dvn)
    # partial derivatives of cos β, sin β, β, V with respect to (V_x, V_y)
    dcb_a = sb * sb * iv
    dcb_b = -cb * sb * iv
    dsb_a = -cb * sb * iv
    dsb_b = cb * cb * iv
    dbeta_a = -sb * iv
    dbeta_b = cb * iv
    dV_a = cb
    dV_b = sb
    ry = F * sb
    drx_a = dF * dV_a * cb + F * dcb_a
    drx_b = dF * dV_b * cb + F * dcb_b
    dry_a = dF * dV_a * sb + F * dsb_a
    dry_b = dF * dV_b * sb + F * dsb_b
    cd = (0.739 + 8.7 * tm / L) * ((1.611 * sig - 2.873) * sig + 1.33)
    cm = cd * 0.5 * rho * (L * tm * sig) * L * L
    lk = 0.4 * L * (0.5 - beta / pil)
    dlk_a = -0.4 * L * dbeta_a / pil
    dlk_b = -0.4 * L * dbeta_b / pil
    sd = math.sin(d)
    cdl = math.cos(d)
    cK = math.cos(K)
    sK = math.sin(K)
    u_, v_, r_, n_, e_, k_, d_ = (_X.surge_speed, _X.sway_speed_port, _X.yaw_rate, _X.north,
                                  _X.east, _X.heading, _X.thruster_angle)
    # surge
    J[u_, u_] = -drx_a / mx
    J[u_, v_] = (-drx_b - my * w) / mx
    J[u_, r_] = -my * b / mx
    J[u_, d_] = -2.0 * tv * sd / mx
    # sway
    J[v_, u_] = (-sy * dry_a - mx * w) / my
    J[v_, v_] = -sy * dry_b / my
    J[v_, r_] = -mx * a / my
    J[v_, d_] = 2.0 * tv * cdl / my
    # yaw
    J[r_, u_] = (dlk_a * ry + lk * dry_a - cm * dV_a * w - b * (mx - my)) / jw
    J[r_, v_] = (dlk_b * ry + lk * dry_b - cm * dV_b * w - a * (mx - my)) / jw
    J[r_, r_] = -cm * V / jw
    J[r_, d_] = L * tv * cdl / jw
    # kinematics
    J[n_, u_] = cK
    J[n_, v_] = sK
    J[n_, k_] = -a * sK + b * cK
    J[e_, u_] = sK
    J[e_, v_] = -cK
    J[e_, k_] = a * cK + b * sK
    J[k_, r_] = 1.0


@njit(cache=True)
def _batched_drift(X, P, out):  # pragma: no cover - compiled
    for i in range(X.shape[0]):
        catamaran_drift(X[i], P[i], out[i])


@njit(cache=True)
def _batched_jacobian(X, P, out):  # pragma: no cover - compiled
    for i in range(X.shape[0]):
        catamaran_jacobian(X[i], P[i], out[i])


def _pack(x: Any, params: CatamaranParams | Any) -> tuple[np.ndarray, np.ndarray, tuple]:
    """States as rows (N, 7), parameters as CatamaranParams records (N,) (the leading
    :class:`CatamaranParams` fields of any subclass or packed array), and the batch shape."""
    x = as_float_array("x", x)
    if x.shape[-1:] != (7,):
        raise ParameterError(f"`x` must end in the 7 catamaran states, got shape {x.shape}")
    if isinstance(params, Params) or (
        isinstance(params, (list, tuple)) and params and isinstance(params[0], Params)
    ):
        p = stack_params(params, CatamaranParams)
        if isinstance(params, Params):
            p = p[0]
    else:
        p = as_float_array("params", params)
    p = p[..., :N_CATAMARAN_PARAMS]
    batch = np.broadcast_shapes(x.shape[:-1], p.shape[:-1])
    X = np.ascontiguousarray(np.broadcast_to(x, batch + (7,)).reshape(-1, 7))
    P = np.ascontiguousarray(
        np.broadcast_to(p, batch + p.shape[-1:]).reshape(-1, p.shape[-1])
    )
    return X, as_records(P, CatamaranParams), batch


def steady_turn(params: CatamaranParams, yaw_rate: float) -> tuple[float, float, float]:
    """Steady turn (V_x [m/s], V_y [m/s], δ [rad]) with the yaw rate ``yaw_rate`` [rad/s].

    Solves Φ_1 = Φ_2 = Φ_3 = 0 at ω = ``yaw_rate`` (Newton's method from the straight run);
    the turning-circle diameter is 2 √(V_x² + V_y²)/ω. Raises ParameterError if no steady
    turn is found (the yaw rate is beyond the largest reachable one).

    Parameters
    ----------
    params : CatamaranParams
        Ship parameters.
    yaw_rate : float
        Yaw rate ω of the turn [rad/s].

    Returns
    -------
    tuple of float
        (V_x [m/s], V_y [m/s], δ [rad]).
    """
    from scipy.optimize import fsolve

    w = float(yaw_rate)

    def f(v: np.ndarray) -> np.ndarray:
        return drift(np.array([v[0], v[1], w, 0.0, 0.0, 0.0, v[2]]), params)[:3]

    sol, info, ier, _ = fsolve(f, [params.straight_speed(), 0.0, w / 0.07], xtol=1e-13,
                               full_output=True)
    if ier != 1 or np.abs(f(sol)).max() > 1e-8 or abs(sol[2]) >= math.pi / 2:
        raise ParameterError(
            f"no steady turn with `yaw_rate` = {w!r} [rad/s] for thruster angles below 90°"
        )
    return float(sol[0]), float(sol[1]), float(sol[2])


def drift(x: Any, params: CatamaranParams | Any) -> np.ndarray:
    """Φ(z) of eq. (3) over leading batch axes: ``x`` (..., 7) → (..., 7).

    Parameters
    ----------
    x : array_like, shape (..., 7)
        States z (SI units, radians).
    params : CatamaranParams or array_like
        Parameters, one set or an array (..., n_params).

    Returns
    -------
    numpy.ndarray, shape (..., 7)
    """
    X, P, batch = _pack(x, params)
    out = np.empty_like(X)
    _batched_drift(X, P, out)
    return out.reshape(batch + (7,))


def jacobian(x: Any, params: CatamaranParams | Any) -> np.ndarray:
    """Analytic Jacobian ∂Φ/∂z of eq. (3) over leading batch axes: (..., 7) → (..., 7, 7).

    Used by the final-state method, eq. (14)-(15); ∂Φ_3/∂δ = L T_v cos δ / J_ω gives W_37 of
    eq. (19).

    Parameters
    ----------
    x : array_like, shape (..., 7)
        States z (SI units, radians).
    params : CatamaranParams or array_like
        Parameters, one set or an array (..., n_params).

    Returns
    -------
    numpy.ndarray, shape (..., 7, 7)
    """
    X, P, batch = _pack(x, params)
    out = np.empty((X.shape[0], 7, 7))
    _batched_jacobian(X, P, out)
    return out.reshape(batch + (7, 7))


CATAMARAN = VesselModel(
    name="catamaran",
    description="twin azimuth-thruster catamaran, 7 states, input thruster rate dδ/dt "
    "(Shushlyapin et al., 2017)",
    params_type=CatamaranParams,
    state_labels=STATES,
    state_units=_UNITS,
    input_labels=INPUTS,
    input_units=("rad/s",),
    disturbance_labels=(),
    disturbance_units=(),
    rhs=catamaran_rhs,
    output=catamaran_output,
    output_labels=OUTPUTS,
    output_units=_OUTPUT_UNITS,
)

CATAMARAN_SERVO = VesselModel(
    name="catamaran-servo",
    description="twin azimuth-thruster catamaran with the first-order thruster drive of eq. (22), "
    "input thruster command v (Shushlyapin et al., 2017)",
    params_type=CatamaranServoParams,
    state_labels=STATES,
    state_units=_UNITS,
    input_labels=SERVO_INPUTS,
    input_units=("rad",),
    disturbance_labels=(),
    disturbance_units=(),
    rhs=catamaran_servo_rhs,
    output=catamaran_output,
    output_labels=OUTPUTS,
    output_units=_OUTPUT_UNITS,
)
