"""A batch of ships whose steady approaches are solved together: a ship without one is left
out (NaN metrics, its reason as the message), the others run as they run alone."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis import maneuvers
from seahelm.analysis.equilibria.equilibrium import EquilibriumError, approach_state
from seahelm.analysis.maneuvers.ships import (
    clear_approaches,
    maneuver_ship,
    steady_approach,
    steady_approaches,
)
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR, MARINER_SERVO

P0 = MARINER_NONLINEAR
#: 100 x the single-screw bias: no straight run with r = 0 exists (the trim fails)
STRONG = P0.replace(Y_0=100 * P0.Y_0, N_0=100 * P0.N_0)
WEAK = P0.replace(N_r=1.1 * P0.N_r)


def _ships(*params):
    return [maneuver_ship(p, servo=MARINER_SERVO, model=MARINER, name=f"m{k}")
            for k, p in enumerate(params)]


def test_steady_approaches_memoise_and_equal_the_one_run_solve():
    clear_approaches()
    out = steady_approaches(MARINER, [P0, STRONG, P0, WEAK], [P0.nominal_speed] * 4)
    assert out[0] is out[2]  # one solve per distinct pair
    assert isinstance(out[1], str) and "no equilibrium found" in out[1]
    ref = approach_state(P0, model=MARINER, trim=True)
    assert out[0].rudder == pytest.approx(ref.inputs["rudder_angle"], rel=1e-12)
    np.testing.assert_allclose(out[0].state, ref.state, rtol=1e-12, atol=1e-14)
    assert steady_approach(MARINER, P0, P0.nominal_speed) is out[0]  # memoised
    with pytest.raises(EquilibriumError, match="no equilibrium found"):
        steady_approach(MARINER, STRONG, P0.nominal_speed)


@pytest.mark.parametrize("run", [
    lambda ships: maneuvers.turning_circle(ships, math.radians(35), sides=1, t_final=60.0),
    lambda ships: maneuvers.zigzag(ships, math.radians(10), sides=1, t_final=80.0),
    lambda ships: maneuvers.pull_out(ships, math.radians(20), sides=1, t_final=60.0),
    lambda ships: maneuvers.direct_spiral(ships, np.radians([10.0, 0.0, -10.0]), hold=40.0),
    lambda ships: maneuvers.reverse_spiral(ships, points=5),
], ids=["turning", "zigzag", "pullout", "direct-spiral", "reverse-spiral"])
def test_a_ship_without_approach_is_left_out_and_the_others_run(run):
    together = run(_ships(P0, STRONG, WEAK)).metrics
    alone = run(_ships(P0, WEAK)).metrics
    failed = together.isel(ship=1)
    assert str(failed["message"].values.ravel()[0]).startswith(
        "not run: no straight approach of 'm1' at 7.7175 m/s (no equilibrium found")
    if "complete" in together:
        assert not failed["complete"].values.any()
    for name, var in together.data_vars.items():
        if var.dtype.kind == "f":
            assert np.isnan(failed[name].values).all(), name
            np.testing.assert_array_equal(together[name].isel(ship=[0, 2]).values,
                                          alone[name].values, err_msg=name)


def test_the_time_series_of_a_left_out_run_say_not_run():
    result = maneuvers.turning_circle(_ships(P0, STRONG), math.radians(35), sides=1,
                                      t_final=20.0)
    sim = result.simulation
    assert sim.status.tolist() == [0, 3]
    assert sim.messages()[1] == "not run: no initial state (its steady approach was not found)"
    assert np.isnan(sim.state[1]).all() and np.isfinite(sim.state[0]).all()
    ds = result.runs
    assert int(ds["status"].isel(ship=1)) == 3


def test_one_ship_or_every_ship_without_approach_raises():
    with pytest.raises(EquilibriumError, match=r"`speed`: no straight approach of 'm0' at "
                                               r"7.7175 m/s \(no equilibrium found"):
        maneuvers.turning_circle(_ships(STRONG)[0], t_final=20.0)
    with pytest.raises(EquilibriumError, match=r"`speed`: none of the 2 approaches: no straight "
                                               r"approach of 'm1'"):
        maneuvers.turning_circle(_ships(STRONG, STRONG), t_final=20.0)
