"""Problem (a batch), BatchLayout and simulate_batch: one typed description from inputs to shaped results."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO

from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.errors import ParameterError
from seahelm.results import flatten_runs
from seahelm.simulation.batch import (
    BatchAxis,
    BatchLayout,
    BatchValues,
    grid_axes,
    simulate_batch,
)
from seahelm.simulation.problem import Problem
from seahelm.simulation.engine import simulate
from seahelm.vessels.nomoto import NOMOTO2

KPS, KDS = (1.0, 2.5), (20.0, 60.0, 90.0)


def _gain_grid(mariner2, **changes):
    gains = [PIDHeadingParams(kp=kp, kd=kd) for kp in KPS for kd in KDS]  # C order: kd fastest
    layout = BatchLayout(axes=grid_axes({"controller.params.kp": KPS,
                                         "controller.params.kd": KDS}))
    kw = dict(model=NOMOTO2, params=mariner2, x0=np.zeros(5), t_final=30.0, dt=0.1,
              controller=PID_HEADING, controller_params=gains, reference=[math.radians(15.0)],
              record_every=5, seed=3, metadata={"title": "grid"}, layout=layout)
    kw.update(changes)
    return Problem(**kw)


def test_simulate_batch_keeps_the_layout_and_equals_single_runs(mariner2):
    result = simulate_batch(_gain_grid(mariner2))
    ds = result.to_xarray()
    assert result.dims == ("kp", "kd") and result.shape == (2, 3)
    assert ds["yaw_rate"].dims == ("kp", "kd", "time")
    assert ds.attrs["title"] == "grid" and ds.attrs["seed"] == 3
    for kp in KPS:
        for kd in KDS:
            alone = simulate(NOMOTO2, mariner2, np.zeros(5), t_final=30.0, dt=0.1,
                             controller=PID_HEADING,
                             controller_params=PIDHeadingParams(kp=kp, kd=kd),
                             reference=[math.radians(15.0)], record_every=5)
            np.testing.assert_allclose(ds["heading"].sel(kp=kp, kd=kd).values,
                                       alone["heading"][0], rtol=1e-13, atol=1e-15)


def test_without_a_layout_the_result_has_one_run_dimension(mariner2):
    result = simulate_batch(_gain_grid(mariner2, layout=None))
    ds = result.to_xarray()
    assert ds["heading"].dims == ("run", "time") and ds.sizes["run"] == 6
    assert flatten_runs(ds) is ds


def test_layout_that_does_not_match_the_runs_is_rejected(mariner2):
    batch = _gain_grid(mariner2, layout=BatchLayout.runs(4))
    with pytest.raises(ParameterError, match=r"batch layout \{'run': 4\} spans 4 run\(s\), "
                                             r"but the engine ran 6"):
        simulate_batch(batch)


def test_run_batch_is_frozen_and_passes_the_engine_its_arguments(mariner2):
    batch = _gain_grid(mariner2)
    with pytest.raises(dataclasses.FrozenInstanceError):
        batch.dt = 0.2
    with pytest.raises(TypeError):
        batch.bounds["heading"] = (0.0, 1.0)
    kwargs = batch.simulate_kwargs()
    assert "layout" not in kwargs
    assert kwargs["t_final"] == 30.0 and kwargs["controller"] is PID_HEADING
    assert kwargs["actuator"] is RUDDER_SERVO  # the default, resolved once
    assert batch.n_runs == 6 and batch.replace(dt=0.05).dt == 0.05
    # the keyword form makes the same problem: the same numbers
    again = simulate(**kwargs)
    np.testing.assert_array_equal(again.state, simulate_batch(batch).state)


def test_a_problem_is_validated_once_on_construction(mariner2):
    # the problem refuses bad timing itself, naming the field; replace() validates again
    with pytest.raises(ParameterError, match=r"`t_final` must be a positive whole multiple") as e:
        _gain_grid(mariner2, t_final=30.05)
    assert (e.value.field, e.value.unit) == ("t_final", "s")
    batch = _gain_grid(mariner2)
    with pytest.raises(ParameterError) as e:
        batch.replace(controller_dt=0.15)
    assert e.value.field == "controller_dt"
    with pytest.raises(ParameterError, match="give a Problem or keyword arguments, not both"):
        simulate(batch, dt=0.1)


def test_layout_point_and_size():
    layout = BatchLayout(axes=(BatchAxis(name="kp", values=[1.0, 2.0, 3.0], key="c.kp"),
                               BatchAxis(name="sample", values=np.arange(4))))
    assert layout.dims == ("kp", "sample") and layout.shape == (3, 4) and layout.size == 12
    assert layout.point(0) == {"kp": 1.0, "sample": 0}
    assert layout.point(6) == {"kp": 2.0, "sample": 2}
    assert layout.point(11) == {"kp": 3.0, "sample": 3}
    with pytest.raises(IndexError, match="run 12 is outside the batch of 12 run"):
        layout.point(12)
    assert BatchLayout.runs(5).dims == ("run",) and BatchLayout.runs(5).is_flat


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: BatchLayout(axes=()), "at least one axis"),
        (lambda: BatchLayout(axes=(BatchAxis(name="kp", values=[1.0]),
                                   BatchAxis(name="kp", values=[2.0]))),
         "batch dimension 'kp' appears twice"),
        (lambda: BatchLayout(axes=(BatchAxis(name="time", values=[1.0]),)),
         "batch dimension 'time' is reserved"),
        (lambda: BatchAxis(name="kp", values=[]),
         r"must be a non-empty 1-D sequence, got shape \(0,\)"),
        (lambda: BatchAxis(name="", values=[1.0]), "must be a non-empty string"),
        (lambda: BatchLayout(axes=(BatchAxis(name="kp", values=[1.0, 2.0]),),
                             values=(BatchValues(name="g", values=[1.0, 2.0, 3.0]),)),
         r"batch values 'g' have 3 entries, the layout \(2,\) has 2 runs"),
        (lambda: BatchLayout.runs(0), r"`n` must be a whole number >= 1 \[runs\], got 0"),
    ],
)
def test_layout_validation(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_grid_axes_names():
    axes = grid_axes({"controller.params.kp": [1.0], "vessel.params.kp": [2.0],
                      "vessel.params.gain": [0.1, 0.2], "vessel.initial.heading": [0.0]},
                     units={"vessel.params.gain": "1/s"}, reserved={"heading"})
    assert [a.name for a in axes] == ["controller.params.kp", "vessel.params.kp", "gain",
                                      "vessel.initial.heading"]
    assert [a.key for a in axes][2] == "vessel.params.gain"
    assert axes[2].attrs == {"key": "vessel.params.gain", "units": "1/s"}


def test_plot_of_a_grid_result_draws_every_run(mariner2):
    import matplotlib.pyplot as plt

    result = simulate_batch(_gain_grid(mariner2))
    fig = result.plot()
    heading_lines = [ln for ln in fig.get_axes()[0].get_lines() if ln.get_linestyle() == "-"]
    assert len(heading_lines) == 6
    plt.close(fig)


def test_the_cached_row_loops_equal_the_generic_loop_for_every_registered_model():
    """VesselModel.derivative/outputs run a generated, disk-cached loop per model function
    (vessels.base._row_loop; the generic loop taking the function as an argument compiled
    in every process): both give the same numbers."""
    from seahelm.registry import VESSEL_MODELS, get_model
    from seahelm.parameters import as_records
    from seahelm.vessels.base import (_batched_output, _batched_rhs, _generic_output,
                                      _generic_rhs, _row_loop)

    rng = np.random.default_rng(7)
    for name in VESSEL_MODELS:
        model = get_model(name)
        assert _row_loop(model.rhs, "rhs") is not None, name
        assert _row_loop(model.output, "output") is not None, name
        n = 5
        x = rng.normal(size=(n, model.n_states)) * 0.1
        x[:, 0] += 1.0  # (a forward speed where the first state is one)
        u = rng.normal(size=(n, model.n_inputs)) * 0.1
        d = np.zeros((n, model.n_disturbances))
        params = _default_params(model)
        if params is None:
            continue
        p = as_records(np.repeat(params.to_array()[None], n, axis=0), model.params_type)
        got, want = np.empty_like(x), np.empty_like(x)
        _batched_rhs(model.rhs, 0.0, x, u, d, p, got)
        _generic_rhs(model.rhs, 0.0, x, u, d, p, want)
        np.testing.assert_array_equal(got, want, err_msg=name)
        y1 = np.empty((n, model.n_outputs))
        y2 = np.empty((n, model.n_outputs))
        _batched_output(model.output, 0.0, x, u, p, y1)
        _generic_output(model.output, 0.0, x, u, p, y2)
        np.testing.assert_array_equal(y1, y2, err_msg=name)


def _default_params(model):
    """The model's default parameters; where the defaults are not a valid set (a 6-DOF
    craft's thruster layout), the catalog ship's of that model; None without defaults."""
    from seahelm.errors import ParameterError
    from seahelm.ships import get_ship, ship_names

    try:
        return model.params_type()
    except TypeError:
        return None
    except ParameterError:
        for name in ship_names():
            ship = get_ship(name)
            if type(ship.params) is model.params_type:  # (otter-quaternion: the otter's)
                return ship.params
        raise
