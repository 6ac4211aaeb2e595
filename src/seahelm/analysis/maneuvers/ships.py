"""The ships of a manoeuvre: ships with their steering gear, the usual time step, and the steady
straight approach (with the equilibrium failures named for the user)."""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..._validate import check_positive
from ...actuators.servo import ServoParams
from ...errors import ParameterError, deprecated_names
from ...parameters import Params
from ...registry import model_for_params
from ...vessels.base import VesselModel
from ...ships import Ship
from ..equilibria.constant_speed import is_constant_speed
from ..equilibria.approach import Approach  # the one Approach type; imported from here too
from ..equilibria.approach_cache import (
    clear_approaches,
    steady_approach,
    steady_approaches,
)
from ..equilibria.equilibrium import (
    EquilibriumError,
    straight_run_speed,
)

__all__ = ["maneuver_ship", "default_time_step"]

STARBOARD, PORT = 1, -1

#: An approach faster than this × the parameter set's speed warns (coefficients are identified
#: near one speed), as does a step longer than this × :func:`default_time_step`.
SPEED_VALIDITY = 1.5
STEP_VALIDITY = 10.0

#: ``ManeuverShip``, the old name of :class:`~seahelm.ships.Ship` (a ship ready for manoeuvres
#: is a ship with a steering gear): deprecated (a warning on access).
__getattr__ = deprecated_names(__name__, {"ManeuverShip": ("seahelm.ships", "Ship", "seahelm.Ship")})


#: How a ship without a steering gear gets one, for the manoeuvres' errors: each manoeuvre
#: takes the ship (not a ``servo=``), so the way is through :func:`maneuver_ship`.
_GIVE_A_GEAR = ("`ship = maneuver_ship(ship, servo=ServoParams(...))` (from "
                "seahelm.analysis.maneuvers and seahelm.actuators.servo), then manoeuvre that ship")


def maneuver_ship(ship: Any, *, servo: ServoParams | None = None,
                  model: VesselModel | None = None, name: str | None = None) -> Ship:
    """A :class:`~seahelm.ships.Ship` with a steering gear, ready for manoeuvres.

    Parameters
    ----------
    ship : Ship, str, path-like or Params
        A ship, a catalog name (e.g. ``"kvlcc2-l7"``, ``"mariner-nonlinear"``), the path of a
        ship file, or a bare parameter set (then ``servo`` is required unless the parameter set
        equals a catalog ship's).
    servo : ServoParams, optional
        Steering gear (``rudder-servo``) replacing the ship's.
    model : VesselModel, optional
        The model (default: the ship's, or the one for the parameter type).
    name : str, optional
        Label (default: the ship's name, or the parameter class name).

    Returns
    -------
    Ship

    Raises
    ------
    ValueError
        For an unknown catalog name (listing the valid ones).
    ParameterError
        If the ship has no steering gear and none is given, or the model does not take the
        parameter set.
    """
    from ...ships import CATALOG, get_ship

    if isinstance(ship, Params):
        params = ship
        found = next((s for s in map(CATALOG.__getitem__, CATALOG)
                      if type(s.params) is type(params) and s.params == params
                      and s.steering_gear is not None), None) if servo is None else None
        if found is not None and model is None:
            base = found
        else:
            if model is None:
                model = model_for_params(type(params))
                if model is None:
                    raise ParameterError(
                        f"no default model for {type(params).__name__}; pass `model=`")
            if not isinstance(params, model.params_type):
                raise ParameterError(
                    f"model '{model.name}' takes {model.params_type.__name__}, got "
                    f"{type(params).__name__}")
            if servo is None:
                raise ParameterError(
                    ": no steering gear is known for this parameter set; give it one: "
                    f"{_GIVE_A_GEAR} (or a Ship with a steering gear)", field="servo")
            if not isinstance(servo, ServoParams):
                raise ParameterError(f"must be ServoParams, got {type(servo).__name__}",
                field="servo")
            # one construction (a Monte-Carlo study makes one ship per sample)
            return Ship(name=name or type(params).__name__, model=model, params=params,
                        steering_gear=_gear(servo))
    elif isinstance(ship, (Ship, str)) or hasattr(ship, "__fspath__"):
        base = get_ship(ship)
    else:
        raise ParameterError(
            "must be a Ship, a catalog name, a ship file path or a parameter set, got "
            f"{type(ship).__name__}", field="ship")
    changes: dict[str, Any] = {}
    if model is not None and model is not base.model:
        if not isinstance(base.params, model.params_type):
            raise ParameterError(
                f"model '{model.name}' takes {model.params_type.__name__}, got "
                f"{type(base.params).__name__}")
        changes["model"] = model
    if servo is not None:
        if not isinstance(servo, ServoParams):
            raise ParameterError(f"must be ServoParams, got {type(servo).__name__}", field="servo")
        if base.steering_gear is None or servo is not base.steering_gear.params:
            changes["steering_gear"] = _gear(servo)
    elif base.steering_gear is None:
        from ...ships import with_steering_gear

        raise ParameterError(
            f": ship '{base.name}' has no steering gear; give it one: {_GIVE_A_GEAR}, or a "
            "ship file's [steering_gear] (catalog ships with one: "
            f"{', '.join(with_steering_gear())})", field="servo")
    if name is not None and name != base.name:
        changes["name"] = name
    ship = dataclasses.replace(base, **changes) if changes else base
    if not _can_maneuver(ship.model):
        raise ParameterError(
            f": ship '{ship.name}' (model '{ship.model.name}') cannot run the standard "
            "manoeuvres: they need a 3-DOF model with surge, sway and yaw states (mmg, "
            "mariner) or a constant-speed steering model with a `speed` parameter (nomoto1, "
            f"nomoto2, voitkunsky); its states: {', '.join(ship.model.state_labels)}",
            field="ship")
    return ship


