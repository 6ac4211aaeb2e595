"""The stopping test (seahelm.analysis.maneuvers.stopping): conversion, metrics, validation."""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.maneuvers import crash_stop, maneuver_ship, stopping_metrics, stopping_ship
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.hydrodynamics.four_quadrant import B4_70_PD10
from seahelm.simulation.engine import simulate
from seahelm.vessels.mmg import KVLCC2_L7_SERVO
from seahelm.vessels.mmg_four_quadrant import MMG_4Q


@pytest.fixture(scope="module")
def l7_stop():
    return crash_stop("kvlcc2-l7")


def test_stopping_ship_converts_an_mmg_ship_and_keeps_the_rest():
    full = stopping_ship("kvlcc2-full")
    base = maneuver_ship("kvlcc2-full")
    assert full.model.name == "mmg-4q" and full.name == "kvlcc2-full"
    assert full.params.reversal_delay == 60.0 and full.params.reversal_time == 40.0
    assert full.params.length == base.params.length and full.servo == base.servo
    assert full.test_speed == base.test_speed and full.particulars == base.particulars
    assert full.propulsion.inputs == ("engine_order",)
    assert "60 s full scale" in full.source_of("reversal_delay")
    l7 = stopping_ship("kvlcc2-l7")
    assert l7.params.reversal_delay == pytest.approx(60.0 / math.sqrt(45.7))
    assert stopping_ship(full) is full  # an mmg-4q ship as it is
    assert stopping_ship(full, reversal_delay=30.0).params.reversal_delay == 30.0
    assert stopping_ship("kvlcc2-full", reversal_delay=90.0).params.reversal_delay == 90.0


@pytest.mark.parametrize("name", ["mariner-nonlinear"])
def test_a_ship_without_a_propeller_is_refused_naming_ship(name):
    with pytest.raises(ParameterError, match="no propeller") as info:
        stopping_ship(name)
    assert info.value.field == "ship"
    with pytest.raises(ParameterError, match="no propeller"):
        crash_stop(name)


def test_bad_inputs_name_their_field():
    with pytest.raises(ParameterError, match="order") as info:
        crash_stop("kvlcc2-l7", order=0.5)
    assert info.value.field == "order"
    with pytest.raises(ParameterError, match="dead_fraction"):
        crash_stop("kvlcc2-l7", dead_fraction=1.0)
    with pytest.raises(ParameterError, match="scale"):
        stopping_ship("kvlcc2-l7", scale=0.5)
    with pytest.raises(ParameterError, match="reversal_delay"):
        stopping_ship("kvlcc2-l7", reversal_delay=-1.0)
    with pytest.raises(ParameterError, match="engine"):
        stopping_ship("kvlcc2-l7", reversal_dela=1.0)


def test_a_model_size_ship_of_unknown_scale_warns():
    l7 = maneuver_ship("kvlcc2-l7")
    assert stopping_ship(l7.replace(name="variant")).params.reversal_delay == pytest.approx(
        60.0 / math.sqrt(45.7))  # the L7's geometry: its scale
    # (a copy keeps the scale its particulars declare, 45.7: tests/test_model_capabilities.py)
    own = dataclasses.replace(l7.replace(name="my-model", params={"propeller_diameter": 0.2}),
                              particulars=dataclasses.replace(l7.particulars, model_scale=None))
    with pytest.warns(ValidityRangeWarning, match="scale"):
        ship = stopping_ship(own)
    assert ship.params.reversal_delay == 60.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert stopping_ship(own, scale=45.7).params.reversal_delay == pytest.approx(
            60.0 / math.sqrt(45.7))


def test_kvlcc2_l7_crash_stop_metrics(l7_stop):
    m = l7_stop.metrics
    assert l7_stop.maneuver == "stopping" and bool(m["complete"])
    assert str(m["message"].item()) == "ok"
    L = float(m["length"])
    head, track = float(m["head_reach"]), float(m["track_reach"])
    assert 5.0 * L < head <= track < 9.0 * L
    assert track <= head * 1.05  # nearly straight: the backing side force swings it late
    delay = float(m["reversal_delay"])
    assert delay < float(m["time_astern"]) < delay + 2.0
    assert float(m["time_astern"]) < float(m["time_dead"])
    lateral = abs(float(m["lateral_deviation"]))
    assert lateral <= float(m["max_lateral_deviation"]) < 0.5 * L
    # the backing single screw swings the bow to starboard
    assert math.degrees(float(m["heading_change"])) > 5.0
    assert m.attrs["rudder"].startswith("held amidships")
    runs = l7_stop.runs
    assert {"propeller_rps", "engine_order", "reversal_clock"} <= set(runs.data_vars)
    # the ship comes to rest: dead in the water, then going astern under astern thrust
    u = runs["surge_speed"].values
    assert u.min() < 0.0 and float(m["speed_dead"]) < 0.1 * float(m["approach_speed_value"])


