"""The reset-mask option of seahelm's vector environments (gymnasium's autoreset): which
sub-environments a reset starts, and what a bad mask gets."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.gym.plant import reset_selection


def test_no_mask_starts_every_sub_environment():
    assert reset_selection(None, 4, False).tolist() == [0, 1, 2, 3]
    assert reset_selection({}, 3, True).tolist() == [0, 1, 2]


def test_a_mask_starts_only_its_sub_environments():
    mask = np.array([True, False, True, False])
    assert reset_selection({"reset_mask": mask}, 4, True).tolist() == [0, 2]


@pytest.mark.parametrize("mask", [np.array([1, 0, 1, 0]), np.array([True, False])])
def test_a_mask_of_another_dtype_or_shape_is_refused_naming_options(mask):
    with pytest.raises(ParameterError, match="reset_mask.*bool array of shape \\(4,\\)") as err:
        reset_selection({"reset_mask": mask}, 4, True)
    assert err.value.field == "options"


def test_the_first_reset_starts_every_one():
    with pytest.raises(ParameterError, match="first reset starts every"):
        reset_selection({"reset_mask": np.array([True, False])}, 2, False)
    assert reset_selection({"reset_mask": np.array([True, True])}, 2, False).tolist() == [0, 1]


def test_a_masked_reset_of_the_vector_env_restarts_only_those():
    """Sub-environment 1 restarted alone: its observation is that of a fresh episode with the
    same seed stream, the others carry on unchanged."""
    pytest.importorskip("gymnasium")
    from seahelm.gym import ShipVectorEnv

    envs = ShipVectorEnv(3, task="HeadingKeeping", ship="kvlcc2-l7")
    obs0, _ = envs.reset(seed=5)
    action = np.full((3, 1), 0.05)
    for _ in range(3):
        moved, *_ = envs.step(action)
    again, _ = envs.reset(options={"reset_mask": np.array([False, True, False])})
    assert np.array_equal(again[[0, 2]], moved[[0, 2]])
    assert not np.array_equal(again[1], moved[1])
    assert envs.elapsed[1] == 0.0 and envs.elapsed[0] > 0.0
