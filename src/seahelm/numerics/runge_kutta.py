"""Explicit Runge–Kutta methods as Butcher tableaus: the registry and one batched numpy step.

A fixed-step method is data, not code: a :class:`ButcherTableau` (``a``, ``b``, ``c`` and the
order), registered by name in :data:`INTEGRATORS`. One numpy step, :func:`rk_step`, advances
a batch of states ``(..., n)`` with any tableau. Generic numerics (no ship): the engine
(:mod:`seahelm.simulation.integrators`, which re-exports these names, and
:mod:`seahelm.simulation.compiled_step`, which writes the same step as numba source) and the
components that integrate a model of their own (:mod:`seahelm.control.final_state_general`)
use them from here. Adding a method is one tableau and one registry line.

For a tableau with s stages, the step from ``t`` to ``t + h`` is::

    k_i = f(t + c_i h, x + h Σ_{j<i} a_ij k_j),   i = 1..s
    x(t + h) ≈ x + h Σ_i b_i k_i

References
----------
Butcher, J. C. (2016). Numerical Methods for Ordinary Differential Equations, 3rd ed. Wiley.
Hairer, E., Nørsett, S. P., Wanner, G. (1993). Solving Ordinary Differential Equations I,
2nd ed. Springer, sec. II.1.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = [
    "ButcherTableau",
    "INTEGRATORS",
    "ORDERS",
    "get_integrator",
    "rk_step",
]

Rhs = Callable[..., np.ndarray]

# round-off allowance of the consistency checks, in units of machine epsilon
_ROUNDOFF = 8.0 * np.finfo(float).eps


@dataclass(frozen=True, kw_only=True)
class ButcherTableau:
    """An explicit Runge–Kutta method: the Butcher tableau (a, b, c) and its order.

    Parameters
    ----------
    name : str
        Short name (the key in :data:`INTEGRATORS` for registered methods).
    a : array_like, shape (s, s)
        Stage coefficients a_ij; strictly lower triangular (explicit methods only).
    b : array_like, shape (s,)
        Weights b_i of the solution; Σ b_i = 1.
    c : array_like, shape (s,)
        Nodes c_i: stage i is evaluated at t + c_i h; c_i = Σ_j a_ij.
    order : int
        Order of accuracy p (global error O(h^p)) for smooth problems.
    description : str, optional
        One line for listings.
    reference : str, optional
        Where the method is published (author and year).

    Raises
    ------
    ParameterError
        If the arrays have inconsistent shapes or are not finite, ``a`` is not strictly lower
        triangular, c_i differs from Σ_j a_ij or Σ b_i from 1 beyond round-off, or ``order``
        is not a whole number >= 1.

    Notes
    -----
    Coefficients are stored as tuples of floats (hashable, so a tableau can key a cache).
    Round-off allowance of the checks: 8 ε (1 + Σ |terms|).
    """

    name: str
    a: tuple[tuple[float, ...], ...]
    b: tuple[float, ...]
    c: tuple[float, ...]
    order: int
    description: str = ""
    reference: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ParameterError(
                f"`name` of a tableau must be a non-empty string, got {self.name!r}"
            )
        label = f"tableau '{self.name}'"
        a = _coefficients(label, "a", self.a)
        b = _coefficients(label, "b", self.b)
        c = _coefficients(label, "c", self.c)
        if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] < 1:
            raise ParameterError(
                f"`a` of {label} must be a square (s, s) array, got shape {a.shape}"
            )
        s = a.shape[0]
        for arg, arr in (("b", b), ("c", c)):
            if arr.shape != (s,):
                raise ParameterError(
                    f"`{arg}` of {label} must have shape ({s},) to match `a` {a.shape}, "
                    f"got {arr.shape}"
                )
        upper = np.argwhere(np.triu(a) != 0.0)
        if upper.size:
            i, j = upper[0]
            raise ParameterError(
                f"`a` of {label} must be strictly lower triangular (explicit methods only): "
                f"a[{i}][{j}] = {float(a[i, j])!r}"
            )
        rows = a.sum(axis=1)
        bad = np.abs(c - rows) > _ROUNDOFF * (1.0 + np.abs(a).sum(axis=1))
        if bad.any():
            i = int(np.argmax(bad))
            raise ParameterError(
                f"`c` of {label} must equal the row sums of `a` (c_i = Σ_j a_ij): "
                f"c[{i}] = {float(c[i])!r}, row sum {float(rows[i])!r}"
            )
        if abs(b.sum() - 1.0) > _ROUNDOFF * (1.0 + np.abs(b).sum()):
            raise ParameterError(f"`b` of {label} must sum to 1, got sum {float(b.sum())!r}")
        if isinstance(self.order, bool) or int(self.order) != self.order or self.order < 1:
            raise ParameterError(
                f"`order` of {label} must be a whole number >= 1, got {self.order!r}"
            )
        object.__setattr__(self, "a", tuple(tuple(float(v) for v in row) for row in a))
        object.__setattr__(self, "b", tuple(float(v) for v in b))
        object.__setattr__(self, "c", tuple(float(v) for v in c))
        object.__setattr__(self, "order", int(self.order))

    @property
    def stages(self) -> int:
        """Number of stages s (right-hand-side evaluations per step)."""
        return len(self.b)


def _coefficients(label: str, arg: str, value: Any) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ParameterError(
            f"`{arg}` of {label} must be a numeric array (ragged rows? give `a` as a "
            f"square (s, s) array), got {value!r}"
        ) from exc
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"`{arg}` of {label} must be finite, got {value!r}")
    return arr


# ------------------------------------------------------------------------------------------
# the registry: one tableau and one line per method
# ------------------------------------------------------------------------------------------
EULER = ButcherTableau(
    name="euler",
    a=[[0.0]],
    b=[1.0],
    c=[0.0],
    order=1,
    description="explicit Euler, x + h f(t, x)",
    reference="Euler (1768), Institutionum calculi integralis",
)
MIDPOINT = ButcherTableau(
    name="midpoint",
    a=[[0.0, 0.0],
       [1 / 2, 0.0]],
    b=[0.0, 1.0],
    c=[0.0, 1 / 2],
    order=2,
    description="explicit midpoint rule",
    reference="Runge (1895), Math. Ann. 46, 167-178",
)
HEUN = ButcherTableau(
    name="heun",
    a=[[0.0, 0.0],
       [1.0, 0.0]],
    b=[1 / 2, 1 / 2],
    c=[0.0, 1.0],
    order=2,
    description="Heun's method (explicit trapezoidal rule)",
    reference="Heun (1900), Z. Math. Phys. 45, 23-38",
)
RALSTON = ButcherTableau(
    name="ralston",
    a=[[0.0, 0.0],
       [2 / 3, 0.0]],
    b=[1 / 4, 3 / 4],
    c=[0.0, 2 / 3],
    order=2,
    description="Ralston's second-order method (minimum error bound)",
    reference="Ralston (1962), Math. Comp. 16, 431-437",
)
BOSH3 = ButcherTableau(
    name="bosh3",
    a=[[0.0, 0.0, 0.0],
       [1 / 2, 0.0, 0.0],
       [0.0, 3 / 4, 0.0]],
    b=[2 / 9, 1 / 3, 4 / 9],
    c=[0.0, 1 / 2, 3 / 4],
    order=3,
    description="Bogacki-Shampine, the third-order solution of the 3(2) pair (fixed step)",
    reference="Bogacki & Shampine (1989), Appl. Math. Lett. 2(4), 321-325",
)
SSPRK3 = ButcherTableau(
    name="ssprk3",
    a=[[0.0, 0.0, 0.0],
       [1.0, 0.0, 0.0],
       [1 / 4, 1 / 4, 0.0]],
    b=[1 / 6, 1 / 6, 2 / 3],
    c=[0.0, 1.0, 1 / 2],
    order=3,
    description="strong-stability-preserving third-order Runge-Kutta (Shu-Osher)",
    reference="Shu & Osher (1988), J. Comput. Phys. 77, 439-471",
)
KUTTA3 = ButcherTableau(
    name="kutta3",
    a=[[0.0, 0.0, 0.0],
       [1 / 2, 0.0, 0.0],
       [-1.0, 2.0, 0.0]],
    b=[1 / 6, 2 / 3, 1 / 6],
    c=[0.0, 1 / 2, 1.0],
    order=3,
    description="Kutta's third-order method",
    reference="Kutta (1901), Z. Math. Phys. 46, 435-453",
)
RK4 = ButcherTableau(
    name="rk4",
    a=[[0.0, 0.0, 0.0, 0.0],
       [1 / 2, 0.0, 0.0, 0.0],
       [0.0, 1 / 2, 0.0, 0.0],
       [0.0, 0.0, 1.0, 0.0]],
    b=[1 / 6, 1 / 3, 1 / 3, 1 / 6],
    c=[0.0, 1 / 2, 1 / 2, 1.0],
    order=4,
    description="the classic fourth-order Runge-Kutta method",
    reference="Kutta (1901), Z. Math. Phys. 46, 435-453",
)
RK38 = ButcherTableau(
    name="rk38",
    a=[[0.0, 0.0, 0.0, 0.0],
       [1 / 3, 0.0, 0.0, 0.0],
       [-1 / 3, 1.0, 0.0, 0.0],
       [1.0, -1.0, 1.0, 0.0]],
    b=[1 / 8, 3 / 8, 3 / 8, 1 / 8],
    c=[0.0, 1 / 3, 2 / 3, 1.0],
    order=4,
    description="Kutta's 3/8 rule (fourth order)",
    reference="Kutta (1901), Z. Math. Phys. 46, 435-453",
)

INTEGRATORS: dict[str, ButcherTableau] = {
    "euler": EULER,
    "midpoint": MIDPOINT,
    "heun": HEUN,
    "ralston": RALSTON,
    "bosh3": BOSH3,
    "ssprk3": SSPRK3,
    "kutta3": KUTTA3,
    "rk4": RK4,
    "rk38": RK38,
}
"""Registry of fixed-step methods by name (the names the engine and scenarios accept)."""

ORDERS: dict[str, int] = {name: tab.order for name, tab in INTEGRATORS.items()}
"""Declared order of each registered method (derived from :data:`INTEGRATORS`)."""


def get_integrator(method: str | ButcherTableau) -> ButcherTableau:
    """The tableau of a fixed-step method given by name or as a tableau.

    Parameters
    ----------
    method : str or ButcherTableau
        A name in :data:`INTEGRATORS` or a :class:`ButcherTableau` (returned as is).

    Returns
    -------
    ButcherTableau

    Raises
    ------
    ValueError
        If ``method`` is an unknown name (the message lists the valid ones).
    TypeError
        If ``method`` is neither a string nor a :class:`ButcherTableau`.
    """
    if isinstance(method, ButcherTableau):
        return method
    if not isinstance(method, str):
        raise TypeError(
            f"integrator must be a name ({', '.join(INTEGRATORS)}) or a ButcherTableau, "
            f"got {method!r}"
        )
    try:
        return INTEGRATORS[method]
    except KeyError:
        raise ValueError(
            f"unknown integrator '{method}'; valid: {', '.join(INTEGRATORS)}"
        ) from None


# ------------------------------------------------------------------------------------------
# numpy: one batched step of any tableau
# ------------------------------------------------------------------------------------------
def _combine(x: np.ndarray, h: float, coefficients: tuple[float, ...], ks: list[np.ndarray]
             ) -> np.ndarray:
    """x + h Σ coefficient_j k_j over the non-zero coefficients (left to right)."""
    acc = None
    for coefficient, k in zip(coefficients, ks):
        if coefficient == 0.0:
            continue
        term = k if coefficient == 1.0 else coefficient * k
        acc = term if acc is None else acc + term
    return x if acc is None else x + h * acc


def rk_step(method: str | ButcherTableau, f: Rhs, t: float, x: np.ndarray, h: float,
            *args: Any) -> np.ndarray:
    """One explicit Runge–Kutta step of a batch of states.

    Parameters
    ----------
    method : str or ButcherTableau
        The method: a name in :data:`INTEGRATORS` or a tableau.
    f : callable(t, x, *args)
        Right-hand side dx/dt, vectorised over the leading axes of ``x``.
    t : float
        Time at the start of the step [s].
    x : numpy.ndarray, shape (..., n)
        State at ``t``; leading axes are batch axes.
    h : float
        Step size [s].
    *args
        Extra arguments of ``f``.

    Returns
    -------
    numpy.ndarray, shape (..., n)
        State at ``t + h``.

    Notes
    -----
    k_i = f(t + c_i h, x + h Σ_{j<i} a_ij k_j), x(t + h) ≈ x + h Σ_i b_i k_i; zero
    coefficients are skipped (Hairer, Nørsett & Wanner (1993), eq. (II.1.8)).
    """
    tab = get_integrator(method)
    ks: list[np.ndarray] = []
    for i in range(tab.stages):
        xi = _combine(x, h, tab.a[i][:i], ks)
        ks.append(f(t + tab.c[i] * h, xi, *args))
    return _combine(x, h, tab.b, ks)
