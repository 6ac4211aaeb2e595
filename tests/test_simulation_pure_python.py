"""The pure-Python closed loop (``simulate(jit=False)``, ``SEAHELM_DISABLE_JIT``,
``NUMBA_DISABLE_JIT``): the same loop as the compiled one, for debugging a component.

Every registered vessel model runs a short batch both ways and the two agree to 1e-12; a
breakpoint in a model's ``rhs`` is reached in the pure path only; the pure path writes nothing
to the kernel cache or numba's. The compiled runs use combinations of components that other
tests compile too (each compiles once per machine), so this file adds little compile time.
"""

from __future__ import annotations

import bdb
import dis
import json
import math
import os
import subprocess
import sys
import textwrap
import warnings
from pathlib import Path

import numpy as np
import pytest

from seahelm.actuators.servo import DIRECT, RUDDER_SERVO, ServoParams
from seahelm.control.auv_depth_heading import AUV_DEPTH_HEADING, AuvDepthHeadingParams
from seahelm.control.final_state import (
    FSM_YAW_RATE_SIMPLE,
    FSM_YAW_RATE_SIMPLE_DRIVE,
    yaw_rate_params,
)
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.registry import VESSEL_MODELS, get_model
from seahelm.simulation.engine import compile_closed_loop, jit_enabled, simulate
from seahelm.simulation.inlining import python_function
from seahelm.vessels.catamaran import CatamaranServoParams, paper_params
from seahelm.vessels.container import CONTAINER_MSS_SERVO, CONTAINER_SHIP
from seahelm.vessels.cpp_ship import CPPShipParams
from seahelm.vessels.mariner import MARINER_NONLINEAR, MARINER_SERVO
from seahelm.vessels.mmg import KVLCC2_L7, KVLCC2_L7_SERVO, KVLCC2_L7_WP0_035
from seahelm.vessels.mmg_four_quadrant import KVLCC2_L7_4Q
from seahelm.vessels.mmg_low_speed import ESSO_OSAKA_3M
from seahelm.vessels.nomoto import Nomoto1Params, Nomoto2Params
from seahelm.vessels.voitkunsky import MARINER_VOITKUNSKY

#: KVLCC2 L7 approach speed [m/s] and a propeller speed near self-propulsion [1/s]
U0_L7, RPS_L7 = 1.179, 10.4


def _nomoto2_disturbance() -> np.ndarray:
    d = np.zeros((2, 21, 4))  # rudder disturbance, sway velocity, current north/east
    d[:, :, 0] = 0.01 * np.sin(0.3 * np.arange(21))[None] * np.array([[1.0], [2.0]])
    return d


