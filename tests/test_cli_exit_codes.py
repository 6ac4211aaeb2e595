"""Exit codes that mean the verdict, and ``--json`` errors as one JSON object (issue 36,
item 5)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from seahelm.cli._common import EXIT_BAD_INPUT, EXIT_NONCOMPLIANT
from seahelm.cli.main import app

runner = CliRunner()


@pytest.mark.parametrize(("ship", "passed"), [("mariner-nonlinear", False),
                                              ("son-nomoto-container", True)])
def test_imo_check_exits_4_when_the_ship_fails(ship, passed):
    checked = runner.invoke(app, ["imo", ship, "--check", "--json"])
    report = json.loads(checked.stdout)
    assert report["passed"] is passed
    assert checked.exit_code == (0 if passed else EXIT_NONCOMPLIANT), checked.output
    plain = runner.invoke(app, ["imo", ship])  # without --check: 0 whatever the verdict
    assert plain.exit_code == 0 and ("PASSES" if passed else "FAILS") in plain.stdout


def test_imo_check_is_documented():
    assert "exit with code 4" in " ".join(runner.invoke(app, ["imo", "--help"]).output.split()
                                          ).lower()


@pytest.mark.parametrize("args", [
    ["imo", "no-such-ship"],
    ["imo", "kvlcc2-l7", "--monte-carlo", "3", "--check"],
    ["run", "no-such-scenario.toml"],
    ["sweep", "no-such-scenario.toml"],
    ["ship", "show", "no-such-ship"],
    ["waves", "spectrum"],  # a parser error: missing --h3
    ["waves", "spectrum", "--h3", "abc"],  # a parser error: not a number
    ["identify", "steady-turn", "no-such.csv"],
    ["maneuver", "turning", "--ship", "no-such-ship"],
])
def test_json_errors_are_one_json_object(args):
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == EXIT_BAD_INPUT, res.output
    error = json.loads(res.stdout)  # exactly one object: json.loads refuses anything more
    assert error == {"error": error["error"], "exit_code": EXIT_BAD_INPUT}
    assert res.stderr.strip() == f"error: {error['error']}"


def test_without_json_errors_leave_stdout_empty():
    res = runner.invoke(app, ["imo", "no-such-ship"])
    assert res.exit_code == EXIT_BAD_INPUT and res.stdout == ""
