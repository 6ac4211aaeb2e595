"""The adaptive reference path (solve_reference), including right-hand sides with kinks."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.simulation.integrators import solve_reference


def _integral_abs_cos(t):
    """∫_0^t |cos s| ds in closed form: sin t up to π/2, then 2 per half period."""
    t = np.asarray(t, dtype=float)
    w = t - math.pi / 2
    q = np.floor(w / math.pi)
    after = 2.0 + 2.0 * q - np.cos(w - q * math.pi)
    return np.where(t <= math.pi / 2, np.sin(t), after)


def _rhs(t, x):
    # a kinked forcing and a smooth decaying state: both must be carried across restarts
    return np.array([abs(math.cos(t)), -0.5 * x[1]])


def test_closed_form_of_the_test_problem():
    s = np.linspace(0.0, 7.0, 200_001)
    numeric = np.concatenate([[0.0], np.cumsum(0.5 * (np.abs(np.cos(s[1:])) + np.abs(np.cos(s[:-1])))
                                               * np.diff(s))])
    np.testing.assert_allclose(_integral_abs_cos(s), numeric, atol=1e-8)


@pytest.mark.parametrize("method", ["DOP853", "RK45", "Radau"])
def test_breakpoints_make_the_tolerance_hold_across_kinks(method):
    t = np.linspace(0.0, 12.0, 25)
    kinks = math.pi / 2 + math.pi * np.arange(4)
    x = solve_reference(_rhs, [0.0, 1.0], t, breakpoints=kinks, rtol=1e-10, atol=1e-12,
                        method=method)
    np.testing.assert_allclose(x[:, 0], _integral_abs_cos(t), rtol=0, atol=1e-8)
    np.testing.assert_allclose(x[:, 1], np.exp(-0.5 * t), rtol=1e-8, atol=0)


def test_breakpoints_on_output_times_ends_and_duplicates():
    t = np.array([0.0, math.pi / 2, 2.0, 1.5 * math.pi])  # kinks on output times, on the end
    kinks = [math.pi / 2, math.pi / 2, 1.5 * math.pi, -3.0, 100.0]
    x = solve_reference(_rhs, [0.0, 1.0], t, breakpoints=kinks)
    np.testing.assert_allclose(x[:, 0], _integral_abs_cos(t), atol=1e-9)
    np.testing.assert_array_equal(x[0], [0.0, 1.0])


def test_bad_time_grid():
    with pytest.raises(ValueError, match="t_eval"):
        solve_reference(_rhs, [0.0, 1.0], [0.0, 2.0, 1.0])
