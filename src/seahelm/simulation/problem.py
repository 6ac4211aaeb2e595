"""One simulation request: :class:`Problem`, validated once and run by ``simulate(problem)``.

A :class:`Problem` says everything the engine needs — what to simulate (a ship, or a model
with its parameters), the actuator and the controller, the environment, the references and
disturbances, the timing, what to record, the batch's axes (:class:`BatchLayout`), the seed and
the options — and checks it in its constructor: the components by name, the timing, the
wiring by signal name, the bounds' labels, the options. Python code, the scenario loader, the
CLI and sweeps all build one; :func:`seahelm.simulation.engine.simulate` runs it (its keyword
form builds one). capytaine's problem objects (validated in their constructor, their
coordinates becoming the result's dimensions) are the model.

What depends on the sizes of the per-run inputs (parameter rows, initial states, signal
arrays, their broadcast to one batch, the recording's memory) is checked by the engine when it
builds those arrays, once, before anything runs.

Every error is a :class:`~seahelm.errors.ParameterError` whose ``field`` is the problem's
field (``dt``, ``controller_dt``, ``bounds.heading``, ``params.Y_v``): a scenario file or the
CLI names it in its own words from that field, never from the message text.

Example::

    problem = Problem(ship="kvlcc2-l7", x0=approach, t_final=120.0, dt=0.05,
                      reference={"rudder_command": math.radians(35.0), "propeller_rps": rps})
    result = simulate(problem)
"""

from __future__ import annotations

import dataclasses
import math
import os
import types
from collections.abc import Mapping
from typing import Any

import numpy as np

from numba.core import config as _numba_config

from ..actuators.base import Actuator
from ..control.base import Controller
from ..environment.loads import Environment
from ..errors import ParameterError
from ..numerics.runge_kutta import get_integrator
from ..parameters import Params
from ..result_layout import BatchLayout
from ..vessels.base import VesselModel
from .environment_stage import check_environment
from .resolve import Components, field_error, resolve_components

__all__ = ["Problem", "OPTION_FIELDS", "jit_enabled"]

#: The fields that are options of the run rather than its inputs.
OPTION_FIELDS: tuple[str, ...] = ("exact_actuator", "jit")


#: Values of ``SEAHELM_DISABLE_JIT`` that leave the JIT on (any other non-empty value turns the
#: pure-Python loop on).
_OFF = ("", "0", "false", "no", "off")


def _numba_jit_disabled() -> bool:
    return bool(_numba_config.DISABLE_JIT)


def jit_enabled(jit: bool | None = None) -> bool:
    """Whether :func:`~seahelm.simulation.engine.simulate` runs the compiled loop (``True``) or the pure-Python one.

    Parameters
    ----------
    jit : bool, optional
        The caller's choice. Default: compiled, unless ``SEAHELM_DISABLE_JIT`` is set (to
        anything but empty, ``0``, ``false``, ``no`` or ``off``) or numba's own JIT is disabled
        (``NUMBA_DISABLE_JIT=1``, read by numba when it is imported).

    Returns
    -------
    bool

    Raises
    ------
    ParameterError
        If ``jit`` is not True, False or None, or is True while numba's JIT is disabled.
    """
    if jit is None:
        off = os.environ.get("SEAHELM_DISABLE_JIT", "").strip().lower() not in _OFF
        return not (off or _numba_jit_disabled())
    if not isinstance(jit, (bool, np.bool_)):
        raise ParameterError(f"must be True, False or None, got {jit!r}", field="jit",
                             value=jit)
    if jit and _numba_jit_disabled():
        raise ParameterError("= True, but numba's JIT is disabled (NUMBA_DISABLE_JIT=1): "
                             "nothing can be compiled in this process", field="jit", value=jit)
    return bool(jit)



