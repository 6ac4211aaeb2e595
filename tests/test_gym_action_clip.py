"""The vector environments' actions: a policy's batch (float32 or float64, of the space's
shape) is clipped in one compiled pass (:func:`seahelm.gym._fused.clip_actions`) to the same
numbers as numpy's ``np.minimum(np.maximum(a, low), high)``; a NaN or infinite action is
refused naming the sub-environment, as on the general path."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("gymnasium")

from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym._fused import clip_actions  # noqa: E402


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_clip_is_numpys(dtype):
    rng = np.random.default_rng(4)
    low, high = np.array([-0.61, 0.0]), np.array([0.61, 17.5])
    a = (rng.uniform(-1.0, 1.0, (257, 2)) * np.array([1.5, 30.0])).astype(dtype)
    a[0] = low  # (on the bounds exactly)
    a[1] = high
    a[2] = [-0.0, -0.0]
    out = np.full(a.shape, np.nan)
    assert clip_actions(a, low, high, out) == -1
    expected = np.minimum(np.maximum(a.astype(np.float64), low), high)
    assert out.dtype == np.float64 and np.array_equal(out, expected)
    assert (out < low).sum() == 0 and (out > high).sum() == 0
    assert ((a < low) | (a > high)).any()  # (some were clipped)


def test_first_non_finite_is_named():
    a = np.zeros((5, 2), dtype=np.float32)
    a[3, 1] = np.inf
    a[4, 0] = np.nan
    assert clip_actions(a, np.array([-1.0, -1.0]), np.array([1.0, 1.0]),
                        np.empty((5, 2))) == 3 * 2 + 1


def test_env_refuses_nan_in_a_batch_naming_the_sub_environment():
    from seahelm.gym import ShipVectorEnv

    envs = ShipVectorEnv(4, task="HeadingKeeping", episode_seconds=10.0, integrator="euler")
    envs.reset(seed=0)
    a = np.zeros((4, 1), dtype=np.float32)
    a[2, 0] = np.nan
    before = envs._sim._z.copy()
    with pytest.raises(ParameterError, match="sub-environment 2") as exc:
        envs.step(a)
    assert exc.value.field == "actions"
    assert np.array_equal(envs._sim._z, before)  # (nothing stepped)
    big = np.full((4, 1), 10.0)  # (clipped to δ_max, float64 batch)
    envs.step(big)
    assert np.array_equal(envs._cmd[:, envs._rudder_col], np.full(4, envs._high[0]))
    envs.close()


def test_clip_of_signed_zeros_is_numpys_bit_for_bit():
    """On a tie with a bound the bound is taken, as numpy's maximum/minimum do: -0.0 against a
    lower bound 0.0 (the default ``propeller_rps`` action's) is +0.0 (it stayed -0.0, equal to
    numpy's by ``==`` but not by its bits; found by the review RV3)."""
    zeros = np.array([-0.0, 0.0])
    for lo in zeros:
        for hi in zeros:
            for x in (-0.0, 0.0, -1.0, 1.0):
                a = np.array([[x]])
                low, high = np.array([lo]), np.array([hi])
                out = np.empty((1, 1))
                assert clip_actions(a, low, high, out) == -1
                expected = np.minimum(np.maximum(a, low), high)
                assert out.view(np.uint64)[0, 0] == expected.view(np.uint64)[0, 0], (x, lo, hi)
    a = np.array([[-0.0, 0.1]] * 4)
    low, high, out = np.array([0.0, -0.61]), np.array([17.5, 0.61]), np.empty((4, 2))
    clip_actions(a, low, high, out)
    ref = np.minimum(np.maximum(a, low), high)
    assert np.array_equal(out.view(np.uint64), ref.view(np.uint64))


def test_huge_finite_actions_in_any_form_are_clipped_not_an_index_error():
    """Finite actions whose sum overflows (1e308 + 1e308 = inf) are clipped on every path: the
    general one (a list, a flat array) raised IndexError looking for the non-finite entry that
    is not there (found by the review RV3); the compiled ndarray path clipped them."""
    from seahelm.gym import ShipVectorEnv

    envs = ShipVectorEnv(2, task="HeadingKeeping", episode_seconds=10.0, integrator="euler")
    envs.reset(seed=0)
    top = np.full(2, envs._high[0])
    for actions in ([[1e308], [1e308]], np.full(2, 1e308), np.full((2, 1), 1e308)):
        np.testing.assert_array_equal(envs._actions(actions)[:, 0], top)
    with pytest.raises(ParameterError, match="sub-environment 1"):
        envs._actions([[1e308], [np.inf]])
    envs.close()
