"""Shared machinery of the manoeuvre library: ships, batch grids, time steps, results.

A manoeuvre function (:func:`~seahelm.analysis.maneuvers.turning_circle`,
:func:`~seahelm.analysis.maneuvers.zigzag`, ...) builds a grid of runs over what varies —
ships (parameter sets), approach speeds, rudder angles, sides — runs it as **one** batch
through :func:`seahelm.simulation.batch.simulate_batch` and returns a
:class:`~seahelm.analysis.maneuvers.result.ManeuverResult`:

``runs``
    the time series, an :class:`xarray.Dataset` with dims ``(*batch_dims, time)`` as
    :meth:`seahelm.results.SimResult.to_xarray` gives them;
``metrics``
    the metrics table: an :class:`xarray.Dataset` over the batch dims (no ``time``), one
    variable per metric with ``units`` and ``long_name`` attributes, SI units and radians,
    NaN where an event was not reached, a boolean ``complete`` and a string ``message`` per
    run that says what was not reached (or ``"ok"``).

A batch dimension exists only for an argument given as a sequence ("dims are named after what
varies"): ``ship`` (index, with the coordinate ``ship_name``), ``approach_speed`` [m/s],
``rudder`` [rad], ``side`` (+1 starboard, −1 port) and the manoeuvre's own. A single run has
no batch dimension at all.

Every manoeuvre starts from a steady straight approach
(:func:`seahelm.analysis.equilibrium.approach_state` with ``trim=True``): surge at the approach
speed, the MMG propeller at its self-propulsion rps (held constant through the manoeuvre), the
rudder at the trim angle that keeps the yaw rate zero (0 for the KVLCC2; about −0.87° for the
Mariner with its single-screw bias Y_0, N_0), heading 0 (north), position at the origin. The
rudder is **ordered** at t = 0 to the manoeuvre's absolute angle and moves there through the
steering gear (rate- and angle-limited servo, ``rudder-servo``), so its travel time counts.
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
import math
import warnings
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..._validate import as_float_array, check_positive
from ...actuators.servo import RUDDER_SERVO, ServoParams
from ...control.open_loop import OPEN_LOOP
from ...errors import ParameterError, ValidityRangeWarning
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

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ...results import SimResult

__all__ = [
    "STEERING_GEAR",
    "ManeuverShip",
    "maneuver_ship",
    "default_time_step",
]

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
    length travelled, and no longer than the steering gear's lag. For the KVLCC2 L7 model
    (L/U = 5.94 s, T_δ = 0.1 s) this is 0.05 s; Mariner (20.9 s, 1 s) 0.2 s; KVLCC2 full scale
    (40.1 s, 0.68 s) 0.2 s. With RK4 the turning-circle advance and tactical diameter then
    agree with a run at dt/4 to better than 0.1 % (``benchmarks/bench_maneuvers.py`` checks
    it).

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
@dataclasses.dataclass
class Axis:
    """One axis of a manoeuvre grid (a batch dimension when ``is_dim``)."""

    name: str
    values: np.ndarray
    units: str = ""
    is_dim: bool = True
    coords: dict[str, tuple[np.ndarray, dict[str, str]]] = dataclasses.field(
        default_factory=dict)
    attrs: dict[str, str] = dataclasses.field(default_factory=dict)

    @property
    def size(self) -> int:
        return int(self.values.size)


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


def value_axis(name: str, value: Any, units: str, *, positive: bool = False,
               attrs: Mapping[str, str] | None = None) -> Axis:
    """An axis from a scalar (no dimension) or a 1-D sequence (a dimension)."""
    arr = as_float_array(name, value, units)
    if arr.ndim > 1 or arr.size == 0:
        raise ParameterError(
            f"`{name}` must be a number or a non-empty 1-D sequence [{units}], got shape "
            f"{arr.shape}")
    if positive:
        check_positive(name, arr, units)
    return Axis(name=name, values=np.atleast_1d(arr).astype(float), units=units,
                is_dim=arr.ndim == 1, attrs=dict(attrs or {}))


def side_axis(sides: Any) -> Axis:
    """The ``side`` axis: +1 starboard, −1 port (a dimension for a sequence)."""
    arr = np.asarray(sides)
    flat = np.atleast_1d(arr).ravel()
    if arr.ndim > 1 or flat.size == 0 or not all(v in (1, -1) for v in flat.tolist()):
        raise ParameterError(
            f"`sides` must be +1 (starboard), -1 (port) or a sequence of them [-], got {sides!r}")
    return Axis(name="side", values=flat.astype(np.int64), units="", is_dim=arr.ndim == 1,
                attrs={"long_name": "side of the turn: +1 starboard, -1 port"})


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


class Plan:
    """A grid of runs: ships × approach speeds × the manoeuvre's own axes (C order)."""

    def __init__(self, ship: Any, speed: Any, rps: Any, axes: Sequence[Axis]) -> None:
        self.ships, ship_dim = _ships(ship)
        n_ships = len(self.ships)
        ship_axis = Axis(name="ship", values=np.arange(n_ships), is_dim=ship_dim,
                         coords={"ship_name": (np.array([s.name for s in self.ships]),
                                               {"long_name": "ship (parameter set)"})})
        has_prop = self.ships[0].has_propeller
        if speed is not None and rps is not None:
            raise ParameterError(
                "give the approach `speed` [m/s] or the propeller `rps` [1/s], not both")
        if rps is not None and not has_prop:
            raise ParameterError(
                f"`rps`: model '{self.ships[0].model.name}' has no propeller_rps input, "
                f"got {rps!r} [1/s]")
        if rps is not None:
            rps_axis = value_axis("rps", rps, "1/s", positive=True)
            speeds = np.array([[_straight_run_speed(s, n) for n in rps_axis.values]
                               for s in self.ships])
            speed_values = speeds[0] if n_ships == 1 else rps_axis.values
            speed_axis = Axis(name="approach_speed" if n_ships == 1 else "approach_rps",
                              values=speed_values, units="m/s" if n_ships == 1 else "1/s",
                              is_dim=rps_axis.is_dim)
        elif speed is not None:
            speed_axis = value_axis("approach_speed", speed, "m/s", positive=True)
            speeds = np.tile(speed_axis.values, (n_ships, 1))
        else:
            speed_axis = Axis(name="approach_speed", values=np.array([math.nan]), units="m/s",
                              is_dim=False)
            speeds = np.array([[s.approach_speed] for s in self.ships])
        self.approaches: dict[tuple[int, int], Approach] = {}
        for i, s in enumerate(self.ships):
            for j, U in enumerate(speeds[i]):
                design = s.approach_speed
                if math.isfinite(design) and U > SPEED_VALIDITY * design:
                    warnings.warn(
                        f"approach speed {U:.4g} m/s is {U / design:.3g} x the speed of "
                        f"'{s.name}''s parameter set ({design:.4g} m/s): its hydrodynamic "
                        "coefficients were identified near that speed", ValidityRangeWarning,
                        stacklevel=3)
                try:
                    self.approaches[(i, j)] = steady_approach(s.model, s.params, float(U))
                except EquilibriumError as exc:
                    raise EquilibriumError(
                        f"`speed`: no straight approach of '{s.name}' at {U:.6g} m/s "
                        f"({exc}){_identified_near(s)}") from None
        if not speed_axis.is_dim and n_ships == 1:
            speed_axis.values = speeds[0].copy()
        self.axes = [ship_axis, speed_axis, *axes]
        names = [a.name for a in self.axes]
        if len(set(names)) != len(names):  # pragma: no cover - internal
            raise ValueError(f"duplicate axis names {names}")
        self.shape = tuple(a.size for a in self.axes)
        self.index = [dict(zip(names, idx)) for idx in itertools.product(
            *(range(n) for n in self.shape))]

    # -- per run ------------------------------------------------------------------------
    @property
    def n_runs(self) -> int:
        return len(self.index)

    @property
    def model(self) -> VesselModel:
        return self.ships[0].model

    def ship(self, run: int) -> ManeuverShip:
        return self.ships[self.index[run]["ship"]]

    def approach(self, run: int) -> Approach:
        i = self.index[run]
        return self.approaches[(i["ship"], i["approach_speed" if "approach_speed" in i
                                             else "approach_rps"])]

    def value(self, run: int, axis: str) -> Any:
        a = next(a for a in self.axes if a.name == axis)
        return a.values[self.index[run][axis]]

    @functools.cached_property
    def _positions(self) -> np.ndarray:
        """Each run's position along every axis, (axes, runs) in C order (as ``index``)."""
        return np.indices(self.shape).reshape(len(self.shape), -1)

    def run_values(self, axis: str) -> np.ndarray:
        """An axis's value of every run, (runs,): :meth:`value` for all runs at once."""
        pos = next(k for k, a in enumerate(self.axes) if a.name == axis)
        return self.axes[pos].values[self._positions[pos]]

    def run_approaches(self) -> list[Approach]:
        """The approach of every run: :meth:`approach` for all runs at once."""
        ship, speed = self._positions[0].tolist(), self._positions[1].tolist()
        return [self.approaches[key] for key in zip(ship, speed)]

    def run_lengths(self) -> np.ndarray:
        """Ship length L of every run [m], (runs,)."""
        return np.array([s.length for s in self.ships])[self._positions[0]]

    @property
    def dims(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.axes if a.is_dim)

    @property
    def dim_shape(self) -> tuple[int, ...]:
        return tuple(a.size for a in self.axes if a.is_dim)

    # -- the batch ----------------------------------------------------------------------
    def simulate(self, *, x0: np.ndarray, actuator_x0: np.ndarray, t_final: float, dt: float,
                 record_every: int, reference: Any = None, controller: Any = OPEN_LOOP,
                 controller_params: Any = None, metadata: Mapping[str, Any] | None = None,
                 controller_every: int = 1, conditions: Any = None) -> "SimResult":
        """Run the grid as one batch (the engine validates the rest).

        ``controller_every`` steps per controller sample: an open-loop schedule that changes
        only at recorded samples can be sampled there (the engine evaluates the model's
        outputs at every controller sample). ``conditions``
        (:class:`~seahelm.environment.loads.Conditions`): wind, waves and current acting from
        t = 0 on (the approach is the calm-water one).
        """
        from ...simulation.batch import BatchAxis, BatchLayout, RunBatch, simulate_batch
        from ...simulation.engine import RecordingTooLarge

        usual = usual_time_step(self.ships, [a.speed for a in self.approaches.values()])
        if dt > STEP_VALIDITY * usual:
            warnings.warn(f"`dt` = {dt:g} s is {dt / usual:.3g} x the usual step of this ship "
                          f"({usual:g} s = min(L/(100 U0), servo lag)): the manoeuvre's events "
                          "may be missed or wrong", ValidityRangeWarning, stacklevel=3)

        dims = [a for a in self.axes if a.is_dim]
        layout = None
        if dims:
            layout = BatchLayout(axes=tuple(
                BatchAxis(name=a.name, values=a.values, units=a.units) for a in dims))
        # (the engine uses no more threads than runs, so a small batch wakes no idle thread)
        batch = RunBatch(
            model=self.model,
            params=(self.ships[0].params if len(self.ships) == 1
                    else [self.ship(i).params for i in range(self.n_runs)]),
            x0=x0, t_final=t_final, dt=dt, actuator=RUDDER_SERVO,
            actuator_params=(self.ships[0].servo if len(self.ships) == 1
                             else [self.ship(i).servo for i in range(self.n_runs)]),
            actuator_x0=actuator_x0, controller=controller,
            controller_params=controller_params, reference=reference,
            controller_dt=controller_every * dt,
            record_every=record_every, metadata=dict(metadata or {}), layout=layout,
            **_conditions_kwargs(conditions, self.model))
        try:
            return simulate_batch(batch)
        except RecordingTooLarge as exc:  # name the manoeuvre's options, not the engine's
            slowest = min(a.speed for a in self.approaches.values())
            raise ParameterError(
                f"`t_final`: {self.n_runs} run(s) of {t_final:.6g} s (at the slowest approach "
                f"speed, {slowest:.4g} m/s) would record {exc.size_text()}; give a faster "
                "approach (`speed` or `rps`) or a shorter `t_final`"
            ) from None

    def runs_dataset(self, result: "SimResult") -> "xr.Dataset":
        """The result's Dataset with the grid's coordinates; a single run loses ``run``."""
        ds = result.to_xarray()
        if not self.dims:
            ds = ds.isel(run=0, drop=True)
        return self._decorate(ds)

    def dataset(self, variables: Mapping[str, tuple[Any, str, str]],
                extra_dims: Mapping[str, tuple[str, int]] | None = None,
                attrs: Mapping[str, Any] | None = None,
                coords: Mapping[str, Any] | None = None) -> "xr.Dataset":
        """A metrics Dataset over the grid's dims from per-run arrays.

        ``variables[name] = (values, units, long_name)`` with ``values`` of shape (runs,) or
        (runs, k); ``extra_dims[name] = (dim, k)`` names the trailing dimension of the latter;
        ``coords`` adds coordinates (e.g. along such a dimension). Strings are stored as
        fixed-width unicode, booleans as bool. Built in one Dataset construction (xarray's
        per-object overhead is most of the cost of a short manoeuvre).
        """
        import xarray as xr

        data = {}
        grid_dims: tuple[str, ...] = self.dims
        grid_shape = self.dim_shape
        for name, (values, units, long_name) in variables.items():
            arr = np.asarray(values)
            if arr.dtype == object:
                arr = arr.astype(str)
            dims, shape = grid_dims, grid_shape
            if arr.ndim == 2:
                dim, k = (extra_dims or {})[name]
                dims, shape = dims + (dim,), shape + (k,)
            var_attrs = {"long_name": long_name}
            if units:
                var_attrs["units"] = units
            arr = arr.reshape(shape)
            # a plain numeric, boolean or string array is what xarray would make of it anyway
            # (its conversions concern objects, dates and other array types): skip them
            data[name] = xr.Variable(dims, arr, var_attrs,
                                     fastpath=type(arr) is np.ndarray and arr.dtype.kind in "biufU")
        all_coords = self._coords()
        all_coords.update(coords or {})
        if not any(np.ndim(c[1]) for c in all_coords.values()):
            # a single run: scalar coordinates need no index
            coord_vars = {k: xr.Variable(*c) for k, c in all_coords.items()}
            fast = _indexless_dataset(data, coord_vars, dict(attrs or {}))
            if fast is not None:
                return fast
            return xr.Dataset(data, coords=xr.Coordinates(coord_vars, indexes={}),
                              attrs=dict(attrs or {}))
        return xr.Dataset(data, coords=all_coords, attrs=dict(attrs or {}))

    def _coords(self) -> dict[str, Any]:
        coords: dict[str, Any] = {}
        for a in self.axes:
            attrs = dict(a.attrs)
            if a.units:
                attrs["units"] = a.units
            if a.is_dim:
                coords[a.name] = (a.name, a.values, attrs)
                for cname, (cvalues, cattrs) in a.coords.items():
                    coords[cname] = (a.name, cvalues, cattrs)
            else:
                if not (a.name == "approach_speed" and np.isnan(a.values[0])):
                    coords[a.name] = ((), a.values[0], attrs)
                for cname, (cvalues, cattrs) in a.coords.items():
                    coords[cname] = ((), cvalues[0], cattrs)
        return coords

    def _decorate(self, ds: "xr.Dataset") -> "xr.Dataset":
        return ds.assign_coords(self._coords())

    def run_messages(self, result: "SimResult") -> list[str]:
        """'ok' or what diverged, per run."""
        return result.messages()


