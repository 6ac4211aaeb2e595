"""Equilibria solved one way (issue 47, item 3, step C): the one-run functions are batches of
one of the batched Newton solvers, with scipy only as the fallback inside for a run the batch
does not solve (whose error is then the one raised)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.equilibria import batch_equilibrium
from seahelm.analysis.equilibria.batch_equilibrium import approach_states
from seahelm.analysis.equilibria.batch_steady_turn import steady_turns
from seahelm.analysis.equilibria import fallback
from seahelm.analysis.equilibria.plant import Plant
from seahelm.analysis.equilibria.equilibrium import (
    EquilibriumError,
    approach_state,
    self_propulsion_rps,
    steady_turn,
)
from seahelm.ships import get_ship
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR

P0 = MARINER_NONLINEAR
STRONG = P0.replace(Y_0=100 * P0.Y_0, N_0=100 * P0.N_0)  # no straight run with r = 0
DELTAS = np.radians([-35.0, -10.0, 5.0, 20.0, 35.0])


@pytest.fixture
def no_scipy(monkeypatch):
    """The scipy solves of the one-run module fail the test if they are called."""
    def called(*args, **kwargs):
        raise AssertionError("the scipy fallback ran")

    monkeypatch.setattr(fallback, "solve", called)
    monkeypatch.setattr(fallback, "self_propulsion", called)
    monkeypatch.setattr(fallback, "turn_fields", called)


def test_the_one_run_approach_is_the_batch_of_one(no_scipy):
    ship = get_ship("kvlcc2-l7")
    one = approach_state(ship, trim=True, heading=0.5)
    batch = approach_states(ship.model, ship.params, trim=True, heading=0.5)
    assert np.array_equal(one.state, batch.state[0])
    assert one.inputs == {"rudder_angle": batch.rudder[0], "propeller_rps": batch.rps[0]}
    assert self_propulsion_rps(ship, [0.8, 1.179]).tolist() == approach_states(
        ship.model, [ship.params] * 2, [0.8, 1.179], trim=False).rps.tolist()


def test_the_one_run_turn_is_the_batch_of_one(no_scipy):
    for ship in (get_ship("kvlcc2-l7"), get_ship("mariner-nonlinear")):
        n = approach_state(ship).inputs.get("propeller_rps")
        one = steady_turn(ship, DELTAS, n)
        batch = steady_turns(ship.model, ship.params, DELTAS, n, fallback=False)
        assert batch.ok.all()
        for k, name in enumerate(one._fields):
            assert np.array_equal(one[k], getattr(batch, name)), name


def test_the_newton_roots_are_scipys_to_rounding():
    # (the change of issue 47 step C: the one-run numbers were scipy's before)
    ship = get_ship("kvlcc2-full")
    n = approach_state(ship).inputs["propeller_rps"]
    newton = steady_turn(ship, DELTAS, n)
    plant = Plant.of(ship)
    scipy = fallback.turn_fields(plant, DELTAS, n, math.radians(2.5))
    np.testing.assert_allclose(np.array(newton[:5]), scipy[:5], rtol=5e-15, atol=1e-17)
    assert fallback.self_propulsion(plant, 7.0, 1000.0) == pytest.approx(
        self_propulsion_rps(ship, 7.0), rel=5e-16)


def test_a_run_the_batch_does_not_solve_falls_back_to_scipy(monkeypatch):
    ship = get_ship("mariner-nonlinear")
    expected = approach_state(ship, trim=True)
    real = batch_equilibrium.approach_states

    def failing(*args, **kwargs):  # every run fails in the batch
        out = real(*args, **kwargs)
        return type(out)(**{**out.__dict__, "status": np.full_like(out.status, 6)})

    monkeypatch.setattr(batch_equilibrium, "approach_states", failing)
    fallback = approach_state(ship, trim=True)
    np.testing.assert_allclose(fallback.state, expected.state, rtol=1e-12, atol=1e-15)
    assert fallback.rudder == pytest.approx(expected.rudder, rel=1e-9)


def test_no_solution_raises_the_fallbacks_error_naming_the_condition():
    with pytest.raises(EquilibriumError, match=r"no equilibrium found for surge, v, rudder "
                                               r"with r = 0"):
        approach_state(STRONG, model=MARINER, trim=True)
    with pytest.raises(EquilibriumError, match=r"no propeller rps in \(0, 2\] \[1/s\] gives "
                                               r"zero surge force at `speed` = 1.179"):
        self_propulsion_rps("kvlcc2-l7", 1.179, max_rps=2.0)
    with pytest.raises(EquilibriumError, match="no equilibrium found"):
        steady_turn(STRONG, math.radians(10.0), model=MARINER)
