"""The default start of a :class:`~seahelm.simulation.problem.Problem` built from a ship.

``Problem(ship="kvlcc2-l7", t_final=120.0, dt=0.1)`` without ``x0`` starts where the CLI's
manoeuvres start: the ship's steady straight approach at its test speed U_0, trimmed
(:func:`seahelm.analysis.maneuvers.ships.steady_approach`, i.e.
:func:`seahelm.analysis.equilibria.equilibrium.approach_state` with ``trim=True``): surge at U_0, the
propeller at its self-propulsion rps, the rudder at the angle that keeps the yaw rate zero,
heading 0, at the origin. Where the actuator has a state of the same name (the steering gear's
``rudder_angle``), it starts there too; an open-loop problem without a ``reference`` holds the
approach's inputs (rudder trim, propeller rps), so the ship keeps going straight. (A state alone
would not: with no reference the propeller is ordered to 0 rps and the KVLCC2 model loses 43 %
of its speed in 60 s.)

The approach is solved by the analysis layer, above the simulation: it is imported here inside
:func:`approach_start` only (``tests/test_import_graph.py``, ``LAZY_UPWARD``), and only for a
problem that asks for it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError
from ..parameters import Params

if TYPE_CHECKING:  # pragma: no cover
    from ..ships import Ship
    from .composition import Composition

__all__ = ["approach_start"]


def _required(ship: "Ship", why: str) -> ParameterError:
    labels = ", ".join(ship.model.state_labels)
    return ParameterError(
        f"is required: {why}; give the initial state ({labels}), e.g. zeros for a craft at "
        "rest, or x0=steady_approach(model, params, speed).state "
        "(seahelm.analysis.maneuvers.ships)", field="x0")


def approach_start(ship: "Ship", params: Any, wiring: "Composition", actuator_x0: Any,
                   reference: Any) -> tuple[np.ndarray, Any, Any]:
    """``(x0, actuator_x0, reference)`` of a problem that starts on the ship's straight approach.

    Parameters
    ----------
    ship : Ship
        The problem's ship (its test speed U_0 is the approach speed).
    params : Params or sequence of Params
        The problem's vessel parameters (one approach per parameter set).
    wiring : Composition
        The problem's checked wiring (which commands feed which inputs).
    actuator_x0, reference : object
        The problem's own; kept where given, else from the approach.

    Returns
    -------
    tuple
        The initial state (n_states,) or (runs, n_states), the actuator's initial state and
        the reference.

    Raises
    ------
    ParameterError
        (field ``x0``) If the ship has no test speed, the parameters are not parameter sets,
        or the approach is not found; the message says how to give ``x0``.
    """
    speed = ship.approach_speed
    if not math.isfinite(speed):
        raise _required(ship, f"ship '{ship.name}' has no test speed, so no straight approach "
                              "to start from")
    one = isinstance(params, Params)
    sets = [params] if one else list(params) if isinstance(params, Sequence) else None
    if not sets or not all(isinstance(p, Params) for p in sets):
        raise _required(ship, "the default (the straight approach) takes parameter sets, "
                              f"got `params` of type {type(params).__name__}")
    from ..analysis.maneuvers.ships import steady_approaches  # (above the simulation: lazily)

    found = steady_approaches(ship.model, sets, [speed] * len(sets))
    failed = [(k, a) for k, a in enumerate(found) if isinstance(a, str)]
    if failed:
        k, why = failed[0]
        raise _required(ship, f"no straight approach of '{ship.name}' at {speed:.6g} m/s"
                              + ("" if one else f" (parameter set {k})") + f": {why}")
    inputs = [{"rudder_angle": a.rudder, "propeller_rps": a.rps} for a in found]
    x0 = np.stack([a.state for a in found])
    actuator = wiring.actuator
    if actuator_x0 is None and any(label in inputs[0] for label in actuator.state_labels):
        actuator_x0 = np.array([[inp.get(label) or 0.0 for label in actuator.state_labels]
                                for inp in inputs])
        actuator_x0 = actuator_x0[0] if one else actuator_x0
    if reference is None and wiring.controller.passthrough:
        reference = {}
        for j, command in enumerate(wiring.commands):
            target = _fed_input(wiring, j)
            values = np.array([inp.get(target) or 0.0 if target else 0.0 for inp in inputs])
            reference[command] = float(values[0]) if one else values.reshape(-1, 1, 1)
    return x0[0] if one else x0, actuator_x0, reference


def _fed_input(wiring: "Composition", command: int) -> str | None:
    """The model input that controller command ``command`` sets (directly, or through the
    actuator channel of the same position as its output), or None."""
    labels = wiring.model.input_labels
    for i, (kind, j) in enumerate(wiring.input_from):
        if kind == "command" and j == command:
            return labels[i]
    if len(wiring.actuator_commands) == len(wiring.actuator_outputs):
        for k, source in enumerate(wiring.actuator_command_from):
            if source == command and wiring.actuator_outputs[k] in labels:
                return wiring.actuator_outputs[k]
    return None
