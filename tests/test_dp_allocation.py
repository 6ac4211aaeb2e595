"""Constrained DP thrust allocation: the compiled Goldfarb–Idnani QP against Clarabel, and the
allocation's constraints, unmet demand and bad input."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from seahelm.control.dp_allocation import ConstrainedAllocation, ThrusterLayout
from seahelm.errors import ParameterError
from seahelm.numerics.qp import STATUS_INFEASIBLE, STATUS_SOLVED, solve_qp_batch

qpsolvers = pytest.importorskip("qpsolvers")


def _reference(g, a, c, b):
    """Clarabel (interior point) through qpsolvers: min ½xᵀGx + aᵀx s.t. −Cx ≤ −b."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return qpsolvers.solve_qp(g, a, -c, -b, solver="clarabel", tol_gap_abs=1e-13,
                                  tol_gap_rel=1e-13, tol_feas=1e-13)


def test_qp_against_clarabel_on_random_problems():
    rng = np.random.default_rng(7)
    nb, n, m = 250, 7, 18
    f = rng.normal(size=(nb, n, n))
    g = f @ f.transpose(0, 2, 1) + 0.3 * np.eye(n)
    a = rng.normal(size=(nb, n))
    c = rng.normal(size=(nb, m, n))
    b = rng.normal(size=(nb, m)) - 1.0
    x, mult, status = solve_qp_batch(g, a, c, b)
    solved = infeasible = 0
    for k in range(nb):
        ref = _reference(g[k], a[k], c[k], b[k])
        if ref is None:
            assert status[k] == STATUS_INFEASIBLE, k
            infeasible += 1
            continue
        assert status[k] == STATUS_SOLVED, k
        np.testing.assert_allclose(x[k], ref, atol=1e-6, rtol=0)
        assert np.all(c[k] @ x[k] - b[k] >= -1e-9)
        assert np.all(mult[k] >= 0)
        solved += 1
    assert solved > 150 and infeasible > 5      # both outcomes exercised


def _random_layout(rng):
    n = int(rng.integers(3, 7))
    az = rng.random(n) < 0.5
    az[0] = True                                # at least one azimuth
    x = rng.uniform(-40, 40, n)
    y = rng.uniform(-8, 8, n)
    direction = rng.choice([0.0, math.pi / 2, math.pi], n)
    tmax = rng.uniform(5e4, 3e5, n)
    tmin = np.where(rng.random(n) < 0.5, -tmax, -0.6 * tmax)
    forb = []
    for i in range(n):
        if az[i] and rng.random() < 0.5:
            s = rng.uniform(0, 2 * math.pi)
            forb.append(((s, s + rng.uniform(0.2, 1.5)),))
        else:
            forb.append(())
    return ThrusterLayout(tuple(f"t{i}" for i in range(n)), tuple(x), tuple(y),
                          tuple(direction), tuple(bool(v) for v in az), tuple(tmax),
                          tuple(tmin), tuple(forb))


@pytest.mark.parametrize("slack_weight", [1e4, 1e6])
def test_allocation_qp_against_clarabel_on_random_layouts_and_demands(slack_weight):
    """≥ 200 demands over random layouts, with and without rate limits: the allocation's QP
    solved by the compiled solver and by Clarabel agree to 1e-6 (scaled thrust f/T_max) with
    ρ = 1e4; with the default ρ = 1e6 (Hessian condition ~1e6, where Clarabel's own answer
    is off by ~1e-4 along the flat directions, its objective sometimes above ours) the
    objectives agree to 1e-8 relative; ours is feasible to 1e-9 in both."""
    rng = np.random.default_rng(11)
    checked = 0
    for _ in range(25):
        while True:
            lay = _random_layout(rng)
            try:
                alloc = ConstrainedAllocation(lay, slack_weight=slack_weight)
                break
            except ParameterError:
                continue
        n = lay.count
        cap = float(np.sum(lay.max_thrust))
        tau = rng.normal(size=(10, 3)) * np.array([0.5 * cap, 0.5 * cap, 10 * cap])
        prev_t = rng.uniform(0.0, 0.5, (10, n)) * np.asarray(lay.max_thrust)
        prev_a = rng.uniform(0, 2 * math.pi, (10, n))
        rated = rng.random() < 0.5
        kw = dict(previous_thrust=prev_t, previous_azimuth=prev_a, dt=0.5,
                  thrust_rate=0.3 * np.asarray(lay.max_thrust), azimuth_rate=0.2) if rated \
            else {}
        res = alloc.allocate(tau, polish=False, **kw)
        # rebuild the same QPs to hand them to the reference
        captured = {}
        orig = alloc.problem

        def spy(*args, **kwargs):
            captured["qp"] = orig(*args, **kwargs)
            return captured["qp"]

        alloc.problem = spy
        res2 = alloc.allocate(tau, polish=False, **kw)
        del alloc.problem
        np.testing.assert_array_equal(res.force, res2.force)
        g, a, c, b = captured["qp"]
        for k in range(len(tau)):
            ref = _reference(g[k], a[k], c[k], b[k])
            if ref is None:
                continue            # a rate box that misses the forbidden wedge: no point
            assert res.status[k] == STATUS_SOLVED
            u = res.force[k]
            ours = _scaled_variables(alloc, u)
            if slack_weight <= 1e4:
                np.testing.assert_allclose(ours, ref, atol=1e-6, rtol=0)
            else:
                def obj(x):
                    return 0.5 * x @ g[k] @ x + a[k] @ x
                assert obj(ours) == pytest.approx(obj(ref), rel=1e-8, abs=1e-12)
            assert np.all(c[k] @ ours - b[k] >= -1e-9)
            checked += 1
    assert checked >= 200


