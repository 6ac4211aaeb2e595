"""``seahelm encounter`` with a ship that has no test speed (the Otter, the DP vessels): refused
with exit 2 and one line naming ``--own-ship`` / ``--target-ship`` and why, before anything
runs (was: "`own_speed` must be > 0 [m/s], got nan" and "`vessels[1].speed`: model 'otter'
has no input 'rudder_angle'", naming no option)."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app


def _fails(args: list[str]) -> str:
    res = CliRunner().invoke(app, ["encounter", *args])
    assert res.exit_code == 2, res.output
    lines = res.output.strip().splitlines()
    assert len(lines) == 1, res.output
    return lines[0]


@pytest.mark.parametrize("option", ["--own-ship", "--target-ship"])
@pytest.mark.parametrize("ship", ["otter", "supply"])
def test_monte_carlo_ship_without_test_speed_names_the_option(option, ship):
    line = _fails(["--monte-carlo", "2", option, ship])
    assert f"`{option}`: ship '{ship}' has no test speed [m/s]" in line
    assert "give a ship with one, e.g." in line and "kvlcc2-full" in line
    assert "own_speed" not in line and "nan" not in line


def test_situations_ship_without_test_speed_names_the_option(tmp_path):
    # refused before the situation file is read
    situation = tmp_path / "situation.json"
    situation.write_text("{}")
    line = _fails([str(situation), "--target-ship", "otter"])
    assert "`--target-ship`: ship 'otter' has no test speed [m/s]" in line


def test_unknown_ship_names_the_option():
    line = _fails(["--monte-carlo", "2", "--own-ship", "no-such-ship"])
    assert line.startswith("error: `--own-ship`: unknown catalog ship 'no-such-ship'")
