"""DP control: the allocation-free QP, the in-loop allocation against ConstrainedAllocation,
and the dp-pid controller holding the supply vessel on its set-point."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.control.dp_allocation import ConstrainedAllocation
from seahelm.control.dp_pid import WORKSPACE, DpPidParams, allocate_step, dp_pid_params
from seahelm.control.thruster_layout import ThrusterLayout
from seahelm.errors import ParameterError
from seahelm.numerics.qp import STATUS_SOLVED, solve_qp_batch
from seahelm.numerics.qp_inplace import solve_qp_rows, workspace_size
from seahelm.parameters import as_records
from seahelm.ships import get_ship

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _record(p):
    return as_records(p.to_array()[None], DpPidParams)[0]


def test_inplace_qp_equals_the_batched_solver_on_random_problems():
    """Random strictly convex QPs whose rows have ≤ 2 nonzeros: the workspace solver gives the
    dense Goldfarb–Idnani solver's minimiser (itself checked against Clarabel) to 1e-9."""
    rng = np.random.default_rng(11)
    worst = 0.0
    for _ in range(60):
        nv = int(rng.integers(2, 9))
        m = int(rng.integers(1, 30))
        a_ = rng.normal(size=(nv, nv))
        g = a_ @ a_.T + 0.1 * np.eye(nv)
        a = rng.normal(size=nv) * 3
        cols = rng.integers(0, nv - 1, size=m)
        c1 = rng.normal(size=m)
        c2 = np.where(rng.random(m) < 0.5, 0.0, rng.normal(size=m))
        b = -np.abs(rng.normal(size=m)) - 0.05  # (x = 0 feasible: a problem with a solution)
        dense = np.zeros((m, nv))
        dense[np.arange(m), cols] = c1
        dense[np.arange(m), cols + 1] += c2
        x_ref, _, status = solve_qp_batch(g[None], a[None], dense[None], b[None])
        assert status[0] == STATUS_SOLVED
        cap = 32
        ws = np.zeros(workspace_size(nv, cap))
        ws[:m], ws[cap:cap + m], ws[2 * cap:2 * cap + m], ws[3 * cap:3 * cap + m] = \
            cols, c1, c2, b
        x = np.zeros(nv)
        assert solve_qp_rows(nv, m, cap, g.ravel(), a, ws, x, 1e-9, 1000) == 0
        worst = max(worst, float(np.max(np.abs(x - x_ref[0]))))
    assert worst < 1e-9, worst


def _azimuth_layout():
    return ThrusterLayout(
        names=("az-1", "az-2", "tunnel"), x=(-30.0, -30.0, 25.0), y=(-6.0, 6.0, 0.0),
        direction=(0.3, 2.0, 0.5 * math.pi), azimuthing=(True, True, False),
        max_thrust=(4e5, 4e5, 2e5), forbidden=(((math.radians(80), math.radians(120)),),
                                               (), ()),
        max_thrust_rate=(5e4, 5e4, 4e4), max_azimuth_rate=(math.inf, math.radians(10),
                                                           math.inf))


@pytest.mark.parametrize("which", ["supply", "azimuths"])
def test_in_loop_allocation_equals_constrained_allocation(which):
    """allocate_step (the compiled loop's) against ConstrainedAllocation.allocate without the
    polish — the same QP (bounds, polygon, rate limits, the sector's linearisation) — on
    random demands and previous states: thrusts and azimuths to 1e-7 of the rating."""
    if which == "supply":
        ship = get_ship("supply")
        lay, p = ship.thrusters, dp_pid_params(ship)
    else:
        ship = get_ship("supply").replace(thrusters=_azimuth_layout())
        lay, p = ship.thrusters, dp_pid_params(ship)
    rec = _record(p)
    alloc = ConstrainedAllocation(lay)
    rng = np.random.default_rng(5)
    n = lay.count
    tmax = np.asarray(lay.max_thrust)
    dt = 0.5
    rates = np.where(np.isfinite(lay.max_thrust_rate), lay.max_thrust_rate, 1e30)
    az_rates = np.where(np.isfinite(lay.max_azimuth_rate), lay.max_azimuth_rate, 1e30)
    ws = np.zeros(WORKSPACE)
    for _ in range(40):
        tau = rng.normal(size=3) * [4e5, 3e5, 1.5e7]
        prev_t = rng.uniform(0.0, 0.6, size=n) * tmax
        prev_t[~np.asarray(lay.azimuthing)] *= rng.choice([-1.0, 1.0])
        prev_a = np.asarray(lay.direction) + np.where(lay.azimuthing,
                                                      rng.uniform(-0.5, 0.5, n), 0.0)
        prev_a[0] = rng.choice([0.5, 2.5, 5.0])           # (not in az-1's 80–120° sector)
        if which == "supply":
            prev_a = np.asarray(lay.direction, dtype=float)
        pf = np.zeros(8), np.zeros(8)
        pf[0][:n], pf[1][:n] = prev_t * np.cos(prev_a), prev_t * np.sin(prev_a)
        pa = np.zeros(8)
        pa[:n] = prev_a
        f, az, un = np.zeros(8), np.zeros(8), np.zeros(3)
        status = allocate_step(rec, *tau, dt, pf[0], pf[1], pa, f, az, un, ws)
        kw = dict(previous_thrust=prev_t[None], previous_azimuth=prev_a[None], dt=dt)
        if which != "supply":
            kw.update(thrust_rate=rates, azimuth_rate=az_rates)
        ref = alloc.allocate(tau[None], polish=False, **kw)
        assert status == ref.status[0] == 0
        np.testing.assert_allclose(f[:n], ref.thrust[0], atol=1e-7 * tmax.max())
        np.testing.assert_allclose(un, ref.unmet[0], atol=1e-7 * tmax.max() * 30)
        on = np.abs(ref.thrust[0]) > 1e-3 * tmax
        np.testing.assert_allclose(np.cos(az[:n][on]), np.cos(ref.azimuth[0][on]), atol=1e-6)
        np.testing.assert_allclose(np.sin(az[:n][on]), np.sin(ref.azimuth[0][on]), atol=1e-6)


