"""``seahelm report -o`` writes only a file named ``.html`` (or ``.htm``). Before: ``seahelm
report result.nc -o out.txt`` wrote a 4.9 MB HTML page named out.txt, exit 0."""
from __future__ import annotations

import os

import numpy as np
import pytest

from conftest import one_error
from seahelm.simulation.engine import simulate
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params


@pytest.mark.parametrize("name, said", [("out.txt", "(suffix '.txt')"), ("page", "(no suffix)")])
def test_a_report_not_named_html_is_refused_before_any_work(tmp_path, name, said):
    result = tmp_path / "result.nc"
    simulate(NOMOTO1, Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0), np.zeros(4),
             t_final=2.0, dt=0.1).to_netcdf(result)
    out = tmp_path / name
    line = one_error(["report", str(result), "-o", str(out)])
    assert line == f"error: `--out` must name an .html file, got {str(out)!r} {said}"
    assert os.listdir(tmp_path) == ["result.nc"]