#: model name -> keyword arguments of simulate: a batch of two runs of ~20 steps each, on
#: components that suit the model (the compiled combinations are those of the model's tests);
#: built when used (CPPShipParams compiles a helper of its own when made)
CASES = {
    "nomoto1": lambda: dict(
        params=[Nomoto1Params(gain=0.185, time_constant=107.3, speed=7.7),
                Nomoto1Params(gain=0.2, time_constant=30.0, speed=5.0, norrbin_n3=400.0)],
        x0=np.zeros(4), t_final=10.0, dt=0.5, actuator=DIRECT, controller=OPEN_LOOP,
        reference=np.array([0.1, -0.35]).reshape(2, 1, 1)),
    "nomoto2": lambda: dict(
        params=[Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7),
                Nomoto2Params(gain=0.25, t1=90.0, t2=6.0, t3=15.0, speed=7.7)],
        x0=np.array([[0.0, 0.0, 0.1, 0.0, 0.0], [0.0, 0.0, -0.2, 0.001, 0.0]]),
        t_final=10.0, dt=0.5, controller_dt=1.0, actuator=RUDDER_SERVO,
        controller=PID_HEADING, controller_params=PIDHeadingParams(kp=3.0, ki=0.001, kd=90.0),
        reference=np.array([0.3, -0.4]).reshape(2, 1, 1), disturbance=_nomoto2_disturbance()),
    "catamaran": lambda: dict(
        params=paper_params(), x0=np.zeros(7), t_final=0.2, dt=0.01, actuator=DIRECT,
        controller=FSM_YAW_RATE_SIMPLE,
        controller_params=yaw_rate_params(time_constant=1.0, step=0.01),
        reference=np.array([0.01, 0.02]).reshape(2, 1, 1)),
    "catamaran-servo": lambda: dict(
        params=CatamaranServoParams(servo_time_constant=0.5, servo_gain=2.0), x0=np.zeros(7),
        t_final=0.2, dt=0.01, actuator=DIRECT, controller=FSM_YAW_RATE_SIMPLE_DRIVE,
        controller_params=yaw_rate_params(
            CatamaranServoParams(servo_time_constant=0.5, servo_gain=2.0), time_constant=1.0,
            step=0.01, servo_command=1.0),
        reference=np.array([0.02, -0.01]).reshape(2, 1, 1)),
    "voitkunsky": lambda: dict(
        params=[MARINER_VOITKUNSKY, MARINER_VOITKUNSKY.replace(h2=0.0)],
        x0=np.array([[0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.5, 0.001, 0.01]]),
        t_final=10.0, dt=0.5, actuator=RUDDER_SERVO, actuator_params=ServoParams(),
        controller=OPEN_LOOP, reference=np.array([0.1, -0.2]).reshape(2, 1, 1)),
    "cpp-ship-calm": lambda: dict(
        params=CPPShipParams(), x0=np.array([[0.9, 0.95], [0.8, 1.0]]),
        t_final=20 * np.pi / 200, dt=np.pi / 200, actuator=DIRECT, controller=OPEN_LOOP,
        reference=np.array([0.7, 0.5]).reshape(2, 1, 1)),
    "cpp-ship-waves": lambda: dict(
        params=CPPShipParams(), x0=np.array([[0.9, 0.95], [0.8, 1.0]]),
        t_final=20 * np.pi / 200, dt=np.pi / 200, actuator=DIRECT, controller=OPEN_LOOP,
        reference=np.array([0.7, 0.5]).reshape(2, 1, 1)),
    "mmg": lambda: dict(
        params=[KVLCC2_L7, KVLCC2_L7_WP0_035], x0=np.array([U0_L7, 0, 0, 0, 0, 0]),
        t_final=2.0, dt=0.1, actuator=RUDDER_SERVO, actuator_params=KVLCC2_L7_SERVO,
        controller=OPEN_LOOP,
        reference={"rudder_command": np.radians([35.0, -20.0]).reshape(2, 1, 1),
                   "propeller_rps": RPS_L7}),
    "mmg-4q": lambda: dict(  # a crash stop: full astern ordered from the approach
        params=[KVLCC2_L7_4Q, KVLCC2_L7_4Q.replace(backing_side_force=0.1)],
        x0=np.array([U0_L7, 0, 0, 0, 0, 0, RPS_L7, 0]), t_final=2.0, dt=0.1,
        actuator=RUDDER_SERVO, actuator_params=KVLCC2_L7_SERVO, controller=OPEN_LOOP,
        reference={"rudder_command": np.radians([0.0, 10.0]).reshape(2, 1, 1),
                   "engine_order": -1.0}),
    "mmg-ls": lambda: dict(  # ahead with 35 deg rudder, and a propeller reversed (astern);
        # rudder and rps given directly (tests/test_reversals.py's combination: the rudder
        # servo of the other MMG cases would be a kernel only this case compiles)
        params=ESSO_OSAKA_3M, x0=np.array([0.3, 0, 0, 0, 0, 0]), t_final=2.0, dt=0.1,
        actuator=DIRECT, controller=OPEN_LOOP,
        reference={"rudder_angle": np.radians([35.0, -20.0]).reshape(2, 1, 1),
                   "propeller_rps": np.array([10.0, -10.0]).reshape(2, 1, 1)}),
    "mariner": lambda: dict(
        params=MARINER_NONLINEAR, x0=np.zeros(6), t_final=2.0, dt=0.1, actuator=RUDDER_SERVO,
        actuator_params=MARINER_SERVO, controller=OPEN_LOOP,
        reference={"rudder_command": np.radians([35.0, -20.0]).reshape(2, 1, 1)}),
    "container": lambda: dict(
        params=CONTAINER_SHIP, x0=np.array([8.0, 0, 0, 0, 0, 0, 0, 0.01]), t_final=2.0,
        dt=0.1, actuator=RUDDER_SERVO, actuator_params=CONTAINER_MSS_SERVO, controller=OPEN_LOOP,
        reference={"rudder_command": np.radians([10.0, -5.0]).reshape(2, 1, 1),
                   "propeller_rps": 80.0 / 60.0}),
    "otter": lambda: dict(
        params=_otter(), x0=np.zeros(14), t_final=1.0, dt=0.05, actuator=DIRECT,
        controller=OPEN_LOOP,
        reference={"propeller_port_speed_command": np.array([90.0, 40.0]).reshape(2, 1, 1),
                   "propeller_starboard_speed_command": 60.0}),
    "otter-quaternion": lambda: dict(
        params=_otter(), x0=np.eye(15)[3], t_final=1.0, dt=0.05, actuator=DIRECT,
        controller=OPEN_LOOP,
        reference={"propeller_port_speed_command": np.array([90.0, 40.0]).reshape(2, 1, 1),
                   "propeller_starboard_speed_command": 60.0}),
    "dp-3dof": lambda: dict(  # Fossen's supply vessel, thrusters' forces held
        params=_supply(), x0=np.array([0, 0, 0.1, 0.5, 0.0, 0.0]), t_final=2.0, dt=0.1,
        actuator=DIRECT, controller=OPEN_LOOP,
        reference={"thrust_surge": np.array([2e5, -1e5]).reshape(2, 1, 1),
                   "thrust_sway": 1e5, "thrust_yaw": 3e6}),
    "remus100": lambda: dict(  # under its depth and heading autopilots (the combination of
        # examples/remus100_dive_turn.toml and tests/test_vessels_six_dof_remus.py)
        params=_remus(), x0=np.array([0, 0, 1.0, 0, 0, 0, 1.5] + [0.0] * 8), t_final=1.0,
        dt=0.05, actuator=DIRECT, controller=AUV_DEPTH_HEADING,
        controller_params=AuvDepthHeadingParams(),
        reference={"depth": np.array([5.0, 10.0]).reshape(2, 1, 1),
                   "heading": np.radians([10.0, -5.0]).reshape(2, 1, 1),
                   "propeller_speed": 150.0}),
}