def steps(t_final: float, dt: float, what: str = "t_final") -> int:
    """``t_final / dt`` as a whole number of steps (ParameterError naming ``what`` if not)."""
    ratio = t_final / dt
    n = int(round(ratio))
    if n < 1 or abs(ratio - n) > 1e-9 * max(1.0, ratio):
        raise ParameterError(
            f"must be a positive whole multiple of `dt` [s]: {what}={t_final!r}, dt={dt!r}",
            field=what, unit="s", value=t_final)
    return n


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class Problem:
    """One simulation request, validated on construction.

    Attributes
    ----------
    t_final, dt : float
        Duration [s] and integration step [s]; ``t_final`` a whole multiple of ``dt``.
    ship : Ship, str or path-like, optional
        A ship (:mod:`seahelm.ships`: a catalog name or a ship file): gives the model, the
        parameters and, where it has one, the steering gear as the actuator.
    model : VesselModel or str, optional
        The vessel model (or its registry name); from the ship when one is given.
    params : Params, sequence of Params or array (runs, n_params), optional
        Vessel parameters, one set or one per run (default: the ship's).
    x0 : array_like, shape (n_states,) or (runs, n_states), optional
        Initial vessel state (SI units, radians). Required without a ``ship``; with one, the
        default is its trimmed straight approach at its test speed, as the manoeuvres start
        (:mod:`seahelm.simulation.ship_start`: the steering gear at the trim angle and, for an
        open-loop problem without a ``reference``, the approach's rudder and rps held). (A
        scenario's ``[vessel] initial`` is different: the states it does not give are 0, so a
        scenario without it starts at rest.)
    controller, controller_params : Controller or str, Params or array, optional
        Controller (default: open loop, reference = command) and its parameters.
    actuator, actuator_params, actuator_x0 : Actuator or str, Params or array, array_like
        Actuator (default: the ship's steering gear, else the rudder servo for a model with a
        ``rudder_angle`` input, else ``direct``), its parameters
        (default: the steering gear's) and initial state (default zeros).
    reference, disturbance : None, scalar, array, callable or mapping, optional
        Controller reference and the model's disturbance inputs
        (:func:`~seahelm.simulation.engine.simulate` lists the forms).
    environment, environment_params : Environment, Params or array, optional
        Wind and wave loads (:mod:`seahelm.environment.loads`) and their parameters.
    controller_dt : float, optional
        Controller sample period [s], a whole multiple of ``dt``: the controller's own
        ``sample_period`` where it has one (a discretised controller; the default then),
        else any (default ``dt``).
    integrator : str or ButcherTableau, optional
        Fixed-step method (default ``"rk4"``).
    record_every : int, optional
        Record every n-th step and the final state (default 1).
    bounds : mapping state label -> (low, high), optional
        Admissible state bounds beyond the model's declared ones.
    seed : int, optional
        Seed the batch's random inputs came from, stored with the results.
    metadata : mapping, optional
        Extra attributes stored with the results.
    layout : BatchLayout, optional
        The dimensions the runs span (default: one ``run`` dimension).
    exact_actuator : bool, optional
        Take the actuator's states from its closed-form step (default: when it has one).
    jit : bool, optional
        Run the compiled loop (default) or the same loop as plain Python (``False``).
    first_order : FirstOrderInLoop, optional
        First-order wave motions evaluated in the loop
        (:func:`~seahelm.environment.first_order_in_loop.first_order_in_loop`), one set of
        components per run; the model must output ``north``, ``east``, ``heading`` and
        ``surge_speed``, and a controller that is to see the first-order yaw must measure
        ``heading``.
    sensors : PositionSensors, optional
        What the controller's ``north``, ``east`` and ``heading`` sensors see: the
        first-order surge, sway and yaw of ``first_order`` and seeded noise
        (:mod:`seahelm.simulation.sensor_stage`).
    post_pass : object, optional
        Computed after the run from its recordings by :func:`simulate`, into the result: an
        object with ``compute(result) -> (extra, metadata)`` (channels for
        :attr:`~seahelm.results.SimResult.extra`, name -> (values (runs, time), unit,
        description), and metadata entries), and ``select_runs(start, stop)`` for a sweep's
        chunks (e.g. a scenario's first-order wave motions after the run,
        :class:`seahelm.scenario.first_order.FirstOrderPostPass`).

    Notes
    -----
    Derived on construction (read-only properties): :attr:`n_steps` and
    :attr:`controller_every` (integration steps, and steps per controller sample),
    :attr:`tableau` (the integrator) and :attr:`wiring` (controller → actuator → model by signal
    name, :func:`~seahelm.simulation.composition.compose`).
    """

    t_final: float
    dt: float
    ship: Any = None
    model: "VesselModel | str | None" = None
    params: Any = None
    x0: Any = None
    controller: "Controller | str | None" = None
    controller_params: Any = None
    actuator: "Actuator | str | None" = None
    actuator_params: Any = None
    actuator_x0: Any = None
    reference: Any = None
    disturbance: Any = None
    environment: Any = None
    environment_params: Any = None
    controller_dt: float | None = None
    integrator: Any = "rk4"
    record_every: int = 1
    bounds: Mapping[str, tuple[float, float]] = dataclasses.field(default_factory=dict)
    seed: int | None = None
    metadata: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    layout: BatchLayout | None = None
    exact_actuator: bool | None = None
    jit: bool | None = None
    first_order: Any = None
    post_pass: Any = None
    sensors: Any = None

    def __post_init__(self) -> None:
        put = object.__setattr__
        # the components and their defaults: resolved in one place (simulation.resolve), as the
        # scenario's problem resolves them
        resolved = resolve_components(ship=self.ship, model=self.model, actuator=self.actuator,
                                      controller=self.controller)
        model, actuator, controller = resolved.model, resolved.actuator, resolved.controller
        put(self, "ship", resolved.ship)
        put(self, "model", model)
        if self.params is None:
            if resolved.params is None:
                raise ParameterError(f"is required ({model.params_type.__name__} of model "
                                     f"'{model.name}', or a `ship`)", field="params")
            put(self, "params", resolved.params)
        _check_params("params", self.params, model.params_type)
        if self.x0 is None and resolved.ship is None:
            raise ParameterError(f"is required: the initial state ({', '.join(model.state_labels)})"
                                 " (or give a `ship`: it starts on its straight approach)",
                                 field="x0")
        if self.x0 is not None and model.check_initial_state is not None:  # a unit quaternion
            x0 = np.asarray(self.x0, dtype=float)
            if x0.shape[-1:] == (model.n_states,):
                model.check_initial_state(x0.reshape(-1, model.n_states))
        put(self, "actuator", actuator)
        if self.actuator_params is None and resolved.actuator_params is not None:
            put(self, "actuator_params", resolved.actuator_params)
        put(self, "controller", controller)
        for name, comp in (("actuator_params", actuator), ("controller_params", controller)):
            if getattr(self, name) is not None:
                _check_params(name, getattr(self, name), comp.params_type)

        # timing
        for name in ("dt", "t_final"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating,
                                                                 np.integer)) \
                    or not (math.isfinite(value) and value > 0):
                what = "a finite number > 0" if isinstance(value, (int, float)) and not \
                    math.isfinite(value) else "> 0"
                raise ParameterError(f"must be {what} [s], got {value!r}", field=name, unit="s",
                                     value=value)
        dt, t_final = float(self.dt), float(self.t_final)
        n_steps = steps(t_final, dt)
        ctrl_dt = self.controller_dt
        if ctrl_dt is None:  # the controller's own period, else every step
            ctrl_dt = dt if controller.sample_period is None else controller.sample_period
        if isinstance(ctrl_dt, bool) or not isinstance(ctrl_dt, (int, float, np.floating,
                                                                 np.integer)) \
                or not (math.isfinite(ctrl_dt) and ctrl_dt > 0):
            raise ParameterError(f"must be > 0 [s], got {ctrl_dt!r}", field="controller_dt",
                                 unit="s", value=ctrl_dt)
        ctrl_every = steps(float(ctrl_dt), dt, "controller_dt")
        if ctrl_every > n_steps:
            raise ParameterError(
                f"= {float(ctrl_dt)!r} s exceeds `t_final` = {t_final!r} s: the controller "
                "would act once, at t = 0", field="controller_dt", unit="s", value=ctrl_dt)
        period = controller.sample_period
        if period is not None and abs(ctrl_every * dt - period) > 1e-9 * period:
            raise ParameterError(
                f"must be {period!r} s, the period controller '{controller.name}' was designed "
                f"or sampled at, got {float(ctrl_dt)!r}", field="controller_dt", unit="s",
                value=ctrl_dt)
        every = self.record_every
        if isinstance(every, bool) or not isinstance(every, (int, float, np.integer)) \
                or int(every) != every or every < 1:
            raise ParameterError(f"must be a whole number >= 1, got {every!r}",
                                 field="record_every", value=every)
        if int(every) > n_steps:
            raise ParameterError(
                f"= {int(every)} exceeds the number of steps ({n_steps} = t_final/dt): nothing "
                "after t = 0 would be recorded", field="record_every", value=every)
        put(self, "record_every", int(every))
        try:
            tableau = get_integrator(self.integrator)
        except (ValueError, TypeError) as exc:
            raise field_error("integrator", exc) from None
        # environment, bounds, options
        wiring = resolved.wiring
        if self.x0 is None:  # a ship's: its trimmed straight approach (simulation.ship_start)
            from .ship_start import approach_start

            for name, value in zip(("x0", "actuator_x0", "reference"), approach_start(
                    resolved.ship, self.params, wiring, self.actuator_x0, self.reference)):
                put(self, name, value)
        if self.environment is not None and not isinstance(self.environment, Environment):
            raise ParameterError(
                f"must be an Environment (seahelm.environment.loads.environment(wind=..., "
                f"waves=...)), got {type(self.environment).__name__}", field="environment")
        if self.environment is None:
            if self.environment_params is not None:
                raise ParameterError("given without an `environment`",
                                     field="environment_params")
        else:
            try:
                check_environment(self.environment, model)
            except ParameterError as exc:
                raise field_error("environment", exc) from None
        labels = model.state_labels + actuator.state_labels
        bounds = dict(self.bounds or {})
        for label, pair in bounds.items():
            if label not in labels:
                raise ParameterError(f"is an unknown state; states: {', '.join(labels)}",
                                     field=f"bounds.{label}")
            ok = (isinstance(pair, (tuple, list)) and len(pair) == 2
                  and all(not isinstance(v, bool) and isinstance(v, (int, float, np.floating))
                          and not math.isnan(v) for v in pair) and pair[0] < pair[1])
            if not ok:
                raise ParameterError(f"must be a pair (low, high) of numbers with low < high, "
                                     f"got {pair!r}", field=f"bounds.{label}", value=pair)
        seed = self.seed
        if seed is not None and (isinstance(seed, bool) or not isinstance(
                seed, (int, np.integer)) or seed < 0):
            raise ParameterError(f"must be a whole number >= 0 (or None), got {seed!r}",
                                 field="seed", value=seed)
        if not isinstance(self.metadata or {}, Mapping):
            raise ParameterError(f"must be a mapping of names to values, got "
                                 f"{type(self.metadata).__name__}", field="metadata")
        for key, value in (self.metadata or {}).items():
            if not isinstance(key, str) or not isinstance(
                    value, (str, int, float, bool, np.integer, np.floating)):
                raise ParameterError(
                    f"values must be text or numbers (they are stored with the results), "
                    f"got {key!r}: {type(value).__name__}", field=f"metadata.{key}")
        exact = self.exact_actuator
        if exact is not None and not isinstance(exact, (bool, np.bool_)):
            raise ParameterError(f"must be True, False or None, got {exact!r}",
                                 field="exact_actuator", value=exact)
        if exact and actuator.advance is None:
            raise ParameterError(f": the actuator '{actuator.name}' has no closed-form step",
                                 field="exact_actuator", value=exact)
        try:
            use_jit = jit_enabled(self.jit)
        except ParameterError as exc:
            raise field_error("jit", exc) from None
        _check_first_order(self.first_order, model, controller)
        if self.sensors is not None:
            from .sensor_stage import check_sensors

            check_sensors(self.sensors, self.first_order, model, controller)
        if self.post_pass is not None and not callable(getattr(self.post_pass, "compute", None)):
            raise ParameterError(f"must have a compute(result) method, got "
                                 f"{type(self.post_pass).__name__}", field="post_pass")
        if self.layout is not None and not isinstance(self.layout, BatchLayout):
            raise ParameterError(f"must be a BatchLayout, got {type(self.layout).__name__}",
                                 field="layout")
        put(self, "bounds", types.MappingProxyType(bounds))
        put(self, "metadata", types.MappingProxyType(dict(self.metadata or {})))
        put(self, "_derived", types.MappingProxyType({
            "n_steps": n_steps, "controller_every": ctrl_every, "controller_dt": float(ctrl_dt),
            "tableau": tableau, "wiring": wiring, "jit": use_jit, "components": resolved}))

    # -- derived ------------------------------------------------------------------------
    def _summary(self) -> tuple[str, list[tuple[str, object]]]:
        from .._repr import describe

        ship = getattr(self.ship, "name", None)
        runs = "as the inputs give" if self.n_runs is None else str(self.n_runs)
        title = f"Problem: {self.model.name}" + (f" ({ship})" if ship else "") + f", runs: {runs}"
        timing = f"t_final {self.t_final:g} s, dt {self.dt:g} s"
        if self.controller_dt is not None:
            timing += f", controller every {self.controller_dt:g} s"
        timing += f" ({self.n_steps} steps)"
        integrator = self.integrator if isinstance(self.integrator, str) else describe(
            self.integrator)
        rows: list[tuple[str, object]] = [
            ("components", f"model {self.model.name}, actuator {describe(self.actuator)}, "
                           f"controller {describe(self.controller)}"),
            ("timing", timing),
            ("integrator", integrator),
            ("initial state", describe(None if self.x0 is None else np.asarray(self.x0))),
            ("reference", describe(self.reference)),
        ]
        for name in ("disturbance", "environment", "first_order", "sensors"):
            if getattr(self, name) is not None:
                rows.append((name, describe(getattr(self, name))))
        if self.layout is not None:
            rows.append(("batch", ", ".join(f"{d}: {n}" for d, n in
                                            zip(self.layout.dims, self.layout.shape))))
        if self.seed is not None:
            rows.append(("seed", self.seed))
        if self.record_every != 1:
            rows.append(("record every", f"{self.record_every} steps"))
        rows.append(("use", "simulate(problem), problem.replace(...)"))
        return title, rows

    def __repr__(self) -> str:
        from .._repr import summary_text

        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        from .._repr import summary_html

        return summary_html(*self._summary())

    @property
    def n_steps(self) -> int:
        """Integration steps, ``t_final / dt``."""
        return self._derived["n_steps"]

    @property
    def controller_every(self) -> int:
        """Integration steps per controller sample."""
        return self._derived["controller_every"]

    @property
    def tableau(self) -> Any:
        """The integrator's Butcher tableau."""
        return self._derived["tableau"]

    @property
    def wiring(self) -> Any:
        """Controller → actuator → model by signal name."""
        return self._derived["wiring"]

    @property
    def components(self) -> Components:
        """The resolved components and their defaults
        (:func:`~seahelm.simulation.resolve.resolve_components`)."""
        return self._derived["components"]

    @property
    def n_runs(self) -> int | None:
        """Number of runs the layout spans (None without a layout: the engine decides)."""
        return None if self.layout is None else self.layout.size

    def simulate_kwargs(self) -> dict[str, Any]:
        """The keyword arguments of :func:`~seahelm.simulation.engine.simulate` that make this
        problem again (components resolved; the layout is the problem's own).

        Returns
        -------
        dict
        """
        kwargs = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                  if f.name not in ("layout", "ship")}
        kwargs["bounds"] = dict(self.bounds)
        kwargs["metadata"] = dict(self.metadata)
        return kwargs

    def __reduce__(self) -> Any:
        # pickled by its fields, made (and validated) again when unpickled
        return (_rebuild, ({f.name: getattr(self, f.name) if f.name not in ("bounds", "metadata")
                            else dict(getattr(self, f.name)) for f in dataclasses.fields(self)},))

    def replace(self, **changes: Any) -> "Problem":
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            New field values.

        Returns
        -------
        Problem
        """
        return dataclasses.replace(self, **changes)


def _check_params(name: str, value: Any, cls: type) -> None:
    """A parameter input: a ``cls`` set, a sequence of them, or an array of rows."""
    if isinstance(value, Params) or (isinstance(value, (list, tuple)) and value
                                      and isinstance(value[0], Params)):
        first = value if isinstance(value, Params) else value[0]
        if not isinstance(first, cls):
            raise ParameterError(f"must be {cls.__name__}, got {type(first).__name__}",
                                 field=name)
        return
    if isinstance(value, (Mapping, str, bytes)):
        raise ParameterError(f"must be {cls.__name__}, a sequence of them or an array of "
                             f"rows (runs, {cls.n_values()}), got {type(value).__name__}",
                             field=name)


def _check_first_order(first_order: Any, model: VesselModel, controller: Controller) -> None:
    """The problem's first-order motions: the object, the model's outputs they are evaluated
    from, and a ``heading`` measurement if the controller is to see the first-order yaw."""
    if first_order is None:
        return
    from ..environment.first_order_in_loop import MOTION_INPUTS, FirstOrderInLoop

    if not isinstance(first_order, FirstOrderInLoop):
        raise ParameterError(
            "must be a FirstOrderInLoop (seahelm.environment.first_order_in_loop."
            f"first_order_in_loop(...)), got {type(first_order).__name__}", field="first_order")
    missing = [f"{n} [{u}]" for n, u in MOTION_INPUTS.items() if n not in model.output_labels]
    if missing:
        raise ParameterError(
            f": model '{model.name}' does not output {', '.join(missing)}, from which the "
            f"first-order motions are evaluated (outputs: {', '.join(model.output_labels)})",
            field="first_order")
    clash = set(first_order.output_signals()[0]) & set(model.output_labels)
    if clash:
        raise ParameterError(f": model '{model.name}' already outputs "
                             f"{', '.join(sorted(clash))}", field="first_order")
    if first_order.autopilot_sees_first_order and "heading" not in \
            controller.measurement_labels:
        raise ParameterError(
            f".autopilot_sees_first_order: controller '{controller.name}' does not measure "
            f"`heading` (it measures {', '.join(controller.measurement_labels) or 'nothing'})",
            field="first_order", value=True)


def _rebuild(fields: dict[str, Any]) -> Problem:
    return Problem(**fields)
