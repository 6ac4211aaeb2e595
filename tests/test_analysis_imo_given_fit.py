"""The fit → posterior → IMO workflow as a library call (issue 47 item 4:
:mod:`seahelm.analysis.imo.given_fit`, what ``seahelm identify nomoto|mmg --imo N`` did inside
the CLI): the command's probabilities are the call's; missing speed or length and a fit that
identifies nothing are refused naming the argument."""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.imo.given_fit import imo_given_nomoto_fit
from seahelm.identification.nomoto_fit import fit_nomoto
from seahelm.identification.records import read_records
from seahelm.errors import ParameterError



def _record(tmp_path):
    """The zig-zag record of the Nomoto fit's tests (5 % noise seed)."""
    from test_analysis_nomoto_fit import synthetic, write_csv

    rec = synthetic(5)
    return write_csv(tmp_path / "zz.csv", ("time", "rudder_angle", "heading"),
                     zip(rec.time, np.degrees(rec.rudder_angle), np.degrees(rec.heading)))


def test_the_command_is_the_library_call(tmp_path):
    from seahelm.cli.main import app

    path = _record(tmp_path)
    res = CliRunner().invoke(app, ["identify", "nomoto", str(path), "--imo", "6", "--seed", "2",
                                   "--speed", "7", "--length", "150", "--json"])
    assert res.exit_code == 0, res.output
    shown = json.loads(res.stdout)["imo"]
    records = read_records([path])
    fit = fit_nomoto(records, 1, seed=2)
    got = imo_given_nomoto_fit(fit, records, 6, speed=7.0, length=150.0, seed=2)
    assert got == shown
    assert got["samples"] == 6 and got["posterior"] == "laplace" and got["seed"] == 2


@pytest.mark.parametrize("speed, length, field", [(None, 150.0, "speed"), (7.0, None, "length")])
def test_speed_and_length_are_needed(speed, length, field):
    with pytest.raises(ParameterError, match="the IMO limits are in ship lengths") as info:
        imo_given_nomoto_fit(None, [], 4, speed=speed, length=length)
    assert info.value.field == field


def test_a_fit_that_identifies_nothing_has_no_posterior():
    fit = SimpleNamespace(unidentifiable=lambda: {"gain", "rudder_offset"})
    with pytest.raises(ParameterError, match="do not identify gain; no posterior") as info:
        imo_given_nomoto_fit(fit, [], 4, speed=7.0, length=150.0)
    assert info.value.field == "fit"
