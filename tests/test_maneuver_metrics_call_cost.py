"""The cheaper forms of one turning circle's fixed cost give the numbers of the forms before.

Issue 46 item 6: one KVLCC2 L7 turning circle end to end must be >= 10x shipmmg, and of its
fixed cost most was Python around small arrays. Each shortcut here is checked against the
general form it replaces, bit for bit (``np.array_equal``), and its fallback is exercised.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")


def _systems(seed: int, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Vandermonde systems of four distinct nodes (as the cubic crossings make them)."""
    rng = np.random.default_rng(seed)
    nodes = np.sort(rng.uniform(-2.0, 3.0, shape + (4,)), axis=-1)
    vander = nodes[..., None] ** np.arange(4)
    return vander, rng.normal(size=shape + (4, 1))


@pytest.mark.parametrize("shape", [(3, 1), (3, 40), (1, 1), (2, 7)])
def test_solve_equals_numpy_linalg_solve_bit_for_bit(shape):
    vander, rhs = _systems(sum(shape), shape)
    for a in (vander, np.swapaxes(vander, -1, -2)):  # (both systems of _cubic_crossings)
        assert np.array_equal(tc._solve(a, rhs), np.linalg.solve(a, rhs))


def test_solve_of_a_singular_system_raises_as_numpy_does():
    a = np.ones((2, 1, 4, 4))
    with pytest.raises(np.linalg.LinAlgError):
        tc._solve(a, np.ones((2, 1, 4, 1)))


def test_solve_without_the_gufunc_is_numpy_linalg_solve(monkeypatch):
    vander, rhs = _systems(5, (3, 2))
    monkeypatch.setattr(tc, "_GESV", None)
    assert np.array_equal(tc._solve(vander, rhs), np.linalg.solve(vander, rhs))


cm = importlib.import_module("seahelm.analysis.maneuvers.common")
sh = importlib.import_module("seahelm.analysis.maneuvers.ships")


@pytest.mark.parametrize("values, allow_zero, positive, ok", [
    ([0.6], False, True, True),
    ([0.0], False, False, False),      # zero: refused unless allow_zero
    ([0.0], True, False, True),
    ([-0.3], False, True, False),      # negative with positive=True
    ([-0.3], False, False, True),      # magnitude only
    ([0.7], False, True, False),       # beyond the KVLCC2's 35 deg
    ([0.5, float("nan")], False, True, False),
    ([0.1, 0.2, 0.3], True, False, True),
])
def test_check_rudder_fast_path_agrees_with_the_array_form(values, allow_zero, positive, ok):
    ship = sh.maneuver_ship("kvlcc2-l7")
    arr = np.array(values)
    assert cm._rudders_fit([ship], arr, allow_zero, positive) is (
        ok and not np.isnan(arr).any())
    if ok:
        cm.check_rudder([ship], "rudder", arr, allow_zero=allow_zero, positive=positive)
    else:  # the array form reports it, as before
        with pytest.raises(cm.ParameterError, match="rudder"):
            cm.check_rudder([ship], "rudder", arr, allow_zero=allow_zero, positive=positive)


def test_positions_of_a_single_run_equal_np_indices():
    plan = cm.Plan("kvlcc2-l7", None, None, [cm.value_axis("rudder", 0.6, "rad"),
                                             cm.side_axis(1)])
    expected = np.indices(plan.shape).reshape(len(plan.shape), -1)
    assert plan._positions.dtype == expected.dtype
    assert np.array_equal(plan._positions, expected)


@pytest.mark.parametrize("ship", ["kvlcc2-l7", "kvlcc2-full", "mariner-nonlinear"])
def test_usual_time_step_of_ready_ships_is_default_time_step(ship):
    s = sh.maneuver_ship(ship)
    for speed in (0.5 * s.approach_speed, s.approach_speed):
        assert sh.usual_time_step([s], [speed]) == sh.default_time_step(s, speed)


track = importlib.import_module("seahelm.analysis.maneuvers.track")


@pytest.mark.parametrize("seed, runs, steps, until", [
    (0, 1, 181, [23]), (1, 17, 120, None), (2, 5, 60, [0, 3, 59, 200, 7]), (3, 2, 4, [1, 2])])
def test_distance_until_fast_path_equals_the_general_form_bit_for_bit(monkeypatch, seed, runs,
                                                                      steps, until):
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.2, 0.8, steps))
    north = np.cumsum(rng.normal(size=(runs, steps)), axis=1)
    east = np.cumsum(rng.normal(size=(runs, steps)), axis=1)
    fast = track.distance_until(north, east, t, until=until)
    assert track._every_run_by_spline(np.atleast_2d(north), np.atleast_2d(east), t,
                                      until) is not None
    monkeypatch.setattr(track, "_every_run_by_spline", lambda *args: None)
    assert np.array_equal(fast, track.distance_until(north, east, t, until=until))


def test_distance_until_leaves_a_nan_run_and_bad_times_to_the_general_form():
    t = np.arange(6.0)
    north = np.array([[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], [0.0, np.nan, 2.0, 3.0, 4.0, 5.0]])
    assert track._every_run_by_spline(north, north.copy(), t, None) is None
    assert np.isnan(track.distance_until(north, north.copy(), t)[1]).any()
    with pytest.raises(ValueError, match="strictly increasing"):
        track.distance_until(north[:1], north[:1], t[::-1])


