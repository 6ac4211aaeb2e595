"""Several vessels in one stepped batch (seahelm.encounters.encounter): with avoidance off an
encounter's vessels move exactly as each alone (bit for bit) and as a plain Simulator driven by
the same PD law written here; an encounter in a batch equals it run alone (avoidance on);
mirrored courses give mirrored tracks; the AIS view's update interval, delay and noise; the
avoidance methods act as the rules ask; bad input names the key, unit and value."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm import Problem, Simulator, get_ship
from seahelm.encounters.encounter import Encounter, HeadingAutopilot, Vessel
from seahelm.encounters.geometry import Situation, relative_bearing
from seahelm.encounters.sensing import AIS
from seahelm.errors import ParameterError

SHIP = "kvlcc2-full"


def _targets():
    """Crossing from starboard, head-on, crossing from port (own ship at the origin, north)."""
    return Vessel(ship=SHIP, north=np.array([4000.0, 6000.0, 4000.0]),
                  east=np.array([4000.0, 100.0, -4000.0]),
                  course=np.array([-math.pi / 2, math.pi, math.pi / 2]))


def _own(**kw):
    return Vessel(ship=SHIP, north=0.0, east=0.0, course=0.0, **kw)


def _same(a, b):
    for name in a.tracks:
        assert np.array_equal(a.tracks[name], b.tracks[name], equal_nan=True), name


def test_coupled_run_without_avoidance_equals_each_vessel_alone_bit_for_bit():
    both = Encounter([_own(avoid=True), _targets()], t_final=120.0, record_every=1).run()
    assert both.tracks["north"].shape == (3, 2, 121)
    own_alone = Encounter([_own()], t_final=120.0, record_every=1).run()
    tgt_alone = Encounter([_targets()], t_final=120.0, record_every=1).run()
    for name in both.tracks:
        assert np.array_equal(both.tracks[name][:, :1], np.broadcast_to(
            own_alone.tracks[name], (3, 1, 121))), name
        assert np.array_equal(both.tracks[name][:, 1:], tgt_alone.tracks[name]), name
    assert np.ptp(both.tracks["east"][:, 1]) > 500  # (they move)


def test_an_encounter_vessel_equals_a_simulator_driven_by_hand():
    """The target of the head-on case, driven by a PD law written here on a plain Simulator."""
    from seahelm.analysis.equilibria.equilibrium import approach_state

    ship = get_ship(SHIP)
    start = approach_state(ship)
    x0 = start.state.copy()
    x0[3:6] = [6000.0, 100.0, math.pi]  # north, east, heading
    ours = Encounter([Vessel(ship=ship, north=6000.0, east=100.0, course=math.pi)],
                     t_final=60.0, record_every=1).run()
    problem = Problem(ship=ship, x0=x0, t_final=60.0, dt=0.1, controller_dt=1.0,
                      record_every=600)
    td = 1.5 * ship.length / ship.approach_speed
    with Simulator(problem) as sim:
        obs = sim.reset()
        headings = [obs["heading"].copy()]
        for _ in range(60):
            err = (math.pi - obs["heading"] + math.pi) % (2 * math.pi) - math.pi
            rudder = np.clip(1.0 * err - 1.0 * td * obs["yaw_rate"], -ship.max_rudder,
                             ship.max_rudder)
            obs = sim.step(np.array([[rudder[0], start.inputs["propeller_rps"]]]))
            headings.append(obs["heading"].copy())
    assert np.array_equal(ours.tracks["heading"][0, 0], np.concatenate(headings))
    assert np.array_equal(ours.tracks["north"][0, 0, -1:], obs["north"])


def test_an_encounter_in_a_batch_equals_it_alone_with_avoidance_on():
    batch = Encounter([_own(avoid=True), _targets()], t_final=300.0,
                      avoidance="velocity-obstacles").run()
    for e in range(3):
        tgt = _targets()
        one = Vessel(ship=SHIP, north=tgt.north[e], east=tgt.east[e], course=tgt.course[e])
        alone = Encounter([_own(avoid=True), one], t_final=300.0,
                          avoidance="velocity-obstacles").run()
        for name in batch.tracks:
            assert np.array_equal(batch.tracks[name][e:e + 1], alone.tracks[name]), name
    assert np.ptp(batch.tracks["heading"][0, 0]) > math.radians(20)  # (it avoided)


def test_mirrored_courses_give_mirrored_tracks():
    """Two identical (symmetric, Nomoto) ships on courses mirrored about north, steering
    routes that turn: the second's track is the first's reflected (east -> -east)."""
    route = np.array([[3000.0, 1500.0], [6000.0, 4000.0]])
    flip = np.array([1.0, -1.0])
    a = Vessel(ship="mariner-nomoto2", north=0.0, east=-2000.0, route=route + [0, -2000.0])
    b = Vessel(ship="mariner-nomoto2", north=0.0, east=2000.0, route=(route + [0, -2000.0]) * flip)
    res = Encounter([a, b], t_final=600.0, record_every=5).run()
    tr = res.tracks
    np.testing.assert_allclose(tr["north"][0, 1], tr["north"][0, 0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(tr["east"][0, 1], -tr["east"][0, 0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(tr["heading"][0, 1], -tr["heading"][0, 0], rtol=0, atol=1e-12)
    assert np.ptp(tr["heading"][0, 0]) > 0.2  # (the route turns)


def test_ais_update_interval_delay_and_noise():
    sensor = AIS(update_interval=3.0, delay=2.0)
    view = sensor.start(1, 1.0, 100.0)
    truth = lambda k: np.full((1, 5), float(k))  # noqa: E731
    seen = [view.update(k, truth(k))[0, 0] for k in range(12)]
    # reports at 0, 3, 6, 9 arrive 2 s later and are held until the next
    assert np.isnan(seen[:2]).all()
    assert seen[2:] == [0, 0, 0, 3, 3, 3, 6, 6, 6, 9]
    noisy = AIS(position_noise=10.0, seed=3).start(2000, 1.0, 100.0)
    v = noisy.update(0, np.zeros((2000, 5)))
    assert 9.0 < v[:, 0].std() < 11.0 and (v[:, 2] == 0).all()
    again = AIS(position_noise=10.0, seed=3).start(2000, 1.0, 100.0).update(0, np.zeros((2000, 5)))
    assert np.array_equal(v, again)


def test_a_delayed_view_changes_nothing_without_avoidance_and_something_with_it():
    base = dict(t_final=300.0)
    quick = Encounter([_own(avoid=True), _targets()], avoidance="rule-based", **base).run()
    late = Encounter([_own(avoid=True), _targets()], avoidance="rule-based",
                     sensor=AIS(delay=60.0, update_interval=10.0), **base).run()
    t_quick = quick.verdicts["action_time"][:2, 0, 0]
    t_late = late.verdicts["action_time"][:2, 0, 0]
    assert (t_late >= t_quick + 60.0).all()


@pytest.mark.parametrize("method", ["rule-based", "velocity-obstacles"])
def test_avoidance_acts_as_the_rules_ask(method):
    free = Encounter([_own(avoid=True), _targets()], t_final=1200.0).run()
    res = Encounter([_own(avoid=True), _targets()], t_final=1200.0, avoidance=method).run()
    sit = res.situation[:, 0]
    assert sit.tolist() == [Situation.CROSSING_GIVE_WAY, Situation.HEAD_ON,
                            Situation.CROSSING_STAND_ON]
    assert free.collision[:2, 0].all()  # without avoidance the give-way cases collide
    v = res.verdicts
    # give-way cases: acted, substantially, to starboard; no collision, no domain intrusion
    assert v["acted"][:2, 0, 0].all() and v["substantial"][:2, 0, 0].all()
    assert not res.collision[:2].any() and not res.near_miss[:2].any()
    turn = res.tracks["desired_heading"][:2, 0] - res.tracks["route_heading"][:2, 0]
    assert (turn.max(axis=1) > math.radians(25)).all() and (turn.min(axis=1) >= 0).all()
    # passed with the target on the own ship's port side
    k = np.argmin(res.pair["range"][:2, 0], axis=1)
    own = np.stack([res.tracks["north"][:2, 0], res.tracks["east"][:2, 0]], -1)
    tgt = np.stack([res.tracks["north"][:2, 1], res.tracks["east"][:2, 1]], -1)
    beta = relative_bearing(own[[0, 1], k], res.tracks["heading"][[0, 1], 0, k], tgt[[0, 1], k])
    assert (beta > math.pi).all()
    # then resumed the route
    assert np.abs(res.tracks["desired_heading"][:2, 0, -1]).max() < 1e-12
    # stand-on (target from port, who does not avoid: collision course) kept course until
    # the last moment (the velocity obstacles act once its inaction is apparent, Rule 17(a)(ii))
    assert v["role"][2, 0, 0] == -1
    if method == "rule-based":
        assert v["kept_course"][2, 0, 0]


def test_mixed_ships_run_as_two_batches_in_lockstep():
    own = _own(avoid=True)
    tgt = Vessel(ship="mariner-nonlinear", north=5000.0, east=5000.0, course=-math.pi / 2)
    res = Encounter([own, tgt], t_final=200.0, avoidance="rule-based").run()
    assert res.tracks["north"].shape[:2] == (1, 2) and (res.status == 0).all()
    assert "mariner-nonlinear" in res.names[1]
    assert res.to_xarray()["north"].dims == ("encounter", "vessel", "time")


@pytest.mark.parametrize("make, match", [
    (lambda: Encounter([_own(), Vessel(ship=SHIP, north=1000.0)], t_final=10.0),
     r"vessels\[1\].course"),
    (lambda: Encounter([_own(), Vessel(ship=SHIP, north=100.0, course=0.0)], t_final=10.0),
     r"vessels\[1\].north.*inside each other's hull"),
    (lambda: Encounter([_own()], t_final=10.0, sensor=AIS(delay=10.0)), "sensor.delay"),
    (lambda: Encounter([_own()], t_final=10.0, sensor=AIS(delay=0.5)), "sensor.delay"),
    (lambda: AIS(position_noise=-1.0), "sensor.position_noise"),
    (lambda: Encounter([_own()], t_final=10.0, avoidance="magic"), "unknown avoidance"),
    (lambda: Encounter([_own(), Vessel(ship="mariner-nomoto1", north=5000.0, course=0.0,
                                       speed=5.0)], t_final=10.0), r"vessels\[1\].speed"),
    (lambda: Encounter([_own()], t_final=10.0, autopilot=HeadingAutopilot(gain=-1.0)),
     "autopilot.gain"),
])
def test_bad_input_names_the_key(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_rule_based_stand_on_keeps_course_while_a_port_crosser_draws_ahead():
    """A target from port passing ahead draws to the starboard bow before the CPA; the
    situation stays the one detected (stand-on), so the baseline keeps its course (Rule 17)."""
    tgt = Vessel(ship=SHIP, north=4600.0, east=-4000.0, course=math.pi / 2, speed=8.0)
    res = Encounter([_own(avoid=True), tgt], t_final=900.0, avoidance="rule-based").run()
    assert res.situation[0, 0] == Situation.CROSSING_STAND_ON
    assert res.min_range[0, 0] < 1852.0  # (a risk: CPA within the threshold)
    beta = relative_bearing(np.stack([res.tracks["north"][0, 0], res.tracks["east"][0, 0]], -1),
                            res.tracks["heading"][0, 0],
                            np.stack([res.tracks["north"][0, 1], res.tracks["east"][0, 1]], -1))
    assert (beta < math.pi / 2).any()  # (it drew to starboard)
    assert res.verdicts["kept_course"][0, 0, 0]
    assert np.abs(res.tracks["desired_heading"][0, 0]).max() == 0.0


def test_velocity_obstacles_stand_on_acts_only_when_the_give_way_does_not_and_clears():
    """A target from the port bow on a near-collision course that does not give way: the own
    ship (stand-on) keeps its course for the observation time (its inaction apparent, Rule
    17(a)(ii); the TCPA at detection is already below ``act_tcpa``), then avoids to
    starboard within its reachable headings and does not collide (tests in
    test_encounters_rule17.py)."""
    from seahelm.encounters.avoidance import VelocityObstacles
    from seahelm.encounters.monte_carlo import sample_geometry

    g = sample_geometry(1, own_speed=7.97, bearing=math.radians(344.0), detection_range=7000.0,
                        dcpa=-180.0, target_speed=7.2, seed=0)
    tgt = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"], speed=7.2)
    method = VelocityObstacles()
    res = Encounter([_own(avoid=True), tgt], t_final=1200.0, avoidance=method).run()
    assert res.situation[0, 0] == Situation.CROSSING_STAND_ON
    t_act = res.verdicts["action_time"][0, 0, 0]
    assert g["tcpa"][0] < method.stand_on.act_tcpa
    assert t_act > method.stand_on.observe
    off = res.tracks["desired_heading"][0, 0] - res.tracks["route_heading"][0, 0]
    assert off.min() >= 0.0 and off.max() > 0.0
    assert not res.collision[0, 0] and res.min_range[0, 0] > 400.0
