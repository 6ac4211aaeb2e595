"""Wiring by signal name (seahelm.simulation.composition) for every combination in use.

COMBINATIONS lists, explicitly, each (model, actuator, controller) that examples/*.toml, the
embedded default scenario, src/ (scenario builders) and tests/ simulate, with the wiring the
composer must find; the mis-wiring tests check that a wrong combination is refused with a
message naming the signals.
"""

from __future__ import annotations

import dataclasses
import tomllib
from importlib import resources
from pathlib import Path

import pytest

from seahelm.actuators.servo import DIRECT, RUDDER_PROPELLER, RUDDER_SERVO
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.control.pid import PID_HEADING
from seahelm.control.path_following import RouteParams
from seahelm.errors import ParameterError
from seahelm.registry import get_actuator, get_controller, get_model
from seahelm.scenario import ActuatorSection, ControllerSection
from seahelm.simulation.composition import compose
from seahelm.ships import catalog
from seahelm.vessels.base import VesselModel
from seahelm.vessels.nomoto import NOMOTO2, Nomoto2Params, nomoto2_output, nomoto2_rhs

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

_SERVO = ("controller.rudder_command -> actuator.rudder_command\n"
          "actuator.rudder_angle -> model.rudder_angle")
_HEADING = "\nmodel.heading -> controller.heading\nmodel.yaw_rate -> controller.yaw_rate"
_RUDDER_DIRECT = ("controller.rudder_angle -> actuator.rudder_angle\n"
                  "actuator.rudder_angle -> model.rudder_angle")
_THRUSTER_RATE = ("controller.thruster_rate_command -> actuator.thruster_rate\n"
                  "actuator.thruster_rate -> model.thruster_rate")

