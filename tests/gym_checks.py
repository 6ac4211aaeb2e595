"""A check the gym tests share: each sub-environment of a ShipVectorEnv gives the observations
and rewards of a ShipEnv started from its state and target (batched = one by one, house style
11)."""

from __future__ import annotations

import numpy as np


def assert_each_sub_env_is_a_single_env(vector_env, single_env, actions, *, seed=9):
    """Step ``vector_env()`` (a ShipVectorEnv) with ``actions`` (steps, envs, actions) and
    each sub-environment's actions through a ``single_env()`` (a ShipEnv) set to its start:
    every observation and reward equal."""
    envs = vector_env()
    envs.reset(seed=seed)
    vsim = envs.plant.simulator
    n = envs.num_envs
    starts = [(vsim.state(i), float(envs.task.target[i])) for i in range(n)]
    batched = [envs.step(a)[:2] for a in actions]
    for i, (state, target) in enumerate(starts):
        env = single_env()
        env.reset(seed=0)
        env.plant.simulator.set_state(0, state)
        env.task.target[0] = target
        for k, a in enumerate(actions):
            obs, reward, *_ = env.step(a[i])
            np.testing.assert_array_equal(obs, batched[k][0][i])
            assert reward == batched[k][1][i]
        env.close()
    envs.close()
