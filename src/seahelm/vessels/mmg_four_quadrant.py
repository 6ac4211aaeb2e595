"""MMG model through zero and negative speed and rps: the crash stop (``mmg-4q``).

The MMG standard model (:mod:`seahelm.vessels.mmg`, Yasukawa & Yoshimura 2015) with

* the propeller rps as a state driven by an engine order through the engine, shaft and
  reversal sequence of :mod:`seahelm.vessels.engine_shaft` (its sequence clock τ is the
  state ``reversal_clock`` [s], 0 in a steady run);
* the four-quadrant propeller (:mod:`seahelm.hydrodynamics.four_quadrant`, Wageningen B4-70
  P/D 1.0 of Roddy, Hess & Faller 2006) for the thrust outside the first quadrant and for the
  torque everywhere, scaled to the ship's propeller by s = k_0 / K_T0(B4-70), so that the
  bollard thrust equals the ship's K_T(0) = k_0;
* hull, wake, thrust deduction and rudder inflow defined for u < 0 and n < 0, and the
  propeller's side force when backing.

Forces by quadrant (u surge speed, n rps)
    **u ≥ 0, n ≥ 0**: exactly the MMG model's forces (its compiled force function is called):
    the MMG standard method is the model there, and with a constant engine order held by the
    governor the run equals the ``mmg`` model's (tested: turning circle and zig-zag of the
    KVLCC2 to round-off).
    **n < 0 or u < 0**: thrust T = s ½ρ C_T*(β)(V_A² + (0.7πnD)²)(π/4)D², β = atan2(V_A,
    0.7πnD), V_A = u (1 − w_P); w_P the MMG wake w_P(β_P) for u ≥ 0 and 0 for u < 0 (the
    propeller then leads the hull: no hull wake); X_P = (1 − t_P) T for n ≥ 0 and X_P = T
    for n < 0 (no thrust deduction for the reversed race: an assumption, no KVLCC2 data).
    Rudder: the MMG formulas with this thrust (the slipstream term vanishes when the race is
    reversed, max(u_P² + 8T/(πρD²), 0)); for u_P < 0 the inflow is reversed (as in ``mmg``).
    Hull (``hull_model``): **0, the default**, the MMG polynomials while |β| ≤ 30° and |r'| ≤ 1
    (their fitted range), the low-speed cross-flow model of Yoshimura, Nakao & Ishibashi
    (2009) (:mod:`seahelm.hydrodynamics.low_speed_hull`: the MMG's linear derivatives, the
    cross-flow drag of the hull's strips, R'_0,astern astern) from |β| ≥ 45° or |r'| ≥ 1.5 —
    so astern (|β| > 90°) always — and a linear blend in between (continuous; tested).
    **1** (:data:`HULL_MIRROR`, the earlier approximation): the MMG hull for u ≥ 0 at any drift
    and for u < 0 its fore-aft mirror, (X, Y, N)(u, v, r) = (−X, Y, −N)_MMG(−u, v, −r), with
    the astern resistance coefficient R'_0,astern in place of R'_0. While a run stays in the
    MMG range both give the same forces, computed by the same code (bit for bit; tested).

Side force of a backing single screw (right-handed propeller turning astern): the stern is
pushed to port, Y_P = −c_Y |T|, N_P = x_R L_pp Y_P (the bow swings to starboard), for n < 0.
c_Y (``backing_side_force``) is an assumption of a few per cent of the astern thrust (the
order quoted for single-screw ships, e.g. Harvald 1983, *Resistance and propulsion of ships*,
§ on propeller side forces); no KVLCC2 value was found.

Ranges and what is not modelled
    The MMG hull polynomials are fits to captive tests at small to moderate drift (KVLCC2:
    |β| up to about 20–30°) and ahead speed. With ``hull_model`` 0 the cross-flow model takes
    over beyond; it is stated for Fn ≤ 0.1 (low speed, no wave-making), and the stopping
    analysis (:mod:`seahelm.analysis.maneuvers.stopping`) warns
    (:class:`~seahelm.errors.ValidityRangeWarning`, an error in strict mode) when a run uses it
    faster. Its C_D is matched to the MMG sway force at 30° and C_rY = C_rN = 1 (no KVLCC2
    values of Yoshimura's coefficients were found): a published model form with estimated
    coefficients, not a fit to the KVLCC2. With ``hull_model`` 1 the stopping analysis warns
    when a run leaves |β| ≤ 30° above 20 % of the approach speed before it is dead in the
    water; astern, the mirrored hull is an approximation (the KVLCC2 is not fore-aft
    symmetric). The crash-stop models of Yasukawa et al. are not implemented. The
    propeller's thrust jumps when n changes sign at u > 0 (the MMG K_T polynomial on one side,
    the B4-70 series on the other): the shaft passes zero in seconds.

References
----------
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
Yoshimura, Y., Nakao, I. & Ishibashi, A. (2009). Unified mathematical model for ocean and
harbour manoeuvring. Proc. MARSIM 2009, Panama City.
Roddy, R. F., Hess, D. E. & Faller, W. E. (2006). Neural network predictions of the
4-quadrant Wageningen propeller series. NSWCCD-50-TR-2006/004.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..constants import GRAVITY
from ..errors import ParameterError
from ..hydrodynamics.four_quadrant import (
    ct_cq,
    fourier_coefficients,
    thrust_coefficient_4q,
    torque_coefficient_4q,
)
from ..hydrodynamics.low_speed_hull import (
    low_speed_hull,
    low_speed_weight,
    matching_cross_flow_drag,
)
from ..parameters import param, signal_indices
from .base import VesselModel
from .engine_shaft import (
    EngineShaftParams,
    check_engine,
    reversal_clock_rate,
    shaft_acceleration,
)
from .mmg import (
    DISTURBANCE_UNITS,
    DISTURBANCES,
    KVLCC2_FULL,
    KVLCC2_L7,
    MMGParams,
    _forces,
    mmg_accelerations,
    mmg_motion,
    mmg_rudder_forces,
    rudder_inflow_angle,
    wake_fraction,
    write_mmg_outputs,
    write_mmg_rates,
)
from .mmg import OUTPUT_UNITS as _MMG_OUTPUT_UNITS
from .mmg import OUTPUTS as _MMG_OUTPUTS

__all__ = ["MMG4QParams", "MMG_4Q", "STATES", "INPUTS", "OUTPUTS", "KVLCC2_FULL_4Q",
           "KVLCC2_L7_4Q", "KVLCC2_ENGINE_NOTE", "self_propulsion_rps", "propeller_torque",
           "from_mmg", "HULL_CROSS_FLOW", "HULL_MIRROR"]

STATES = ("surge_speed", "sway_speed", "yaw_rate", "north", "east", "heading", "propeller_rps",
          "reversal_clock")
STATE_UNITS = ("m/s", "m/s", "rad/s", "m", "m", "rad", "1/s", "s")
INPUTS = ("rudder_angle", "engine_order")
INPUT_UNITS = ("rad", "1")
OUTPUTS = _MMG_OUTPUTS + ("propeller_rps", "propeller_torque", "advance_angle")
OUTPUT_UNITS = _MMG_OUTPUT_UNITS + ("1/s", "N·m", "rad")

S = signal_indices(STATES)
U = signal_indices(INPUTS)
D = signal_indices(DISTURBANCES)
Y = signal_indices(OUTPUTS)

#: ``hull_model`` values: the cross-flow low-speed hull (default) and the mirrored MMG hull.
HULL_CROSS_FLOW = 0.0
HULL_MIRROR = 1.0

#: C_T*, C_Q* coefficients of the B4-70 P/D 1.0 series (a compile-time constant).
_COEFFS = fourier_coefficients()
#: K_T at J = 0 of the series: C_T*(0) (π/8)(0.7π)².
KT0_SERIES = float(thrust_coefficient_4q(0.0)) * math.pi / 8.0 * (0.7 * math.pi) ** 2


@dataclass(frozen=True, kw_only=True)
class MMG4QParams(MMGParams, EngineShaftParams):
    """The MMG parameters, the engine and shaft (:class:`EngineShaftParams`) and the astern
    hull and propeller terms (module docstring)."""

    R_0_astern: float = param(0.022, unit="-", symbol="R'_0,astern", low=0.0,
                              doc="resistance coefficient going astern (default: R'_0; "
                                  "no astern resistance data)")
    backing_side_force: float = param(0.05, unit="-", symbol="c_Y", low=0.0, high=0.5,
                                      doc="side force of the backing propeller over |T|")
    hull_model: float = param(HULL_CROSS_FLOW, unit="-", symbol="hull", low=0.0, high=1.0,
                              doc="hull astern and at large drift: 0 the cross-flow model of "
                                  "Yoshimura et al. 2009 (blended from the MMG's beyond 30 deg "
                                  "or r' 1), 1 the fore-aft mirror of the MMG hull astern")
    cross_flow_drag: float = param(0.888, unit="-", symbol="C_D", low=0.0, high=5.0,
                                   low_inclusive=False,
                                   doc="cross-flow drag coefficient of the hull, > 0 (default: "
                                       "the KVLCC2's, matched to the MMG sway force at 30 deg)")
    C_rY: float = param(1.0, unit="-", symbol="C_rY", low=0.0, high=5.0,
                        doc="yaw-rate factor of the cross-flow velocity in the sway force")
    C_rN: float = param(1.0, unit="-", symbol="C_rN", low=0.0, high=5.0,
                        doc="yaw-rate factor of the cross-flow velocity in the yaw moment")

    def validate(self) -> None:
        """The MMG and engine cross-field checks; ``hull_model`` is 0 or 1."""
        MMGParams.validate(self)
        check_engine(self)
        if self.hull_model not in (HULL_CROSS_FLOW, HULL_MIRROR):
            raise ParameterError(
                f"must be {HULL_CROSS_FLOW:g} (cross-flow low-speed hull) or {HULL_MIRROR:g} "
                f"(mirrored MMG hull), got {self.hull_model!r}", field="hull_model",
                unit="-", value=self.hull_model)


@njit(cache=True)
def _propeller_4q(u_P, n, p):  # pragma: no cover - compiled
    """Scaled four-quadrant thrust, torque and advance angle for V_A = u_P."""
    dp = p.propeller_diameter
    w = 0.7 * math.pi * n * dp
    beta = math.atan2(u_P, w)
    ct, cq = ct_cq(beta, _COEFFS)
    s = p.k_0 / KT0_SERIES
    base = 0.5 * p.rho * (u_P * u_P + w * w) * 0.25 * math.pi * dp * dp
    return s * ct * base, s * cq * base * dp, beta


@njit(cache=True)
def _forces4q(u, v, r, delta, n, p):  # pragma: no cover - compiled
    """(X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, T, Q, F_N, u_R, v_R, U, β, β_adv)."""
    L = p.length
    mirror = p.hull_model >= 0.5
    w = 0.0
    if not mirror:
        w = low_speed_weight(u, v, r, L, p.min_froude_number * math.sqrt(GRAVITY * L))
    ahead = u >= 0.0 and n >= 0.0 and w == 0.0  # the MMG model's own forces, bit for bit
    flip = mirror and u < 0.0  # the fore-and-aft mirror of the ahead hull
    # One call of the MMG force function for every branch: each call site is a copy of it in
    # the compiled kernel (three of them doubled the crash stop's compile time).
    hull = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    if ahead or flip or w < 1.0:
        hull = _forces(-u if flip else u, v, -r if flip else r, delta if ahead else 0.0,
                       n if ahead else 0.0, p)
    rho = p.rho
    speed = 0.0
    rn = 0.0
    beta = 0.0
    X_H = 0.0
    Y_H = 0.0
    N_H = 0.0
    w_P = 0.0
    if ahead:
        w_P = hull[9]
    else:
        speed = math.sqrt(u * u + v * v)
        u_nd = max(speed, p.min_froude_number * math.sqrt(GRAVITY * L))
        rn = r * L / u_nd
        beta = math.atan2(-v, u)
        if flip:  # the mirrored hull, with the astern resistance
            q = 0.5 * rho * L * p.draft * speed * speed
            X_H = -hull[0] + (p.R_0_astern - p.R_0) * q
            Y_H = hull[1]
            N_H = -hull[2]
        else:  # the MMG hull (w < 1) blended into the cross-flow model (w > 0); mirror: w = 0
            if w < 1.0:  # (one code block for both hull models: the same rounding in both)
                X_H, Y_H, N_H = hull[0], hull[1], hull[2]
            if w > 0.0:
                X_L, Y_L, N_L = low_speed_hull(u, v, r, L, p.draft, rho, -p.R_0,
                                               -p.R_0_astern, p.X_vr, p.Y_v, p.Y_r, p.N_v,
                                               p.N_r, p.cross_flow_drag, p.C_rY, p.C_rN)
                X_H = w * X_L + (1.0 - w) * X_H
                Y_H = w * Y_L + (1.0 - w) * Y_H
                N_H = w * N_L + (1.0 - w) * N_H
            if u >= 0.0:
                w_P = wake_fraction(beta - p.x_P * rn, p.w_P0, p.C_1, p.C_2_plus, p.C_2_minus)
    # One call of the four-quadrant propeller for both branches (each call site is a copy of
    # its Fourier series in the compiled kernel)
    u_P = u * (1.0 - w_P)
    thrust, torque, b_adv = _propeller_4q(u_P, n, p)
    if ahead:
        (X_H, Y_H, N_H, X_P, X_R, Y_R, N_R, thrust, F_N, w_P, u_R, v_R, speed, beta) = hull
        return (X_H, Y_H, N_H, X_P, 0.0, 0.0, X_R, Y_R, N_R, thrust, torque, F_N, u_R, v_R,
                speed, beta, b_adv)
    X_P = (1.0 - p.t_P) * thrust if n >= 0.0 else thrust
    Y_P = 0.0
    N_P = 0.0
    if n < 0.0:
        Y_P = -p.backing_side_force * abs(thrust)
        N_P = p.x_R * L * Y_P
    # rudder: the MMG formulas (mmg.mmg_rudder_forces) with this thrust
    X_R, Y_R, F_N, cos_d, u_R, v_R = mmg_rudder_forces(u_P, thrust, beta, rn, speed, delta, p)
    N_R = -(p.x_R * L + p.a_H * p.x_H * L) * F_N * cos_d
    return (X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, thrust, torque, F_N, u_R, v_R,
            speed, beta, b_adv)


@njit(cache=True)
def mmg4q_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of the four-quadrant MMG model for one run (module docstring)."""
    uu = x[S.surge_speed]
    v = x[S.sway_speed]
    r = x[S.yaw_rate]
    n = x[S.propeller_rps]
    (X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, _T, torque, _F_N, _u_R, _v_R, _U, _b,
     _b_adv) = _forces4q(uu, v, r, u[U.rudder_angle], n, p)
    X = X_H + X_P + X_R + d[D.force_x]
    Yf = Y_H + Y_R + Y_P + d[D.force_y]
    N = N_H + N_R + N_P + d[D.moment_z]
    du, dv, dr = mmg_accelerations(X, Yf, N, uu, v, r, p)
    write_mmg_rates(x, d, dx, du, dv, dr)
    clock = x[S.reversal_clock]
    dx[S.propeller_rps] = shaft_acceleration(n, u[U.engine_order], torque, clock, p)
    dx[S.reversal_clock] = reversal_clock_rate(n, u[U.engine_order], clock, p)


