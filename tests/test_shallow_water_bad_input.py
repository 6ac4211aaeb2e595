"""``--depth`` barely above the draft (issue 43 campaign)."""

from __future__ import annotations

from conftest import one_error


def test_a_depth_below_the_draft_shows_the_draft_as_given():
    # was: "must be greater than the draft 0.45499999999999996 [m]" (a float's repr)
    line = one_error(["maneuver", "turning", "--ship", "kvlcc2-l7", "--depth", "0.3"])
    assert line == "error: `--depth` must be greater than the draft 0.455 [m], got 0.3"


def test_no_approach_at_a_depth_at_the_draft_names_the_depth(recwarn):
    # 0.455 m is above the draft's float (0.45499999999999996 m): the approach's Jacobian is
    # singular there, which was blamed on `--speed` ("no straight approach ... at 1.179 m/s")
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, ["maneuver", "turning", "--ship", "kvlcc2-l7", "--depth",
                                   "0.455"])
    assert res.exit_code == 2, res.stderr
    line = res.stderr.strip().splitlines()[-1]  # (after the ValidityRangeWarning of h/d = 1)
    assert line.startswith("error: `--depth` = 0.455 m is 1 x the draft (0.455 m): no straight "
                           "approach of 'kvlcc2-l7' at 1.179 m/s ("), line
    assert line.endswith("; give deeper water"), line
    assert "`--speed`" not in line
