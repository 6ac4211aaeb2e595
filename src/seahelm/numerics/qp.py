"""A small dense strictly convex QP solver, compiled and batched: Goldfarb–Idnani's dual method.

Solves, for each problem k of a batch::

    minimise ½ xᵀ G x + aᵀ x   subject to   C x ≥ b          (G symmetric positive definite)

by the dual active-set method of Goldfarb & Idnani (1983), "A numerically stable dual method
for solving strictly convex quadratic programs", *Mathematical Programming* 27, 1–33
(§3, the algorithm of steps 0–3). It starts from the unconstrained minimum x = −G⁻¹a (so it
needs no feasible start), adds the most violated constraint p, and moves along the primal
direction z = H n⁺ and the dual direction r = N* n⁺ (their eq. 4.1–4.2, with
N* = (Nᵀ G⁻¹ N)⁻¹ Nᵀ G⁻¹ and H = G⁻¹ (I − N N*)), dropping a constraint whose multiplier would
become negative (the partial step) until p is active (the full step). Where the paper updates
a QR factorisation of L⁻¹N, this recomputes N* and H from the active set at every step: the
problems here are small (tens of variables and constraints), so the O(q³) solve is cheap
and plainer to check. A problem with no feasible point ends with status 1.

The kernel is compiled with numba (``cache=True``); :func:`solve_qp_batch` runs one problem per
batch element. Checked against Clarabel through ``qpsolvers`` (tests/test_dp_allocation.py).
"""

from __future__ import annotations

import numpy as np
from numba import int64, njit

__all__ = ["solve_qp_batch", "STATUS_SOLVED", "STATUS_INFEASIBLE", "STATUS_MAX_ITER"]

STATUS_SOLVED = 0
STATUS_INFEASIBLE = 1
STATUS_MAX_ITER = 2


@njit(cache=True, nogil=True)
def _directions(linv, lt, c, active, q, n_plus):  # pragma: no cover - compiled
    """z = H n⁺, r = N* n⁺ and ‖(I − Q₁Q₁ᵀ) L⁻¹n⁺‖² / ‖L⁻¹n⁺‖² for the active rows
    ``active[:q]`` of ``c``, in the Cholesky frame G = LLᵀ (G–I §4: with L⁻¹N = Q₁R,
    z = L⁻ᵀ(I − Q₁Q₁ᵀ)L⁻¹n⁺ and r = R⁻¹Q₁ᵀL⁻¹n⁺)."""
    nv = linv.shape[0]
    d = linv @ n_plus
    dd = d @ d
    if q == 0:
        return lt @ d, np.zeros(0), 1.0
    nt = np.empty((nv, q))
    for j in range(q):
        nt[:, j] = linv @ c[active[j]]
    q1, rr = np.linalg.qr(nt)
    d1 = np.ascontiguousarray(q1.T) @ d
    d2 = d - np.ascontiguousarray(q1) @ d1
    r = np.linalg.solve(rr, d1)
    return lt @ d2, r, (d2 @ d2) / dd


