"""seahelm.gym's collision-avoidance task on seahelm.encounters: gymnasium's checker passes; a
constant action is the Encounter run (avoidance off for 0; an own ship steering its route
course + a for a) bit for bit; a collision terminates; the reward terms have the documented
signs on hand-made geometries; the target may avoid by the rule-based method; bad input names
its argument."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402
from seahelm.encounters import Encounter, Situation, Vessel  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym import CollisionAvoidance, EncounterEnv, EncounterVectorEnv  # noqa: E402

SHIP = "kvlcc2-l7"


@pytest.mark.parametrize("target_avoidance", [None, "rule-based"])
def test_check_env_passes_without_a_warning(target_avoidance):
    env = EncounterEnv(ship=SHIP, target_avoidance=target_avoidance, episode_seconds=30.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env, skip_render_check=True)
    env.close()


def test_make_and_make_vec_are_registered():
    env = gymnasium.make("seahelm/CollisionAvoidance-v0", episode_seconds=20.0)
    assert isinstance(env.unwrapped, EncounterEnv)
    assert env.unwrapped.action_labels == ("course_change",)
    env.close()
    envs = gymnasium.make_vec("seahelm/CollisionAvoidance-v0", num_envs=6, episode_seconds=20.0)
    assert isinstance(envs, EncounterVectorEnv)
    obs, _ = envs.reset(seed=0)
    assert obs.shape == (6, 12) and envs.observation_space.contains(obs)
    envs.close()


@dataclasses.dataclass(frozen=True)
class _RouteOffset:
    """An 'avoidance method' that steers the avoiding vessels' route heading + offset."""

    offset: float

    def start(self, n_encounters, n_vessels, avoid, encounter):
        return {"avoid": avoid}

    def desired(self, time, truth, view, route_heading, state):
        out = route_heading.copy()
        out[:, state["avoid"]] = route_heading[:, state["avoid"]] + self.offset
        return out


@pytest.mark.parametrize("action", [0.0, 0.3])
def test_a_constant_action_is_the_encounter_run(action):
    n, seconds = 4, 40.0
    envs = EncounterVectorEnv(n, ship=SHIP, episode_seconds=seconds, autoreset_mode="Disabled")
    envs.reset(seed=5)
    g = {k: v.copy() for k, v in envs.start_geometry.items()}
    stepped = [envs.vessel_states]
    for _ in range(int(seconds)):
        envs.step(np.full((n, 1), action))
        stepped.append(envs.vessel_states)
    envs.close()
    stepped = np.stack(stepped, axis=-1)  # (encounters, vessels, 6, time)
    own = Vessel(ship=SHIP, north=0.0, east=0.0, course=0.0, avoid=action != 0.0)
    target = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"])
    avoidance = None if action == 0.0 else _RouteOffset(action)  # off: the route course
    result = Encounter([own, target], t_final=seconds, avoidance=avoidance,
                       record_every=1).run()
    for j, name in enumerate(("north", "east", "course", "speed", "heading", "yaw_rate")):
        np.testing.assert_array_equal(stepped[:, :, j], result.tracks[name], err_msg=name)
    assert np.ptp(result.tracks["heading"][:, 0]) > (0.1 if action else -1.0)  # it turned
    # batched = one by one: each sub-environment is its encounter run alone
    for e in (0, n - 1):
        alone = Encounter([own, dataclasses.replace(target, north=g["north"][e],
                                                    east=g["east"][e], course=g["course"][e])],
                          t_final=seconds, avoidance=avoidance, record_every=1).run()
        np.testing.assert_array_equal(stepped[e, :, 0], alone.tracks["north"][0])
        np.testing.assert_array_equal(stepped[e, :, 4], alone.tracks["heading"][0])


