"""The Python ends of a vector environment's step, compiled (issue 52, speed): the actions'
check and clip (:func:`clip_actions`), and the end of a heading-keeping step --
observations, reward, terminations and the autoreset bookkeeping of every sub-environment in
one pass (the numpy expressions it replaces cost some 40 array calls a step, a tenth of a
1,024-environment Euler step).

The arithmetic is that of the numpy expressions of :class:`~seahelm.gym.tasks.HeadingKeeping`,
:func:`~seahelm.gym.tasks.weighted_sum` and :class:`~seahelm.gym.base.BatchEnv` (``_step_end``,
``_cast``), operation for operation and in their order (numba compiles without
``fastmath``: no fused multiply-adds, no reassociation; the float ``%`` is numpy's and
Python's, fmod with the sign of the divisor), so every number is the same, bit for bit
(``tests/test_gym_state_path.py``); the one transcendental function, the bell exp(-(ψ̃/σ_ψ)²), is
still computed by numpy, between the two passes.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["clip_actions", "heading_error_pass", "heading_keeping_end"]

_TWO_PI = 2.0 * np.pi


@njit(cache=True)
def clip_actions(a, low, high, out):  # pragma: no cover - compiled
    """The actions clipped to the box into ``out``, as ``np.minimum(np.maximum(a, low),
    high)`` (exact: comparisons and copies), unless one is not finite.

    Parameters
    ----------
    a : ndarray (envs, actions)
        The actions (float32 or float64).
    low, high : ndarray (actions,)
        The box [the actions' units].
    out : ndarray float64 (envs, actions)
        Written.

    Returns
    -------
    int
        -1, or the flat index (row-major) of the first action that is NaN or infinite
        (``out`` then partly written: the caller refuses the step).
    """
    k = a.shape[1]
    for i in range(a.shape[0]):
        for j in range(k):
            x = np.float64(a[i, j])
            if not math.isfinite(x):
                return i * k + j
            if x <= low[j]:  # (numpy's maximum: the bound on a tie, so -0.0 at 0.0 is +0.0)
                x = low[j]
            if x >= high[j]:  # (numpy's minimum: the bound on a tie)
                x = high[j]
            out[i, j] = x
    return -1


@njit(cache=True)
def heading_error_pass(z, j_heading, target, scale, error, arg):  # pragma: no cover
    """The wrapped heading errors ψ̃ = wrap(ψ − ψ_d) into ``error`` and the bell's exponent
    −(ψ̃/σ_ψ)² into ``arg`` (runs,).

    Parameters
    ----------
    z : ndarray (runs, states)
        The simulator's states.
    j_heading : int
        The heading's column.
    target : ndarray (runs,)
        ψ_d [rad].
    scale : float
        σ_ψ [rad].
    error, arg : ndarray (runs,)
        Written.
    """
    for i in range(z.shape[0]):
        x = z[i, j_heading] - target[i] + np.pi
        # (x already in [0, 2π), as nearly always: x % 2π is x itself -- fmod is exact and
        # Python's % then changes nothing -- without the fmod, four fifths of this pass)
        e = (x if 0.0 <= x < _TWO_PI else x % _TWO_PI) - np.pi
        error[i] = e
        y = e / scale
        y = y * y
        arg[i] = -y


@njit(cache=True)
def heading_keeping_end(z, cols, cmd, j_rudder, previous, error, bell, status, elapsed,
                        restart, consts, weights, low, high, obs, reward, terminated,
                        truncated, done):  # pragma: no cover - compiled
    """Observations (float32, NaN as 0, clipped to the box), reward, terminations and the
    episodes ended, of every sub-environment after a heading-keeping step.

    Parameters
    ----------
    z : ndarray (runs, states)
        The simulator's states.
    cols : ndarray of int (3,)
        The columns of the yaw rate, surge and sway speeds.
    cmd : ndarray (runs, commands)
        The commands; ``j_rudder`` the rudder command's column.
    j_rudder : int
    previous : ndarray (runs,)
        The rudder commands of the step before [rad].
    error, bell : ndarray (runs,)
        ψ̃ [rad] and exp(−(ψ̃/σ_ψ)²) (:func:`heading_error_pass`, then numpy's exp).
    status : ndarray of int (runs,)
        The runs' statuses (non-zero: diverged).
    elapsed : ndarray (runs,)
        Time in the episode [s].
    restart : ndarray of bool (runs,)
        The sub-environments restarted by this step (reward 0, both flags False).
    consts : ndarray (5,)
        L/U_0 [s], δ_max [rad], the largest heading error [rad], the episode's length less
        1e-9 [s], 1.0 (unused).
    weights : ndarray (5,)
        The reward weights of heading, yaw_rate, rudder, rudder_rate, failure (a term of
        weight 0 is left out of the sum, as :func:`~seahelm.gym.tasks.weighted_sum`).
    low, high : ndarray (5,)
        The observation box.
    obs : ndarray float32 (runs, 5)
        Written: heading error, yaw rate, surge and sway speeds, rudder command.
    reward : ndarray (runs,)
    terminated, truncated, done : ndarray of bool (runs,)
        Written (``done``: either flag, the next step's restarts).
    """
    c_r, max_rudder, max_error, last = consts[0], consts[1], consts[2], consts[3]
    j_r, j_u, j_v = cols[0], cols[1], cols[2]
    for i in range(z.shape[0]):
        e = error[i]
        r = z[i, j_r]
        rudder = cmd[i, j_rudder]
        failed = abs(e) > max_error or status[i] != 0
        t_yaw = r * c_r
        t_yaw = -(t_yaw * t_yaw)
        t_rud = rudder / max_rudder
        t_rud = -(t_rud * t_rud)
        t_rate = rudder - previous[i]
        t_rate = t_rate / max_rudder
        t_rate = -(t_rate * t_rate)
        t_fail = -(1.0 if failed else 0.0)
        total = 0.0
        if weights[0] != 0.0:
            total += weights[0] * bell[i]
        if weights[1] != 0.0:
            total += weights[1] * t_yaw
        if weights[2] != 0.0:
            total += weights[2] * t_rud
        if weights[3] != 0.0:
            total += weights[3] * t_rate
        if weights[4] != 0.0:
            total += weights[4] * t_fail
        term = failed
        trunc = (not term) and elapsed[i] >= last
        if restart[i]:
            total = 0.0
            term = False
            trunc = False
        reward[i] = total
        terminated[i] = term
        truncated[i] = trunc
        done[i] = term or trunc
        obs[i, 0] = _cast(e, low[0], high[0])
        obs[i, 1] = _cast(r, low[1], high[1])
        obs[i, 2] = _cast(z[i, j_u], low[2], high[2])
        obs[i, 3] = _cast(z[i, j_v], low[3], high[3])
        obs[i, 4] = _cast(rudder, low[4], high[4])


@njit(cache=True)
def _cast(x, low, high):  # pragma: no cover - compiled
    """x as :meth:`BatchEnv._cast <seahelm.gym.base.BatchEnv._cast>` makes an observation:
    NaN 0, then max(x, low), min(x, high), float32. (Numbers only: a helper taking the
    arrays cost 25 ns a call, their reference counts.)"""
    if math.isnan(x):
        x = 0.0
    if not x >= low:
        x = low
    if not x <= high:
        x = high
    return np.float32(x)