def _otter():
    from seahelm.vessels.six_dof.otter import otter_params

    return otter_params()


def _remus():
    from seahelm.vessels.six_dof.remus100 import remus100_params

    return remus100_params()


def _run(name: str, **kw):
    case = CASES[name]()
    params, x0 = case.pop("params"), case.pop("x0")
    return simulate(get_model(name), params, x0, **case, **kw)


def assert_agree(python, compiled) -> None:
    """The two results to 1e-12: relative, or absolute on the scale of each channel."""
    assert python.metadata["execution"] == "python"
    assert compiled.metadata["execution"] == "compiled"
    np.testing.assert_array_equal(python.status, compiled.status)
    np.testing.assert_array_equal(python.time, compiled.time)
    for what in ("state", "output", "command"):
        a, b = getattr(python, what), getattr(compiled, what)
        assert a.shape == b.shape
        labels = getattr(compiled, f"{what}_labels")
        for j, label in enumerate(labels):
            scale = np.nanmax(np.abs(b[..., j]), initial=0.0)
            np.testing.assert_allclose(a[..., j], b[..., j], rtol=1e-12, atol=1e-12 * scale,
                                       err_msg=f"{what} {label}")


def _supply():
    from seahelm.ships import get_ship

    return get_ship("supply").params


def test_every_registered_model_has_a_case():
    assert set(CASES) == set(VESSEL_MODELS)


@pytest.mark.parametrize("name", list(VESSEL_MODELS))
def test_pure_python_loop_agrees_with_the_compiled_one(name):
    compiled = _run(name)
    python = _run(name, jit=False)
    assert python.state.shape[0] == 2 and np.isfinite(python.state).all()
    assert_agree(python, compiled)
    assert np.ptp(python.state[:, -1], axis=0).max() > 0  # the two runs differ


