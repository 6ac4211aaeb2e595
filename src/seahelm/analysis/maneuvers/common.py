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
(:func:`seahelm.analysis.equilibria.equilibrium.approach_state` with ``trim=True``): surge at the
approach speed, the MMG propeller at its self-propulsion rps (held constant through the manoeuvre),
the rudder at the trim angle that keeps the yaw rate zero (0 for the KVLCC2; about −1.11° for the
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
from typing import TYPE_CHECKING, Any

import numpy as np

from ..._validate import as_float_array, check_positive
from ...actuators.servo import RUDDER_SERVO
from ...control.open_loop import OPEN_LOOP
from ...errors import ParameterError, ValidityRangeWarning, deprecated_names
from ...resources import WorkTooLarge
from ...simulation.batch import BatchAxis, BatchLayout, simulate_batch
from ...simulation.memory import RecordingTooLarge
from ...simulation.problem import Problem
from ...vessels.base import VesselModel
from ..equilibria.equilibrium import EquilibriumError
from .datasets import _indexless_dataset, _single_run_dataset, _variable, _xarray
from .ships import (  # re-exported: the manoeuvres and tests import them from here
    SPEED_VALIDITY, STEP_VALIDITY, maneuver_ship, _ships, default_time_step, usual_time_step,
    Approach, steady_approach, steady_approaches, _identified_near, _straight_run_speed,
)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ...results import SimResult
    from ...ships import Ship

#: ``ManeuverShip``, the old name of :class:`~seahelm.ships.Ship`: deprecated.
__getattr__ = deprecated_names(__name__, {"ManeuverShip": ("seahelm.ships", "Ship",
                                                          "seahelm.Ship")})

__all__ = [
    "maneuver_ship",
    "default_time_step",
]

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


def value_axis(name: str, value: Any, units: str, *, positive: bool = False,
               attrs: Mapping[str, str] | None = None) -> Axis:
    """An axis from a scalar (no dimension) or a 1-D sequence (a dimension)."""
    arr = as_float_array(name, value, units)
    if arr.ndim > 1 or arr.size == 0:
        raise ParameterError(
            f"must be a number or a non-empty 1-D sequence [{units}], got shape "
            f"{arr.shape}", field=name)
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
            f"must be +1 (starboard), -1 (port) or a sequence of them [-], got {sides!r}",
            field="sides")
    return Axis(name="side", values=flat.astype(np.int64), units="", is_dim=arr.ndim == 1,
                attrs={"long_name": "side of the turn: +1 starboard, -1 port"})


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
                f": model '{self.ships[0].model.name}' has no propeller_rps input, "
                f"got {rps!r} [1/s]", field="rps")
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
        self.warned = False  #: whether a ValidityRangeWarning was issued (speed, time step)
        self.approaches: dict[tuple[int, int], Approach] = {}
        #: (ship, speed) -> why its approach was not found; its runs are left out of the batch
        self.failed: dict[tuple[int, int], str] = {}
        self._solve_approaches(speeds, ship_dim)
        if not speed_axis.is_dim and n_ships == 1:
            speed_axis.values = speeds[0].copy()
        self.axes = [ship_axis, speed_axis, *axes]
        if len({a.name for a in self.axes}) != len(self.axes):  # pragma: no cover - internal
            raise ValueError(f"duplicate axis names {[a.name for a in self.axes]}")
        self.shape = tuple(a.size for a in self.axes)

    def freeze(self) -> "Plan":
        """The plan with its axes' values read-only (kept for later requests, :mod:`.prepared`, it
        gives them to every result's coordinates: none may change the next one's)."""
        for values in [a.values for a in self.axes] + [c[0] for a in self.axes
                                                        for c in a.coords.values()]:
            values.flags.writeable = False
        return self

    def _layout(self) -> BatchLayout | None:
        """The batch's layout: the grid's dimensions (None for a single run)."""
        dims = [BatchAxis(name=a.name, values=a.values, units=a.units) for a in self.axes
                if a.is_dim]
        return BatchLayout(axes=tuple(dims)) if dims else None

    @functools.cached_property
    def index(self) -> list[dict[str, int]]:
        """Each run's position along every axis by name, in C order (built when first asked:
        a batch of many ships reads :meth:`run_values` instead)."""
        names = [a.name for a in self.axes]
        return [dict(zip(names, idx)) for idx in itertools.product(
            *(range(n) for n in self.shape))]

    def _solve_approaches(self, speeds: np.ndarray, ship_dim: bool) -> None:
        """Every (ship, speed)'s steady approach in one batch (:func:`steady_approaches`).

        A batch of ships records a ship's failure in :attr:`failed` (its runs are not
        simulated, their metrics are NaN and their message the reason) and gives it a stand-in
        approach that is never run; a single ship's failure, or every ship's, raises.
        """
        keys = []
        for i, s in enumerate(self.ships):
            design = s.approach_speed
            for j, U in enumerate(speeds[i]):
                if math.isfinite(design) and U > SPEED_VALIDITY * design:
                    warnings.warn(
                        f"approach speed {U:.4g} m/s is {U / design:.3g} x the speed of "
                        f"'{s.name}''s parameter set ({design:.4g} m/s): its hydrodynamic "
                        "coefficients were identified near that speed", ValidityRangeWarning,
                        stacklevel=4)
                    self.warned = True
                keys.append((i, j))
        solved = steady_approaches(self.model, [self.ships[i].params for i, _ in keys],
                                   [float(speeds[i][j]) for i, j in keys])
        for (i, j), a in zip(keys, solved):
            if isinstance(a, Approach):
                self.approaches[(i, j)] = a
                continue
            s, U = self.ships[i], float(speeds[i][j])
            why = f"no straight approach of '{s.name}' at {U:.6g} m/s ({a})"
            if not ship_dim or len(self.failed) + 1 == len(keys):
                every = "" if not ship_dim else f"none of the {len(keys)} approaches: "
                depth = float(s.water_depth or math.inf)
                if not ship_dim and math.isfinite(depth):  # (barely above the keel: say so)
                    draft = float(getattr(s.particulars, "draft", None) or s.params.draft)
                    raise EquilibriumError(
                        f"= {depth:g} m is {depth / draft:.4g} x the draft ({draft:.4g} m): "
                        f"{why}; give deeper water", field="water_depth", unit="m",
                        value=depth)
                raise EquilibriumError(f": {every}{why}{_identified_near(s)}",
                                       field="speed")
            self.failed[(i, j)] = why
        if self.failed:
            stand_in = next(iter(self.approaches.values()))
            for (i, j) in self.failed:
                self.approaches[(i, j)] = stand_in._replace(speed=float(speeds[i][j]))

    # -- per run ------------------------------------------------------------------------
    @functools.cached_property
    def run_ok(self) -> np.ndarray:
        """Whether each run's approach was found (False: left out of the batch), (runs,)."""
        if not self.failed:
            return np.ones(self.n_runs, dtype=bool)
        speed_pos = self._positions[1]
        return np.array([(i, j) not in self.failed
                         for i, j in zip(self._positions[0].tolist(), speed_pos.tolist())])

    def run_failure(self, run: int) -> str | None:
        """Why run ``run``'s approach was not found (None if it was)."""
        i = self.index[run]
        return self.failed.get((i["ship"], i["approach_speed" if "approach_speed" in i
                                            else "approach_rps"]))

    @property
    def n_runs(self) -> int:
        return math.prod(self.shape)

    @property
    def model(self) -> VesselModel:
        return self.ships[0].model

    def ship(self, run: int) -> "Ship":
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
        if self.n_runs == 1:  # (one run: position 0 on every axis, without np.indices)
            return np.zeros((len(self.shape), 1), dtype=int)  # (np.indices' dtype)
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
        return self._lengths[self._positions[0]]

    @functools.cached_property
    def _lengths(self) -> np.ndarray:
        """Each ship's length L [m] (asked for three times by a manoeuvre)."""
        return np.array([s.length for s in self.ships])

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
        """Run the grid as one batch (the engine validates the rest): :meth:`run` of
        :meth:`problem`.

        ``controller_every`` steps per controller sample: an open-loop schedule that changes
        only at recorded samples can be sampled there (the engine evaluates the model's
        outputs at every controller sample). ``conditions``
        (:class:`~seahelm.environment.loads.Conditions`): wind, waves and current acting from
        t = 0 on (the approach is the calm-water one).
        """
        return self.run(self.problem(
            x0=x0, actuator_x0=actuator_x0, t_final=t_final, dt=dt, record_every=record_every,
            reference=reference, controller=controller, controller_params=controller_params,
            metadata=metadata, controller_every=controller_every, conditions=conditions,
            stacklevel=4))

    def problem(self, *, x0: np.ndarray, actuator_x0: np.ndarray, t_final: float, dt: float,
                record_every: int, reference: Any = None, controller: Any = OPEN_LOOP,
                controller_params: Any = None, metadata: Mapping[str, Any] | None = None,
                controller_every: int = 1, conditions: Any = None,
                stacklevel: int = 3) -> Problem:
        """The grid's batch as a validated :class:`~seahelm.simulation.problem.Problem` (the
        arguments of :meth:`simulate`); warns (``stacklevel``: at the manoeuvre's caller) and
        sets :attr:`warned` for a ``dt`` beyond :data:`STEP_VALIDITY` × the usual step."""
        usual = usual_time_step(self.ships, [a.speed for a in self.approaches.values()])
        if dt > STEP_VALIDITY * usual:
            warnings.warn(f"`dt` = {dt:g} s is {dt / usual:.3g} x the usual step of this ship "
                          f"({usual:g} s = min(L/(100 U0), servo lag)): the manoeuvre's events "
                          "may be missed or wrong", ValidityRangeWarning, stacklevel=stacklevel)
            self.warned = True
        layout = self._layout()
        runs = np.arange(self.n_runs)
        extra = _conditions_kwargs(conditions, self.model)
        if self.failed:  # only the runs with an approach (scattered back below)
            runs = np.flatnonzero(self.run_ok)
            x0, actuator_x0, reference, controller_params, extra = (
                _select_runs(v, runs, self.n_runs)
                for v in (x0, actuator_x0, reference, controller_params, extra))
        batch = Problem(
            model=self.model,
            params=(self.ships[0].params if len(self.ships) == 1
                    else [self.ship(i).params for i in runs.tolist()]),
            x0=x0, t_final=t_final, dt=dt, actuator=RUDDER_SERVO,
            actuator_params=(self.ships[0].servo if len(self.ships) == 1
                             else [self.ship(i).servo for i in runs.tolist()]),
            actuator_x0=actuator_x0, controller=controller,
            controller_params=controller_params, reference=reference,
            controller_dt=controller_every * dt,
            record_every=record_every, metadata=dict(metadata or {}),
            layout=None if self.failed else layout, **extra)
        return batch  # (the engine uses no more threads than runs: a small batch wakes none)

    def run(self, batch: Problem) -> "SimResult":
        """Run the grid's batch (:meth:`problem`; the same one again gives the same result); a
        batch too large for memory or the work guard in the manoeuvre's words."""
        try:  # (a plan that failed some approaches: their runs scattered back as not run)
            result = simulate_batch(batch)
            return result if not self.failed else _scatter_runs(
                result, np.flatnonzero(self.run_ok), self.n_runs, self._layout())
        except (WorkTooLarge, RecordingTooLarge) as exc:  # in the manoeuvre's words
            too_much = (exc.over if isinstance(exc, WorkTooLarge)
                        else f"it would record {exc.size_text()}")
            shallow = [s for s in self.ships if math.isfinite(s.water_depth or math.inf)]
            if shallow:  # (a ship in very shallow water barely turns or stops: say so)
                found = shallow[0]
                depth = float(found.water_depth)
                draft = float(getattr(found.particulars, "draft", None) or found.params.draft)
                raise ParameterError(
                    f"= {depth:g} m is {depth / draft:.4g} x the draft ({draft:.4g} m): there "
                    f"the ship's predicted motion (its steady yaw rate, its stopping) is so slow "
                    f"that the manoeuvre would last {batch.t_final:.3g} s: {too_much}; give deeper "
                    "water", field="water_depth", unit="m", value=depth) from None
            if isinstance(exc, WorkTooLarge):
                usual = usual_time_step(self.ships, [a.speed for a in self.approaches.values()])
                raise ParameterError(
                    f"= {batch.dt:g} s: {exc.over}; a larger `dt` (the usual step of this ship is "
                    f"{usual:.3g} s), a shorter `t_final` or fewer runs {exc.anyway}",
                    field="dt", unit="s", value=batch.dt) from None
            slowest = min(a.speed for a in self.approaches.values())
            raise ParameterError(
                f": {self.n_runs} run(s) of {batch.t_final:.6g} s (at the slowest approach "
                f"speed, {slowest:.4g} m/s) would record {exc.size_text()}; give a faster "
                "approach (`speed` or `rps`) or a shorter `t_final`", field="t_final") from None

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
        grid_dims: tuple[str, ...] = self.dims
        if not grid_dims and not self.failed and not extra_dims and not coords:
            # a single run (the grid has no dimension): its 0-d variables put in place at once
            single = _single_run_dataset(variables, self._coords(), dict(attrs or {}))
            if single is not None:
                return single
        data = {}
        grid_shape = self.dim_shape
        failed = np.flatnonzero(~self.run_ok) if self.failed else None
        for name, (values, units, long_name) in variables.items():
            arr = np.asarray(values)
            if failed is not None and arr.shape[:1] == (self.n_runs,):
                arr = _mask_failed(self, name, arr, failed)
            if arr.dtype.kind == "O":
                arr = arr.astype(str)
            dims, shape = grid_dims, grid_shape
            if arr.ndim == 2:
                dim, k = (extra_dims or {})[name]
                dims, shape = dims + (dim,), shape + (k,)
            var_attrs = {"long_name": long_name, "units": units} if units else {
                "long_name": long_name}
            if arr.shape != shape:
                arr = arr.reshape(shape)
            # a plain numeric, boolean or string array is what xarray would make of it anyway
            # (its conversions concern objects, dates and other array types): skip them
            data[name] = _variable(dims, arr, var_attrs, own=True)
        all_coords = self._coords()
        all_coords.update(coords or {})
        if not any(np.ndim(c[1]) for c in all_coords.values()):
            # a single run: scalar coordinates need no index
            coord_vars = {}
            for k, (cdims, cvalues, cattrs) in all_coords.items():
                carr = np.asarray(cvalues)  # (what xarray makes of a scalar: skip its checks)
                coord_vars[k] = _variable(cdims, carr, cattrs)
            fast = _indexless_dataset(data, coord_vars, dict(attrs or {}))
            if fast is not None:
                return fast
            xr = _xarray()
            return xr.Dataset(data, coords=xr.Coordinates(coord_vars, indexes={}),
                              attrs=dict(attrs or {}))
        return _xarray().Dataset(data, coords=all_coords, attrs=dict(attrs or {}))

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