def sample_ships(base: Ship, params: Sequence[Params], servos: Sequence[ServoParams] | None,
                 names: Sequence[str]) -> list[Ship]:
    """The ships of Monte-Carlo samples of ``base``: its model, sample k's parameter set
    ``params[k]``, steering gear of ``servos[k]`` (default: the base's) and name ``names[k]``.

    Each equals ``maneuver_ship(params[k], servo=..., model=base.model, name=names[k])``. The
    first is built so (every check of :class:`~seahelm.ships.Ship` runs); the others are
    copies of it with their own parameter set, steering gear, name and test speed (the
    parameter set's design speed), which is all a check of that construction could find
    different between samples: same model and parameter type, no particulars, deep water.
    A study of 10,000 samples builds them in milliseconds instead of a second.

    Parameters
    ----------
    base : Ship
        The scenario's ship (with a steering gear).
    params : sequence of Params
        Each sample's parameter set (validated), of the base's parameter type.
    servos : sequence of ServoParams, optional
        Each sample's steering-gear parameters.
    names : sequence of str
        Each sample's name.

    Returns
    -------
    list of Ship
    """
    gear = base.servo if servos is None else None
    first = maneuver_ship(params[0], servo=gear if servos is None else servos[0],
                          model=base.model, name=names[0])
    out = [first]
    cls = type(params[0])
    speed_field = first._speed_field
    fields = {f.name: first.__dict__[f.name] for f in dataclasses.fields(Ship)}
    for k in range(1, len(params)):
        p = params[k]
        if type(p) is not cls or (servos is not None and type(servos[k]) is not ServoParams):
            out.append(maneuver_ship(p, servo=gear if servos is None else servos[k],
                                     model=base.model, name=names[k]))
            continue
        ship = object.__new__(Ship)  # (a copy of the first, frozen fields set in place)
        ship.__dict__.update(fields)
        ship.__dict__["params"] = p
        ship.__dict__["name"] = names[k]
        if servos is not None:
            ship.__dict__["steering_gear"] = _gear(servos[k])
        ship.__dict__["test_speed"] = (None if speed_field is None
                                       else float(getattr(p, speed_field)))
        out.append(ship)
    return out


@functools.lru_cache(maxsize=64)
def _can_maneuver(model: VesselModel) -> bool:
    """Whether a model can run the standard manoeuvres (a 3-DOF model with surge, sway and yaw
    states, or a constant-speed steering model): a property of the (frozen) model, asked
    once per model rather than at every manoeuvre call."""
    states = set(model.state_labels)
    return bool(({"sway_speed", "yaw_rate", "heading"} <= states
                 and states & {"surge_speed", "surge_perturbation"})
                or is_constant_speed(model))


@functools.lru_cache(maxsize=64)
def _gear(servo: ServoParams) -> Any:
    """The rudder-servo steering gear of ``servo`` (one object per parameter set)."""
    from ...ships import SteeringGear

    return SteeringGear(actuator="rudder-servo", params=servo,
                        provenance="given as a parameter set (ServoParams)")


