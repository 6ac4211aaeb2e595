"""Batched steady turns (analysis.batch_steady_turn) against the one-at-a-time solve.

The reference is :func:`seahelm.analysis.equilibria.equilibrium.steady_turn`: scipy's hybr (relative
step 1e-13) along a continuation in r, brentq on the crossing and a polish at δ. Both solves end
at the round-off floor of the same equations, so they agree to ~1e-15; the bound asserted is
1e-9 relative (every field of a turn is far from zero).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import seahelm.analysis.equilibria.batch_steady_turn as bst
from seahelm.analysis.equilibria.batch_steady_turn import (
    TurnStatus,
    steady_turn_states,
    steady_turns,
)
from seahelm.analysis.equilibria.equilibrium import (
    EquilibriumError,
    self_propulsion_rps,
    steady_turn,
    steady_turn_state,
)
from seahelm.analysis.imo.probability import monte_carlo_ships
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR
from seahelm.vessels.mmg import KVLCC2_L7, MMG

TOL = 1e-9
FIELDS = ("surge_speed", "sway_speed", "yaw_rate", "speed", "drift_angle", "radius")
DEG = math.pi / 180.0


def _reference(model, params, rudder, rps):
    """The one-at-a-time turns (rows of FIELDS; None where it raises)."""
    rows = []
    for i, (p, d) in enumerate(zip(params, rudder)):
        n = None if rps is None else float(np.broadcast_to(rps, (len(params),))[i])
        try:
            rows.append(tuple(steady_turn(p, float(d), n, model=model)))
        except EquilibriumError as exc:
            rows.append(str(exc))
    return rows


def _assert_same(batch, reference):
    for i, ref in enumerate(reference):
        if isinstance(ref, str):
            assert not batch.ok[i], (i, ref)
            continue
        assert batch.ok[i], (i, batch.message[i])
        got = [getattr(batch, f)[i] for f in FIELDS]
        np.testing.assert_allclose(got, ref, rtol=TOL, atol=0.0, err_msg=f"run {i}")


def _monte_carlo(name, n, rudders, *, seed=1, uncertainty=0.1):
    ship = get_ship(name)
    params = [s.params for s in monte_carlo_ships(ship, n, seed=seed, uncertainty=uncertainty)
              for _ in rudders]
    delta = np.tile(np.asarray(rudders) * DEG, n)
    rps = (self_propulsion_rps(ship.params, ship.approach_speed, model=ship.model)
           if ship.has_propeller else None)
    return ship.model, params, delta, rps


@pytest.mark.parametrize("name, n", [("kvlcc2-l7", 8), ("kvlcc2-full", 4),
                                     ("mariner-nonlinear", 5)])
def test_a_monte_carlo_equals_the_one_at_a_time_solve(name, n):
    model, params, delta, rps = _monte_carlo(name, n, (35, -35, 20, -20, 10, -10, 2, -1))
    batch = steady_turns(model, params, delta, rps, fallback=False)
    assert batch.ok.all(), batch.message
    assert not batch.fallback.any()  # every turn solved by the batch itself
    _assert_same(batch, _reference(model, params, delta, rps))
    np.testing.assert_array_equal(batch.rudder, delta)


def test_the_propeller_rps_per_run_and_one_ship_for_many_rudders():
    n0 = self_propulsion_rps(KVLCC2_L7, KVLCC2_L7.approach_speed)
    rps = n0 * np.array([0.7, 1.0, 1.3, 1.0])
    delta = np.array([15.0, -15.0, 25.0, 0.0]) * DEG
    batch = steady_turns(MMG, KVLCC2_L7, delta, rps)
    _assert_same(batch, _reference(MMG, [KVLCC2_L7] * 4, delta, rps))
    # at the straight run's own rudder angle (0 for this ship) the turn is the straight run
    assert batch.yaw_rate[3] == 0.0 and batch.radius[3] == math.inf


def test_the_continuation_in_rudder_is_taken_where_the_spiral_curve_is_steep(monkeypatch):
    """Wide draws of the Mariner: many turns go on in δ from the last good point (stage 4),
    as the one-run solve's do; the failures are the one-run solve's failures."""
    handed = []
    real = bst._continue_in_rudder

    def spy(*args, **kwargs):
        handed.append(len(args[5]["run"]))
        return real(*args, **kwargs)

    monkeypatch.setattr(bst, "_continue_in_rudder", spy)
    model, params, delta, rps = _monte_carlo("mariner-nonlinear", 12, (35, -35, 5, -0.5),
                                             seed=3, uncertainty=0.3)
    batch = steady_turns(model, params, delta, rps, fallback=False)
    assert handed and handed[0] > 0
    reference = _reference(model, params, delta, rps)
    _assert_same(batch, reference)
    assert batch.ok.sum() == sum(not isinstance(r, str) for r in reference) > 20


@pytest.mark.parametrize("name", ["mariner-nomoto1", "mariner-nomoto2"])
def test_constant_speed_models_are_solved_one_run_after_the_other(name):
    ship = get_ship(name)
    params = [s.params for s in monte_carlo_ships(ship, 5, seed=2)]
    delta = np.array([10.0, -20.0, 35.0, -5.0, 1.0]) * DEG
    batch = steady_turns(ship.model, params, delta)
    assert batch.fallback.all()
    _assert_same(batch, _reference(ship.model, params, delta, None))


def _impossible():
    """A Mariner whose wide draw has no steady turn at 35 deg (the continuation in δ stalls)."""
    return monte_carlo_ships(get_ship("mariner-nonlinear"), 28, seed=3, uncertainty=0.3)[27]


def test_an_impossible_turn_fails_with_its_reason_and_the_others_are_solved():
    bad = _impossible().params
    strong = MARINER_NONLINEAR.replace(Y_0=100 * MARINER_NONLINEAR.Y_0,
                                       N_0=100 * MARINER_NONLINEAR.N_0)
    params = [MARINER_NONLINEAR, bad, strong, MARINER_NONLINEAR]
    delta = np.array([35.0, 35.0, 10.0, -35.0]) * DEG
    with pytest.raises(EquilibriumError) as one:
        steady_turn(bad, 35 * DEG)
    with pytest.raises(EquilibriumError) as two:
        steady_turn(strong, 10 * DEG)
    batch = steady_turns(MARINER, params, delta, fallback=False)
    assert batch.status.tolist() == [0, TurnStatus.LINE_SEARCH, TurnStatus.STRAIGHT_RUN, 0]
    assert batch.message[1].startswith("no equilibrium found for surge, v, r with rudder = ")
    assert batch.message[2].startswith("no equilibrium found for surge, v, rudder with r = 0")
    assert np.isnan([getattr(batch, f)[1:3] for f in FIELDS]).all()
    _assert_same(batch, _reference(MARINER, params, delta, None))
    # with the fallback (the default): the one-at-a-time solve's own message
    again = steady_turns(MARINER, params, delta)
    assert again.status.tolist() == [0, TurnStatus.NO_STEADY_TURN, TurnStatus.NO_STEADY_TURN, 0]
    assert again.message[1:3] == (str(one.value), str(two.value))
    assert again.fallback.tolist() == [False] * 4


def test_bad_arguments_raise_for_the_batch():
    n = self_propulsion_rps(KVLCC2_L7, KVLCC2_L7.approach_speed)
    with pytest.raises(ParameterError, match="rudder"):
        steady_turns(MMG, KVLCC2_L7, [10 * DEG, 40 * DEG], n)
    with pytest.raises(ParameterError, match="rudder"):
        steady_turns(MMG, KVLCC2_L7, [10 * DEG], n, max_rudder=5 * DEG)
    with pytest.raises(ParameterError, match="rps"):
        steady_turns(MMG, KVLCC2_L7, 10 * DEG)
    with pytest.raises(ParameterError, match="rps"):
        steady_turns(MMG, KVLCC2_L7, 10 * DEG, [n, -n])
    with pytest.raises(ParameterError, match="rps"):
        steady_turns(MARINER, MARINER_NONLINEAR, 10 * DEG, 1.0)
    with pytest.raises(ParameterError, match="one per run"):
        steady_turns(MMG, [KVLCC2_L7] * 3, [DEG, DEG], n)
    with pytest.raises(ParameterError, match="one per run"):
        steady_turns(MMG, [KVLCC2_L7] * 2, [DEG, DEG, DEG], n)
    with pytest.raises(ParameterError, match="no runs"):
        steady_turns(MMG, [], 10 * DEG, n)


@pytest.mark.parametrize("name", ["kvlcc2-l7", "mariner-nonlinear", "mariner-nomoto2",
                                  "son-nomoto-container"])
def test_the_states_of_the_turns_equal_steady_turn_state(name):
    ship = get_ship(name)
    rps = (self_propulsion_rps(ship.params, ship.approach_speed, model=ship.model)
           if ship.has_propeller else None)
    delta = np.array([20.0, -20.0, 8.0]) * DEG
    states, turns = steady_turn_states(ship.model, ship.params, delta, rps)
    assert turns.ok.all()
    for i, d in enumerate(delta):
        ref = steady_turn_state(ship.params, float(d), rps, model=ship.model).state
        np.testing.assert_allclose(states[i], ref, rtol=TOL, atol=TOL * ship.approach_speed)
