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


# one reduction for the angle checks: the errors the two passes gave, in their order
ANGLE_LABELS = ("heading", "rudder_command", "surge_force", "rudder_2")
ANGLE_UNITS = ("rad", "rad", "N", "rad")


def _check(values):
    from seahelm.simulation.inputs import _check_angles

    _check_angles("reference", np.asarray(values, dtype=float), ANGLE_LABELS, ANGLE_UNITS)


def test_angles_within_range_pass_and_forces_are_not_angles():
    _check([[[-6e3, 1.5, 1e9, -1.5]]])
    _check(np.zeros((3, 5, 4)))


def test_a_rudder_beyond_a_right_angle_is_named_before_a_heading_of_many_turns():
    with pytest.raises(Exception, match=r"channel 'rudder_command' reaches 2 rad \(114\.592 deg\)"):
        _check([[[1e5, 2.0, 0.0, 0.0]]])


def test_the_second_rudder_channel_and_the_largest_magnitude_over_runs_and_time():
    values = np.zeros((2, 3, 4))
    values[1, 2, 3] = -1.75
    values[0, 1, 3] = 1.7
    with pytest.raises(Exception, match=r"channel 'rudder_2' of run 1 reaches -1\.75 rad"):
        _check(values)


def test_a_heading_of_many_turns_is_named():
    from seahelm.errors import ParameterError

    with pytest.raises(ParameterError, match=r"channel 'heading' reaches 20000 rad, more than a "
                                             r"thousand turns") as err:
        _check([[[-2e4, 0.1, 0.0, 0.0]]])
    assert err.value.field == "reference" and err.value.value == 2e4


def test_a_signal_with_fewer_channels_than_labels_checks_those_it_has():
    from seahelm.simulation.inputs import _check_angles

    _check_angles("reference", np.array([[[0.1]]]), ANGLE_LABELS, ANGLE_UNITS)
    with pytest.raises(Exception, match="'heading' reaches"):
        _check_angles("reference", np.array([[[1e5]]]), ANGLE_LABELS, ANGLE_UNITS)


@pytest.mark.parametrize("extra", [{"dt": 0.1}, {"reference": np.array([0.1, 0.2])},
                                   {"x0": np.zeros((2, 3))}, {"throw": True, "sensors": 0}])
def test_a_problem_and_a_keyword_argument_are_refused(extra):
    # simulate(problem) skips the keyword form's bookkeeping; anything else given with it,
    # an array too (no truth value asked of it), is still refused, naming it
    from seahelm.errors import ParameterError
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.problem import Problem

    problem = Problem(ship="mariner-nonlinear", t_final=1.0, dt=0.5)
    name = next(k for k in extra if k != "throw")
    with pytest.raises(ParameterError, match=f"not both \\(got {name}\\)") as err:
        simulate(problem, **extra)
    assert err.value.field == name
    assert simulate(problem, throw=True).ok.all()  # (throw and progress are not fields)