@njit(cache=True)
def mmg4q_output(t, x, u, p, y):  # pragma: no cover - compiled
    """Outputs (``OUTPUTS`` order) for one run."""
    delta = u[U.rudder_angle]
    (_X_H, _Y_H, _N_H, _X_P, _Y_P, _N_P, _X_R, _Y_R, _N_R, thrust, torque, F_N, u_R, v_R,
     speed, beta, b_adv) = _forces4q(x[S.surge_speed], x[S.sway_speed], x[S.yaw_rate], delta,
                                     x[S.propeller_rps], p)
    write_mmg_outputs(x, y, speed, beta, thrust, F_N, rudder_inflow_angle(delta, u_R, v_R))
    y[Y.propeller_rps] = x[S.propeller_rps]
    y[Y.propeller_torque] = torque
    y[Y.advance_angle] = b_adv


MMG_4Q = VesselModel(
    name="mmg-4q",
    description="MMG model through zero and negative speed and rps: engine, shaft and "
    "reversal, four-quadrant B4-70 propeller (Roddy et al. 2006), low-speed cross-flow hull "
    "astern and at large drift (Yoshimura et al. 2009) (crash stop)",
    params_type=MMG4QParams,
    state_labels=STATES,
    state_units=STATE_UNITS,
    input_labels=INPUTS,
    input_units=INPUT_UNITS,
    disturbance_labels=DISTURBANCES,
    disturbance_units=DISTURBANCE_UNITS,
    rhs=mmg4q_rhs,
    output=mmg4q_output,
    output_labels=OUTPUTS,
    output_units=OUTPUT_UNITS,
    motion=mmg_motion,
)