def _select_runs(value: Any, runs: np.ndarray, n: int) -> Any:
    """``value`` (an array, a list or a dict of them over the grid's runs) for ``runs`` only;
    what does not run along the first axis (one value for all) as it is."""
    if isinstance(value, Mapping):
        return {k: _select_runs(v, runs, n) for k, v in value.items()}
    if isinstance(value, list) and len(value) == n:
        return [value[i] for i in runs.tolist()]
    if isinstance(value, np.ndarray) and value.ndim and value.shape[0] == n and n > 1:
        return value[runs]
    return value


def _scatter_runs(result: "SimResult", runs: np.ndarray, n: int, layout: Any) -> "SimResult":
    """The result of the runs ``runs`` as a result over all ``n`` runs of the grid: the others
    NaN, status :attr:`~seahelm.simulation.engine.RunStatus.NOT_RUN`, parameters NaN."""
    from ...simulation.engine import RunStatus

    def full(a: np.ndarray, fill: Any = np.nan) -> np.ndarray:
        if a.shape[0] != runs.size:  # (one row for all runs)
            return a
        out = np.full((n,) + a.shape[1:], fill, dtype=np.result_type(a, type(fill)))
        out[runs] = a
        return out

    return dataclasses.replace(
        result, state=full(result.state), output=full(result.output),
        command=full(result.command), reference=full(result.reference),
        disturbance=full(result.disturbance),
        status=full(result.status, int(RunStatus.NOT_RUN)).astype(result.status.dtype),
        failure_time=full(result.failure_time), failure_state=full(result.failure_state),
        params={k: (cls, full(np.broadcast_to(arr, (runs.size, arr.shape[-1]))))
                for k, (cls, arr) in result.params.items()},
        layout=layout)