def _indexless_dataset(data: Mapping[str, Any], coords: Mapping[str, Any],
                       attrs: dict[str, Any]) -> "xr.Dataset | None":
    """A Dataset of ready :class:`xarray.Variable` objects that need no index, built directly.

    ``xr.Dataset(...)`` merges, aligns and copies every variable: for a single run's metrics
    (twenty 0-d variables) that took about 1 ms, half of a whole turning circle, where putting
    the variables in place takes microseconds. This does the latter through xarray's
    ``Dataset._construct_direct`` once it has checked what that constructor assumes: every
    variable a Variable, no name shared by data and coordinates, no dimension coordinate (which
    would need an index) and consistent dimension sizes. None when a check fails or this
    xarray lacks the constructor: the caller then builds the Dataset the ordinary way
    (``tests/test_analysis_maneuvers.py`` checks that both give identical Datasets).
    """
    import xarray as xr

    construct = getattr(xr.Dataset, "_construct_direct", None)
    if construct is None or set(data) & set(coords):  # pragma: no cover - other xarray
        return None
    variables = {**data, **coords}
    dims: dict[str, int] = {}
    for name, var in variables.items():
        if type(var) is not xr.Variable or name in var.dims:
            return None
        for dim, size in zip(var.dims, var.shape):
            if dims.setdefault(dim, size) != size:
                return None
    try:
        return construct(variables, set(coords), dims, attrs, {}, None)
    except TypeError:  # pragma: no cover - a changed signature
        return None


