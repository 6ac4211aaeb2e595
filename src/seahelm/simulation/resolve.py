"""The components of one run, resolved in one place: :func:`resolve_components`.

A :class:`~seahelm.simulation.problem.Problem` made in Python and the one a scenario file
describes (:func:`seahelm.scenario.prepare_runs`) take their ship, vessel model, actuator and
controller, the wiring between them, and their default parameters from this one function, so
the same arguments give the same components, the same kernel and the same parameter values
whichever way the problem was made:

* the model is the one named, else the ship's (a named model must be the ship's);
* the actuator is the one named, else the ship's steering gear, else the rudder servo; its
  default parameters are the steering gear's when its actuator is the one used;
* the controller is the one named, else open loop (reference = command);
* the wiring is :func:`~seahelm.simulation.composition.compose` of the three;
* the vessel's parameters are the ship's; values written over them
  (:meth:`Components.vessel_params`) are over its deep-water values on a ship in shallow
  water, taken to the ship's depth after (as a ship file writes them).

Every error is a :class:`~seahelm.errors.ParameterError` whose ``field`` is the problem's
field (``ship``, ``model``, ``actuator``, ``controller``).
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Mapping
from typing import Any

from ..actuators.base import Actuator
from ..actuators.servo import DIRECT, RUDDER_SERVO
from ..control.base import Controller
from ..control.open_loop import OPEN_LOOP
from ..errors import ParameterError
from ..parameters import Params
from ..registry import get_actuator, get_controller, get_model
from ..vessels.base import VesselModel
from .composition import Composition, compose

__all__ = ["Components", "resolve_components"]


def field_error(name: str, exc: Exception) -> ParameterError:
    """``exc`` as a :class:`ParameterError` of the problem's field ``name``."""
    if isinstance(exc, ParameterError) and exc.field is not None:
        return exc.within(name) if not exc.field.startswith(name) else exc
    return ParameterError(f": {exc}", field=name)


@dataclasses.dataclass(frozen=True, eq=False)
class Components:
    """A run's components and their defaults, resolved (:func:`resolve_components`).

    Attributes
    ----------
    ship : Ship or None
        The ship, if one was given.
    model : VesselModel
        The vessel model.
    actuator : Actuator
        The actuator.
    controller : Controller
        The controller.
    wiring : Composition
        Controller → actuator → model by signal name.
    params : Params or None
        The vessel's default parameters: the ship's (None without a ship: they must be given).
    actuator_params : Params or None
        The actuator's default parameters: the ship's steering gear's when its actuator is
        the one used, else None (the actuator's own defaults).
    """

    ship: Any
    model: VesselModel
    actuator: Actuator
    controller: Controller
    wiring: Composition
    params: Params | None
    actuator_params: Params | None

    def vessel_params(self, values: Mapping[str, float]) -> Params:
        """The vessel's parameters with ``values`` written over the ship's (or alone, without a
        ship); on a ship in shallow water over its deep-water values, taken to its depth after
        (:func:`seahelm.ships.water_depth.params_at_depth`).

        Parameters
        ----------
        values : mapping of field name to value
            Parameter values (SI units).

        Returns
        -------
        Params

        Raises
        ------
        ParameterError
            A value outside its range, or an unknown name (from the parameters' dataclass).
        TypeError
            A required parameter missing (no ship to take it from).
        """
        ship = self.ship
        base = None if ship is None else (ship.deep_water_params or ship.params)
        built = self.model.params_type.from_mapping(values, base=base)
        if ship is not None and ship.in_shallow_water:
            from ..ships.water_depth import params_at_depth

            built = params_at_depth(ship, built)
        return built

    def actuator_params_with(self, values: Mapping[str, float]) -> Params:
        """The actuator's parameters with ``values`` written over its defaults
        (:attr:`actuator_params`, else the actuator's own).

        Parameters
        ----------
        values : mapping of field name to value

        Returns
        -------
        Params
        """
        return self.actuator.params_type.from_mapping(values, base=self.actuator_params)


@functools.cache
def _ship_lookup() -> Any:
    """:func:`seahelm.ships.get_ship`, imported when first needed (``seahelm.ships`` is not
    imported with the simulation; an import statement at every call of
    :func:`resolve_components` cost more than the lookup of a catalog ship)."""
    from ..ships import get_ship

    return get_ship


def resolve_components(*, ship: Any = None, model: Any = None, actuator: Any = None,
                       controller: Any = None) -> Components:
    """A run's ship, model, actuator, controller, wiring and default parameters (module
    docstring: the rules).

    Parameters
    ----------
    ship : Ship, str or path-like, optional
        A ship (a catalog name or a ship file).
    model : VesselModel or str, optional
        The vessel model (default: the ship's).
    actuator : Actuator or str, optional
        The actuator (default: the ship's steering gear, else the rudder servo).
    controller : Controller or str, optional
        The controller (default: open loop).

    Returns
    -------
    Components

    Raises
    ------
    ParameterError
        Naming the field (``ship``, ``model``, ``actuator``, ``controller``): an unknown name,
        neither a model nor a ship, a model that is not the ship's, components whose signals
        do not connect (at ``controller``).
    """
    if ship is not None:
        try:
            ship = _ship_lookup()(ship)
        except ValueError as exc:
            raise field_error("ship", exc) from None
    if model is None:
        if ship is None:
            raise ParameterError("is required: give a `model` (seahelm models lists them) "
                                 "or a `ship`", field="model")
        model = ship.model
    else:
        try:
            model = get_model(model)
        except ValueError as exc:
            raise field_error("model", exc) from None
        if ship is not None and model is not ship.model:
            raise ParameterError(f"'{model.name}' is not the model of ship '{ship.name}' "
                                 f"('{ship.model.name}')", field="model")
    if not isinstance(model, VesselModel):  # pragma: no cover - get_model checks
        raise ParameterError(f"must be a VesselModel, got {type(model).__name__}", field="model")
    gear = None if ship is None else ship.steering_gear
    if actuator is None:
        # (a craft without a rudder input, the Otter's thrusters: no rudder servo either)
        actuator = gear.actuator if gear is not None else (
            RUDDER_SERVO if "rudder_angle" in model.input_labels else DIRECT)
    else:
        try:
            actuator = get_actuator(actuator)
        except ValueError as exc:
            raise field_error("actuator", exc) from None
    if not isinstance(actuator, Actuator):  # pragma: no cover - get_actuator checks
        raise ParameterError(f"must be an Actuator, got {type(actuator).__name__}",
                             field="actuator")
    try:
        controller = get_controller(OPEN_LOOP if controller is None else controller)
    except ValueError as exc:
        raise field_error("controller", exc) from None
    if not isinstance(controller, Controller):  # pragma: no cover - get_controller checks
        raise ParameterError(f"must be a Controller, got {type(controller).__name__}",
                             field="controller")
    try:
        wiring = compose(model, actuator, controller)
    except ParameterError as exc:
        raise field_error("controller", exc) from None
    return Components(
        ship=ship, model=model, actuator=actuator, controller=controller, wiring=wiring,
        params=None if ship is None else ship.params,
        actuator_params=gear.params if gear is not None and gear.actuator is actuator else None)
