"""A ``[simulation]`` scenario: the :class:`~seahelm.simulation.problem.Problem` it describes.

Resolves and checks what only the scenario knows: names (models, catalog entries, parameters,
state and signal channels), parameter ranges (through the components' parameter dataclasses),
signal specifications and the batch (grid and Monte-Carlo draws). What the engine runs --
timing, command counts, bounds labels, shapes -- the engine validates when the batch runs;
:func:`run_batch` re-raises its error naming the scenario file and the key it most likely
comes from.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..registry import get_controller, get_model
from ..simulation.batch import BatchAxis, BatchLayout, BatchValues, grid_axes
from ..simulation.problem import Problem
from ..simulation.resolve import resolve_components
from ..resources import WorkTooLarge, check_work
from ..simulation.engine import check_record_memory
from ..control.guided import guided
from ..control.path_following import GuidanceLaw, RouteParams, get_guidance_law, route_params
from ..simulation.signals import Constant, make_signal
from .environment import KEY_UNITS as _ENV_UNITS, environment_runs
from .errors import ScenarioError, at_key as _err
from .first_order import FirstOrderPostPass
from ..ships.file_format import is_ship_path
from .particulars import refuse_varied_particulars
from .samples import drawn_kinds, samples_draws
from .vessel import ship_key, vessel_ship
from .schema import Scenario

__all__ = ["prepare_runs", "run_batch", "monte_carlo_draws"]


def _is_angle(unit: str) -> bool:
    return unit.startswith("rad")


def _channel(name: str, labels: tuple[str, ...], units: tuple[str, ...]) -> tuple[int, float]:
    """Index and degree scale of a channel written as ``label`` or ``label_deg``."""
    if name in labels:
        return labels.index(name), 1.0
    if name.endswith("_deg") and name[:-4] in labels:
        j = labels.index(name[:-4])
        if not _is_angle(units[j]):
            raise ValueError(f"'{name[:-4]}' is not an angle (unit [{units[j]}]), drop `_deg`")
        return j, math.pi / 180.0
    raise ValueError(
        f"unknown channel '{name}'; valid: {', '.join(labels) or '(none)'} "
        "(angles also as <name>_deg)"
    )


#: Runs one scenario batch may have (grid points × Monte-Carlo samples).
MAX_RUNS = 1_000_000

_OVERRIDABLE = ("vessel.params.", "vessel.initial.", "actuator.params.", "controller.params.",
                "controller.reference.", "environment.disturbance.", "environment.wind.",
                "environment.waves.", "guidance.")

#: Each field of the :class:`~seahelm.simulation.problem.Problem` -> the scenario key an
#: error of it (its ``field``, first part) is said at, or None: a field the scenario sets from
#: no key of its own. Checked against ``Problem``'s fields below: a field added to the problem
#: without a line here fails on import, not silently in a message.
_FIELD_KEYS: dict[str, str | None] = {
    "t_final": "simulation.t_final",
    "dt": "simulation.dt",
    "ship": "vessel.ship",
    "model": "vessel.model",
    "params": "vessel.params",
    "x0": "vessel.initial",
    "controller": "controller.model",
    "controller_params": "controller.params",
    "actuator": "actuator.model",
    "actuator_params": "actuator.params",
    "actuator_x0": None,
    "reference": "controller.reference",
    "disturbance": "environment.disturbance",
    "environment": "environment",
    "environment_params": "environment",
    "controller_dt": "controller.dt",
    "integrator": "simulation.integrator",
    "record_every": "simulation.record_every",
    "bounds": "simulation.bounds",
    "seed": None,
    "metadata": None,
    "layout": None,
    "exact_actuator": "simulation.exact_actuator",
    "jit": None,
    "first_order": "environment.waves.autopilot_sees_first_order",
    "post_pass": "environment.waves.first_order_motions",
    "sensors": "sensors",
}
if set(_FIELD_KEYS) != {f.name for f in dataclasses.fields(Problem)}:  # pragma: no cover
    raise AssertionError("scenario.runs._FIELD_KEYS must name every field of Problem: "
                         f"{sorted(set(_FIELD_KEYS) ^ {f.name for f in dataclasses.fields(Problem)})}")

#: Field of the problem -> the scenario key it comes from (those said at a key), in the order
#: of ``Problem``'s fields.
_ENGINE_KEYS = {f.name: _FIELD_KEYS[f.name] for f in dataclasses.fields(Problem)
                if _FIELD_KEYS[f.name] is not None}


def _key_units(key: str, model: Any, actuator: Any, wiring: Any) -> str:
    """Unit of the values written for a batch key (``deg`` for ``_deg`` keys; "" if unknown)."""
    section, _, name = key.rpartition(".")
    if name.endswith("_deg"):
        return "deg"
    if key in _ENV_UNITS:
        return _ENV_UNITS[key]
    tables = {
        "vessel.params": {i.name: i.unit for i in model.params_type.info()},
        "actuator.params": {i.name: i.unit for i in actuator.params_type.info()},
        "controller.params": {i.name: i.unit for i in wiring.controller.params_type.info()},
        "guidance": {i.name: i.unit for i in wiring.controller.params_type.info()},
        "vessel.initial": dict(zip(model.state_labels, model.state_units)),
        "controller.reference": dict(zip(wiring.references, wiring.reference_units)),
        "environment.disturbance": dict(zip(model.disturbance_labels, model.disturbance_units)),
    }
    return tables.get(section, {}).get(name, "")


def _expand_batch(
    scn: Scenario, source: str, reserved: set[str], units: Callable[[str], str]
) -> tuple[list[dict[str, float]], int | None, BatchLayout]:
    """Per-run overrides {"section.kind.key": value} in C order, the seed and the layout."""
    grid_keys = list(scn.batch.grid)
    mc = scn.batch.monte_carlo
    for key in grid_keys:
        if not scn.batch.grid[key]:
            raise _err(source, f"batch.grid.{key}", "needs at least one value, got []")
    kinds = drawn_kinds(mc, source)
    for key in grid_keys + list(kinds):
        if not key.startswith(_OVERRIDABLE):
            raise _err(source, f"batch.{key}",
                       f"cannot vary '{key}'; keys start with one of: {', '.join(_OVERRIDABLE)}")
    grid = [dict(zip(grid_keys, combo))
            for combo in itertools.product(*(scn.batch.grid[k] for k in grid_keys))] or [{}]
    axes = list(grid_axes(scn.batch.grid, units={k: units(k) for k in grid_keys},
                          reserved=reserved))
    if mc is None:
        layout = BatchLayout(axes=tuple(axes)) if axes else BatchLayout.runs(1)
        return grid, None, layout
    drawn = monte_carlo_draws(mc, np.arange(len(grid) * mc.runs), source)
    runs: list[dict[str, float]] = []
    n = 0
    for point in grid:
        for _ in range(mc.runs):
            draw = dict(point)
            draw.update({key: float(v[n]) for key, v in drawn.items()})
            runs.append(draw)
            n += 1
    axes.append(BatchAxis(name="sample", values=np.arange(mc.runs)))
    values = tuple(
        BatchValues(name=key, values=drawn[key], units=units(key),
                    attrs={"key": key, "distribution": kind})
        for key, kind in kinds.items()
    )
    try:
        layout = BatchLayout(axes=tuple(axes), values=values)
    except ParameterError as exc:
        raise _err(source, "batch", str(exc)) from None
    return runs, mc.seed, layout


def monte_carlo_draws(mc: Any, indices: np.ndarray, source: str = "<string>"
                      ) -> dict[str, np.ndarray]:
    """The draws of ``[batch.monte_carlo]`` for the given sample indices (flat, over grid
    points × samples): each sample from its own generator, ``SeedSequence(seed)``'s child of
    that index (:func:`seahelm.numerics.sampling.draw_samples`), so any subset of samples,
    drawn in any process, has the values the whole batch has.

    Parameters
    ----------
    mc : MonteCarloSection
        The validated section.
    indices : ndarray of int
        Flat sample indices.
    source : str, optional
        Name of the scenario in error messages.

    Returns
    -------
    dict of key path to ndarray, shape (len(indices),)
    """
    from ..numerics.sampling import CorrelatedNormal, get_distribution

    marginals = {}
    for key, dist in mc.draws.items():
        params = {k: getattr(dist, k) for k in ("mean", "std", "low", "high")
                  if getattr(dist, k) is not None}
        try:
            marginals[key] = get_distribution(dist.distribution, **params)
        except ParameterError as exc:
            raise _err(source, f"batch.monte_carlo.draws.{key}", str(exc)) from None
    blocks = [CorrelatedNormal(tuple(b.keys), b.mean, b.covariance) for b in mc.correlated]
    from ..numerics.sampling import draw_samples

    out = draw_samples(marginals, mc.seed, indices, blocks)
    out.update(samples_draws(mc, indices, source))  # [batch.monte_carlo] samples = FILE
    return out


@dataclasses.dataclass(frozen=True, eq=False)
class _ScenarioSignals:
    """The time-varying reference or disturbance channels of a scenario's runs.

    Called by the engine with its own time grid (the scenario does not build one); returns
    shape (runs|1, steps+1, channels). Random signals draw run ``i``'s realisation from the
    ``i``-th child of ``SeedSequence(seed)``, with the signal's own ``seed`` and, in a
    Monte-Carlo batch, the batch's seed (``SeedSequence([seed, batch_seed])``): a new batch
    seed draws new seas, as it draws new parameters.
    """

    source: str
    path: str
    n_channels: int
    #: per run (or one for all runs): (channel index, name, spec as written, signal)
    runs: tuple[tuple[tuple[int, str, Any, Any], ...], ...]
    batch_seed: int | None = None
    #: flat index of the first run (a chunk of a larger batch draws the runs' own seas)
    first_run: int = 0

    def __call__(self, t_grid: np.ndarray) -> np.ndarray:
        t_grid = np.asarray(t_grid, dtype=float)
        out = np.zeros((len(self.runs), t_grid.size, self.n_channels))
        # random signals that draw many runs at once (draw_runs) are drawn per channel and
        # signal in one call; row i equals the single-run draw of run i's seed
        groups: dict[tuple[int, Any], list[tuple[int, Any, Any]]] = {}
        for i, channels in enumerate(self.runs):
            for j, name, spec, sig in channels:
                try:
                    if getattr(sig, "random", False):
                        entropy = sig.seed if self.batch_seed is None else [sig.seed,
                                                                            self.batch_seed]
                        seq = np.random.SeedSequence(entropy,
                                                     spawn_key=(self.first_run + i,))
                        if hasattr(sig, "draw_runs"):
                            groups.setdefault((j, sig), []).append((i, seq, (name, spec)))
                        else:
                            out[i, :, j] = sig(t_grid, seed=seq)
                    else:
                        out[i, :, j] = sig(t_grid)
                except (ValueError, TypeError) as exc:
                    raise _err(self.source, f"{self.path}.{name}",
                               f"{exc} (got {spec!r})") from None
        for (j, sig), members in groups.items():
            rows = [i for i, _, _ in members]
            try:
                out[rows, :, j] = sig.draw_runs(t_grid, [seq for _, seq, _ in members])
            except (ValueError, TypeError) as exc:
                name, spec = members[0][2]
                raise _err(self.source, f"{self.path}.{name}",
                           f"{exc} (got {spec!r})") from None
        return out


def _signal_input(
    per_run: list[dict[str, Any]], labels: tuple[str, ...], units: tuple[str, ...],
    path: str, source: str, batch_seed: int | None = None,
) -> Any:
    """A reference/disturbance input of :func:`simulate` from per-run channel specifications.

    ``None`` when nothing is given; constants as an array (runs|1, 1, channels); anything that
    varies in time as a :class:`_ScenarioSignals` the engine samples on its grid.
    """
    if not any(per_run):
        return None
    runs = []
    for spec in per_run:
        channels = []
        for name, value in spec.items():
            try:
                j, scale = _channel(name, labels, units)
                sig = make_signal(value, scale=scale)
            except (ValueError, TypeError) as exc:
                raise _err(source, f"{path}.{name}", f"{exc} (got {value!r})") from None
            channels.append((j, name, value, sig))
        runs.append(tuple(channels))
    if all(isinstance(sig, Constant) for chans in runs for _, _, _, sig in chans):
        arr = np.zeros((len(runs), 1, len(labels)))
        for i, chans in enumerate(runs):
            for j, _, _, sig in chans:
                arr[i, 0, j] = sig.value
        return arr
    return _ScenarioSignals(source=source, path=path, n_channels=len(labels), runs=tuple(runs),
                            batch_seed=batch_seed)


def prepare_runs(scn: Scenario, *, source: str = "<string>", text: str = "",
                 in_memory: bool = True) -> Problem:
    """The batch a validated scenario describes: components, per-run inputs and the layout.

    Resolves and validates names, parameters (through the components' parameter
    dataclasses), initial states and signal specifications. Timing, command counts and bounds
    labels are left to the engine, which validates them when the batch runs.

    Parameters
    ----------
    scn : Scenario
        Validated scenario schema.
    source : str, optional
        Name of the source used in error messages (default "<string>").
    text : str, optional
        Scenario text, stored with the results (default "").

    in_memory : bool, optional
        The whole batch will be held in memory at once (default True: its recordings are
        checked against the memory this process may use before it is expanded); False for a
        sweep, which streams it in chunks, each checked on its own.

    Returns
    -------
    Problem
        Components, parameter arrays (runs, n_params), initial states (SI units, radians),
        reference and disturbance inputs, and the layout: the grid's dimensions (named by the
        last component of each key path, or the full path where that is ambiguous), plus
        ``sample`` for Monte-Carlo (draws stored as batch values), or one ``run``.

    Raises
    ------
    ScenarioError
        Naming the source, the key path, the value and what was expected.
    """
    refuse_varied_particulars(scn, source)  # (they vary in [maneuver] scenarios only)
    model = _vessel_model(scn, source)
    ship = vessel_ship(scn, source)
    if ship is not None and ship.model is not model:
        raise _err(source, ship_key(scn),
                   f"'{ship.name}' is a ship of model '{ship.model.name}', not '{model.name}'")
    try:
        controller = get_controller(scn.controller.model)
    except ValueError as exc:
        raise _err(source, "controller.model", str(exc)) from None
    guidance = _guidance(scn, source, controller)
    if guidance is not None and guidance[0] is not None:  # the law steers the heading controller
        try:
            controller = guided(guidance[0], controller)
        except ParameterError as exc:
            raise _err(source, "guidance.law", str(exc)) from None
    try:  # the components, their wiring and defaults, as the Problem resolves them: a ship's
        # own steering gear unless [actuator] names another actuator
        comp = resolve_components(
            ship=ship, model=model, controller=controller,
            actuator=scn.actuator.model if "model" in scn.actuator.model_fields_set else None)
    except ParameterError as exc:
        raise _engine_error(source, exc, None) from None
    actuator, wiring = comp.actuator, comp.wiring

    # names a batch dimension must not take: the result's variables and dimensions
    reserved = {*model.state_labels, *actuator.state_labels, *model.output_labels,
                *_summary_names(model.state_labels + actuator.state_labels),
                *controller.output_labels,
                *wiring.commands, *model.disturbance_labels,
                *(f"reference_{lab}" for lab in wiring.references),
                "status", "failure_time", "status_message", "run", "sample", "time"}
    from ..environment.loads import WAVE_OUTPUTS, WIND_OUTPUTS

    env_channels = (len(WIND_OUTPUTS) + 1 if scn.environment.wind is not None else 0) + (
        len(WAVE_OUTPUTS) + 1 if scn.environment.waves is not None else 0)
    reserved |= {*WIND_OUTPUTS, *WAVE_OUTPUTS, "wind_gust", "wave_load_fluctuation"}
    _check_size(scn, source, in_memory, model.n_states + actuator.n_states + model.n_outputs
                + len(wiring.commands) + len(controller.output_labels) + len(wiring.references)
                + model.n_disturbances + env_channels)  # what the engine records
    runs, seed, layout = _expand_batch(
        scn, source, reserved, lambda key: _key_units(key, model, actuator, wiring))
    env = environment_runs(scn, model, runs, source)
    dist_labels, dist_units = model.disturbance_labels, model.disturbance_units
    if env is not None:
        dist_labels += env.environment.signal_labels
        dist_units += env.environment.signal_units

    def random(spec: dict[str, Any]) -> bool:
        return any(isinstance(v, dict) and v.get("kind") == "sea" for v in spec.values())

    # a random signal gives every run its own realisation
    varied_ref = random(scn.controller.reference) or any(
        k.startswith("controller.reference.") for r in runs for k in r)
    disturbance = _with_current(scn, model, source)
    varied_dist = random(disturbance) or any(
        k.startswith(("environment.disturbance.", "environment.wind.", "environment.waves."))
        for r in runs for k in r) or (env is not None and any(
            getattr(v, "random", False) for sig in env.signals for v in sig.values()))

    def section(over: dict[str, float], prefix: str, base: dict[str, Any]) -> dict[str, Any]:
        out = dict(base)
        out.update({k[len(prefix):]: v for k, v in over.items() if k.startswith(prefix)})
        return out

    for path, table in (("vessel.initial", scn.vessel.initial),
                        ("controller.reference", scn.controller.reference),
                        ("environment.disturbance", scn.environment.disturbance)):
        both = [k for k in table if k.endswith("_deg") and k[:-4] in table]
        if both:
            raise _err(source, f"{path}.{both[0]}",
                       f"give `{both[0][:-4]}` [rad] or `{both[0]}` [deg], not both")
    mp, ap, cp, x0s, refs, dists = [], [], [], [], [], []
    for i, over in enumerate(runs):
        where = f" (run {i}: {over})" if over else ""
        for key, sec, cls, build, bucket in (
            ("vessel.params", scn.vessel.params, model.params_type, comp.vessel_params, mp),
            ("actuator.params", scn.actuator.params, actuator.params_type,
             comp.actuator_params_with, ap),
            ("controller.params", scn.controller.params, controller.params_type,
             controller.params_type.from_mapping, cp),
        ):
            values = section(over, key + ".", sec)
            if key == "controller.params" and guidance is not None:
                values = {**section(over, "guidance.", guidance[1]), **values}
            try:
                bucket.append(build(values).to_array())
            except ParameterError as exc:
                named = (exc.field or "").partition("[")[0]
                if guidance is not None and named in guidance[1]:
                    key = "guidance"  # a route or law value, written in [guidance]
                raise _err(source, key, f"{exc}{where}") from None
            except TypeError as exc:
                missing = [f for f in cls.field_names() if f not in values]
                raise _err(source, key,
                           f"missing required parameter(s) {', '.join(missing)} for "
                           f"{cls.__name__} ({exc}){where}") from None
        init = section(over, "vessel.initial.", scn.vessel.initial)
        x0 = np.zeros(model.n_states)
        for name, value in init.items():
            try:
                j, scale = _channel(name, model.state_labels, model.state_units)
            except ValueError as exc:
                raise _err(source, f"vessel.initial.{name}", f"{exc} (got {value!r})") from None
            x0[j] = value * scale
        x0s.append(x0)
        if varied_ref or not refs:
            refs.append(section(over, "controller.reference.", scn.controller.reference))
        if varied_dist or not dists:
            dists.append({**section(over, "environment.disturbance.", disturbance),
                          **(env.signals[i] if env is not None else {})})

    sim = scn.simulation
    assert sim is not None  # (a [maneuver] scenario goes to .maneuver)
    in_loop = None
    if env is not None and env.first_order is not None:
        from .first_order import first_order_in_the_loop

        in_loop = first_order_in_the_loop(
            env.first_order, seed, source,
            surge_sway=scn.sensors is not None and scn.sensors.wave_motion)
    sensors = None
    if scn.sensors is not None:
        from ..simulation.sensor_stage import PositionSensors

        sn = scn.sensors
        sensors = PositionSensors(noise_north=sn.noise_north, noise_east=sn.noise_east,
                                  noise_heading=math.radians(sn.noise_heading_deg),
                                  wave_motion=sn.wave_motion, seed=sn.seed)
    inputs = dict(
        model=comp.model,
        params=np.array(mp),
        x0=np.array(x0s),
        t_final=sim.t_final,
        dt=sim.dt,
        controller=controller,
        controller_params=np.array(cp),
        actuator=actuator,
        actuator_params=np.array(ap),
        reference=_signal_input(refs, wiring.references, wiring.reference_units,
                                "controller.reference", source, seed),
        disturbance=_signal_input(dists, dist_labels, dist_units, "environment.disturbance",
                                  source, seed),
        controller_dt=scn.controller.dt,
        integrator=sim.integrator,
        record_every=sim.record_every,
        bounds=dict(sim.bounds),
        seed=seed,
        metadata={"title": scn.title, "scenario_source": source, "scenario_text": text,
                  **({} if ship is None or not is_ship_path(scn.vessel.ship or "") else
                     {"ship_file": str(scn.vessel.ship)})},
        layout=layout,
        environment=None if env is None else env.environment,
        environment_params=None if env is None else env.params,
        exact_actuator=sim.exact_actuator,
        first_order=in_loop,
        sensors=sensors,
        ship=comp.ship,  # (its name and provenance reach the result's metadata)
        post_pass=(None if env is None or env.first_order is None or in_loop is not None
                   else FirstOrderPostPass(tuple(env.first_order), seed, source)),
    )
    try:  # the problem validates itself: its errors name their field, the key comes from it
        return Problem(**inputs)
    except ParameterError as exc:
        raise _engine_error(source, exc, layout) from exc


def _engine_error(source: str, exc: ParameterError, layout: BatchLayout | None) -> ScenarioError:
    """The problem's (or the engine's) error with the scenario's file and the key of its field.

    The key comes from the error's ``field`` (:data:`_ENGINE_KEYS`), the grid point from its
    ``run``: never from the message's words."""
    message = str(exc)
    key = None
    if exc.field:
        head, _, rest = exc.field.partition(".")
        base = _ENGINE_KEYS.get(head)
        if base is not None:  # said in the scenario's words: the key, then the reason
            key = f"{base}.{rest}" if rest else base
            message = exc.reason.lstrip(": ")
    run = exc.run
    if run is not None and layout is not None and not layout.is_flat and run < layout.size:
        message += f" (run {run}: {layout.point(run)})"
    return ScenarioError(f"{source}: [{key}] {message}" if key else f"{source}: {message}")


