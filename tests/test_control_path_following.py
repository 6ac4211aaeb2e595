"""Waypoint routes and LOS/ILOS path following (Fossen 2021, §12.4) on the Mariner with a PID
heading controller: geometry, zero steady cross-track error without drift, LOS's offset in a
cross current and ILOS removing it, switching inside the acceptance circle, batches, bad input.

Uses two kernels: Mariner + rudder servo + ``los+pid-heading`` and ``ilos+pid-heading``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.control.guided import guided
from seahelm.control.path_following import ILOS, LOS, MAX_WAYPOINTS, get_guidance_law, route_params
from seahelm.control.pid import PID_HEADING
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.simulation.engine import simulate
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR, MARINER_SERVO

U0 = MARINER_NONLINEAR.nominal_speed  # 7.7175 m/s
GAINS = dict(kp=3.0, ki=0.0, kd=60.0, max_command=math.radians(35.0))
DELTA = 800.0  # look-ahead [m]
CURRENT = 1.0  # cross current [m/s], to the east


def _run(law, params, *, x0=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), current=(0.0, 0.0),
         t_final=1500.0, vessel=MARINER_NONLINEAR):
    ctrl = guided(law, PID_HEADING)
    cps = [ctrl.params_type(**p.as_dict(), **GAINS) for p in params]
    dist = np.zeros((len(cps), 1, 5))
    dist[:, 0, 3:] = np.asarray(current)
    res = simulate(MARINER, vessel, np.asarray(x0, dtype=float), t_final=t_final,
                   dt=0.1, controller=ctrl, controller_params=cps, actuator=RUDDER_SERVO,
                   actuator_params=MARINER_SERVO, disturbance=dist, controller_dt=0.5,
                   record_every=5)
    assert res.ok.all(), res.messages()
    return res


STRAIGHT = [[0.0, 0.0], [30000.0, 0.0]]  # due north


def test_cross_track_geometry_on_a_leg():
    """y_e positive to starboard of the path, x_e along it (eq. 12.52), for a leg heading
    north-east: a point 100 m to the right and 50 m along."""
    from seahelm.control.path_following import cross_track
    from seahelm.parameters import as_records

    p = route_params([[0.0, 0.0], [1000.0, 1000.0]])
    rec = as_records(p.to_array()[None, :], type(p))[0]
    c = math.sqrt(0.5)
    # 50 m along the north-east course, then 100 m to starboard of it (south-east: −N, +E)
    north, east = 50.0 * c - 100.0 * c, 50.0 * c + 100.0 * c
    pi_k, x_e, y_e, length = cross_track(rec, 0, north, east)
    assert pi_k == pytest.approx(math.pi / 4) and length == pytest.approx(1000.0 * math.sqrt(2))
    assert x_e == pytest.approx(50.0) and y_e == pytest.approx(100.0)


#: The Mariner without its single-screw bias Y_0, N_0 (which steers it to starboard at zero
#: rudder, with a drift angle: a "current" of its own): port-starboard symmetric.
SYMMETRIC = MARINER_NONLINEAR.replace(Y_0=0.0, Y_0u=0.0, Y_0uu=0.0, N_0=0.0, N_0u=0.0, N_0uu=0.0)


def test_los_converges_to_the_path_without_drift_and_keeps_an_offset_in_a_cross_current():
    p = route_params(STRAIGHT, law=LOS, lookahead=DELTA)
    res = _run(LOS, [p, p], x0=(0.0, 0.0, 0.0, 0.0, 300.0, 0.0),
               current=[[0.0, 0.0], [0.0, CURRENT]], vessel=SYMMETRIC)
    xte = res["cross_track_error"]
    assert xte[0, 0] == pytest.approx(300.0)  # started 300 m to starboard
    assert abs(xte[0, -1]) < 0.05  # no drift: on the path (m)
    tail = xte[1, -60:]  # the last 300 s
    assert np.ptp(tail) < 0.5  # steady
    # LOS in a cross current V_c: the heading must crab by asin(V_c/U) against it, which LOS
    # only commands with an offset y_e = Δ tan(asin(V_c/U)) downstream (to starboard here)
    expected = DELTA * math.tan(math.asin(CURRENT / U0))
    assert tail.mean() == pytest.approx(expected, rel=0.05)


def test_ilos_removes_the_cross_track_offset_of_a_cross_current():
    """κ = U/4 (critical damping of the linearised cross-track dynamics): within 0.1 m after
    2,000 s, where LOS keeps ~104 m; the single-screw bias is removed too (the real Mariner)."""
    p = route_params(STRAIGHT, law=ILOS, lookahead=DELTA, kappa=U0 / 4.0)
    res = _run(ILOS, [p], current=(0.0, CURRENT), t_final=2500.0)
    xte = res["cross_track_error"][0]
    assert np.abs(xte).max() > 20.0  # the current did push the ship off first
    assert np.abs(xte[-100:]).max() < 0.1  # within 0.1 m over the last 500 s
    # and the heading crabs into the current by asin(V_c / U) (the speed through the water)
    heading = res["heading"][0, -1]
    speed = res["speed"][0, -1]
    assert heading == pytest.approx(-math.asin(CURRENT / speed), abs=2e-3)


def test_waypoints_switch_inside_the_acceptance_circle_and_the_route_completes():
    route = [[0.0, 0.0], [4000.0, 0.0], [4000.0, 4000.0], [0.0, 4000.0]]
    radius = 400.0
    p = route_params(route, law=LOS, lookahead=600.0, acceptance_radius=radius)
    res = _run(LOS, [p], t_final=2400.0)
    wp = res["waypoint_index"][0]
    north, east = res["north"][0], res["east"][0]
    switches = np.flatnonzero(np.diff(wp) != 0) + 1
    assert wp[0] == 0 and sorted(set(wp.tolist())) == [0.0, 1.0, 2.0, 3.0]
    assert len(switches) == 3
    for k, i in enumerate(switches):  # the first sample on the new leg is inside the circle
        target = route[k + 1]
        assert math.hypot(north[i] - target[0], east[i] - target[1]) <= radius
        assert math.hypot(north[i - 1] - target[0], east[i - 1] - target[1]) > radius * 0.9
    assert wp[-1] == 3.0  # complete: the last waypoint was reached


def test_a_batch_of_look_aheads_is_one_run_each():
    ps = [route_params(STRAIGHT, law=LOS, lookahead=d) for d in (400.0, 800.0, 1600.0)]
    batch = _run(LOS, ps, current=(0.0, CURRENT), t_final=1500.0)
    single = _run(LOS, [ps[1]], current=(0.0, CURRENT), t_final=1500.0)
    np.testing.assert_array_equal(batch["cross_track_error"][1], single["cross_track_error"][0])
    offsets = batch["cross_track_error"][:, -1]
    assert offsets[0] < offsets[1] < offsets[2]  # the offset grows with the look-ahead


@pytest.mark.parametrize("waypoints, values, match", [
    ([[0.0, 0.0]], {}, r"`waypoints`: a route needs 2 to 32 waypoints, got 1"),
    ([[0.0, 0.0]] * 33, {}, r"a route needs 2 to 32 waypoints, got 33"),
    ([[0.0, 0.0], [100.0, 50.0], [100.0, 50.0]], {},
     r"route: waypoints 1 and 2 are the same point \(100, 50\) \[m\]"),
    ([0.0, 1.0, 2.0], {}, r"`waypoints` must be a list of \(north, east\) points \[m\], got "
                          r"shape \(3,\)"),
    ([[0.0, 0.0], [float("nan"), 0.0]], {}, r"waypoints"),
    (STRAIGHT, {"lookahead": 0.0}, r"`lookahead` must be in \(0, inf\] \[m\], got 0.0"),
    (STRAIGHT, {"lookahead": -5.0}, r"`lookahead` must be in \(0, inf\] \[m\], got -5.0"),
    (STRAIGHT, {"acceptance_radius": 0.0}, r"`acceptance_radius` must be in \(0, inf\] \[m\]"),
    (STRAIGHT, {"lookahead": 100.0, "lookahead_min": 200.0},
     r"`lookahead_min` must not exceed `lookahead` \[m\]"),
])
def test_bad_routes_and_gains_are_clear_errors(waypoints, values, match):
    with pytest.raises(ParameterError, match=match):
        route_params(waypoints, **values)


def test_laws_by_name_and_bad_combinations():
    assert get_guidance_law("ilos") is ILOS and get_guidance_law(LOS) is LOS
    with pytest.raises(ParameterError, match=r"unknown guidance law 'pure-pursuit'; valid: los, "
                                             r"ilos"):
        get_guidance_law("pure-pursuit")
    with pytest.raises(ParameterError, match=r"guidance 'los' steers a heading controller"):
        guided(LOS, OPEN_LOOP)
    assert MAX_WAYPOINTS == 32
    ctrl = guided(ILOS, PID_HEADING)
    assert ctrl.name == "ilos+pid-heading" and ctrl.reference_labels == ()
    assert ctrl.output_labels == ("heading_reference", "cross_track_error",
                                  "along_track_distance", "waypoint_index")
    assert dict(zip(ctrl.output_labels, ctrl.output_units))["cross_track_error"] == "m"
    assert guided("ilos", PID_HEADING) is not None


# -- the [guidance] section of a scenario --------------------------------------------------
SCENARIO = """title = "route"
[vessel]
catalog = "mariner-nonlinear"
[vessel.initial]
heading_deg = 90.0
[actuator.params]
max_angle_deg = 40.0
max_rate_deg = 5.0
time_constant = 1.0
[controller]
model = "pid-heading"
dt = 0.5
[controller.params]
kp = 3.0
ki = 0.0
kd = 60.0
[guidance]
law = "ilos"
waypoints = [[0.0, 0.0], [0.0, 6000.0], [8000.0, 6000.0]]
acceptance_radius = 500.0
lookahead = 800.0
kappa = 1.93
[environment.disturbance]
current_east = 1.0
[simulation]
t_final = 600.0
dt = 0.1
record_every = 5
"""


def test_scenario_guidance_equals_the_api():
    from seahelm.scenario import parse_scenario, run_scenario

    res = run_scenario(parse_scenario(SCENARIO, source="r.toml"))
    p = route_params([[0.0, 0.0], [0.0, 6000.0], [8000.0, 6000.0]], law=ILOS,
                     acceptance_radius=500.0, lookahead=800.0, kappa=1.93)
    api = _run(ILOS, [p], x0=(0.0, 0.0, 0.0, 0.0, 0.0, math.pi / 2), current=(0.0, 1.0),
               t_final=600.0)
    np.testing.assert_allclose(res["cross_track_error"], api["cross_track_error"], rtol=1e-12,
                               atol=1e-9)
    ds = res.to_xarray()
    assert ds["cross_track_error"].attrs["units"] == "m"
    assert ds["controller.route_north"].dims == ("run", "controller.route_north_index")


def test_scenario_grid_over_a_guidance_value_is_a_dimension():
    from seahelm.scenario import parse_scenario

    batch = parse_scenario(SCENARIO + '[batch.grid]\n"guidance.lookahead" = [400.0, 800.0]\n')
    assert batch.layout.dims == ("lookahead",)
    cls = batch.controller.params_type
    col = cls.value_names().index("lookahead")
    assert batch.controller_params[:, col].tolist() == [400.0, 800.0]


@pytest.mark.parametrize("edit, match", [
    (('law = "ilos"', 'law = "pure-pursuit"'),
     r"r.toml: \[guidance.law\] unknown guidance law 'pure-pursuit'; valid: los, ilos"),
    (('law = "ilos"', 'law = "los"'),
     r"r.toml: \[guidance.kappa\] the 'los' law has no integral gain \(kappa is ILOS's\)"),
    (("waypoints = [[0.0, 0.0], [0.0, 6000.0], [8000.0, 6000.0]]", "waypoints = [[0.0, 0.0]]"),
     r"r.toml: \[guidance\] `waypoints`: a route needs 2 to 32 waypoints, got 1"),
    (("[8000.0, 6000.0]]", "[0.0, 6000.0]]"),
     r"r.toml: \[guidance\] route: waypoints 1 and 2 are the same point"),
    (("lookahead = 800.0", "lookahead = 0.0"),
     r"r.toml: \[guidance.lookahead\] must be > 0 \[m\], got 0.0"),
    (('model = "pid-heading"', 'model = "open-loop"'),
     r"r.toml: \[guidance.law\] guidance 'ilos' steers a heading controller"),
])
def test_bad_guidance_sections(edit, match):
    from seahelm.scenario import ScenarioError, parse_scenario

    assert edit[0] in SCENARIO
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(SCENARIO.replace(*edit), source="r.toml")


def test_the_look_ahead_shrinks_with_the_cross_track_error():
    """Δ(y_e) = (Δ_max − Δ_min) exp(−γ y_e²) + Δ_min (Fossen 2021 eq. 12.76)."""
    from seahelm.control.path_following import _lookahead
    from seahelm.parameters import as_records

    p = route_params(STRAIGHT, lookahead=1000.0, lookahead_min=200.0, lookahead_gamma=1e-4)
    rec = as_records(p.to_array()[None, :], type(p))[0]
    for y_e in (0.0, 50.0, -120.0, 1000.0):
        assert _lookahead(rec, y_e) == pytest.approx(800.0 * math.exp(-1e-4 * y_e**2) + 200.0)
    const = as_records(route_params(STRAIGHT, lookahead=700.0).to_array()[None, :], LOS.params_type)
    assert _lookahead(const[0], 300.0) == 700.0


def test_any_heading_controller_on_any_model_and_many_routes_in_one_batch():
    """Nomoto-2 (constant speed) with the PID and with the compensated PID of Lvov (2014),
    whose other references (delta_k_wind, delta_k_wave) stay references of the guided
    controller; two routes in one batch run as each alone."""
    from seahelm.control.compensation import COMPENSATED_PID
    from seahelm.registry import get_controller
    from seahelm.ships import get_ship as catalog_entry
    from seahelm.vessels.nomoto import NOMOTO2

    ship = catalog_entry("mariner-nomoto2").params
    routes = [[[0.0, 0.0], [20000.0, 0.0]], [[0.0, 0.0], [5000.0, 5000.0], [5000.0, 20000.0]]]
    for inner in (PID_HEADING, COMPENSATED_PID):
        ctrl = get_controller(f"los+{inner.name}")
        assert ctrl is guided(LOS, inner)
        assert ctrl.reference_labels == tuple(r for r in inner.reference_labels
                                              if r != "heading")
        cps = [ctrl.params_type(**route_params(r, lookahead=600.0).as_dict(), **GAINS)
               for r in routes]
        kw = dict(t_final=2000.0, dt=0.1, controller=ctrl, actuator=RUDDER_SERVO,
                  actuator_params=MARINER_SERVO, controller_dt=0.5, record_every=10)
        x0 = np.array([0.0, 200.0, 0.0, 0.0, 0.0])  # 200 m to starboard, heading north
        batch = simulate(NOMOTO2, ship, x0, controller_params=cps, **kw)
        assert batch.ok.all()
        xte = batch["cross_track_error"]
        assert abs(xte[0, -1]) < 0.05  # the straight route: on the path
        assert batch["waypoint_index"][1, -1] == 1.0  # the second route turned its corner
        alone = simulate(NOMOTO2, ship, x0, controller_params=cps[1], **kw)
        np.testing.assert_array_equal(alone["cross_track_error"][0], xte[1])


def test_environment_current_section_sets_the_current_channels():
    from seahelm.scenario import ScenarioError, parse_scenario

    text = SCENARIO.replace("[environment.disturbance]\ncurrent_east = 1.0\n",
                            "[environment.current]\nspeed = 2.0\ndirection_deg = 30.0\n")
    batch = parse_scenario(text)
    j = [MARINER.disturbance_labels.index(c) for c in ("current_north", "current_east")]
    np.testing.assert_allclose(batch.disturbance[0, 0, j], [2.0 * math.cos(math.radians(30.0)),
                                                            1.0], rtol=1e-15)
    for edit, match in (
        (("direction_deg = 30.0", "direction_deg = 360.0"),
         r"\[environment.current.direction_deg\] must be < 360 \[deg\], got 360.0"),
        (("speed = 2.0", "speed = -1.0"),
         r"\[environment.current.speed\] must be >= 0 \[m/s\], got -1.0"),
        (("[environment.current]", "[environment.disturbance]\ncurrent_north = 0.5\n"
          "[environment.current]"),
         r"\[environment.current\] the current is given twice: here and as "
         r"environment.disturbance.current_north"),
    ):
        with pytest.raises(ScenarioError, match=match):
            parse_scenario(text.replace(*edit))
    voitkunsky = ('[vessel]\ncatalog = "mariner-voitkunsky"\n[environment.current]\n'
                  'speed = 1.0\ndirection_deg = 0.0\n[simulation]\nt_final = 10.0\ndt = 0.1\n')
    with pytest.raises(ScenarioError, match=r"\[environment.current\] model 'voitkunsky' has no "
                                            r"current channels"):
        parse_scenario(voitkunsky)


def test_on_track_starts_at_each_legs_first_crossing_of_its_line():
    from seahelm.analysis.maneuvers.metrics import on_track

    xte = np.array([[-400.0, -200.0, 50.0, 10.0, -5.0, 300.0, 100.0, 2.0, -1.0],
                    [3.0, 2.0, 1.0, 0.02, 0.5, 0.4, 0.3, 0.2, 0.1]])
    leg = np.array([[0, 0, 0, 0, 0, 1, 1, 1, 1], [0] * 9])
    got = on_track(xte, leg)
    want = np.array([[0, 0, 1, 1, 1, 0, 0, 1, 1],  # crossings; 2.0 is within 1 % of 300
                     [0, 0, 0, 1, 1, 1, 1, 1, 1]], dtype=bool)  # 0.02 <= 1 % of 3.0
    np.testing.assert_array_equal(got, want)


def test_the_route_metrics_tell_the_leg_approach_from_the_track_keeping():
    """max_abs_cross_track_error_m of the ILOS example is the distance to the new leg at a
    waypoint switch (about the 500 m acceptance radius); on track, from each leg's first
    crossing, it is the overshoot onto the leg, and the run ends on the line."""
    from pathlib import Path

    from seahelm.analysis.maneuvers import summarize
    from seahelm.scenario import load_scenario, run_scenario

    path = Path(__file__).parent.parent / "examples" / "mariner_route_ilos.toml"
    row = summarize(run_scenario(load_scenario(path)))[0]
    assert 450.0 < row["max_abs_cross_track_error_m"] <= 500.0 + 1.0
    assert row["max_abs_cross_track_error_on_track_m"] < 0.6 * row["max_abs_cross_track_error_m"]
    assert abs(row["final_cross_track_error_m"]) < 1.0
