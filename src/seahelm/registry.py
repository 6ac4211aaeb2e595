"""Registries of the pluggable components, by name.

Entries are ``"module:attribute"`` strings resolved on first lookup, so listing names imports
nothing heavy. :func:`get_model`, :func:`get_actuator` and :func:`get_controller` accept a name
or the object itself; an unknown name raises ValueError listing the valid ones. :func:`lookup`
is that rule for any registry (the studies' printed-vs-corrected variants use it too).
"""

from __future__ import annotations

import functools
import importlib
import sys
from collections.abc import Mapping
from typing import Any

from ._validate import lookup_name
from .actuators.base import Actuator
from .control.base import Controller
from .vessels.base import VesselModel

__all__ = ["VESSEL_MODELS", "ACTUATORS", "CONTROLLERS", "get_model", "get_actuator",
           "get_controller", "lookup", "model_for_params", "controller_signals"]

VESSEL_MODELS: dict[str, str] = {
    "nomoto1": "seahelm.vessels.nomoto:NOMOTO1",
    "nomoto2": "seahelm.vessels.nomoto:NOMOTO2",
    "catamaran": "seahelm.vessels.catamaran:CATAMARAN",
    "catamaran-servo": "seahelm.vessels.catamaran:CATAMARAN_SERVO",
    "voitkunsky": "seahelm.vessels.voitkunsky:VOITKUNSKY",
    "cpp-ship-calm": "seahelm.vessels.cpp_ship:CPP_SHIP_CALM",
    "cpp-ship-waves": "seahelm.vessels.cpp_ship:CPP_SHIP_WAVES",
    "mmg": "seahelm.vessels.mmg:MMG",
    "mmg-4q": "seahelm.vessels.mmg_four_quadrant:MMG_4Q",
    "mmg-ls": "seahelm.vessels.mmg_low_speed:MMG_LS",
    "mariner": "seahelm.vessels.mariner:MARINER",
    "container": "seahelm.vessels.container:CONTAINER",
    "otter": "seahelm.vessels.six_dof.otter:OTTER",
    "otter-quaternion": "seahelm.vessels.six_dof.otter:OTTER_QUATERNION",
    "remus100": "seahelm.vessels.six_dof.remus100:REMUS100",
    "dp-3dof": "seahelm.vessels.dp_three_dof:DP_3DOF",
}

ACTUATORS: dict[str, str] = {
    "rudder-servo": "seahelm.actuators.servo:RUDDER_SERVO",
    "rudder-propeller": "seahelm.actuators.servo:RUDDER_PROPELLER",
    "direct": "seahelm.actuators.servo:DIRECT",
}

CONTROLLERS: dict[str, str] = {
    "pid-heading": "seahelm.control.pid:PID_HEADING",
    "pid-heading-rps": "seahelm.control.pid:PID_HEADING_RPS",
    "lq-heading": "seahelm.control.lq_heading:LQ_HEADING",
    "lq-heading-rps": "seahelm.control.lq_heading:LQ_HEADING_RPS",
    "lq-cross-track": "seahelm.control.lq_cross_track:LQ_CROSS_TRACK",
    "lq-cross-track-rps": "seahelm.control.lq_cross_track:LQ_CROSS_TRACK_RPS",
    "open-loop": "seahelm.control.open_loop:OPEN_LOOP",
    "compensated-pid": "seahelm.control.compensation:COMPENSATED_PID",
    "fsm-yaw-rate": "seahelm.control.final_state:FSM_YAW_RATE",
    "fsm-yaw-rate-simple": "seahelm.control.final_state:FSM_YAW_RATE_SIMPLE",
    "fsm-heading": "seahelm.control.final_state:FSM_HEADING",
    "fsm-yaw-rate-drive": "seahelm.control.final_state:FSM_YAW_RATE_DRIVE",
    "fsm-yaw-rate-simple-drive": "seahelm.control.final_state:FSM_YAW_RATE_SIMPLE_DRIVE",
    "fsm-heading-drive": "seahelm.control.final_state:FSM_HEADING_DRIVE",
    "heading-rate-baseline": "seahelm.control.baselines:HEADING_RATE_BASELINE",
    "drift-thruster-baseline": "seahelm.control.baselines:DRIFT_THRUSTER_BASELINE",
    "pid-yaw-rate": "seahelm.control.baselines:PID_YAW_RATE",
    "zigzag": "seahelm.control.zigzag:ZIGZAG",
    "zigzag-rps": "seahelm.control.zigzag:ZIGZAG_RPS",
    "thrust-heading": "seahelm.control.thrust_heading:THRUST_HEADING",
    "auv-depth-heading": "seahelm.control.auv_depth_heading:AUV_DEPTH_HEADING",
    "dp-pid": "seahelm.control.dp_pid:DP_PID",
    "dp-pid-observer": "seahelm.control.dp_observer:DP_PID_OBSERVER",
}


