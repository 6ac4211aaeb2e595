"""Bad input to ``seahelm dp capability`` and ``[[thrusters]]`` tables (the bad-input campaign)."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.ships.thrusters_file import layout_from_tables

TUNNEL = {"name": "bow", "kind": "tunnel", "x": 30.0, "y": 0.0, "max_thrust": 2e5}


def _azimuth(**sectors):
    return [TUNNEL, {"name": "az", "kind": "azimuth", "x": -30.0, "y": 0.0,
                     "max_thrust": 5e5, **sectors}]


@pytest.mark.parametrize("sectors, key, says", [
    # was: accepted as (0°, 0°), an empty sector: the azimuth was free all round
    ({"forbidden_sectors_deg": [[0, 360]]}, "thrusters[1].forbidden_sectors_deg[0]",
     "spans 360 [deg], a full turn or more"),
    # was: accepted as (350°, 40°), a 50° sector
    ({"forbidden_sectors_deg": [[-10, 400]]}, "thrusters[1].forbidden_sectors_deg[0]",
     "spans 410 [deg]"),
    ({"forbidden_sectors": [[0.0, 7.0]]}, "thrusters[1].forbidden_sectors[0]",
     "spans 7 [rad]"),
    # was: "`thrusters.forbidden` of thruster 'az' cover 360" (no index, not the file's key)
    ({"forbidden_sectors_deg": [[0, 180], [170, 360]]}, "thrusters[1].forbidden_sectors_deg",
     "cover 360 [deg] together"),
])
def test_forbidden_sectors_leaving_no_direction_are_refused_by_key(sectors, key, says):
    with pytest.raises(ParameterError, match=r"\A`" + key.replace("[", r"\[").replace(
            "]", r"\]") + "` " + says.replace("[", r"\[").replace("]", r"\]")) as info:
        layout_from_tables(_azimuth(**sectors))
    assert info.value.field == key


def test_sectors_with_directions_left_still_load():
    layout = layout_from_tables(_azimuth(forbidden_sectors_deg=[[350, 10], [80, 100]]))
    assert len(layout.forbidden[1]) == 2


def test_absurdly_many_headings_are_refused():
    # was: --headings 100000000 ran on (no answer after minutes)
    res = CliRunner().invoke(app, ["dp", "capability", "supply", "--headings", "100000000"])
    assert res.exit_code == 2, res.output
    assert res.output.strip() == ("error: `--headings` must be ≤ 3600 (0.1° apart) [-], got "
                                  "100000000")
