"""The per-combination frame of ``prepare`` (:func:`seahelm.simulation.frame._frame`).

Made once per wiring and stages (issue 46: a batch of one run rebuilt these labels, bounds and
sizes at every call): it must be what the components give, and a problem's own ``bounds``
must never reach the next problem of the same combination through it.
"""

from __future__ import annotations

import math

import numpy as np
from seahelm.simulation.engine import prepare
from seahelm.simulation.frame import _frame
from seahelm.simulation.problem import Problem
from seahelm.simulation.stages import stages_of


def _problem(**kw):
    return Problem(ship="kvlcc2-l7", t_final=2.0, dt=0.1, **kw)


def test_the_frame_is_what_the_components_give():
    p = _problem()
    model, actuator, controller, wiring = p.model, p.actuator, p.controller, p.wiring
    f = _frame(wiring, stages_of(p))
    assert f.labels == model.state_labels + actuator.state_labels
    assert f.out_labels == model.output_labels and f.dist_labels == model.disturbance_labels
    assert f.n_commands == len(wiring.commands) + len(controller.output_labels)
    assert f.lower.tolist() == list(model.state_lower) + [-math.inf] * actuator.n_states
    assert f.upper.tolist() == list(model.state_upper) + [math.inf] * actuator.n_states
    assert not f.lower.flags.writeable and not f.upper.flags.writeable
    assert _frame(wiring, stages_of(p)) is f  # (once per combination)


def test_a_problems_bounds_stay_its_own():
    wide = prepare(_problem())
    lower0 = wide.slices.arrays.params[3].copy()
    tight = prepare(_problem(bounds={"sway_speed": (-0.01, 0.01)}))
    j = tight.labels.index("sway_speed")
    assert tight.slices.arrays.params[3][j] == -0.01 and tight.slices.arrays.params[4][j] == 0.01
    again = prepare(_problem())
    assert np.array_equal(again.slices.arrays.params[3], lower0, equal_nan=True)
    assert again.slices.arrays.params[3] is not _frame(again.problem.wiring, ()).lower
    assert again.slices.arrays.params[3].flags.writeable
