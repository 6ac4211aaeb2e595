"""Result files read back as SimResult: the same channels, parameters, status, metadata and
batch layout as the result that was written, so metrics computed from the file equal those
computed in memory."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.analysis.maneuvers import summarize
from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.errors import ParameterError
from seahelm.result_io import read_result, result_from_dataset
from seahelm.simulation.batch import BatchAxis, BatchLayout, BatchValues, simulate_batch
from seahelm.simulation.problem import Problem
from seahelm.vessels.nomoto import NOMOTO2


@pytest.fixture(scope="module")
def result():
    from seahelm.ships import get_ship

    mariner = get_ship("mariner-nomoto2").params
    gains = [PIDHeadingParams(kp=kp, kd=60.0) for kp in (1.0, 4.0) for _ in range(3)]
    layout = BatchLayout(
        axes=(BatchAxis(name="kp", values=[1.0, 4.0], key="controller.params.kp",
                        units="rad/rad"),
              BatchAxis(name="sample", values=np.arange(3))),
        values=(BatchValues(name="vessel.params.gain", values=np.linspace(0.15, 0.2, 6),
                            units="1/s", attrs={"distribution": "normal"}),))
    batch = Problem(model=NOMOTO2, params=mariner, x0=np.zeros(5), t_final=60.0, dt=0.1,
                     controller=PID_HEADING, controller_params=gains, controller_dt=0.5,
                     reference=[np.radians(20.0)], bounds={"yaw_rate": (-0.006, 0.006)},
                     layout=layout, metadata={"title": "round trip"})
    return simulate_batch(batch)


def test_a_file_reads_back_as_the_result_it_was_written_from(result, tmp_path):
    back = read_result(result.to_netcdf(tmp_path / "r.nc"))
    assert back.dims == result.dims == ("kp", "sample") and back.shape == (2, 3)
    np.testing.assert_array_equal(back.time, result.time)
    np.testing.assert_array_equal(back.state, result.state)
    assert back.state_labels == result.state_labels and back.state_units == result.state_units
    for label in result.channel_names():
        np.testing.assert_array_equal(back[label],
                                      np.broadcast_to(result[label], back[label].shape))
    np.testing.assert_array_equal(back.status, result.status)
    np.testing.assert_array_equal(back.failure_time, result.failure_time)
    assert back.status[3:].all() and not back.status[:3].any()  # kp = 4 leaves the bounds
    for comp, (cls, arr) in result.params.items():
        back_cls, back_arr = back.params[comp]
        assert back_cls.__name__ == cls.__name__
        assert back_cls.value_names() == cls.value_names()
        np.testing.assert_array_equal(back_arr, np.broadcast_to(arr, back_arr.shape))
    assert back.metadata["title"] == "round trip" and back.metadata["model"] == "nomoto2"
    (axis, sample), (drawn,) = back.layout.axes, back.layout.values
    assert (axis.name, axis.key, axis.units, list(axis.values)) == \
        ("kp", "controller.params.kp", "rad/rad", [1.0, 4.0])
    assert sample.name == "sample" and sample.key == ""
    np.testing.assert_array_equal(drawn.values, result.layout.values[0].values)
    assert dict(drawn.attrs) == {"distribution": "normal"} and drawn.units == "1/s"


def test_metrics_from_the_file_equal_those_in_memory(result, tmp_path):
    back = read_result(result.to_netcdf(tmp_path / "r.nc"))
    np.testing.assert_equal(summarize(back), summarize(result))
    # and the Dataset in memory, shaped or flat, reads back the same
    np.testing.assert_equal(summarize(result_from_dataset(result.to_xarray(flat=True))),
                            summarize(result))


def test_what_is_not_a_result_is_refused():
    import xarray as xr

    with pytest.raises(ParameterError, match="not a seahelm simulation result"):
        result_from_dataset(xr.Dataset({"x": ("t", np.arange(3.0))}))
