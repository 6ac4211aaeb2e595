"""Voitkunsky's nonlinear steering model (yaw rate and drift angle), as used by Romanov & Chirkova.

The model, Romanov & Chirkova, eq. (1) (after Voitkunsky, Pershits & Titov, 1973)::

    dω/dt = −q31 β − r31 ω − s31 α                     + m_d
    dβ/dt = −q21 β − r21 ω − h2 β|β| − s21 α           − f_d

ω yaw rate [rad/s], β drift angle [rad], α rudder angle [rad]. Coefficient units follow from
the equations: q31, s31 [1/s²]; r31, q21, s21, h2 [1/s]; r21 [–].

Sign conventions (as in :mod:`seahelm.vessels.base`): heading ψ clockwise from north, a positive
yaw rate turns to starboard, and the parameter set decides which rudder sign turns which way
(the catalog set :data:`MARINER_VOITKUNSKY` has s31 < 0, so a positive rudder angle gives a
positive yaw rate, as the engine expects). **The drift angle β is positive when the velocity
vector lies to port of the heading**, i.e. β = −atan(v/u) with v the sway velocity to starboard —
the Russian-literature convention, in which β > 0 in a steady turn to starboard. Course over
ground is ψ − β, and the kinematics at the constant speed U of the velocity vector are::

    ẋ_N = U cos(ψ − β) − v_c sin ψ,    ẏ_E = U sin(ψ − β) + v_c cos ψ,    ψ̇ = ω

(v_c: an optional sway drift velocity, e.g. a current, as in the Nomoto models). The outputs
report surge speed U cos β and sway speed −U sin β, then ``speed`` U and ``drift_angle`` β.

Disturbances (sampled on the simulation grid, normalised like the coefficients, in state
units so that issue 7's wind and wave loads add directly):

``yaw_moment`` m_d [rad/s²]
    external yaw moment divided by the yaw inertia including added inertia, N_ext/(I_z − N_ṙ);
    positive turns to starboard.
``sway_force`` f_d [rad/s]
    external sway force divided by (m − Y_v̇)·U; positive pushes to starboard. Because
    β = −v/U it enters dβ/dt with a minus sign.
``sway_velocity`` v_c [m/s]
    a kinematic drift (current) added to the position kinematics only.
``force_y`` [N], ``moment_z`` [N·m]
    the same loads in newtons (wind and waves of :mod:`seahelm.environment.loads`), normalised
    by the parameters ``sway_mass`` (m − Y_v̇) and ``yaw_inertia`` (I_z − N_ṙ), which must then
    be given (> 0): f_d += F_y/((m − Y_v̇) U), m_d += N/(I_z − N_ṙ). A constant-speed model
    takes no surge load.

The static (steady-turn) regime, its branches and the reduced model eq. (4) live in
:mod:`seahelm.identification.reduced.turns`.

References
----------
Romanov, A. V., Chirkova, M. M. Transforming the mathematical model of ship manoeuvrability to
minimise the time to estimate its coefficients (in Russian), VGAVT. Eq. (1)-(5).
Voitkunsky, Ya. I., Pershits, R. Ya., Titov, I. A. (1973). Handbook of ship theory: propulsors
and manoeuvrability (in Russian). Leningrad: Sudostroenie.
Chislett, M. S., Strøm-Tejsen, J. (1965). Planar motion mechanism tests and full-scale steering
and manoeuvring predictions for a Mariner class vessel. Hydro- og Aerodynamisk Laboratorium,
Report Hy-6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit
from numpy.typing import ArrayLike

from ..constants import RHO_SEAWATER
from ..errors import ParameterError
from ..parameters import Params, param, signal_indices
from .base import NAV_OUTPUT_UNITS, NAV_OUTPUTS, VesselModel

__all__ = [
    "VoitkunskyParams",
    "VOITKUNSKY",
    "MARINER_VOITKUNSKY",
    "MARINER_VOITKUNSKY_PROVENANCE",
    "voitkunsky_from_linear_derivatives",
    "steady_course_keeping",
]


@dataclass(frozen=True, kw_only=True)
class VoitkunskyParams(Params):
    """Coefficients of Voitkunsky's steering model, Romanov & Chirkova eq. (1) (SI units)."""

    q21: float = param(unit="1/s", symbol="q21", doc="drift damping: dβ/dt per drift angle (−)")
    r21: float = param(unit="-", symbol="r21", doc="dβ/dt per yaw rate (−); ≈ −(1 − Y_r/mU)")
    s21: float = param(unit="1/s", symbol="s21", doc="dβ/dt per rudder angle (−)")
    h2: float = param(unit="1/s", symbol="h2", low=0.0,
                      doc="nonlinear drift damping: dβ/dt per β|β| (−), ≥ 0")
    q31: float = param(unit="1/s²", symbol="q31", doc="dω/dt per drift angle (−)")
    r31: float = param(unit="1/s", symbol="r31", doc="yaw damping: dω/dt per yaw rate (−)")
    s31: float = param(unit="1/s²", symbol="s31", doc="dω/dt per rudder angle (−)")
    speed: float = param(unit="m/s", symbol="U", low=0.0, doc="speed of the velocity vector")
    length: float = param(100.0, unit="m", symbol="L", low=0.0, low_inclusive=False,
                          doc="length between perpendiculars (for plots and scaling)")
    sway_mass: float = param(0.0, unit="kg", symbol="m − Y_v̇", low=0.0,
                             doc="mass plus added mass in sway, for the force_y channel "
                                 "(0: not given)")
    yaw_inertia: float = param(0.0, unit="kg·m²", symbol="I_z − N_ṙ", low=0.0,
                               doc="yaw inertia plus added inertia, for the moment_z channel "
                                   "(0: not given)")


