"""A problem that lets its checked inputs be kept is prepared again without re-checking them.

:func:`seahelm.simulation.frame.keep_inputs` (used by a manoeuvre's prepared request, issue 46)
lets :func:`~seahelm.simulation.engine.prepare` keep a problem's converted and checked inputs on
it: preparing it again copies them (every batch owns its arrays) instead of converting and
checking them anew. The results are the same bit for bit; a caller's own problem is prepared
afresh (its arrays may have changed in place); the machine's guards run at every call.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from seahelm.simulation.engine import prepare, simulate
from seahelm.simulation.frame import _Inputs, keep_inputs
from seahelm.simulation.problem import Problem

engine = importlib.import_module("seahelm.simulation.engine")


def _problem(**kw):
    x0 = np.zeros((2, 6))
    x0[:, 0] = [1.0, 1.2]
    kw = {"ship": "kvlcc2-l7", "x0": x0, "t_final": 5.0, "dt": 0.1,
          "reference": {"rudder_command": 0.2, "propeller_rps": 11.0}} | kw
    return Problem(**kw)


def _spy(monkeypatch):
    calls = []
    real = engine.problem_inputs
    monkeypatch.setattr(engine, "problem_inputs",
                        lambda *a, **k: (calls.append(1), real(*a, **k))[1])
    return calls


def _equal(a, b):
    for field in ("time", "state", "output", "command", "reference", "disturbance", "status"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    for key in a.params:
        assert np.array_equal(a.params[key][1], b.params[key][1]), key


def test_kept_inputs_are_checked_once_and_give_the_same_numbers(monkeypatch):
    calls = _spy(monkeypatch)
    fresh = simulate(_problem())
    p = keep_inputs(_problem())
    first, again, third = simulate(p), simulate(p), simulate(p)
    assert len(calls) == 2  # (the fresh problem's and the kept one's first preparation)
    for r in (first, again, third):
        _equal(fresh, r)
    kept = p.__dict__["_kept_inputs"]
    assert type(kept) is _Inputs and not kept.z.flags.writeable
    assert np.array_equal(kept.z[:, 0], [1.0, 1.2])  # (no run wrote into what is kept)


def test_every_batch_owns_its_arrays():
    p = keep_inputs(_problem())
    a, b = prepare(p), prepare(p)
    kept = p.__dict__["_kept_inputs"]
    for ga, gb in zip(a.slices.arrays, b.slices.arrays):
        assert not np.shares_memory(ga, gb) or ga.size == 0
    for arr in a.slices.arrays:
        assert arr.flags.writeable
        for name in ("mp", "ap", "cp", "z", "lower", "upper", "dist", "ref"):
            assert not np.shares_memory(arr, getattr(kept, name))
    assert not np.shares_memory(a.info["mp"], b.info["mp"])


def test_a_callers_problem_is_prepared_afresh(monkeypatch):
    calls = _spy(monkeypatch)
    p = _problem()
    before = simulate(p)
    p.x0[:, 0] = 0.5  # (changed in place: the next run starts from it, as always)
    after = simulate(p)
    assert len(calls) == 2 and "_kept_inputs" not in p.__dict__
    assert after.state[0, 0, 0] == 0.5 and before.state[0, 0, 0] == 1.0


def test_the_guards_run_at_every_call(monkeypatch):
    p = keep_inputs(_problem())
    simulate(p)

    def refuse(*args, **kwargs):
        raise engine.RecordingTooLarge("too large (test)", need=10**12, total=10**9)

    monkeypatch.setattr(engine, "check_record_memory", refuse)
    with pytest.raises(engine.RecordingTooLarge):
        simulate(p)


def test_a_problem_that_fails_its_checks_fails_again():
    p = keep_inputs(_problem(bounds={"surge_speed": (1.1, 2.0)}))  # run 0 starts at 1.0
    for _ in range(2):
        with pytest.raises(engine.ParameterError, match="initial state of run 0"):
            simulate(p)
    assert p.__dict__["_kept_inputs"] is None


def test_a_kept_batch_starts_without_the_zero_step_call(monkeypatch):
    slicing = importlib.import_module("seahelm.simulation.slicing")
    calls = []
    real = slicing._Slices.warm_up
    monkeypatch.setattr(slicing._Slices, "warm_up",
                        lambda self, *a: (calls.append(1), real(self, *a))[1])
    fresh = simulate(_problem())
    p = keep_inputs(_problem())
    first, again = simulate(p), simulate(p)
    assert len(calls) == 2  # (the fresh problem's and the kept one's first batch)
    assert again.metadata["execution"] == "compiled"
    _equal(fresh, first)
    _equal(fresh, again)


def test_kept_records_are_what_as_records_makes():
    from seahelm.parameters import as_records

    p = keep_inputs(_problem())
    prepare(p)
    kept = p.__dict__["_kept_inputs"]
    for which, (rows, cls) in enumerate(((kept.mp, kept.m_cls), (kept.ap, kept.a_cls),
                                         (kept.cp, kept.c_cls))):
        mine = rows.copy()
        got, want = kept.as_records(mine, which, cls), as_records(rows.copy(), cls)
        assert got.dtype == want.dtype and got.shape == want.shape
        assert got.tobytes() == want.tobytes() and got.flags.writeable
        if rows.shape[1] == 0:  # (no field: records on a buffer of their own, as_records')
            assert kept.records[which] is None
        else:
            assert np.shares_memory(got, mine) and got.flags.c_contiguous
    batch = prepare(p)
    assert batch.info["kept"]
    for rec, rows in zip(batch.slices.arrays.params[:3], (batch.info["mp"], batch.info["ap"],
                                                          batch.info["cp"])):
        assert np.shares_memory(rec, rows) or rows.shape[1] == 0
