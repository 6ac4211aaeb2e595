"""DP controller: nonlinear PID with a reference model and wind feedforward, the constrained
thrust allocation at every control step, and the thrusters' shaft lag.

Per controller sample (period h), with the set-point η_ref = (x_N, y_E, ψ) (references
``north``, ``east``, ``heading``), the reference-model states η_d and the integral z (Fossen
2021, *Handbook of Marine Craft Hydrodynamics and Motion Control*, 2nd ed., §12.2.6, the
nonlinear PID for DP with pole placement; the supply-vessel DP example of Fossen's MSS and
PythonVehicleSimulator)::

    ẽ = η − η_d   (ψ̃ wrapped to [−π, π))
    K_p = Ω² M_d,  K_d = 2 Z Ω M_d − D_d,  K_i = (ω/10) K_p        (diagonal, per DOF)
    τ_c = −Rᵀ(ψ) K_p ẽ − K_d ν − Rᵀ(ψ) K_i z − τ_wind
    z ← z + h ẽ
    η_d ← η_d + h (η_ref − η_d) / T_ref,   T_ref = 5/ω                (first-order reference)

M_d, D_d are the diagonals of the design model's M and D (the vessel's, :func:`dp_pid_params`),
Ω = diag(ω_surge, ω_sway, ω_yaw), Z the relative dampings, and τ_wind the measured wind load
in body axes (references ``wind_force_x`` [N], ``wind_force_y`` [N], ``wind_moment_z`` [N·m]:
what a wind sensor and the vessel's wind model give; zero: no feedforward), cancelled by
feedforward (Fossen 2021, §12.2.7).

**Allocation, in the loop**: τ_c is allocated over the thrusters by the constrained,
minimum-power QP of :mod:`seahelm.control.dp_allocation` (thrust bounds, the azimuth disc as an
inscribed polygon, thrust-rate and azimuth-rate limits from the previous step, one forbidden
sector per azimuth by the fixed-azimuth linearisation, unmet demand as weighted slack), built
here in compiled code and solved by the compiled Goldfarb–Idnani method
(:func:`seahelm.numerics.qp._solve_one`) for every run at every control step; without the
active-set polish of the Python version, so a demand that is met is met to O(1/ρ) of itself.
The tests check this allocation against :meth:`ConstrainedAllocation.allocate` (which is
checked against Clarabel).

**Thrusters**: each thruster's normalised shaft speed s = n/n_max follows its command
s_c = sign(f_c) √(abs(f_c)/T_max) with the first-order lag ṡ = (s_c − s)/T_n (forward Euler at
the control step; T_n = 0: none), and delivers f = T_max s abs(s) (thrust ∝ n abs(n),
Fossen 2021 §11.2); the commands are the delivered generalized force B f (``thrust_surge``,
``thrust_sway``, ``thrust_yaw``: the inputs of the ``dp-3dof`` model). Azimuths turn to the
commanded direction within the step (the allocation limits the turning rate).

Recorded outputs: the demand τ_c (``demand_surge`` …), what the allocation leaves unmet
(``unmet_surge`` …) and each thruster's delivered thrust (``thrust_1`` … ``thrust_8``).
"""

from __future__ import annotations

import collections
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import int64, njit

from .._codegen import called_not_inlined
from ..errors import ParameterError
from ..numerics.qp_inplace import solve_qp_rows, workspace_size
from ..parameters import Params, param, signal_indices
from .base import Controller, wrap_pi

__all__ = ["DpPidParams", "DP_PID", "MAX_DP_THRUSTERS", "dp_pid_params", "allocate_step",
           "state_indices"]

#: Thrusters a DP controller takes (the first ``thruster_count`` of its vectors).
MAX_DP_THRUSTERS = 8
_N = MAX_DP_THRUSTERS
_Z = (0.0,) * _N
_NV = 2 * _N                       # QP variables at most (every thruster an azimuth)
_MR = _N * (64 + 6)                # QP rows at most (64-gon, sector, rate box)
#: Floats of the allocation's workspace (a slice of the controller's state: the engine's
#: loop allocates nothing).
WORKSPACE = _NV * _NV + 5 * _NV + workspace_size(_NV, _MR)

MEASUREMENTS: tuple[str, ...] = ("north", "east", "heading", "surge_speed", "sway_speed",
                                 "yaw_rate")
