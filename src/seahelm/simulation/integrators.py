"""Fixed-step integrators over a leading batch axis, and an adaptive reference path.

The fixed-step methods are pure functions ``step(f, t, x, h, *args) -> x_next`` for any
vectorised right-hand side ``f(t, x, *args)`` over arrays of shape ``(..., n)``, and
:func:`integrate` runs one of them over a time grid. The same three methods are compiled into
the closed-loop kernel (:mod:`seahelm.simulation.kernel_template`); the tests check both
against closed-form solutions (orders 1, 2, 4).

:func:`solve_reference` is the adaptive path through :func:`scipy.integrate.solve_ivp` for
accuracy checks.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from .._validate import as_float_array, check_positive

__all__ = ["euler_step", "heun_step", "rk4_step", "INTEGRATORS", "integrate", "solve_reference",
           "get_integrator"]

Rhs = Callable[..., np.ndarray]


def euler_step(f: Rhs, t: float, x: np.ndarray, h: float, *args: Any) -> np.ndarray:
    """Explicit Euler: x + h f(t, x). Order 1.

    Parameters
    ----------
    f : callable(t, x, *args)
        Right-hand side dx/dt.
    t : float
        Time at the start of the step [s].
    x : numpy.ndarray, shape (..., n)
        State at ``t``.
    h : float
        Step size [s].
    *args
        Extra arguments of ``f``.

    Returns
    -------
    numpy.ndarray, shape (..., n)
        State at ``t + h``.
    """
    return x + h * f(t, x, *args)


def heun_step(f: Rhs, t: float, x: np.ndarray, h: float, *args: Any) -> np.ndarray:
    """Heun (explicit trapezoid): order 2.

    Parameters
    ----------
    f : callable(t, x, *args)
        Right-hand side dx/dt.
    t : float
        Time at the start of the step [s].
    x : numpy.ndarray, shape (..., n)
        State at ``t``.
    h : float
        Step size [s].
    *args
        Extra arguments of ``f``.

    Returns
    -------
    numpy.ndarray, shape (..., n)
        State at ``t + h``.
    """
    k1 = f(t, x, *args)
    k2 = f(t + h, x + h * k1, *args)
    return x + 0.5 * h * (k1 + k2)


def rk4_step(f: Rhs, t: float, x: np.ndarray, h: float, *args: Any) -> np.ndarray:
    """Classic fourth-order Runge–Kutta.

    Parameters
    ----------
    f : callable(t, x, *args)
        Right-hand side dx/dt.
    t : float
        Time at the start of the step [s].
    x : numpy.ndarray, shape (..., n)
        State at ``t``.
    h : float
        Step size [s].
    *args
        Extra arguments of ``f``.

    Returns
    -------
    numpy.ndarray, shape (..., n)
        State at ``t + h``.
    """
    k1 = f(t, x, *args)
    k2 = f(t + 0.5 * h, x + 0.5 * h * k1, *args)
    k3 = f(t + 0.5 * h, x + 0.5 * h * k2, *args)
    k4 = f(t + h, x + h * k3, *args)
    return x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


INTEGRATORS: dict[str, Callable[..., np.ndarray]] = {
    "euler": euler_step,
    "heun": heun_step,
    "rk4": rk4_step,
}
"""Registry of fixed-step methods by name (the names the engine and scenarios accept)."""

ORDERS = {"euler": 1, "heun": 2, "rk4": 4}


def get_integrator(name: str) -> Callable[..., np.ndarray]:
    """Look up a fixed-step method; an unknown name raises ValueError listing the valid ones.

    Parameters
    ----------
    name : {"euler", "heun", "rk4"}
        Name in :data:`INTEGRATORS`.

    Returns
    -------
    callable
        Step function ``step(f, t, x, h, *args)``.

    Raises
    ------
    ValueError
        If ``name`` is unknown (the message lists the valid ones).
    """
    try:
        return INTEGRATORS[name]
    except KeyError:
        raise ValueError(
            f"unknown integrator '{name}'; valid: {', '.join(INTEGRATORS)}"
        ) from None


def integrate(
    f: Rhs,
    x0: Any,
    t: Any,
    *args: Any,
    method: str = "rk4",
) -> np.ndarray:
    """Integrate ``ẋ = f(t, x, *args)`` over the time grid ``t`` with a fixed-step method.

    Parameters
    ----------
    f : callable
        Vectorised right-hand side over ``(..., n)`` arrays.
    x0 : array_like, shape (..., n)
        Initial state; leading axes are batch axes.
    t : array_like, shape (m,)
        Increasing time grid [s]; the steps may differ.
    method : {"euler", "heun", "rk4"}

    Returns
    -------
    numpy.ndarray, shape (m, ..., n)
        The state at every grid time.
    """
    step = get_integrator(method)
    x = as_float_array("x0", x0)
    t = as_float_array("t", t, "s")
    if t.ndim != 1 or t.size < 1:
        raise ValueError(f"`t` must be a 1-D time grid [s], got shape {t.shape}")
    check_positive("time step", np.diff(t), "s") if t.size > 1 else None
    out = np.empty((t.size,) + x.shape)
    out[0] = x
    for k in range(t.size - 1):
        x = step(f, t[k], x, t[k + 1] - t[k], *args)
        out[k + 1] = x
    return out


def solve_reference(
    f: Rhs,
    x0: Any,
    t_eval: Any,
    *args: Any,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
    breakpoints: Any = None,
) -> np.ndarray:
    """Adaptive high-accuracy solution with :func:`scipy.integrate.solve_ivp` (one run).

    An adaptive solver's error estimate assumes a smooth right-hand side: a step that straddles
    a kink (a jump in a derivative of ``f``, e.g. a saturation or a piecewise coefficient)
    can be far less accurate than ``rtol`` claims, and how much depends on where the steps fall
    (so on the scipy version). Pass the times of such kinks as ``breakpoints``: the solve is then
    restarted at each one, so no step crosses a kink and the tolerances mean what they say.

    Parameters
    ----------
    f : callable(t, x, *args)
        Right-hand side dx/dt.
    x0 : array_like, shape (n,)
        Initial state at ``t_eval[0]``.
    t_eval : array_like, shape (m,)
        Output times [s], increasing; the solve runs from the first to the last.
    *args
        Extra arguments of ``f``.
    rtol, atol : float, optional
        Relative and absolute tolerances (default 1e-10, 1e-12).
    method : str, optional
        :func:`scipy.integrate.solve_ivp` method (default "DOP853").
    breakpoints : array_like, optional
        Times [s] where ``f`` is not smooth; those outside the open interval of ``t_eval`` are
        ignored.

    Returns
    -------
    numpy.ndarray, shape (m, n)
        The state at each time of ``t_eval``.

    Raises
    ------
    RuntimeError
        If the solver fails.
    """
    x0 = as_float_array("x0", x0)
    t_eval = as_float_array("t_eval", t_eval, "s")
    if t_eval.ndim != 1 or t_eval.size < 1 or np.any(np.diff(t_eval) <= 0):
        raise ValueError(f"`t_eval` must be a 1-D increasing time grid [s], got {t_eval!r}")
    t0, t1 = float(t_eval[0]), float(t_eval[-1])
    cuts = np.array([], dtype=float) if breakpoints is None else np.unique(
        as_float_array("breakpoints", breakpoints, "s").ravel())
    eps = 1e-12 * max(1.0, abs(t0), abs(t1))  # a breakpoint on an end (to round-off) is none
    cuts = cuts[(cuts > t0 + eps) & (cuts < t1 - eps)]
    if cuts.size > 1:
        cuts = cuts[np.concatenate([[True], np.diff(cuts) > eps])]
    edges = np.concatenate([[t0], cuts, [t1]])
    out = np.empty((t_eval.size, x0.size))
    out[0] = x0
    x = x0
    for a, b in zip(edges[:-1], edges[1:]):
        inside = (t_eval > a) & (t_eval < b)
        times = np.append(t_eval[inside], b)  # always end on the segment's end
        sol = solve_ivp(
            lambda t, x: np.asarray(f(t, x, *args), dtype=float),
            (float(a), float(b)),
            x,
            t_eval=times,
            rtol=rtol,
            atol=atol,
            method=method,
        )
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed on [{a:g}, {b:g}] s: {sol.message}")
        out[inside] = sol.y[:, :-1].T
        x = sol.y[:, -1]
        if b in t_eval:
            out[np.searchsorted(t_eval, b)] = x
    return out
