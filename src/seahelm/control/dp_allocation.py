"""Constrained thrust allocation for dynamic positioning (surge, sway, yaw), batched.

The allocation problem of a horizontal-plane thruster layout, at each control step (Johansen &
Fossen 2013, "Control allocation — a survey", *Automatica* 49(5), §2.2 and §3.1 — the
quadratic-programming formulation with slack)::

    minimise   Σ_j w_j u_j²  +  ρ ‖S s‖²
    subject to B f + s = τ_c,   u_j = f_j / T_max(j),   f within the thrusters' limits

* **variables**: a fixed-direction thruster (tunnel, main propeller) has one, its thrust f_i
  along its direction α_i (negative astern, down to ``min_thrust``); an azimuth thruster two,
  its force components (f_x, f_y) in the body frame — the "extended thrust" form that makes
  the configuration matrix B constant (Johansen & Fossen 2013, §2.2.2).
* **minimum power**: the quadratic Σ w_j (f_j/T_max)² — the usual convex stand-in for the
  power Σ abs(f)^{3/2} (Johansen & Fossen 2013, §2.2.1); ``weights`` w (default 1) penalise a
  thruster's use.
* **thrust bounds**: min_thrust ≤ f_i ≤ max_thrust for a fixed thruster; for an azimuth the
  disc |f| ≤ max_thrust as the inscribed regular polygon of ``polygon_sides`` sides
  (cos(π/M) of the rating on the flats: 0.995 for M = 32), thrust ahead only.
* **rate limits** (given the previous thrusts, azimuths and the step dt): abs(f − f_prev) ≤ Ṫ dt
  for a fixed thruster; each force component of an azimuth within Ṫ dt/√2 of its previous
  value (a box inside the disc of radius Ṫ dt); the azimuth within α_prev ± α̇ dt.
* **forbidden sectors** (the fixed-azimuth linearisation): the azimuth's admissible directions
  this step are the allowed arc that holds α_prev, cut to α_prev ± α̇ dt; when that wedge is at
  most 180° it is the two half-planes of its edges, otherwise the half-plane centred as near
  α_prev as the wedge allows (a convex inner part of the wedge). Without a previous azimuth
  (a static capability), the caller chooses the allowed arc (:meth:`ConstrainedAllocation.
  pieces` lists the convex pieces).
* **unmet demand**: the slack s = τ_c − B f, weighted by ρ (``slack_weight``, default 1e6) in
  the scaled units S (force rows / Σ T_max, the yaw row / (Σ T_max · L_ref)), so a demand the
  thrusters can meet leaves s ≈ 0 (of the order of 1/ρ of the demand) and one they cannot
  leaves the least-squares rest, reported in N and N·m.

Eliminating s gives a strictly convex QP in u alone, solved by the compiled Goldfarb–Idnani
dual active-set method (:func:`seahelm.numerics.qp.solve_qp_batch`), one demand per batch
element. Checked against Clarabel (through qpsolvers) in tests/test_dp_allocation.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..numerics.qp import STATUS_SOLVED, solve_qp_batch
from .thruster_layout import ThrusterLayout

__all__ = ["ThrusterLayout", "ConstrainedAllocation", "AllocationResult", "DP_DOFS"]

#: The controlled generalized forces, in τ order.
DP_DOFS: tuple[str, ...] = ("surge", "sway", "yaw")
_TWO_PI = 2.0 * math.pi


def _wrap(a):
    return np.mod(a, _TWO_PI)


@dataclass
class AllocationResult:
    """What the allocation gives for a batch of demands (arrays, batch first)."""

    #: force of each thruster [N], shape (batch, n, 2): body x and y components
    force: np.ndarray
    #: thrust magnitude [N] (signed along the direction for a fixed thruster), (batch, n)
    thrust: np.ndarray
    #: direction [rad] of each thruster, (batch, n) (an azimuth at zero thrust keeps α_prev)
    azimuth: np.ndarray
    #: the demand not met, τ_c − B f [N, N, N·m], (batch, 3)
    unmet: np.ndarray
    #: solver status per demand (0 solved)
    status: np.ndarray
    #: the QP's value per demand (scaled units)
    objective: np.ndarray


class ConstrainedAllocation:
    """Constrained, minimum-power thrust allocation of (surge, sway, yaw) demands (see module).

    Parameters
    ----------
    layout : ThrusterLayout
    weights : array_like, optional
        One per thruster (> 0; default 1): the power weight of each.
    slack_weight : float, optional
        ρ, the weight of the unmet demand in scaled units (default 1e6).
    polygon_sides : int, optional
        Sides of the polygon inscribed in an azimuth's thrust disc (default 32, ≥ 8).

    Raises
    ------
    ParameterError
        Configuration matrix of rank below 3 (the layout cannot produce every surge, sway and
        yaw), weights not > 0.
    """

    def __init__(self, layout: ThrusterLayout, *, weights: Any = None,
                 slack_weight: float = 1e6, polygon_sides: int = 32) -> None:
        n = layout.count
        w = np.ones(n) if weights is None else np.asarray(weights, dtype=float).reshape(-1)
        if w.shape != (n,) or not np.all(np.isfinite(w) & (w > 0)):
            raise ParameterError(f"must be {n} numbers > 0 [-], got {weights!r}",
                                 field="weights", unit="-")
        if not (slack_weight > 0 and math.isfinite(slack_weight)):
            raise ParameterError(f"must be > 0 [-], got {slack_weight!r}",
                                 field="slack_weight", unit="-", value=slack_weight)
        if int(polygon_sides) < 8:
            raise ParameterError(f"must be ≥ 8 [-], got {polygon_sides!r}",
                                 field="polygon_sides", unit="-", value=polygon_sides)
        self.layout = layout
        self.polygon_sides = int(polygon_sides)
        self.slack_weight = float(slack_weight)
        tmax = np.asarray(layout.max_thrust, dtype=float)
        self._tmax = tmax
        cols, owner, scale, wv = [], [], [], []
        for i in range(n):
            x, y = float(layout.x[i]), float(layout.y[i])
            dirs = ((1.0, 0.0), (0.0, 1.0)) if layout.azimuthing[i] else \
                ((math.cos(layout.direction[i]), math.sin(layout.direction[i])),)
            for cx, cy in dirs:
                cols.append((cx, cy, x * cy - y * cx))
                owner.append(i)
                scale.append(tmax[i])
                wv.append(w[i])
        #: the configuration matrix B (3 × variables) of forces [N] per unit variable [N]
        self.matrix = np.array(cols, dtype=float).T
        self._owner = np.array(owner)
        self._scale = np.array(scale)
        self._w = np.array(wv)
        rank = int(np.linalg.matrix_rank(self.matrix))
        if rank < 3:
            raise ParameterError(
                f": the configuration matrix of the layout has rank {rank} [-], below the 3 "
                "controlled DOF (surge, sway, yaw): some demand cannot be produced",
                field="thrusters", unit="-", value=rank)
        f_ref = float(tmax.sum())
        l_ref = max(1.0, float(np.max(np.hypot(layout.x, layout.y))))
        #: the scaling S of the demand rows (1/N, 1/N, 1/(N·m))
        self.demand_scale = np.array([1.0 / f_ref, 1.0 / f_ref, 1.0 / (f_ref * l_ref)])
        bs = self.demand_scale[:, None] * self.matrix * self._scale[None, :]
        self._bs = bs
        self._g = np.diag(self._w) + self.slack_weight * bs.T @ bs

    # -- the QP ----------------------------------------------------------------------------
    def pieces(self) -> list[list[tuple[float, float]]]:
        """Per thruster, the convex pieces (≤ 180°) of its allowed arcs [rad] (one (0, 2π) piece
        for an azimuth without forbidden sectors or for a fixed thruster)."""
        out = []
        for i in range(self.layout.count):
            if not self.layout.azimuthing[i] or not self.layout.forbidden[i]:
                out.append([(0.0, _TWO_PI)])
                continue
            ps = []
            for a, b in self.layout.allowed_arcs(i):
                k = max(1, math.ceil((b - a) / math.pi - 1e-12))
                edges = np.linspace(a, b, k + 1)
                ps.extend((float(edges[j]), float(edges[j + 1])) for j in range(k))
            out.append(ps)
        return out

    def problem(self, tau: Any, *, wedges: Any = None, previous_force: Any = None,
                thrust_step: Any = None):
        """The QP min ½uᵀGu + aᵀu s.t. Cu ≥ b for each demand (scaled variables u = f/T_max).

        Parameters
        ----------
        tau : array_like, shape (batch, 3)
            Demands [N, N, N·m].
        wedges : array_like, shape (batch, n, 2) or (batch, n, 3), optional
            Admissible azimuth interval (lo, hi) [rad] per azimuth thruster (hi − lo ≥ 2π: no
            constraint), and for a wedge over 180° the centre of the half-plane used (default
            the middle; kept within [lo + π/2, hi − π/2]); ignored for fixed thrusters.
        previous_force : array_like, shape (batch, n, 2), optional
            Previous force components [N] (with ``thrust_step``).
        thrust_step : array_like, shape (n,), optional
            Ṫ dt [N]: the largest thrust change this step.

        Returns
        -------
        g, a, c, b : numpy.ndarray
            Shapes (batch, v, v), (batch, v), (batch, m, v), (batch, m).
        """
        tau = np.atleast_2d(np.asarray(tau, dtype=float))
        if tau.shape[-1] != 3:
            raise ParameterError(f"must hold (surge, sway, yaw) demands, got shape "
                                 f"{tau.shape}", field="tau")
        nb = tau.shape[0]
        lay = self.layout
        nv = self.matrix.shape[1]
        ms = self.polygon_sides
        rows_c, rows_b = [], []          # lists of (batch, v) / (batch,) arrays
        col = 0
        ang = np.arange(ms) * (_TWO_PI / ms)
        inner = math.cos(math.pi / ms)
        for i in range(lay.count):
            tmax = self._tmax[i]
            if not lay.azimuthing[i]:
                e = np.zeros(nv)
                e[col] = 1.0
                rows_c += [np.broadcast_to(e, (nb, nv)), np.broadcast_to(-e, (nb, nv))]
                rows_b += [np.full(nb, lay.min_thrust[i] / tmax), np.full(nb, -1.0)]
                if thrust_step is not None and previous_force is not None:
                    pf = np.asarray(previous_force, dtype=float)[:, i, :]
                    d = (math.cos(lay.direction[i]), math.sin(lay.direction[i]))
                    fp = (pf[:, 0] * d[0] + pf[:, 1] * d[1]) / tmax
                    st = float(thrust_step[i]) / tmax
                    rows_c += [np.broadcast_to(e, (nb, nv)), np.broadcast_to(-e, (nb, nv))]
                    rows_b += [fp - st, -(fp + st)]
                col += 1
                continue
            for th in ang:              # polygon: −(cos θ u_x + sin θ u_y) ≥ −cos(π/M)
                e = np.zeros(nv)
                e[col], e[col + 1] = -math.cos(th), -math.sin(th)
                rows_c.append(np.broadcast_to(e, (nb, nv)))
                rows_b.append(np.full(nb, -inner))
            if wedges is not None:
                wd = np.asarray(wedges, dtype=float)[:, i, :]
                lo, hi = wd[:, 0], wd[:, 1]
                width = hi - lo
                half = width <= math.pi + 1e-12
                none = width >= _TWO_PI - 1e-12
                # ≤ 180°: left of the lo edge and right of the hi edge
                c1 = np.zeros((nb, nv))
                c2 = np.zeros((nb, nv))
                c1[:, col], c1[:, col + 1] = -np.sin(lo), np.cos(lo)
                c2[:, col], c2[:, col + 1] = np.sin(hi), -np.cos(hi)
                # > 180°: one half-plane centred in [lo + 90°, hi − 90°] (the given centre)
                mid = wd[:, 2] if wd.shape[1] > 2 else 0.5 * (lo + hi)
                c3 = np.zeros((nb, nv))
                c3[:, col], c3[:, col + 1] = np.cos(mid), np.sin(mid)
                c1 = np.where(half[:, None], c1, c3)
                c2 = np.where(half[:, None], c2, 0.0)
                c1 = np.where(none[:, None], 0.0, c1)
                c2 = np.where(none[:, None], 0.0, c2)
                rows_c += [c1, c2]
                rows_b += [np.zeros(nb), np.zeros(nb)]
            if thrust_step is not None and previous_force is not None:
                pf = np.asarray(previous_force, dtype=float)[:, i, :] / tmax
                st = float(thrust_step[i]) / tmax / math.sqrt(2.0)
                for j in range(2):
                    e = np.zeros(nv)
                    e[col + j] = 1.0
                    rows_c += [np.broadcast_to(e, (nb, nv)), np.broadcast_to(-e, (nb, nv))]
                    rows_b += [pf[:, j] - st, -(pf[:, j] + st)]
            col += 2
        c = np.stack(rows_c, axis=1) if rows_c else np.zeros((nb, 0, nv))
        b = np.stack(rows_b, axis=1) if rows_b else np.zeros((nb, 0))
        g = np.broadcast_to(self._g, (nb, nv, nv))
        a = -self.slack_weight * (tau * self.demand_scale[None, :]) @ self._bs
        return np.ascontiguousarray(g), a, np.ascontiguousarray(c), np.ascontiguousarray(b)

    def _polish(self, tau, u, mult, status, c, b):
        """Meet a demand the QP found feasible exactly: on the QP's active rows, solve
        min Σ w u² s.t. B_s u = S τ and the active rows as equalities (the KKT system); keep
        it where it satisfies every row (to 1e-9) — then the unmet demand is zero to
        round-off instead of O(1/ρ)."""
        nv = u.shape[1]
        ts = tau * self.demand_scale[None, :]
        w = np.diag(self._w)
        out = u.copy()
        for k in range(u.shape[0]):
            if status[k] != STATUS_SOLVED:
                continue
            rest = ts[k] - self._bs @ u[k]
            if np.max(np.abs(rest)) > 1e-3:          # a demand beyond the thrusters: keep
                continue
            act = np.flatnonzero(mult[k] > 0.0)
            eq = np.vstack([self._bs, c[k][act]])
            rhs = np.concatenate([ts[k], b[k][act]])
            ne = eq.shape[0]
            if ne > nv:
                continue
            kkt = np.zeros((nv + ne, nv + ne))
            kkt[:nv, :nv] = w
            kkt[:nv, nv:] = eq.T
            kkt[nv:, :nv] = eq
            try:
                sol = np.linalg.solve(kkt, np.concatenate([np.zeros(nv), rhs]))
            except np.linalg.LinAlgError:
                continue
            x = sol[:nv]
            if np.all(c[k] @ x - b[k] >= -1e-9) and np.all(np.isfinite(x)):
                out[k] = x
        return out

    def _result(self, tau, u, status, g, a, prev_azimuth=None) -> AllocationResult:
        lay = self.layout
        nb = tau.shape[0]
        f = u * self._scale[None, :]
        force = np.zeros((nb, lay.count, 2))
        thrust = np.zeros((nb, lay.count))
        azimuth = np.zeros((nb, lay.count))
        col = 0
        for i in range(lay.count):
            if lay.azimuthing[i]:
                force[:, i, :] = f[:, col:col + 2]
                thrust[:, i] = np.hypot(f[:, col], f[:, col + 1])
                default = (np.full(nb, lay.direction[i]) if prev_azimuth is None
                           else np.asarray(prev_azimuth, dtype=float)[:, i])
                azimuth[:, i] = np.where(thrust[:, i] > 1e-9 * self._tmax[i],
                                         _wrap(np.arctan2(f[:, col + 1], f[:, col])), default)
                col += 2
            else:
                d = lay.direction[i]
                force[:, i, 0], force[:, i, 1] = f[:, col] * math.cos(d), f[:, col] * math.sin(d)
                thrust[:, i] = f[:, col]
                azimuth[:, i] = d
                col += 1
        unmet = tau - f @ self.matrix.T
        obj = 0.5 * np.einsum("bi,bij,bj->b", u, g, u) + np.einsum("bi,bi->b", a, u)
        return AllocationResult(force, thrust, azimuth, unmet, status, obj)

    def allocate(self, tau: Any, *, previous_thrust: Any = None, previous_azimuth: Any = None,
                 dt: float | None = None, thrust_rate: Any = None,
                 azimuth_rate: Any = None, polish: bool = True) -> AllocationResult:
        """Allocate a batch of demands, one QP each (rate limits when the previous state is given).

        Parameters
        ----------
        tau : array_like, shape (batch, 3) or (3,)
            Demands (surge [N], sway [N], yaw [N·m]).
        previous_thrust, previous_azimuth : array_like, shape (batch, n), optional
            The thrusters' previous thrust [N] and direction [rad] (for the rate limits and
            the forbidden sectors' linearisation; default: zero thrust at ``direction``).
        dt : float, optional
            Control step [s] (with the rates).
        thrust_rate : array_like, shape (n,), optional
            Largest thrust rate Ṫ [N/s] per thruster (default: none).
        azimuth_rate : array_like, shape (n,), optional
            Largest azimuth rate α̇ [rad/s] per thruster (default: none).
        polish : bool, optional
            Meet a feasible demand exactly on the QP's active set (default True; see
            :meth:`_polish`); False gives the QP's own answer (unmet ~ 1/ρ of the demand).

        Returns
        -------
        AllocationResult
        """
        tau = np.atleast_2d(np.asarray(tau, dtype=float))
        nb = tau.shape[0]
        lay = self.layout
        n = lay.count
        if dt is not None and not (dt > 0 and math.isfinite(dt)):
            raise ParameterError(f"must be > 0 [s], got {dt!r}", field="dt", unit="s",
                                 value=dt)
        pt = np.zeros((nb, n)) if previous_thrust is None else \
            np.broadcast_to(np.asarray(previous_thrust, dtype=float), (nb, n))
        pa = np.broadcast_to(np.asarray(lay.direction, dtype=float), (nb, n)) \
            if previous_azimuth is None else \
            np.broadcast_to(np.asarray(previous_azimuth, dtype=float), (nb, n))
        pa = _wrap(pa)
        prev_force = np.stack([pt * np.cos(pa), pt * np.sin(pa)], axis=-1)
        step = None
        if thrust_rate is not None:
            if dt is None:
                raise ParameterError("needs `dt` [s]", field="thrust_rate", unit="N/s")
            rate = np.broadcast_to(np.asarray(thrust_rate, dtype=float), (n,))
            if np.any(rate <= 0):
                raise ParameterError(f"must be > 0 [N/s], got {list(rate)}",
                                     field="thrust_rate", unit="N/s")
            step = rate * dt
        az_step = np.full(n, np.inf)
        if azimuth_rate is not None:
            if dt is None:
                raise ParameterError("needs `dt` [s]", field="azimuth_rate", unit="rad/s")
            ar = np.broadcast_to(np.asarray(azimuth_rate, dtype=float), (n,))
            if np.any(ar <= 0):
                raise ParameterError(f"must be > 0 [rad/s], got {list(ar)}",
                                     field="azimuth_rate", unit="rad/s")
            az_step = ar * dt
        wedges = np.zeros((nb, n, 3))
        wedges[:, :, 1] = _TWO_PI
        for i in range(n):
            if not lay.azimuthing[i]:
                continue
            arcs = lay.allowed_arcs(i)
            for k in range(nb):
                lo, hi, a0 = _arc_holding(arcs, pa[k, i])
                if math.isfinite(az_step[i]) and 2 * az_step[i] < _TWO_PI:
                    lo, hi = max(lo, a0 - az_step[i]), min(hi, a0 + az_step[i])
                centre = min(max(a0, lo + 0.5 * math.pi), hi - 0.5 * math.pi)
                wedges[k, i] = (lo, hi, centre)
        g, a, c, b = self.problem(tau, wedges=wedges, previous_force=prev_force,
                                  thrust_step=step)
        u, mult, status = solve_qp_batch(g, a, c, b)
        if polish:
            u = self._polish(tau, u, mult, status, c, b)
        return self._result(tau, u, status, g, a, pa)

    def capacity(self, tau: Any, *, polish: bool = True) -> AllocationResult:
        """Static allocation (no previous state, no rates): the best over the convex pieces of
        the azimuths' allowed arcs (every combination), for each demand.

        Parameters
        ----------
        tau : array_like, shape (batch, 3)
        polish : bool, optional
            As for :meth:`allocate`.

        Returns
        -------
        AllocationResult
            For each demand the combination with the least objective.
        """
        tau = np.atleast_2d(np.asarray(tau, dtype=float))
        nb = tau.shape[0]
        pieces = self.pieces()
        combos = np.array(np.meshgrid(*[np.arange(len(p)) for p in pieces], indexing="ij"))
        combos = combos.reshape(len(pieces), -1).T
        nc = combos.shape[0]
        wedges = np.zeros((nc, self.layout.count, 2))
        for k, combo in enumerate(combos):
            for i, j in enumerate(combo):
                wedges[k, i] = pieces[i][j]
        tt = np.repeat(tau, nc, axis=0)
        ww = np.tile(wedges, (nb, 1, 1))
        g, a, c, b = self.problem(tt, wedges=ww)
        u, mult, status = solve_qp_batch(g, a, c, b)
        if polish:
            u = self._polish(tt, u, mult, status, c, b)
        res = self._result(tt, u, status, g, a)
        obj = np.where(status == STATUS_SOLVED, res.objective, np.inf).reshape(nb, nc)
        best = np.argmin(obj, axis=1) + np.arange(nb) * nc
        return AllocationResult(res.force[best], res.thrust[best], res.azimuth[best],
                                res.unmet[best], res.status[best], res.objective[best])


def _arc_holding(arcs, a0):
    """The allowed arc (lo, hi) holding a0 ∈ [0, 2π), unrolled so that lo ≤ a0 ≤ hi, and a0;
    the nearest arc's near edge (a zero-width wedge, and that edge) when a0 is forbidden."""
    best, dist = None, np.inf
    for lo, hi in arcs:
        for shift in (0.0, _TWO_PI, -_TWO_PI):
            a = a0 + shift
            if lo <= a <= hi:
                if hi - lo >= _TWO_PI - 1e-12:
                    return a0 - math.pi, a0 + math.pi, a0
                return lo - shift, hi - shift, a0
            d = min(abs(a - lo), abs(a - hi))
            if d < dist:
                e = lo if abs(a - lo) <= abs(a - hi) else hi
                best, dist = (e - shift, e - shift, e - shift), d
    return best