def run_batch(
    batch: Problem,
    *,
    progress: Callable[[int, int], None] | None = None,
    throw: bool = False,
) -> Any:
    """Simulate a ``[simulation]`` scenario's batch; returns a
    :class:`~seahelm.results.SimResult`.

    The engine validates what it runs before anything is integrated; its errors are raised
    as :class:`ScenarioError` naming the scenario file and the key they most likely come
    from. The result keeps the batch's layout (e.g. dims ``(kp, kd, time)``).

    Parameters
    ----------
    batch : Problem
        Result of :func:`load_scenario`, :func:`parse_scenario` or :func:`prepare_runs`.
    progress : callable(done_steps, total_steps), optional
        Called between chunks of the simulation loop.
    throw : bool, optional
        Raise :class:`~seahelm.errors.SimulationDiverged` on the first diverged run instead of
        recording it (default False).

    Returns
    -------
    SimResult

    Raises
    ------
    ScenarioError
        If the engine rejects the batch (timing, command counts, bounds labels, ...).
    """
    from ..simulation.batch import simulate_batch

    source = str(batch.metadata.get("scenario_source", "<string>"))
    try:
        return simulate_batch(batch, throw=throw, progress=progress)
    except ScenarioError:
        raise
    except ParameterError as exc:
        raise _engine_error(source, exc, batch.layout) from exc


