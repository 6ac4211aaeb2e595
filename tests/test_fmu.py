"""seahelm fmu: the FMU is a valid FMI 2.0 co-simulation unit with units and start values; run
by fmpy (its own master loop, and simulate_fmu) it gives simulate()'s trajectories of the same
problem to 1e-9; a ship without a steering gear is refused by name; fmpy setting an unknown
parameter, and a step that cannot be made, give clear errors."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
import fmpy.fmi2  # noqa: E402
pytest.importorskip("pythonfmu")

from typer.testing import CliRunner  # noqa: E402

from seahelm import Problem, get_ship, simulate  # noqa: E402
from seahelm.analysis.equilibria.equilibrium import approach_state  # noqa: E402
from seahelm.cli.main import app  # noqa: E402
from seahelm.errors import ParameterError  # noqa: E402
from seahelm.fmu import build_fmu  # noqa: E402

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
OUTPUTS = ("north", "east", "heading", "surge_speed", "sway_speed", "speed", "yaw_rate",
           "rudder_angle")


@pytest.fixture(scope="module")
def kv_fmu(tmp_path_factory) -> Path:
    return build_fmu("kvlcc2-l7", tmp_path_factory.mktemp("fmu") / "kv.fmu")


def test_the_model_description_has_units_starts_and_validates(kv_fmu):
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(kv_fmu)) == []
    md = fmpy.read_model_description(str(kv_fmu))
    assert md.fmiVersion == "2.0" and md.coSimulation is not None
    v = {x.name: x for x in md.modelVariables}
    n0 = approach_state(get_ship("kvlcc2-l7"), trim=True).inputs["propeller_rps"]
    assert (v["rudder_command"].causality, v["rudder_command"].unit) == ("input", "rad")
    assert v["propeller_rps"].unit == "1/s"
    assert float(v["propeller_rps"].start) == pytest.approx(n0, rel=1e-15)  # (16 digits)
    for name, unit in (("north", "m"), ("east", "m"), ("heading", "rad"),
                       ("surge_speed", "m/s"), ("sway_speed", "m/s"), ("yaw_rate", "rad/s"),
                       ("speed", "m/s"), ("rudder_angle", "rad")):
        assert (v[name].causality, v[name].unit) == ("output", unit), name
        assert v[name].start is not None, name
    assert float(v["surge_speed"].start) == 1.179  # the approach
    params = {n for n, x in v.items() if x.causality == "parameter"}
    assert params == {"initial_north", "initial_east", "initial_heading", "integration_step",
                      "wind_speed", "wind_direction"}
    assert {u.name for u in md.unitDefinitions} >= {"m", "rad", "m/s", "rad/s", "1/s", "s"}
    with zipfile.ZipFile(kv_fmu) as z:
        assert "resources/ship.toml" in z.namelist()  # the ship's data travel with it


def _fmpy_loop(path: Path, rudder: np.ndarray, rps: np.ndarray, **parameters) -> dict:
    """fmpy as the master: one doStep of 1 s per command, the outputs after each."""
    md = fmpy.read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzipped = fmpy.extract(str(path))
    fmu = fmpy.fmi2.FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                              modelIdentifier=md.coSimulation.modelIdentifier,
                              instanceName="kv")
    fmu.instantiate()
    try:
        fmu.setupExperiment(startTime=0.0, stopTime=float(rudder.size))
        fmu.enterInitializationMode()
        for name, value in parameters.items():
            fmu.setReal([vr[name]], [value])
        fmu.exitInitializationMode()
        out_vr = [vr[n] for n in OUTPUTS]
        rows = [fmu.getReal(out_vr)]
        for k in range(rudder.size):
            fmu.setReal([vr["rudder_command"], vr["propeller_rps"]], [rudder[k], rps[k]])
            fmu.doStep(currentCommunicationPoint=float(k), communicationStepSize=1.0)
            rows.append(fmu.getReal(out_vr))
        fmu.terminate()
    finally:
        fmu.freeInstance()
    return dict(zip(OUTPUTS, np.array(rows).T))


def test_fmpy_run_equals_simulate_of_the_same_problem(kv_fmu):
    ship = get_ship("kvlcc2-l7")
    start = approach_state(ship, trim=True)
    n0 = start.inputs["propeller_rps"]
    t_final = 40
    rudder = np.radians(np.where(np.arange(t_final) < 15, 20.0, -35.0))
    rps = np.where(np.arange(t_final) < 25, n0, 0.8 * n0)
    x0 = start.state.copy()
    labels = list(ship.model.state_labels)
    x0[labels.index("heading")], x0[labels.index("north")], x0[labels.index("east")] = \
        0.4, 5.0, -3.0
    steps_per_s = 10
    reference = np.stack([np.repeat(np.append(rudder, rudder[-1]), steps_per_s)[:t_final * 10 + 1],
                          np.repeat(np.append(rps, rps[-1]), steps_per_s)[:t_final * 10 + 1]],
                         axis=1)
    res = simulate(Problem(ship=ship, x0=x0, actuator_x0=[start.inputs["rudder_angle"]],
                           t_final=float(t_final), dt=0.1, controller_dt=0.1,
                           reference=reference, record_every=10))
    got = _fmpy_loop(kv_fmu, rudder, rps, initial_heading=0.4, initial_north=5.0,
                     initial_east=-3.0)
    for name in OUTPUTS:
        if name == "rudder_angle":
            expected = res.state[0, :, list(res.state_labels).index(name)]
        else:
            expected = res.output[0, :, list(res.output_labels).index(name)]
        np.testing.assert_allclose(got[name], expected, rtol=0, atol=1e-9, err_msg=name)
    assert abs(got["heading"][-1] - got["heading"][15]) > 0.3  # (it turned, both ways)
    assert got["surge_speed"][-1] < 0.9  # (slower on 0.8 n0 and the turns)


def test_the_example_runs_fmpy_simulate_fmu_and_draws_the_comparison(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLES / "fmu_fmpy.py"), str(tmp_path)],
                          capture_output=True, text=True, timeout=600,
                          env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    m = re.search(r"largest difference ([\d.e+-]+) \(SI units\)", proc.stdout)
    assert m and float(m.group(1)) <= 1e-9, proc.stdout
    assert (tmp_path / "fmu_fmpy.png").stat().st_size > 20_000


_IN_PROCESS = """
import gc, sys
import fmpy
from seahelm.fmu import build_fmu
path = build_fmu("kvlcc2-l7", sys.argv[1])
for _ in range(2):
    fmpy.simulate_fmu(str(path), stop_time=2.0, step_size=1.0)
