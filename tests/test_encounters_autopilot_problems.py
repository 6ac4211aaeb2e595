"""Encounter.autopilot_problems: the encounter's ships steered by its heading autopilot in the
compiled loop, each on its initial course, uncoupled (the benchmark's like-for-like
reference, issue 51 "Speed")."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm import get_ship, simulate
from seahelm.encounters.encounter import Encounter, HeadingAutopilot, Vessel


@pytest.mark.parametrize("ship", ["kvlcc2-full", "mariner-nomoto2"])
def test_autopilot_problems_carry_the_encounter_autopilot_and_courses(ship):
    s = get_ship(ship)
    own = Vessel(ship=ship, course=0.0, avoid=True)
    tgt = Vessel(ship=ship, north=np.array([4000.0, 6000.0]), east=np.array([4000.0, 100.0]),
                 course=np.array([-math.pi / 2, math.pi]))
    enc = Encounter([own, tgt], t_final=60.0, autopilot=HeadingAutopilot(gain=2.0,
                                                                         derivative_time=0.5))
    (problem,) = enc.autopilot_problems()
    held = "propeller_rps" in enc.problems[0].wiring.commands
    assert problem.controller.name == ("pid-heading-rps" if held else "pid-heading")
    td = 0.5 * s.length / s.approach_speed  # T_d [s]
    for p in problem.controller_params:
        assert (p.kp, p.ki, p.kd) == (2.0, 0.0, 2.0 * td)
    # runs in the encounter's flat order: (own, target) of encounter 0, then of 1
    np.testing.assert_array_equal(np.asarray(problem.reference).reshape(-1),
                                  [0.0, -math.pi / 2, 0.0, math.pi])
    if held:  # the self-propulsion rps the uncoupled reference holds
        (open_loop,) = enc.uncoupled_problems()
        ref = open_loop.reference
        j = open_loop.wiring.commands.index("propeller_rps")
        np.testing.assert_array_equal([p.propeller_rps for p in problem.controller_params],
                                      ref[:, 0, j])

def test_autopilot_problems_move_the_ships_as_the_encounter_without_avoidance():
    own = Vessel(ship="kvlcc2-full", course=0.3)
    tgt = Vessel(ship="kvlcc2-full", north=5000.0, east=np.array([-3000.0, 3000.0]),
                 course=np.array([1.0, -2.0]), speed=np.array([5.0, 7.0]))
    enc = Encounter([own, tgt], t_final=120.0, record_every=120)
    res = enc.run()
    (problem,) = enc.autopilot_problems()
    ds = simulate(problem).to_xarray()
    for name in ("north", "east", "heading", "speed"):
        got = ds[name].values[:, -1].reshape(2, 2)
        np.testing.assert_allclose(got, res.tracks[name][:, :, -1], rtol=0, atol=1e-6,
                                   err_msg=name)
