"""SimResult: xarray layout, NetCDF round trip with metadata, CSV, atomic writes, plots."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from seahelm import __version__
from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.results import atomic_write, load_result
from seahelm.simulation.engine import simulate
from seahelm.vessels.nomoto import NOMOTO2


@pytest.fixture(scope="module")
def result():
    from seahelm.ships import get_ship

    p = get_ship("mariner-nomoto2").params
    return simulate(NOMOTO2, [p, p.replace(gain=0.2)], np.zeros(5), t_final=60.0, dt=0.1,
                    controller=PID_HEADING, controller_params=PIDHeadingParams(kp=2.0),
                    reference=[math.radians(10.0)], record_every=10, seed=42,
                    metadata={"scenario_text": "title = 'x'\n"})


def test_to_xarray_layout(result):
    ds = result.to_xarray()
    assert dict(ds.sizes) == {"run": 2, "time": 61}
    for name in ("north", "east", "heading", "yaw_rate", "yaw_aux", "rudder_angle",
                 "surge_speed", "rudder_command", "reference_heading", "rudder_disturbance"):
        assert ds[name].dims == ("run", "time"), name
    assert ds["heading"].attrs["units"] == "rad"
    assert ds["vessel.gain"].values.tolist() == [0.185, 0.2]
    assert ds["controller.kp"].attrs["units"] == "rad/rad"
    assert ds.attrs["seahelm_version"] == __version__
    assert ds.attrs["integrator"] == "rk4"
    assert ds.attrs["dt"] == 0.1 and ds.attrs["seed"] == 42
    assert "created" in ds.attrs
    np.testing.assert_array_equal(ds["heading"].values, result["heading"])


def test_netcdf_round_trip_keeps_values_and_metadata(result, tmp_path):
    path = result.to_netcdf(tmp_path / "out" / "r.nc")
    back = load_result(path)
    ref = result.to_xarray()
    for name in ref.data_vars:
        if name == "status_message":
            assert list(back[name].values) == list(ref[name].values)
        else:
            np.testing.assert_array_equal(back[name].values, ref[name].values)
            assert back[name].attrs.get("units") == ref[name].attrs.get("units")
    for key in ("seahelm_version", "integrator", "dt", "seed", "scenario_text", "model"):
        assert back.attrs[key] == ref.attrs[key]
    assert not list(tmp_path.joinpath("out").glob("*.tmp"))


def test_csv_export(result, tmp_path):
    import pandas as pd

    frame = pd.read_csv(result.to_csv(tmp_path / "r.csv"))
    assert len(frame) == 2 * 61
    assert {"run", "time", "heading", "rudder_angle"} <= set(frame.columns)
    np.testing.assert_allclose(frame.loc[frame.run == 1, "heading"], result["heading"][1],
                               rtol=1e-9)


def test_atomic_write_keeps_old_file_on_failure(tmp_path):
    target = tmp_path / "keep.txt"
    target.write_text("old")

    def broken(tmp):
        with open(tmp, "w") as fh:
            fh.write("half")
        raise RuntimeError("disk on fire")

    with pytest.raises(RuntimeError, match="disk on fire"):
        atomic_write(target, broken)
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_load_result_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="result file not found"):
        load_result(tmp_path / "nope.nc")


def test_plot_draws_four_panels(result):
    import matplotlib.pyplot as plt

    fig = result.plot()
    axes = fig.get_axes()
    assert [a.get_title() for a in axes] == ["Heading", "Rudder angle (positive turns to starboard)",
                                             "Yaw rate", "Track"]
    assert len(axes[0].get_lines()) >= 2  # runs and reference
    plt.close(fig)


def test_channel_lookup_lists_names(result):
    with pytest.raises(KeyError, match="no channel 'flap_angle'; channels: north, east"):
        result["flap_angle"]


def test_dataset_is_xarray(result):
    assert isinstance(result.to_xarray(), xr.Dataset)


def test_layout_shapes_the_dataset_and_survives_netcdf(result, tmp_path):
    import dataclasses

    from seahelm.results import flatten_runs
    from seahelm.simulation.batch import BatchAxis, BatchLayout

    axis = BatchAxis(name="gain", values=[0.185, 0.2], key="vessel.params.gain", units="1/s")
    shaped = dataclasses.replace(result, layout=BatchLayout(axes=(axis,)))
    ds = shaped.to_xarray()
    assert ds["heading"].dims == ("gain", "time") and ds["status"].dims == ("gain",)
    assert "run" not in ds.variables
    assert ds["gain"].attrs == {"key": "vessel.params.gain", "units": "1/s"}
    np.testing.assert_array_equal(ds["heading"].values, result["heading"])
    back = load_result(shaped.to_netcdf(tmp_path / "g.nc"))
    assert back["heading"].dims == ("gain", "time")
    assert back["gain"].values.tolist() == [0.185, 0.2]
    assert back["gain"].attrs["key"] == "vessel.params.gain"
    flat = flatten_runs(back)
    assert flat["heading"].dims == ("run", "time") and flat["gain"].dims == ("run",)
    np.testing.assert_array_equal(flat["heading"].values, result["heading"])
    # a plain result: the flat view is the Dataset itself
    assert result.to_xarray(flat=True)["heading"].dims == ("run", "time")


def test_layout_must_match_the_number_of_runs(result):
    import dataclasses

    from seahelm.errors import ParameterError
    from seahelm.simulation.batch import BatchLayout

    with pytest.raises(ParameterError, match=r"spans 3 run\(s\), but the engine ran 2"):
        dataclasses.replace(result, layout=BatchLayout.runs(3))
