"""A manoeuvre's approach speed far below the model's range is refused up front.

Before: ``seahelm maneuver turning --speed 1e-4`` worked 18 s and exited 0 with both turns
diverged ("state out of bounds at t = 182518 s" of a 1.4e7 s horizon); 0.01 m/s failed on the
steady turn with a solver message. Now one line naming ``--speed``, the model and its range.
"""
from __future__ import annotations

import pytest

from seahelm.cli.maneuver import LOWEST_SPEED_FRACTION, check_speed_rps
from seahelm.ships import get_ship

from conftest import one_error


@pytest.mark.parametrize("command", ["turning", "zigzag", "pullout", "stopping"])
@pytest.mark.parametrize("speed", ["1e-4", "0.1"])
def test_a_speed_below_the_models_range_is_one_error_line(command, speed):
    line = one_error(["maneuver", command, "--speed", speed])
    assert line == (f"error: `--speed` = {float(speed):g} m/s is below the range of "
                    "'kvlcc2-l7''s model mmg: from 0.1 x the speed its parameter set was "
                    "identified at (1.179 m/s), 0.1179 m/s (a model for manoeuvring at "
                    "moderate speed; above 1.5 x it warns)")


def test_the_imo_check_refuses_it_too():
    assert one_error(["imo", "kvlcc2-l7", "--speed", "1e-4"]).startswith(
        "error: `--speed` = 0.0001 m/s is below the range of 'kvlcc2-l7''s model mmg")


def test_a_low_speed_model_takes_a_low_speed():
    # esso-osaka-3m's mmg-ls is made for low speeds (its min_speed): no such refusal. The
    # check every manoeuvre command makes up front (the refusals above come from it), called
    # as the commands call it: a turning circle run through the CLI compiled a kernel only this
    # test used (mmg-ls on its rudder servo, open loop: ~24 CPU-s in a fresh clone) to show it
    esso = get_ship("esso-osaka-3m")
    assert "min_speed" in esso.params.field_names()
    assert 0.02 < LOWEST_SPEED_FRACTION * esso.approach_speed  # (refused on another model)
    check_speed_rps(esso, 0.02, None)  # no ParameterError


def test_a_turning_circle_shorter_than_one_default_sample_runs():
    # before: "`controller_dt` = 0.25 s exceeds `--t-final` = 0.05 s" (an option never given)
    from seahelm.analysis.maneuvers import turning_circle

    result = turning_circle("kvlcc2-l7", sides=1, t_final=0.05, dt=0.05)
    assert not bool(result.metrics["complete"])  # (nothing reached in one step, and said so)
    assert result.runs.sizes["time"] == 2