def test_a_collision_terminates_with_the_collision_term():
    envs = EncounterVectorEnv(3, ship=SHIP, dcpa=0.01)  # on a collision course: CPA ±0.07 m
    envs.reset(seed=1)
    g = {k: v.copy() for k, v in envs.start_geometry.items()}
    for steps in range(1, 300):
        obs, reward, terminated, truncated, _ = envs.step(np.zeros((3, 1)))
        if terminated.any():
            break
    assert terminated.any() and not truncated.any()
    hit = terminated
    rng = obs[hit, envs.observation_labels.index("target_range")]
    assert (rng < envs.task.touch).all()  # (L_own + L_target) / 2
    assert (reward[hit] <= -100.0).all()
    obs, reward, terminated, *_ = envs.step(np.zeros((3, 1)))  # next step: a new encounter
    assert (reward[hit] == 0.0).all() and not terminated[hit].any()
    assert (obs[hit, envs.observation_labels.index("target_range")] > 11 * 7.0).all()
    # the others went on through that restart exactly as their encounter alone
    assert (~hit).any()
    states = envs.vessel_states
    for e in np.flatnonzero(~hit):
        alone = Encounter([Vessel(ship=SHIP, course=0.0),
                           Vessel(ship=SHIP, north=g["north"][e], east=g["east"][e],
                                  course=g["course"][e])],
                          t_final=float(steps + 1), record_every=1).run()
        np.testing.assert_array_equal(states[e, :, 0], alone.tracks["north"][0, :, -1])
        np.testing.assert_array_equal(states[e, :, 4], alone.tracks["heading"][0, :, -1])
    assert envs.elapsed[hit].tolist() == [0.0] * int(hit.sum())
    envs.close()


def _task(**kw):
    return CollisionAvoidance(1, own_length=100.0, target_length=100.0, own_speed=5.0,
                              target_speed=5.0, **kw)


def _vessel(north, east, heading, speed=5.0):
    # north, east, course, speed, heading, yaw rate
    return np.array([[north, east, heading, speed, heading, 0.0]])


def _terms(task, own, target):
    obs, terms, collided, passed = task.evaluate(own, target, np.array([[5.0, 0.0]]),
                                                 np.zeros(1), np.zeros((1, 2)))
    return {k: float(v[0]) for k, v in terms.items()}, bool(collided[0]), bool(passed[0]), obs


def test_reward_signs_on_hand_made_geometries():
    task = _task()
    own0 = _vessel(0.0, 0.0, 0.0)
    head_on = _vessel(2000.0, 0.0, math.pi)
    task.begin(np.arange(1), own0, head_on)
    assert task.situation[0] == Situation.HEAD_ON
    # far, on the route, on course: every term 0
    terms, collided, passed, obs = _terms(task, own0, head_on)
    assert terms == {"collision": 0.0, "domain": 0.0, "colreg_side": 0.0, "route": 0.0}
    assert not collided and not passed
    assert obs[0, 7] == 2000.0 and obs[0, 9] == pytest.approx(200.0)  # range, TCPA 2000/10
    # give-way (head-on), turned 10° to port before the CPA: the COLREG term
    port = _vessel(0.0, 0.0, -math.radians(10.0))
    assert _terms(task, port, head_on)[0]["colreg_side"] == -1.0
    starboard = _vessel(0.0, 0.0, math.radians(10.0))
    assert _terms(task, starboard, head_on)[0]["colreg_side"] == 0.0
    # a target inside the domain (ahead, 2 L: d = 0.5): -(1 - d)
    near = _vessel(200.0, 0.0, math.pi)
    terms, collided, *_ = _terms(task, own0, near)
    assert terms["domain"] == pytest.approx(-0.5) and not collided
    # within half the lengths' sum: a collision
    terms, collided, *_ = _terms(task, own0, _vessel(60.0, 0.0, math.pi))
    assert collided and terms["collision"] == -1.0 and terms["domain"] < -0.8
    # off the route by σ_e = 2 L: -(1 - e^-1)
    terms, *_ = _terms(task, _vessel(0.0, 200.0, 0.0), head_on)
    assert terms["route"] == pytest.approx(-(1.0 - math.exp(-1.0)))
    # passed: opening (TCPA < 0) and outside the domain; the COLREG term no longer counts
    terms, collided, passed, _ = _terms(task, port, _vessel(-1000.0, 50.0, math.pi))
    assert passed and not collided and terms["colreg_side"] == 0.0
    # stand-on (crossing from port): a turn to port is not the give-way side's fault
    from_port = _vessel(1000.0, -1000.0, math.pi / 2)
    task.begin(np.arange(1), own0, from_port)
    assert task.situation[0] == Situation.CROSSING_STAND_ON
    assert _terms(task, port, from_port)[0]["colreg_side"] == 0.0