# (q typed int64 from the start: numba otherwise types the call with it first as the literal 0
# it starts at, and compiled _directions for (..., Literal[int](0), ...) as well)
@njit(cache=True, nogil=True, locals={"q": int64})
def _solve_one(g, a, c, b, x, u, active_out, tol, max_iter):  # pragma: no cover - compiled
    """One QP by Goldfarb–Idnani (1983) §3; x, u (multipliers per row) and active_out filled."""
    nv = g.shape[0]
    m = c.shape[0]
    linv = np.linalg.inv(np.linalg.cholesky(g))
    lt = np.ascontiguousarray(linv.T)      # (contiguous: '@' on a transposed view is slow)
    x[:] = -(lt @ (linv @ a))
    u[:] = 0.0
    active = np.empty(nv + 1, dtype=np.int64)
    is_active = np.zeros(m, dtype=np.bool_)
    q = 0
    it = 0
    while True:
        # step 1: the most violated constraint (scaled by its row norm)
        p = -1
        worst = -tol
        for i in range(m):
            if is_active[i]:
                continue
            nrm = np.sqrt(np.sum(c[i] * c[i]))
            if nrm == 0.0:
                continue
            s = (c[i] @ x - b[i]) / nrm
            if s < worst:
                worst = s
                p = i
        if p < 0:
            break
        u_p = 0.0
        while True:
            it += 1
            if it > max_iter:
                active_out[:] = -1
                active_out[:q] = active[:q]
                return STATUS_MAX_ITER
            n_plus = c[p]
            z, r, free = _directions(linv, lt, c, active, q, n_plus)
            # partial step length t1: the first active multiplier reaching zero
            t1 = np.inf
            k = -1
            for j in range(q):
                if r[j] > 1e-12:
                    tj = u[active[j]] / r[j]
                    if tj < t1:
                        t1 = tj
                        k = j
            # full step length t2: constraint p satisfied with equality
            zn = z @ n_plus
            t2 = np.inf
            # z = 0 when n⁺ lies in the span of the active rows (always so when q = n)
            if q < nv and free > 1e-20:
                t2 = -(n_plus @ x - b[p]) / zn
            t = min(t1, t2)
            if t == np.inf:
                active_out[:] = -1
                active_out[:q] = active[:q]
                return STATUS_INFEASIBLE
            if t2 == np.inf:
                # step in dual space only, then drop constraint k
                for j in range(q):
                    u[active[j]] -= t * r[j]
                u_p += t
            else:
                x += t * z
                for j in range(q):
                    u[active[j]] -= t * r[j]
                u_p += t
            if t2 <= t1:
                u[p] = u_p
                active[q] = p
                is_active[p] = True
                q += 1
                break
            # drop the k-th active constraint
            dropped = active[k]
            u[dropped] = 0.0
            is_active[dropped] = False
            for j in range(k, q - 1):
                active[j] = active[j + 1]
            q -= 1
    active_out[:] = -1
    active_out[:q] = active[:q]
    return STATUS_SOLVED


@njit(cache=True, nogil=True)
def _solve_batch(g, a, c, b, tol, max_iter):  # pragma: no cover - compiled
    nb, nv = a.shape
    m = c.shape[1]
    x = np.empty((nb, nv))
    u = np.empty((nb, m))
    active = np.empty((nb, nv + 1), dtype=np.int64)
    status = np.empty(nb, dtype=np.int64)
    for k in range(nb):
        status[k] = _solve_one(g[k], a[k], c[k], b[k], x[k], u[k], active[k], tol, max_iter)
    return x, u, status


def solve_qp_batch(g, a, c, b, *, tol: float = 1e-9, max_iter: int = 0):
    """Solve min ½xᵀGx + aᵀx s.t. Cx ≥ b for each problem of a batch (Goldfarb–Idnani 1983).

    Parameters
    ----------
    g : array_like, shape (batch, n, n)
        Hessians, symmetric positive definite.
    a : array_like, shape (batch, n)
        Linear terms.
    c : array_like, shape (batch, m, n)
        Constraint rows (m ≥ 0; a row of zeros is ignored).
    b : array_like, shape (batch, m)
        Constraint bounds.
    tol : float, optional
        Violation (per unit row norm) below which a constraint counts as satisfied.
    max_iter : int, optional
        Steps allowed per problem (default 10 (n + m) + 10).

    Returns
    -------
    x : numpy.ndarray, shape (batch, n)
        The minimisers.
    multipliers : numpy.ndarray, shape (batch, m)
        Lagrange multipliers u ≥ 0 of the rows (zero for inactive rows).
    status : numpy.ndarray of int, shape (batch,)
        :data:`STATUS_SOLVED` (0), :data:`STATUS_INFEASIBLE` (1) or :data:`STATUS_MAX_ITER` (2).
    """
    # C-contiguous and writable: a read-only view (np.broadcast_to of one problem's Hessian,
    # which np.ascontiguousarray passes through) would compile _solve_batch a second time
    g, a, c, b = (np.require(v, dtype=float, requirements=("C", "W")) for v in (g, a, c, b))
    nb, nv = a.shape
    if c.ndim != 3 or c.shape[0] != nb or c.shape[2] != nv or b.shape != c.shape[:2] \
            or g.shape != (nb, nv, nv):
        raise ValueError(f"QP shapes do not fit: g {g.shape}, a {a.shape}, c {c.shape}, "
                         f"b {b.shape}")
    if not max_iter:
        max_iter = 10 * (nv + c.shape[1]) + 10
    return _solve_batch(g, a, c, b, float(tol), int(max_iter))