def self_propulsion_rps(params: MMGParams, speed: float) -> float:
    """The rps of the straight run at ``speed`` [m/s] (X_H + X_P = 0, δ = 0, w_P = w_P0).

    Parameters
    ----------
    params : MMGParams
        Ship (the MMG K_T polynomial).
    speed : float
        Surge speed [m/s], > 0.

    Returns
    -------
    float
        n [1/s].

    Raises
    ------
    ParameterError
        If the K_T polynomial gives no positive rps at this speed (k_0 ≤ 0, or a thrust that
        never equals the resistance), naming ``k_0`` (it divided by zero or took the root of
        a negative number).
    """
    p = params
    q = 0.5 * p.rho * p.length * p.draft * speed * speed
    u_P = speed * (1.0 - p.w_P0)
    dp = p.propeller_diameter
    # (1 − t_P) ρ D² (k0 D² n² + k1 D u_P n + k2 u_P²) = R_0 q
    a = p.k_0 * dp * dp
    b = p.k_1 * dp * u_P
    c = p.k_2 * u_P * u_P - p.R_0 * q / ((1.0 - p.t_P) * p.rho * dp * dp)
    disc = b * b - 4.0 * a * c
    n = (-b + math.sqrt(disc)) / (2.0 * a) if a > 0.0 and disc >= 0.0 else math.nan
    if not (math.isfinite(n) and n > 0.0):
        raise ParameterError(
            f"no self-propulsion rps at {speed:.6g} m/s: the propeller's K_T(J) = k_0 + k_1 J "
            f"+ k_2 J² (k_0={p.k_0!r}, k_1={p.k_1!r}, k_2={p.k_2!r}) never balances the "
            f"resistance (K_T(0) = k_0 must be > 0)", field="k_0")
    return float(n)


