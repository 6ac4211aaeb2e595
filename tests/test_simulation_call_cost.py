"""The engine's fixed cost per call (issues 46 and 49): its shortcuts keep what the general
paths did -- every kernel array writable, the record-memory refusal of a batch the reference
makes larger."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.simulation.kernel_args import GROUPS, KernelArrays


def _arrays() -> KernelArrays:
    def group(n: int) -> tuple[np.ndarray, ...]:
        return tuple(np.zeros((2, 3)) for _ in range(n))

    return KernelArrays(**{name: group(len(members)) for name, members in GROUPS.items()},
                        stages=(group(2), group(1)), stage_names=("environment", "sensors"))


def test_writable_arrays_are_the_same_object():
    arrays = _arrays()
    assert arrays.writable() is arrays


@pytest.mark.parametrize("where", [(name, j) for name, members in GROUPS.items()
                                   for j in range(len(members))]
                         + [("stages", (0, 1)), ("stages", (1, 0))])
def test_a_read_only_array_in_any_group_is_copied(where):
    arrays = _arrays()
    name, j = where
    if name == "stages":
        q, m = j
        ro = arrays.stages[q][m]
    else:
        ro = getattr(arrays, name)[j]
    ro[...] = 7.0
    ro.flags.writeable = False
    got = arrays.writable()
    assert got is not arrays
    assert all(a.flags.writeable for a in got)
    copied = [a for a in got if a is not ro and np.array_equal(a, ro)]
    assert len(copied) == 1 and not any(a is ro for a in got)
    # the other arrays are passed on as they are (no copy)
    assert sum(a is b for a, b in zip(got, arrays)) == len(list(arrays)) - 1
    assert got.stage_names == arrays.stage_names


def test_more_runs_from_the_reference_than_counted_early_are_still_checked(monkeypatch):
    # the early check counts runs of the parameters, states and stages; a reference of 400
    # runs (one ship, one initial state) makes the batch 400 times larger: refused
    import seahelm.simulation.memory as memory
    from seahelm.resources import MemoryLimit
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.memory import RecordingTooLarge
    from seahelm.simulation.problem import Problem

    limit = MemoryLimit(2_000_000, "the cgroup's memory limit")
    monkeypatch.setattr(memory, "memory_limit", lambda: limit)
    monkeypatch.setattr(memory, "ASK_ABOVE", 0)
    kw = dict(ship="mariner-nonlinear", t_final=100.0, dt=0.1, record_every=1)
    ref = np.full((400, 1, 1), 0.05)
    problem = Problem(**kw, reference=ref[:1])
    assert problem.n_steps == 1000
    with pytest.raises(RecordingTooLarge, match="400 run"):
        simulate(Problem(**kw, reference=ref))
