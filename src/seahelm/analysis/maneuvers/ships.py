"""The ships of a manoeuvre: catalog entries with their steering gear, the usual time step,
and the steady straight approach (with the equilibrium failures named for the user)."""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from ..._validate import check_positive
from ...actuators.servo import ServoParams
from ...errors import ParameterError
from ...parameters import Params
from ...vessels.base import VesselModel
from ...vessels.mariner import MARINER_SERVO
from ...vessels.mmg import KVLCC2_FULL_SERVO, KVLCC2_L7_SERVO
from ..equilibrium import (
    DEFAULT_MODELS,
    EquilibriumError,
    approach_state,
    straight_run_speed,
)

__all__ = ["STEERING_GEAR", "ManeuverShip", "maneuver_ship", "default_time_step"]

#: Steering gear of the catalog entries that have one (the presets of the vessel modules).
STEERING_GEAR: dict[str, ServoParams] = {
    "kvlcc2-full": KVLCC2_FULL_SERVO,
    "kvlcc2-l7": KVLCC2_L7_SERVO,
    "kvlcc2-l7-wp0-0.35": KVLCC2_L7_SERVO,
    "kvlcc2-l7-xp-0.5": KVLCC2_L7_SERVO,
    "mariner-nonlinear": MARINER_SERVO,
}

STARBOARD, PORT = 1, -1

#: An approach faster than this × the parameter set's speed warns (coefficients are identified
#: near one speed), as does a step longer than this × :func:`default_time_step`.
SPEED_VALIDITY = 1.5
STEP_VALIDITY = 10.0


@dataclasses.dataclass(frozen=True, eq=False)
class ManeuverShip:
    """A ship ready for manoeuvres: its model, parameter set, steering gear and a name.

    Attributes
    ----------
    name : str
        Label in results and tables (the catalog name for a catalog entry).
    model : VesselModel
        The 3-DOF model (signals as :mod:`seahelm.analysis.equilibrium` needs them).
    params : Params
        Its parameter set.
    servo : ServoParams
        Steering gear (``rudder-servo`` actuator): angle limit, rate limit, lag.
    """

    name: str
    model: VesselModel
    params: Params
    servo: ServoParams

    @property
    def length(self) -> float:
        """Ship length L [m] (the parameter set's ``length``)."""
        return float(self.params.length)

    @property
    def approach_speed(self) -> float:
        """Default approach (test) speed U_0 [m/s] of the parameter set."""
        p = self.params
        return float(getattr(p, "approach_speed", getattr(p, "nominal_speed", math.nan)))

    @property
    def max_rudder(self) -> float:
        """Steering-gear angle limit [rad]."""
        return float(self.servo.max_angle)

    @property
    def has_propeller(self) -> bool:
        """Whether the model has a ``propeller_rps`` input."""
        return "propeller_rps" in self.model.input_labels


def maneuver_ship(ship: Any, *, servo: ServoParams | None = None,
                  model: VesselModel | None = None, name: str | None = None) -> ManeuverShip:
    """A :class:`ManeuverShip` from a catalog name, catalog entry or parameter set.

    Parameters
    ----------
    ship : str, CatalogEntry, Params or ManeuverShip
        Catalog name (e.g. ``"kvlcc2-l7"``, ``"mariner-nonlinear"``), catalog entry, parameter
        set, or a ship already made (returned as is unless ``servo``/``model``/``name`` change
        it).
    servo : ServoParams, optional
        Steering gear. Default: :data:`STEERING_GEAR` for a catalog entry (or a parameter set
        equal to one); required otherwise.
    model : VesselModel, optional
        The model (default: the catalog entry's, or the one for the parameter type).
    name : str, optional
        Label (default: the catalog name, or the parameter class name).

    Returns
    -------
    ManeuverShip

    Raises
    ------
    ValueError
        For an unknown catalog name (listing the valid ones).
    ParameterError
        If no steering gear is known for the parameter set and none is given, or the model
        does not take the parameter set.
    """
    from ...registry import get_model
    from ...vessels.catalog import CATALOG, CatalogEntry, get

    if isinstance(ship, ManeuverShip):
        if servo is None and model is None and name is None:
            return ship
        return ManeuverShip(name=name or ship.name, model=model or ship.model,
                            params=ship.params, servo=servo or ship.servo)
    entry = None
    if isinstance(ship, str):
        entry = get(ship)
    elif isinstance(ship, CatalogEntry):
        entry = ship
    elif isinstance(ship, Params):
        entry = next((e for e in CATALOG.values()
                      if type(e.params) is type(ship) and e.params == ship
                      and e.name in STEERING_GEAR), None)
    else:
        raise ParameterError(
            "`ship` must be a catalog name, a catalog entry, a parameter set or a "
            f"ManeuverShip, got {type(ship).__name__}")
    params = entry.params if entry is not None and not isinstance(ship, Params) else ship
    if model is None:
        model = get_model(entry.model) if entry is not None else DEFAULT_MODELS.get(type(params))
        if model is None:
            raise ParameterError(
                f"no default model for {type(params).__name__}; pass `model=`")
    if not isinstance(params, model.params_type):
        raise ParameterError(
            f"model '{model.name}' takes {model.params_type.__name__}, got "
            f"{type(params).__name__}")
    if servo is None:
        servo = STEERING_GEAR.get(entry.name) if entry is not None else None
        if servo is None:
            raise ParameterError(
                "`servo`: no steering gear is known for this parameter set; pass "
                "`servo=ServoParams(...)` (known for the catalog entries "
                f"{', '.join(sorted(STEERING_GEAR))})")
    if not isinstance(servo, ServoParams):
        raise ParameterError(f"`servo` must be ServoParams, got {type(servo).__name__}")
    label = name or (entry.name if entry is not None else type(params).__name__)
    return ManeuverShip(name=label, model=model, params=params, servo=servo)