def _mask_failed(plan: "Plan", name: str, arr: np.ndarray, failed: np.ndarray) -> np.ndarray:
    """A metric with the runs left out (no approach) as NaN / False, their message the
    reason."""
    out = arr.copy()
    if name == "message":
        out = out.astype(object)
        for i in failed.tolist():
            out[i] = f"not run: {plan.run_failure(i)}"
    elif out.dtype.kind == "f":
        out[failed] = np.nan
    elif out.dtype.kind == "b":
        out[failed] = False
    return out


def _conditions_kwargs(conditions: Any, model: VesselModel) -> dict[str, Any]:
    """The engine's environment and current arguments for a manoeuvre's ``conditions``."""
    if conditions is None:
        return {}
    from ...environment.loads import Conditions

    if not isinstance(conditions, Conditions):
        raise ParameterError(f"must be a Conditions (seahelm.environment.loads), "
                             f"got {type(conditions).__name__}", field="conditions")
    current = conditions.disturbance(model)
    return {"environment": conditions.environment,
            "environment_params": conditions.params,
            "disturbance": current or None}


def record_every_for(dt: float, record_dt: float | None, t_final: float | None = None) -> int:
    """Steps per recorded sample for a wanted recording interval (default: every step); a
    ``record_dt`` longer than ``t_final`` [s] (nothing recorded after t = 0) is refused."""
    if record_dt is None:
        return 1
    check_positive("record_dt", record_dt, "s")
    if t_final is not None and record_dt > t_final:
        raise ParameterError(f"= {record_dt!r} s is longer than `t_final` = {t_final:.6g} s: "
                             "nothing after t = 0 would be recorded", field="record_dt",
                             unit="s", value=record_dt)
    ratio = float(record_dt) / dt
    if ratio < 1.0 - 1e-9 or abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1.0):
        raise ParameterError(f"must be a whole multiple of `dt` [s]: "
                             f"record_dt={record_dt!r}, dt={dt!r}", field="record_dt")
    return max(1, int(round(ratio)))


