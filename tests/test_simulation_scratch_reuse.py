"""A finished batch hands its scratch buffers to the next batch of the same kernel, zeroed.

Building a slice's two dozen scratch views cost some 20 µs, a tenth of a short manoeuvre
(issue 46 item 6); :meth:`seahelm.simulation.slicing._Slices.release` keeps them for the next
batch, which must see them as fresh ones (all zero) and give the same results bit for bit.
"""

from __future__ import annotations

import numpy as np

from seahelm.simulation import slicing
from seahelm.simulation.engine import prepare, simulate
from seahelm.simulation.problem import Problem
from seahelm.vessels.nomoto import NOMOTO2, Nomoto2Params


def _problem(runs: int = 1) -> Problem:
    return Problem(model=NOMOTO2, params=Nomoto2Params(gain=0.1, t1=20.0, t2=2.0, t3=3.0, speed=5.0), x0=np.zeros((runs, NOMOTO2.n_states)),
                   t_final=20.0, dt=0.1, reference={"rudder_command": 0.1})


def test_released_buffers_serve_the_next_batch_zeroed():
    first = prepare(_problem())
    sets = list(first.slices.scratch)
    for blocks in first.slices._blocks:
        for block in blocks:
            block.fill(7)  # (what a run leaves in them)
    first.slices.release()
    assert first.slices.scratch == []
    second = prepare(_problem())
    reused = list(second.slices.scratch)
    assert any(a is b for a in reused for b in sets)
    for sc in reused:
        for view in sc:
            assert not np.any(view), "a reused buffer is not zeroed"


def test_results_equal_with_fresh_and_reused_buffers():
    slicing._SCRATCH.clear()
    fresh = simulate(_problem(3))  # (fresh buffers, released at the end)
    assert slicing._SCRATCH  # kept for the next batch
    again = simulate(_problem(3))
    np.testing.assert_array_equal(fresh.state, again.state)
    np.testing.assert_array_equal(fresh.output, again.output)
    np.testing.assert_array_equal(fresh.command, again.command)


def test_at_most_scratch_kept_sets_per_kernel():
    slicing._SCRATCH.clear()
    batches = [prepare(_problem()) for _ in range(slicing.SCRATCH_KEPT + 3)]
    for b in batches:
        b.slices.release()
    assert all(len(v) <= slicing.SCRATCH_KEPT for v in slicing._SCRATCH.values())
