"""The manoeuvres' steady turns in one batch (zig-zag reachability and default durations,
turning-circle durations, pull-out starts) against the one-at-a-time steady_turn."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.equilibria.equilibrium import EquilibriumError, steady_turn, steady_turn_state
from seahelm.analysis.imo.probability import monte_carlo_ships
from seahelm.analysis.maneuvers import maneuver_ship, pull_out, zigzag
from seahelm.analysis.maneuvers.ships import (
    steady_approach,
    steady_yaw_rate,
    steady_yaw_rates,
)
from seahelm.ships import get_ship

DEG = math.pi / 180.0


def _members(name, n, **kw):
    return [maneuver_ship(s) for s in monte_carlo_ships(get_ship(name), n, **kw)]


@pytest.mark.parametrize("name", ["kvlcc2-l7", "mariner-nonlinear"])
def test_the_zigzag_steady_yaw_rates_equal_the_one_at_a_time_turns(name):
    ships = _members(name, 4, seed=5)
    pairs = np.array([10.0, 20.0]) * DEG
    m = zigzag(ships, pairs, pairs, sides=(1, -1), t_final=30.0 if name == "kvlcc2-l7"
               else 120.0, record_dt=1.0).metrics
    got = m["steady_yaw_rate_at_rudder"].transpose("ship", "pair", "side").values
    for i, s in enumerate(ships):
        a = steady_approach(s.model, s.params, s.approach_speed)
        for j, d in enumerate(pairs):
            for k, side in enumerate((1, -1)):
                ref = steady_turn(s.params, side * d, a.rps, model=s.model).yaw_rate
                assert got[i, j, k] == pytest.approx(side * abs(ref), rel=1e-9)


def test_the_batch_raises_what_the_one_at_a_time_estimate_raises():
    good = _members("mariner-nonlinear", 2, seed=3, uncertainty=0.3)[:2]
    bad = _members("mariner-nonlinear", 28, seed=3, uncertainty=0.3)[27]
    groups = [(s, np.array([d, -d]), steady_approach(s.model, s.params, s.approach_speed))
              for s in (good[0], bad, good[1]) for d in (35 * DEG,)]
    with pytest.raises(EquilibriumError) as one:
        for g in groups:
            steady_yaw_rate(*g)
    with pytest.raises(EquilibriumError) as batch:
        steady_yaw_rates(groups)
    assert str(batch.value) == str(one.value)
    assert batch.value.field == one.value.field == "t_final"
    # without the impossible ship: the rates of each group, in its shape
    rates = steady_yaw_rates([groups[0], groups[2]])
    for g, r in zip((groups[0], groups[2]), rates):
        np.testing.assert_allclose(r, steady_yaw_rate(*g), rtol=1e-9)
        assert r.shape == (2,)


def test_the_pull_out_starts_in_the_one_at_a_time_steady_turns():
    ships = _members("kvlcc2-l7", 3, seed=9)
    m = pull_out(ships, [15 * DEG, 25 * DEG], t_final=5.0).metrics
    r0 = m["initial_yaw_rate"].transpose("ship", "rudder", "side").values
    for i, s in enumerate(ships):
        a = steady_approach(s.model, s.params, s.approach_speed)
        for j, d in enumerate((15 * DEG, 25 * DEG)):
            for k, side in enumerate((1, -1)):
                ref = steady_turn_state(s.params, side * d, a.rps, model=s.model).state
                assert r0[i, j, k] == pytest.approx(ref[s.model.state_index("yaw_rate")],
                                                    rel=1e-9)
