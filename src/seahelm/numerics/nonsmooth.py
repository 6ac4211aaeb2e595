"""Non-smooth operating points: one-sided Jacobians, kink detection and the two linear pieces.

A model with a switch (MMG's flow-straightening coefficient γ_R, which is ``gamma_R_minus``
for β_R < 0 and ``gamma_R_plus`` for β_R > 0 in v_R = U γ_R β_R, Yasukawa & Yoshimura 2015) has no
Jacobian on the switching surface. The central difference there returns the mean of the two
one-sided derivatives: a model of neither side. :func:`one_sided_jacobians` takes the forward
and backward difference quotients

    D₊(h) = (f(x + h e_j) − f(x))/h,   D₋(h) = (f(x) − f(x − h e_j))/h

(= f'(x) ± c₁h + c₂h² ∓ …), extrapolated over h, h/2, h/4, … in Richardson's tableau with the
factors 2^i − 1 (Dahlquist & Björck 2008, §3.4.3), each with its error estimate (the last
correction plus the rounding ε max|f|/h amplified by the tableau).

Detection (:func:`kinked_columns`)
    Column j of the Jacobian is *kinked* when, for some output i, the one-sided derivatives
    differ by more than ``ratio`` (100) times their combined error estimate **and** by more than
    ``relative`` (10⁻⁶) of the row's scale max_k |J_ik| h_k / h_j (unit-free). At a smooth
    point both sides converge to f'(x) and differ by their truncation error only (measured: at
    most 1.3 error estimates and 7·10⁻¹² of the row scale for the Mariner, the KVLCC2's surge
    and propeller columns); at the KVLCC2's zero-drift kink the sway and yaw columns differ by
    27 % and 16 % of the row scale, 10⁸–10¹² error estimates.

The two pieces (:func:`side_jacobians`)
    A switching surface s(x) = 0 through the point, with normal n, gives two pieces with
    gradients G₊ (s > 0) and G₋. The forward quotient of column j is G₊'s where n_j > 0 and
    G₋'s where n_j < 0, and the jump forward − backward does not tell which (for a kink like
    |n·x| it is |n_j| either way). So the relative sign of n_j and n_ref is measured: the
    forward quotient along the direction d = h_ref e_ref + h_j e_j equals F_ref + F_j
    (forward quotients) when n_j and n_ref have one sign, and F_ref + B_j or B_ref + F_j (B:
    backward) when they have opposite signs; the closest of the three decides, row by row.
    Several switches may meet at one point, each acting on its own rows (the KVLCC2's
    straight run: γ_R in the sway and yaw rows, the wake's |β_P| in the surge row), so the
    reference column is per row: the first kinked column (in the order of the variables) that
    jumps in that row. Side "+" is the piece the reference variable increases into (for every
    row, the cone of directions containing +e_ref), side "−" the one it decreases into.
    Entries that do not jump keep the central difference. ``switches`` counts the distinct
    sign patterns of the rows (as far as the rows tell, the surfaces that meet there).

References
----------
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
Dahlquist, G., Björck, Å. (2008). Numerical Methods in Scientific Computing, vol. 1. SIAM.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["one_sided_jacobians", "kinked_columns", "side_jacobians", "Kink"]

_EPS = np.finfo(float).eps


def one_sided_jacobians(f: Callable[[np.ndarray], np.ndarray], x0: Any, step: Any, *,
                        levels: int = 4) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                  np.ndarray]:
    """Forward and backward Richardson-extrapolated Jacobians of f at x0 (module docstring).

    Parameters
    ----------
    f : callable
        ``f(X)`` for X of shape (k, n) returns shape (k, m), one batched call.
    x0 : array_like, shape (n,)
    step : array_like, shape (n,)
        The largest step of each variable (> 0); halved ``levels`` − 1 times.
    levels : int, optional
        Rows of the tableau (default 4).

    Returns
    -------
    forward, forward_error, backward, backward_error : numpy.ndarray, shape (m, n)
    """
    x0 = np.asarray(x0, dtype=float)
    n = x0.size
    h = np.broadcast_to(np.asarray(step, dtype=float), x0.shape)
    hk = h[None, :] / 2.0 ** np.arange(levels)[:, None]  # (levels, n)
    eye = np.eye(n)
    points = np.concatenate([x0 + hk[:, :, None] * eye, x0 - hk[:, :, None] * eye])
    values = np.asarray(f(np.concatenate([x0[None], points.reshape(-1, n)])), dtype=float)
    f0, m = values[0], values.shape[-1]
    values = values[1:].reshape(2, levels, n, m)
    out: list[np.ndarray] = []
    for side, sign in ((0, 1.0), (1, -1.0)):
        tableau = [sign * (values[side] - f0) / hk[:, :, None]]  # (levels, n, m)
        for i in range(1, levels):
            prev = tableau[-1]
            tableau.append(prev[1:] + (prev[1:] - prev[:-1]) / (2.0 ** i - 1.0))
        best, second = tableau[-1][0], tableau[-2][-1]
        scale = np.maximum(np.abs(values[side]).max(axis=0), np.abs(f0))
        rounding = 2.0 ** levels * _EPS * scale / hk[-1][:, None]
        out += [best.T.copy(), (np.abs(best - second) + rounding).T.copy()]
    return out[0], out[1], out[2], out[3]


@dataclasses.dataclass(frozen=True)
class Kink:
    """Which Jacobian entries jump at a point, and on which side each piece takes what.

    Attributes
    ----------
    columns : tuple of int
        The kinked columns (variables).
    reference : tuple of int
        The first kinked column of each row that jumps there (−1: the row does not jump).
    signs : numpy.ndarray, shape (m, n)
        +1 where side "+" takes the forward quotient, −1 the backward, 0 the central
        difference (no jump).
    jump : tuple of float
        The largest unit-free jump of each kinked column, |J₊ − J₋| h_j / row scale.
    switches : int
        Distinct sign patterns of the jumping rows (switching surfaces that meet there).
    """

    columns: tuple[int, ...]
    reference: tuple[int, ...]
    signs: np.ndarray
    jump: tuple[float, ...]
    switches: int


def _directional(f: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, d: np.ndarray,
                 levels: int) -> np.ndarray:
    """Richardson-extrapolated forward quotient of f along d (rows: directions)."""
    t = 1.0 / 2.0 ** np.arange(levels)  # (levels,)
    k, n = d.shape
    points = x0 + t[:, None, None] * d[None]  # (levels, k, n)
    values = np.asarray(f(np.concatenate([x0[None], points.reshape(-1, n)])), dtype=float)
    f0 = values[0]
    tableau = [(values[1:].reshape(levels, k, -1) - f0) / t[:, None, None]]
    for i in range(1, levels):
        prev = tableau[-1]
        tableau.append(prev[1:] + (prev[1:] - prev[:-1]) / (2.0 ** i - 1.0))
    return tableau[-1][0]  # (k, m)


def kinked_columns(forward: np.ndarray, forward_error: np.ndarray, backward: np.ndarray,
                   backward_error: np.ndarray, step: Any, *, ratio: float = 100.0,
                   relative: float = 1e-6, f: Callable[[np.ndarray], np.ndarray] | None = None,
                   x0: Any = None, levels: int = 4) -> Kink:
    """The entries whose one-sided derivatives differ (module docstring: detection).

    Parameters
    ----------
    forward, forward_error, backward, backward_error : numpy.ndarray, shape (m, n)
        From :func:`one_sided_jacobians`.
    step : array_like, shape (n,)
        The steps (the variables' natural sizes) that make the comparison unit-free.
    ratio : float, optional
        How many combined error estimates a difference must exceed (default 100).
    relative : float, optional
        Fraction of the row scale a difference must exceed (default 10⁻⁶).
    f, x0, levels : optional
        The function, the point and the tableau rows, to measure the relative signs of the
        surface normal (module docstring); without ``f`` every sign is taken as +1.

    Returns
    -------
    Kink
        ``columns`` empty at a smooth point.
    """
    h = np.asarray(step, dtype=float)
    jump = forward - backward
    mean = 0.5 * (forward + backward)
    row_scale = np.maximum(np.abs(mean * h[None, :]).max(axis=1), 1e-300)[:, None]
    scaled = jump * h[None, :] / row_scale  # unit-free, (m, n)
    big = (np.abs(jump) > ratio * (forward_error + backward_error)) & \
        (np.abs(scaled) > relative)
    columns = tuple(int(j) for j in np.flatnonzero(big.any(axis=0)))
    signs = np.zeros(jump.shape, dtype=int)
    reference = []
    pairs = sorted({(int(np.flatnonzero(big[i])[0]), int(j)) for i in range(jump.shape[0])
                    for j in np.flatnonzero(big[i])[1:]})
    if pairs and f is not None:
        d = np.zeros((len(pairs), h.size))
        for row, (r, j) in enumerate(pairs):
            d[row, r], d[row, j] = h[r], h[j]
        along = _directional(f, np.asarray(x0, dtype=float), d, levels)  # (pairs, m)
    for i in range(jump.shape[0]):
        hits = np.flatnonzero(big[i])
        reference.append(int(hits[0]) if hits.size else -1)
        if not hits.size:
            continue
        r = hits[0]
        signs[i, r] = 1
        for j in hits[1:]:
            if f is None:
                signs[i, j] = 1
                continue
            got = along[pairs.index((int(r), int(j))), i]
            same = abs(got - (forward[i, r] * h[r] + forward[i, j] * h[j]))
            other = min(abs(got - (forward[i, r] * h[r] + backward[i, j] * h[j])),
                        abs(got - (backward[i, r] * h[r] + forward[i, j] * h[j])))
            signs[i, j] = 1 if same <= other else -1
    patterns = {tuple(signs[i, list(columns)]) for i in range(jump.shape[0]) if reference[i] >= 0}
    return Kink(columns=columns, reference=tuple(reference), signs=signs,
                jump=tuple(float(np.abs(scaled[:, j]).max()) for j in columns),
                switches=len(patterns))


def side_jacobians(forward: np.ndarray, forward_error: np.ndarray, backward: np.ndarray,
                   backward_error: np.ndarray, central: np.ndarray, central_error: np.ndarray,
                   kink: Kink) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
    """The Jacobians (and error estimates) of the two sides of a kink (module docstring).

    Parameters
    ----------
    forward, forward_error, backward, backward_error : numpy.ndarray, shape (m, n)
        From :func:`one_sided_jacobians`.
    central, central_error : numpy.ndarray, shape (m, n)
        The central-difference Jacobian and its error (kept where nothing jumps).
    kink : Kink
        From :func:`kinked_columns`.

    Returns
    -------
    tuple
        ((J₊, E₊), (J₋, E₋)): side "+" takes the forward quotient where ``kink.signs`` is +1
        and the backward one where it is −1; side "−" the other way round.
    """
    sides = []
    for flip in (1, -1):
        s = kink.signs * flip
        J = np.where(s > 0, forward, np.where(s < 0, backward, central))
        E = np.where(s > 0, forward_error, np.where(s < 0, backward_error, central_error))
        sides.append((J, E))
    return tuple(sides)