def _environment_case():
    """MMG + servo with Blendermann's wind and Lvov's wave loads (the combination of
    tests/test_environment_loads.py), on the KVLCC2 L7 model's dimensions (rounded)."""
    from seahelm.environment.loads import blendermann_wind_params, environment, lvov_wave_params

    env = environment(wind="blendermann", waves="lvov")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)  # C_b 0.81 > 0.8 of eq. (5)-(7)
        waves = lvov_wave_params(length=7.0, beam=1.27, draft=0.455, block_coefficient=0.81)
    wind = blendermann_wind_params("tanker-loaded", windage_frontal_area=0.54,
                                   windage_lateral_area=1.70, windage_centre=-0.52,
                                   length_overall=7.11)
    params = [env.params(**wind, **waves, wind_speed=w, wave_height=h, wave_length=5.0,
                         wind_direction=math.radians(a), wave_direction=math.radians(a))
              for w, h, a in ((8.0, 0.05, 30.0), (12.0, 0.1, -60.0))]
    return dict(environment=env, environment_params=params)


def test_pure_python_loop_with_wind_and_waves_agrees():
    kw = _environment_case()
    compiled = _run("mmg", **kw)
    python = _run("mmg", jit=False, **kw)
    assert_agree(python, compiled)
    # the loads act: the environment's outputs (after the model's) are not zero
    assert np.abs(python.output[:, 1:, len(get_model("mmg").output_labels):]).max() > 0


def _first_body_line(func) -> int:
    code = func.__code__
    return sorted({line for _, line in dis.findlinestarts(code)
                   if line is not None and line > code.co_firstlineno})[0]


class _Breakpoints(bdb.Bdb):
    """A debugger that records where its breakpoints stop and goes on (pdb without a prompt)."""

    def __init__(self) -> None:
        super().__init__()
        self.stops: list[tuple[str, int]] = []
        self._started = False

    def user_line(self, frame) -> None:
        if self._started:
            self.stops.append((frame.f_code.co_name, frame.f_lineno))
        self._started = True
        self.set_continue()


def test_a_breakpoint_in_a_models_rhs_is_hit_in_the_pure_path_only():
    from seahelm.vessels import mmg

    rhs = mmg.MMG.rhs.py_func
    line = _first_body_line(rhs)
    kw = dict(t_final=0.2, dt=0.1, reference={"rudder_command": 0.1, "propeller_rps": RPS_L7})
    for jit, expected in ((False, True), (True, False)):
        debugger = _Breakpoints()
        debugger.set_break(rhs.__code__.co_filename, line)
        try:
            res = debugger.runcall(simulate, mmg.MMG, KVLCC2_L7,
                                   np.array([U0_L7, 0, 0, 0, 0, 0]), actuator=RUDDER_SERVO,
                                   actuator_params=KVLCC2_L7_SERVO, jit=jit, **kw)
        finally:
            debugger.clear_all_breaks()
            sys.settrace(None)
        hits = [s for s in debugger.stops if s == (rhs.__name__, line)]
        # RK4: 4 stages a step, 2 steps
        assert len(hits) == (8 if expected else 0), (jit, debugger.stops[:5])
        assert res.metadata["execution"] == ("compiled" if jit else "python")


def test_the_switches(monkeypatch):
    monkeypatch.delenv("SEAHELM_DISABLE_JIT", raising=False)
    assert jit_enabled() is True and jit_enabled(False) is False
    for value, expected in (("1", False), ("yes", False), ("0", True), ("false", True),
                            ("", True), (" Off ", True)):
        monkeypatch.setenv("SEAHELM_DISABLE_JIT", value)
        assert jit_enabled() is expected, value
        assert jit_enabled(True) is True  # the argument wins
    monkeypatch.setenv("SEAHELM_DISABLE_JIT", "1")
    assert _run("nomoto1").metadata["execution"] == "python"
    assert _run("nomoto1", jit=True).metadata["execution"] == "compiled"
    with pytest.raises(ParameterError, match=r"`jit` must be True, False or None, got 'no'"):
        _run("nomoto1", jit="no")


def test_the_python_module_is_cached_and_lives_in_memory():
    from seahelm.vessels.nomoto import NOMOTO1

    a = compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, "rk4", jit=False)
    assert a is compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, "rk4", jit=False)
    assert a.__file__.startswith("<seahelm_python_loop_")
    compiled = compile_closed_loop(NOMOTO1, DIRECT, OPEN_LOOP, "rk4")
    assert a is not compiled and Path(compiled.__file__).is_file()
    # the model is bound as its Python function (a copy sharing its code): nothing compiles
    assert a.model_rhs.__code__ is NOMOTO1.rhs.py_func.__code__
    assert not hasattr(a.model_rhs, "py_func") and not hasattr(a.run_slice, "py_func")
    # a traceback or a debugger shows the generated loop's lines
    import linecache

    assert "def run_slice(" in "".join(linecache.getlines(a.__file__))