def _vessel_model(scn: Scenario, source: str) -> Any:
    """The vessel model: ``vessel.model``, or the model of the ship ``vessel.ship``."""
    name = scn.vessel.model
    if name is None:
        ship = vessel_ship(scn, source)
        if ship is None:
            raise _err(source, "vessel.model",
                       "give a vessel model (see `seahelm models`) or a ship (vessel.ship: a "
                       "catalog name or a ship file)")
        return ship.model
    try:
        return get_model(name)
    except ValueError as exc:
        raise _err(source, "vessel.model", str(exc)) from None


def _guidance(scn: Scenario, source: str, controller: Any
              ) -> tuple[GuidanceLaw | None, dict[str, Any]] | None:
    """The ``[guidance]`` law and its parameter values (route and gains), checked; the law is
    None for a controller that follows the route itself (its parameters are a
    :class:`~seahelm.control.path_following.RouteParams`, e.g. ``lq-cross-track``)."""
    g = scn.guidance
    if g is None:
        return None
    gains = {k: v for k in ("acceptance_radius", "lookahead", "lookahead_min",
                            "lookahead_gamma", "kappa")
             if (v := getattr(g, k)) is not None}
    if issubclass(controller.params_type, RouteParams):
        extra = [k for k in ("law", *gains) if k in g.model_fields_set and k not in
                 controller.params_type.field_names()]
        if extra:
            raise _err(source, f"guidance.{extra[0]}",
                       f"controller '{controller.name}' follows the route itself: [guidance] "
                       "takes its waypoints and acceptance_radius, no guidance law or its gains")
        try:
            values = route_params(g.waypoints, params_type=RouteParams, **gains).as_dict()
        except ParameterError as exc:
            raise _err(source, "guidance", str(exc)) from None
        return None, values
    try:
        law = get_guidance_law(g.law)
    except ParameterError as exc:
        raise _err(source, "guidance.law", str(exc)) from None
    if "kappa" in gains and "kappa" not in law.params_type.field_names():
        raise _err(source, "guidance.kappa",
                   f"the '{law.name}' law has no integral gain (kappa is ILOS's), got "
                   f"{gains['kappa']!r}")
    try:
        values = route_params(g.waypoints, law=law, **gains).as_dict()
    except ParameterError as exc:
        raise _err(source, "guidance", str(exc)) from None
    return law, values


