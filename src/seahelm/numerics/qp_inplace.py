"""Goldfarb–Idnani's dual active-set QP without allocation, for rows of at most two nonzeros.

The same method as :mod:`seahelm.numerics.qp` (Goldfarb & Idnani 1983, *Mathematical
Programming* 27, 1–33, §3: start at the unconstrained minimum, add the most violated
constraint, partial and full steps along z = H n⁺ and r = N* n⁺), written for a compiled
closed loop that allocates nothing (the engine compiles its loop without numba's runtime):
every array is a slice of one caller-given workspace. The directions come from G⁻¹ (its
Cholesky factor, once per problem) and the Cholesky factor of S = Nᵀ G⁻¹ N of the active rows:
r = S⁻¹ Nᵀ G⁻¹ n⁺, z = G⁻¹ n⁺ − G⁻¹ N r, the same quantities as the paper's eq. (4.1)–(4.2)
(there through a QR factorisation); the test of n⁺ lying in the span of the active rows is
n⁺ᵀz / n⁺ᵀG⁻¹n⁺ (= ‖(I − Q₁Q₁ᵀ)L⁻¹n⁺‖² / ‖L⁻¹n⁺‖² of the QR form).

A constraint row k is c1 x[col] + c2 x[col + 1] ≥ b (c2 = 0: one variable), as the thrust
allocation's rows are (bounds, rate limits, an azimuth's polygon and sector half-planes).
Checked against :func:`seahelm.numerics.qp.solve_qp_batch` in tests/test_dp_control.py.
"""

from __future__ import annotations

import math

from numba import int64, njit

__all__ = ["workspace_size", "solve_qp_rows"]


def workspace_size(n_vars: int, n_rows: int) -> int:
    """Floats of workspace :func:`solve_qp_rows` needs (the rows themselves included).

    Parameters
    ----------
    n_vars : int
        Variables.
    n_rows : int
        Constraint rows at most (the capacity ``cap``).

    Returns
    -------
    int
    """
    return 6 * n_rows + 5 * n_vars * n_vars + 6 * (n_vars + 1)


@njit(cache=True)
def _chol(a, l, n, off_a, off_l):  # pragma: no cover - compiled
    """Lower Cholesky factor of the n × n matrix at a[off_a:] into l[off_l:]; False if not
    positive definite."""
    for i in range(n):
        for j in range(i + 1):
            s = a[off_a + i * n + j]
            for k in range(j):
                s -= l[off_l + i * n + k] * l[off_l + j * n + k]
            if i == j:
                if s <= 0.0:
                    return False
                l[off_l + i * n + i] = math.sqrt(s)
            else:
                l[off_l + i * n + j] = s / l[off_l + j * n + j]
        for j in range(i + 1, n):
            l[off_l + i * n + j] = 0.0
    return True


@njit(cache=True)
def _chol_solve(l, n, off_l, rhs, off_r, out, off_o):  # pragma: no cover - compiled
    """Solve L Lᵀ y = rhs (L at l[off_l:], n × n) into out[off_o:]."""
    for i in range(n):
        s = rhs[off_r + i]
        for k in range(i):
            s -= l[off_l + i * n + k] * out[off_o + k]
        out[off_o + i] = s / l[off_l + i * n + i]
    for i in range(n - 1, -1, -1):
        s = out[off_o + i]
        for k in range(i + 1, n):
            s -= l[off_l + k * n + i] * out[off_o + k]
        out[off_o + i] = s / l[off_l + i * n + i]


