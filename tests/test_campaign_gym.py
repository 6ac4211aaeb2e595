"""Bad input to :mod:`seahelm.gym` (the bad-input campaign): each is a ParameterError naming
the keyword, not a TypeError/AttributeError from deep inside."""

import pytest

pytest.importorskip("gymnasium")

from seahelm.errors import ParameterError  # noqa: E402
from seahelm.gym.vector import ShipVectorEnv  # noqa: E402


@pytest.mark.parametrize("reward, says", [({"heading": "a"}, "must be a number, got 'a'"),
                                          ([1, 2], "must be a mapping")])
def test_a_bad_reward_weight_names_reward(reward, says):
    with pytest.raises(ParameterError, match=says) as info:
        ShipVectorEnv(1, ship="kvlcc2-l7", reward=reward)
    assert info.value.field == "reward"


@pytest.mark.parametrize("period", [0.05, 0.25])
def test_an_action_period_off_the_time_step_names_action_period(period):
    # was: "`controller_dt` must be a positive whole multiple of `dt`", a keyword the gym
    # user never gave
    with pytest.raises(ParameterError, match=r"`action_period` must be a whole multiple of "
                                             r"dt = 0\.1 s") as info:
        ShipVectorEnv(1, ship="kvlcc2-l7", dt=0.1, action_period=period)
    assert info.value.field == "action_period"