def propeller_torque(params: MMGParams, speed: float, rps: float) -> float:
    """Propeller torque Q [N·m] of the scaled series at V_A = speed (1 − w_P0), rps n.

    Parameters
    ----------
    params : MMGParams
        Ship (propeller diameter, wake, k_0 for the scale).
    speed : float
        Surge speed [m/s] of a straight run.
    rps : float
        Propeller rps [1/s].

    Returns
    -------
    float
        Q [N·m].
    """
    p = params
    dp = p.propeller_diameter
    u_P = speed * (1.0 - p.w_P0)
    w = 0.7 * math.pi * rps * dp
    beta = math.atan2(u_P, w)
    cq = float(torque_coefficient_4q(beta))  # (numpy: importing compiles nothing)
    s = p.k_0 / KT0_SERIES
    return float(s * cq * 0.5 * p.rho * (u_P * u_P + w * w) * 0.25 * math.pi * dp ** 3)


KVLCC2_ENGINE_NOTE = (
    "Engine defaults of the catalog KVLCC2 (no published engine data were found in the stored "
    "sources: reasoned estimates): the approach speed 15.5 kn is taken at 85 % MCR on the "
    "propeller law, P_MCR = P_D(U_0)/0.85 with P_D = 2 pi n Q of the scaled B4-70 series at "
    "the self-propulsion rps, n_MCR = n_SP / 0.85^(1/3); full astern n_astern = -0.7 n_MCR; "
    "reversal delay (fuel cut, the propeller windmilling, until the air start) 60 s full scale "
    "(crash-astern practice of slow-speed two-stroke diesels: air brake once the rpm has "
    "fallen to 20-40 % of full ahead, a cautious motor ship reversed about 3 min after the "
    "order; seahelm.vessels.engine_shaft); "
    "reversal below 0.25 n_MCR; reversal (brake) time 40 s full scale; governor 2 s; shaft "
    "inertia 1.2e6 kg m^2 full scale (propeller of about 65 t with a radius of gyration of "
    "about 0.22 D, its entrained water about 25 %, engine and shafting of the same order as "
    "the propeller), scaled to another ship by (rho/1025) (D_P/9.86 m)^5. L7 model: the times "
    "Froude-scaled (1/sqrt(45.7)), the inertia by that rule (= (1000/1025)/45.65^5).")


