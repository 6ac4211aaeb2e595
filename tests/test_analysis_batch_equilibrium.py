"""Batched steady approaches (analysis.batch_equilibrium) against the one-run solve.

The reference is :func:`seahelm.analysis.equilibria.equilibrium.approach_state` (``trim=True``):
brentq to |Δn| ≤ 1e-14 + 4 ε n for the rps, scipy's hybr to a relative step of 1e-13 for the trim.
Both solves stop at the round-off floor of the same equations, so they agree to ~1e-15; the
bound asserted here is 1e-11 relative (rps, rudder, surge) and 1e-11 (U/L or 1 rad) absolute
for what is zero or near zero (sway speed, rudder, drift angle).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.equilibria.batch_equilibrium import ApproachStatus, approach_states
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.errors import ParameterError
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR
from seahelm.vessels.mmg import KVLCC2_FULL, KVLCC2_L7, MMG

TOL = 1e-11
LINEAR = ("Y_v", "Y_r", "N_v", "N_r")


def _reference(model, params, speeds):
    rows = []
    for p, U in zip(params, speeds):
        a = approach_state(p, float(U), model=model, trim=True)
        rows.append((a.state, a.inputs["rudder_angle"], a.inputs.get("propeller_rps", np.nan)))
    return (np.stack([r[0] for r in rows]), np.array([r[1] for r in rows]),
            np.array([r[2] for r in rows]))


def _drift_reference(model, params, state, rudder, rps):
    out = []
    for p, x, d, n in zip(params, state, rudder, rps):
        u = np.zeros(model.n_inputs)
        u[model.input_labels.index("rudder_angle")] = d
        if "propeller_rps" in model.input_labels:
            u[model.input_labels.index("propeller_rps")] = n
        out.append(model.outputs(0.0, x, u, p)[model.output_index("drift_angle")])
    return np.array(out)


def _assert_same(model, params, speeds, batch):
    state, rudder, rps = _reference(model, params, speeds)
    assert batch.ok.all(), batch.message
    U = np.asarray(speeds, dtype=float)
    np.testing.assert_allclose(batch.rps, rps, rtol=TOL, atol=0.0)
    np.testing.assert_allclose(batch.rudder, rudder, rtol=TOL, atol=TOL)
    # surge and sway speeds to TOL x U (the surge perturbation of the Mariner is near 0),
    # yaw rate, position and heading are 0 in both
    np.testing.assert_allclose(batch.state, state, rtol=TOL, atol=TOL * float(np.max(U)))
    np.testing.assert_allclose(batch.drift_angle,
                               _drift_reference(model, params, state, rudder, rps),
                               rtol=TOL, atol=TOL)
    np.testing.assert_array_equal(batch.speed, U)
    assert batch.message == ("ok",) * len(params)


@pytest.mark.parametrize("model, params", [(MMG, KVLCC2_L7), (MMG, KVLCC2_FULL),
                                           (MARINER, MARINER_NONLINEAR)],
                         ids=["kvlcc2-l7", "kvlcc2-full", "mariner"])
def test_catalog_ships_equal_the_one_run_solve(model, params):
    U = getattr(params, "approach_speed", getattr(params, "nominal_speed", None))
    batch = approach_states(model, params)
    _assert_same(model, [params], [U], batch)


def test_mariner_trims_against_its_bias():
    """Y_0, N_0 of the single-screw Mariner need a rudder angle to keep a straight course."""
    batch = approach_states(MARINER, [MARINER_NONLINEAR])
    assert math.degrees(batch.rudder[0]) == pytest.approx(-1.108, abs=1e-3)
    assert batch.state[0, MARINER.state_index("sway_speed")] != 0.0
    # untrimmed: rudder 0 and the nominal state
    plain = approach_states(MARINER, [MARINER_NONLINEAR], trim=False)
    assert plain.rudder[0] == 0.0 and not plain.state[0].any()


@pytest.fixture(scope="module")
def kvlcc2_draws():
    rng = np.random.default_rng(32)
    params = [KVLCC2_L7.replace(**{n: getattr(KVLCC2_L7, n) * (1.0 + 0.1 * rng.standard_normal())
                                   for n in LINEAR + ("R_0", "w_P0", "t_P")})
              for _ in range(200)]
    speeds = KVLCC2_L7.approach_speed * rng.uniform(0.6, 1.4, size=200)
    return params, speeds


def test_a_monte_carlo_of_kvlcc2_sets_equals_the_one_run_solve(kvlcc2_draws):
    params, speeds = kvlcc2_draws
    batch = approach_states(MMG, params, speeds)
    _assert_same(MMG, params, speeds, batch)
    # one speed for all broadcasts
    one = approach_states(MMG, params[:3], float(speeds[0]))
    np.testing.assert_array_equal(one.speed, [speeds[0]] * 3)


def test_a_monte_carlo_of_biased_mariner_sets_equals_the_one_run_solve():
    """A non-trivial trim in every run: the Mariner's bias and linear terms drawn."""
    rng = np.random.default_rng(7)
    p0 = MARINER_NONLINEAR
    params = [p0.replace(**{n: getattr(p0, n) * (1.0 + 0.3 * rng.standard_normal())
                            for n in ("Y_0", "N_0") + LINEAR}) for _ in range(40)]
    batch = approach_states(MARINER, params)
    _assert_same(MARINER, params, [p0.nominal_speed] * len(params), batch)
    assert (batch.iterations >= 2).all()


