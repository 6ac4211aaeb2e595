"""First-order wave motions inside the closed loop (seahelm.environment.first_order_in_loop):
the in-loop values are the post-pass's on the same recorded states (open and closed loop),
the controller sees ψ + ψ₁ when asked (its commands are those of a P law on heading_total),
off changes nothing bit for bit, a batch equals its runs one by one, bad requests are refused,
and a PID that sees the first-order yaw works its rudder, which the wave filter undoes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.environment import rao_io
from seahelm.environment.first_order import OUTPUT_NAMES
from seahelm.environment.first_order_in_loop import first_order_in_loop
from seahelm.environment.rao import closed_form_rao
from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.errors import ParameterError
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.problem import Problem
from seahelm.simulation.signals import Ramp

H3 = 4.0
WAVES_FROM = math.radians(135.0)


@pytest.fixture(scope="module")
def barge():
    return rao_io.read_rao(rao_io.box_barge_database())


@pytest.fixture(scope="module")
def sea():
    return spectrum_from_wave_height("rakhmanin-firsov-2", H3)


@pytest.fixture(scope="module")
def mariner():
    ship = get_ship("mariner-nonlinear")
    start = approach_state(ship, trim=True)
    return ship, dict(ship=ship, x0=start.state, actuator_x0=[start.inputs["rudder_angle"]],
                      dt=0.1)


def _check_against_post_pass(fo, res):
    """Every in-loop DOF equals the post-pass on the recorded north, east, heading, speed."""
    post = fo.post_pass(res)
    for dof in fo.dofs:
        np.testing.assert_allclose(res[OUTPUT_NAMES[dof]], post[dof], rtol=0, atol=1e-9)
        assert np.abs(post[dof]).max() > 1e-3  # (something to compare)
    if "yaw" in fo.dofs:
        np.testing.assert_allclose(res["heading_total"], res["heading"] + post["yaw"],
                                   rtol=0, atol=1e-9)


def test_a_full_turn_equals_the_post_pass(mariner, barge, sea):
    """A turn through more than a full circle (the relative wave heading goes round the table)
    in a short-crested sea (cos-2s, one direction per component: the general path), the box
    barge's panel-method RAOs with yaw: the PID of :func:`test_off_changes_nothing_bit_for_bit`
    (which sees ψ) following a heading ramp of 8 rad in 660 s, its rudder at the stop most of
    the way. (The kernel of that test: the turn was an open-loop 15° rudder, a combination
    only this test compiled; the open loop with the motions in it is the container's below.)"""
    ship, kw = mariner
    fo = first_order_in_loop(sea, barge, wave_direction=WAVES_FROM, runs=2, seed=4,
                             spreading="cos-2s", spreading_parameter=4.0)
    gains = PIDHeadingParams(kp=2.0, ki=0.0, kd=20.0, max_command=ship.max_rudder)
    res = simulate(**kw, t_final=660.0, controller=PID_HEADING, controller_params=gains,
                   controller_dt=0.5, reference={"heading": Ramp(0.0, 660.0, 0.0, 8.0)},
                   first_order=fo)
    assert np.all(res.status == 0)
    assert np.all(np.ptp(res["heading"], axis=1) > 2 * math.pi)  # a full turn and more
    assert res.metadata["controller_heading"] == "heading"
    _check_against_post_pass(fo, res)


def test_speed_interpolation_and_model_roll(sea):
    """The 4-DOF container (it rolls) turning at decreasing speed, with closed-form RAOs at
    three speeds (interpolated in u, long-crested: the fast path): the in-loop values equal the
    post-pass, and ``roll`` is the model's roll angle plus the first-order roll."""
    ship = get_ship("son-nomoto-container")
    start = approach_state(ship, trim=True)
    u0 = float(start.state[0])
    raos = [closed_form_rao(ship, s) for s in (0.6 * u0, 0.8 * u0, u0)]
    fo = first_order_in_loop(sea, raos, wave_direction=WAVES_FROM, runs=1, seed=9)
    assert fo.dofs == ("heave", "roll", "pitch")
    res = simulate(ship=ship, x0=start.state, actuator_x0=[start.inputs["rudder_angle"]],
                   dt=0.1, t_final=200.0, first_order=fo,
                   reference={"rudder_command": math.radians(20.0),
                              "propeller_rps": start.inputs["propeller_rps"]})
    assert np.all(res.status == 0)
    assert res["surge_speed"].min() < 0.85 * u0  # the speed falls through the tables
    _check_against_post_pass(fo, res)
    np.testing.assert_array_equal(res["roll"], res["roll_angle"] + res["roll_wave"])


def test_closed_loop_equals_the_post_pass_and_the_autopilot_sees_the_total(mariner, barge,
                                                                          sea):
    """A P autopilot (K_p = 2, no I, no D) that sees ψ + ψ₁: at every sample its command is
    −K_p·wrap(heading_total) (clipped), computed here from the recorded heading_total, and
    not −K_p·heading; and the in-loop values equal the post-pass on the closed-loop track."""
    ship, kw = mariner
    fo = first_order_in_loop(sea, barge, wave_direction=WAVES_FROM, runs=2, seed=3,
                             autopilot_sees_first_order=True)
    gains = PIDHeadingParams(kp=2.0, ki=0.0, kd=0.0, max_command=ship.max_rudder)
    res = simulate(**kw, t_final=200.0, controller=PID_HEADING, controller_params=gains,
                   controller_dt=0.5, reference={"heading": 0.0}, first_order=fo)
    assert np.all(res.status == 0)
    assert res.metadata["controller_heading"].startswith("heading_total")
    _check_against_post_pass(fo, res)
    k = np.arange(0, res.time.size - 1, 5)  # the controller's samples (0.5 s / 0.1 s)
    seen = res["heading_total"][:, k]
    wrapped = (seen + math.pi) % (2 * math.pi) - math.pi
    expected = np.clip(-2.0 * wrapped, -ship.max_rudder, ship.max_rudder)
    np.testing.assert_allclose(res["rudder_command"][:, k], expected, rtol=0, atol=1e-12)
    lf_only = np.clip(-2.0 * res["heading"][:, k], -ship.max_rudder, ship.max_rudder)
    assert np.abs(res["rudder_command"][:, k] - lf_only).max() > 0.01  # ψ₁ is seen


def test_off_changes_nothing_bit_for_bit(mariner, barge, sea):
    """Motions as outputs only (the autopilot sees ψ) leave states, commands and the model's
    outputs exactly as without them (the stage writes outputs only). (Against the engine
    before the stage existed the no-waves results are bit-for-bit equal too: measured on the
    Mariner, the 4-DOF container and the KVLCC2.)"""
    ship, kw = mariner
    gains = PIDHeadingParams(kp=2.0, ki=0.01, kd=20.0, max_command=ship.max_rudder)
    common = dict(**kw, t_final=100.0, controller=PID_HEADING, controller_params=gains,
                  controller_dt=0.5, reference={"heading": 0.2})
    off = simulate(**common)
    fo = first_order_in_loop(sea, barge, wave_direction=WAVES_FROM, runs=1, seed=1)
    on = simulate(**common, first_order=fo)
    np.testing.assert_array_equal(on.state, off.state)
    np.testing.assert_array_equal(on.command, off.command)
    n = off.output.shape[-1]
    np.testing.assert_array_equal(on.output[..., :n], off.output)
    assert on.output_labels[:n] == off.output_labels
    assert "first_order_in_loop" not in off.metadata and "first_order_in_loop" in on.metadata


def test_a_batch_equals_its_runs_one_by_one(mariner, barge, sea):
    """Three runs seeded from SeedSequence(11) against run i alone seeded with child i."""
    ship, kw = mariner
    gains = PIDHeadingParams(kp=2.0, ki=0.0, kd=20.0, max_command=ship.max_rudder)
    common = dict(**kw, t_final=100.0, controller=PID_HEADING, controller_params=gains,
                  controller_dt=0.5, reference={"heading": 0.0})
    batch = simulate(**common, first_order=first_order_in_loop(
        sea, barge, wave_direction=WAVES_FROM, runs=3, seed=11, spreading="cos-2s",
        autopilot_sees_first_order=True))
    children = np.random.SeedSequence(11).spawn(3)
    for i in range(3):
        one = simulate(**common, first_order=first_order_in_loop(
            sea, barge, wave_direction=WAVES_FROM, runs=1, seed=[children[i]],
            spreading="cos-2s", autopilot_sees_first_order=True))
        np.testing.assert_array_equal(one.output[0], batch.output[i])
        np.testing.assert_array_equal(one.state[0], batch.state[i])


def test_refusals(mariner, barge, sea):
    ship, kw = mariner
    closed = closed_form_rao(ship, 7.0)
    with pytest.raises(ParameterError, match=r"autopilot_sees_first_order.*no yaw.*capytaine"):
        first_order_in_loop(sea, closed, wave_direction=0.0, autopilot_sees_first_order=True)
    with pytest.raises(ParameterError, match=r"`dofs` must include 'yaw'"):
        first_order_in_loop(sea, barge, wave_direction=0.0, dofs=("heave",),
                            autopilot_sees_first_order=True)
    with pytest.raises(ParameterError, match="autopilot_sees_first_order"):
        first_order_in_loop(sea, barge, wave_direction=0.0, autopilot_sees_first_order="yes")
    fo = first_order_in_loop(sea, barge, wave_direction=0.0, runs=2,
                             autopilot_sees_first_order=True)
    with pytest.raises(ParameterError, match=r"does not measure `heading`"):
        Problem(**kw, t_final=10.0, first_order=fo)  # open loop: no heading measured
    with pytest.raises(ParameterError, match="must be a FirstOrderInLoop"):
        Problem(**kw, t_final=10.0, first_order="yes")
    with pytest.raises(ParameterError, match=r"`first_order` has 2 runs"):
        simulate(**kw, t_final=10.0, first_order=first_order_in_loop(
            sea, barge, wave_direction=0.0, runs=2), params=[ship.params] * 3)
    with pytest.raises(ParameterError, match=r"drawn for 1 run\(s\), the batch has 3"):
        simulate(**kw, t_final=10.0, first_order=first_order_in_loop(
            sea, barge, wave_direction=0.0, runs=1), params=[ship.params] * 3)


@pytest.mark.slow
def test_an_autopilot_that_sees_the_first_order_yaw_works_its_rudder(mariner, barge):
    """The Mariner holding course 0 in a sea of h3% = 6 m from 135° (the box barge's yaw RAO:
    ψ₁ of 0.73° standard deviation; no wave loads, so the low-frequency heading is nearly
    still), 4 runs of 2,000 s, statistics after 500 s. A PID of bandwidth 0.05 rad/s that sees
    ψ does not move the rudder; seeing ψ + ψ₁ its rudder rate is 0.69°/s RMS; the wave filter
    (designed for the sea's shaping filter) in front of a PID of bandwidth 0.07 rad/s brings it
    back to 0.068°/s at a low-frequency heading error no larger (measured 0.0093° against
    0.0053°, low-passed at 0.1 rad/s)."""
    from scipy import signal

    from seahelm.control.autopilot_design import pid_pole_placement
    from seahelm.control.wave_filter import design_wave_filter, wave_filtered
    from seahelm.environment.shaping import shaping_filter
    from seahelm.environment.wave_yaw import wave_yaw_filter

    ship, kw = mariner
    K, T = 0.1848, 107.2
    sea6 = spectrum_from_wave_height("rakhmanin-firsov-2", 6.0)
    plain = pid_pole_placement(K, T, bandwidth=0.05, max_command=ship.max_rudder).params
    faster = pid_pole_placement(K, T, bandwidth=0.07, max_command=ship.max_rudder).params
    wave = wave_yaw_filter(shaping_filter(sea6), gain=K, time_constant=T,
                           rudder_per_slope=10.0)
    filtered = wave_filtered(PID_HEADING, design_wave_filter(
        K, T, wave, 0.5, measurement_std=math.radians(0.05)))
    dt, k0 = kw["dt"], int(500 / kw["dt"])
    b, a = signal.butter(4, 0.1 / (math.pi / dt))
    stats = {}
    for name, sees, ctl, gains in (("lf", False, PID_HEADING, plain),
                                   ("total", True, PID_HEADING, plain),
                                   ("filtered", True, filtered, faster)):
        fo = first_order_in_loop(sea6, barge, wave_direction=WAVES_FROM, runs=4, seed=5,
                                 autopilot_sees_first_order=sees)
        res = simulate(**kw, t_final=2000.0, controller=ctl, controller_params=gains,
                       controller_dt=0.5, reference={"heading": 0.0}, first_order=fo)
        assert np.all(res.status == 0)
        delta = res["rudder_angle"]
        stats[name] = (
            math.degrees(np.sqrt(np.mean((np.diff(delta, axis=1)[:, k0:] / dt) ** 2))),
            math.degrees(np.sqrt(np.mean(signal.filtfilt(b, a, res["heading"], axis=1)[
                :, k0:] ** 2))),
            math.degrees(res["yaw_wave"][:, k0:].std()))
    assert stats["total"][2] == pytest.approx(0.73, abs=0.05)
    assert stats["lf"][0] < 1e-3
    assert stats["total"][0] == pytest.approx(0.69, rel=0.05)
    assert stats["filtered"][0] < stats["total"][0] / 5
    assert stats["filtered"][1] <= 1.2 * stats["total"][1]


@pytest.mark.parametrize("kwargs, field, match", [
    ({"rao": None}, "rao", "must be an RAO or a sequence of RAOs at increasing speeds, got "
                           "NoneType"),
    ({"dofs": []}, "dofs", r"must be a non-empty sequence of degrees of freedom, got \[\]"),
    ({"dofs": "heave"}, "dofs", "must be a non-empty sequence of degrees of freedom, got "
                                "'heave'"),
])
def test_bad_rao_or_dofs_are_parameter_errors_in_the_loop_and_after_it(barge, sea, kwargs,
                                                                       field, match):
    """(rao=None was a bare TypeError, dofs=[] an IndexError, dofs='heave' "has no 'h'"), in
    first_order_in_loop and in the post-pass first_order_motions, which share the check."""
    from seahelm.environment.first_order import first_order_motions

    args = {"rao": barge, **kwargs}
    with pytest.raises(ParameterError, match=match) as info:
        first_order_in_loop(sea, args.pop("rao"), wave_direction=0.0, runs=1, **args)
    assert info.value.field == field
    record = {"time": np.arange(3.0), **{k: np.zeros((1, 3)) for k in (
        "north", "east", "heading")}, "surge_speed": np.ones((1, 3))}
    args = {"rao": barge, **kwargs}
    with pytest.raises(ParameterError, match=match):
        first_order_motions(record, sea, args.pop("rao"), wave_direction=0.0, **args)