REFERENCES: tuple[str, ...] = ("north", "east", "heading", "wind_force_x", "wind_force_y",
                               "wind_moment_z")
COMMANDS: tuple[str, ...] = ("thrust_surge", "thrust_sway", "thrust_yaw")
#: The passive observer's states (:mod:`seahelm.control.dp_observer`; unused by ``dp-pid``).
OBSERVER_STATES: tuple[str, ...] = (
    "wave_state_north", "wave_north", "wave_state_east", "wave_east", "wave_state_heading",
    "wave_heading", "estimated_north", "estimated_east", "estimated_heading", "bias_x",
    "bias_y", "bias_n", "estimated_surge_speed", "estimated_sway_speed", "estimated_yaw_rate",
    "applied_surge", "applied_sway", "applied_yaw")
STATES: tuple[str, ...] = (("integral_north", "integral_east", "integral_heading",
                            "desired_north", "desired_east", "desired_heading")
                           + tuple(f"force_x_{k + 1}" for k in range(_N))
                           + tuple(f"force_y_{k + 1}" for k in range(_N))
                           + tuple(f"shaft_{k + 1}" for k in range(_N))
                           + tuple(f"azimuth_{k + 1}" for k in range(_N))
                           + OBSERVER_STATES
                           + tuple(f"scratch_{k + 1}" for k in range(2 * _N + 3))
                           + tuple(f"workspace_{k + 1}" for k in range(WORKSPACE)))
OUTPUTS: tuple[str, ...] = (("demand_surge", "demand_sway", "demand_yaw", "unmet_surge",
                             "unmet_sway", "unmet_yaw")
                            + tuple(f"thrust_{k + 1}" for k in range(_N)))



def state_indices(names: tuple[str, ...]) -> Any:
    """Named positions in :data:`STATES` of only the states ``names`` (``S.desired_north``).

    Compiled code reads the states it names through these; the vectors (forces, shafts,
    azimuths, scratch, the allocation's workspace) are read by offset. Not
    ``signal_indices(STATES)``: numba builds a global named tuple whole, one LLVM
    ``insertvalue`` per field, wherever a field of it is read, and the 5,153 fields of all the
    states made most of the DP loop's IR (see :func:`seahelm.simulation.inlining.
    _slim_index_tuples`, which the loop's copies then needed and these do not).

    Parameters
    ----------
    names : tuple of str
        States of :data:`STATES`.

    Returns
    -------
    collections.namedtuple
        ``S.<name> == STATES.index(name)`` for every name.
    """
    return collections.namedtuple("States", names)(*(STATES.index(n) for n in names))


_M = signal_indices(MEASUREMENTS)
_R = signal_indices(REFERENCES)
_C = signal_indices(COMMANDS)
#: The states the control law reads by name.
_S = state_indices(("integral_north", "integral_east", "integral_heading", "desired_north",
                    "desired_east", "desired_heading"))
_O = signal_indices(OUTPUTS)
_FX0 = STATES.index("force_x_1")
_FY0 = STATES.index("force_y_1")
_SH0 = STATES.index("shaft_1")
_AZ0 = STATES.index("azimuth_1")
_TH0 = len(COMMANDS) + OUTPUTS.index("thrust_1")
_SC0 = STATES.index("scratch_1")
_WS0 = STATES.index("workspace_1")
_TWO_PI = 2.0 * math.pi


def _vec(doc, unit, default=_Z, low=-math.inf):
    return param(default, unit=unit, size=_N, doc=doc, low=low)


