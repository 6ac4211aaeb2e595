"""The cheaper forms of one turning circle's fixed cost give the numbers of the forms before.

Issue 46 item 6: one KVLCC2 L7 turning circle end to end must be >= 10x shipmmg, and of its
fixed cost most was Python around small arrays. Each shortcut here is checked against the
general form it replaces, bit for bit (``np.array_equal``), and its fallback is exercised.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")


def _systems(seed: int, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Vandermonde systems of four distinct nodes (as the cubic crossings make them)."""
    rng = np.random.default_rng(seed)
    nodes = np.sort(rng.uniform(-2.0, 3.0, shape + (4,)), axis=-1)
    vander = nodes[..., None] ** np.arange(4)
    return vander, rng.normal(size=shape + (4, 1))


@pytest.mark.parametrize("shape", [(3, 1), (3, 40), (1, 1), (2, 7)])
def test_solve_equals_numpy_linalg_solve_bit_for_bit(shape):
    vander, rhs = _systems(sum(shape), shape)
    for a in (vander, np.swapaxes(vander, -1, -2)):  # (both systems of _cubic_crossings)
        assert np.array_equal(tc._solve(a, rhs), np.linalg.solve(a, rhs))


def test_solve_of_a_singular_system_raises_as_numpy_does():
    a = np.ones((2, 1, 4, 4))
    with pytest.raises(np.linalg.LinAlgError):
        tc._solve(a, np.ones((2, 1, 4, 1)))


def test_solve_without_the_gufunc_is_numpy_linalg_solve(monkeypatch):
    vander, rhs = _systems(5, (3, 2))
    monkeypatch.setattr(tc, "_GESV", None)
    assert np.array_equal(tc._solve(vander, rhs), np.linalg.solve(vander, rhs))