kernels = importlib.import_module("seahelm.analysis.maneuvers.turning_kernels")


def _steady_array_form(change, r, speed):
    """The steady end of a turn as the metrics formed it with numpy before (written out)."""
    n = change.shape[0]
    steady_r, steady_U = r[:, -1], speed[:, -1]
    with np.errstate(divide="ignore", invalid="ignore"):
        radius = np.where(steady_r != 0.0, steady_U / np.abs(steady_r), np.inf)
    back = change <= change[:, -1:] - 0.5 * np.pi
    last_back = back.shape[1] - 1 - np.argmax(back[:, ::-1], axis=1)
    r_back = r[np.arange(n), last_back]
    with np.errstate(invalid="ignore"):
        steady = (back.any(axis=1) & np.isfinite(steady_r)
                  & (np.abs(steady_r - r_back) <= 0.01 * np.abs(steady_r)))
    return radius, steady


def test_steady_ends_equal_the_array_form_bit_for_bit():
    rng = np.random.default_rng(7)
    runs, steps = 60, 50
    change = np.cumsum(rng.uniform(0.0, 0.2, (runs, steps)), axis=1)
    r = rng.normal(0.05, 0.01, (runs, steps))
    r[:, -1] = r[:, -2] * rng.choice([1.0, 1.005, 1.02], runs)  # steady, barely, not
    speed = rng.uniform(0.5, 1.5, (runs, steps))
    change[0] = np.linspace(0.0, 1.0, steps)   # never 90 deg before the end
    r[1, -1] = 0.0                             # no turn: infinite radius
    r[2, -1] = -0.0
    r[3, -1] = np.nan                          # a diverged run
    change[4, -1] = np.nan
    speed[5, -1] = np.nan
    r[6, -10] = np.nan                         # NaN where the 90 deg sample may fall
    radius, steady = np.empty(runs), np.empty(runs, dtype=np.bool_)
    kernels._steady_ends(change, r, speed, radius, steady)
    expected_radius, expected_steady = _steady_array_form(change, r, speed)
    assert np.array_equal(radius, expected_radius, equal_nan=True)
    assert np.array_equal(steady, expected_steady)
    assert steady.any() and not steady.all()


def test_as_records_equal_the_view_of_the_rows():
    from numba import typeof

    from seahelm.control.open_loop import OPEN_LOOP
    from seahelm.parameters import as_records, stack_params
    from seahelm.ships import get_ship

    params = get_ship("kvlcc2-l7").params
    for cls, rows in ((type(params), stack_params([params, params])),
                      (OPEN_LOOP.params_type, np.zeros((3, 0)))):
        got = as_records(rows, cls)
        base = np.zeros((rows.shape[0], 1)) if rows.shape[1] == 0 else rows
        view = base.view(cls._record_view_dtype()).reshape(rows.shape[0])
        assert got.dtype == view.dtype and got.shape == view.shape
        assert typeof(got) == typeof(view) and got.flags.writeable
        assert got.tobytes() == view.tobytes()
    got = as_records(stack_params(params), type(params))
    assert np.shares_memory(got, got.base) and got[0].length == params.length


@pytest.mark.parametrize("value", [0.5, -1e300, 3, np.float64(2.0), np.arange(3.0),
                                   np.arange(3), [1.0, 2.0], np.arange(4.0)[::2]])
def test_as_float_array_fast_paths_equal_the_general_form(value):
    from seahelm._validate import as_float_array

    got = as_float_array("x", value, "m")
    expected = np.asarray(value, dtype=float)
    assert got.dtype == expected.dtype and got.shape == expected.shape
    assert np.array_equal(got, expected)
    if isinstance(value, np.ndarray) and value.dtype == np.float64:
        assert got is value  # (no copy, as np.asarray gave none)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), np.array([1.0, np.nan])])
def test_as_float_array_fast_paths_still_refuse_non_finite(value):
    from seahelm._validate import as_float_array
    from seahelm.errors import ParameterError

    with pytest.raises(ParameterError, match=r"`x` must be finite \[m\]"):
        as_float_array("x", value, "m")
    assert np.isnan(as_float_array("x", value, "m", finite=False)).any() or np.isinf(
        as_float_array("x", value, "m", finite=False)).any()


def test_registry_entries_by_module_path_resolve_to_the_imported_objects():
    import importlib as il

    from seahelm import registry

    for table, get in ((registry.CONTROLLERS, registry.get_controller),
                       (registry.ACTUATORS, registry.get_actuator)):
        for name, entry in table.items():
            if isinstance(entry, str):
                module, attr = entry.split(":")
                assert get(name) is getattr(il.import_module(module), attr)


@pytest.mark.parametrize("ship", ["kvlcc2-l7", "mariner-nonlinear", "mariner-nomoto1",
                                  "otter", "remus100", "shushlyapin2017-dp"])
def test_can_maneuver_is_the_states_rule(ship):
    from seahelm.ships import get_ship

    model = get_ship(ship).model
    states = set(model.state_labels)
    rule = bool(({"sway_speed", "yaw_rate", "heading"} <= states
                 and states & {"surge_speed", "surge_perturbation"})
                or sh.is_constant_speed(model))
    assert sh._can_maneuver(model) is rule