@dataclass(frozen=True, kw_only=True)
class DpPidParams(Params):
    """DP controller parameters (defaults: Fossen's supply vessel, the catalog's ``supply``;
    :func:`dp_pid_params` fills them from any ship with thrusters)."""

    mass_surge: float = param(6764400.0, unit="kg", symbol="M_11", low=0.0,
                              low_inclusive=False, doc="design model: M_11")
    mass_sway: float = param(11341200.0, unit="kg", symbol="M_22", low=0.0,
                             low_inclusive=False, doc="design model: M_22")
    inertia_yaw: float = param(4452378192.0, unit="kg·m²", symbol="M_33", low=0.0,
                               low_inclusive=False, doc="design model: M_33")
    damping_surge: float = param(77071.05342208935, unit="kg/s", symbol="D_11", low=0.0,
                                 doc="design model: D_11")
    damping_sway: float = param(254678.92792830087, unit="kg/s", symbol="D_22", low=0.0,
                                doc="design model: D_22")
    damping_yaw: float = param(385007267.6231961, unit="kg·m²/s", symbol="D_33", low=0.0,
                               doc="design model: D_33")
    frequency_surge: float = param(0.1, unit="rad/s", symbol="ω_1", low=0.0,
                                   low_inclusive=False, doc="closed-loop natural frequency, surge")
    frequency_sway: float = param(0.1, unit="rad/s", symbol="ω_2", low=0.0,
                                  low_inclusive=False, doc="closed-loop natural frequency, sway")
    frequency_yaw: float = param(0.2, unit="rad/s", symbol="ω_3", low=0.0,
                                 low_inclusive=False, doc="closed-loop natural frequency, yaw")
    damping_ratio: float = param(1.0, unit="-", symbol="ζ", low=0.0, low_inclusive=False,
                                 doc="closed-loop relative damping (all DOF)")
    integral_ratio: float = param(0.1, unit="-", symbol="κ", low=0.0,
                                  doc="K_i = κ ω K_p (Fossen's 1/10)")
    reference_factor: float = param(5.0, unit="-", symbol="c_ref", low=0.0,
                                    doc="reference-model time constant T_ref = c_ref/ω "
                                        "(0: the set-point itself)")
    thruster_count: float = param(6.0, unit="-", low=1.0, high=_N,
                                  doc="thrusters used (the first of the vectors)")
    thruster_x: tuple = _vec("thruster position x", "m",
                             (30.0, 22.0, -22.0, -30.0, -30.0, -30.0, 0.0, 0.0))
    thruster_y: tuple = _vec("thruster position y", "m", (0.0, 0.0, 0.0, 0.0, 8.0, -8.0, 0, 0))
    thruster_direction: tuple = _vec("direction of a fixed thruster (an azimuth's initial)",
                                     "rad", (0.5 * math.pi,) * 4 + (0.0,) * 4)
    thruster_azimuthing: tuple = _vec("1: azimuth thruster", "-", _Z, 0.0)
    thruster_max_thrust: tuple = _vec("largest thrust", "N", (200000.0,) * 4
                                      + (798720.0,) * 2 + (1.0,) * 2, 0.0)
    thruster_min_thrust: tuple = _vec("smallest thrust of a fixed thruster (astern < 0)", "N",
                                      (-200000.0,) * 4 + (-798720.0,) * 2 + (-1.0,) * 2)
    thruster_max_rate: tuple = _vec("largest thrust rate (0: none)", "N/s", _Z, 0.0)
    thruster_max_azimuth_rate: tuple = _vec("largest azimuth rate (0: none)", "rad/s", _Z, 0.0)
    thruster_forbidden_start: tuple = _vec("start of the forbidden sector (ccw)", "rad")
    thruster_forbidden_end: tuple = _vec("end of the forbidden sector (= start: none)", "rad")
    thruster_weight: tuple = _vec("power weight w in Σ w (f/T_max)²", "-", (1.0,) * _N, 0.0)
    thruster_time_constant: float = param(0.0, unit="s", symbol="T_n", low=0.0,
                                          doc="shaft-speed lag (0: none)")
    slack_weight: float = param(1e6, unit="-", symbol="ρ", low=0.0, low_inclusive=False,
                                doc="weight of the unmet demand (scaled)")
    polygon_sides: float = param(32.0, unit="-", low=8.0, high=64.0,
                                 doc="sides of an azimuth's thrust polygon")


