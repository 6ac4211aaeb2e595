"""The component contract (ARCHITECTURE.md, "Component contract") holds for every component.

Compiled component code reads its parameters by name from a record (``p.gain``), never by
position (``p[0]``, ``p[_I_H]``, ``p[_NP + 8]``), and indexes its signal vectors through named
constants (``x[S.heading]``), not bare integers. These tests scan the source of the compiled
functions of every registered model, actuator and controller and of the seahelm numba
functions they call, and of every compiled function in the component packages that takes
parameters, so the rule cannot regress.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import numpy as np
import pytest
from numba.core.registry import CPUDispatcher

from seahelm.registry import (
    ACTUATORS,
    CONTROLLERS,
    VESSEL_MODELS,
    get_actuator,
    get_controller,
    get_model,
)

#: positional parameter access: p[...]
POSITIONAL_PARAM = re.compile(r"(?<![\w.])p\s*\[")
#: a signal vector indexed by a bare integer, e.g. x[2], dx[0], y[3], cmd[0], ref[1]
SIGNALS = ("x", "u", "d", "y", "dx", "f", "xa", "ca", "ya", "dxa", "z", "ref", "cs", "cmd", "sig")
BARE_INDEX = re.compile(r"(?<![\w.])(" + "|".join(SIGNALS) + r")\s*\[\s*-?\d+\s*\]")

#: packages whose compiled code is held to the contract (the studies hold compiled code too)
COMPONENT_PACKAGES = ("vessels", "actuators", "control", "analysis", "studies")


def _components():
    for table, getter, attrs in ((VESSEL_MODELS, get_model, ("rhs", "output")),
                                 (ACTUATORS, get_actuator, ("rhs", "output")),
                                 (CONTROLLERS, get_controller, ("init", "step"))):
        for name in sorted(table):
            comp = getter(name)
            for attr in attrs + (("advance",) if getattr(comp, "advance", None) else ()):
                yield f"{name}.{attr}", getattr(comp, attr)


def _seahelm_dispatchers_called(func: CPUDispatcher, seen: dict[str, CPUDispatcher]) -> None:
    """``func`` and, recursively, the seahelm numba functions its code refers to by name."""
    py = func.py_func
    key = f"{py.__module__}.{py.__qualname__}"
    if key in seen:
        return
    seen[key] = func
    for name in py.__code__.co_names:
        obj = py.__globals__.get(name)
        if isinstance(obj, CPUDispatcher) and obj.py_func.__module__.startswith("seahelm."):
            _seahelm_dispatchers_called(obj, seen)


def _registered_functions() -> dict[str, CPUDispatcher]:
    seen: dict[str, CPUDispatcher] = {}
    for _, func in _components():
        assert isinstance(func, CPUDispatcher)
        _seahelm_dispatchers_called(func, seen)
    return seen


def _package_functions_taking_params() -> dict[str, CPUDispatcher]:
    """Every numba function defined in the component packages with a parameter named ``p``."""
    found: dict[str, CPUDispatcher] = {}
    for pkg in COMPONENT_PACKAGES:
        base = importlib.import_module(f"seahelm.{pkg}")
        for info in pkgutil.walk_packages(base.__path__, prefix=f"seahelm.{pkg}."):
            module = importlib.import_module(info.name)
            for obj in vars(module).values():
                if (isinstance(obj, CPUDispatcher) and obj.py_func.__module__ == info.name
                        and "p" in inspect.signature(obj.py_func).parameters):
                    found[f"{info.name}.{obj.py_func.__qualname__}"] = obj
    return found


REGISTERED = _registered_functions()
ALL_WITH_PARAMS = {**_package_functions_taking_params(), **REGISTERED}


def _code(func: CPUDispatcher) -> str:
    """The function's source without its docstring and comments."""
    src = inspect.getsource(func.py_func)
    doc = func.py_func.__doc__
    if doc:
        src = src.replace(doc, "")
    return "\n".join(line.split("#", 1)[0] for line in src.splitlines())


def test_the_scan_sees_the_components_and_their_helpers():
    names = set(REGISTERED)
    # registered entry points and helpers they call, across modules
    for key in ("seahelm.vessels.nomoto.nomoto2_rhs", "seahelm.vessels.catamaran.catamaran_drift",
                "seahelm.vessels.cpp_ship._rhs_core", "seahelm.vessels.cpp_ship._initial_thrust",
                "seahelm.actuators.servo.rudder_propeller_rhs",
                "seahelm.actuators.servo.limited_lag_rate",
                "seahelm.control.final_state.fsm_thruster_rate",
                "seahelm.vessels.catamaran.catamaran_yaw_acceleration",
                "seahelm.control.base.wrap_pi"):
        assert key in names
    # compiled code that takes parameters but is not a registered component
    for key in ("seahelm.studies.platonov.averaged_system.rhs_averaged",
                "seahelm.studies.platonov.averaged_system._original_rhs",
                "seahelm.vessels.catamaran.catamaran_jacobian"):
        assert key in ALL_WITH_PARAMS