def final_time(t_final: float, dt: float, name: str = "t_final") -> float:
    """``t_final`` rounded up to a whole number of steps (at least one step: a duration
    shorter than ``dt`` is an error, not one step of ``dt``)."""
    if t_final < dt * (1.0 - 1e-9):
        raise ParameterError(f"must be at least one step `dt` [s]: {name}={t_final!r}, "
                             f"dt={dt!r}", field=name)
    return math.ceil(t_final / dt - 1e-9) * dt


def check_rudder(ships: Sequence["Ship"], name: str, values: np.ndarray, *,
                 allow_zero: bool = False, positive: bool = False) -> None:
    """|δ| within the steering gear's limit of every ship (ParameterError naming it); with
    ``positive``, δ > 0 (a manoeuvre whose side is its ``sides``: a negative angle on side +1
    turned to port labelled starboard, issue 43's mixed-sign turns)."""
    if np.ndim(values) <= 1 and np.size(values) <= 8 and _rudders_fit(ships, values, allow_zero,
                                                                    positive):
        return  # (a few angles, all within every limit: no numpy pass to take)
    if positive and np.any(np.asarray(values) < 0):
        v = float(np.asarray(values).ravel()[np.flatnonzero(np.asarray(values).ravel() < 0)[0]])
        raise ParameterError(f"must be > 0 [rad]: the side of the turn is `sides` (+1 "
                             f"starboard, -1 port), got {v!r}", field=name, unit="rad", value=v)
    seen: set[float] = set()
    for s in ships:
        limit = s.max_rudder
        if limit in seen:  # (the samples of a study mostly share their steering gear's)
            continue
        seen.add(limit)
        bad = ~((np.abs(values) <= limit * (1 + 1e-12)) & ((np.abs(values) > 0) | allow_zero))
        if np.any(bad):
            v = float(np.asarray(values).ravel()[np.flatnonzero(np.asarray(bad).ravel())[0]])
            lo = "[0" if allow_zero else "(0"
            raise ParameterError(
                f"must be in {lo}, {limit:.6g}] [rad] in magnitude (the steering "
                f"gear limit of '{s.name}', {math.degrees(limit):.4g} deg), got {v!r}", field=name)


def _rudders_fit(ships: Sequence["Ship"], values: Any, allow_zero: bool,
                 positive: bool) -> bool:
    """Whether a few rudder angles pass :func:`check_rudder`: its tests in Python floats, the
    same comparisons as its array form (a NaN passes none), so that it has nothing to report
    and no numpy pass to take (False: the array form finds what to report)."""
    angles = np.asarray(values, dtype=float).ravel().tolist()
    if positive and any(v < 0.0 for v in angles):
        return False
    limits = {s.max_rudder for s in ships} if len(ships) > 1 else (ships[0].max_rudder,)
    return all(abs(v) <= limit * (1 + 1e-12) and (abs(v) > 0 or allow_zero)
               for limit in limits for v in angles)