# (model, actuator, controller): (controller references, wiring), with where each is used
COMBINATIONS = {
    # examples/mariner_*.toml, the default scenario, examples/quickstart.py, test_control_pid,
    # test_results, test_simulation_engine, benchmarks/bench_engine.py
    ("nomoto2", "rudder-servo", "pid-heading"): (("heading",), _SERVO + _HEADING),
    # test_simulation_engine (default actuator and controller)
    ("nomoto1", "rudder-servo", "open-loop"): (("rudder_command",), _SERVO),
    ("nomoto2", "rudder-servo", "open-loop"): (("rudder_command",), _SERVO),
    # test_vessels_nomoto, test_simulation_engine, test_simulation_integrators
    ("nomoto1", "direct", "open-loop"): (("rudder_angle",), _RUDDER_DIRECT),
    ("nomoto2", "direct", "open-loop"): (("rudder_angle",), _RUDDER_DIRECT),
    # examples/voitkunsky_rudder_steps.toml, examples/make_steady_turn_log.py,
    # test_vessels_voitkunsky
    ("voitkunsky", "rudder-servo", "open-loop"): (("rudder_command",), _SERVO),
    ("voitkunsky", "direct", "open-loop"): (("rudder_angle",), _RUDDER_DIRECT),
    # examples/compensation_*.toml, control.compensation.compensation_scenario,
    # test_control_compensation, examples/compensation_table.py
    ("voitkunsky", "rudder-servo", "compensated-pid"): (
        ("heading", "delta_k_wind", "delta_k_wave"), _SERVO + _HEADING),
    ("voitkunsky", "rudder-servo", "pid-heading"): (("heading",), _SERVO + _HEADING),
    # examples/catamaran_constant_thruster.toml, test_vessels_catamaran,
    # test_control_final_state
    ("catamaran", "direct", "open-loop"): (
        ("thruster_rate",),
        "controller.thruster_rate -> actuator.thruster_rate\n"
        "actuator.thruster_rate -> model.thruster_rate"),
    # examples/catamaran_*.toml, test_control_final_state, test_vessels_catamaran,
    # benchmarks/bench_catamaran.py
    ("catamaran", "direct", "fsm-yaw-rate"): (("yaw_rate",), _THRUSTER_RATE),
    ("catamaran", "direct", "fsm-yaw-rate-simple"): (("yaw_rate",), _THRUSTER_RATE),
    ("catamaran", "direct", "fsm-heading"): (("heading",), _THRUSTER_RATE),
    # test_control_baselines
    ("catamaran", "direct", "heading-rate-baseline"): (("heading",), _THRUSTER_RATE + _HEADING),
    ("catamaran", "direct", "drift-thruster-baseline"): (("drift_angle",), _THRUSTER_RATE),
    ("catamaran", "direct", "pid-yaw-rate"): (
        ("yaw_rate",), _THRUSTER_RATE + "\nmodel.yaw_rate -> controller.yaw_rate"),
    # test_control_final_state (the thruster drive of eq. (22)-(23))
    ("catamaran-servo", "direct", "fsm-yaw-rate-simple-drive"): (
        ("yaw_rate",),
        "controller.thruster_command -> actuator.thruster_command\n"
        "actuator.thruster_command -> model.thruster_command"),
    # seahelm.analysis.maneuvers (turning circles, spirals, pull-outs), test_vessels_mmg,
    # test_vessels_mariner, test_analysis_maneuvers, test_analysis_imo, test_cli_maneuver,
    # benchmarks/bench_maneuvers.py
    ("mmg", "rudder-servo", "open-loop"): (
        ("rudder_command", "propeller_rps"),
        _SERVO + "\ncontroller.propeller_rps -> model.propeller_rps"),
    ("mariner", "rudder-servo", "open-loop"): (("rudder_command",), _SERVO),
    # seahelm.analysis.maneuvers.zigzag (and the IMO check built on it)
    ("mmg", "rudder-servo", "zigzag-rps"): (
        (), _SERVO + "\ncontroller.propeller_rps -> model.propeller_rps" + _HEADING),
    ("mariner", "rudder-servo", "zigzag"): ((), _SERVO + _HEADING),
    # the 4-DOF container ship: examples/container_turning_heel.toml, test_vessels_container
    ("container", "rudder-servo", "open-loop"): (
        ("rudder_command", "propeller_rps"),
        _SERVO + "\ncontroller.propeller_rps -> model.propeller_rps"),
    ("container", "rudder-servo", "zigzag-rps"): (
        (), _SERVO + "\ncontroller.propeller_rps -> model.propeller_rps" + _HEADING),
    # examples/container_waves_motions.toml, container_seakeeping_sweep.toml (heading
    # autopilot, shaft at a constant speed)
    ("container", "rudder-servo", "pid-heading-rps"): (
        ("heading",), _SERVO + "\ncontroller.propeller_rps -> model.propeller_rps" + _HEADING),
    # test_control_path_following, examples/mariner_route_*.toml: the guidance law feeds the
    # PID's heading reference inside the controller; it reads the position as well
    ("mariner", "rudder-servo", "los+pid-heading"): (
        (), _SERVO + _HEADING + "\nmodel.north -> controller.north\nmodel.east -> controller.east"),
    ("mariner", "rudder-servo", "ilos+pid-heading"): (
        (), _SERVO + _HEADING + "\nmodel.north -> controller.north\nmodel.east -> controller.east"),
    # examples/mariner_route_lq.toml: a controller that follows the route itself
    ("mariner", "rudder-servo", "lq-cross-track"): (
        (), _SERVO + "\nmodel.north -> controller.north\nmodel.east -> controller.east"
        + _HEADING + "\nmodel.sway_speed -> controller.sway_speed"),
    # test_vessels_cpp_ship
    ("cpp-ship-waves", "direct", "open-loop"): (
        ("pitch_ratio",),
        "controller.pitch_ratio -> actuator.pitch_ratio\n"
        "actuator.pitch_ratio -> model.pitch_ratio"),
    # examples/otter_route_current.toml: LOS feeds the heading, the surge force is the user's;
    # the shaft-speed commands pass the direct actuator to the model's two propellers
    ("otter", "direct", "los+thrust-heading"): (
        ("surge_force",),
        "controller.propeller_port_speed_command -> actuator.propeller_port_speed_command\n"
        "controller.propeller_starboard_speed_command -> "
        "actuator.propeller_starboard_speed_command\n"
        "actuator.propeller_port_speed_command -> model.propeller_port_speed_command\n"
        "actuator.propeller_starboard_speed_command -> model.propeller_starboard_speed_command"
        + _HEADING + "\nmodel.north -> controller.north\nmodel.east -> controller.east"),
    # examples/remus100_dive_turn.toml: depth (stern planes), heading (rudder), shaft speed
    ("remus100", "direct", "auv-depth-heading"): (
        ("depth", "heading", "propeller_speed"),
        "controller.propeller_speed_command -> actuator.propeller_speed_command\n"
        "controller.rudder_command -> actuator.rudder_command\n"
        "controller.stern_plane_command -> actuator.stern_plane_command\n"
        "actuator.propeller_speed_command -> model.propeller_speed_command\n"
        "actuator.rudder_command -> model.rudder_command\n"
        "actuator.stern_plane_command -> model.stern_plane_command\n"
        "model.depth -> controller.depth\nmodel.pitch -> controller.pitch\n"
        "model.heading -> controller.heading\nmodel.heave_speed -> controller.heave_speed\n"
        "model.pitch_rate -> controller.pitch_rate\nmodel.yaw_rate -> controller.yaw_rate"),
    # examples/supply_dp_setpoint.toml: the DP controller's generalized thrust passes the
    # direct actuator to the DP model; it measures position, heading and the body velocities;
    # its references are the set-point and the measured wind load (feedforward)
    # examples/supply_dp_observer_waves.toml, test_dp_observer, test_sensor_stage: the
    # observer measures position and heading only (the sensor stage reroutes them)
    ("dp-3dof", "direct", "dp-pid-observer"): (
        ("north", "east", "heading", "wind_force_x", "wind_force_y", "wind_moment_z"),
        "controller.thrust_surge -> actuator.thrust_surge\n"
        "controller.thrust_sway -> actuator.thrust_sway\n"
        "controller.thrust_yaw -> actuator.thrust_yaw\n"
        "actuator.thrust_surge -> model.thrust_surge\n"
        "actuator.thrust_sway -> model.thrust_sway\n"
        "actuator.thrust_yaw -> model.thrust_yaw\n"
        "model.north -> controller.north\nmodel.east -> controller.east\n"
        "model.heading -> controller.heading"),
    ("dp-3dof", "direct", "dp-pid"): (
        ("north", "east", "heading", "wind_force_x", "wind_force_y", "wind_moment_z"),
        "controller.thrust_surge -> actuator.thrust_surge\n"
        "controller.thrust_sway -> actuator.thrust_sway\n"
        "controller.thrust_yaw -> actuator.thrust_yaw\n"
        "actuator.thrust_surge -> model.thrust_surge\n"
        "actuator.thrust_sway -> model.thrust_sway\n"
        "actuator.thrust_yaw -> model.thrust_yaw\n"
        "model.north -> controller.north\nmodel.east -> controller.east\n"
        "model.heading -> controller.heading\nmodel.surge_speed -> controller.surge_speed\n"
        "model.sway_speed -> controller.sway_speed\nmodel.yaw_rate -> controller.yaw_rate"),
}