def test_batch_equals_single_runs():
    ships = ["kvlcc2-l7", "kvlcc2-l7-xp-0.5"]
    batch = crash_stop(ships, order=[-1.0, -0.5], t_final=200.0, dt=0.05).metrics
    assert dict(batch.sizes) == {"ship": 2, "order": 2}
    for i, name in enumerate(ships):
        for j, order in enumerate((-1.0, -0.5)):
            one = crash_stop(name, order=order, t_final=200.0, dt=0.05).metrics
            for key in ("head_reach", "track_reach", "lateral_deviation", "time_dead",
                        "time_astern", "heading_change"):
                assert float(batch[key].isel(ship=i, order=j)) == pytest.approx(
                    float(one[key]), rel=1e-12, abs=1e-12)
    # half astern stops later than full astern
    assert np.all(batch["track_reach"].isel(order=1) > batch["track_reach"].isel(order=0))


def test_a_run_that_does_not_stop_in_time_is_reported_not_raised():
    m = crash_stop("kvlcc2-l7", t_final=10.0).metrics
    assert not bool(m["complete"]) and math.isnan(float(m["head_reach"]))
    assert "not dead in the water within t_final" in str(m["message"].item())


# ---------------------------------------------------------------------------------------
# validation: the straight-line 1-DOF stop against the independent integral
# ---------------------------------------------------------------------------------------
def _ct_star(beta):
    """C_T*(β) = 0.01 Σ_k (A_k cos kβ + B_k sin kβ), Roddy et al. (2006) eq. 2, from the
    printed B4-70 table (written here independently of the library's series)."""
    k = np.arange(B4_70_PD10.shape[0])
    return 0.01 * float(np.sum(B4_70_PD10[:, 0] * np.cos(k * beta)
                               + B4_70_PD10[:, 1] * np.sin(k * beta)))


def test_straight_line_head_reach_equals_the_integral():
    """Rudder amidships, no backing side force, the shaft held at the astern rps from the
    order: M u̇ = −R'_0 ½ρLd u² + T(u) with T the scaled four-quadrant thrust, X_P = T astern.
    The head reach to u = 0.05 U_0 is ∫ M u du / (R(u) − T(u)) (quad), the time ∫ M du/(R − T)."""
    ship = stopping_ship("kvlcc2-l7", backing_side_force=0.0)
    p = ship.params.replace(max_power=1e3 * ship.params.max_power)  # the governor holds n
    U0, n = p.approach_speed, p.astern_rps
    r = simulate(MMG_4Q, p, [U0, 0, 0, 0, 0, 0, n, 0], t_final=80.0, dt=0.01,
                 actuator=RUDDER_SERVO, actuator_params=KVLCC2_L7_SERVO, actuator_x0=[0.0],
                 controller=OPEN_LOOP, reference={"rudder_command": 0.0, "engine_order": -1.0})
    np.testing.assert_array_equal(r["propeller_rps"], n)
    np.testing.assert_array_equal(r["east"], 0.0)
    found = stopping_metrics(r.time, r["north"], r["east"], r["heading"], r["surge_speed"], U0,
                             propeller_rps=r["propeller_rps"])
    # independently: mass with the surge added mass, resistance, thrust
    rho, L, d, D = p.rho, p.length, p.draft, p.propeller_diameter
    M = rho * p.displacement + p.m_x * 0.5 * rho * L * L * d
    kt0 = _ct_star(0.0) * math.pi / 8.0 * (0.7 * math.pi) ** 2
    scale = p.k_0 / kt0

    def net_astern_force(u):  # R(u) − T(u) > 0
        u_p = u * (1.0 - p.w_P0)
        w = 0.7 * math.pi * n * D
        thrust = (scale * _ct_star(math.atan2(u_p, w)) * 0.5 * rho * (u_p ** 2 + w ** 2)
                  * 0.25 * math.pi * D ** 2)
        return p.R_0 * 0.5 * rho * L * d * u * u - thrust

    u_dead = 0.05 * U0
    reach = quad(lambda u: M * u / net_astern_force(u), u_dead, U0, epsabs=0, epsrel=1e-12)[0]
    time = quad(lambda u: M / net_astern_force(u), u_dead, U0, epsabs=0, epsrel=1e-12)[0]
    assert found["head_reach"][0] == pytest.approx(reach, rel=1e-6)
    assert found["track_reach"][0] == pytest.approx(reach, rel=1e-6)
    assert found["time_dead"][0] == pytest.approx(time, rel=1e-6)
    assert found["lateral_deviation"][0] == 0.0 and found["heading_change"][0] == 0.0
    # energy: the work of resistance and astern thrust equals the kinetic energy lost
    t = r.time
    u = r["surge_speed"][0]
    keep = t <= found["time_dead"][0]
    power = np.array([net_astern_force(v) * v for v in u[keep]])
    work = float(np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t[keep])))
    lost = 0.5 * M * (U0 ** 2 - u[keep][-1] ** 2)
    assert work >= lost * (1.0 - 1e-5)
    assert work == pytest.approx(lost, rel=1e-4)


