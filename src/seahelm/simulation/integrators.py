"""Explicit Runge–Kutta methods for the engine: batched fixed steps and an adaptive reference path.

A fixed-step method is data, not code: a :class:`ButcherTableau` (``a``, ``b``, ``c`` and the
order), registered by name in :data:`INTEGRATORS`, and one numpy step, :func:`rk_step`. Those
are generic numerics and live in :mod:`seahelm.numerics.runge_kutta` (so a component that
integrates a model of its own needs no simulation import); this module re-exports them, and
:func:`integrate` runs the step over a time grid. For the compiled closed loop,
:mod:`seahelm.simulation.compiled_step` writes the same step as numba source, which
:func:`seahelm.simulation.engine.compile_closed_loop` puts into the kernel. Adding a method is
one tableau and one registry line (in :mod:`seahelm.numerics.runge_kutta`); the tests check
every registered tableau's declared order against closed-form solutions, in numpy and in the
compiled engine.

For a tableau with s stages, the step from ``t`` to ``t + h`` is::

    k_i = f(t + c_i h, x + h Σ_{j<i} a_ij k_j),   i = 1..s
    x(t + h) ≈ x + h Σ_i b_i k_i

:func:`solve_reference` is the adaptive path through :func:`scipy.integrate.solve_ivp` for
accuracy checks.

References
----------
Butcher, J. C. (2016). Numerical Methods for Ordinary Differential Equations, 3rd ed. Wiley.
Hairer, E., Nørsett, S. P., Wanner, G. (1993). Solving Ordinary Differential Equations I,
2nd ed. Springer, sec. II.1.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .._validate import as_float_array, check_positive
from ..numerics.runge_kutta import (  # (the tableaus by name too, as before the move)
    BOSH3,
    EULER,
    HEUN,
    INTEGRATORS,
    KUTTA3,
    MIDPOINT,
    ORDERS,
    RALSTON,
    RK4,
    RK38,
    SSPRK3,
    ButcherTableau,
    get_integrator,
    rk_step,
)

__all__ = [
    "ButcherTableau",
    "INTEGRATORS",
    "ORDERS",
    "get_integrator",
    "rk_step",
    "integrate",
    "solve_reference",
]

Rhs = Callable[..., np.ndarray]


def integrate(
    f: Rhs,
    x0: Any,
    t: Any,
    *args: Any,
    method: str | ButcherTableau = "rk4",
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
    *args
        Extra arguments of ``f``.
    method : str or ButcherTableau
        A name in :data:`INTEGRATORS` (default "rk4") or a tableau.

    Returns
    -------
    numpy.ndarray, shape (m, ..., n)
        The state at every grid time.
    """
    tab = get_integrator(method)
    x = as_float_array("x0", x0)
    t = as_float_array("t", t, "s")
    if t.ndim != 1 or t.size < 1:
        raise ValueError(f"`t` must be a 1-D time grid [s], got shape {t.shape}")
    check_positive("time step", np.diff(t), "s") if t.size > 1 else None
    out = np.empty((t.size,) + x.shape)
    out[0] = x
    for k in range(t.size - 1):
        x = rk_step(tab, f, t[k], x, t[k + 1] - t[k], *args)
        out[k + 1] = x
    return out


# ------------------------------------------------------------------------------------------
# adaptive reference
# ------------------------------------------------------------------------------------------
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
    from scipy.integrate import solve_ivp  # scipy.integrate costs 0.6 s at import

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
