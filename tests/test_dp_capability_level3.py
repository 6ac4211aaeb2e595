"""DP capability level 3 (time domain, one batch) against level 1 where they must agree."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.dp.level1 import dp_vessel, level1_capability
from seahelm.analysis.dp.level3 import level3_capability
from seahelm.errors import ParameterError


@pytest.fixture(scope="module")
def both():
    l3 = level3_capability("supply", headings=4, wind_speeds=[10.0, 15.0], failures="none",
                           duration=600.0, dt=0.5)
    l1 = level1_capability(dp_vessel("supply"), headings=4, failures="none")
    return l3, l1


def test_level3_holds_what_level1_holds(both):
    """Constant mean loads, no wave motion: a wind is held in the time domain exactly when the
    static allocation balances it (level 1's U*: 21.3 m/s head-on, 12.0 m/s on the beam)."""
    l3, l1 = both
    want = l3.wind_speeds[None, :] <= l1.wind_speed[0][:, None]
    np.testing.assert_array_equal(l3.held[0], want)
    assert l3.wind_speed[0].tolist() == [15.0, 10.0, 15.0, 10.0]


def test_the_mean_thrust_is_the_static_demand(both):
    """Where held, the delivered thrust over the last half balances the mean load: the time
    domain's mean thrust equals level 1's static demand −τ_env (to 1e-3 of the load)."""
    l3, _ = both
    held = l3.held[0]
    rest = (l3.mean_thrust + l3.load)[0][held]
    scale = np.abs(l3.load[0][held]).max(axis=1, keepdims=True)
    assert np.all(np.abs(rest) <= 1e-3 * scale + 50.0), rest
    assert np.all(l3.excursion[0][held] < 5.0) and np.all(l3.excursion[0][~held] > 5.0)


@pytest.mark.parametrize("kw, field", [({"headings": 0}, "headings"),
                                       ({"wind_speeds": []}, "wind_speeds"),
                                       ({"wind_speeds": [40.0]}, "wind_speeds")])
def test_bad_grids_are_refused(kw, field):
    with pytest.raises(ParameterError) as info:
        level3_capability("supply", **kw)
    assert info.value.field == field


def test_a_failure_naming_no_thruster_is_refused():
    with pytest.raises(ParameterError, match="names no thruster"):
        level3_capability("supply", failures=["stern-tunnel-9"], headings=1,
                          wind_speeds=[5.0], duration=10.0)


def test_cli_level3(tmp_path):
    import json

    from typer.testing import CliRunner

    from seahelm.cli import app

    runner = CliRunner()
    files = {"--out": tmp_path / "l3.nc", "--json-out": tmp_path / "l3.json",
             "--plot": tmp_path / "l3.png"}
    res = runner.invoke(app, ["dp", "capability", "supply", "--level", "3", "--headings", "2",
                              "--winds", "10", "--failures", "none", "--duration", "300",
                              "--json", *(str(x) for kv in files.items() for x in kv)])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["level"] == 3 and out["wind_speed_m_s"]["intact"] == [10.0, 10.0]
    # the files: the same numbers (JSON), the grid's dimensions (NetCDF), a figure
    assert json.loads(files["--json-out"].read_text())["wind_speed_m_s"] == out["wind_speed_m_s"]
    import xarray as xr

    with xr.open_dataset(files["--out"]) as ds:
        assert ds.attrs["level"] == 3 and ds.held.dims == ("case", "direction", "wind")
        assert ds.held.values.tolist() == [[[1], [1]]]
        np.testing.assert_array_equal(ds.wind_speed.values, [[10.0, 10.0]])
    assert files["--plot"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for args, words in ((["--level", "2"], ["--level", "1 or 3", "2"]),
                        (["--level", "3", "--winds", "10,x"], ["--winds", "[m/s]", "10,x"]),
                        (["--level", "3", "--winds", "50"], ["--winds", "m/s", "50"]),
                        (["--level", "3", "--workers", "0"], ["--workers", "[-]", "0"]),
                        (["--level", "3", "--duration", "-5"], ["--duration", "[s]", "-5"])):
        res = runner.invoke(app, ["dp", "capability", "supply", *args])
        assert res.exit_code == 2, (args, res.output)
        line = res.stderr.strip()
        assert "\n" not in line and all(w in line for w in words), (args, line)


def test_level3_on_dask_equals_in_process():
    pytest.importorskip("distributed")
    kw = dict(headings=2, wind_speeds=[10.0, 15.0], failures=["main-port"], duration=200.0,
              dt=0.5)
    here = level3_capability("supply", **kw)
    there = level3_capability("supply", workers=2, **kw)
    np.testing.assert_array_equal(there.held, here.held)
    np.testing.assert_array_equal(there.excursion, here.excursion)
    np.testing.assert_allclose(there.mean_thrust, here.mean_thrust, rtol=1e-12)  # (the means
    # of the same records, summed in another order)
    with pytest.raises(ParameterError) as info:
        level3_capability("supply", workers=0, **kw)
    assert info.value.field == "workers"