def dp_pid_params(ship: Any, **changes: Any) -> DpPidParams:
    """The DP controller's parameters for a ship with thrusters and a ``dp-3dof`` model.

    Parameters
    ----------
    ship : Ship
        A ship (:func:`seahelm.ships.get_ship`) with ``thrusters`` (≤ 8; at most one forbidden sector per azimuth) whose
        parameters have the diagonal of M and D (``m11`` … ``d33``).
    **changes
        Other :class:`DpPidParams` fields (gains: ``frequency_surge``, …).

    Returns
    -------
    DpPidParams

    Raises
    ------
    ParameterError
        More than 8 thrusters, more than one forbidden sector on a thruster, a model without
        the M and D diagonal.
    """
    sh = ship
    lay = getattr(sh, "thrusters", None)
    if lay is None:
        raise ParameterError(f"ship {sh.name!r} declares no thrusters", field="ship",
                             value=sh.name)
    n = lay.count
    if n > _N:
        raise ParameterError(f"has {n} thrusters; the DP controller takes at most {_N} [-]",
                             field="thrusters", unit="-", value=n)
    p = sh.params
    missing = [k for k in ("m11", "m22", "m33", "d11", "d22", "d33") if not hasattr(p, k)]
    if missing:
        raise ParameterError(f"model {sh.model.name!r} has no {', '.join(missing)} (the "
                             "design model's M and D)", field="ship", value=sh.name)
    start, end = [0.0] * _N, [0.0] * _N
    for i, secs in enumerate(lay.forbidden):
        if len(secs) > 1:
            raise ParameterError(f"of thruster {lay.names[i]!r}: the DP controller takes one "
                                 f"forbidden sector per thruster, got {len(secs)}",
                                 field="thrusters.forbidden_sectors", value=len(secs))
        if secs:
            start[i], end[i] = secs[0]

    def pad(values, fill):
        return tuple(float(v) for v in values) + (fill,) * (_N - n)

    def finite(values):
        return pad([v if math.isfinite(v) else 0.0 for v in values], 0.0)

    kw = dict(mass_surge=p.m11, mass_sway=p.m22, inertia_yaw=p.m33, damping_surge=p.d11,
              damping_sway=p.d22, damping_yaw=p.d33, thruster_count=float(n),
              thruster_x=pad(lay.x, 0.0), thruster_y=pad(lay.y, 0.0),
              thruster_direction=pad(lay.direction, 0.0),
              thruster_azimuthing=pad([1.0 if a else 0.0 for a in lay.azimuthing], 0.0),
              thruster_max_thrust=pad(lay.max_thrust, 1.0),
              thruster_min_thrust=pad([0.0 if a else m for a, m in zip(lay.azimuthing,
                                                                       lay.min_thrust)], -1.0),
              thruster_max_rate=finite(lay.max_thrust_rate),
              thruster_max_azimuth_rate=finite(lay.max_azimuth_rate),
              thruster_forbidden_start=tuple(start), thruster_forbidden_end=tuple(end))
    kw.update(changes)
    return DpPidParams(**kw)


@njit(cache=True)
def _layout_scale(p, n):  # pragma: no cover - compiled
    f_ref = 0.0
    l_ref = 1.0
    for i in range(n):
        f_ref += p.thruster_max_thrust[i]
        l_ref = max(l_ref, math.hypot(p.thruster_x[i], p.thruster_y[i]))
    return f_ref, l_ref


@njit(cache=True)
def _arc_wedge(p, i, a0, step):  # pragma: no cover - compiled
    """The admissible azimuth interval (lo, hi) and half-plane centre this step: the allowed
    arc holding a0 (one forbidden sector), cut to a0 ± step (ThrusterLayout's rule)."""
    s0 = p.thruster_forbidden_start[i] % _TWO_PI
    s1 = p.thruster_forbidden_end[i] % _TWO_PI
    lo, hi = a0 - math.pi, a0 + math.pi
    if s0 != s1:
        width = (s1 - s0) % _TWO_PI
        # the allowed arc is [s0 + width, s0 + 2π], unrolled to hold a0 if it can
        alo = s0 + width
        ahi = s0 + _TWO_PI
        shift = math.floor((a0 - alo) / _TWO_PI) * _TWO_PI
        alo += shift
        ahi += shift
        if a0 <= ahi:
            lo, hi = alo, ahi
        else:                                   # a0 forbidden: the nearer edge, zero width
            d_hi = a0 - ahi
            d_lo = alo + _TWO_PI - a0
            edge = ahi if d_hi <= d_lo else alo + _TWO_PI
            return edge, edge, edge
    if step > 0.0 and 2.0 * step < _TWO_PI:
        lo = max(lo, a0 - step)
        hi = min(hi, a0 + step)
    centre = min(max(a0, lo + 0.5 * math.pi), hi - 0.5 * math.pi)
    return lo, hi, centre


