"""A stepped interval's outputs come from the same call of the compiled loop that steps it
(``run_slice``'s ``out``; issue 46 item 6: one call per interval, not the loop and then the
outputs' function): they are the outputs the loop's other way (``observe_runs``) gives at the
same state, bit for bit, with and without the environment's loads."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm import Problem, Simulator
from seahelm.registry import get_model

from test_simulation_pure_python import CASES, _environment_case


def _problem(name: str, **kw) -> Problem:
    return Problem(model=get_model(name), **CASES[name](), **kw)


@pytest.mark.parametrize("name, env", [("nomoto2", False), ("mmg", True)])
def test_a_step_observes_in_its_own_call_what_observe_runs_gives(name, env, monkeypatch):
    problem = _problem(name, **(_environment_case() if env else {}))
    with Simulator(problem) as sim:
        b = sim._batch
        sim.reset()
        calls = []
        run = b.slices.run
        monkeypatch.setattr(b.slices, "run", lambda *a, **k: (calls.append(a), run(*a, **k)))

        def refuse(*a, **k):
            raise AssertionError("a step called the outputs' function")

        monkeypatch.setattr(b.slices, "observe", refuse)
        for q in range(4):
            calls.clear()
            obs = sim.step()
            assert len(calls) == 1  # the step, its outputs included
            monkeypatch.undo()
            expected = np.zeros_like(obs.values)
            b.slices.observe(int(sim._k[0]), b.dt, expected)  # observe_runs at this state
            monkeypatch.setattr(b.slices, "run",
                                lambda *a, **k: (calls.append(a), run(*a, **k)))
            monkeypatch.setattr(b.slices, "observe", refuse)
            assert np.array_equal(obs.values, expected), q  # bit for bit
            assert np.isfinite(obs.values).all()
        np.testing.assert_array_equal(obs.time, 4 * problem.controller_every * problem.dt)
