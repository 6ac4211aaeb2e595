"""Closed-form equilibria a model declares (issue 47, item 3, step E): the MMG model declares
the closed form of its straight run's self-propulsion rps (capability
``closed-form-self-propulsion``); the batched solver takes it first, and it equals the Newton
root the solver finds without it."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from seahelm.analysis.equilibria import closed_forms
from seahelm.analysis.equilibria.batch_equilibrium import approach_states
from seahelm.analysis.equilibria.equilibrium import approach_state, self_propulsion_rps
from seahelm.analysis.equilibria.plant import Plant
from seahelm.registry import VESSEL_MODELS, get_model
from seahelm.ships import get_ship
from seahelm.vessels.mmg import MMG

WITHOUT = dataclasses.replace(MMG, capabilities=MMG.capabilities
                              - {"closed-form-self-propulsion"})


def test_only_the_mmg_model_declares_it_and_the_form_is_named():
    declared = [n for n in VESSEL_MODELS
                if get_model(n).supports("closed-form-self-propulsion")]
    assert declared == ["mmg"]
    assert closed_forms.CLOSED_FORMS["closed-form-self-propulsion"] == (
        "seahelm.vessels.mmg_four_quadrant:self_propulsion_rps")


@pytest.mark.parametrize("name", ["kvlcc2-l7", "kvlcc2-full", "kvlcc2-l7-wp0-0.35"])
def test_the_closed_form_is_taken_and_equals_the_newton_root(name):
    ship = get_ship(name)
    speeds = ship.params.approach_speed * np.array([0.3, 0.6, 1.0, 1.2])
    ps = [ship.params] * speeds.size
    closed = approach_states(MMG, ps, speeds, trim=False)
    newton = approach_states(WITHOUT, ps, speeds, trim=False)
    assert closed.ok.all() and newton.ok.all()
    assert (closed.iterations == 0).all() and (newton.iterations > 0).all()
    np.testing.assert_allclose(closed.rps, newton.rps, rtol=4e-16, atol=0.0)
    # the model's own surge balance vanishes at the closed form to round-off
    assert np.all(np.abs(closed.residual) <= 1e-15)
    # the trim from the closed-form rps is the trim from the Newton rps (to rounding)
    t_closed = approach_states(MMG, ship.params, trim=True)
    t_newton = approach_states(WITHOUT, ship.params, trim=True)
    np.testing.assert_allclose(t_closed.state, t_newton.state, rtol=1e-15, atol=1e-17)


def test_the_one_run_functions_take_it_too():
    ship = get_ship("kvlcc2-l7")
    form = closed_forms.self_propulsion_rps(Plant(MMG, [ship.params]), np.array([1.179]))
    assert self_propulsion_rps(ship, 1.179) == form[0]
    assert approach_state(ship).rps == form[0]


def test_no_closed_form_where_the_model_declares_none():
    osaka = get_ship("esso-osaka-3m")  # mmg-ls: its own propeller model
    assert np.isnan(closed_forms.self_propulsion_rps(
        Plant(osaka.model, [osaka.params]), np.array([0.3]))).all()
    assert approach_states(osaka.model, osaka.params, trim=False).iterations[0] > 0


def test_a_declared_form_that_does_not_balance_the_model_is_not_taken(monkeypatch):
    ship = get_ship("kvlcc2-l7")
    monkeypatch.setitem(closed_forms.CLOSED_FORMS, "closed-form-self-propulsion",
                        "seahelm.vessels.mmg_four_quadrant:propeller_torque")  # not the rps
    monkeypatch.setattr("seahelm.vessels.mmg_four_quadrant.propeller_torque",
                        lambda p, U: 1.01 * 11.851590315879161)
    got = approach_states(MMG, ship.params, trim=False)
    ref = approach_states(WITHOUT, ship.params, trim=False)
    assert got.iterations[0] > 0 and got.rps[0] == ref.rps[0]