# (the counters typed int64 from the start: numba otherwise types the calls with them first
# as the literal 0 they start at, and compiled solve_qp_rows and _row for those too; cap, the
# constant _MR, likewise: solve_qp_rows was compiled for Literal[int](560) besides int64)
@called_not_inlined  # (once per controller interval: a call, not copied into the loop)
@njit(cache=True, locals={"nv": int64, "row": int64, "col": int64, "cap": int64})
def allocate_step(p, tau0, tau1, tau2, dt, prev_fx, prev_fy, prev_az, f_out, az_out,
                  unmet, ws):  # pragma: no cover - compiled
    """One constrained allocation (see the module): the thrusters' forces (f_out [N], signed
    along a fixed thruster's direction, the magnitude for an azimuth), directions az_out
    [rad] and the unmet demand; returns the QP's status. ``prev_*``: the previous forces
    (body x, y) [N] and azimuths [rad]; ``ws``: the workspace (:data:`WORKSPACE` floats)."""
    n = int(p.thruster_count)
    f_ref, l_ref = _layout_scale(p, n)
    sc0 = 1.0 / f_ref
    sc2 = 1.0 / (f_ref * l_ref)
    ms = int(p.polygon_sides)
    nv = 0
    for i in range(n):
        nv += 2 if p.thruster_azimuthing[i] > 0.5 else 1
    o_g, o_a, o_bs, o_x, o_q = 0, _NV * _NV, _NV * _NV + _NV, _NV * _NV + 4 * _NV, \
        _NV * _NV + 5 * _NV
    rows = ws[o_q:]
    cap = _MR
    for k in range(3 * nv):
        ws[o_bs + k] = 0.0
    col = 0
    row = 0
    inner = math.cos(math.pi / ms)
    for i in range(n):
        tmax = p.thruster_max_thrust[i]
        x, y = p.thruster_x[i], p.thruster_y[i]
        rate = p.thruster_max_rate[i]
        if p.thruster_azimuthing[i] < 0.5:
            d = p.thruster_direction[i]
            cx, cy = math.cos(d), math.sin(d)
            ws[o_bs + col] = cx * sc0 * tmax
            ws[o_bs + nv + col] = cy * sc0 * tmax
            ws[o_bs + 2 * nv + col] = (x * cy - y * cx) * sc2 * tmax
            ws[o_a + col] = p.thruster_weight[i]          # (the weights, for now)
            row = _row(rows, cap, row, col, 1.0, 0.0, p.thruster_min_thrust[i] / tmax)
            row = _row(rows, cap, row, col, -1.0, 0.0, -1.0)
            if rate > 0.0:
                fp = (prev_fx[i] * cx + prev_fy[i] * cy) / tmax
                st = rate * dt / tmax
                row = _row(rows, cap, row, col, 1.0, 0.0, fp - st)
                row = _row(rows, cap, row, col, -1.0, 0.0, -(fp + st))
            col += 1
            continue
        for j in range(2):
            cx, cy = (1.0, 0.0) if j == 0 else (0.0, 1.0)
            ws[o_bs + col + j] = cx * sc0 * tmax
            ws[o_bs + nv + col + j] = cy * sc0 * tmax
            ws[o_bs + 2 * nv + col + j] = (x * cy - y * cx) * sc2 * tmax
            ws[o_a + col + j] = p.thruster_weight[i]
        for k in range(ms):
            th = k * (_TWO_PI / ms)
            row = _row(rows, cap, row, col, -math.cos(th), -math.sin(th), -inner)
        a0 = prev_az[i] % _TWO_PI
        lo, hi, centre = _arc_wedge(p, i, a0, p.thruster_max_azimuth_rate[i] * dt)
        width = hi - lo
        if width < _TWO_PI - 1e-12:
            if width <= math.pi + 1e-12:
                row = _row(rows, cap, row, col, -math.sin(lo), math.cos(lo), 0.0)
                row = _row(rows, cap, row, col, math.sin(hi), -math.cos(hi), 0.0)
            else:
                row = _row(rows, cap, row, col, math.cos(centre), math.sin(centre), 0.0)
        if rate > 0.0:
            st = rate * dt / tmax / math.sqrt(2.0)
            for j in range(2):
                pf = (prev_fx[i] if j == 0 else prev_fy[i]) / tmax
                row = _row(rows, cap, row, col + j, 1.0, 0.0, pf - st)
                row = _row(rows, cap, row, col + j, -1.0, 0.0, -(pf + st))
        col += 2
    rho = p.slack_weight
    for r in range(nv):
        for k in range(nv):
            s = 0.0
            for d in range(3):
                s += ws[o_bs + d * nv + r] * ws[o_bs + d * nv + k]
            ws[o_g + r * nv + k] = rho * s
        ws[o_g + r * nv + r] += ws[o_a + r]
    t0, t1, t2 = tau0 * sc0, tau1 * sc0, tau2 * sc2
    for k in range(nv):
        ws[o_a + k] = -rho * (t0 * ws[o_bs + k] + t1 * ws[o_bs + nv + k]
                              + t2 * ws[o_bs + 2 * nv + k])
    u = ws[o_x:o_x + nv]
    status = solve_qp_rows(nv, row, cap, ws[o_g:o_g + nv * nv], ws[o_a:o_a + nv], rows, u, 1e-9,
                           10 * (nv + row) + 10)
    col = 0
    r0, r1, r2 = tau0, tau1, tau2
    for i in range(n):
        tmax = p.thruster_max_thrust[i]
        x, y = p.thruster_x[i], p.thruster_y[i]
        if p.thruster_azimuthing[i] < 0.5:
            f = u[col] * tmax
            d = p.thruster_direction[i]
            fx, fy = f * math.cos(d), f * math.sin(d)
            f_out[i] = f
            az_out[i] = d
            col += 1
        else:
            fx, fy = u[col] * tmax, u[col + 1] * tmax
            f_out[i] = math.hypot(fx, fy)
            az_out[i] = math.atan2(fy, fx) % _TWO_PI if f_out[i] > 1e-9 * tmax \
                else prev_az[i]
            col += 2
        r0 -= fx
        r1 -= fy
        r2 -= x * fy - y * fx
    unmet[0], unmet[1], unmet[2] = r0, r1, r2
    return status