def _conditions_kwargs(conditions: Any, model: VesselModel) -> dict[str, Any]:
    """The engine's environment and current arguments for a manoeuvre's ``conditions``."""
    if conditions is None:
        return {}
    from ...environment.loads import Conditions

    if not isinstance(conditions, Conditions):
        raise ParameterError(f"`conditions` must be a Conditions (seahelm.environment.loads), "
                             f"got {type(conditions).__name__}")
    current = conditions.disturbance(model)
    return {"environment": conditions.environment,
            "environment_params": conditions.params,
            "disturbance": current or None}


def record_every_for(dt: float, record_dt: float | None) -> int:
    """Steps per recorded sample for a wanted recording interval (default: every step)."""
    if record_dt is None:
        return 1
    check_positive("record_dt", record_dt, "s")
    ratio = float(record_dt) / dt
    if ratio < 1.0 - 1e-9 or abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1.0):
        raise ParameterError(f"`record_dt` must be a whole multiple of `dt` [s]: "
                             f"record_dt={record_dt!r}, dt={dt!r}")
    return max(1, int(round(ratio)))


def final_time(t_final: float, dt: float, name: str = "t_final") -> float:
    """``t_final`` rounded up to a whole number of steps (at least one step: a duration
    shorter than ``dt`` is an error, not one step of ``dt``)."""
    if t_final < dt * (1.0 - 1e-9):
        raise ParameterError(f"`{name}` must be at least one step `dt` [s]: {name}={t_final!r}, "
                             f"dt={dt!r}")
    return math.ceil(t_final / dt - 1e-9) * dt


def check_rudder(ships: Sequence[ManeuverShip], name: str, values: np.ndarray, *,
                 allow_zero: bool = False) -> None:
    """|δ| within the steering gear's limit of every ship (ParameterError naming it)."""
    for s in ships:
        limit = s.max_rudder
        bad = ~((np.abs(values) <= limit * (1 + 1e-12)) & ((np.abs(values) > 0) | allow_zero))
        if np.any(bad):
            v = float(np.asarray(values).ravel()[np.flatnonzero(np.asarray(bad).ravel())[0]])
            lo = "[0" if allow_zero else "(0"
            raise ParameterError(
                f"`{name}` must be in {lo}, {limit:.6g}] [rad] in magnitude (the steering "
                f"gear limit of '{s.name}', {math.degrees(limit):.4g} deg), got {v!r}")
