"""One resolver for a run (issue 46 item 3): a scenario's Problem and the Problem made in Python
with the same arguments resolve to the same components, kernel and parameters.

Both take the ship, model, actuator, controller, their wiring and their default parameters from
:func:`seahelm.simulation.resolve.resolve_components`. The Python side here is written from the
scenario's TOML as a user would write it (names, the catalog ship, the parameter values given),
not from the scenario's Problem; only the per-run inputs that are no resolution (initial state,
timing, signals, environment) are taken over.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from seahelm import Problem, get_ship
from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.control.guided import guided
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.control.path_following import RouteParams, get_guidance_law, route_params
from seahelm.errors import ParameterError
from seahelm.registry import get_controller
from seahelm.scenario import load_scenario, parse_scenario
from seahelm.simulation.engine import prepare
from seahelm.simulation.resolve import resolve_components

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SIMULATION = sorted(p for p in EXAMPLES.glob("*.toml")
                    if "[simulation]" in p.read_text())

_GAINS = ("acceptance_radius", "lookahead", "lookahead_min", "lookahead_gamma", "kappa")


def _varied(doc: dict, section: str) -> set[str]:
    """The fields of ``section`` (e.g. ``vessel.params``) a [batch] varies."""
    batch = doc.get("batch", {})
    keys = list(batch.get("grid", {})) + list(batch.get("monte_carlo", {}).get("draws", {}))
    for block in batch.get("monte_carlo", {}).get("correlated", []):
        keys += list(block.get("keys", []))
    out = {k[len(section) + 1:] for k in keys if k.startswith(section + ".")}
    return out | {k.removesuffix("_deg") for k in out}


def _python_problem(path: Path, scenario: Problem, jit: bool | None = False) -> Problem:
    """The Problem a user writes in Python for the scenario at ``path``."""
    doc = tomllib.loads(path.read_text())
    vessel = doc["vessel"]
    ship = vessel.get("ship", vessel.get("catalog"))
    if ship is not None:
        ship = get_ship(ship)
        if "water_depth" in vessel:
            ship = ship.at_depth(vessel["water_depth"])
    controller = get_controller(doc.get("controller", {}).get("model", "open-loop"))
    cparams = dict(doc.get("controller", {}).get("params", {}))
    g = doc.get("guidance")
    if g is not None:
        gains = {k: g[k] for k in _GAINS if k in g}
        if issubclass(controller.params_type, RouteParams):
            route = route_params(g["waypoints"], params_type=RouteParams, **gains)
        else:
            law = get_guidance_law(g.get("law", "los"))
            route = route_params(g["waypoints"], law=law, **gains)
            controller = guided(law, controller)
        cparams = {**route.as_dict(), **cparams}
    model = None if vessel.get("model") is None else vessel["model"]
    vparams = vessel.get("params", {})
    params = None
    if vparams:
        base = ship.params if ship is not None else None
        from seahelm.registry import get_model

        params = get_model(model or ship.model).params_type.from_mapping(vparams, base=base)
    actuator = doc.get("actuator", {}).get("model")
    aparams = doc.get("actuator", {}).get("params")
    if aparams:
        from seahelm.registry import get_actuator

        gear = None if ship is None else ship.steering_gear
        act = get_actuator(actuator) if actuator else (gear.actuator if gear else RUDDER_SERVO)
        base = gear.params if gear is not None and gear.actuator is act else None
        aparams = act.params_type.from_mapping(aparams, base=base)
    sensors = None
    if "sensors" in doc:  # [sensors]: the noise of the heading in degrees there
        from seahelm.simulation.sensor_stage import PositionSensors

        sn = dict(doc["sensors"])
        sn["noise_heading"] = math.radians(sn.pop("noise_heading_deg", 0.0))
        sensors = PositionSensors(**sn)
    return Problem(
        ship=ship, model=model, actuator=actuator, controller=controller,
        params=params, actuator_params=aparams or None,
        controller_params=controller.params_type.from_mapping(cparams) if cparams else None,
        x0=scenario.x0, t_final=scenario.t_final, dt=scenario.dt,
        controller_dt=doc.get("controller", {}).get("dt"),
        integrator=scenario.integrator, record_every=scenario.record_every,
        reference=scenario.reference, disturbance=scenario.disturbance,
        environment=scenario.environment, environment_params=scenario.environment_params,
        first_order=scenario.first_order, sensors=sensors, bounds=dict(scenario.bounds),
        jit=jit)


def _same_rows(name: str, a: np.ndarray, b: np.ndarray, fields: tuple[str, ...],
               varied: set[str]) -> None:
    keep = [j for j, f in enumerate(fields) if f not in varied]
    a, b = np.broadcast_arrays(a[:, keep], b[:, keep])
    np.testing.assert_array_equal(a, b, err_msg=name)


@pytest.mark.filterwarnings("ignore:Lvov:seahelm.errors.ValidityRangeWarning")  # (examples')
@pytest.mark.parametrize("path", SIMULATION, ids=lambda p: p.stem)
def test_a_scenario_resolves_as_the_python_problem(path: Path) -> None:
    assert len(SIMULATION) >= 25  # (every [simulation] example, not an empty glob)
    scenario = load_scenario(path).replace(jit=False)
    python = _python_problem(path, scenario)
    doc = tomllib.loads(path.read_text())
    # the components, by identity (the registry's objects) or, for a guided controller, by
    # what it is made of
    assert scenario.model is python.model
    assert scenario.actuator is python.actuator
    assert scenario.controller.name == python.controller.name
    assert getattr(scenario.ship, "name", None) == getattr(python.ship, "name", None)
    assert scenario.wiring.commands == python.wiring.commands
    assert scenario.wiring.references == python.wiring.references
    assert scenario.controller_dt == python.controller_dt
    # the kernel: the generated loop's name is the hash of its text (components, integrator,
    # stages, exact actuator step)
    sb, pb = prepare(scenario), prepare(python)
    assert sb.kernel.__name__ == pb.kernel.__name__
    # the parameter rows, but for the fields a [batch] varies
    for key, section, cls in (("mp", "vessel.params", scenario.model.params_type),
                              ("ap", "actuator.params", scenario.actuator.params_type),
                              ("cp", "controller.params", scenario.controller.params_type)):
        varied = _varied(doc, section) | (_varied(doc, "guidance") if key == "cp" else set())
        _same_rows(f"{path.stem}: {key}", sb.info[key], pb.info[key], cls.value_names(),
                   varied)


@pytest.mark.parametrize("name", ["mariner_course_change", "mariner_route_los",
                                  "voitkunsky_rudder_steps", "supply_dp_setpoint"])
def test_the_python_problem_runs_the_scenarios_runs_bit_for_bit(name: str) -> None:
    """Compiled, as ``seahelm run`` runs them (these four: also bit for bit as before the one
    resolver, by the hashes of their results against main)."""
    from seahelm.simulation.engine import simulate

    path = EXAMPLES / f"{name}.toml"
    scenario = load_scenario(path)
    a, b = simulate(scenario), simulate(_python_problem(path, scenario, jit=None))
    assert a.channel_names() == b.channel_names()
    for channel in a.channel_names():
        np.testing.assert_array_equal(a[channel], b[channel], err_msg=channel)
    np.testing.assert_array_equal(a.status, b.status)


def test_the_resolver_defaults() -> None:
    """The rules: a ship's model, parameters and steering gear; the rudder servo and open loop
    by default; a named actuator that is the gear's takes the gear's parameters."""
    ship = get_ship("kvlcc2-l7")
    c = resolve_components(ship="kvlcc2-l7")
    assert c.model is ship.model and c.params is ship.params
    assert c.actuator is ship.steering_gear.actuator
    assert c.actuator_params is ship.steering_gear.params
    assert c.controller is OPEN_LOOP
    bare = resolve_components(model="nomoto2")
    assert bare.actuator is RUDDER_SERVO and bare.actuator_params is None and bare.params is None
    named = resolve_components(ship=ship, actuator=ship.steering_gear.actuator.name)
    assert named.actuator_params is ship.steering_gear.params
    with pytest.raises(ParameterError, match="is not the model of ship"):
        resolve_components(ship=ship, model="nomoto2")
    with pytest.raises(ParameterError) as err:
        resolve_components(model="nomoto2", actuator="no-such-actuator")
    assert err.value.field == "actuator"


def test_shallow_water_overrides_are_to_the_deep_water_values() -> None:
    """On a ship in shallow water an override is to its deep-water value, taken to its depth
    after -- in Python through the resolver as in a scenario file."""
    ship = get_ship("kvlcc2-l7")
    deep = resolve_components(ship=ship)
    depth = 2.0 * ship.particulars.draft if ship.particulars is not None else 40.0
    shallow = ship.at_depth(depth)
    c = resolve_components(ship=shallow)
    assert c.vessel_params({}).to_array().tolist() == shallow.params.to_array().tolist()
    assert deep.vessel_params({}).to_array().tolist() == ship.params.to_array().tolist()
    text = (f'[vessel]\nship = "kvlcc2-l7"\nwater_depth = {depth!r}\n'
            '[simulation]\nt_final = 1.0\ndt = 0.5\n')
    problem = parse_scenario(text)
    np.testing.assert_array_equal(np.asarray(problem.params)[0], shallow.params.to_array())
    assert math.isfinite(depth)


_KVLCC2 = ('[vessel]\nship = "kvlcc2-l7"\n{depth}[vessel.params]\n{params}'
           '[vessel.initial]\nsurge_speed = 1.18\n{actuator}'
           '[controller.reference]\nrudder_command_deg = 10.0\npropeller_rps = 10.0\n'
           '[simulation]\nt_final = 2.0\ndt = 0.1\n')


@pytest.mark.parametrize("actuator", ["", '[actuator]\nmodel = "rudder-servo"\n',
                                      '[actuator.params]\ntime_constant = 0.2\n'])
@pytest.mark.parametrize("depth,params", [("", ""), ("water_depth = 0.9\n", ""),
                                          ("water_depth = 0.9\n", "x_G = 0.02\n")])
def test_a_ship_scenario_resolves_as_the_python_problem(actuator: str, depth: str,
                                                        params: str) -> None:
    """A ship with a steering gear (the examples' [simulation] ships have none), in deep and
    shallow water, with and without overrides: the scenario's gear, its parameters and the
    vessel's parameters are the Python problem's (an override on a ship in shallow water is to
    its deep-water value: seahelm.ships.water_depth.params_at_depth of it)."""
    from seahelm.ships.water_depth import params_at_depth

    scenario = parse_scenario(_KVLCC2.format(depth=depth, params=params, actuator=actuator))
    ship = get_ship("kvlcc2-l7")
    gear = ship.steering_gear
    vparams = None
    if depth:
        shallow = ship.at_depth(0.9)
        vparams = (params_at_depth(shallow, ship.params.replace(x_G=0.02)) if params
                   else None)
        ship = shallow
    elif params:
        vparams = ship.params.replace(x_G=0.02)
    aparams = gear.params.replace(time_constant=0.2) if "time_constant" in actuator else None
    python = Problem(ship=ship, params=vparams, actuator_params=aparams,
                     actuator="rudder-servo" if "model" in actuator else None,
                     x0=scenario.x0, t_final=2.0, dt=0.1, reference=scenario.reference,
                     jit=False)
    scenario = scenario.replace(jit=False)
    assert scenario.actuator is python.actuator is gear.actuator
    sb, pb = prepare(scenario), prepare(python)
    assert sb.kernel.__name__ == pb.kernel.__name__
    for key in ("mp", "ap", "cp"):
        np.testing.assert_array_equal(*np.broadcast_arrays(sb.info[key], pb.info[key]),
                                      err_msg=key)
    np.testing.assert_array_equal(pb.info["ap"][0], (aparams or gear.params).to_array())