@pytest.mark.parametrize("combo", list(COMBINATIONS), ids="/".join)
def test_every_combination_in_use_composes_as_expected(combo):
    model, actuator, controller = get_model(combo[0]), get_actuator(combo[1]), \
        get_controller(combo[2])
    references, wiring = COMBINATIONS[combo]
    comp = compose(model, actuator, controller)
    assert comp.describe() == wiring
    assert comp.references == references
    assert len(comp.reference_units) == len(references)
    # every model input is fed exactly once, every measurement is a model output
    assert len(comp.input_from) == model.n_inputs
    for name, j in zip(controller.measurement_labels, comp.measurement_from):
        assert model.output_labels[j] == name


def _ship_model(vessel: dict) -> str:
    """The model of a scenario's ship: a catalog ship's, or the MMG model of a ship estimated
    from its particulars."""
    if "particulars" in vessel:
        return "mmg"
    return catalog.get(vessel.get("ship") or vessel["catalog"]).model.name


def _scenario_combo(text: str) -> tuple[str, str, str]:
    scn = tomllib.loads(text)
    if "maneuver" in scn:  # the manoeuvre's loop: the catalog ship's model and steering gear
        model = _ship_model(scn["vessel"])
        controller = "open-loop"
        if scn["maneuver"]["kind"] == "zigzag":  # the zig-zag's own heading-triggered logic
            controller = "zigzag-rps" if model == "mmg" else "zigzag"
        return (model, "rudder-servo", controller)
    model = scn["vessel"].get("model") or _ship_model(scn["vessel"])
    if "guidance" in scn:  # the route's law steers the heading controller
        name = scn["controller"]["model"]
        if issubclass(get_controller(name).params_type, RouteParams):  # it follows the route
            return (model, scn.get("actuator", {}).get("model", ActuatorSection().model), name)
        return (model, scn.get("actuator", {}).get("model", ActuatorSection().model),
                f"{scn['guidance'].get('law', 'los')}+{name}")
    return (model,
            scn.get("actuator", {}).get("model", ActuatorSection().model),
            scn.get("controller", {}).get("model", ControllerSection().model))