def _ships(ship: Any) -> tuple[list[Ship], bool]:
    """One ship or a sequence of them (a ``ship`` dimension); all on one model."""
    if isinstance(ship, (list, tuple)):
        if not ship:
            raise ParameterError(": an empty sequence of ships", field="ship")
        if all(type(s) is Ship and s.steering_gear is not None for s in ship):
            # ready already (a Monte-Carlo study's samples): maneuver_ship would return each
            # unchanged after its model's check, which is one per model
            checked: dict[int, Ship] = {}
            for s in ship:
                if id(s.model) not in checked:
                    checked[id(s.model)] = maneuver_ship(s)
            ships = list(ship)
        else:
            ships = [maneuver_ship(s) for s in ship]
        models = {s.model.name for s in ships}
        if len(models) > 1:
            raise ParameterError(
                f": all ships of one batch must use one model, got {', '.join(models)}",
                field="ship")
        return ships, True
    return [maneuver_ship(ship)], False


def default_time_step(ship: Any, speed: float | None = None) -> float:
    """The integration step the manoeuvres use by default [s].

    dt = min(L/(100 U), T_δ) rounded down to 1, 2 or 5 × 10ⁿ s: a hundred steps per ship
    length travelled, and no longer than the steering gear's lag (the rudder's motion is
    resolved at any speed). For the KVLCC2 L7 model (L/U = 5.94 s, T_δ = 0.1 s) this is
    0.05 s; Mariner (20.9 s, 1 s) 0.2 s; KVLCC2 full scale (40.1 s, 0.68 s) 0.2 s. With RK4
    the turning-circle advance and tactical diameter then agree with a run at dt/4 to better
    than 0.001 %, and still to better than 0.1 % at 10× this step (:data:`STEP_VALIDITY`,
    beyond which a manoeuvre warns; ``benchmarks/bench_maneuvers.py`` checks both). The lag
    does not bound the step for stability: the engine takes the servo's states from its
    closed-form solution (:func:`seahelm.actuators.servo.limited_lag_advance`).

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path) or Params
        The ship (:func:`maneuver_ship`).
    speed : float, optional
        Approach speed [m/s] (default: the ship's).

    Returns
    -------
    float
        Time step [s].
    """
    return _time_step(maneuver_ship(ship), speed)


def _time_step(s: Ship, speed: float | None) -> float:
    """:func:`default_time_step` of a ship ready for manoeuvres (:func:`maneuver_ship`)."""
    U = s.approach_speed if speed is None else float(speed)
    check_positive("speed", U, "m/s")
    raw = min(s.length / (100.0 * U), float(s.servo.time_constant))
    exponent = math.floor(math.log10(raw))
    for mantissa in (5.0, 2.0, 1.0):
        value = mantissa * 10.0 ** exponent
        if value <= raw * (1 + 1e-12):
            return float(f"{value:.12g}")
    return float(f"{10.0 ** exponent:.12g}")  # pragma: no cover - mantissa 1 always fits


def usual_time_step(ships: Sequence[Ship], speeds: Any) -> float:
    """The smallest :func:`default_time_step` of the ships at any of the approach speeds.

    The step shrinks as the speed grows (dt ∝ L/U before rounding down), so it is each distinct
    ship (length, steering-gear lag) at the fastest speed: one evaluation per distinct ship,
    not one per ship and speed (10⁴ Monte-Carlo ships would make 10⁸).
    """
    fastest = max(float(u) for u in speeds)
    steps: dict[tuple[float, float], float] = {}
    for s in ships:
        key = (s.length, float(s.servo.time_constant))
        if key not in steps:  # (the ships of a plan are ready: no maneuver_ship again)
            steps[key] = (_time_step(s, fastest) if type(s) is Ship and s.steering_gear
                          is not None else default_time_step(s, fastest))
    return min(steps.values())


# ------------------------------------------------------------------------------------------
# grids of runs
# ------------------------------------------------------------------------------------------
def _identified_near(ship: Any) -> str:
    """"; its parameter set was identified near 1.18 m/s" (empty without a design speed)."""
    design = ship.approach_speed
    return (f"; the parameter set of '{ship.name}' was identified near {design:.4g} m/s"
            if math.isfinite(design) else "")


def _straight_run_speed(ship: Any, rps: float) -> float:
    try:
        return straight_run_speed(ship.params, rps, model=ship.model)
    except EquilibriumError as exc:
        raise EquilibriumError(f": no straight run of '{ship.name}' at {rps:.6g} 1/s "
                               f"({exc})", field="rps") from None