def _ships(ship: Any) -> tuple[list[ManeuverShip], bool]:
    """One ship or a sequence of them (a ``ship`` dimension); all on one model."""
    if isinstance(ship, (list, tuple)):
        if not ship:
            raise ParameterError("`ship`: an empty sequence of ships")
        ships = [maneuver_ship(s) for s in ship]
        models = {s.model.name for s in ships}
        if len(models) > 1:
            raise ParameterError(
                f"`ship`: all ships of one batch must use one model, got {', '.join(models)}")
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
    ship : str, CatalogEntry, Params or ManeuverShip
        The ship (:func:`maneuver_ship`).
    speed : float, optional
        Approach speed [m/s] (default: the ship's).

    Returns
    -------
    float
        Time step [s].
    """
    s = maneuver_ship(ship)
    U = s.approach_speed if speed is None else float(speed)
    check_positive("speed", U, "m/s")
    raw = min(s.length / (100.0 * U), float(s.servo.time_constant))
    exponent = math.floor(math.log10(raw))
    for mantissa in (5.0, 2.0, 1.0):
        value = mantissa * 10.0 ** exponent
        if value <= raw * (1 + 1e-12):
            return float(f"{value:.12g}")
    return float(f"{10.0 ** exponent:.12g}")  # pragma: no cover - mantissa 1 always fits


def usual_time_step(ships: Sequence["ManeuverShip"], speeds: Any) -> float:
    """The smallest :func:`default_time_step` of the ships at any of the approach speeds.

    The step shrinks as the speed grows (dt ∝ L/U before rounding down), so it is each distinct
    ship (length, steering-gear lag) at the fastest speed: one evaluation per distinct ship,
    not one per ship and speed (10⁴ Monte-Carlo ships would make 10⁸).
    """
    fastest = max(float(u) for u in speeds)
    steps: dict[tuple[float, float], float] = {}
    for s in ships:
        key = (s.length, float(s.servo.time_constant))
        if key not in steps:
            steps[key] = default_time_step(s, fastest)
    return min(steps.values())


# ------------------------------------------------------------------------------------------
# grids of runs
# ------------------------------------------------------------------------------------------
class Approach(NamedTuple):
    """Steady straight approach of one ship at one speed."""

    state: np.ndarray
    rudder: float
    rps: float | None
    speed: float


@functools.lru_cache(maxsize=512)
def _approach(model: VesselModel, params: Params, speed: float) -> Approach:
    a = approach_state(params, speed, model=model, trim=True)
    state = a.state.copy()
    state.setflags(write=False)
    return Approach(state, float(a.inputs["rudder_angle"]), a.inputs.get("propeller_rps"),
                    float(speed))


def steady_approach(model: VesselModel, params: Params, speed: float) -> Approach:
    """The trimmed straight approach of :func:`~seahelm.analysis.equilibrium.approach_state`.

    Memoised per (model, parameter set, speed): parameter sets are frozen, so the equilibrium
    of a ship at a speed is computed once per process (the self-propulsion rps and the trim
    take a few tens of milliseconds, more than a short manoeuvre's simulation).
    """
    return _approach(model, params, float(speed))


def _identified_near(ship: Any) -> str:
    """"; its parameter set was identified near 1.18 m/s" (empty without a design speed)."""
    design = ship.approach_speed
    return (f"; the parameter set of '{ship.name}' was identified near {design:.4g} m/s"
            if math.isfinite(design) else "")


def _straight_run_speed(ship: Any, rps: float) -> float:
    try:
        return straight_run_speed(ship.params, rps, model=ship.model)
    except EquilibriumError as exc:
        raise EquilibriumError(f"`rps`: no straight run of '{ship.name}' at {rps:.6g} 1/s "
                               f"({exc})") from None


def steady_yaw_rate(ship: Any, rudder: Any, approach: Approach) -> np.ndarray:
    """|r| [rad/s] of the steady turns at ``rudder`` [rad] from ``approach``
    (:func:`~seahelm.analysis.equilibrium.steady_turn`), an error naming the approach and
    `t_final` (which skips the estimate that needs it) if there is none."""
    from ..equilibrium import steady_turn

    try:
        return np.abs(steady_turn(ship.params, rudder, approach.rps, model=ship.model,
                                  max_rudder=ship.max_rudder).yaw_rate)
    except EquilibriumError as exc:
        deg = ", ".join(f"{math.degrees(d):.4g}" for d in np.atleast_1d(rudder))
        raise EquilibriumError(
            f"`t_final`: no steady turn of '{ship.name}' at rudder {deg} deg from the approach "
            f"at {approach.speed:.6g} m/s, to estimate the manoeuvre's duration ({exc})"
            f"{_identified_near(ship)}; give `t_final` to skip the estimate") from None