def test_the_reward_is_the_weighted_sum():
    w = {"collision": 10.0, "domain": 2.0, "colreg_side": 3.0, "route": 4.0}
    task = _task(reward=w)
    own = _vessel(0.0, 150.0, -math.radians(20.0))
    target = _vessel(300.0, 0.0, math.pi)
    task.begin(np.arange(1), _vessel(0.0, 0.0, 0.0), target)
    terms = task.evaluate(own, target, np.array([[5.0, 0.0]]), np.zeros(1), np.zeros((1, 2)))[1]
    assert all(terms[k][0] < 0 for k in ("domain", "colreg_side", "route"))
    expected = sum(w[k] * terms[k][0] for k in w)
    assert task.reward(terms)[0] == pytest.approx(expected)


def test_a_rule_based_target_gives_way_to_starboard():
    # a target that is give-way (head-on, crossing with the own ship to starboard) turns
    envs = EncounterVectorEnv(8, ship=SHIP, target_avoidance="rule-based",
                              episode_seconds=60.0, autoreset_mode="Disabled")
    envs.reset(seed=3)
    course = envs.start_geometry["course"].copy()
    for _ in range(60):
        envs.step(np.zeros((8, 1)))
    heading = envs.vessel_states[:, 1, 4]
    turned = ((heading - course + np.pi) % (2 * np.pi)) - np.pi
    assert (turned > math.radians(5.0)).any()  # to starboard
    assert (turned > -math.radians(1.0)).all()  # never to port
    envs.close()


def test_seeds_reproduce_and_actions_are_clipped_nan_refused():
    def run(seed, action):
        envs = EncounterVectorEnv(2, ship=SHIP, episode_seconds=10.0)
        seen = [envs.reset(seed=seed)[0]]
        for _ in range(3):
            seen.append(envs.step(np.full((2, 1), action))[0])
        return envs, seen

    e1, a = run(4, 0.5)
    e2, b = run(4, 10.0)  # clipped to +45°
    for x, y in zip(a[:1], b[:1]):
        np.testing.assert_array_equal(x, y)
    e3, c = run(4, math.pi / 4)
    for x, y in zip(b, c):
        np.testing.assert_array_equal(x, y)
    with pytest.raises(ParameterError, match=r"action 'course_change' of sub-environment 1 is "
                                             r"nan; actions must be finite \[rad\]"):
        e1.step(np.array([[0.0], [np.nan]]))
    with pytest.raises(ParameterError, match=r"actions.*shape \(2, 1\)"):
        e1.step(np.zeros((3, 1)))
    for e in (e1, e2, e3):
        e.close()


def test_bad_input_is_refused_by_name():
    with pytest.raises(ParameterError, match="ship.*unknown catalog ship 'no-such-ship'"):
        EncounterVectorEnv(2, ship="no-such-ship")
    with pytest.raises(ParameterError, match="target_ship.*'nope'"):
        EncounterVectorEnv(2, target_ship="nope")
    with pytest.raises(ParameterError, match="unknown keyword 'route' of task "
                                             "CollisionAvoidance"):
        EncounterVectorEnv(2, route=[[0, 0], [1, 0]])
    with pytest.raises(ParameterError, match="avoidance.*'dodge'"):
        EncounterVectorEnv(2, target_avoidance="dodge")
    with pytest.raises(ParameterError, match="unknown reward term 'speed'"):
        EncounterVectorEnv(2, reward={"speed": 1.0})
    with pytest.raises(ParameterError, match=r"dcpa.*smaller than the detection range"):
        EncounterVectorEnv(2, dcpa=15.0)
    with pytest.raises(ParameterError, match=r"detection_range.*0 < low <= high"):
        EncounterVectorEnv(2, detection_range=(20.0, 10.0))
    with pytest.raises(ParameterError, match="num_envs.*>= 1, got 0"):
        EncounterVectorEnv(0)
    with pytest.raises(ParameterError, match="reset"):
        EncounterVectorEnv(1).step(np.zeros((1, 1)))


def test_the_docs_example_runs():
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "docs" / "guide"
            / "driven-from-outside.rst").read_text()
    section = text[text.index("**Collision avoidance**"):]
    lines = section[section.index(".. code-block:: python"):].splitlines()[2:]
    block = []
    for line in lines:
        if line and not line.startswith("    "):
            break
        block.append(line[4:])
    namespace: dict = {}
    exec("\n".join(block), namespace)  # noqa: S102 - the page's own example
    assert namespace["obs"].shape == (64, 12) and namespace["reward"].shape == (64,)
    namespace["envs"].close()