def _check_size(scn: Scenario, source: str, in_memory: bool, channels: int) -> None:
    """Refuse a batch whose recordings cannot fit in memory before it is expanded (drawing a
    million Monte-Carlo samples takes a while; the engine checks the exact size again)."""
    sim = scn.simulation
    assert sim is not None
    grid = scn.batch.grid
    mc = scn.batch.monte_carlo
    n_runs = math.prod(len(v) for v in grid.values()) * (mc.runs if mc is not None else 1)
    if n_runs > MAX_RUNS:
        sizes = " x ".join([str(len(v)) for v in grid.values()]
                           + ([f"{mc.runs} samples"] if mc is not None else []))
        raise _err(source, "batch",
                   f"{n_runs:,} runs ({sizes}) is more than one batch holds ({MAX_RUNS:,}); "
                   "split the study into several scenarios")
    steps = sim.t_final / sim.dt
    if not steps < 1e15:
        raise _err(source, "simulation.t_final",
                   f"{steps:.3g} steps (t_final/dt = {sim.t_final!r}/{sim.dt!r}) cannot run")
    n_rec = int(steps) // sim.record_every + 1 + (int(steps) % sim.record_every != 0)
    if not in_memory:  # (a sweep: each chunk is checked when it is made)
        return
    try:  # (one batch: all its runs at once)
        check_work(n_runs, steps, record_bytes=8.0 * n_runs * n_rec * channels)
    except WorkTooLarge as exc:
        raise _err(source, "simulation.t_final", exc.reason.removeprefix(": ")) from None
    try:
        check_record_memory(n_runs, n_rec, channels)
    except ParameterError as exc:
        raise _err(source, "simulation.record_every", str(exc)) from None