STATES: tuple[str, ...] = ("north", "east", "heading", "yaw_rate", "drift_angle")
INPUTS: tuple[str, ...] = ("rudder_angle",)
DISTURBANCES: tuple[str, ...] = ("yaw_moment", "sway_force", "sway_velocity", "force_y",
                                 "moment_z")
#: The navigation outputs plus the speed U [m/s] and the drift angle β [rad] (port positive).
OUTPUTS: tuple[str, ...] = NAV_OUTPUTS + ("speed", "drift_angle")

_X = signal_indices(STATES)
_U = signal_indices(INPUTS)
_D = signal_indices(DISTURBANCES)
_Y = signal_indices(OUTPUTS)


@njit(cache=True)
def voitkunsky_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    q21, r21, s21, h2 = p.q21, p.r21, p.s21, p.h2
    q31, r31, s31, speed = p.q31, p.r31, p.s31, p.speed
    psi = x[_X.heading]
    omega = x[_X.yaw_rate]
    beta = x[_X.drift_angle]
    alpha = u[_U.rudder_angle]
    m_d = d[_D.yaw_moment] if d.shape[0] > _D.yaw_moment else 0.0
    f_d = d[_D.sway_force] if d.shape[0] > _D.sway_force else 0.0
    v_c = d[_D.sway_velocity] if d.shape[0] > _D.sway_velocity else 0.0
    force = d[_D.force_y] if d.shape[0] > _D.force_y else 0.0
    moment = d[_D.moment_z] if d.shape[0] > _D.moment_z else 0.0
    if force != 0.0:  # (a load in newtons, normalised as sway_force)
        f_d += force / (p.sway_mass * speed)
    if moment != 0.0:
        m_d += moment / p.yaw_inertia
    cs = math.cos(psi)
    sn = math.sin(psi)
    dx[_X.north] = speed * math.cos(psi - beta) - v_c * sn
    dx[_X.east] = speed * math.sin(psi - beta) + v_c * cs
    dx[_X.heading] = omega
    dx[_X.yaw_rate] = -q31 * beta - r31 * omega - s31 * alpha + m_d
    dx[_X.drift_angle] = -q21 * beta - r21 * omega - h2 * beta * abs(beta) - s21 * alpha - f_d


@njit(cache=True)
def voitkunsky_output(t, x, u, p, y):  # pragma: no cover - compiled
    speed = p.speed
    y[_Y.north] = x[_X.north]
    y[_Y.east] = x[_X.east]
    y[_Y.heading] = x[_X.heading]
    y[_Y.yaw_rate] = x[_X.yaw_rate]
    y[_Y.surge_speed] = speed * math.cos(x[_X.drift_angle])
    y[_Y.sway_speed] = -speed * math.sin(x[_X.drift_angle])
    y[_Y.speed] = speed
    y[_Y.drift_angle] = x[_X.drift_angle]


@njit(cache=True)
def voitkunsky_motion(x, p):  # pragma: no cover - compiled
    """Surge U cos β and sway −U sin β [m/s] and heading [rad] (for the loads)."""
    beta = x[_X.drift_angle]
    return p.speed * math.cos(beta), -p.speed * math.sin(beta), x[_X.heading]