@pytest.mark.parametrize("key", sorted(ALL_WITH_PARAMS))
def test_parameters_are_read_by_name(key):
    code = _code(ALL_WITH_PARAMS[key])
    bad = [line.strip() for line in code.splitlines() if POSITIONAL_PARAM.search(line)]
    assert not bad, f"{key} reads parameters by position (use p.<name>): {bad}"


@pytest.mark.parametrize("key", sorted(ALL_WITH_PARAMS))
def test_signals_are_indexed_by_name(key):
    code = _code(ALL_WITH_PARAMS[key])
    bad = [line.strip() for line in code.splitlines() if BARE_INDEX.search(line)]
    assert not bad, (f"{key} indexes a signal vector by a bare integer (use the constants of "
                     f"seahelm.parameters.signal_indices): {bad}")


def test_the_scan_catches_positional_access():
    assert POSITIONAL_PARAM.search("    gain, tc = p[0], p[_I_K1]")
    assert POSITIONAL_PARAM.search("tu = p [_NP + 8]")
    assert not POSITIONAL_PARAM.search("gain = p.gain; q = mp[0]; dx[_X.north] = 0.0")
    assert BARE_INDEX.search("    dx[3] = r")
    assert BARE_INDEX.search("cmd[0] = u")
    assert not BARE_INDEX.search("dx[_X.yaw_rate] = r; c[0, 3]; X[i]; J[i, j] = 0.0")


@pytest.mark.parametrize("name", sorted(VESSEL_MODELS))
def test_models_declare_the_navigation_outputs(name):
    from seahelm.vessels.base import NAV_OUTPUTS

    model = get_model(name)
    assert model.output_labels[:len(NAV_OUTPUTS)] == NAV_OUTPUTS
    assert all(lab.isidentifier() for lab in model.output_labels)


@pytest.mark.parametrize("name", sorted(CONTROLLERS))
def test_controller_measurements_are_outputs_of_some_model(name):
    ctrl = get_controller(name)
    outputs = {lab for m in VESSEL_MODELS for lab in get_model(m).output_labels}
    assert set(ctrl.measurement_labels) <= outputs



@pytest.mark.parametrize("kind, name", [("model", n) for n in VESSEL_MODELS]
                         + [("actuator", n) for n in ACTUATORS]
                         + [("controller", n) for n in CONTROLLERS])
def test_parameter_fields_refuse_booleans_strings_and_non_finite_values_by_name_and_unit(kind,
                                                                                        name):
    import dataclasses
    import math

    from seahelm.errors import ParameterError

    comp = {"model": get_model, "actuator": get_actuator, "controller": get_controller}[kind](name)
    cls = comp.params_type
    fields = [f for f in dataclasses.fields(cls) if not f.metadata.get("size")]
    if not fields:
        pytest.skip(f"{kind} '{name}' has no scalar parameters")

    def valid(f):  # the default, or a number inside the field's range
        if f.default is not dataclasses.MISSING:
            return f.default
        low, high = f.metadata.get("low", -math.inf), f.metadata.get("high", math.inf)
        return min(max(1.0, low + 0.5 if math.isfinite(low) else 1.0), high)

    base = {f.name: valid(f) for f in dataclasses.fields(cls) if not f.metadata.get("size")
            or f.default is dataclasses.MISSING}
    for f in fields[:3]:
        unit = f.metadata.get("unit", "")
        for bad, what in ((True, "a number"), ("1.0", "a number"), (math.nan, "finite")):
            with pytest.raises(ParameterError) as exc:
                cls(**{**base, f.name: bad})
            msg = str(exc.value)
            assert msg.startswith(f"`{f.name}` must be {what}"), msg
            assert not unit or f"[{unit}]" in msg, msg


@pytest.mark.parametrize("name", sorted(n for n in ACTUATORS if get_actuator(n).advance))
def test_an_actuators_closed_form_step_solves_its_rhs(name):
    """Whatever an actuator's ``advance`` computes must be the solution of its ``rhs`` under a
    held command: the engine uses it instead of integrating ``rhs``. Checked against RK4 at a
    fine step from seeded states and commands (the commands beyond the limits too)."""
    import dataclasses
    import math

    act = get_actuator(name)
    cls = act.params_type
    values = {}
    for f in dataclasses.fields(cls):  # the defaults, and 2.0 where a field has none
        if f.default is dataclasses.MISSING:
            values[f.name] = 2.0
    p = cls(**values).to_record()
    rng = np.random.default_rng(7)
    n, steps = act.n_states, 4000
    for _ in range(5):
        xa = rng.uniform(-1.0, 1.0, n)
        ca = rng.uniform(-3.0, 3.0, max(n, 1))
        h = float(rng.uniform(0.5, 20.0))
        got = np.empty(n)
        act.advance(h, xa, ca, p, got)

        def f(x):
            dx = np.empty(n)
            act.rhs(0.0, x, ca, p, dx)
            return dx

        x, dt = xa.copy(), h / steps
        for _ in range(steps):
            k1 = f(x)
            k2 = f(x + 0.5 * dt * k1)
            k3 = f(x + 0.5 * dt * k2)
            k4 = f(x + dt * k3)
            x = x + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        np.testing.assert_allclose(got, x, rtol=0, atol=1e-8 * max(1.0, math.fabs(h)))