@njit(cache=True)
def _row(rows, cap, k, col, c1, c2, b):  # pragma: no cover - compiled
    """Row k of the QP: c1 u[col] + c2 u[col + 1] ≥ b (the workspace layout of
    :func:`seahelm.numerics.qp_inplace.solve_qp_rows`); returns k + 1."""
    rows[k] = col
    rows[cap + k] = c1
    rows[2 * cap + k] = c2
    rows[3 * cap + k] = b
    return k + 1


@njit(cache=True)
def dp_pid_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    for k in range(cs.shape[0]):
        cs[k] = 0.0
    cs[_S.desired_north] = y[_M.north]
    cs[_S.desired_east] = y[_M.east]
    cs[_S.desired_heading] = y[_M.heading]
    for i in range(_N):
        cs[_AZ0 + i] = p.thruster_direction[i]


@njit(cache=True)
def dp_pid_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    dp_control(dt, y[_M.north], y[_M.east], y[_M.heading], y[_M.surge_speed],
               y[_M.sway_speed], y[_M.yaw_rate], ref, p, cs, cmd)


@njit(cache=True)
def dp_control(dt, north, east, psi, surge, sway, yaw_rate, ref, p, cs,
               cmd):  # pragma: no cover - compiled
    """The PID, reference model, allocation and shaft lag of one step (see the module), from
    the position, heading and velocity given (measured, or an observer's estimates)."""
    c, s = math.cos(psi), math.sin(psi)
    e0 = north - cs[_S.desired_north]
    e1 = east - cs[_S.desired_east]
    e2 = wrap_pi(psi - cs[_S.desired_heading])
    zeta = p.damping_ratio
    w0, w1, w2 = p.frequency_surge, p.frequency_sway, p.frequency_yaw
    kp0, kp1, kp2 = w0 * w0 * p.mass_surge, w1 * w1 * p.mass_sway, w2 * w2 * p.inertia_yaw
    kd0 = 2.0 * zeta * w0 * p.mass_surge - p.damping_surge
    kd1 = 2.0 * zeta * w1 * p.mass_sway - p.damping_sway
    kd2 = 2.0 * zeta * w2 * p.inertia_yaw - p.damping_yaw
    kap = p.integral_ratio
    # NED-frame P and I terms, rotated to the body: −Rᵀ(K_p ẽ + K_i z)
    pn = kp0 * e0 + kap * w0 * kp0 * cs[_S.integral_north]
    pe = kp1 * e1 + kap * w1 * kp1 * cs[_S.integral_east]
    tau0 = -(c * pn + s * pe) - kd0 * surge - ref[_R.wind_force_x]
    tau1 = -(-s * pn + c * pe) - kd1 * sway - ref[_R.wind_force_y]
    tau2 = -(kp2 * e2 + kap * w2 * kp2 * cs[_S.integral_heading]) - kd2 * yaw_rate \
        - ref[_R.wind_moment_z]
    cs[_S.integral_north] += dt * e0
    cs[_S.integral_east] += dt * e1
    cs[_S.integral_heading] += dt * e2
    cf = p.reference_factor
    if cf > 0.0:
        cs[_S.desired_north] += dt * (ref[_R.north] - cs[_S.desired_north]) * w0 / cf
        cs[_S.desired_east] += dt * (ref[_R.east] - cs[_S.desired_east]) * w1 / cf
        cs[_S.desired_heading] += dt * wrap_pi(ref[_R.heading] - cs[_S.desired_heading]) \
            * w2 / cf
    else:
        cs[_S.desired_north] = ref[_R.north]
        cs[_S.desired_east] = ref[_R.east]
        cs[_S.desired_heading] = ref[_R.heading]
    n = int(p.thruster_count)
    f = cs[_SC0:_SC0 + _N]
    az = cs[_SC0 + _N:_SC0 + 2 * _N]
    unmet = cs[_SC0 + 2 * _N:_SC0 + 2 * _N + 3]
    allocate_step(p, tau0, tau1, tau2, dt, cs[_FX0:_FX0 + _N], cs[_FY0:_FY0 + _N],
                  cs[_AZ0:_AZ0 + _N], f, az, unmet, cs[_WS0:])
    tn = p.thruster_time_constant
    out0 = 0.0
    out1 = 0.0
    out2 = 0.0
    for i in range(n):
        tmax = p.thruster_max_thrust[i]
        cs[_FX0 + i] = f[i] * math.cos(az[i])
        cs[_FY0 + i] = f[i] * math.sin(az[i])
        cs[_AZ0 + i] = az[i]
        sh = cs[_SH0 + i]
        delivered = tmax * sh * abs(sh) if tn > 0.0 else f[i]
        q = f[i] / tmax
        s_cmd = math.sqrt(q) if q >= 0.0 else -math.sqrt(-q)
        cs[_SH0 + i] = sh + dt * (s_cmd - sh) / tn if tn > 0.0 else s_cmd
        fx, fy = delivered * math.cos(az[i]), delivered * math.sin(az[i])
        out0 += fx
        out1 += fy
        out2 += p.thruster_x[i] * fy - p.thruster_y[i] * fx
        cmd[_TH0 + i] = delivered
    cmd[_C.thrust_surge] = out0
    cmd[_C.thrust_sway] = out1
    cmd[_C.thrust_yaw] = out2
    k0 = len(COMMANDS)
    cmd[k0 + _O.demand_surge] = tau0
    cmd[k0 + _O.demand_sway] = tau1
    cmd[k0 + _O.demand_yaw] = tau2
    cmd[k0 + _O.unmet_surge] = unmet[0]
    cmd[k0 + _O.unmet_sway] = unmet[1]
    cmd[k0 + _O.unmet_yaw] = unmet[2]


DP_PID = Controller(
    name="dp-pid",
    description="DP: nonlinear PID by pole placement, first-order reference model, wind "
    "feedforward, constrained thrust allocation in the loop, shaft lag (Fossen 2021, §12.2)",
    params_type=DpPidParams,
    state_labels=STATES,
    state_units=("m·s", "m·s", "rad·s", "m", "m", "rad") + ("N",) * (2 * _N) + ("-",) * _N
    + ("rad",) * _N + ("m·s", "m", "m·s", "m", "rad·s", "rad", "m", "m", "rad", "N", "N",
                        "N·m", "m/s", "m/s", "rad/s", "N", "N", "N·m") + ("",) * (2 * _N + 3 + WORKSPACE),
    reference_labels=REFERENCES,
    reference_units=("m", "m", "rad", "N", "N", "N·m"),
    command_labels=COMMANDS,
    command_units=("N", "N", "N·m"),
    init=dp_pid_init,
    step=dp_pid_step,
    measurement_labels=MEASUREMENTS,
    output_labels=OUTPUTS,
    output_units=("N", "N", "N·m", "N", "N", "N·m") + ("N",) * _N,
)