def test_energy_dissipated_covers_the_kinetic_energy_in_the_full_crash_stop(l7_stop):
    """Full run (engine sequence, 3 DOF): the kinetic energy ½(m + m_x)u² + ½(m + m_y)v² at
    the order is gone at the dead point, and the astern thrust did work against the motion."""
    runs, m = l7_stop.runs, l7_stop.metrics
    p = l7_stop.ships[0].params
    t = runs["time"].values
    keep = t <= float(m["time_dead"])
    scale = 0.5 * p.rho * p.length ** 2 * p.draft
    mass = p.rho * p.displacement
    u, v = runs["surge_speed"].values[keep], runs["sway_speed"].values[keep]
    energy = 0.5 * (mass + p.m_x * scale) * u ** 2 + 0.5 * (mass + p.m_y * scale) * v ** 2
    assert energy[-1] < 0.01 * energy[0]
    thrust = runs["thrust"].values[keep]
    assert np.all(thrust[t[keep] > float(m["time_astern"]) + 1.0] < 0.0)


def test_head_reach_is_plausible_against_the_momentum_estimate(l7_stop):
    """The classic estimate s = U_0 t_d + ½ M U_0² / T_astern (constant bollard astern thrust,
    no resistance; e.g. shipcalculators.com "Crash stop distance") is an upper bound of the
    order of the computed head reach: resistance and the larger astern thrust at ahead speed
    shorten the stop."""
    m = l7_stop.metrics
    p = l7_stop.ships[0].params
    U0 = float(m["approach_speed_value"])
    M = p.rho * p.displacement + p.m_x * 0.5 * p.rho * p.length ** 2 * p.draft
    kt0 = _ct_star(0.0) * math.pi / 8.0 * (0.7 * math.pi) ** 2
    w = 0.7 * math.pi * p.astern_rps * p.propeller_diameter
    bollard = abs(p.k_0 / kt0 * _ct_star(math.pi) * 0.5 * p.rho * w * w * 0.25 * math.pi
                  * p.propeller_diameter ** 2)
    estimate = U0 * p.reversal_delay + 0.5 * M * U0 ** 2 / bollard
    assert 0.5 * estimate < float(m["head_reach"]) < 1.1 * estimate


def test_ensemble_check_includes_stopping_for_ships_that_can_stop():
    from seahelm.analysis.imo.probability import imo_probabilities

    ens = imo_probabilities(["kvlcc2-l7", "kvlcc2-l7-xp-0.5"])
    (row,) = [r for r in ens.rows if r["ability"] == "stopping"]
    assert row["passed"] == row["total"] == 2 and row["limit"] == 15.0
    assert 5.0 < row["median"] < 9.0 and ens.stopping_note == ""
    single = crash_stop("kvlcc2-l7-xp-0.5").metrics
    assert float(single["track_reach"]) / 7.0 < 9.0


@pytest.mark.parametrize("k_0", [0.0, -0.1])
def test_a_propeller_without_thrust_at_zero_advance_is_refused_naming_k_0(k_0):
    """k_0 <= 0 divided by zero (or took the root of a negative number) in the engine
    estimate: exit 1 from the CLI instead of a bad-input error naming the coefficient."""
    from seahelm.ships import get_ship

    ship = get_ship("kvlcc2-l7").replace(params={"k_0": k_0})
    with pytest.raises(ParameterError, match="no self-propulsion rps") as exc:
        stopping_ship(ship)
    assert exc.value.field == "k_0"


def test_a_run_outside_the_cross_flow_hulls_range_warns_and_raises_in_strict_mode():
    """An L7 made directionally unstable (N'_v = −1, the backing side force 50 % of |T|)
    swings while fast: the cross-flow hull is then used above its Fn 0.1."""
    from seahelm.errors import strict_validity
    match = "cross-flow hull .* Fn up to"
    ship = stopping_ship("kvlcc2-l7", backing_side_force=0.5, N_v=-1.0, reversal_delay=0.0)
    with pytest.warns(ValidityRangeWarning, match=match):
        r = crash_stop(ship, speed=1.6, t_final=200.0)
    assert "outside its range" in str(r.metrics["message"].values)
    with strict_validity(), pytest.raises(ParameterError, match=match):
        crash_stop(ship, speed=1.6, t_final=200.0)
    # the catalog L7 stays inside with either hull (the suite turns the warning into an error)
    for hull_model in (0.0, 1.0):
        crash_stop(stopping_ship("kvlcc2-l7", hull_model=hull_model))
