"""One Approach type (issue 47, item 3, step B): the one-run approach, the manoeuvres' approach
and a batch's runs are the same type, from one module; solved approaches are kept in a bounded
cache object (no module-level memo dictionaries)."""
from __future__ import annotations

import numpy as np
import pytest

from seahelm.analysis.equilibria import batch_equilibrium, equilibrium
from seahelm.analysis.equilibria.batch_equilibrium import approach_states
from seahelm.analysis.equilibria import approach as approach_module
from seahelm.analysis.equilibria.approach import Approach
from seahelm.analysis.equilibria.approach_cache import (
    APPROACHES,
    ApproachCache,
    steady_approach,
    steady_approaches,
)
from seahelm.analysis.equilibria.equilibrium import EquilibriumError, approach_state
from seahelm.analysis.maneuvers import common, ships
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR

P0 = MARINER_NONLINEAR
STRONG = P0.replace(Y_0=100 * P0.Y_0, N_0=100 * P0.N_0)  # no straight run with r = 0


def test_one_approach_type_in_one_module():
    assert equilibrium.Approach is Approach
    assert ships.Approach is Approach and common.Approach is Approach
    assert batch_equilibrium.BatchApproach is approach_module.BatchApproach
    assert batch_equilibrium.ApproachStatus is approach_module.ApproachStatus
    for name in ("_MEMO", "_KEYS", "MEMO_SIZE", "_MemoKey", "_memo_key"):
        assert not hasattr(ships, name), name


def test_the_one_run_approach_reads_as_the_manoeuvres_approach():
    ship = get_ship("kvlcc2-l7")
    a = approach_state(ship, trim=True)
    assert isinstance(a, Approach)
    assert a.speed == ship.params.approach_speed
    assert a.rudder == a.inputs["rudder_angle"]
    assert a.rps == a.inputs["propeller_rps"] > 0.0
    m = approach_state("mariner-nonlinear", trim=True)
    assert m.rps is None and m.speed == P0.nominal_speed
    assert set(m.inputs) == {"rudder_angle"}


def test_a_batch_run_is_an_approach_equal_to_the_one_run_solve():
    ship = get_ship("kvlcc2-l7")
    batch = approach_states(ship.model, [ship.params, ship.params.replace(N_r=1.05 *
                                                                          ship.params.N_r)])
    one = approach_state(ship, trim=True)
    first = batch.approach(0)
    assert isinstance(first, Approach)
    np.testing.assert_allclose(first.state, one.state, rtol=1e-11, atol=1e-14)
    assert first.rps == pytest.approx(one.rps, rel=1e-12)
    assert first.speed == one.speed
    assert not first.state.flags.writeable
    with pytest.raises(TypeError):
        first.inputs["rudder_angle"] = 1.0  # read-only: a kept approach is shared


def test_a_cache_object_keeps_at_most_its_size_least_recently_used_out():
    cache = ApproachCache(2)
    U = P0.nominal_speed
    weak, weaker = P0.replace(N_r=1.1 * P0.N_r), P0.replace(N_r=1.2 * P0.N_r)
    before = len(APPROACHES)
    a0 = steady_approach(MARINER, P0, U, cache=cache)
    assert steady_approach(MARINER, P0, U, cache=cache) is a0  # kept
    out = steady_approaches(MARINER, [weak, STRONG, weak], [U] * 3, cache=cache)
    assert out[0] is out[2] and isinstance(out[1], str)  # one solve per pair; failure told
    assert len(cache) == 2  # P0 and weak (the failure is not kept)
    steady_approach(MARINER, P0, U, cache=cache)  # P0 now the most recently used
    steady_approach(MARINER, weaker, U, cache=cache)  # weak goes out
    assert len(cache) == 2
    assert steady_approach(MARINER, P0, U, cache=cache) is a0
    assert steady_approach(MARINER, weak, U, cache=cache) is not out[0]  # solved again
    assert len(APPROACHES) == before  # the shared cache untouched
    with pytest.raises(EquilibriumError, match="no equilibrium found"):
        steady_approach(MARINER, STRONG, U, cache=cache)
    cache.clear()
    assert len(cache) == 0


def test_a_cache_size_must_be_a_whole_number():
    with pytest.raises(ParameterError, match="whole number >= 1, got 0") as err:
        ApproachCache(0)
    assert err.value.field == "size"