def test_the_list_covers_every_example_scenario():
    texts = {p.name: p.read_text() for p in sorted(EXAMPLES.glob("*.toml"))}
    texts["default.toml"] = resources.files("seahelm").joinpath("data/default.toml").read_text()
    assert len(texts) > 10
    missing = {name: _scenario_combo(t) for name, t in texts.items()
               if _scenario_combo(t) not in COMBINATIONS}
    assert not missing, f"add these to COMBINATIONS: {missing}"


# -- a 3-DOF-like model fed by the two-channel actuator ------------------------------------
SHIP_3DOF = VesselModel(
    name="test-3dof",
    description="Nomoto-2 dynamics with a second input, to test the wiring only",
    params_type=Nomoto2Params,
    state_labels=NOMOTO2.state_labels,
    state_units=NOMOTO2.state_units,
    input_labels=("rudder_angle", "propeller_rps"),
    input_units=("rad", "1/s"),
    disturbance_labels=(),
    disturbance_units=(),
    rhs=nomoto2_rhs,
    output=nomoto2_output,
    output_labels=NOMOTO2.output_labels,
    output_units=NOMOTO2.output_units,
)


def test_rudder_propeller_feeds_both_inputs_of_a_two_input_model():
    comp = compose(SHIP_3DOF, RUDDER_PROPELLER, OPEN_LOOP)
    assert comp.references == ("rudder_command", "propeller_rps_command")
    assert comp.reference_units == ("rad", "1/s")
    assert comp.describe() == (
        "controller.rudder_command -> actuator.rudder_command\n"
        "controller.propeller_rps_command -> actuator.propeller_rps_command\n"
        "actuator.rudder_angle -> model.rudder_angle\n"
        "actuator.propeller_rps -> model.propeller_rps")
    # the direct actuator: one channel per input, named after it
    direct = compose(SHIP_3DOF, DIRECT, OPEN_LOOP)
    assert direct.references == ("rudder_angle", "propeller_rps")
    # a heading autopilot on the rudder servo, the shaft speed commanded directly
    pid = dataclasses.replace(PID_HEADING, name="pid-and-shaft",
                              command_labels=("rudder_command", "propeller_rps_command"))
    mixed = compose(SHIP_3DOF, RUDDER_SERVO, pid)
    assert mixed.input_from == (("actuator", 0), ("command", 1))


# -- mis-wiring is refused, naming the signals -----------------------------------------------
def test_unknown_measurement_is_named():
    ctrl = dataclasses.replace(PID_HEADING, name="pid-roll",
                               measurement_labels=("heading", "roll_angle"))
    with pytest.raises(ParameterError, match=r"measures 'roll_angle'.*model outputs: north, "
                                             r"east, heading, yaw_rate"):
        compose(NOMOTO2, RUDDER_SERVO, ctrl)


def test_two_output_actuator_on_a_one_input_model_is_refused():
    with pytest.raises(ParameterError, match=r"actuator output 'propeller_rps' is not an input "
                                             r"of the model \(model inputs: rudder_angle\)"):
        compose(NOMOTO2, RUDDER_PROPELLER, PID_HEADING)


def test_unfed_model_input_is_named():
    # a rudder autopilot on the catamaran, whose input is the thruster rate
    with pytest.raises(ParameterError, match=r"model input 'thruster_rate' is not fed.*"
                                             r"'thruster_rate_command'.*controller commands: "
                                             r"rudder_command"):
        compose(get_model("catamaran"), DIRECT, PID_HEADING)
    # the thruster-rate controller on the drive-input model needs its -drive variant
    with pytest.raises(ParameterError, match=r"model input 'thruster_command' is not fed.*"
                                             r"controller commands: thruster_rate_command"):
        compose(get_model("catamaran-servo"), DIRECT, get_controller("fsm-yaw-rate-simple"))


def test_unused_command_is_named():
    ctrl = dataclasses.replace(PID_HEADING, name="pid-and-shaft",
                               command_labels=("rudder_command", "propeller_rps_command"))
    with pytest.raises(ParameterError, match=r"controller command\(s\) propeller_rps_command "
                                             r"feed nothing.*channels: rudder_command.*inputs: "
                                             r"rudder_angle"):
        compose(NOMOTO2, RUDDER_SERVO, ctrl)