def _scaled_variables(alloc, force):
    out = []
    for i in range(alloc.layout.count):
        t = alloc.layout.max_thrust[i]
        if alloc.layout.azimuthing[i]:
            out += [force[i, 0] / t, force[i, 1] / t]
        else:
            d = alloc.layout.direction[i]
            out.append((force[i, 0] * math.cos(d) + force[i, 1] * math.sin(d)) / t)
    return np.array(out)


def _tunnel_layout(forbidden=()):
    # two stern azimuths and a bow tunnel thruster
    return ThrusterLayout(("bow", "port", "stbd"), (30.0, -30.0, -30.0), (0.0, -5.0, 5.0),
                          (math.pi / 2, 0.0, 0.0), (False, True, True), (1e5, 2e5, 2e5),
                          None, ((), forbidden, ()))


def test_feasible_demand_is_met_and_bounds_hold():
    alloc = ConstrainedAllocation(_tunnel_layout())
    tau = np.array([[1e5, 5e4, 1e6], [-2e5, 0.0, 0.0], [0.0, 1e5, -2e6]])
    res = alloc.allocate(tau)
    assert np.all(res.status == STATUS_SOLVED)
    # met exactly (polished on the active set) ...
    np.testing.assert_allclose(res.unmet / np.array([5e5, 5e5, 5e5 * 30.4]), 0.0, atol=1e-12)
    # ... and by the QP alone up to the slack weight's 1/ρ (ρ = 1e6 in scaled units)
    raw = alloc.allocate(tau, polish=False)
    np.testing.assert_allclose(raw.unmet / np.array([5e5, 5e5, 5e5 * 30.4]), 0.0, atol=1e-5)
    np.testing.assert_allclose(raw.force, res.force, rtol=0, atol=1e-5 * 2e5)
    assert np.all(np.abs(res.thrust[:, 0]) <= 1e5 * (1 + 1e-9))
    assert np.all(res.thrust[:, 1:] <= 2e5 * (1 + 1e-9))


def test_infeasible_demand_reports_the_rest():
    """A surge demand beyond the two azimuths' 2 × 2e5 N (the polygon's flats: cos(π/32) of it)
    leaves the rest unmet."""
    alloc = ConstrainedAllocation(_tunnel_layout())
    res = alloc.allocate([[1e6, 0.0, 0.0]])
    most = 2 * 2e5 * math.cos(math.pi / 32)
    assert res.unmet[0, 0] == pytest.approx(1e6 - most, rel=1e-4)
    assert abs(res.unmet[0, 1]) < 1.0 and abs(res.unmet[0, 2]) < 30.0


