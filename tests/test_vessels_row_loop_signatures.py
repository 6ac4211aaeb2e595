"""A model's numpy-level derivative and outputs reach its compiled row loops as one signature,
whatever broadcasts (issue 47 item 7: a broadcast that broadcasts nothing is a read-only view,
and the rows loops of the MMG and four-quadrant models compiled a second time for it)."""

from __future__ import annotations

import numpy as np

from seahelm.vessels.base import _row_loop
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params


def test_broadcast_or_full_batch_compiles_one_row_loop_signature():
    p = Nomoto1Params(gain=0.08, time_constant=20.0, speed=7.0)
    rng = np.random.default_rng(2)
    x = rng.normal(size=(3, NOMOTO1.n_states))
    u = rng.normal(size=(3, NOMOTO1.n_inputs))
    full = NOMOTO1.derivative(0.0, x, u, p)   # x, u of the batch's shape: no broadcast
    rhs = _row_loop(NOMOTO1.rhs, "rhs")
    before = list(rhs.signatures)
    one = [NOMOTO1.derivative(0.0, x[k], u[k], p) for k in range(3)]
    shared_u = NOMOTO1.derivative(0.0, x, u[0], p)   # u broadcast
    tiled = NOMOTO1.derivative(0.0, x, u, [p, p, p])
    assert list(rhs.signatures) == before
    for k in range(3):
        assert np.array_equal(one[k], full[k]) and np.array_equal(tiled[k], full[k])
    assert np.array_equal(shared_u[0], full[0])
    y = NOMOTO1.outputs(0.0, x, u, p)
    out = _row_loop(NOMOTO1.output, "output")
    before = list(out.signatures)
    assert np.array_equal(NOMOTO1.outputs(0.0, x[1], u[1], p), y[1])
    assert np.array_equal(NOMOTO1.outputs(0.0, x, u[0], p)[0], y[0])
    assert list(out.signatures) == before
