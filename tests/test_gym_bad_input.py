"""Bad input to :mod:`seahelm.gym` at its public boundary: a ParameterError naming the keyword
the user gave (``episode_seconds``, ``action``/``actions``, ``num_envs``), not the engine's
names or a bare numpy error from deep inside."""

import pytest

gymnasium = pytest.importorskip("gymnasium")

import seahelm.gym  # noqa: E402,F401  (registers the environments)
from seahelm.errors import ParameterError  # noqa: E402


@pytest.mark.parametrize("env_id", ["seahelm/HeadingKeeping-v0",
                                    "seahelm/CollisionAvoidance-v0"])
def test_a_too_long_episode_names_episode_seconds(env_id):
    # was: "`t_final`: 1 run(s) x 1e+13 steps ... a shorter `t_final`" (the engine's name)
    with pytest.raises(ParameterError, match=r"^`episode_seconds`: .* steps x runs .*a shorter "
                                             r"`episode_seconds` \(got 1e\+12 s\)") as info:
        gymnasium.make(env_id, episode_seconds=1e12)
    assert info.value.field == "episode_seconds"
    assert "t_final" not in str(info.value)


@pytest.mark.parametrize("env_id, labels", [
    ("seahelm/HeadingKeeping-v0", r"rudder_command \[rad\]"),
    ("seahelm/CollisionAvoidance-v0", r"course_change \[rad\]")])
def test_a_missing_action_says_missing_and_the_shape(env_id, labels):
    # was: "`actions`: action 'rudder_command' of sub-environment 0 is nan" (numpy turns None
    # into NaN)
    env = gymnasium.make(env_id)
    env.reset(seed=0)
    with pytest.raises(ParameterError, match=r"^`action`: missing \(None\); step\(\) needs an "
                                             rf"array of shape \(1,\) \({labels}\)$") as info:
        env.step(None)
    assert info.value.field == "action"
    env.close()


@pytest.mark.parametrize("env_id, labels", [
    ("seahelm/HeadingKeeping-v0", r"envs, rudder_command \[rad\]"),
    ("seahelm/CollisionAvoidance-v0", r"envs, course_change \[rad\]")])
def test_missing_vector_actions_say_missing_and_the_shape(env_id, labels):
    envs = gymnasium.make_vec(env_id, num_envs=3)
    envs.reset(seed=0)
    with pytest.raises(ParameterError, match=r"^`actions`: missing \(None\); step\(\) needs an "
                                             rf"array of shape \(3, 1\) \({labels}\)$"):
        envs.step(None)
    envs.close()