def test_the_in_loop_qp_compiles_one_signature():
    """allocate_step passes the constant row capacity _MR and solve_qp_rows its counters
    starting at 0: typed int64 (numba locals), solve_qp_rows, _chol and _chol_solve hold no
    Literal[int] signature beside the int64 one a direct call makes (issue 47 item 7:
    solve_qp_rows was compiled for Literal[int](560) as well). Meaningful with an empty
    numba cache, as in CI (a cached allocate_step is loaded without typing its calls)."""
    from numba.core import types

    from seahelm.numerics import qp_inplace

    g, a = np.eye(2), np.array([-1.0, 0.0])
    cap = 4
    ws = np.zeros(workspace_size(2, cap))
    ws[0], ws[cap], ws[2 * cap], ws[3 * cap] = 0, -1.0, 0.0, -0.5   # -x0 >= -0.5
    x = np.zeros(2)
    assert solve_qp_rows(2, 1, cap, g.ravel(), a, ws, x, 1e-9, 100) == 0
    assert x[0] == pytest.approx(0.5, abs=1e-12)
    z = np.zeros(8)
    allocate_step(_record(dp_pid_params(get_ship("supply"))), 1e4, 0.0, 0.0, 0.5, z, z.copy(),
                  z.copy(), np.zeros(8), np.zeros(8), np.zeros(3), np.zeros(WORKSPACE))
    literal = {name: [str(s) for s in getattr(qp_inplace, name).signatures]
               for name in ("solve_qp_rows", "_chol", "_chol_solve")
               if any(isinstance(t, types.Literal)
                      for s in getattr(qp_inplace, name).signatures for t in s)}
    assert literal == {}


def test_dp_pid_params_from_a_ship_and_refusals():
    ship = get_ship("supply")
    p = dp_pid_params(ship)
    assert p.mass_surge == ship.params.m11 and p.damping_yaw == ship.params.d33
    assert p.thruster_count == 6 and p.thruster_max_thrust[:6] == ship.thrusters.max_thrust
    assert p == DpPidParams()                   # the defaults are the supply vessel's
    with pytest.raises(ParameterError, match="declares no thrusters"):
        dp_pid_params(get_ship("kvlcc2-l7"))
    two = _azimuth_layout()
    two = ThrusterLayout(two.names, two.x, two.y, two.direction, two.azimuthing,
                         two.max_thrust, forbidden=(((0.1, 0.2), (1.0, 1.2)), (), ()))
    with pytest.raises(ParameterError, match="one forbidden sector per thruster"):
        dp_pid_params(ship.replace(thrusters=two))


def test_the_supply_vessel_holds_its_set_point_in_a_current(tmp_path):
    """examples/supply_dp_setpoint.toml: 10 m north, 10 m east, 10° from rest in a 0.2 m/s
    current; the integral action takes the current out: at 600 s within 0.3 m and 0.05°, at
    rest over ground, and the mean thrust balances the current's drag D ν_r."""
    from seahelm.scenario import load_scenario, run_scenario

    text = (EXAMPLES / "supply_dp_setpoint.toml").read_text().replace("t_final = 300.0",
                                                                      "t_final = 600.0")
    path = tmp_path / "dp.toml"
    path.write_text(text)
    res = run_scenario(load_scenario(path))
    assert res.ok.all()
    last = {k: float(np.asarray(res[k])[0, -1]) for k in
            ("north", "east", "heading", "surge_speed", "sway_speed", "thrust_surge",
             "thrust_sway")}
    assert abs(last["north"] - 10.0) < 0.3 and abs(last["east"] - 10.0) < 0.3
    assert abs(math.degrees(last["heading"]) - 10.0) < 0.05
    # at rest over ground: the water moves past at the current, ν_r = −Rᵀ V_c
    psi = last["heading"]
    nu_r = np.array([-0.2 * math.sin(psi), -0.2 * math.cos(psi)])
    np.testing.assert_allclose([last["surge_speed"], last["sway_speed"]], nu_r, atol=5e-3)
    d = get_ship("supply").params.damping_matrix()[:2, :2]
    np.testing.assert_allclose([last["thrust_surge"], last["thrust_sway"]], d @ nu_r,
                               rtol=0.05, atol=2e3)
