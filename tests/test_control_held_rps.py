"""The ``-rps`` controllers built by one combinator (issue 47 item 4):
:func:`seahelm.control.held_rps.with_held_rps` instead of four hand-written copies
(``pid-heading-rps``, ``lq-heading-rps``, ``zigzag-rps``, ``lq-cross-track-rps``). The registered
names, signals and parameters are those of before, and a run of each equals, bit for bit, the
run of the hand-written twin it replaced (kept here as the reference: their step functions as
they were)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numba import njit

from seahelm.control.base import Controller
from seahelm.control.held_rps import with_held_rps
from seahelm.control.lq_cross_track import LQ_CROSS_TRACK, lq_cross_track_law
from seahelm.control.lq_heading import LQ_HEADING, lq_heading_step
from seahelm.control.path_following import route_params
from seahelm.control.pid import PID_HEADING, pid_heading_step
from seahelm.control.zigzag import ZIGZAG, zigzag_rudder
from seahelm.registry import get_controller


# -- the hand-written twins as they were (steps, then Controllers) ----------------------------
@njit(cache=False)
def old_pid_heading_rps_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    pid_heading_step(t, dt, z, y, ref, p, cs, cmd)
    cmd[1] = p.propeller_rps


@njit(cache=False)
def old_lq_heading_rps_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    lq_heading_step(t, dt, z, y, ref, p, cs, cmd)
    cmd[1] = p.propeller_rps


@njit(cache=False)
def old_zigzag_rps_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    cmd[0] = zigzag_rudder(dt, y, p, cs)
    cmd[1] = p.propeller_rps


@njit(cache=False)
def old_lq_cross_track_rps_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    cmd[0] = lq_cross_track_law(dt, y, p, cs, cmd[2:])
    cmd[1] = p.propeller_rps


def _old(base: Controller, step) -> Controller:
    return dataclasses.replace(base, command_labels=base.command_labels + ("propeller_rps",),
                               command_units=base.command_units + ("1/s",),
                               params_type=get_controller(base.name + "-rps").params_type,
                               step=step, name=f"old-{base.name}-rps")


ROUTE = [[0.0, 0.0], [2000.0, 0.0]]
CASES = {
    "pid-heading-rps": (PID_HEADING, old_pid_heading_rps_step,
                        dict(kp=2.0, ki=0.01, kd=30.0), {"reference": [math.radians(10.0)]}),
    "lq-heading-rps": (LQ_HEADING, old_lq_heading_rps_step,
                       dict(k_heading=2.0, k_yaw_rate=30.0, k_integral=0.01, k_sway=0.5),
                       {"reference": [math.radians(10.0)]}),
    "zigzag-rps": (ZIGZAG, old_zigzag_rps_step,
                   dict(rudder_amplitude=math.radians(10.0), heading_trigger=math.radians(10.0)),
                   {}),
    "lq-cross-track-rps": (LQ_CROSS_TRACK, old_lq_cross_track_rps_step,
                           dict(k_integral=0.0026, k_cross_track=0.3, k_heading=4.9,
                                k_yaw_rate=10.0, k_sway=-0.86, max_command=math.radians(35.0),
                                acceptance_radius=7.0),
                           {}),
}


def _params(name: str, params_type: type, gains: dict) -> object:
    if "cross" in name:
        return route_params(ROUTE, params_type=params_type, **gains, propeller_rps=11.85)
    return params_type(**gains, propeller_rps=11.85)


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_registered_twin_is_the_combinators(name):
    base, _, _, _ = CASES[name]
    twin = get_controller(name)
    assert twin is with_held_rps(base, description=twin.description)
    assert twin.name == name and twin.command_labels == base.command_labels + ("propeller_rps",)
    for attr in ("state_labels", "reference_labels", "reference_units", "measurement_labels",
                 "output_labels", "output_units", "init", "sample_period"):
        assert getattr(twin, attr) == getattr(base, attr), attr
    assert twin.params_type.field_names() == base.params_type.field_names() + (
        "propeller_rps",)
    assert issubclass(twin.params_type, base.params_type)
    info = {i.name: i for i in twin.params_type.info()}["propeller_rps"]
    assert info.unit == "1/s"


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_run_equals_the_hand_written_twins(name):
    """kvlcc2-l7 (rudder and propeller) under each twin, 60 s, the pure-Python loop (the
    same functions numba compiles): every recorded signal bit for bit."""
    from seahelm.ships import get_ship
    from seahelm.simulation.engine import simulate

    base, old_step, gains, extra = CASES[name]
    ship = get_ship("kvlcc2-l7")
    x0 = np.zeros(ship.model.n_states)
    x0[ship.model.state_labels.index("surge_speed")] = 1.179
    x0[ship.model.state_labels.index("east")] = 5.0 if "cross" in name else 0.0
    runs = []
    for controller in (get_controller(name), _old(base, old_step)):
        params = _params(name, controller.params_type, gains)
        runs.append(simulate(ship=ship, x0=x0, t_final=60.0, dt=0.1, controller=controller,
                             controller_params=[params], controller_dt=0.5, jit=False,
                             **extra).to_xarray())
    new, old = runs
    assert set(new.data_vars) == set(old.data_vars)
    for var in new.data_vars:
        np.testing.assert_array_equal(new[var].values, old[var].values, err_msg=var)
    assert float(np.abs(new["propeller_rps"]).max()) == 11.85  # (the rps reached the model)


def test_a_compiled_run_equals_the_hand_written_twins():
    """The cross-track twin (its recorded outputs move one slot up), compiled."""
    from seahelm.ships import get_ship
    from seahelm.simulation.engine import simulate

    base, old_step, gains, _ = CASES["lq-cross-track-rps"]
    ship = get_ship("kvlcc2-l7")
    x0 = np.zeros(ship.model.n_states)
    x0[ship.model.state_labels.index("surge_speed")] = 1.179
    x0[ship.model.state_labels.index("east")] = 5.0
    runs = [simulate(ship=ship, x0=x0, t_final=120.0, dt=0.1, controller=c,
                     controller_params=[_params("cross", c.params_type, gains)],
                     controller_dt=0.5).to_xarray()
            for c in (get_controller("lq-cross-track-rps"), _old(base, old_step))]
    for var in runs[0].data_vars:
        np.testing.assert_array_equal(runs[0][var].values, runs[1][var].values, err_msg=var)


def test_a_controller_that_holds_an_rps_already_is_refused():
    with pytest.raises(ValueError, match="cannot hold a propeller rps"):
        with_held_rps(get_controller("pid-heading-rps"))


def test_the_params_pickle():
    import pickle

    p = get_controller("zigzag-rps").params_type(rudder_amplitude=0.1, heading_trigger=0.1,
                                                  propeller_rps=3.0)
    assert pickle.loads(pickle.dumps(p)) == p
