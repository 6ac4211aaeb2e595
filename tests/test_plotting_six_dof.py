"""The 6-DOF figure: a result with depth, roll and pitch states gets track, depth, attitude,
propellers and fins (or the cross-track error of a guided craft without fins)."""

from __future__ import annotations

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

from seahelm.plotting.six_dof import is_six_dof  # noqa: E402
from seahelm.plotting.timeseries import plot_result  # noqa: E402
from seahelm.simulation.engine import simulate  # noqa: E402
from seahelm.simulation.problem import Problem  # noqa: E402


def test_an_otter_result_gets_the_six_dof_figure():
    ds = simulate(Problem(ship="otter", x0=np.zeros(14), t_final=2.0, dt=0.02, actuator="direct",
                          reference={"propeller_port_speed_command": 80.0,
                                     "propeller_starboard_speed_command": 60.0})).to_xarray()
    assert is_six_dof(ds)
    fig = plot_result(ds)
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["Track", "Depth", "Roll and pitch", "Propellers", "Fins", "Heading"]
    props = fig.axes[3]
    assert props.get_ylabel() == "shaft speed [rad/s]"
    # the port shaft speed is drawn in rad/s (not converted to degrees)
    np.testing.assert_allclose(props.lines[0].get_ydata(), ds["propeller_port_speed"].values[0])
    matplotlib.pyplot.close(fig)
