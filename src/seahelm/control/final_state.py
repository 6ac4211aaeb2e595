"""Final-state method (метод конечного состояния, МКС) controllers (Shushlyapin et al., 2017).

The general method (eq. (12)-(15)) for any control-affine system, numpy and batched, with its
own closed loop for tests and small studies, is :mod:`seahelm.control.final_state_general`
(:class:`~seahelm.control.final_state_general.FinalStateController`).

Compiled controllers for the catamaran (:mod:`seahelm.vessels.catamaran`, engine plug-ins)
    With the criterion J = z_3 = ω (eq. (16)), G = W_37 and eq. (15) gives (eq. (19)-(21))::

        W_37 = h L T_v cos δ / J_ω
        eq. (20):  u = (ω* − (ω + Φ_3(z) h)) / (T_u W_37)      ("fsm-yaw-rate")
        eq. (21):  u = (ω* − ω) / (T_u W_37)                    ("fsm-yaw-rate-simple")

    u = dδ/dt is the thruster rate. In eq. (21) only the product T_u·h matters (eq. (21) is an
    integral yaw-rate controller with the gain J_ω/(T_u h L T_v cos δ) scheduled on δ).
    For the listing's parameters (``shushlyapin2017-listing``), found by simulation and by
    :func:`closed_loop_eigenvalues`:

    * T_u·h = 0.01 s² reproduces the paper's figures: ω* = 0.08 rad/s with δ = 86.2° and a
      96.9 m turning circle; ω* = 0.00072 rad/s with δ = 0.601°, slowest closed-loop
      eigenvalue −0.065 1/s (τ ≈ 15 s), settling to 5 % in ≈ 50 s from rest.
    * Sensitivity (slowest real part at ω* = 0.00072 rad/s): −0.098, −0.065, −0.039,
      −0.017 1/s at T_u·h = 0.005, 0.01, 0.02, 0.05 s², i.e. 5 % settling ≈ 3/|λ| ≈ 31, 46,
      78, 170 s: "about 50 s" pins T_u·h to roughly 0.008-0.012 s². The turn at 0.08 rad/s
      is least damped near the stability bound (−0.001 1/s at 0.0065 s², −0.065 at 0.01).
    * The loop interacts with the listing's lightly damped 14.5 rad/s yaw-sway mode. With
      continuous control (the MathCAD listing evaluates u inside the right-hand side) it is
      unstable below T_u·h = 0.0065 s² at the 0.08 rad/s turn (δ ≈ 86°, the gain grows as
      1/cos δ) — the paper's "about 0.006" — and has no practical bound near δ = 0. A sampled
      controller (period T_s, zero-order hold) needs more: 0.0072 s² at the 0.08 rad/s turn
      with T_s = 0.0005 s, 0.0093 at 0.002 s, 0.018 at 0.01 s; near δ = 0 about
      0.99·T_s s²/s. The examples therefore run the controller every 0.001 s.
    * For the physically consistent set (J_ω 1220 times larger) the same behaviour needs
      T_u·h ≈ 12 s², and 0.1 s sampling is fine.

    Heading, eq. (17) ("fsm-heading"): to turn from K_0 to K* at the yaw rate ω*, the
    yaw-rate reference is ω* sign(ΔK) until t* = t_0 + |ΔK|/ω* and 0 afterwards
    (ΔK = K* − K_0 wrapped to [−π, π)). With ``ramp_time`` T_r > 0 the reference is instead a
    trapezoid with ramps of length T_r and the same area |ΔK| (the smooth variant the paper
    suggests, "soft start"): no jump at either end. A change of K* restarts the program from
    the current heading.

    Thruster drive, eq. (22)-(23): with ``servo_command`` = 1 the command is not u but the
    drive input v = δ/k_δ + (T_δ/k_δ) u, so that the first-order drive
    dδ/dt = (−δ + k_δ v)/T_δ (model ``catamaran-servo``) turns the thrusters at exactly the
    rate u of eq. (20)/(21). The controllers command ``thruster_rate_command`` (the input
    ``thruster_rate`` of model ``catamaran``, with the ``direct`` actuator); their ``-drive``
    variants (:data:`FSM_YAW_RATE_DRIVE`, ...) are the same laws commanding
    ``thruster_command``, the drive input of ``catamaran-servo``.

Guard (not in the paper)
    W_37 vanishes at δ = ±90°, where eq. (19)-(21) divide by zero. The controllers use
    cos δ clipped below at cos(``max_angle``) (default 89°) and stop turning the thrusters
    further out once |δ| ≥ ``max_angle``: a yaw-rate reference beyond the largest reachable
    one then holds δ at ±``max_angle`` instead of diverging.

References
----------
Shushlyapin, E. A., Karapetyan, V. A., Bezuglaya, A. E., Afonina, A. A. (2017), SPIIRAS
Proceedings 4(53), eq. (12)-(23). Shushlyapin, E. A. (2012). Control of nonlinear systems based
on the prediction of the final state of the uncontrolled motion. Sevastopol: SevNTU.
Alekseev, V. M. (1961). An estimate for the perturbations of the solutions of ordinary
differential equations. Vestnik MGU, Ser. 1, 2, 28-36.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from .._validate import check_positive
from ..errors import ParameterError
from ..parameters import param, signal_indices
from ..vessels.catamaran import STATES as CATAMARAN_STATES
from ..vessels.catamaran import CatamaranParams, catamaran_yaw_acceleration
from .base import Controller, wrap_pi

__all__ = [
    "FinalStateYawRateParams",
    "FinalStateHeadingParams",
    "FSM_YAW_RATE",
    "FSM_YAW_RATE_SIMPLE",
    "FSM_HEADING",
    "FSM_YAW_RATE_DRIVE",
    "FSM_YAW_RATE_SIMPLE_DRIVE",
    "FSM_HEADING_DRIVE",
    "yaw_rate_params",
    "heading_params",
    "heading_program",
    "closed_loop_eigenvalues",
]


# ------------------------------------------------------------------------------------------
# the paper's compiled controllers (engine plug-ins)
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class FinalStateYawRateParams(CatamaranParams):
    """Final-state yaw-rate controller, eq. (20)/(21): the controller's model of the ship
    (the :class:`~seahelm.vessels.catamaran.CatamaranParams` fields, defaults the listing)
    plus the method's T_u and h, the cos δ guard and the thruster-drive transform eq. (23).

    Build it from a vessel parameter set with :func:`yaw_rate_params`.
    """

    time_constant: float = param(1.0, unit="s", symbol="T_u", low=0.0, low_inclusive=False,
                                 doc="time constant of dJ/dt = (J* − J)/T_u")
    step: float = param(0.01, unit="s", symbol="h", low=0.0, low_inclusive=False,
                        doc="prediction step h of eq. (15) (only T_u·h matters in eq. (21))")
    max_angle: float = param(math.radians(89.0), unit="rad", symbol="δ_max", low=0.0,
                             low_inclusive=False, high=math.pi / 2,
                             doc="guard: cos δ ≥ cos δ_max in W_37, no turning beyond ±δ_max")
    servo_command: float = param(0.0, unit="-", symbol="", low=0.0, high=1.0,
                                 doc="1: output the drive input v of eq. (23); 0: u = dδ/dt")
    servo_time_constant: float = param(1.0, unit="s", symbol="T_δ", low=0.0,
                                       low_inclusive=False, doc="drive time constant, eq. (22)")
    servo_gain: float = param(1.0, unit="-", symbol="k_δ", low=0.0, low_inclusive=False,
                              doc="drive gain, eq. (22)")

    def validate(self) -> None:
        super().validate()
        if self.servo_command not in (0.0, 1.0):
            raise ParameterError(
                f"`servo_command` must be 0 or 1 [-], got {self.servo_command!r}"
            )
        if self.max_angle >= math.pi / 2:
            raise ParameterError(
                f"`max_angle` must be < π/2 [rad] (W_37 ∝ cos δ vanishes at 90°), "
                f"got {self.max_angle!r}"
            )


@dataclass(frozen=True, kw_only=True)
class FinalStateHeadingParams(FinalStateYawRateParams):
    """Heading program eq. (17) on top of the yaw-rate controller (eq. (21), or eq. (20))."""

    turn_rate: float = param(0.0022, unit="rad/s", symbol="ω*", low=0.0, low_inclusive=False,
                             doc="yaw rate of the turn")
    ramp_time: float = param(0.0, unit="s", symbol="T_r", low=0.0,
                             doc="0: eq. (17) (switch ω* → 0 at t*); > 0: trapezoid ramps")
    full_prediction: float = param(0.0, unit="-", symbol="", low=0.0, high=1.0,
                                   doc="0: yaw-rate law eq. (21); 1: eq. (20)")

    def validate(self) -> None:
        super().validate()
        if self.full_prediction not in (0.0, 1.0):
            raise ParameterError(
                f"`full_prediction` must be 0 or 1 [-], got {self.full_prediction!r}"
            )


def _with_vessel(cls: type, vessel: CatamaranParams | None, kw: dict[str, Any]) -> Any:
    """``cls`` built from the vessel's fields (and its servo's, if any) plus ``kw``."""
    vessel = CatamaranParams() if vessel is None else vessel
    base = {n: getattr(vessel, n) for n in CatamaranParams.field_names()}
    if hasattr(vessel, "servo_time_constant"):
        kw.setdefault("servo_time_constant", vessel.servo_time_constant)
        kw.setdefault("servo_gain", vessel.servo_gain)
    return cls(**base, **kw)


def yaw_rate_params(vessel: CatamaranParams | None = None, **kw: Any) -> FinalStateYawRateParams:
    """Controller parameters whose model of the ship is ``vessel`` (default: the listing).

    ``kw`` sets the controller's own fields (``time_constant``, ``step``, ``max_angle``,
    ``servo_command``, ``servo_time_constant``, ``servo_gain``); given a
    :class:`~seahelm.vessels.catamaran.CatamaranServoParams`, the drive constants are taken
    from it.

    Parameters
    ----------
    vessel : CatamaranParams or CatamaranServoParams, optional
        The controller's model of the ship (default: ``CatamaranParams()``).
    **kw
        Fields of :class:`FinalStateYawRateParams` not taken from ``vessel``.

    Returns
    -------
    FinalStateYawRateParams
    """
    return _with_vessel(FinalStateYawRateParams, vessel, kw)


def heading_params(vessel: CatamaranParams | None = None, **kw: Any) -> FinalStateHeadingParams:
    """Heading-controller parameters (see :func:`yaw_rate_params`; adds ``turn_rate``,
    ``ramp_time``, ``full_prediction``).

    Parameters
    ----------
    vessel : CatamaranParams or CatamaranServoParams, optional
        The controller's model of the ship (default: ``CatamaranParams()``).
    **kw
        Fields of :class:`FinalStateHeadingParams` not taken from ``vessel``.

    Returns
    -------
    FinalStateHeadingParams
    """
    return _with_vessel(FinalStateHeadingParams, vessel, kw)


def closed_loop_eigenvalues(vessel: CatamaranParams, yaw_rate: float, tu_h: float,
                            sample_time: float | None = None) -> np.ndarray:
    """Eigenvalues [1/s] of eq. (21)'s loop linearised about the steady turn at ``yaw_rate``.

    The loop (V_x, V_y, ω, δ) with dδ/dt = (ω* − ω) J_ω/(T_u h L T_v cos δ). With
    ``sample_time`` T_s the control is held over T_s (the engine's zero-order hold) and the
    returned values are the discrete eigenvalues mapped back by log(λ)/T_s. The loop is stable
    when every real part is negative; the slowest one gives the settling time.

    Parameters
    ----------
    vessel : CatamaranParams
        Ship parameters.
    yaw_rate : float
        Yaw rate ω of the steady turn [rad/s].
    tu_h : float
        Product T_u·h of the controller time constant T_u [s] and prediction step h [s]
        of eq. (15) [s²] (> 0).
    sample_time : float, optional
        Control sample period T_s [s] (default None: continuous control).

    Returns
    -------
    numpy.ndarray, shape (4,)
        Eigenvalues [1/s] (complex).

    Raises
    ------
    ParameterError
        Non-positive ``tu_h`` or ``sample_time``.
    """
    from scipy.linalg import expm

    from ..vessels.catamaran import jacobian, steady_turn

    check_positive("tu_h", tu_h, "s²")
    vx, vy, d = steady_turn(vessel, yaw_rate)
    A7 = jacobian(np.array([vx, vy, yaw_rate, 0.0, 0.0, 0.0, d]), vessel)
    idx = [0, 1, 2, 6]
    A = A7[np.ix_(idx, idx)]
    k = vessel.yaw_moment_of_inertia / (tu_h * vessel.length * vessel.thrust * math.cos(d))
    if sample_time is None:
        Acl = A.copy()
        Acl[3, 2] -= k
        return np.linalg.eigvals(Acl)
    check_positive("sample_time", sample_time, "s")
    M = np.zeros((5, 5))
    M[:4, :4] = A
    M[3, 4] = 1.0
    E = expm(M * sample_time)
    Ad, Bd = E[:4, :4], E[:4, 4]
    Acl = Ad - k * np.outer(Bd, np.eye(4)[2])
    return np.log(np.linalg.eigvals(Acl).astype(complex)) / sample_time


#: The closed-loop state z starts with the catamaran's states (the controllers read the whole z).
_Z = signal_indices(CATAMARAN_STATES)


@njit(cache=True)
def fsm_thruster_rate(z, wref, p, full, dt):  # pragma: no cover - compiled
    """u = dδ/dt of eq. (20) (``full``) or eq. (21), with the cos δ guard.

    ``dt`` is the controller's sample period: the guard also keeps the held rate from carrying
    δ past ±max_angle within one period (dt ≤ 0 disables that part). ``p`` is a
    :class:`FinalStateYawRateParams` record (or a subclass's).
    """
    L = p.length
    tv = p.thrust
    jw = (1.0 + p.k66) * p.yaw_inertia
    tu = p.time_constant
    h = p.step
    amax = p.max_angle
    d = z[_Z.thruster_angle]
    c = math.cos(d)
    cmin = math.cos(amax)
    if c < cmin:
        c = cmin
    w37 = h * L * tv * c / jw
    zbar = z[_Z.yaw_rate]
    if full:
        zbar += catamaran_yaw_acceleration(z, p) * h
    u = (wref - zbar) / (tu * w37)
    if u > 0.0:
        if d >= amax:
            u = 0.0
        elif dt > 0.0 and d + u * dt > amax:
            u = (amax - d) / dt
    elif u < 0.0:
        if d <= -amax:
            u = 0.0
        elif dt > 0.0 and d + u * dt < -amax:
            u = (-amax - d) / dt
    return u


@njit(cache=True)
def fsm_command(z, u, p):  # pragma: no cover - compiled
    """The command: u itself, or the drive input v = δ/k_δ + (T_δ/k_δ) u of eq. (23)."""
    if p.servo_command != 0.0:
        return (z[_Z.thruster_angle] + p.servo_time_constant * u) / p.servo_gain
    return u


_YR_REFERENCES: tuple[str, ...] = ("yaw_rate",)
_YR_R = signal_indices(_YR_REFERENCES)
_C = signal_indices(("command",))  # the one command, whatever it is named (see below)


@njit(cache=True)
def fsm_yaw_rate_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    pass


@njit(cache=True)
def fsm_yaw_rate_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    cmd[_C.command] = fsm_command(z, fsm_thruster_rate(z, ref[_YR_R.yaw_rate], p, True, dt), p)


@njit(cache=True)
def fsm_yaw_rate_simple_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    cmd[_C.command] = fsm_command(z, fsm_thruster_rate(z, ref[_YR_R.yaw_rate], p, False, dt), p)


@njit(cache=True)
def heading_program_rate(tau, dk, wmax, ramp):  # pragma: no cover - compiled
    """Yaw-rate reference of the heading program τ = t − t_0 after its start, eq. (17).

    ``dk`` heading change [rad] (signed), ``wmax`` ω* > 0, ``ramp`` T_r ≥ 0 (0: eq. (17)).
    """
    s = 1.0 if dk >= 0.0 else -1.0
    adk = abs(dk)
    if ramp <= 0.0:
        if tau < adk / wmax:
            return s * wmax
        return 0.0
    wp = min(wmax, adk / ramp)
    if wp <= 0.0:
        return 0.0
    total = adk / wp + ramp
    if tau < 0.0 or tau >= total:
        return 0.0
    if tau < ramp:
        return s * wp * tau / ramp
    if tau > total - ramp:
        return s * wp * (total - tau) / ramp
    return s * wp


_H_REFERENCES: tuple[str, ...] = ("heading",)
_H_STATES: tuple[str, ...] = ("program_target", "program_start_time", "program_heading_change",
                              "yaw_rate_reference")
_H_R = signal_indices(_H_REFERENCES)
_H_S = signal_indices(_H_STATES)


@njit(cache=True)
def fsm_heading_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    cs[_H_S.program_target] = ref[_H_R.heading]  # K* of the running program
    cs[_H_S.program_start_time] = 0.0  # t_0
    cs[_H_S.program_heading_change] = wrap_pi(ref[_H_R.heading] - z[_Z.heading])  # ΔK
    cs[_H_S.yaw_rate_reference] = heading_program_rate(0.0, cs[_H_S.program_heading_change],
                                                       p.turn_rate, p.ramp_time)


@njit(cache=True)
def fsm_heading_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    if ref[_H_R.heading] != cs[_H_S.program_target]:
        # new wanted course: restart the program from the current heading
        cs[_H_S.program_target] = ref[_H_R.heading]
        cs[_H_S.program_start_time] = t
        cs[_H_S.program_heading_change] = wrap_pi(ref[_H_R.heading] - z[_Z.heading])
    wref = heading_program_rate(t - cs[_H_S.program_start_time],
                                cs[_H_S.program_heading_change], p.turn_rate, p.ramp_time)
    cs[_H_S.yaw_rate_reference] = wref
    cmd[_C.command] = fsm_command(
        z, fsm_thruster_rate(z, wref, p, p.full_prediction != 0.0, dt), p)


def heading_program(t: Any, heading_change: float, turn_rate: float, ramp_time: float = 0.0
                    ) -> np.ndarray:
    """The yaw-rate reference ω*(t) of the heading program (eq. (17), or ramped) at times ``t``
    [s] after its start (numpy; the compiled controller uses the same function).

    Parameters
    ----------
    t : array_like
        Times since the start of the program [s].
    heading_change : float
        Total heading change Δψ [rad] (sign gives the turn direction).
    turn_rate : float
        Magnitude of the yaw rate of the turn [rad/s] (> 0).
    ramp_time : float, optional
        Duration of the yaw-rate ramps [s] (>= 0, default 0: eq. (17)).

    Returns
    -------
    numpy.ndarray
        ω*(t) [rad/s], shape of ``t``.
    """
    check_positive("turn_rate", turn_rate, "rad/s")
    if not ramp_time >= 0.0:
        raise ParameterError(f"`ramp_time` must be >= 0 [s], got {ramp_time!r}")
    t = np.asarray(t, dtype=float)
    out = np.array([heading_program_rate(float(s), float(heading_change), float(turn_rate),
                                         float(ramp_time)) for s in t.ravel()])
    return out.reshape(t.shape)


#: The command: the thruster rate u = dδ/dt of eq. (20)/(21) for the ``catamaran`` model with the
#: ``direct`` actuator; the ``*_DRIVE`` variants name it after the drive input v of eq. (22)
#: (``thruster_command``, the input of ``catamaran-servo``), for ``servo_command`` = 1.
_CMD = ("thruster_rate_command",)
_CMD_DRIVE = ("thruster_command",)

FSM_YAW_RATE = Controller(
    name="fsm-yaw-rate",
    description="final-state-method yaw-rate control of the catamaran, eq. (20) "
    "(Shushlyapin et al., 2017)",
    params_type=FinalStateYawRateParams,
    state_labels=(),
    reference_labels=_YR_REFERENCES,
    reference_units=("rad/s",),
    command_labels=_CMD,
    command_units=("rad/s",),
    state_units=(),
    init=fsm_yaw_rate_init,
    step=fsm_yaw_rate_step,
)

FSM_YAW_RATE_SIMPLE = Controller(
    name="fsm-yaw-rate-simple",
    description="simplified final-state-method yaw-rate control, eq. (21): "
    "u = (ω* − ω)/(T_u W37) (Shushlyapin et al., 2017)",
    params_type=FinalStateYawRateParams,
    state_labels=(),
    reference_labels=_YR_REFERENCES,
    reference_units=("rad/s",),
    command_labels=_CMD,
    command_units=("rad/s",),
    state_units=(),
    init=fsm_yaw_rate_init,
    step=fsm_yaw_rate_simple_step,
)

FSM_HEADING = Controller(
    name="fsm-heading",
    description="heading program eq. (17) (or ramped) with final-state yaw-rate control "
    "eq. (21)/(20) (Shushlyapin et al., 2017)",
    params_type=FinalStateHeadingParams,
    state_labels=_H_STATES,
    reference_labels=_H_REFERENCES,
    reference_units=("rad",),
    command_labels=_CMD,
    command_units=("rad/s",),
    state_units=("rad", "s", "rad", "rad/s"),
    init=fsm_heading_init,
    step=fsm_heading_step,
)

FSM_YAW_RATE_DRIVE = dataclasses.replace(
    FSM_YAW_RATE, name="fsm-yaw-rate-drive", command_labels=_CMD_DRIVE,
    command_units=("rad",),
    description=FSM_YAW_RATE.description + ", commanding the thruster drive eq. (22)-(23)")
FSM_YAW_RATE_SIMPLE_DRIVE = dataclasses.replace(
    FSM_YAW_RATE_SIMPLE, name="fsm-yaw-rate-simple-drive", command_labels=_CMD_DRIVE,
    command_units=("rad",),
    description=FSM_YAW_RATE_SIMPLE.description + ", commanding the thruster drive eq. (22)-(23)")
FSM_HEADING_DRIVE = dataclasses.replace(
    FSM_HEADING, name="fsm-heading-drive", command_labels=_CMD_DRIVE,
    command_units=("rad",),
    description=FSM_HEADING.description + ", commanding the thruster drive eq. (22)-(23)")
