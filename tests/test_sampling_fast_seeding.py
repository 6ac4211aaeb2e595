"""The Monte-Carlo draws' generators computed for many samples at once: numpy's, bit for bit.

:func:`seahelm.numerics.sampling.draw_samples` sets one generator to each sample's PCG64 state
(computed for all samples by :func:`~seahelm.numerics.sampling._pcg64_states`) instead of
building ``default_rng(SeedSequence(seed, spawn_key=(i,)))`` per sample; the draws must be the
same numbers as that generator's, for every distribution and the correlated blocks.
"""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.numerics import sampling as S

SEEDS = [0, 1, 2, 99, 2**32 - 1, 2**32, 2**40 + 7, 2**64 + 3, 12345678901234567890123]
INDICES = np.array([0, 1, 2, 3, 17, 1000, 2**31, 2**32 - 1])


@pytest.mark.parametrize("seed", SEEDS)
def test_states_are_numpys_seed_sequence_children(seed):
    states = S._pcg64_states(seed, INDICES)
    assert len(states) == INDICES.size
    for (state, inc), i in zip(states, INDICES.tolist()):
        ref = np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(i,))).state["state"]
        assert (state, inc) == (ref["state"], ref["inc"]), (seed, i)


def test_indices_beyond_one_word_fall_back():
    assert S._pcg64_states(1, np.array([0, 2**32])) is None
    assert S._pcg64_states(1, np.array([], dtype=np.int64)) is None


def _one_generator_per_sample(marginals, seed, indices, correlated=()):
    """The draws as made before: a fresh generator per sample (the reference)."""
    keys = list(marginals) + [k for b in correlated for k in b.keys]
    out = {k: np.empty(len(indices)) for k in keys}
    for n, i in enumerate(indices):
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(int(i),)))
        for key, dist in marginals.items():
            out[key][n] = dist.sample(rng)
        for block in correlated:
            for key, v in zip(block.keys, block.sample(rng)):
                out[key][n] = v
    return out


MARGINALS = {
    "a": S.get_distribution("normal", mean=1.0, std=0.1),
    "b": S.get_distribution("uniform", low=0.0, high=2.0),
    "c": S.get_distribution("truncnormal", mean=0.0, std=1.0, low=-1.0, high=1.0),
    "d": S.get_distribution("lognormal", mean=0.0, std=0.5),
}
BLOCK = S.CorrelatedNormal(("x", "y"), np.array([0.0, 1.0]), np.array([[1.0, 0.5], [0.5, 2.0]]))


@pytest.mark.parametrize("seed", [0, 7, 2**33 + 5])
@pytest.mark.parametrize("indices", [np.arange(300), np.array([250, 3, 99, 0, 3]),
                                     np.array([5, 2**32 + 1, 0])])
def test_draws_equal_a_fresh_generator_per_sample(seed, indices):
    got = S.draw_samples(MARGINALS, seed, indices, [BLOCK])
    want = _one_generator_per_sample(MARGINALS, seed, indices, [BLOCK])
    assert set(got) == set(want)
    for key in want:
        np.testing.assert_array_equal(got[key], want[key], err_msg=key)