def test_failures_are_recorded_per_run_and_the_others_solved():
    strong = MARINER_NONLINEAR.replace(Y_0=100 * MARINER_NONLINEAR.Y_0,
                                       N_0=100 * MARINER_NONLINEAR.N_0)
    batch = approach_states(MARINER, [MARINER_NONLINEAR, strong, MARINER_NONLINEAR])
    assert batch.status.tolist() == [0, ApproachStatus.LINE_SEARCH, 0]
    assert batch.ok.tolist() == [True, False, True]
    assert "no equilibrium found for surge, v, rudder with r = 0" in batch.message[1]
    assert np.isnan(batch.state[1]).all() and np.isnan(batch.rudder[1])
    assert batch.rudder[0] == batch.rudder[2]
    # a propeller too weak for the speed: rps out of range
    fast = approach_states(MMG, [KVLCC2_L7, KVLCC2_L7], [1.0, 5.0], max_rps=20.0)
    assert fast.status.tolist() == [0, ApproachStatus.RPS_OUT_OF_RANGE]
    assert fast.message[1] == ("no propeller rps in (0, 20] [1/s] gives zero surge force at "
                               "`speed` = 5.0 [m/s]")
    assert fast.rps[0] == pytest.approx(approach_state(KVLCC2_L7, 1.0, trim=True)
                                        .inputs["propeller_rps"], rel=TOL)


def test_no_self_propulsion_point_is_a_recorded_failure():
    """R_0 = 0 and no other drag at v = r = 0: the stopped propeller drags, the surge force
    is negative; a wake fraction of one makes the propeller push at n = 0 — J = 0."""
    batch = approach_states(MMG, [KVLCC2_L7, KVLCC2_L7.replace(R_0=0.0)])
    assert batch.status[0] == 0
    if batch.status[1] != 0:
        assert batch.status[1] == ApproachStatus.NO_SELF_PROPULSION
        assert "no self-propulsion point" in batch.message[1]


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(speed=-1.0), r"`speed` must be > 0 \[m/s\], got -1.0"),
        (dict(speed=[1.0, 0.0]), r"`speed` must be > 0 \[m/s\], got 0.0"),
        (dict(speed=[1.0, 2.0, 3.0]), r"`speed` must be a number or one per run \(2\)"),
        (dict(heading=math.inf), r"`heading` must be finite \[rad\]"),
        (dict(max_rps=0.0), r"`max_rps` must be > 0 \[1/s\]"),
        (dict(max_iterations=0), r"`max_iterations` must be a whole number >= 1"),
    ],
)
def test_bad_arguments_raise_naming_them(kwargs, match):
    with pytest.raises(ParameterError, match=match) as info:
        approach_states(MMG, [KVLCC2_L7, KVLCC2_L7], **kwargs)
    if "speed" in kwargs and np.ndim(kwargs["speed"]) and len(kwargs["speed"]) == 2:
        assert info.value.run == 1


def test_a_perturbation_model_admits_only_its_nominal_speed():
    with pytest.raises(ParameterError, match=r"`speed` must be the nominal speed U_0 = 7.7175"):
        approach_states(MARINER, [MARINER_NONLINEAR], 5.0)
    with pytest.raises(ParameterError, match=r"`params`: no parameter sets"):
        approach_states(MARINER, [])


def test_heading_and_untrimmed_approach():
    batch = approach_states(MMG, [KVLCC2_L7], heading=0.5, trim=False)
    ref = approach_state(KVLCC2_L7, heading=0.5)
    np.testing.assert_allclose(batch.state[0], ref.state, rtol=TOL, atol=TOL)
    assert batch.rps[0] == pytest.approx(ref.inputs["propeller_rps"], rel=TOL)


def test_constant_speed_models_are_solved_run_by_run():
    from seahelm.ships import get_ship

    ship = get_ship("mariner-nomoto2")
    batch = approach_states(ship.model, [ship.params, ship.params])
    ref = approach_state(ship.params, model=ship.model, trim=True)
    assert batch.ok.all()
    np.testing.assert_array_equal(batch.state[1], ref.state)
    assert np.isnan(batch.rps).all()
