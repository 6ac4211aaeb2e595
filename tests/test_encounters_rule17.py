"""Rule 17 for the velocity-obstacles method as a stand-on vessel, on hand-made geometries:
it keeps course while the give-way vessel acts; acts only when the give-way vessel does not
and the CPA stays below the threshold within the stated time; never to port for a vessel on
its port side; one side for a vessel overtaking it from the starboard quarter."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.encounters import Encounter, Vessel
from seahelm.encounters.avoidance import StandOnRules, VelocityObstacles
from seahelm.encounters.geometry import Situation
from seahelm.encounters.monte_carlo import sample_geometry
from seahelm.errors import ParameterError

SHIP = "kvlcc2-full"
OWN_SPEED = 7.97  # [m/s] (the KVLCC2's approach speed, rounded as the encounter rounds it)


def _crossing(bearing_deg: float, dcpa: float) -> dict[str, np.ndarray]:
    """A target from the port side at 9 km, 7.2 m/s, with the signed CPA ``dcpa`` [m]."""
    return sample_geometry(1, own_speed=OWN_SPEED, bearing=math.radians(bearing_deg),
                           detection_range=9000.0, dcpa=dcpa, target_speed=7.2, seed=0)


def _run(target: Vessel, method: VelocityObstacles, t_final: float = 1200.0,
         own_speed: float | None = None):
    own = Vessel(ship=SHIP, course=0.0, speed=own_speed, avoid=True)
    return Encounter([own, target], t_final=t_final, avoidance=method, record_every=1).run()


def _offset(res) -> np.ndarray:
    """The own ship's desired heading less its route's [rad] over time."""
    return res.tracks["desired_heading"][0, 0] - res.tracks["route_heading"][0, 0]


def test_stand_on_keeps_course_while_the_give_way_vessel_acts():
    """The target from port (give-way, Rule 15) alters 60° to starboard at once: the CPA
    opens and the own ship never leaves its route (Rule 17(a)(i))."""
    g = _crossing(320.0, 300.0)
    course = float(g["course"][0]) + math.radians(60.0)
    far = [[g["north"][0] + 30000.0 * math.cos(course), g["east"][0] + 30000.0 * math.sin(course)]]
    tgt = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"], speed=7.2,
                 route=far)
    res = _run(tgt, VelocityObstacles())
    assert res.situation[0, 0] == Situation.CROSSING_STAND_ON
    assert np.abs(_offset(res)).max() == 0.0
    assert res.verdicts["kept_course"][0, 0, 0]
    assert not res.collision[0, 0]


def test_stand_on_acts_to_starboard_when_the_cpa_stays_close_at_the_stated_tcpa():
    """The same target keeping its course (TCPA 780 s at detection, CPA 300 m): the own ship
    keeps its route until the TCPA falls below ``act_tcpa`` (600 s) with the CPA still
    inside the radius (Rule 17(a)(ii)) -- not at the 300 s emergency -- then turns to
    starboard (the target is on its port side, 17(c)) and clears."""
    g = _crossing(320.0, 300.0)
    tgt = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"], speed=7.2)
    method = VelocityObstacles()
    res = _run(tgt, method)
    off = _offset(res)
    first = res.time[np.flatnonzero(off != 0.0)[0]]
    due = g["tcpa"][0] - method.stand_on.act_tcpa  # (both on straight lines until then)
    assert due > method.stand_on.observe  # (the TCPA, not the observation time, decides)
    assert due - method.every - 1.0 <= first <= due + method.every + 1.0
    assert off.min() >= 0.0 and off.max() >= math.radians(20.0)
    assert not res.collision[0, 0] and res.min_range[0, 0] > 1000.0


def test_stand_on_waits_the_observation_time_for_a_risk_seen_late():
    """A target detected at TCPA below ``act_tcpa`` (the geometry of 340°): the own ship
    gives the give-way vessel ``observe`` seconds before acting."""
    g = _crossing(340.0, 300.0)
    tgt = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"], speed=7.2)
    method = VelocityObstacles(stand_on=StandOnRules(observe=200.0))
    res = _run(tgt, method)
    off = _offset(res)
    first = res.time[np.flatnonzero(off != 0.0)[0]]
    assert g["tcpa"][0] < 600.0 + 200.0
    assert 200.0 <= first <= 200.0 + method.every + 1.0
    assert not res.collision[0, 0]


def test_stand_on_never_turns_to_port_for_a_vessel_on_its_port_side():
    """A target from 320° passing astern (CPA -600 m): the velocity obstacles alone would pass
    astern of it by a turn to port (shown with ``keep_side=False``); with Rule 17(c) the own
    ship turns to starboard only."""
    g = _crossing(320.0, -600.0)
    tgt = Vessel(ship=SHIP, north=g["north"], east=g["east"], course=g["course"], speed=7.2)
    free = _run(tgt, VelocityObstacles(stand_on=StandOnRules(keep_side=False)))
    assert _offset(free).min() < -math.radians(20.0)  # (the geometry asks for it)
    res = _run(tgt, VelocityObstacles())
    assert res.situation[0, 0] == Situation.CROSSING_STAND_ON
    off = _offset(res)
    assert off.min() >= 0.0 and off.max() > math.radians(20.0)
    assert not res.collision[0, 0] and res.min_range[0, 0] > 1000.0


@pytest.mark.parametrize("bearing, distance, course, speed, side, least", [
    # encounter 882: from the starboard quarter crossing to port, CPA 157 m: to starboard,
    # behind its track, clear (405 m)
    (163.2883316979162, 1898.4021607369677, -10.015571374909102, 7.34, 1, 350.0),
    # encounter 75: from the port quarter crossing to starboard, CPA 114 m: to port, behind
    # its track (to starboard, into it, it collided: 217 m), just clear (323 m; the KVLCC2s
    # touch at 320 m)
    (189.58067230403972, 1680.990994767355, 6.476331852122172, 7.62, -1, 320.0),
])
def test_overtaken_acts_on_one_side_without_crossing_the_overtakers_track(
        bearing, distance, course, speed, side, least):
    """Encounters 882 and 75 of the Monte-Carlo (seed 51), by hand: the own ship at half
    speed (3.98 m/s) overtaken from a quarter by a target crossing its track from that side.
    882 used to act only at the 300 s emergency, swinging between -60° and +40°, and collide
    (least range 64 m). Keeping the side of passing it had when it started to act, the own
    ship turns towards the overtaker's stern, never into its track."""
    brg = math.radians(bearing)
    tgt = Vessel(ship=SHIP, north=distance * math.cos(brg), east=distance * math.sin(brg),
                 course=math.radians(course), speed=speed)
    res = _run(tgt, VelocityObstacles(), t_final=900.0, own_speed=3.98)
    assert res.situation[0, 0] == Situation.OVERTAKEN
    off = _offset(res)
    assert (off != 0.0).any() and (off * side >= 0.0).all()
    assert not res.collision[0, 0] and res.min_range[0, 0] > least


@pytest.mark.parametrize("make, match", [
    (lambda: StandOnRules(act_tcpa=0.0), r"avoidance.act_tcpa.*|must be > 0 \[s\]"),
    (lambda: StandOnRules(act_tcpa=math.inf), "must be > 0 \\[s\\], got inf"),
    (lambda: StandOnRules(observe=-1.0), "must be >= 0 \\[s\\], got -1.0"),
    (lambda: VelocityObstacles(stand_on=600.0), "must be a StandOnRules, got float"),
])
def test_bad_stand_on_rules_name_the_field(make, match):
    with pytest.raises(ParameterError, match=match) as info:
        make()
    assert info.value.field.startswith("avoidance.")