def yaw_lag(ship: Any) -> float:
    """The time a constant-speed model's yaw rate takes to build up [s]
    (:meth:`~seahelm.analysis.equilibria.constant_speed.ConstantSpeedPlant.lag`; T of Nomoto 1),
    added to the default durations of the manoeuvres; 0 for a model with a surge state (whose
    defaults stay as they were)."""
    if not is_constant_speed(ship.model):
        return 0.0
    return _lag(ship.model, ship.params)


@functools.lru_cache(maxsize=64)
def _lag(model: VesselModel, params: Params) -> float:
    from ..equilibria.constant_speed import ConstantSpeedPlant

    return ConstantSpeedPlant(params, model, EquilibriumError).lag()


def steady_yaw_rate(ship: Any, rudder: Any, approach: Approach) -> np.ndarray:
    """|r| [rad/s] of the steady turns at ``rudder`` [rad] from ``approach``
    (:func:`~seahelm.analysis.equilibria.equilibrium.steady_turn`), an error naming the approach and
    `t_final` (which skips the estimate that needs it) if there is none."""
    from ..equilibria.equilibrium import steady_turn

    try:
        return np.abs(steady_turn(ship.params, rudder, approach.rps, model=ship.model,
                                  max_rudder=ship.max_rudder).yaw_rate)
    except EquilibriumError as exc:
        raise _no_steady_turn(ship, rudder, approach, str(exc)) from None


def _no_steady_turn(ship: Any, rudder: Any, approach: Approach, reason: str
                    ) -> EquilibriumError:
    deg = ", ".join(f"{math.degrees(d):.4g}" for d in np.atleast_1d(rudder))
    return EquilibriumError(
        f": no steady turn of '{ship.name}' at rudder {deg} deg from the approach "
        f"at {approach.speed:.6g} m/s, to estimate the manoeuvre's duration ({reason})"
        f"{_identified_near(ship)}; give `t_final` to skip the estimate", field="t_final")


def steady_yaw_rates(groups: Sequence[tuple[Any, Any, Approach]]) -> list[np.ndarray]:
    """:func:`steady_yaw_rate` of many (ship, rudder angles, approach) groups in one batch.

    The steady turns of all groups are solved together
    (:func:`~seahelm.analysis.equilibria.batch_steady_turn.steady_turns`, the one-at-a-time
    :func:`~seahelm.analysis.equilibria.equilibrium.steady_turn` for a run that fails there), one
    batch per model; the results equal :func:`steady_yaw_rate`'s to the solvers' tolerance.

    Parameters
    ----------
    groups : sequence of (Ship, float or array_like, Approach)
        A ship, its rudder angle(s) δ [rad] and the approach whose rps the turns hold.

    Returns
    -------
    list of numpy.ndarray
        |r| [rad/s] per group, of the shape of its rudder angles.

    Raises
    ------
    EquilibriumError
        For the first group (in order) with a rudder angle without a steady turn, worded as
        :func:`steady_yaw_rate` words it.
    ParameterError
        If a rudder angle is beyond a ship's steering gear, or an rps is missing or not > 0.
    """
    from ..equilibria.batch_steady_turn import steady_turns

    shapes = [np.shape(d) for _, d, _ in groups]
    rates: list[np.ndarray | None] = [None] * len(groups)
    by_model: dict[int, list[int]] = {}
    for g, (ship, _, _) in enumerate(groups):
        by_model.setdefault(id(ship.model), []).append(g)
    failures: dict[int, str] = {}
    for members in by_model.values():
        params, rudders, rps, limits, spans = [], [], [], [], []
        for g in members:
            ship, d, a = groups[g]
            flat = np.ravel(np.asarray(d, dtype=float)).tolist()
            spans.append((len(rudders), len(rudders) + len(flat)))
            params.extend([ship.params] * len(flat))
            rudders.extend(flat)
            rps.extend([a.rps] * len(flat))
            limits.extend([ship.max_rudder] * len(flat))
        if not rudders:
            continue
        turns = steady_turns(groups[members[0]][0].model, params, np.array(rudders),
                             None if rps[0] is None else np.array(rps, dtype=float),
                             max_rudder=np.array(limits))
        ok, yaw = turns.ok, np.abs(turns.yaw_rate)
        for g, (lo, hi) in zip(members, spans):
            if not ok[lo:hi].all():
                failures[g] = turns.message[lo + int(np.argmin(ok[lo:hi]))]
            rates[g] = yaw[lo:hi].reshape(shapes[g])
    if failures:
        g = min(failures)
        ship, d, a = groups[g]
        raise _no_steady_turn(ship, d, a, failures[g])
    return rates  # type: ignore[return-value]
