"""One plant for the equilibrium solvers (issue 47, item 3): the one-run solvers and the
batched ones resolve the same state and input indices, speed offset, length and reference
speed on every registered model (or refuse it with the same message).

The expected table is written from the models' declared labels and the catalog ships'
particulars, not computed by the code under test.
"""
from __future__ import annotations

import numpy as np
import pytest

from seahelm.registry import VESSEL_MODELS, get_model
from seahelm.ships import get_ship

KN = 1852.0 / 3600.0

#: model -> (a parameter source, the resolution or the refusal's text)
EXPECTED = {
    "mmg": ("kvlcc2-full", dict(i_u=0, u_offset=0.0, i_v=1, i_r=2, i_psi=5, j_delta=0,
                                j_rps=1, length=320.0, u_ref=15.5 * KN)),
    "mmg-ls": ("esso-osaka-3m", dict(i_u=0, u_offset=0.0, i_v=1, i_r=2, i_psi=5, j_delta=0,
                                     j_rps=1, length=3.0, u_ref=0.3)),
    # (its propeller rps is a state, driven by the input engine_order: no rps input)
    "mmg-4q": ("kvlcc2-l7-4q", dict(i_u=0, u_offset=0.0, i_v=1, i_r=2, i_psi=5, j_delta=0,
                                    j_rps=None, length=7.0, u_ref=1.179)),
    "mariner": ("mariner-nonlinear", dict(i_u=0, u_offset=7.7175, i_v=1, i_r=2, i_psi=5,
                                          j_delta=0, j_rps=None, length=160.93,
                                          u_ref=7.7175)),
    "container": ("son-nomoto-container", dict(i_u=0, u_offset=0.0, i_v=1, i_r=2, i_psi=5,
                                               j_delta=0, j_rps=1, length=175.0, u_ref=7.0)),
    # constant-speed models: the surge held (step D; before, refused: "needs a state
    # 'surge_speed'"), their speed the parameter `speed`, the steering states resolved
    "nomoto1": ("mariner-nomoto1", dict(i_u=None, u_offset=0.0, i_v=None, i_r=3, i_psi=2,
                                        j_delta=0, j_rps=None, length=160.93, u_ref=7.7175,
                                        steering=[3])),
    "nomoto2": ("mariner-nomoto2", dict(i_u=None, u_offset=0.0, i_v=None, i_r=3, i_psi=2,
                                        j_delta=0, j_rps=None, length=160.93, u_ref=7.7175,
                                        steering=[3, 4])),
    "voitkunsky": ("mariner-voitkunsky", dict(i_u=None, u_offset=0.0, i_v=None, i_r=3,
                                              i_psi=2, j_delta=0, j_rps=None, length=160.93,
                                              u_ref=7.7175, steering=[3, 4])),
    "cpp-ship-calm": ("cpp-ship-calm", "needs a state 'surge_speed'"),
    "cpp-ship-waves": ("cpp-ship-waves", "needs a state 'surge_speed'"),
    "catamaran": ("shushlyapin2017-consistent", "has no state 'sway_speed'"),
    "catamaran-servo": ("catamaran-servo", "has no state 'sway_speed'"),
    "otter": ("otter", "has no input 'rudder_angle'"),
    "otter-quaternion": ("otter", "has no input 'rudder_angle'"),
    "remus100": ("remus100", "has no input 'rudder_angle'"),
    "dp-3dof": ("supply", "has no input 'rudder_angle'"),
}
FIELDS = ("i_u", "u_offset", "i_v", "i_r", "i_psi", "j_delta", "j_rps", "length", "u_ref")


def _params(model, source):
    if source == "kvlcc2-l7-4q":
        from seahelm.vessels.mmg_four_quadrant import KVLCC2_L7_4Q
        return KVLCC2_L7_4Q
    if source in ("cpp-ship-calm", "cpp-ship-waves", "catamaran-servo"):
        return model.params_type()
    return get_ship(source).params


def _one_run(params, model):  # (before issue 47: equilibrium._Plant(params, model))
    from seahelm.analysis.equilibria.plant import Plant
    return Plant.of(params, model)


def _batch(model, params):  # (before: batch_equilibrium._Batch(model, params))
    from seahelm.analysis.equilibria.plant import Plant
    return Plant(model, params)


def _resolved(plant):
    out = {}
    for k in FIELDS:
        value = getattr(plant, k)
        out[k] = value if value is None or isinstance(value, int) else float(np.ravel(value)[0])
    return out


def test_every_registered_model_is_in_the_table():
    assert set(EXPECTED) == set(VESSEL_MODELS)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_one_run_and_batch_resolve_the_same_signals(name):
    model = get_model(name)
    source, expected = EXPECTED[name]
    params = _params(model, source)
    if isinstance(expected, str):
        with pytest.raises(ValueError, match=expected) as one:
            _one_run(params, model)
        with pytest.raises(ValueError, match=expected) as many:
            _batch(model, [params])
        assert str(one.value) == str(many.value)
        return
    one, many = _one_run(params, model), _batch(model, [params, params])
    got = _resolved(one)
    floats = ("u_offset", "length", "u_ref")
    assert {k: got[k] for k in FIELDS if k not in floats} == {
        k: expected[k] for k in FIELDS if k not in floats}
    assert [got[k] for k in floats] == pytest.approx([expected[k] for k in floats], rel=1e-15)
    assert _resolved(many) == _resolved(one)
    for k in ("u_offset", "length", "u_ref"):  # per run in a batch
        assert np.shape(getattr(many, k)) == (2,)
    assert one.surge_held == ("steering" in expected)
    assert one.steering == expected.get("steering")


def test_the_constant_speed_solves_stand_on_the_surge_held_plant():
    from seahelm.analysis.equilibria.constant_speed import ConstantSpeedPlant
    from seahelm.analysis.equilibria.plant import Plant

    ship = get_ship("mariner-nomoto2")
    cs = ConstantSpeedPlant(ship.params, ship.model)
    assert isinstance(cs.plant, Plant) and cs.plant.surge_held
    assert cs.steering == [3, 4] and cs.speed == 7.7175
    assert cs.rate == 7.7175 / 160.93  # U/L
    assert cs.scale.tolist() == [cs.rate, cs.rate]  # both steering states in rad/s
