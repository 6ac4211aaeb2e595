"""Bad input to ``seahelm linearize`` found by this round's campaign (issue 43)."""

from __future__ import annotations

import pytest

from conftest import one_error


@pytest.mark.parametrize("ship", ["kvlcc2-l7", "son-nomoto-container"])
def test_no_speed_is_named_on_either_side_of_a_kink(ship):
    # the KVLCC2's straight run is a kink (gamma_R switches at beta_R = 0): its sides' "no
    # Nomoto form" came in the library's words ("`model` the linear model has poles ..."),
    # as tests/test_cli_reliability_messages.py's test_linearize_at_no_speed_names_the_speed
    # found; son-nomoto-container at 1e-9 m/s is found non-smooth too, and said the same
    line = one_error(["linearize", ship, "--speed", "1e-9"])
    assert line.startswith("error: `--speed` 1e-09 m/s: the ship's linear model there has no "
                           "Nomoto form (the linear model has poles "), line
    assert "give a speed at which the ship moves and is straight-line stable" in line
    assert "`model`" not in line


@pytest.mark.parametrize("option", ["--speed", "--rps"])
def test_an_infinite_value_is_not_said_to_be_below_zero(option):
    # was: "`--speed` must be > 0 [m/s], got inf"
    args = ["linearize", "kvlcc2-l7", option, "inf"] + (["--rudder", "10"]
                                                       if option == "--rps" else [])
    unit = "m/s" if option == "--speed" else "1/s"
    assert one_error(args) == f"error: `{option}` must be a finite number > 0 [{unit}], got inf"
