"""First use and bad input of the FMU (the bad-input campaign): fmpy's ``simulate_fmu`` without
``output_interval`` runs to the stop time (it used to pick stop_time/1000 as the
communication step, 0.005 s for 5 s, not a multiple of integration_step: the run stopped at
t = 0 without an exception), and a negative or NaN wind speed is refused (it used to be a
calm sea, silently)."""

from __future__ import annotations

from pathlib import Path

import pytest

fmpy = pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")
from fmpy.fmi1 import FMICallException  # noqa: E402
from seahelm.fmu import build_fmu  # noqa: E402


@pytest.fixture(scope="module")
def kv_fmu(tmp_path_factory) -> Path:
    return build_fmu("kvlcc2-l7", tmp_path_factory.mktemp("fmu") / "kv.fmu")


def test_simulate_fmu_with_its_defaults_reaches_the_stop_time(kv_fmu):
    res = fmpy.simulate_fmu(str(kv_fmu), stop_time=5.0, start_values={"rudder_command": 0.2})
    assert res["time"][-1] == 5.0
    assert list(res["time"]) == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]  # the 1 s DefaultExperiment
    assert res["heading"][-1] > 0.01  # turned to starboard under 0.2 rad of rudder


@pytest.mark.parametrize("wind", [-5.0, float("nan")])
def test_a_bad_wind_speed_is_refused(kv_fmu, wind):
    with pytest.raises(FMICallException, match="fmi2ExitInitializationMode"):
        fmpy.simulate_fmu(str(kv_fmu), stop_time=1.0, start_values={"wind_speed": wind})