def lookup(kind: str, table: Mapping[str, Any], name: Any, cls: type | tuple[type, ...],
           *, error: type[ValueError] = ValueError) -> Any:
    """A strategy by name from a registry ``table``, or the strategy object itself.

    The one lookup rule of every registry: an instance of ``cls`` is returned as is, a name is
    looked up, anything else raises. Entries are the objects themselves or ``"module:attribute"``
    strings, imported on first lookup (so listing names imports nothing heavy).

    Parameters
    ----------
    kind : str
        What is looked up, for the error message (``"vessel model"``, ``"delta_k_method"``).
    table : mapping of str to object or str
        The registry: name -> object, or name -> ``"module:attribute"``.
    name : str or object
        A key of ``table``, or an instance of ``cls``.
    cls : type or tuple of type
        The strategy type(s) accepted as they are.
    error : type, optional
        ValueError or a subclass (e.g. :class:`~seahelm.errors.ParameterError`) to raise.

    Returns
    -------
    object
        The registered (or given) strategy.

    Raises
    ------
    ValueError
        If ``name`` is neither a key of ``table`` nor a ``cls`` (the message lists the keys).
    """
    if isinstance(name, cls):
        return name
    entry = lookup_name(kind, table, name, error=error, sort=True)
    if isinstance(entry, str):
        module, attr = entry.split(":")
        loaded = sys.modules.get(module)  # (imported already, the usual case: no import call)
        if loaded is None or getattr(getattr(loaded, "__spec__", None), "_initializing", False):
            loaded = importlib.import_module(module)
        return getattr(loaded, attr)
    return entry


def get_model(name: str | VesselModel) -> VesselModel:
    """A vessel model by registry name (or the model itself).

    Parameters
    ----------
    name : str or VesselModel
        Registry name, or the model itself.

    Returns
    -------
    VesselModel

    Raises
    ------
    ValueError
        If ``name`` is not a registered vessel model (the message lists the valid ones).
    """
    return lookup("vessel model", VESSEL_MODELS, name, VesselModel)


def get_actuator(name: str | Actuator) -> Actuator:
    """An actuator by registry name (or the actuator itself).

    Parameters
    ----------
    name : str or Actuator
        Registry name, or the actuator itself.

    Returns
    -------
    Actuator

    Raises
    ------
    ValueError
        If ``name`` is not a registered actuator (the message lists the valid ones).
    """
    return lookup("actuator", ACTUATORS, name, Actuator)


def get_controller(name: str | Controller) -> Controller:
    """A controller by registry name (or the controller itself).

    ``"<law>+<name>"`` (e.g. ``"ilos+pid-heading"``) is the heading controller ``name`` steered
    by a path-following law (:func:`seahelm.control.guided.guided`).

    Parameters
    ----------
    name : str or Controller
        Registry name, ``<law>+<name>``, or the controller itself.

    Returns
    -------
    Controller

    Raises
    ------
    ValueError
        If ``name`` is not a registered controller (the message lists the valid ones).
    """
    if isinstance(name, str) and "+" in name and name not in CONTROLLERS:
        from .control.guided import guided
        from .control.path_following import GUIDANCE_LAWS

        law, _, inner = name.partition("+")
        if law not in GUIDANCE_LAWS:
            raise ValueError(f"unknown guidance law '{law}' in '{name}'; valid: "
                             f"{', '.join(GUIDANCE_LAWS)}")
        return guided(GUIDANCE_LAWS[law], lookup("controller", CONTROLLERS, inner, Controller))
    return lookup("controller", CONTROLLERS, name, Controller)


@functools.lru_cache(maxsize=None)
def model_for_params(params_type: type) -> VesselModel | None:
    """The one registered vessel model whose parameters are ``params_type`` (exactly).

    What a bare parameter set is simulated with when no model is named (``MMGParams`` → the
    MMG model): found in the registry, so a new model needs no table of defaults. None when no
    model, or more than one, takes that type.

    Parameters
    ----------
    params_type : type
        A :class:`~seahelm.parameters.Params` subclass.

    Returns
    -------
    VesselModel or None
    """
    found = [m for m in map(get_model, VESSEL_MODELS) if m.params_type is params_type]
    return found[0] if len(found) == 1 else None


@functools.lru_cache(maxsize=None)
def _declared_units() -> dict[tuple[str, str], frozenset[str]]:
    """The units the registered models and actuators declare, by (role, signal name): what a
    command may feed (``"command"``: actuator command channels, model inputs) and what a
    measurement may read (``"output"``: model outputs)."""
    found: dict[tuple[str, str], set[str]] = {}
    for model in map(get_model, VESSEL_MODELS):
        for name, unit in zip(model.input_labels, model.input_units):
            found.setdefault(("command", name), set()).add(unit)
        for name, unit in zip(model.output_labels, model.output_units):
            found.setdefault(("output", name), set()).add(unit)
    for actuator in map(get_actuator, ACTUATORS):
        for name, unit in zip(actuator.command_labels, actuator.command_units):
            found.setdefault(("command", name), set()).add(unit)
    return {k: frozenset(v) for k, v in found.items()}


def controller_signals(controller: str | Controller) -> list[tuple[str, str, str]]:
    """A controller's declared signals (:meth:`Controller.signals`) with the units of its
    commands and measurements filled in: a controller names them, the components it is wired
    to declare their units. A command's unit is that of the actuator channel or model input
    of its name (``rudder_command``: rad, the rudder servo's command; ``X_command`` also
    feeds an input ``X``), a measurement's that of the model output it reads; left blank where
    the registered components do not agree on one unit.

    Parameters
    ----------
    controller : str or Controller
        A controller or its registered name.

    Returns
    -------
    list of tuple of str
        ``(kind, name, unit)`` per signal.
    """
    ctrl = get_controller(controller)
    declared = _declared_units()
    rows = []
    for kind, name, unit in ctrl.signals():
        if not unit and kind in ("command", "measurement"):
            if kind == "command":
                # (the wiring's rule, seahelm.simulation.composition.COMMAND_SUFFIX)
                names = (name, name.removesuffix("_command"))
                units = set().union(*(declared.get(("command", n), ()) for n in names))
            else:
                units = set(declared.get(("output", name), ()))
            if len(units) == 1:
                unit = units.pop()
        rows.append((kind, name, unit))
    return rows