def from_mmg(params: MMGParams, *, scale: float = 1.0, **engine: float) -> MMG4QParams:
    """The four-quadrant parameters of an MMG ship with the engine estimate of
    :data:`KVLCC2_ENGINE_NOTE` (``scale`` the Froude scale λ of a model, 1 full scale);
    ``engine`` overrides fields.

    Parameters
    ----------
    params : MMGParams
        The ship.
    scale : float, optional
        Froude scale factor λ (45.7 for the L7 model) of the time estimates (the inertia
        scales with ρ D_P⁵ whatever λ).
    **engine : float
        Any :class:`MMG4QParams` field to set instead of the estimate.

    Returns
    -------
    MMG4QParams
    """
    n_sp = self_propulsion_rps(params, params.approach_speed)
    q_sp = propeller_torque(params, params.approach_speed, n_sp)
    p_mcr = 2.0 * math.pi * n_sp * q_sp / 0.85
    n_mcr = n_sp / 0.85 ** (1.0 / 3.0)
    root = math.sqrt(scale)
    values = dict(
        shaft_inertia=1.2e6 * (params.rho / 1025.0) * (params.propeller_diameter / 9.86) ** 5,
        rated_rps=n_mcr,
        max_power=p_mcr, astern_rps=-0.7 * n_mcr, reversal_time=40.0 / root,
        reversal_delay=60.0 / root,
        reversal_rps=0.25 * n_mcr, governor_time_constant=2.0 / root,
        R_0_astern=params.R_0)
    if "cross_flow_drag" not in engine:  # (Yoshimura's C_D regression was not available)
        values["cross_flow_drag"] = matching_cross_flow_drag(params.Y_v, params.Y_vvv)
    values.update(engine)
    fields = {f: getattr(params, f) for f in MMGParams.field_names()}
    return MMG4QParams(**{**fields, **values})


#: KVLCC2 full scale with the engine estimate (:data:`KVLCC2_ENGINE_NOTE`).
KVLCC2_FULL_4Q = from_mmg(KVLCC2_FULL)
#: KVLCC2 L7 model (1/45.7) with the Froude-scaled engine estimate.
KVLCC2_L7_4Q = from_mmg(KVLCC2_L7, scale=45.7)
