"""The light restart of a vector environment's sub-environments (issue 52, speed):
:func:`~seahelm.simulation.stepping_reference.restart_runs` restarts only the runs that ended
and observes only them; the thread pool's slices are shared with the calling thread. Both
must leave every number as it was: the reference here is the earlier composition, still
public -- :func:`restart_clock` of the runs, :func:`set_states`, then a whole
:meth:`Simulator.observe`."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("gymnasium")

from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import ShipVectorEnv  # noqa: E402
from seahelm.simulation.stepping_reference import (restart_clock, restart_runs,  # noqa: E402
                                                   set_states)

N = 1024


class _WholeRestart(ShipVectorEnv):
    """The restart as it was: the runs reset by ``Simulator.reset`` (inside restart_clock),
    their states set, then every run observed."""

    def _begin(self, sel):
        p, sim = self.plant, self._sim
        restart_clock(sim, sel)
        self._cmd[sel] = p.command_start
        self._previous[sel] = p.command_start[self._rudder_col]
        self._done[sel] = False
        self.elapsed[sel] = 0.0
        set_states(sim, sel, self.task.begin(sel, self._rng))
        return sim.observe()


def _episode(cls, task, **kw):
    envs = cls(N, task=task, ship="kvlcc2-l7", episode_seconds=30.0, **kw)
    rng = np.random.default_rng(1)
    lo, hi = envs.single_action_space.low, envs.single_action_space.high
    obs, _ = envs.reset(seed=3)
    rows = [obs]
    bias = rng.uniform(lo, hi, (N, lo.size))  # (a turn of its own a sub-environment: the
    for _ in range(45):  # heading-keeping episodes fail at scattered steps)
        # (beyond the box: clipped)
        o, r, te, tr, _ = envs.step(bias + rng.uniform(0.4 * lo, 0.4 * hi, (N, lo.size)))
        rows += [o, r, te, tr]
    rows.append(envs.reset(options={"reset_mask": np.arange(N) % 3 == 0})[0])
    rows.append(envs.step(np.zeros((N, lo.size)))[0])
    envs.close()
    return rows


@pytest.mark.parametrize("task, kw", [("HeadingKeeping", {}),
                                      ("PathFollowing", {"autopilot": "pid-heading-rps"})])
def test_a_seeded_episode_is_bit_for_bit_the_whole_restarts(task, kw):
    new = _episode(ShipVectorEnv, task, **kw)
    old = _episode(_WholeRestart, task, **kw)
    terminated = np.array(new[3:-2:4])
    # restarts of a few runs at a time (the light path) and of most (the whole-batch path)
    per_step = terminated.sum(axis=1)
    assert task == "PathFollowing" or (0 < per_step).sum() > 5
    assert len(new) == len(old)
    for a, b in zip(new, old):
        assert np.array_equal(a, b)


@pytest.fixture(scope="module")
def envs():
    e = ShipVectorEnv(N, task="HeadingKeeping", ship="kvlcc2-l7", episode_seconds=30.0)
    e.reset(seed=0)
    yield e
    e.close()


def test_restart_runs_equals_reset_set_states_observe(envs):
    sim = envs._sim
    for _ in range(3):
        sim.step(np.tile(envs.plant.command_start, (N, 1)) + [0.2, 0.0])
    saved = [x.copy() for x in (sim._z, sim._cs, sim._cmd, sim._ca)]
    sel = np.array([0, 1, 2, 17, 500, N - 1])
    heading = np.linspace(-1.0, 1.0, sel.size)
    light = restart_runs(sim, sel, {"heading": heading})
    after = [x.copy() for x in (sim._z, sim._cs, sim._cmd, sim._ca)]
    for live, old in zip((sim._z, sim._cs, sim._cmd, sim._ca), saved):
        live[...] = old
    sim._k[:] = 3 * sim._batch.ctrl_every
    restart_clock(sim, sel)
    set_states(sim, sel, {"heading": heading})
    whole = sim.observe()
    assert np.array_equal(light.values, whole.values)
    assert np.array_equal(light.time, np.zeros(N)) and np.array_equal(whole.time, light.time)
    for a, b in zip(after, (sim._z, sim._cs, sim._cmd, sim._ca)):
        assert np.array_equal(a, b)
    assert np.array_equal(sim._z[sel, sim.state_labels.index("heading")], heading)


def test_restart_runs_refuses_a_bad_state_and_changes_nothing(envs):
    sim = envs._sim
    before = sim._z.copy(), sim._k.copy(), sim._out.copy()
    with pytest.raises(ParameterError) as info:
        restart_runs(sim, [4, 5], {"heading": [0.0, np.nan]})
    assert info.value.field == "values" and info.value.run == 5
    with pytest.raises(ParameterError) as info:
        restart_runs(sim, [4, 5], {"rudder": 0.0})
    assert "unknown state 'rudder'" in str(info.value)
    with pytest.raises(ParameterError) as info:
        restart_runs(sim, [N], {})
    assert info.value.field == "runs"
    for a, b in zip(before, (sim._z, sim._k, sim._out)):
        assert np.array_equal(a, b)


def test_a_slice_that_raises_is_raised_after_every_thread_stopped(envs):
    slices = envs._sim._batch.slices
    if slices.threads < 2:
        pytest.skip("one thread")
    done = []

    def one(s):
        if s == 3:
            raise RuntimeError("slice 3")
        done.append(s)

    with pytest.raises(RuntimeError, match="slice 3"):
        slices._shared(one)
    assert sorted(done) == [s for s in range(len(slices.bounds)) if s != 3]