def test_python_function_follows_helpers_recursion_and_closures():
    from numba import njit

    @njit
    def leaf(x):
        return 2.0 * x

    def make():
        @njit
        def held(x):
            return leaf(x) + 1.0
        return held

    held = make()

    @njit
    def top(n, x):
        return held(x) if n <= 0 else top(n - 1, x) + 1.0

    twin = python_function(top)
    assert twin(2, 3.0) == 9.0
    assert not leaf.signatures and not held.signatures and not top.signatures  # no compile
    assert twin.__code__ is top.py_func.__code__
    assert top.py_func.__globals__ is not twin.__globals__  # the module is not modified


SUBPROCESS = textwrap.dedent("""
    import json, math, sys
    import numpy as np
    from seahelm.actuators.servo import RUDDER_SERVO
    from seahelm.control.pid import PID_HEADING, PIDHeadingParams
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2, Nomoto2Params

    kw = dict(t_final=5.0, dt=0.5, actuator=RUDDER_SERVO, controller=PID_HEADING,
              controller_params=PIDHeadingParams(kp=3.0, ki=0.001, kd=90.0),
              reference=[0.3])
    p = Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7)
    res = simulate(NOMOTO2, p, np.zeros(5), jit=None if sys.argv[1] == "default" else False,
                   **kw)
    try:
        simulate(NOMOTO2, p, np.zeros(5), jit=True, **kw)
        refused = ""
    except Exception as exc:
        refused = f"{type(exc).__name__}: {exc}"
    print(json.dumps({"state": res.state.tolist(), "execution": res.metadata["execution"],
                      "refused": refused}))
""")


def _files(*dirs: Path) -> list[str]:
    return [str(f) for d in dirs if d.exists() for f in d.rglob("*") if f.is_file()]


def test_numba_disable_jit_runs_the_same_python_loop(tmp_path):
    """numba's own switch: ``njit`` returns plain functions; the engine runs them as they are
    (the same numbers as ``jit=False``) and writes no cache."""
    kernels, numba_cache = tmp_path / "kernels", tmp_path / "numba"
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1", "SEAHELM_CACHE_DIR": str(kernels),
           "NUMBA_CACHE_DIR": str(numba_cache)}
    env.pop("SEAHELM_DISABLE_JIT", None)
    out = subprocess.run([sys.executable, "-c", SUBPROCESS, "default"], env=env,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    got = json.loads(out.stdout)
    assert got["execution"] == "python"
    assert got["refused"].startswith("ParameterError: `jit` = True, but numba's JIT is disabled")
    assert _files(kernels, numba_cache) == []
    from seahelm.vessels.nomoto import NOMOTO2

    here = simulate(NOMOTO2, Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7),
                    np.zeros(5), t_final=5.0, dt=0.5, actuator=RUDDER_SERVO,
                    controller=PID_HEADING,
                    controller_params=PIDHeadingParams(kp=3.0, ki=0.001, kd=90.0),
                    reference=[0.3], jit=False)
    np.testing.assert_array_equal(np.array(got["state"]), here.state)


def test_the_pure_path_writes_no_cache(tmp_path):
    """``jit=False`` in a process with empty caches, an environment included (its stage is
    generated too): no kernel file, no numba cache file."""
    kernels, numba_cache = tmp_path / "kernels", tmp_path / "numba"
    env = {**os.environ, "SEAHELM_CACHE_DIR": str(kernels), "NUMBA_CACHE_DIR": str(numba_cache)}
    env.pop("NUMBA_DISABLE_JIT", None)
    script = textwrap.dedent("""
        import sys
        sys.path.insert(0, sys.argv[1])
        import numpy as np
        import test_simulation_pure_python as t
        res = t._run("mmg", jit=False, **t._environment_case())
        assert res.metadata["execution"] == "python" and (res.status == 0).all()
    """)
    out = subprocess.run([sys.executable, "-c", script, str(Path(__file__).parent)], env=env,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert _files(kernels, numba_cache) == []
