"""seahelm.simulation.stepping_reference.set_controller_param refuses what the controller's
parameter class refuses: a value inside the field's range that its ``validate`` rejects (a
zig-zag's ``first_side`` of 0.5, which the loop would read as a side of +1/-1 it is not) is
refused naming ``values`` and the run, and nothing is written; text is refused by name too.
The pure-Python loop (``jit=False``): nothing compiles."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm import Problem, Simulator
from seahelm.control.zigzag import ZIGZAG, ZigZagParams
from seahelm.errors import ParameterError
from seahelm.simulation.stepping_reference import set_controller_param
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params


def _simulator() -> Simulator:
    return Simulator(Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=40.0,
                                                                  speed=5.0),
                             x0=np.zeros((3, NOMOTO1.n_states)), t_final=4.0, dt=0.5,
                             controller=ZIGZAG, controller_params=ZigZagParams(), jit=False))


def _sides(sim: Simulator) -> np.ndarray:
    return sim._batch.slices.arrays.get("params", "controller")["first_side"].copy()


def test_a_value_the_class_refuses_is_refused_by_name():
    with _simulator() as sim:
        sim.reset()
        before = _sides(sim)
        with pytest.raises(ParameterError, match="first_side") as info:
            set_controller_param(sim, "first_side", [1.0, 0.5, -1.0])
        assert info.value.field == "values" and info.value.run == 1
        assert info.value.value == 0.5
        np.testing.assert_array_equal(_sides(sim), before)  # nothing written
        with pytest.raises(ParameterError) as info:
            set_controller_param(sim, "first_side", "port")
        assert info.value.field == "values"


def test_values_the_class_admits_are_written():
    with _simulator() as sim:
        sim.reset()
        set_controller_param(sim, "first_side", -1.0, runs=[0, 2])
        np.testing.assert_array_equal(_sides(sim), [-1.0, 1.0, -1.0])
        sim.step()