# (q, the active-set size, and the Hessian's offset typed int64: numba otherwise types the
# calls with them as the literal 0 they start at, compiling _chol and _chol_solve again)
@njit(cache=True, locals={"q": int64, "off_g": int64})
def solve_qp_rows(nv, m, cap, g, a, ws, x, tol, max_iter):  # pragma: no cover - compiled
    """min ½xᵀGx + aᵀx s.t. row k: c1 x[col] + c2 x[col+1] ≥ b, by Goldfarb–Idnani (see module).

    ``g`` (nv·nv, row-major, SPD) and ``a`` (nv) are read; the rows are in the workspace
    ``ws`` (:func:`workspace_size` of nv and ``cap``): ws[k] = col, ws[cap + k] = c1,
    ws[2 cap + k] = c2, ws[3 cap + k] = b for k < m ≤ cap. The solution goes to ``x`` (nv).
    Returns 0 solved, 1 infeasible, 2 too many steps (and 3: G not positive definite)."""
    big_m = cap
    o_col, o_c1, o_c2, o_b = 0, big_m, 2 * big_m, 3 * big_m
    o_mult, o_isact = 4 * big_m, 5 * big_m
    o_l = 6 * big_m
    o_ginv = o_l + nv * nv
    o_s = o_ginv + nv * nv
    o_ls = o_s + nv * nv
    o_gn = o_ls + nv * nv                  # column j (of the active rows) at o_gn + j·nv
    o_act = o_gn + nv * nv
    o_v = o_act + nv + 1                   # G⁻¹ n⁺
    o_w = o_v + nv + 1                     # Nᵀ G⁻¹ n⁺
    o_r = o_w + nv + 1
    o_z = o_r + nv + 1
    o_e = o_z + nv + 1                     # a unit vector
    off_g = 0
    if not _chol(g, ws, nv, off_g, o_l):
        return 3
    for j in range(nv):                    # G⁻¹, column by column
        for i in range(nv):
            ws[o_e + i] = 0.0
        ws[o_e + j] = 1.0
        _chol_solve(ws, nv, o_l, ws, o_e, ws, o_v)
        for i in range(nv):
            ws[o_ginv + i * nv + j] = ws[o_v + i]
    for i in range(nv):
        s = 0.0
        for j in range(nv):
            s += ws[o_ginv + i * nv + j] * a[j]
        x[i] = -s
    for k in range(m):
        ws[o_mult + k] = 0.0
        ws[o_isact + k] = 0.0
    q = 0
    it = 0
    while True:
        p = -1
        worst = -tol
        for k in range(m):
            if ws[o_isact + k] > 0.5:
                continue
            col = int(ws[o_col + k])
            c1, c2 = ws[o_c1 + k], ws[o_c2 + k]
            nrm = math.sqrt(c1 * c1 + c2 * c2)
            if nrm == 0.0:
                continue
            val = c1 * x[col] + (c2 * x[col + 1] if c2 != 0.0 else 0.0) - ws[o_b + k]
            sv = val / nrm
            if sv < worst:
                worst = sv
                p = k
        if p < 0:
            return 0
        u_p = 0.0
        pcol = int(ws[o_col + p])
        pc1, pc2 = ws[o_c1 + p], ws[o_c2 + p]
        while True:
            it += 1
            if it > max_iter:
                return 2
            # v = G⁻¹ n⁺
            for i in range(nv):
                v = ws[o_ginv + i * nv + pcol] * pc1
                if pc2 != 0.0:
                    v += ws[o_ginv + i * nv + pcol + 1] * pc2
                ws[o_v + i] = v
            for i in range(nv):
                ws[o_z + i] = ws[o_v + i]
            if q > 0:
                for j in range(q):              # w_j = n_jᵀ v, S_ij = n_iᵀ G⁻¹ n_j
                    kj = int(ws[o_act + j])
                    cj = int(ws[o_col + kj])
                    w = ws[o_c1 + kj] * ws[o_v + cj]
                    if ws[o_c2 + kj] != 0.0:
                        w += ws[o_c2 + kj] * ws[o_v + cj + 1]
                    ws[o_w + j] = w
                    for i in range(q):
                        ki = int(ws[o_act + i])
                        ci = int(ws[o_col + ki])
                        sij = ws[o_c1 + ki] * ws[o_gn + j * nv + ci]
                        if ws[o_c2 + ki] != 0.0:
                            sij += ws[o_c2 + ki] * ws[o_gn + j * nv + ci + 1]
                        ws[o_s + i * q + j] = sij
                if not _chol(ws, ws, q, o_s, o_ls):
                    return 3
                _chol_solve(ws, q, o_ls, ws, o_w, ws, o_r)
                for j in range(q):
                    rj = ws[o_r + j]
                    for i in range(nv):
                        ws[o_z + i] -= rj * ws[o_gn + j * nv + i]
            zn = pc1 * ws[o_z + pcol] + (pc2 * ws[o_z + pcol + 1] if pc2 != 0.0 else 0.0)
            vn = pc1 * ws[o_v + pcol] + (pc2 * ws[o_v + pcol + 1] if pc2 != 0.0 else 0.0)
            free = zn / vn if vn > 0.0 else 0.0
            t1 = math.inf
            kk = -1
            for j in range(q):
                rj = ws[o_r + j]
                if rj > 1e-12:
                    tj = ws[o_mult + int(ws[o_act + j])] / rj
                    if tj < t1:
                        t1 = tj
                        kk = j
            t2 = math.inf
            if q < nv and free > 1e-20:
                val = pc1 * x[pcol] + (pc2 * x[pcol + 1] if pc2 != 0.0 else 0.0) - ws[o_b + p]
                t2 = -val / zn
            t = min(t1, t2)
            if t == math.inf:
                return 1
            if t2 != math.inf:
                for i in range(nv):
                    x[i] += t * ws[o_z + i]
            for j in range(q):
                ws[o_mult + int(ws[o_act + j])] -= t * ws[o_r + j]
            u_p += t
            if t2 <= t1:
                ws[o_mult + p] = u_p
                ws[o_act + q] = p
                ws[o_isact + p] = 1.0
                for i in range(nv):
                    ws[o_gn + q * nv + i] = ws[o_v + i]
                q += 1
                break
            dropped = int(ws[o_act + kk])
            ws[o_mult + dropped] = 0.0
            ws[o_isact + dropped] = 0.0
            for j in range(kk, q - 1):
                ws[o_act + j] = ws[o_act + j + 1]
                for i in range(nv):
                    ws[o_gn + j * nv + i] = ws[o_gn + (j + 1) * nv + i]
            q -= 1