VOITKUNSKY = VesselModel(
    name="voitkunsky",
    description="Voitkunsky nonlinear steering model (yaw rate, drift angle with β|β|), "
    "Romanov & Chirkova eq. (1), constant speed",
    params_type=VoitkunskyParams,
    state_labels=STATES,
    state_units=("m", "m", "rad", "rad/s", "rad"),
    input_labels=INPUTS,
    input_units=("rad",),
    disturbance_labels=DISTURBANCES,
    disturbance_units=("rad/s²", "rad/s", "m/s", "N", "N·m"),
    rhs=voitkunsky_rhs,
    output=voitkunsky_output,
    output_labels=OUTPUTS,
    output_units=NAV_OUTPUT_UNITS + ("m/s", "rad"),
    state_lower=(-np.inf, -np.inf, -np.inf, -np.inf, -0.5 * math.pi),
    state_upper=(np.inf, np.inf, np.inf, np.inf, 0.5 * math.pi),
    load_params=("sway_mass", "yaw_inertia"),
    motion=voitkunsky_motion,
)


def steady_course_keeping(
    params: VoitkunskyParams, yaw_moment: ArrayLike, sway_force: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Steady course keeping (ω = 0) under constant loads: drift angle β and rudder angle δ.

    With the normalised disturbances m_d (``yaw_moment``) and f_d (``sway_force``) of the
    model, ω = 0 in eq. (1) gives 0 = −q31 β − s31 δ + m_d, 0 = −q21 β − h2 β|β| − s21 δ − f_d;
    eliminating δ gives h2 β|β| − a β + c = 0 with a = s21 q31/s31 − q21, c = f_d + s21 m_d/s31,
    a monotone equation in β when a < 0 (a course-stable ship), solved in closed form.

    Parameters
    ----------
    params : VoitkunskyParams
        The model.
    yaw_moment : array_like
        Normalised yaw-moment disturbance m_d [rad/s²] (the ``yaw_moment`` channel).
    sway_force : array_like
        Normalised sway-force disturbance f_d [rad/s] (the ``sway_force`` channel).

    Returns
    -------
    drift, rudder : numpy.ndarray
        Steady drift angle β [rad] and rudder angle δ [rad].

    Raises
    ------
    ParameterError
        If the model is not course-stable (a ≥ 0): there is no steady state.
    """
    q21, s21, h2, q31, s31 = params.q21, params.s21, params.h2, params.q31, params.s31
    yaw_moment = np.asarray(yaw_moment, dtype=float)
    sway_force = np.asarray(sway_force, dtype=float)
    a = s21 * q31 / s31 - q21
    c = sway_force + s21 * yaw_moment / s31
    if a >= 0.0:
        raise ParameterError("the Voitkunsky model is not course-stable (a >= 0); no steady state")
    if h2 == 0.0:
        beta = c / a
    else:
        # β ≥ 0 branch: h2 β² + |a| β + c = 0 (c ≤ 0); β < 0 branch mirrored
        disc = np.sqrt(a * a + 4.0 * h2 * np.abs(c))
        beta = -np.sign(c) * (disc - abs(a)) / (2.0 * h2)
    delta = (yaw_moment - q31 * beta) / s31
    return beta, delta


def voitkunsky_from_linear_derivatives(
    *,
    mass: float,
    inertia: float,
    xg: float,
    y_vdot: float,
    y_rdot: float,
    n_vdot: float,
    n_rdot: float,
    y_v: float,
    y_r: float,
    n_v: float,
    n_r: float,
    y_delta: float,
    n_delta: float,
    y_vvv: float,
    n_vvv: float,
    speed: float,
    length: float,
    beta_range: float = 0.3,
    rho: float = RHO_SEAWATER,
) -> VoitkunskyParams:
    """Voitkunsky coefficients from nondimensional (prime-system) manoeuvring derivatives.

    The linear part is exact: with v' = v/U = −β, r' = ωL/U, t' = tU/L and the mass matrix
    M = [[m' − Y_v̇', m'x_G' − Y_ṙ'], [m'x_G' − N_v̇', I_z' − N_ṙ']], the state matrix
    A' = M⁻¹[[Y_v', Y_r'], [N_v', N_r']] and input vector B' = M⁻¹[Y_δ', N_δ'] give
    q21 = −(U/L) A'11, r21 = A'12, s21 = (U/L) B'1, q31 = (U/L)² A'21, r31 = −(U/L) A'22,
    s31 = −(U/L)² B'2. ``y_r`` must already contain the −m' (centripetal) term, as the Mariner
    tables do. The rudder sign is taken as given (pass −Y_δ', −N_δ' to flip it).

    The nonlinear part is an approximation, because eq. (1) has a β|β| term in the drift
    equation only: the sway row of M⁻¹ applied to (Y_vvv', N_vvv') v'³ is replaced by its
    least-squares fit k·v'|v'| on |β| ≤ ``beta_range`` (k = 5·beta_range/6); the cubic term
    of the yaw row and all cross terms (Y_vvr, ...) are dropped.

    Parameters
    ----------
    mass, inertia : float
        Nondimensional mass m' and yaw moment of inertia I_z' [-].
    xg : float
        Nondimensional longitudinal centre of gravity x_G' [-].
    y_vdot, y_rdot, n_vdot, n_rdot : float
        Added-mass derivatives Y_v̇', Y_ṙ', N_v̇', N_ṙ' [-].
    y_v, y_r, n_v, n_r : float
        Linear damping derivatives Y_v', Y_r' (including −m'), N_v', N_r' [-].
    y_delta, n_delta : float
        Rudder derivatives Y_δ', N_δ' [-].
    y_vvv, n_vvv : float
        Cubic sway derivatives Y_vvv', N_vvv' [-].
    speed : float
        Ship speed U [m/s].
    length : float
        Ship length L [m].
    beta_range : float, optional
        Drift-angle range |β| ≤ ``beta_range`` of the nonlinear fit [rad] (default 0.3).
    rho : float, optional
        Water density [kg/m³] of the dimensional masses ``sway_mass`` = (m' − Y_v̇') ½ρL³ and
        ``yaw_inertia`` = (I_z' − N_ṙ') ½ρL⁵ (default sea water).

    Returns
    -------
    VoitkunskyParams
    """
    m_mat = np.array([[mass - y_vdot, mass * xg - y_rdot], [mass * xg - n_vdot, inertia - n_rdot]])
    m_inv = np.linalg.inv(m_mat)
    a = m_inv @ np.array([[y_v, y_r], [n_v, n_r]])
    b = m_inv @ np.array([y_delta, n_delta])
    c1 = m_inv[0, 0] * y_vvv + m_inv[0, 1] * n_vvv
    s = speed / length
    k = 5.0 * beta_range / 6.0
    return VoitkunskyParams(
        q21=float(-s * a[0, 0]),
        r21=float(a[0, 1]),
        s21=float(s * b[0]),
        h2=float(max(-s * c1 * k, 0.0)),
        q31=float(s * s * a[1, 0]),
        r31=float(-s * a[1, 1]),
        s31=float(-s * s * b[1]),
        speed=float(speed),
        length=float(length),
        sway_mass=float((mass - y_vdot) * 0.5 * rho * length ** 3),
        yaw_inertia=float((inertia - n_rdot) * 0.5 * rho * length ** 5),
    )


#: Mariner-class derivatives (Chislett & Strøm-Tejsen, 1965, as tabulated in Fossen's MSS
#: ``mariner.m``), prime system, rudder sign flipped so that positive rudder turns to starboard.
_MARINER_DERIVATIVES = dict(
    mass=798e-5, inertia=39.2e-5, xg=-0.023,
    y_vdot=-748e-5, y_rdot=-9.354e-5, n_vdot=4.646e-5, n_rdot=-43.8e-5,
    y_v=-1160e-5, y_r=-499e-5, n_v=-264e-5, n_r=-166e-5,
    y_delta=-278e-5, n_delta=139e-5,
    y_vvv=-8078e-5, n_vvv=1636e-5,
    speed=7.7175, length=160.93, beta_range=0.3,
)

MARINER_VOITKUNSKY: VoitkunskyParams = voitkunsky_from_linear_derivatives(**_MARINER_DERIVATIVES)

MARINER_VOITKUNSKY_PROVENANCE = (
    "Mariner-class cargo ship (L = 160.93 m, U = 15 kn = 7.7175 m/s), derived here from the "
    "prime-system hydrodynamic derivatives of Chislett & Strøm-Tejsen (1965) as tabulated in "
    "Fossen's MSS mariner.m (rudder sign flipped: positive rudder turns to starboard). Linear "
    "coefficients exact (they reproduce the Nomoto constants K = 0.185 1/s, T1 = 118 s, "
    "T2 = 7.76 s, T3 = 18.5 s of the mariner-nomoto2 entry); h2 approximates the sway-row "
    "Y_vvv/N_vvv cubic by a β|β| least-squares fit on |β| ≤ 0.3 rad, the yaw-row cubic and cross "
    "terms are dropped. Not from Romanov & Chirkova, who publish no coefficient values."
)
