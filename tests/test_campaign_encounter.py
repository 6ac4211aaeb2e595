"""Bad input to ``seahelm encounter`` (the bad-input campaign): exit 2 with one line naming the
option or key, before anything runs."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

import seahelm.cli.encounter as cli_encounter
from seahelm.cli.main import app

ONE_VESSEL = """
[encounter]
t_final = 60.0
[[vessel]]
ship = "kvlcc2-l7"
course_deg = 0.0
"""


def _fails(args: list[str]) -> str:
    res = CliRunner().invoke(app, ["encounter", *args])
    assert res.exit_code == 2, res.output
    lines = res.output.strip().splitlines()
    assert len(lines) == 1, res.output
    return lines[0]


@pytest.mark.parametrize("args, says", [
    # was: "`detection_range` ... got (-3.75, -5.0)" and "`dcpa` |dcpa| must be smaller ..."
    (["--detection", "-5"], "`--detection` must be > 1235 [m]"),
    (["--detection", "1"], "`--detection` must be > 1235 [m]"),
    # was: "expected non-negative integer" (numpy's, naming nothing)
    (["--seed", "-1"], "`--seed` must be an integer >= 0, got -1"),
    # was: "`target_speed`: no target in these ranges ..." (not an option)
    (["--t-final", "30"], "`--t-final`: no target detected at 9000 m reaches its CPA"),
])
def test_monte_carlo_options_are_named(args, says):
    assert says in _fails(["--monte-carlo", "3", *args])


def test_a_monte_carlo_too_big_for_the_memory_is_refused_before_drawing(monkeypatch):
    # was: --monte-carlo 1000000000 drew its geometry until the kernel killed it (exit 137)
    monkeypatch.setattr(cli_encounter, "_physical_memory", lambda: 10**6)
    line = _fails(["--monte-carlo", "1000"])
    assert line.startswith("error: `--monte-carlo` needs about 0.0121 GB for its tracks"), line


def test_a_missing_scenario_file_is_named(tmp_path):
    # was: "[Errno 2] No such file or directory: ..."
    assert f"`{tmp_path / 'no.toml'}`: no such file" in _fails([str(tmp_path / "no.toml")])


def test_an_encounter_of_one_vessel_says_it_needs_a_target(tmp_path):
    # was: exit 0 and a table without a row
    (tmp_path / "one.toml").write_text(ONE_VESSEL)
    assert "`vessel`: an encounter needs the own ship and at least one target" in _fails(
        [str(tmp_path / "one.toml")])
