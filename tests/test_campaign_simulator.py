"""Bad input to :class:`seahelm.Simulator` (the bad-input campaign): a command that is not a
number is a ParameterError naming ``commands`` (it was numpy's bare ValueError), and the
simulator stays usable."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm import Problem, Simulator, get_ship
from seahelm.errors import ParameterError


def test_a_command_that_is_not_a_number_is_named_and_changes_nothing():
    ship = get_ship("mariner-nomoto1")
    problem = Problem(ship=ship, x0=np.zeros((2, len(ship.model.state_labels))), t_final=5.0,
                      dt=0.1, controller_dt=1.0)
    with Simulator(problem) as sim:
        sim.reset()
        before = sim.state(0)
        with pytest.raises(ParameterError, match=r"\A`commands` \['rudder_command'\] must be "
                                                 r"a number or numbers .* got 'a'\Z") as info:
            sim.step({"rudder_command": "a"})
        assert info.value.field == "commands"
        assert sim.state(0) == before and list(sim.time) == [0.0, 0.0]
        obs = sim.step({"rudder_command": 0.1})
        assert list(obs.time) == [1.0, 1.0]