module = sys.modules["seahelm_kvlcc2_l7"]
junk = [dict(a=i) for i in range(100_000)]
gc.collect()
print(module.__name__, sorted(k for k in vars(module) if not k.startswith("__")))
"""


def test_a_master_in_the_same_process_leaves_the_slave_module_whole(tmp_path):
    # pythonfmu 0.7's wrapper released the slave module's namespace once too often per
    # instance: the module's dictionary was freed (then `<module '?'>`, a segfault at a later
    # garbage collection) -- seahelm.fmu.slave.hold_namespace
    proc = subprocess.run([sys.executable, "-c", _IN_PROCESS, str(tmp_path / "kv.fmu")],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.strip().endswith(
        "seahelm_kvlcc2_l7 ['ShipSlave', 'hold_namespace', 'seahelm_kvlcc2_l7']"), proc.stdout


def test_an_unknown_parameter_is_named_by_fmpy(kv_fmu):
    with pytest.raises(Exception, match="could not be set: initial_headng"):
        fmpy.simulate_fmu(str(kv_fmu), stop_time=1.0, step_size=1.0,
                          start_values={"initial_headng": 0.5})


def test_a_step_that_cannot_be_made_fails_with_its_reason(kv_fmu):
    messages = []
    res = fmpy.simulate_fmu(str(kv_fmu), stop_time=1.0, step_size=0.25, output_interval=0.25,
                            logger=lambda *a: messages.append(a), debug_logging=True)
    assert res["time"].max() == 0.0  # (fmpy stops at the failed step)
    assert [(m[2], m[4]) for m in messages] == [
        (3, b"step_size 0.25 s is not a whole multiple of integration_step = 0.1 s")]  # error


def test_a_ship_without_a_steering_gear_is_refused_by_name(tmp_path):
    with pytest.raises(ParameterError, match="ship 'mariner-nomoto1' has no steering gear"):
        build_fmu("mariner-nomoto1", tmp_path / "m.fmu")
    res = CliRunner().invoke(app, ["fmu", "mariner-nomoto1", "-o", str(tmp_path / "m.fmu")])
    assert res.exit_code == 2
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and "'mariner-nomoto1' has no steering gear" in lines[0], lines
    assert not (tmp_path / "m.fmu").exists()


def test_cli_writes_the_fmu_and_refuses_its_input(tmp_path):
    from seahelm.ships import ship_to_toml

    kv = tmp_path / "kv.toml"
    kv.write_text(ship_to_toml(get_ship("kvlcc2-l7")))
    out = tmp_path / "kv.fmu"
    res = CliRunner().invoke(app, ["fmu", str(kv), "-o", str(out)])
    assert res.exit_code == 0, res.stderr
    assert zipfile.is_zipfile(out)
    before = kv.read_bytes()
    res = CliRunner().invoke(app, ["fmu", str(kv), "-o", str(kv), "--force"])
    assert res.exit_code == 2 and "is a file this command reads" in res.stderr
    assert kv.read_bytes() == before