def scenario_work(scn: Scenario) -> tuple[int, float] | None:
    """The runs and the steps of a run of a ``[simulation]`` scenario (None for a manoeuvre:
    its durations come from the ship), from the validated text, before anything is expanded.
    """
    sim = scn.simulation
    if sim is None:
        return None
    grid = scn.batch.grid
    mc = scn.batch.monte_carlo
    n_runs = math.prod(len(v) for v in grid.values()) * (mc.runs if mc is not None else 1)
    return n_runs, sim.t_final / sim.dt


def _with_current(scn: Scenario, model: Any, source: str) -> dict[str, Any]:
    """The disturbance channels, with ``[environment.current]`` as ``current_north`` and
    ``current_east`` [m/s] (for a model that has them)."""
    out = dict(scn.environment.disturbance)
    current = scn.environment.current
    if current is None:
        return out
    channels = ("current_north", "current_east")
    if not set(channels) <= set(model.disturbance_labels):
        raise _err(source, "environment.current",
                   f"model '{model.name}' has no current channels (current_north, current_east "
                   "[m/s]; the mariner, mmg, nomoto1 and nomoto2 models have them)")
    both = [c for c in channels if c in out]
    if both:
        raise _err(source, "environment.current",
                   f"the current is given twice: here and as environment.disturbance."
                   f"{both[0]}")
    angle = math.radians(current.direction_deg)
    if isinstance(current.speed, dict):  # a speed profile in time, along a fixed direction
        try:
            out["current_north"] = make_signal(current.speed, scale=math.cos(angle))
            out["current_east"] = make_signal(current.speed, scale=math.sin(angle))
        except (ParameterError, ValueError, TypeError) as exc:
            raise _err(source, "environment.current.speed",
                       f"{exc} (got {current.speed!r})") from None
        return out
    out["current_north"] = current.speed * math.cos(angle)
    out["current_east"] = current.speed * math.sin(angle)
    return out


def _summary_names(states: tuple[str, ...]) -> set[str]:
    """The names of the per-run summary metrics (:func:`seahelm.analysis.maneuvers.summarize`),
    which a batch dimension must not take (its column would be overwritten in the table)."""
    names = {"final_yaw_rate", "final_heading_rad", "turning_diameter_m", "settling_time_s",
             "heading_error_deg", "overshoot_deg", "yaw_rate_error",
             "max_abs_cross_track_error_m", "max_abs_cross_track_error_on_track_m",
             "rms_cross_track_error_m",
             "final_cross_track_error_m", "time_to_complete_s", "mean_abs_rudder_deg",
             "rudder_reversals_per_min"}
    for lab in states:
        names |= {f"final_{lab}", f"{lab}_deg", f"max_abs_{lab}_deg"}
    return names
