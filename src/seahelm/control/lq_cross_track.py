"""LQ-integral cross-track control: straight-line path following by state feedback on the route.

On leg k of a route (:mod:`seahelm.control.path_following`: path angle π_k, cross-track error
y_e positive to starboard) the ship's linear model at the service speed U, with the path
kinematics ẏ_e = U sin ψ̃ + v cos ψ̃ ≈ U ψ̃ + v (ψ̃ = ψ − π_k), is augmented with the integral
of the cross-track error::

    d/dt (∫y_e, y_e, ψ̃, [v,] r) = A_a (∫y_e, y_e, ψ̃, [v,] r) + b_a δ

and the rudder is the linear-quadratic optimal state feedback δ = −K x, minimising
∫ (xᵀQx + ρ δ²) dt with Bryson's weights (1/allowed value²; continuous algebraic Riccati
equation, scipy) — Fossen (2021), §15.3 (LQ with integral action) on the path-following
model of §12.4. Written as a heading law::

    χ   = sat((k_y y_e + k_i ∫y_e)/k_ψ, χ_max)          approach angle
    ψ_d = π_k − χ                                        (recorded as ``heading_reference``)
    δ_c = sat(−k_ψ wrap(ψ − ψ_d) − k_r r − k_v v, δ_max)

which is δ = −K x exactly while |χ| < χ_max (``max_approach_angle``, default 30°); far from
the line the ship approaches it at χ_max instead of a linear law's heading errors of many
radians. The integral (the crab angle against a cross current or wind, as ILOS's) is
integrated at the controller period (explicit Euler), frozen while the rudder or the approach
angle is saturated and integrating would deepen it (conditional integration, Åström &
Hägglund 2006, §3.5), and reset when the active leg changes. Waypoint switching as for LOS.
The records: ``heading_reference``, ``cross_track_error``, ``along_track_distance``,
``waypoint_index`` (as the guided controllers', so the path-following metrics and figures apply).

:func:`lq_cross_track` designs the gains from the ship's steering block (sway and yaw rate, or
yaw rate alone) and U; :class:`LQCrossTrackDesign` gives the controller's parameters for a
route. ``lq-cross-track-rps`` holds a constant propeller rps too (MMG ships).

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §12.4 (path following), §15.3 (LQ with integral action).
Bryson, A. E., Ho, Y.-C. (1975). Applied Optimal Control, §5.4.
Åström, K. J., Hägglund, T. (2006). Advanced PID Control, §3.5 (anti-windup).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numba import njit

from .._validate import check_positive
from ..errors import ParameterError
from ..parameters import param, signal_indices
from .autopilot_design import _warn_margins, loop_margins, state_space_response
from .base import Controller, wrap_pi
from .held_rps import with_held_rps
from .path_following import (GUIDANCE_OUTPUT_UNITS, GUIDANCE_OUTPUTS, GUIDANCE_STATES,
                             RouteParams, _advance_waypoints, cross_track, route_params)

__all__ = ["LQCrossTrackParams", "LQCrossTrackRpsParams", "LQCrossTrackDesign",
           "lq_cross_track", "LQ_CROSS_TRACK", "LQ_CROSS_TRACK_RPS"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class LQCrossTrackParams(RouteParams):
    """A route and the gains of the LQ-integral cross-track controller (module docstring)."""

    k_integral: float = param(0.0, unit="rad/(m·s)", symbol="k_i", doc="gain on ∫y_e dt")
    k_cross_track: float = param(0.01, unit="rad/m", symbol="k_y",
                                 doc="gain on the cross-track error")
    k_heading: float = param(1.0, unit="rad/rad", symbol="k_ψ", low=0.0, low_inclusive=False,
                             doc="gain on the heading error relative to the path")
    k_yaw_rate: float = param(0.0, unit="s", symbol="k_r", doc="gain on the yaw rate")
    k_sway: float = param(0.0, unit="rad·s/m", symbol="k_v", doc="gain on the sway speed")
    max_command: float = param(math.radians(35.0), unit="rad", symbol="δ_max", low=0.0,
                               low_inclusive=False, doc="command saturation (anti-windup)")
    max_approach_angle: float = param(math.radians(30.0), unit="rad", symbol="χ_max", low=0.0,
                                      low_inclusive=False, high=math.pi / 2,
                                      doc="largest approach angle to the path")


MEASUREMENTS: tuple[str, ...] = ("north", "east", "heading", "yaw_rate", "sway_speed")
COMMANDS: tuple[str, ...] = ("rudder_command",)

_M = signal_indices(MEASUREMENTS)
_C = signal_indices(COMMANDS + ("propeller_rps",))
_S = signal_indices(GUIDANCE_STATES)
_G = signal_indices(GUIDANCE_OUTPUTS)
_FIRST_OUTPUT = len(COMMANDS)  # the records follow the commands in ``cmd``


@njit(cache=True)
def lq_cross_track_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_S.segment] = 0.0
    cs[_S.integral] = 0.0
    cs[_S.complete] = 0.0


@njit(cache=True)
def lq_cross_track_law(dt, y, p, cs, out):  # pragma: no cover - compiled
    """The law of the module docstring: switches legs (resetting the integral), writes the
    records into ``out`` (heading reference, cross-track error, along-track distance, waypoint
    index) and returns δ_c [rad]."""
    north = y[_M.north]
    east = y[_M.east]
    before = cs[_S.segment]
    k = _advance_waypoints(p, cs, north, east)
    if cs[_S.segment] != before:
        cs[_S.integral] = 0.0
    pi_k, x_e, y_e, _ = cross_track(p, k, north, east)
    integral = cs[_S.integral]
    chi_unsat = (p.k_cross_track * y_e + p.k_integral * integral) / p.k_heading
    chi_max = p.max_approach_angle
    chi = min(max(chi_unsat, -chi_max), chi_max)
    psi_d = wrap_pi(pi_k - chi)
    u_unsat = (-p.k_heading * wrap_pi(y[_M.heading] - psi_d) - p.k_yaw_rate * y[_M.yaw_rate]
               - p.k_sway * y[_M.sway_speed])
    umax = p.max_command
    u = min(max(u_unsat, -umax), umax)
    if (u == u_unsat or y_e * u_unsat > 0.0) and (chi == chi_unsat or y_e * chi_unsat < 0.0):
        cs[_S.integral] = integral + y_e * dt
    out[_G.heading_reference] = psi_d
    out[_G.cross_track_error] = y_e
    out[_G.along_track_distance] = x_e
    out[_G.waypoint_index] = p.n_waypoints - 1.0 if cs[_S.complete] != 0.0 else float(k)
    return u


@njit(cache=True)
def lq_cross_track_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    cmd[_C.rudder_command] = lq_cross_track_law(dt, y, p, cs, cmd[_FIRST_OUTPUT:])


LQ_CROSS_TRACK = Controller(
    name="lq-cross-track",
    description="LQ-integral cross-track controller: state feedback on the cross-track error, "
    "its integral, the heading relative to the route, yaw rate and sway (a route, [guidance])",
    params_type=LQCrossTrackParams,
    state_labels=tuple(f"guidance_{s}" for s in GUIDANCE_STATES),
    reference_labels=(),
    reference_units=(),
    command_labels=COMMANDS,
    command_units=("rad",),
    state_units=("-", "m·s", "-"),
    init=lq_cross_track_init,
    step=lq_cross_track_step,
    measurement_labels=MEASUREMENTS,
    output_labels=GUIDANCE_OUTPUTS,
    output_units=GUIDANCE_OUTPUT_UNITS,
)

#: ``lq-cross-track`` holding a constant propeller rps (:func:`~seahelm.control.held_rps.
#: with_held_rps`; its recorded outputs follow the rps), for models with rudder and propeller
#: inputs (MMG).
LQ_CROSS_TRACK_RPS = with_held_rps(LQ_CROSS_TRACK, description=(
    "LQ-integral cross-track controller (as 'lq-cross-track') that also holds a constant "
    "propeller rps, for models with rudder and propeller inputs (MMG)"))
#: As :class:`LQCrossTrackParams`, and the propeller rps it holds.
LQCrossTrackRpsParams = LQ_CROSS_TRACK_RPS.params_type


# ------------------------------------------------------------------------------------------
# the design
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class LQCrossTrackDesign:
    """An LQ(-integral) cross-track design.

    Attributes
    ----------
    gains : dict of str to float
        ``k_integral``, ``k_cross_track``, ``k_heading``, ``k_yaw_rate``, ``k_sway`` (the
        controller's parameter names).
    gain : numpy.ndarray
        K, the state-feedback row on :attr:`states`.
    states : tuple of str
        ``cross_track_error_integral`` (with integral action), ``cross_track_error``,
        ``heading_error``, then the steering states.
    A, b : numpy.ndarray
        The augmented design model ẋ = A x + b δ.
    Q, R : numpy.ndarray
        The weights.
    poles : numpy.ndarray
        Eigenvalues of A − b K [1/s].
    gain_margin, phase_margin, crossover : float
        Of the loop broken at the rudder, K (sI − A)⁻¹ b: [-], [rad], [rad/s].
    speed : float
        U [m/s] of the design.
    max_command : float
        The controller's rudder saturation [rad].
    """

    gains: dict[str, float]
    gain: np.ndarray
    states: tuple[str, ...]
    A: np.ndarray
    b: np.ndarray
    Q: np.ndarray
    R: np.ndarray
    poles: np.ndarray
    gain_margin: float
    phase_margin: float
    crossover: float
    speed: float
    max_command: float

    def params(self, waypoints: Any, *, propeller_rps: float | None = None,
               **values: Any) -> LQCrossTrackParams:
        """The controller's parameters for a route.

        Parameters
        ----------
        waypoints : array_like, shape (n, 2)
            Waypoints (north, east) [m] (:func:`~seahelm.control.path_following.route_params`).
        propeller_rps : float, optional
            The rps to hold: gives :class:`LQCrossTrackRpsParams` (``lq-cross-track-rps``).
        **values
            Other parameters (``acceptance_radius``, ``max_approach_angle``).

        Returns
        -------
        LQCrossTrackParams or LQCrossTrackRpsParams
        """
        cls = LQCrossTrackParams if propeller_rps is None else LQCrossTrackRpsParams
        extra = {} if propeller_rps is None else {"propeller_rps": propeller_rps}
        return route_params(waypoints, params_type=cls, **self.gains,
                            max_command=self.max_command, **extra, **values)


def lq_cross_track(A: Any, b: Any, states: Sequence[str], speed: float, *,
                   max_cross_track: float, max_heading_error: float = math.radians(20.0),
                   max_integral: float | None = None, max_yaw_rate: float | None = None,
                   max_rudder: float = math.radians(35.0), max_command: float | None = None,
                   integral: bool = True) -> LQCrossTrackDesign:
    """LQ(-integral) cross-track gains from a linear steering block (module docstring).

    Parameters
    ----------
    A : array_like, shape (n, n)
        The steering block (states ``states``: ``yaw_rate`` and optionally ``sway_speed``)
        at the speed U [1/s], e.g. ``linearize(ship).select(states=[...])``.
    b : array_like, shape (n,)
        Its rudder column.
    states : sequence of str
        Names of the block's states.
    speed : float
        U [m/s]: the surge speed at the operating point, ∂ẏ_e/∂ψ̃ of the kinematics
        ẏ_e = u sin ψ̃ + v cos ψ̃ (the linearised model's ∂(east)'/∂(heading) on a route
        due north).
    max_cross_track : float
        Bryson weight: allowed cross-track error [m].
    max_heading_error : float, optional
        Allowed heading error relative to the path [rad] (default 20°).
    max_integral : float, optional
        Allowed ∫y_e dt [m·s] (default 100 s × ``max_cross_track``).
    max_yaw_rate : float, optional
        Allowed yaw rate [rad/s] (default: not weighted).
    max_rudder : float, optional
        Allowed rudder angle [rad] (ρ = 1/δ²; default 35°).
    max_command : float, optional
        The controller's saturation (default ``max_rudder``).
    integral : bool, optional
        With the integral state (default True; False: LQ on y_e, ψ̃ and the block only).

    Returns
    -------
    LQCrossTrackDesign

    Raises
    ------
    ParameterError
        For a state that is not ``yaw_rate``/``sway_speed``, non-positive weights or speed,
        or an uncontrollable augmented pair.
    """
    from scipy.linalg import solve_continuous_are

    A = np.atleast_2d(np.asarray(A, dtype=float))
    b = np.atleast_1d(np.asarray(b, dtype=float))
    states = tuple(states)
    if [s for s in states if s not in ("yaw_rate", "sway_speed")] or "yaw_rate" not in states:
        raise ParameterError(f"must be yaw_rate and optionally sway_speed, got {states}",
                             field="states")
    n = len(states)
    if A.shape != (n, n) or b.shape != (n,):
        raise ParameterError(f"A must be ({n}, {n}) and b ({n},) for states {states}, got "
                             f"{A.shape} and {b.shape}", field="A")
    check_positive("speed", speed, "m/s")
    check_positive("max_cross_track", max_cross_track, "m")
    check_positive("max_heading_error", max_heading_error, "rad")
    check_positive("max_rudder", max_rudder, "rad")
    m = 3 if integral else 2  # (∫y_e,) y_e, ψ̃
    o = m - 2  # index of y_e
    Aa = np.zeros((m + n, m + n))
    if integral:
        Aa[0, o] = 1.0
    Aa[o, o + 1] = speed  # ẏ_e = U ψ̃ + v
    if "sway_speed" in states:
        Aa[o, m + states.index("sway_speed")] = 1.0
    Aa[o + 1, m + states.index("yaw_rate")] = 1.0  # ψ̃' = r
    Aa[m:, m:] = A
    ba = np.concatenate([np.zeros(m), b])
    ctrb = np.column_stack([np.linalg.matrix_power(Aa, k) @ ba for k in range(m + n)])
    sv = np.linalg.svd(ctrb / np.maximum(np.abs(ctrb).max(axis=0), 1e-300), compute_uv=False)
    if not sv[-1] > 1e-12 * sv[0]:
        raise ParameterError(
            "the rudder does not control this model (the augmented pair (A, b) is "
            f"uncontrollable: controllability singular values {sv[0]:.3g} ... {sv[-1]:.3g})",
            field="A")
    q = np.zeros(m + n)
    if integral:
        q[0] = 1.0 / (max_integral if max_integral is not None
                      else 100.0 * max_cross_track) ** 2
    q[o] = 1.0 / max_cross_track ** 2
    q[o + 1] = 1.0 / max_heading_error ** 2
    if max_yaw_rate is not None:
        check_positive("max_yaw_rate", max_yaw_rate, "rad/s")
        q[m + states.index("yaw_rate")] = 1.0 / max_yaw_rate ** 2
    R = np.array([[1.0 / max_rudder ** 2]])
    try:
        P = solve_continuous_are(Aa, ba[:, None], np.diag(q), R)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ParameterError(f"has no stabilising LQ solution ({exc})", field="A") from None
    k = (ba @ P) / R[0, 0]
    poles = np.linalg.eigvals(Aa - np.outer(ba, k))
    gm, pm, wc = loop_margins(lambda w: state_space_response(Aa, ba, k, w))
    cmd = max_command or max_rudder
    _warn_margins(gm, pm, "the LQ cross-track design")
    gains = {"k_integral": float(k[0]) if integral else 0.0,
             "k_cross_track": float(k[o]), "k_heading": float(k[o + 1]),
             "k_yaw_rate": float(k[m + states.index("yaw_rate")]),
             "k_sway": float(k[m + states.index("sway_speed")]) if "sway_speed" in states
             else 0.0}
    if not gains["k_heading"] > 0:
        raise ParameterError(f"gives a heading gain {gains['k_heading']:.4g} <= 0 (the law "
                             "needs k_ψ > 0)", field="A")
    names = (("cross_track_error_integral",) if integral else ()) + (
        "cross_track_error", "heading_error") + states
    return LQCrossTrackDesign(gains=gains, gain=k, states=names, A=Aa, b=ba, Q=np.diag(q), R=R,
                              poles=poles, gain_margin=gm, phase_margin=pm, crossover=wc,
                              speed=float(speed), max_command=float(cmd))
