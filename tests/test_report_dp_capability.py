"""The report section of a DP capability file (seahelm.report.dp_capability): ``seahelm report``
on ``seahelm dp capability --out`` of level 1 and level 3 shows the rose and the table of the
winds held, and such a file is reported alone."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from seahelm.cli import app
from seahelm.errors import ParameterError
from seahelm.report.inputs import combined_report_data, load_report_data
from seahelm.report.sections import build_sections

runner = CliRunner()


def _write(tmp_path, name, *args):
    path = tmp_path / name
    res = runner.invoke(app, ["dp", "capability", *args, "--out", str(path)])
    assert res.exit_code == 0, res.output
    return path


def _section(path):
    data = load_report_data(path)
    found = [s for s in build_sections(data) if s.id == "dp-capability"]
    assert len(found) == 1
    return data, found[0]


def test_level1_section(tmp_path):
    path = _write(tmp_path, "l1.nc", "shushlyapin2017-dp", "--headings", "4")
    data, sec = _section(path)
    with xr.open_dataset(path) as ds:
        wind = ds.wind_speed.values
        cases = [str(c) for c in ds.case.values]
    assert "level 1" in sec.title and data.title.startswith("DP capability level 1")
    figure = next(b for b in sec.blocks if isinstance(b, dict))
    np.testing.assert_allclose(figure["data"][0]["r"][:4], wind[0])       # intact
    np.testing.assert_allclose(figure["data"][1]["r"][:4], wind[1:].min(axis=0))  # worst
    text = "".join(b for b in sec.blocks if isinstance(b, str))
    assert all(c in text for c in cases) and "least wind held" in text


def test_level3_section_and_the_html(tmp_path):
    path = _write(tmp_path, "l3.nc", "supply", "--level", "3", "--headings", "2", "--winds",
                  "10", "--failures", "none", "--duration", "300")
    data, sec = _section(path)
    assert "level 3" in sec.title and data.n_runs == 2
    text = "".join(b for b in sec.blocks if isinstance(b, str))
    assert "2 of 2 runs held" in text and "excursion" in text
    html = tmp_path / "r.html"
    res = runner.invoke(app, ["report", str(path), "--out", str(html)])
    assert res.exit_code == 0, res.output
    assert "DP station-keeping capability, level 3" in html.read_text()


def test_it_is_reported_alone(tmp_path):
    a = _write(tmp_path, "a.nc", "shushlyapin2017-dp", "--headings", "2")
    b = _write(tmp_path, "b.nc", "shushlyapin2017-dp", "--headings", "3")
    with pytest.raises(ParameterError, match="reported alone"):
        combined_report_data([a, b])
