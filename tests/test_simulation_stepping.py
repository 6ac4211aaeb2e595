"""Stepping a batch from outside (seahelm.simulation.stepping.Simulator): one controller
interval at a time over the whole horizon gives ``simulate(problem)``'s trajectories bit for bit
for every registered vessel model (and with the environment's loads, and with first-order wave
motions in the loop); external commands by name equal an open-loop schedule; a coupling hook
sees the outputs and writes the next commands and disturbances; bad input is one
ParameterError that changes no state; a diverged run is refused alone.

The cases are those of tests/test_simulation_pure_python.py (the compiled combinations other
tests compile too: the stepped loop is the same compiled module)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm import Problem, Simulator, simulate
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError, SimulationDiverged
from seahelm.registry import VESSEL_MODELS, get_model
from seahelm.simulation.engine import RunStatus
from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

from test_simulation_pure_python import CASES, _environment_case


def _problem(name: str, **kw) -> Problem:
    case = CASES[name]()
    return Problem(model=get_model(name), **case, **kw)


def _stepped(problem: Problem, **kw):
    with Simulator(problem, **kw) as sim:
        sim.reset()
        for _ in range(sim.n_intervals):
            sim.step()
        assert (sim.time == problem.t_final).all() or (sim.status != 0).any()
        return sim.result()


def assert_bit_for_bit(stepped, whole) -> None:
    np.testing.assert_array_equal(stepped.status, whole.status)
    np.testing.assert_array_equal(stepped.time, whole.time)
    for what in ("state", "output", "command", "reference", "disturbance"):
        a, b = getattr(stepped, what), getattr(whole, what)
        assert a.shape == b.shape, what
        assert np.array_equal(a, b, equal_nan=True), what  # bit for bit
        assert np.isfinite(b).all(), what


@pytest.mark.parametrize("name", list(VESSEL_MODELS))
def test_stepping_each_interval_equals_simulate_bit_for_bit(name):
    problem = _problem(name)
    whole = simulate(problem)
    assert_bit_for_bit(_stepped(problem), whole)
    assert np.ptp(whole.state[:, -1], axis=0).max() > 0  # (two runs that differ)


def test_stepping_with_wind_and_waves_equals_simulate():
    problem = _problem("mmg", **_environment_case())
    whole = simulate(problem)
    assert np.abs(whole.output[:, 1:, len(get_model("mmg").output_labels):]).max() > 0
    assert_bit_for_bit(_stepped(problem), whole)


def test_stepping_with_first_order_motions_in_the_loop_equals_simulate():
    from seahelm.analysis.equilibria.equilibrium import approach_state
    from seahelm.control.pid import PID_HEADING, PIDHeadingParams
    from seahelm.environment import rao_io
    from seahelm.environment.first_order_in_loop import first_order_in_loop
    from seahelm.environment.spectra import spectrum_from_wave_height
    from seahelm.ships import get_ship

    ship = get_ship("mariner-nonlinear")
    start = approach_state(ship, trim=True)
    fo = first_order_in_loop(spectrum_from_wave_height("rakhmanin-firsov-2", 4.0),
                             rao_io.read_rao(rao_io.box_barge_database()),
                             wave_direction=math.radians(135.0), runs=2, seed=4,
                             autopilot_sees_first_order=True)
    problem = Problem(ship=ship, x0=start.state, actuator_x0=[start.inputs["rudder_angle"]],
                      dt=0.1, t_final=30.0, controller=PID_HEADING, controller_dt=1.0,
                      controller_params=PIDHeadingParams(kp=2.0, ki=0.0, kd=20.0),
                      reference={"heading": 0.2}, first_order=fo)
    whole = simulate(problem)
    assert np.abs(whole["heading_total"] - whole["heading"]).max() > 1e-4
    assert_bit_for_bit(_stepped(problem), whole)


def test_stepping_several_intervals_and_a_short_last_interval():
    """n intervals at once, and a horizon that is no multiple of the controller period."""
    problem = _problem("nomoto2").replace(t_final=10.5, disturbance=None)
    whole = simulate(problem)
    with Simulator(problem) as sim:
        sim.reset()
        sim.step(n=3)
        obs = sim.step(n=10)  # runs to the end of the horizon (8 intervals), not past it
        np.testing.assert_array_equal(obs.time, [10.5, 10.5])
        assert_bit_for_bit(sim.result(), whole)
        with pytest.raises(ParameterError, match="end of the horizon") as err:
            sim.step(runs=[1])
        assert err.value.field == "runs"


def _nomoto1(**kw) -> Problem:
    return Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0, speed=5.0),
                   x0=np.array([[0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.3, 0.0]]), t_final=20.0,
                   dt=0.1, controller_dt=1.0, **kw)


def test_external_commands_by_name_equal_an_open_loop_schedule():
    """Commands given at every interval (the rudder angle of a zigzag-like schedule) make the
    trajectories of the same schedule given as the open-loop reference."""
    times = np.arange(201) * 0.1
    schedule = 0.1 * np.sign(np.sin(2 * np.pi * np.floor(times) / 8.0) + 1e-9)
    whole = simulate(_nomoto1(controller=OPEN_LOOP, reference=schedule[:, None]))
    problem = _nomoto1()
    with Simulator(problem) as sim:
        assert sim.command_labels == whole.command_labels
        obs = sim.reset()
        assert set(obs) >= {"heading", "yaw_rate"}
        for q in range(20):
            obs = sim.step({sim.command_labels[0]: schedule[10 * q]})
        res = sim.result()
    assert np.array_equal(res.state, whole.state)
    np.testing.assert_array_equal(obs["heading"], whole["heading"][:, -1])
    np.testing.assert_allclose(obs.values, whole.output[:, -1], rtol=0, atol=1e-15)


def test_selected_runs_step_alone_and_a_reset_run_starts_again():
    problem = _nomoto1()
    with Simulator(problem) as sim:
        sim.reset()
        sim.step([0.1], n=5)
        obs = sim.step([[0.2]], runs=[1])  # run 1 alone: one row of commands
        np.testing.assert_array_equal(obs.time, [5.0, 6.0])
        before = sim.state(0)
        sim.reset(runs=[0])
        np.testing.assert_array_equal(sim.time, [0.0, 6.0])
        assert sim.state(0) != before and sim.state(0)["heading"] == 0.0
        obs = sim.step([[0.0], [0.0]])  # each run one interval on from its own time
        np.testing.assert_array_equal(obs.time, [1.0, 7.0])


def test_state_and_set_state():
    problem = _nomoto1()
    with Simulator(problem) as sim:
        sim.reset()
        sim.step([0.1], n=3)
        state = sim.state(1)
        assert list(state) == list(sim.state_labels)
        sim.set_state(1, {"heading": 1.0})
        assert sim.state(1)["heading"] == 1.0
        assert sim.state(1)["yaw_rate"] == state["yaw_rate"]
        obs = sim.step([0.0])
        assert abs(obs["heading"][1] - 1.0) < 0.1  # it went on from there
        with pytest.raises(ParameterError, match="unknown state 'heeding'"):
            sim.set_state(0, {"heeding": 1.0})
        with pytest.raises(ParameterError, match="shape"):
            sim.set_state(0, [1.0, 2.0])
        with pytest.raises(ParameterError, match="not finite"):
            sim.set_state(0, {"heading": math.nan})


def test_coupling_hook_reads_outputs_and_writes_the_next_commands():
    """A P law on heading written by the hook between intervals gives the trajectories of
    the same law computed by the caller from each step's outputs (bit for bit): the hook is
    called after every interval but the last of a step, with the outputs at that time."""
    kp, target = 2.0, 0.2

    def law(heading):
        return np.clip(kp * (target - heading), -0.5, 0.5)[:, None]

    with Simulator(_nomoto1()) as sim:  # the caller's loop
        obs = sim.reset()
        for _ in range(20):
            obs = sim.step(law(obs["heading"]))
        by_hand = sim.result()
    calls = []

    def hook(time, outputs, commands, disturbance):
        calls.append(time.copy())
        assert not outputs.flags.writeable
        commands[:] = law(outputs[:, sim.output_labels.index("heading")])

    sim = Simulator(_nomoto1(), coupling=hook)
    obs = sim.reset()
    sim.step(law(obs["heading"]), n=20)
    res = sim.result()
    sim.close()
    assert len(calls) == 19 and calls[0].tolist() == [1.0, 1.0]
    assert np.ptp(res["heading"]) > 0.1
    assert np.array_equal(res.state, by_hand.state)
    assert np.array_equal(res.command, by_hand.command)


def test_coupling_hook_writes_disturbances_held_over_the_next_interval():
    from seahelm.vessels.nomoto import NOMOTO2, Nomoto2Params

    params = Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7)
    base = dict(model=NOMOTO2, params=params, x0=np.zeros((2, 5)), t_final=10.0, dt=0.5,
                controller=OPEN_LOOP, controller_dt=1.0, reference=np.zeros((2, 1, 1)))
    push = np.zeros((2, 1, 4))
    push[:, 0, 0] = [0.01, 0.02]
    # the disturbance the hook writes from t = 1 s on, given from t = 1 s on in the problem
    series = np.zeros((2, 21, 4))
    series[:, 2:, 0] = push[:, 0, 0][:, None]
    series[:, 1, 0] = 0.0
    whole = simulate(Problem(**base, disturbance=series))

    def hook(time, outputs, commands, disturbance):
        assert commands is None  # the controller's commands this step
        disturbance[:, 0] = push[:, 0, 0]

    with Simulator(Problem(**base, disturbance=np.zeros((2, 1, 4))), coupling=hook) as sim:
        sim.reset()
        sim.step(n=10)
        res = sim.result()
    # the held value acts from the interval after the first; the recorded disturbance is the
    # problem's (zeros)
    assert np.abs(res.state[:, -1] - whole.state[:, -1]).max() < 0.05 * np.abs(
        whole.state[:, -1]).max()
    assert np.abs(res.state[:, -1, 2]).max() > 0
    assert (res.disturbance == 0).all()


def test_bad_input_is_one_parameter_error_and_changes_nothing():
    problem = _nomoto1()
    sim = Simulator(problem)
    with pytest.raises(ParameterError, match="reset") as err:
        sim.step()
    assert err.value.field == "reset"
    sim.reset()
    sim.step([0.1])
    z, t = sim.state(0), sim.time.copy()
    bad = [
        (dict(commands=[[0.1, 0.2]]), "commands", r"shape \(2, 1\)"),
        (dict(commands=[math.nan]), "commands", "must be finite"),
        (dict(commands={"rudder": 0.1}), "commands", "unknown command 'rudder'"),
        (dict(runs=[2]), "runs", r"-2 \.\.\. 1 \(negative: from the end, as numpy\), got 2"),
        (dict(runs=[-3]), "runs", "got -3"),  # (-1 is the last run, as numpy)
        (dict(n=0), "n", "integer >= 1"),
        (dict(commands=[[0.1]], runs=[0, 1]), "commands", r"\(2, 1\)"),
    ]
    for kwargs, field, message in bad:
        with pytest.raises(ParameterError, match=message) as err:
            sim.step(**kwargs)
        assert err.value.field == field, kwargs
    assert sim.state(0) == z and (sim.time == t).all()
    obs = sim.step([0.1])  # still usable
    np.testing.assert_array_equal(obs.time, [2.0, 2.0])
    sim.close()


@pytest.mark.parametrize("mischief", ["raise", "nan"])
def test_a_coupling_hook_that_fails_changes_no_state(mischief):
    def hook(time, outputs, commands, disturbance):
        if time[0] >= 3.0:
            if mischief == "raise":
                raise RuntimeError("sensor offline")
            commands[1, 0] = math.nan

    sim = Simulator(_nomoto1(), coupling=hook)
    sim.reset()
    sim.step([0.1], n=2)
    before = (sim.state(0), sim.state(1), sim.time.copy())
    with pytest.raises(ParameterError, match="sensor offline" if mischief == "raise"
                       else "wrote nan to commands 'rudder_command' of run 1") as err:
        sim.step([0.1], n=4)
    assert err.value.field == "coupling"
    assert (sim.state(0), sim.state(1)) == before[:2] and (sim.time == before[2]).all()
    rec = sim.result()
    assert np.isnan(rec.state[:, 20:]).all() and np.isfinite(rec.state[:, :20]).all()
    sim.coupling = None
    np.testing.assert_array_equal(sim.step([0.1]).time, [3.0, 3.0])
    sim.close()


def test_a_diverged_run_is_reported_and_refused_alone():
    """Run 1 leaves its bounds; run 0 goes on."""
    problem = _nomoto1(bounds={"heading": (-0.5, 0.5)})
    with Simulator(problem) as sim:
        sim.reset()
        obs = sim.step([[0.0], [0.6]], n=20)
        assert obs.status.tolist() == [RunStatus.OK, RunStatus.OUT_OF_BOUNDS]
        assert "run 1 diverged at t = " in sim.failure(1) and sim.failure(0) is None
        with pytest.raises(ParameterError, match="run 1 has stopped") as err:
            sim.step([0.0], runs=[1])
        assert err.value.field == "runs"
        sim.reset(runs=[0])
        assert sim.step([[0.0]], runs=[0]).time[0] == 1.0  # run 0 alone is fine
    with Simulator(problem, throw=True) as sim:
        sim.reset()
        with pytest.raises(SimulationDiverged, match="run 1 diverged"):
            sim.step([[0.0], [0.6]], n=20)


def test_the_engine_page_example_runs(capsys):
    """docs/guide/engine.rst's stepping example: four runs steered to four headings."""
    from pathlib import Path

    page = (Path(__file__).parents[1] / "docs" / "guide" / "engine.rst").read_text()
    section = page[page.index("Stepping the batch from outside"):]
    lines = section[section.index(".. code-block:: python"):].splitlines()[2:]
    end = next(i for i, line in enumerate(lines) if line and not line.startswith("    "))
    code = "\n".join(line[4:] for line in lines[:end])
    exec(compile(code, "engine.rst", "exec"), {})
    printed = capsys.readouterr().out
    headings = [float(v) for v in printed[printed.index("[") + 1:printed.index("]")].split()]
    np.testing.assert_allclose(headings, [5.0, 10.0, 15.0, 20.0], atol=1.0)
    assert "(4, 1201, 7)" in printed  # (every 0.1 s step recorded)


def test_the_keyword_form_of_simulate_takes_problems_fields():
    """simulate's keywords are Problem's fields (its layout aside) and the two run options:
    the keyword form passes them on by name, from that list."""
    import dataclasses
    import inspect

    from seahelm.simulation.engine import simulate as engine_simulate

    keywords = set(inspect.signature(engine_simulate).parameters) - {"throw", "progress"}
    assert keywords == {f.name for f in dataclasses.fields(Problem)} - {"layout"}
    problem = _nomoto1(record_every=5, seed=3, metadata={"who": "test"})
    kwargs = problem.simulate_kwargs()
    res = simulate(kwargs.pop("model"), **kwargs)
    assert res.metadata["seed"] == 3 and res.metadata["who"] == "test"
    assert np.array_equal(res.state, simulate(problem).state) and res.time.size == 41