def test_rate_limits_bound_the_step():
    alloc = ConstrainedAllocation(_tunnel_layout())
    prev_t = np.array([[0.0, 1e5, 1e5]])
    prev_a = np.zeros((1, 3))
    res = alloc.allocate([[0.0, 3e5, 0.0]], previous_thrust=prev_t, previous_azimuth=prev_a,
                         dt=0.1, thrust_rate=1e5, azimuth_rate=0.3)
    assert abs(res.thrust[0, 0]) <= 1e4 * (1 + 1e-9)                # Ṫ dt
    assert np.all(np.abs(res.azimuth[0, 1:]) <= 0.03 + 1e-9)         # α̇ dt
    step = np.hypot(res.force[0, 1:, 0] - 1e5, res.force[0, 1:, 1])
    assert np.all(step <= 1e4 * (1 + 1e-9))


def test_forbidden_sector_is_avoided():
    sector = (math.radians(60), math.radians(120))
    alloc = ConstrainedAllocation(_tunnel_layout((sector,)))
    free = ConstrainedAllocation(_tunnel_layout())
    tau = [[0.0, 2e5, -4e6]]
    f_free = free.capacity(tau)
    assert 60 < math.degrees(f_free.azimuth[0, 1]) < 120               # it would go there
    res = alloc.capacity(tau)
    az = math.degrees(res.azimuth[0, 1]) % 360
    assert az == pytest.approx(60.0, abs=1e-6)                      # on the sector's edge
    assert np.all(np.abs(res.unmet) < np.array([1e-6, 1e-6, 1e-4]))  # still met
    # the linearised step from an azimuth at 50° stays in the allowed arc holding it
    res = alloc.allocate(tau, previous_azimuth=[[math.pi / 2, math.radians(50), 0.0]])
    az = math.degrees(res.azimuth[0, 1]) % 360
    assert az <= 60 + 1e-6 or res.thrust[0, 1] < 1e-6


def test_bad_input():
    with pytest.raises(ParameterError, match="rank 2"):
        ConstrainedAllocation(ThrusterLayout(("a", "b"), (0.0, 0.0), (0.0, 0.0), (0.0, 0.0),
                                             (True, True), (1e5, 1e5)))
    with pytest.raises(ParameterError, match="cover 360"):
        _tunnel_layout(((0.0, math.pi), (math.pi - 0.1, 2 * math.pi + 0.05)))
    with pytest.raises(ParameterError, match="names no thruster"):
        _tunnel_layout().without("aft")
    with pytest.raises(ParameterError, match="max_thrust"):
        ThrusterLayout(("a",), (0.0,), (0.0,), (0.0,), (True,), (0.0,))


def test_read_only_problems_compile_no_second_qp_kernel():
    """One allocation demand makes the Hessian a read-only np.broadcast_to view (issue 47 item
    7): the QP kernel must not compile a read-only signature for it (it cost a second compile
    of _solve_batch in the suite). Same answer, bit for bit, from read-only and writable input."""
    from seahelm.numerics import qp

    rng = np.random.default_rng(3)
    f = rng.normal(size=(1, 4, 4))
    g = f @ np.swapaxes(f, 1, 2) + 4 * np.eye(4)
    a, c, b = rng.normal(size=(1, 4)), rng.normal(size=(1, 5, 4)), rng.normal(size=(1, 5))
    x, mult, status = solve_qp_batch(g, a, c, b)
    before = list(qp._solve_batch.signatures)
    frozen = [np.broadcast_to(v, v.shape) for v in (g, a, c, b)]
    assert not any(v.flags.writeable for v in frozen)
    x2, mult2, status2 = solve_qp_batch(*frozen)
    assert list(qp._solve_batch.signatures) == before
    assert np.array_equal(x2, x) and np.array_equal(mult2, mult) and np.array_equal(status2, status)
    res = ConstrainedAllocation(_tunnel_layout()).allocate([[1e5, 0.0, 0.0]])   # nb = 1
    assert list(qp._solve_batch.signatures) == before
    assert res.status[0] == STATUS_SOLVED


def test_the_qp_step_directions_compile_once():
    """_solve_one's active-set size q starts at the literal 0: typed int64 from the start
    (numba locals), _directions is compiled for int64 alone, not for Literal[int](0) as well
    (issue 47 item 7)."""
    from seahelm.numerics import qp

    g = np.eye(2)[None]
    x, _, status = solve_qp_batch(g, np.array([[-1.0, 0.0]]), np.array([[[-1.0, 0.0]]]),
                                  np.array([[-0.5]]))
    assert status[0] == STATUS_SOLVED and x[0, 0] == pytest.approx(0.5, abs=1e-12)
    assert [str(s[4]) for s in qp._directions.signatures] == ["int64"]
