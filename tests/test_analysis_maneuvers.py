"""The manoeuvre library (seahelm.analysis.maneuvers): turning circles, zig-zags, spirals, pull-outs.

Simulations use three component combinations only: MMG + rudder servo + open loop, MMG + rudder
servo + zigzag-rps, Mariner + rudder servo + open loop (the Mariner's zig-zag controller is
checked by composition, without compiling it). Expected values come from independent
computations written here (interpolation of the recorded track, analytic test signals, the
model's own right-hand side), never from the code under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.equilibria.equilibrium import (
    rudder_for_yaw_rate,
    self_propulsion_rps,
    steady_turn,
)
from seahelm.analysis.maneuvers import (
    default_time_step,
    direct_spiral,
    maneuver_ship,
    metrics_rows,
    pull_out,
    reverse_spiral,
    turning_circle,
    zigzag,
    zigzag_metrics,
)
from seahelm.control.zigzag import ZIGZAG, ZIGZAG_RPS, ZigZagParams, ZigZagRpsParams
from seahelm.errors import ParameterError
from seahelm.registry import get_controller
from seahelm.ships import Ship
from seahelm.simulation.composition import compose
from seahelm.vessels.mariner import MARINER, MARINER_NONLINEAR, MARINER_SERVO
from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO, MMG

DEG = math.pi / 180.0
L7 = KVLCC2_L7.length
SYMMETRIC = KVLCC2_L7.replace(gamma_R_minus=0.5, gamma_R_plus=0.5, C_2_minus=1.3,
                              C_2_plus=1.3)
UNBIASED_MARINER = MARINER_NONLINEAR.replace(Y_0=0.0, Y_0u=0.0, Y_0uu=0.0, N_0=0.0, N_0u=0.0,
                                             N_0uu=0.0)


# ------------------------------------------------------------------------------------------
# independent interpolation of a recorded track
# ------------------------------------------------------------------------------------------
def first_crossing(t, psi, change):
    """The time of the first heading change >= change and the 4 samples around it: the cubic
    through them (scipy's barycentric interpolation) solved by brentq in the bracketing
    interval."""
    from scipy.interpolate import BarycentricInterpolator
    from scipy.optimize import brentq

    d = np.abs(psi - psi[0])
    hits = np.nonzero(d >= change)[0]
    if hits.size == 0:
        return None
    k = int(hits[0])
    assert k > 0
    j0 = min(max(k - 2, 0), t.size - 4)
    nodes = slice(j0, j0 + 4)
    cubic = BarycentricInterpolator(t[nodes], d[nodes])
    when = brentq(lambda x: float(cubic(x)) - change, t[k - 1], t[k], xtol=1e-14, rtol=1e-15)
    return nodes, when


def lerp(a, crossing):
    from scipy.interpolate import BarycentricInterpolator

    nodes, when = crossing
    return float(BarycentricInterpolator(lerp.t[nodes], a[nodes])(when))


def by_hand(run):
    """Advance, transfer, TD, times, 10 deg point of one run (original course north)."""
    t = run["time"].values
    lerp.t = t
    n, e, psi = run["north"].values, run["east"].values, run["heading"].values
    assert psi[0] == 0.0 and n[0] == 0.0 and e[0] == 0.0
    out = {}
    c90, c180, c10 = (first_crossing(t, psi, a * DEG) for a in (90.0, 180.0, 10.0))
    out["advance"] = lerp(n, c90)
    out["transfer"] = abs(lerp(e, c90))
    out["time_90"] = c90[1]
    out["tactical_diameter"] = abs(lerp(e, c180))
    out["time_180"] = c180[1]
    out["time_10"] = c10[1]
    # the arc length of the splines through the positions up to the 10 deg point, by quad
    from scipy.integrate import quad
    from scipy.interpolate import CubicSpline

    sn, se = CubicSpline(t, n), CubicSpline(t, e)
    speed = lambda x: math.hypot(float(sn(x, 1)), float(se(x, 1)))  # noqa: E731
    nodes = c10[0]
    t_end = t[nodes.start:nodes.stop]
    s_nodes = [sum(quad(speed, a, b, epsabs=1e-13)[0] for a, b in zip(t[:-1], t[1:]) if b <= x)
               for x in t_end]
    out["distance_10"] = lerp(np.r_[np.zeros(nodes.start), s_nodes,
                                    np.zeros(t.size - nodes.stop)], c10)
    out["steady_radius"] = run["speed"].values[-1] / abs(run["yaw_rate"].values[-1])
    return out


@pytest.fixture(scope="module")
def l7_turns():
    """35 deg circles of KVLCC2 L7 and of a variant symmetric by side: dims ship x side."""
    sym = maneuver_ship(SYMMETRIC, servo=KVLCC2_L7_SERVO, name="kvlcc2-l7-symmetric")
    return turning_circle(["kvlcc2-l7", sym], 35 * DEG, t_final=80.0)


def test_turning_result_shape(l7_turns):
    m, runs = l7_turns.metrics, l7_turns.runs
    assert m["complete"].dims == ("ship", "side")
    assert list(m["ship_name"].values) == ["kvlcc2-l7", "kvlcc2-l7-symmetric"]
    assert list(m["side"].values) == [1, -1]
    assert runs["heading"].dims == ("ship", "side", "time")
    assert m["advance"].attrs["units"] == "m"
    assert bool(m["complete"].all())
    # 80 s is about 270 deg: complete, but not yet steady, and the message says so
    assert all(str(msg).startswith("ok; the turn was not yet steady")
               for msg in m["message"].values.ravel())
    assert m.attrs["dt"] == 0.05 and runs["time"].values[-1] == pytest.approx(80.0)
    # rudder ordered at t = 0 to +-35 deg through the steering gear (15.8 deg/s)
    rudder = runs["rudder_angle"].sel(ship=0)
    assert rudder.sel(side=1).values[0] == 0.0
    assert rudder.sel(side=1).values[-1] == pytest.approx(35 * DEG, abs=1e-9)
    assert rudder.sel(side=-1).values[-1] == pytest.approx(-35 * DEG, abs=1e-9)


@pytest.mark.parametrize("ship", [0, 1])
@pytest.mark.parametrize("side", [1, -1])
def test_turning_metrics_equal_an_independent_interpolation(l7_turns, ship, side):
    m = l7_turns.metrics.sel(ship=ship, side=side)
    expected = by_hand(l7_turns.runs.sel(ship=ship, side=side))
    for key, value in expected.items():
        assert float(m[key]) == pytest.approx(value, rel=1e-10, abs=1e-10), key
    # the 90 deg point is on the turning side
    assert np.sign(l7_turns.runs.sel(ship=ship, side=side)["east"].values[-1]) == side


def test_symmetric_variant_turns_the_same_to_both_sides(l7_turns):
    m = l7_turns.metrics.sel(ship=1)
    for key in ("advance", "transfer", "tactical_diameter", "time_90", "time_180", "time_10",
                "distance_10", "steady_radius", "steady_speed", "speed_loss"):
        assert float(m[key].sel(side=1)) == pytest.approx(float(m[key].sel(side=-1)),
                                                          rel=1e-9), key
    for key in ("steady_drift_angle", "steady_yaw_rate"):
        assert float(m[key].sel(side=1)) == pytest.approx(-float(m[key].sel(side=-1)),
                                                          rel=1e-9), key


def test_standard_kvlcc2_turns_differently_by_side(l7_turns):
    """gamma_R and C_2 by the sign of beta_R, beta_P: the port turn is faster in yaw."""
    m = l7_turns.metrics.sel(ship=0)
    assert float(m["time_180"].sel(side=1)) > 1.01 * float(m["time_180"].sel(side=-1))
    assert float(m["steady_radius"].sel(side=1)) > 1.01 * float(m["steady_radius"].sel(side=-1))
    # IMO-sized numbers of the L7 model (the MMG tests bracket them the same way)
    assert 3.0 < float(m["advance"].sel(side=1)) / L7 < 3.4
    assert 3.0 < float(m["tactical_diameter"].sel(side=1)) / L7 < 3.5


def test_turning_never_reaching_180_deg_is_reported():
    res = turning_circle("kvlcc2-l7", 35 * DEG, sides=1, t_final=30.0)
    m = res.metrics
    assert m["complete"].dims == ()  # a single run: no batch dims
    assert math.isfinite(float(m["advance"])) and math.isnan(float(m["tactical_diameter"]))
    assert math.isnan(float(m["time_180"]))
    assert not bool(m["complete"])
    assert "180 deg heading change not reached within t_final = 30 s" in str(m["message"].item())
    row = metrics_rows(m)[0]
    assert row["complete"] is False and math.isnan(row["tactical_diameter"])


def test_batched_equals_one_by_one():
    kwargs = dict(t_final=40.0)
    batch = turning_circle("kvlcc2-l7", np.array([10.0, 35.0]) * DEG, sides=(1, -1), **kwargs)
    assert batch.metrics["complete"].dims == ("rudder", "side")
    for rudder in (10.0, 35.0):
        for side in (1, -1):
            one = turning_circle("kvlcc2-l7", rudder * DEG, sides=side, **kwargs)
            b = batch.metrics.sel(rudder=rudder * DEG, side=side)
            for key in ("advance", "transfer", "time_90", "time_10", "distance_10",
                        "steady_yaw_rate", "final_heading_change"):
                np.testing.assert_allclose(float(b[key]), float(one.metrics[key]), rtol=0,
                                           atol=1e-12, err_msg=key)
            run = batch.runs.sel(rudder=rudder * DEG, side=side)
            np.testing.assert_allclose(run["heading"].values, one.runs["heading"].values,
                                       rtol=0, atol=1e-12)


def test_single_run_metrics_built_directly_equal_xarrays_construction(monkeypatch):
    """A single run's metrics skip xarray's merge (common._indexless_dataset); the Dataset is
    the one xr.Dataset(...) builds: same variables in the same order, values, attributes."""
    from seahelm.analysis.maneuvers import common

    def calls():
        return (turning_circle("kvlcc2-l7", 35 * DEG, sides=1, t_final=40.0).metrics,
                pull_out("kvlcc2-l7", 20 * DEG, sides=1, t_final=40.0).metrics)

    fast = calls()
    monkeypatch.setattr(common, "_indexless_dataset", lambda *args: None)
    slow = calls()
    for f, s in zip(fast, slow):
        assert f.identical(s)
        assert list(f.variables) == list(s.variables) and repr(f) == repr(s)
        assert f["message"].dtype == s["message"].dtype and not f.indexes


def test_speed_and_rps_dimensions():
    n = self_propulsion_rps(KVLCC2_L7, 1.0)
    by_rps = turning_circle("kvlcc2-l7", 35 * DEG, sides=1, rps=n, t_final=10.0)
    assert float(by_rps.metrics["approach_speed_value"]) == pytest.approx(1.0, rel=1e-9)
    speeds = turning_circle("kvlcc2-l7", 35 * DEG, sides=1, speed=[1.0, 1.179], t_final=10.0)
    assert speeds.metrics["complete"].dims == ("approach_speed",)
    np.testing.assert_allclose(speeds.metrics["propeller_rps"].values,
                               [n, self_propulsion_rps(KVLCC2_L7, 1.179)], rtol=1e-12)
    first = speeds.runs.sel(approach_speed=1.0)
    assert first["surge_speed"].values[0] == pytest.approx(1.0, rel=1e-12)


# ------------------------------------------------------------------------------------------
# the Mariner: Y_0/N_0 bias -> documented asymmetry; without it the turns mirror
# ------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def mariner_turns():
    unbiased = maneuver_ship(UNBIASED_MARINER, servo=MARINER_SERVO, name="mariner-unbiased")
    return turning_circle(["mariner-nonlinear", unbiased], 35 * DEG, t_final=330.0)


def test_mariner_turns_tighter_to_starboard(mariner_turns):
    """With zero rudder the Mariner turns slowly to starboard (Y_0, N_0): the approach needs a
    rudder trim and the starboard circle is tighter than the port one."""
    m = mariner_turns.metrics.sel(ship=0)
    runs = mariner_turns.runs.sel(ship=0)
    trim = float(runs["rudder_angle"].sel(side=1).values[0])
    assert trim < -0.5 * DEG  # a port trim keeps the approach straight
    assert runs["yaw_rate"].sel(side=1).values[0] == 0.0
    td_s, td_p = (float(m["tactical_diameter"].sel(side=s)) for s in (1, -1))
    assert td_p > 1.02 * td_s
    assert float(m["steady_yaw_rate"].sel(side=1)) > -1.02 * float(
        m["steady_yaw_rate"].sel(side=-1)) > 0
    expected = by_hand(runs.sel(side=-1))
    assert float(m["tactical_diameter"].sel(side=-1)) == pytest.approx(
        expected["tactical_diameter"], rel=1e-12)


def test_mariner_without_the_bias_mirrors(mariner_turns):
    m = mariner_turns.metrics.sel(ship=1)
    for key in ("advance", "transfer", "tactical_diameter", "time_90", "time_180"):
        assert float(m[key].sel(side=1)) == pytest.approx(float(m[key].sel(side=-1)),
                                                          rel=1e-9), key
    assert float(mariner_turns.runs["rudder_angle"].sel(ship=1, side=1).values[0]) == 0.0


# ------------------------------------------------------------------------------------------
# zig-zag metrics on an analytic heading signal (no simulation)
# ------------------------------------------------------------------------------------------
#: extremes (time [s], heading [deg]) of a synthetic zig-zag; between them the heading follows
#: half a cosine, so the extremes are exactly these points and the signal is monotonic between
PEAKS_T = np.array([0.0, 20.013, 45.037, 75.021, 103.3])
PEAKS_PSI = np.array([0.0, 15.0, -22.5, 17.25, -12.0])
TRIGGER = 10.0


def synthetic(t):
    psi = np.empty_like(t)
    for k in range(PEAKS_T.size - 1):
        a, b = PEAKS_T[k], PEAKS_T[k + 1]
        sel = (t >= a) & (t <= b)
        pa, pb = PEAKS_PSI[k], PEAKS_PSI[k + 1]
        psi[sel] = 0.5 * (pa + pb) + 0.5 * (pa - pb) * np.cos(np.pi * (t[sel] - a) / (b - a))
    return np.radians(psi)


def crossing_time(k, level):
    """Time the half-cosine segment k passes ``level`` [deg] (solved analytically)."""
    a, b = PEAKS_T[k], PEAKS_T[k + 1]
    pa, pb = PEAKS_PSI[k], PEAKS_PSI[k + 1]
    c = (level - 0.5 * (pa + pb)) / (0.5 * (pa - pb))
    return a + (b - a) * math.acos(c) / math.pi


@pytest.mark.parametrize("first_side", [1, -1])
def test_zigzag_metrics_on_a_synthetic_heading(first_side):
    t = np.arange(0.0, 103.3, 0.05)
    psi = first_side * synthetic(t) + 0.3  # base heading 0.3 rad
    m = zigzag_metrics(t, psi, trigger=math.radians(TRIGGER), first_side=first_side,
                       base_heading=0.3)
    executes = [crossing_time(0, TRIGGER), crossing_time(1, -TRIGGER), crossing_time(2, TRIGGER)]
    overshoots = [15.0 - TRIGGER, 22.5 - TRIGGER, 17.25 - TRIGGER]
    assert m.message == ["ok"]
    np.testing.assert_allclose(m.execute_time[0], executes, atol=2e-4)
    np.testing.assert_allclose(np.degrees(m.overshoot[0]), overshoots, atol=1e-4)
    # the curvature of the test signal jumps at each extreme (half-cosines of different
    # lengths meet there), which biases the parabola's vertex time by a fraction of a step
    np.testing.assert_allclose(m.overshoot_time[0], PEAKS_T[1:4], atol=0.2 * 0.05)
    np.testing.assert_allclose(np.degrees(m.extreme_heading[0]),
                               first_side * PEAKS_PSI[1:4], atol=1e-4)
    assert m.initial_turning_time[0] == pytest.approx(executes[0], abs=2e-4)
    assert m.time_to_check_yaw[0] == pytest.approx(PEAKS_T[1] - executes[0], abs=0.2 * 0.05)
    assert m.period[0] == pytest.approx(executes[2] - executes[0], abs=4e-4)


def test_zigzag_metrics_report_what_is_not_reached():
    t = np.arange(0.0, 103.3, 0.05)
    psi = synthetic(t)
    early = t <= 70.0  # the fourth execute (+10 deg at 66.6 s) is in, its extreme (75 s) is not
    m = zigzag_metrics(t[early], np.stack([psi[early], psi[early]]),
                       trigger=[math.radians(TRIGGER), math.radians(30.0)], first_side=1)
    assert np.all(np.isfinite(m.overshoot[0, :2])) and math.isnan(m.overshoot[0, 2])
    assert math.isfinite(m.execute_time[0, 2]) and math.isfinite(m.period[0])
    assert "overshoot 3 not reached" in m.message[0]
    # a 30 deg trigger is never reached: nothing is, and it says so
    assert np.all(np.isnan(m.overshoot[1])) and math.isnan(m.initial_turning_time[1])
    assert "second execute (heading +30 deg) not reached" in m.message[1]


@pytest.mark.parametrize("kwargs, match", [
    (dict(trigger=0.0), r"`trigger` must be > 0 \[rad\]"),
    (dict(trigger=0.1, first_side=0), r"`first_side` must be \+1 or -1"),
    (dict(trigger=0.1, order_time=500.0), r"`order_time` must lie in"),
])
def test_zigzag_metrics_validation(kwargs, match):
    t = np.arange(0.0, 10.0, 0.1)
    with pytest.raises(ParameterError, match=match):
        zigzag_metrics(t, np.zeros_like(t), **kwargs)


# ------------------------------------------------------------------------------------------
# the zig-zag controller and manoeuvre
# ------------------------------------------------------------------------------------------
def test_zigzag_controllers_compose_with_both_models():
    two = compose(MMG, RUDDER_SERVO, ZIGZAG_RPS)
    assert two.describe() == (
        "controller.rudder_command -> actuator.rudder_command\n"
        "actuator.rudder_angle -> model.rudder_angle\n"
        "controller.propeller_rps -> model.propeller_rps\n"
        "model.heading -> controller.heading\n"
        "model.yaw_rate -> controller.yaw_rate")
    one = compose(MARINER, RUDDER_SERVO, ZIGZAG)
    assert one.describe() == (
        "controller.rudder_command -> actuator.rudder_command\n"
        "actuator.rudder_angle -> model.rudder_angle\n"
        "model.heading -> controller.heading\n"
        "model.yaw_rate -> controller.yaw_rate")
    assert get_controller("zigzag") is ZIGZAG and get_controller("zigzag-rps") is ZIGZAG_RPS
    with pytest.raises(ParameterError, match="model input 'propeller_rps' is not fed"):
        compose(MMG, RUDDER_SERVO, ZIGZAG)


@pytest.mark.parametrize("kwargs, match", [
    (dict(first_side=0.5), r"`first_side` must be \+1 \(starboard\) or -1"),
    (dict(heading_trigger=0.0), r"`heading_trigger` must be in \(0"),
])
def test_zigzag_params_validation(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        ZigZagParams(**kwargs)
    with pytest.raises(ParameterError, match=r"`propeller_rps` must be in \(0"):
        ZigZagRpsParams(propeller_rps=0.0)


@pytest.fixture(scope="module")
def l7_zigzags():
    return zigzag("kvlcc2-l7", 10 * DEG)  # 10/10 to both sides


def test_zigzag_reverses_the_rudder_at_the_sample_nearest_the_trigger(l7_zigzags):
    dt = l7_zigzags.metrics.attrs["dt"]
    assert dt == 0.025  # half the default step of the L7
    for side in (1, -1):
        run = l7_zigzags.runs.sel(side=side)
        t = run["time"].values
        dev = side * run["heading"].values  # base heading 0
        cmd = side * run["rudder_command"].values
        assert cmd[0] == pytest.approx(10 * DEG)
        # the heading passes the trigger between samples j - 1 and j (linear interpolation)
        j = int(np.argmax(dev >= 10 * DEG))
        t_cross = t[j - 1] + (10 * DEG - dev[j - 1]) / (dev[j] - dev[j - 1]) * dt
        # the order is reversed (and held over the step) at the sample nearest the crossing
        k = int(np.argmax(cmd < 0))
        assert np.all(cmd[:k] == pytest.approx(10 * DEG)) and cmd[k] == pytest.approx(-10 * DEG)
        assert abs(t[k] - t_cross) <= 0.5 * dt + 1e-3 * dt
        assert k in (j - 1, j)
        # the propeller is held at the approach's self-propulsion rps
        np.testing.assert_allclose(run["propeller_rps"].values,
                                   self_propulsion_rps(KVLCC2_L7, KVLCC2_L7.approach_speed))


def test_zigzag_overshoots_agree_with_the_recorded_extremes(l7_zigzags):
    m = l7_zigzags.metrics
    assert bool(m["complete"].all())
    for side in (1, -1):
        run = l7_zigzags.runs.sel(side=side)
        t, dev = run["time"].values, side * run["heading"].values
        k2 = int(np.argmax(dev >= 10 * DEG))
        k3 = k2 + int(np.argmax(dev[k2:] <= -10 * DEG))
        first = dev[k2:k3].max() - 10 * DEG  # largest recorded sample beyond the trigger
        mm = m.sel(side=side)
        # the parabola's vertex is at or above the largest sample, by less than 1e-4 deg
        o1 = float(mm["overshoot"].sel(n=1))
        assert 0.0 <= o1 - first < 1e-4 * DEG
        assert float(mm["overshoot_time"].sel(n=1)) == pytest.approx(
            t[k2 + int(np.argmax(dev[k2:k3]))], abs=0.025)
        # the first execute by linear interpolation of the recorded heading
        w = (10 * DEG - dev[k2 - 1]) / (dev[k2] - dev[k2 - 1])
        assert float(mm["initial_turning_time"]) == pytest.approx(
            t[k2 - 1] + w * (t[k2] - t[k2 - 1]), abs=1e-12)
    # IMO-sized: 10/10 first overshoots of a few degrees, second larger
    o = np.degrees(m["overshoot"].values)
    assert np.all((2.0 < o[:, 0]) & (o[:, 0] < 10.0)), o


def test_zigzag_trigger_out_of_reach_is_refused_before_running():
    with pytest.raises(ParameterError, match=r"`heading` trigger 60 deg is not reached within "
                                             r"`t_final` = 20.0 \[s\] with 10 deg rudder"):
        zigzag("kvlcc2-l7", 10 * DEG, 60 * DEG, t_final=20.0)


def test_zigzag_without_the_reachability_check_runs_and_says_what_was_not_reached():
    # what an ensemble does: the trigger is not refused, the run ends without its execute
    m = zigzag("kvlcc2-l7", 10 * DEG, 60 * DEG, sides=1, t_final=20.0,
               check_reachable=False).metrics
    assert not bool(m["complete"])
    assert np.isnan(m["overshoot"].values).all()
    # (the first execute is the order at t = 0; the trigger crossing is the second)
    assert "second execute (heading +60 deg) not reached within t = 20 s" in str(
        m["message"].item())
    # and a reachable one gives the same numbers with or without the check
    with_check = zigzag("kvlcc2-l7", 10 * DEG, sides=1, t_final=60.0).metrics
    without = zigzag("kvlcc2-l7", 10 * DEG, sides=1, t_final=60.0,
                     check_reachable=False).metrics
    np.testing.assert_array_equal(with_check["overshoot"].values, without["overshoot"].values)
    with pytest.raises(ParameterError, match="`check_reachable`.*only with a given `t_final`"):
        zigzag("kvlcc2-l7", 10 * DEG, check_reachable=False)


def test_zigzag_cut_short_is_flagged():
    res = zigzag("kvlcc2-l7", 10 * DEG, sides=1, t_final=30.0)
    m = res.metrics
    assert not bool(m["complete"])
    assert math.isfinite(float(m["overshoot"].sel(n=1)))
    assert math.isnan(float(m["overshoot"].sel(n=3))) and math.isnan(float(m["period"]))
    assert "not reached within t = 30 s" in str(m["message"].item())


def test_zigzag_pairs_dimension():
    res = zigzag("kvlcc2-l7", np.array([20.0, 20.0]) * DEG, np.array([20.0, 10.0]) * DEG,
                 sides=1, t_final=40.0)
    m = res.metrics
    assert m["complete"].dims == ("pair",)
    np.testing.assert_allclose(np.degrees(m["trigger"].values), [20.0, 10.0])
    # the smaller trigger reverses earlier
    t2 = m["initial_turning_time"].values
    assert t2[1] < t2[0]


# ------------------------------------------------------------------------------------------
# pull-out and spirals
# ------------------------------------------------------------------------------------------
def test_pullout_kvlcc2_keeps_turning_to_port():
    """KVLCC2 L7 is course-unstable on the port side: after a port turn the yaw rate settles
    at a non-zero equilibrium with zero rudder (the model's accelerations vanish there)."""
    res = pull_out("kvlcc2-l7", 20 * DEG, t_final=300.0)
    m = res.metrics
    port = res.runs.sel(side=-1)
    r_port = float(m["residual_yaw_rate"].sel(side=-1))
    assert r_port < -0.01  # rad/s, r' = r L/U about -0.13
    assert abs(float(m["residual_yaw_rate"].sel(side=1))) < 0.1 * abs(r_port)
    assert float(m["residual_gap"]) > 0.01
    # the end of the port run is a steady turn with zero rudder: accelerations ~ 0
    labels = MMG.state_labels
    x = np.array([float(port[k].values[-1]) for k in labels])
    u = [float(port["rudder_angle"].values[-1]), float(port["propeller_rps"].values[-1])]
    assert abs(u[0]) < 1e-9
    dx = MMG.derivative(0.0, x, u, KVLCC2_L7)
    assert abs(dx[labels.index("yaw_rate")]) < 1e-6  # [rad/s^2]; 35 deg turns start at ~1e-2
    assert abs(dx[labels.index("surge_speed")]) < 1e-4  # [m/s^2]; the speed settles last
    # it starts in the steady turn at +-20 deg
    r20 = steady_turn(KVLCC2_L7, [20 * DEG, -20 * DEG],
                      self_propulsion_rps(KVLCC2_L7, 1.179)).yaw_rate
    np.testing.assert_allclose(m["initial_yaw_rate"].values, r20, rtol=1e-12)


def test_pullout_mariner_returns_to_its_zero_rudder_turn():
    res = pull_out("mariner-nonlinear", 20 * DEG)
    m = res.metrics
    bias = steady_turn(MARINER_NONLINEAR, 0.0).yaw_rate  # the slow starboard turn at 0 rudder
    np.testing.assert_allclose(m["residual_yaw_rate"].values, [bias, bias], rtol=1e-3)
    assert abs(float(m["residual_gap"])) < 1e-3 * bias
    assert bool(m["settled"].all())


def test_reverse_spiral_kvlcc2_has_a_loop_mariner_none():
    kv = reverse_spiral("kvlcc2-l7", points=21).metrics
    mar = reverse_spiral("mariner-nonlinear", points=21).metrics
    width = math.degrees(float(kv["loop_width"]))
    assert 0.3 < width < 0.5
    assert float(kv["loop_rudder_low"]) == pytest.approx(0.0, abs=1e-9)  # the kink at r = 0
    assert float(mar["loop_width"]) == 0.0
    assert np.all(np.diff(mar["rudder_angle"].values) > 0)
    # every point is a steady turn of the model (independent check through the rhs)
    n = self_propulsion_rps(KVLCC2_L7, 1.179)
    for j in range(kv.sizes["point"]):
        r, d = float(kv["yaw_rate"][j]), float(kv["rudder_angle"][j])
        curve = rudder_for_yaw_rate(KVLCC2_L7, r, n)
        x = np.array([curve.surge_speed, curve.sway_speed, r, 0.0, 0.0, 0.0])
        acc = MMG.derivative(0.0, x, [d, n], KVLCC2_L7)[:3]
        assert np.max(np.abs(acc)) < 1e-9


def test_direct_spiral_legs_differ_inside_the_loop():
    program = np.array([5.0, 1.0, 0.0, -1.0, -5.0, -1.0, 0.0, 1.0, 5.0]) * DEG
    m = direct_spiral("kvlcc2-l7", program, hold=250.0).metrics
    r = m["yaw_rate"].values
    legs = m["leg"].values
    assert list(legs) == [-1, -1, -1, -1, -1, 1, 1, 1, 1]
    # at 0 deg: still turning to starboard coming down, to port coming up
    assert r[2] >= 0.0 > r[6]
    assert r[6] < -0.01
    # outside the loop both legs agree with the steady turn
    n = self_propulsion_rps(KVLCC2_L7, 1.179)
    r5 = steady_turn(KVLCC2_L7, [5 * DEG, -5 * DEG], n).yaw_rate
    np.testing.assert_allclose(r[[0, 8]], r5[0], rtol=1e-3)
    np.testing.assert_allclose(r[4], r5[1], rtol=1e-3)
    assert float(m["loop_width"]) > 0.0


def test_direct_spiral_mariner_has_no_loop():
    program = np.array([5.0, 0.0, -3.0, -5.0, -3.0, 0.0, 5.0]) * DEG
    m = direct_spiral("mariner-nonlinear", program).metrics
    r = m["yaw_rate"].values
    np.testing.assert_allclose(r[[1, 2]], r[[5, 4]], rtol=1e-3)  # same r both ways
    assert math.degrees(float(m["loop_width"])) < 1e-3
    assert bool(m["settled"].all())


# ------------------------------------------------------------------------------------------
# inputs
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("call, match", [
    (lambda: turning_circle("kvlcc2-l7", 40 * DEG),
     r"`rudder` must be in \(0, 0.610865\] \[rad\] in magnitude \(the steering gear limit of "
     r"'kvlcc2-l7', 35 deg\), got 0.698"),
    (lambda: turning_circle("kvlcc2-l7", 0.0), r"`rudder` must be in \(0,"),
    (lambda: turning_circle("kvlcc2-l7", speed=-1.0),
     r"`approach_speed` must be > 0 \[m/s\], got -1.0"),
    (lambda: turning_circle("kvlcc2-l7", rps=0.0), r"`rps` must be > 0 \[1/s\], got 0.0"),
    (lambda: turning_circle("kvlcc2-l7", speed=1.0, rps=10.0), r"not both"),
    (lambda: turning_circle("mariner-nonlinear", rps=2.0),
     r"`rps`: model 'mariner' has no propeller_rps input, got 2.0 \[1/s\]"),
    (lambda: turning_circle("mariner-nonlinear", speed=5.0),
     r"`speed` must be the nominal speed U_0 = 7.7175 \[m/s\]"),
    (lambda: turning_circle("kvlcc2-l7", sides=0), r"`sides` must be \+1 \(starboard\)"),
    (lambda: turning_circle("kvlcc2-l7", heading_change=1.0), r"`heading_change` must be >= pi"),
    (lambda: zigzag("kvlcc2-l7", 10 * DEG, 200 * DEG), r"`heading` trigger must be in \(0, pi\)"),
    (lambda: zigzag("kvlcc2-l7", [10 * DEG, 20 * DEG], [10 * DEG]), r"pairs"),
    (lambda: pull_out("kvlcc2-l7", 36 * DEG), r"`rudder` must be in \(0"),
    (lambda: direct_spiral("kvlcc2-l7", [0.1]), r"at least 2 angles"),
    (lambda: reverse_spiral("kvlcc2-l7", [0.0, -0.01, 0.01]), r"increasing"),
    (lambda: maneuver_ship(KVLCC2_L7.replace(R_0=0.03)),
     r"`servo`: no steering gear is known for this parameter set"),
    (lambda: maneuver_ship(3.0), r"`ship` must be a Ship, a catalog name, a ship file path or a "
                                 r"parameter set, got float"),
])
def test_bad_inputs_are_refused(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_unknown_catalog_entry_lists_the_valid_ones():
    with pytest.raises(ValueError, match=r"unknown catalog ship 'kvlcc3'; valid: .*kvlcc2-l7"):
        turning_circle("kvlcc3")


def test_maneuver_ship_and_time_step():
    s = maneuver_ship(KVLCC2_L7)  # equal to the catalog entry: its steering gear
    assert isinstance(s, Ship) and s.name == "kvlcc2-l7" and s.servo == KVLCC2_L7_SERVO
    assert maneuver_ship("mariner-nonlinear").servo == MARINER_SERVO
    assert default_time_step("kvlcc2-l7") == 0.05  # min(7/117.9, 0.1) -> 0.05
    assert default_time_step("mariner-nonlinear") == 0.2  # min(0.2085, 1) -> 0.2
    assert default_time_step("kvlcc2-full") == 0.2  # min(0.401, 0.676) -> 0.2


def _rows_one_by_one(metrics):
    """The metrics table row by row with xarray's isel (the reference for metrics_rows)."""
    import itertools

    batch = list(metrics["complete"].dims)
    rows = []
    for idx in itertools.product(*(range(metrics.sizes[d]) for d in batch)):
        sel = metrics.isel(dict(zip(batch, idx)))
        row = {str(k): c.item() for k, c in sel.coords.items() if c.ndim == 0}
        for name, var in sel.data_vars.items():
            if var.ndim == 0:
                row[str(name)] = var.item()
            elif var.ndim == 1:
                row.update({f"{name}_{k}": v for k, v in enumerate(var.values.tolist(), 1)})
        rows.append(row)
    return rows


@pytest.mark.parametrize("kind", ["turning", "zigzag"])
def test_metrics_rows_equal_the_rows_selected_one_by_one(kind):
    ships = [maneuver_ship(KVLCC2_L7.replace(N_r=n_r), servo=KVLCC2_L7_SERVO, name=f"s{k}")
             for k, n_r in enumerate((-0.049, -0.045, -0.053))]
    if kind == "turning":
        result = turning_circle(ships, np.array([20.0, 35.0]) * DEG, sides=(1, -1),
                                t_final=30.0)
    else:
        result = zigzag(ships, 10 * DEG, 10 * DEG, sides=(1, -1), t_final=60.0)
    got, want = metrics_rows(result.metrics), _rows_one_by_one(result.metrics)
    assert len(got) == len(want) == 3 * (4 if kind == "turning" else 2)
    for g, w in zip(got, want):
        assert list(g) == list(w)
        for key in w:
            if isinstance(w[key], float) and math.isnan(w[key]):
                assert math.isnan(g[key]), key
            else:
                assert g[key] == w[key] and type(g[key]) is type(w[key]), key


@pytest.mark.parametrize("ship", ["kvlcc2-l7", "kvlcc2-full", "mariner-nonlinear"])
def test_coarse_recording_measures_the_events_of_every_step_recording(ship):
    """Events interpolated by cubics: recording every L/(20 U0) (the default) gives the
    metrics of recording every step to 1e-6 of the ship length (distances; the times to 90
    and 180 deg to 1e-6 L/U0), every L/(5 U0) to 5e-5 (the end of the rudder's ramp is a
    kink the cubics smooth over); the default interval is the one stated."""
    from seahelm.analysis.maneuvers.turning_circle import SAMPLES_PER_LENGTH

    fine = turning_circle(ship, 35 * DEG, sides=1, record_dt=None)
    dt = fine.metrics.attrs["dt"]
    every = turning_circle(ship, 35 * DEG, sides=1, record_dt=dt).metrics
    length = float(every["length"])
    speed = float(every["approach_speed_value"])
    want = max(1, math.floor(length / speed / SAMPLES_PER_LENGTH / dt + 1e-9))
    assert fine.metrics.attrs["record_dt"] == pytest.approx(want * dt, rel=1e-12)
    coarse = turning_circle(ship, 35 * DEG, sides=1, record_dt=4 * want * dt).metrics
    for m, tol in ((fine.metrics, 1e-6), (coarse, 5e-5)):
        for key in ("advance", "transfer", "tactical_diameter", "distance_10"):
            assert float(m[key]) == pytest.approx(float(every[key]), abs=tol * length), key
        for key in ("time_90", "time_180"):
            assert float(m[key]) == pytest.approx(float(every[key]),
                                                  abs=tol * length / speed), key
        for key in ("steady_speed", "steady_yaw_rate", "final_heading_change"):
            assert float(m[key]) == pytest.approx(float(every[key]), rel=1e-12), key


def test_a_ship_without_a_steering_gear_is_told_a_way_that_works():
    """The manoeuvres take a ship, not a ``servo=``: the error of a ship without a steering
    gear names ``maneuver_ship(ship, servo=ServoParams(...))``, and that way works (it said
    "pass `servo=ServoParams(...)`", an argument ``turning_circle`` does not have)."""
    import inspect

    from seahelm.actuators.servo import ServoParams
    from seahelm.analysis.maneuvers import maneuver_ship as public_maneuver_ship

    with pytest.raises(ParameterError, match=r"`ship = maneuver_ship\(ship, servo=ServoParams"
                                             r"\(\.\.\.\)\)` \(from seahelm\.analysis\.maneuvers"
                                             r" and seahelm\.actuators\.servo\)") as info:
        turning_circle("mariner-nomoto1")
    assert "servo" not in inspect.signature(turning_circle).parameters
    assert "catalog ships with one: " in str(info.value)
    geared = public_maneuver_ship("mariner-nomoto1", servo=ServoParams())
    assert geared.steering_gear is not None and geared.model.name == "nomoto1"


def test_the_metrics_table_of_one_run_and_of_a_batch_as_a_dataframe():
    """``ManeuverResult.to_dataframe()``: one row per run, a single run's 0-dimensional table
    too (xarray's ``Dataset.to_dataframe`` refuses it), the values those of the Dataset."""
    one = turning_circle("kvlcc2-l7", sides=1)
    assert one.metrics.sizes == {}  # (what xarray cannot tabulate)
    frame = one.to_dataframe()
    assert frame.shape[0] == 1
    assert frame["tactical_diameter"].iloc[0] == float(one.metrics["tactical_diameter"])
    both = turning_circle("kvlcc2-l7")
    table = both.to_dataframe()
    assert list(table["side"]) == [int(s) for s in both.metrics["side"]]
    np.testing.assert_array_equal(table["advance"], both.metrics["advance"].values)
    assert table.loc[0, "tactical_diameter"] == frame.loc[0, "tactical_diameter"]
