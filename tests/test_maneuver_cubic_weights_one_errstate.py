"""The cubic crossings' two solves under one error state (issue 46: one turning circle's
Python-level calls): ``_cubic_weights`` gives the weights of the form before -- each solve
``np.linalg.solve``, the transposed systems by ``np.swapaxes`` -- bit for bit, on brackets
with distinct nodes, with placeholders (``good`` False) and with NaN starts; ``_solve``'s
``quiet`` form equals ``np.linalg.solve`` and still raises on a singular system."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")

POWERS = np.arange(4)


def _brackets(seed: int, shape: tuple[int, int]):
    rng = np.random.default_rng(seed)
    s_nodes = np.sort(rng.uniform(-2.0, 3.0, shape + (4,)), axis=-1)
    c_nodes = np.sort(rng.uniform(0.0, 4.0, shape + (4,)), axis=-1)
    good = np.ones(shape, dtype=bool)
    s = rng.uniform(0.0, 1.0, shape)
    levels = rng.uniform(0.5, 3.0, shape[0])
    j0 = rng.integers(0, 100, shape)
    return levels, j0, s_nodes, c_nodes, good, s


def _reference(levels, j0, s_nodes, c_nodes, good, s):
    """The weights by np.linalg.solve and np.swapaxes (the form the code had before)."""
    vander = s_nodes[..., None] ** POWERS
    if not good.all():
        vander[~good] = np.eye(4)
    coef = np.linalg.solve(vander, c_nodes[..., None])[..., 0]
    s = s.copy()
    tc._newton(np.ascontiguousarray(coef), levels, s)
    powers = s[..., None] ** POWERS
    weights = np.linalg.solve(np.swapaxes(vander, -1, -2), powers[..., None])[..., 0]
    return j0, weights if good.all() else np.where(good[..., None], weights, np.nan)


@pytest.mark.parametrize("shape", [(3, 1), (3, 40), (2, 7)])
@pytest.mark.parametrize("variant", ["all good", "placeholders", "nan start"])
def test_cubic_weights_equal_the_two_solves_apart(shape, variant):
    args = list(_brackets(sum(shape), shape))
    if variant == "placeholders":
        args[4][0, 0] = False
        args[5][0, 0] = 0.0
    if variant == "nan start":
        args[5][-1, -1] = np.nan
    want_j0, want = _reference(*[a.copy() for a in args])
    got_j0, got = tc._cubic_weights(*[a.copy() for a in args])
    assert np.array_equal(got_j0, want_j0)
    assert np.array_equal(got, want, equal_nan=True)
    assert np.isfinite(got).any()


def test_quiet_solve_equals_numpy_linalg_solve():
    _, _, s_nodes, _, _, _ = _brackets(3, (3, 5))
    vander = s_nodes[..., None] ** POWERS
    rhs = np.random.default_rng(4).normal(size=(3, 5, 4, 1))
    for a in (vander, vander.transpose(0, 1, 3, 2)):
        with np.errstate(all="ignore"):
            got = tc._solve(a, rhs, quiet=True)
        assert np.array_equal(got, np.linalg.solve(a, rhs))
    with np.errstate(all="ignore"), pytest.raises(np.linalg.LinAlgError):
        tc._solve(np.ones((2, 1, 4, 4)), np.ones((2, 1, 4, 1)), quiet=True)
