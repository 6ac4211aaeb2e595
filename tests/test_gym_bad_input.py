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


@pytest.mark.parametrize("env_id", ["seahelm/HeadingKeeping-v0",
                                    "seahelm/CollisionAvoidance-v0"])
def test_too_many_envs_for_the_memory_name_num_envs(env_id):
    # was: numpy's "Unable to allocate 43.7 TiB for an array with shape (1000000000000, 6)"
    # (a bare MemoryError naming nothing)
    with pytest.raises(ParameterError, match=r"^`num_envs` = 1000000000000 needs about [0-9.e+]+ "
                                             r"GB \([0-9]+ B a sub-environment\), more than "
                                             r"the [0-9.]+ GB this process may use \(.+\); "
                                             r"give at most [0-9]+$") as info:
        gymnasium.make_vec(env_id, num_envs=10**12)
    assert info.value.field == "num_envs"


def test_the_memory_check_passes_what_fits():
    from seahelm.gym.plant import BYTES_PER_ENV, check_env_memory
    from seahelm.resources import memory_limit

    room = memory_limit().bytes
    check_env_memory(int(0.9 * room // BYTES_PER_ENV), BYTES_PER_ENV)  # no error
    with pytest.raises(ParameterError, match="`num_envs`"):
        check_env_memory(int(1.1 * room // BYTES_PER_ENV), BYTES_PER_ENV)
