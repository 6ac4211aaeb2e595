"""Scenario files (TOML): schema, validation and the runs they describe.

A scenario is validated in one place, before anything runs. Structure and types are checked by
pydantic; names (models, catalog entries, parameters, state and signal channels) and values
(parameter ranges) by the components themselves. Every error names the file, the key path, the
bad value and what was expected, and is raised as :class:`ScenarioError` (a
:class:`~seahelm.errors.ParameterError`, so the CLI exits with code 2).

Layout (see ``examples/*.toml``)::

    title = "..."
    [vessel]            model, catalog (optional named parameter set), params, initial
    [actuator]          model, params
    [controller]        model, dt (sample period [s]), params, reference (per channel)
    [environment]       disturbance (per channel)
    [simulation]        t_final, dt, integrator, record_every, bounds
    [batch]             grid = {"controller.params.kp" = [..]}, [batch.monte_carlo] runs, seed, draws

Angles may be written in degrees with a ``_deg`` suffix on any parameter, initial state,
reference or disturbance channel whose unit is radians; they are converted at this edge.
The grid is a Cartesian product; Monte-Carlo draws are made per grid point with generators
spawned from ``SeedSequence(seed)``, and the seed is stored with the results.
"""

from __future__ import annotations

import itertools
import math
import tomllib
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from .errors import ParameterError
from .parameters import Params
from .registry import get_actuator, get_controller, get_model
from .simulation.integrators import INTEGRATORS
from .simulation.signals import make_signal
from .vessels import catalog

__all__ = ["Scenario", "ScenarioError", "load_scenario", "parse_scenario", "run_scenario",
           "default_scenario_text", "PreparedRuns", "prepare_runs"]


class ScenarioError(ParameterError):
    """A scenario file is invalid (the message names the file, key path, value, expectation)."""


SignalSpec = float | dict[str, Any]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class VesselSection(_Strict):
    model: str
    catalog: str | None = None
    params: dict[str, float] = Field(default_factory=dict)
    initial: dict[str, float] = Field(default_factory=dict)


class ActuatorSection(_Strict):
    model: str = "rudder-servo"
    params: dict[str, float] = Field(default_factory=dict)


class ControllerSection(_Strict):
    model: str = "open-loop"
    dt: Annotated[float, Field(gt=0)] | None = None
    params: dict[str, float] = Field(default_factory=dict)
    reference: dict[str, SignalSpec] = Field(default_factory=dict)


class EnvironmentSection(_Strict):
    disturbance: dict[str, SignalSpec] = Field(default_factory=dict)


class SimulationSection(_Strict):
    t_final: Annotated[float, Field(gt=0)]
    dt: Annotated[float, Field(gt=0)]
    integrator: Literal["euler", "heun", "rk4"] = "rk4"
    record_every: Annotated[int, Field(ge=1)] = 1
    bounds: dict[str, tuple[float, float]] = Field(default_factory=dict)


class Distribution(_Strict):
    distribution: Literal["normal", "uniform", "lognormal"]
    mean: float | None = None
    std: Annotated[float, Field(ge=0)] | None = None
    low: float | None = None
    high: float | None = None

    @model_validator(mode="after")
    def _check(self) -> "Distribution":
        if self.distribution in ("normal", "lognormal") and (self.mean is None or self.std is None):
            raise ValueError(f"a {self.distribution} draw needs `mean` and `std`")
        if self.distribution == "uniform":
            if self.low is None or self.high is None or not self.high > self.low:
                raise ValueError("a uniform draw needs `low` < `high`")
        return self


class MonteCarloSection(_Strict):
    runs: Annotated[int, Field(ge=1, le=1_000_000)]
    seed: int
    draws: dict[str, Distribution] = Field(default_factory=dict)


class BatchSection(_Strict):
    grid: dict[str, list[float]] = Field(default_factory=dict)
    monte_carlo: MonteCarloSection | None = None


class Scenario(_Strict):
    """The validated structure of a scenario file."""

    title: str = ""
    description: str = ""
    vessel: VesselSection
    actuator: ActuatorSection = Field(default_factory=ActuatorSection)
    controller: ControllerSection = Field(default_factory=ControllerSection)
    environment: EnvironmentSection = Field(default_factory=EnvironmentSection)
    simulation: SimulationSection
    batch: BatchSection = Field(default_factory=BatchSection)


# ------------------------------------------------------------------------------------------
def default_scenario_text() -> str:
    """The embedded default scenario: a 20° course change of the Mariner under PID."""
    return resources.files("seahelm").joinpath("data/default.toml").read_text()


def parse_scenario(text: str, *, source: str = "<string>") -> "PreparedRuns":
    """Parse and fully validate scenario text; nothing runs.

    Parameters
    ----------
    text : str
        TOML scenario text.
    source : str, optional
        Name of the source used in error messages (default "<string>").

    Returns
    -------
    PreparedRuns

    Raises
    ------
    ScenarioError
        If the text is not valid TOML or fails validation (one line per error).
    """
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{source}: not valid TOML: {exc}") from None
    try:
        scn = Scenario.model_validate(raw)
    except ValidationError as exc:
        lines = []
        for err in exc.errors():
            path = ".".join(str(p) for p in err["loc"]) or "<root>"
            value = err.get("input")
            shown = "" if isinstance(value, dict) else f", got {value!r}"
            lines.append(f"{source}: [{path}] {err['msg']}{shown}")
        raise ScenarioError("\n".join(lines)) from None
    return prepare_runs(scn, source=source, text=text)


def load_scenario(path: str | Path) -> "PreparedRuns":
    """Read, parse and validate a scenario file.

    Parameters
    ----------
    path : str or pathlib.Path
        TOML scenario file.

    Returns
    -------
    PreparedRuns

    Raises
    ------
    ScenarioError
        If the file is missing, not valid TOML or fails validation.
    """
    path = Path(path)
    if not path.is_file():
        raise ScenarioError(f"scenario file not found: {path}")
    return parse_scenario(path.read_text(), source=str(path))


# ------------------------------------------------------------------------------------------
class PreparedRuns:
    """Everything :func:`seahelm.simulation.engine.simulate` needs, validated.

    Attributes: ``scenario`` (the pydantic model), ``source``, ``text``, the components, the
    per-run parameter arrays, ``x0``, ``reference`` and ``disturbance`` callables/arrays,
    ``run_labels`` (what varies per run) and ``seed``.
    """

    def __init__(self, **kw: Any) -> None:
        self.__dict__.update(kw)

    @property
    def n_runs(self) -> int:
        return int(self.x0.shape[0])


def _err(source: str, path: str, message: str) -> ScenarioError:
    return ScenarioError(f"{source}: [{path}] {message}")


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


def _params(cls: type[Params], values: dict[str, float], base: Params | None) -> Params:
    return cls.from_mapping(values, base=base)


def _expand_batch(scn: Scenario, source: str) -> tuple[list[dict[str, float]], int | None]:
    """Per-run overrides {"section.kind.key": value} from the grid and Monte-Carlo draws."""
    grid_keys = list(scn.batch.grid)
    for key in grid_keys:
        if not scn.batch.grid[key]:
            raise _err(source, f"batch.grid.{key}", "needs at least one value, got []")
    grid = [dict(zip(grid_keys, combo))
            for combo in itertools.product(*(scn.batch.grid[k] for k in grid_keys))] or [{}]
    mc = scn.batch.monte_carlo
    if mc is None:
        return grid, None
    runs: list[dict[str, float]] = []
    children = np.random.SeedSequence(mc.seed).spawn(len(grid) * mc.runs)
    n = 0
    for point in grid:
        for _ in range(mc.runs):
            rng = np.random.default_rng(children[n])
            n += 1
            draw = dict(point)
            for key, dist in mc.draws.items():
                if dist.distribution == "normal":
                    draw[key] = float(rng.normal(dist.mean, dist.std))
                elif dist.distribution == "lognormal":
                    draw[key] = float(rng.lognormal(dist.mean, dist.std))
                else:
                    draw[key] = float(rng.uniform(dist.low, dist.high))
            runs.append(draw)
    return runs, mc.seed


_OVERRIDABLE = ("vessel.params.", "vessel.initial.", "actuator.params.", "controller.params.",
                "controller.reference.", "environment.disturbance.")


def prepare_runs(scn: Scenario, *, source: str = "<string>", text: str = "") -> PreparedRuns:
    """Resolve names, parameters, initial states and signals of every run (validating all).

    Parameters
    ----------
    scn : Scenario
        Validated scenario schema.
    source : str, optional
        Name of the source used in error messages (default "<string>").
    text : str, optional
        Scenario text, stored with the results (default "").

    Returns
    -------
    PreparedRuns
        Models, parameter arrays (runs, n_params), initial states (SI units, radians) and the
        reference and disturbance signals on the time grid.
    """
    try:
        model = get_model(scn.vessel.model)
    except ValueError as exc:
        raise _err(source, "vessel.model", str(exc)) from None
    try:
        actuator = get_actuator(scn.actuator.model)
    except ValueError as exc:
        raise _err(source, "actuator.model", str(exc)) from None
    try:
        controller = get_controller(scn.controller.model)
    except ValueError as exc:
        raise _err(source, "controller.model", str(exc)) from None
    base_params: Params | None = None
    if scn.vessel.catalog is not None:
        try:
            entry = catalog.get(scn.vessel.catalog)
        except ValueError as exc:
            raise _err(source, "vessel.catalog", str(exc)) from None
        if entry.model != model.name:
            raise _err(source, "vessel.catalog",
                       f"'{entry.name}' is a parameter set for model '{entry.model}', "
                       f"not '{model.name}'")
        base_params = entry.params
    if controller.n_commands != actuator.n_commands:
        raise _err(source, "controller.model",
                   f"'{controller.name}' gives {controller.n_commands} command(s) but actuator "
                   f"'{actuator.name}' takes {actuator.n_commands}")
    if scn.controller.dt is not None:
        ratio = scn.controller.dt / scn.simulation.dt
        if abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1):
            raise _err(source, "controller.dt",
                       f"must be a whole multiple of simulation.dt = {scn.simulation.dt} s, "
                       f"got {scn.controller.dt}")
    ratio = scn.simulation.t_final / scn.simulation.dt
    if abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1):
        raise _err(source, "simulation.t_final",
                   f"must be a whole multiple of simulation.dt = {scn.simulation.dt} s, "
                   f"got {scn.simulation.t_final}")
    labels = model.state_labels + actuator.state_labels
    for label in scn.simulation.bounds:
        if label not in labels:
            raise _err(source, f"simulation.bounds.{label}",
                       f"unknown state; valid: {', '.join(labels)}")

    runs, seed = _expand_batch(scn, source)
    for key in set().union(*runs):
        if not key.startswith(_OVERRIDABLE):
            raise _err(source, f"batch.{key}",
                       f"cannot vary '{key}'; keys start with one of: {', '.join(_OVERRIDABLE)}")

    t_grid = np.arange(int(round(ratio)) + 1) * scn.simulation.dt
    mp, ap, cp, x0s, refs, dists = [], [], [], [], [], []
    def random(spec: dict[str, Any]) -> bool:
        return any(isinstance(v, dict) and v.get("kind") == "sea" for v in spec.values())

    # a random signal gives every run its own realisation
    varied_ref = random(scn.controller.reference) or any(
        k.startswith("controller.reference.") for r in runs for k in r)
    varied_dist = random(scn.environment.disturbance) or any(
        k.startswith("environment.disturbance.") for r in runs for k in r)

    def section(over: dict[str, float], prefix: str, base: dict[str, Any]) -> dict[str, Any]:
        out = dict(base)
        out.update({k[len(prefix):]: v for k, v in over.items() if k.startswith(prefix)})
        return out

    def signals(spec: dict[str, Any], labels_: tuple[str, ...], units: tuple[str, ...],
                path: str, run: int) -> np.ndarray:
        arr = np.zeros((t_grid.size, max(len(labels_), 1)))
        for name, value in spec.items():
            try:
                j, scale = _channel(name, labels_, units)
                sig = make_signal(value, scale=scale)
                if getattr(sig, "random", False):
                    # run i draws from the i-th child of SeedSequence(seed)
                    seq = np.random.SeedSequence(sig.seed, spawn_key=(run,))
                    arr[:, j] = sig(t_grid, seed=seq)
                else:
                    arr[:, j] = sig(t_grid)
            except (ValueError, TypeError) as exc:
                raise _err(source, f"{path}.{name}", f"{exc} (got {value!r})") from None
        return arr[:, : len(labels_)] if labels_ else arr[:, :0]

    cache: dict[str, Any] = {}
    for i, over in enumerate(runs):
        where = f" (run {i}: {over})" if over else ""
        for key, sec, cls, base, bucket in (
            ("vessel.params", scn.vessel.params, model.params_type, base_params, mp),
            ("actuator.params", scn.actuator.params, actuator.params_type, None, ap),
            ("controller.params", scn.controller.params, controller.params_type, None, cp),
        ):
            values = section(over, key + ".", sec)
            try:
                bucket.append(_params(cls, values, base).to_array())
            except ParameterError as exc:
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
        if varied_ref or "ref" not in cache:
            cache["ref"] = signals(section(over, "controller.reference.", scn.controller.reference),
                                   controller.reference_labels, controller.reference_units,
                                   "controller.reference", i)
            refs.append(cache["ref"])
        if varied_dist or "dist" not in cache:
            cache["dist"] = signals(section(over, "environment.disturbance.",
                                            scn.environment.disturbance),
                                    model.disturbance_labels, model.disturbance_units,
                                    "environment.disturbance", i)
            dists.append(cache["dist"])

    def const_or_series(arrs: list[np.ndarray]) -> np.ndarray:
        stack = np.stack(arrs)  # (runs|1, steps+1, channels)
        if stack.shape[2] == 0:
            return stack[:, :1, :]
        if np.all(stack == stack[:, :1, :]):
            return stack[:, :1, :]
        return stack

    return PreparedRuns(
        scenario=scn,
        source=source,
        text=text,
        model=model,
        actuator=actuator,
        controller=controller,
        params=np.array(mp),
        actuator_params=np.array(ap),
        controller_params=np.array(cp),
        x0=np.array(x0s),
        reference=const_or_series(refs),
        disturbance=const_or_series(dists),
        run_overrides=runs,
        seed=seed,
    )


def run_scenario(
    prepared: PreparedRuns,
    *,
    progress: Callable[[int, int], None] | None = None,
    throw: bool = False,
) -> Any:
    """Simulate a prepared scenario; returns a :class:`~seahelm.results.SimResult`.

    Parameters
    ----------
    prepared : PreparedRuns
        Result of :func:`load_scenario`, :func:`parse_scenario` or :func:`prepare_runs`.
    progress : callable(done_steps, total_steps), optional
        Called between chunks of the simulation loop.
    throw : bool, optional
        Raise :class:`~seahelm.errors.SimulationDiverged` on the first diverged run instead of
        recording it (default False).

    Returns
    -------
    SimResult
    """
    from .simulation.engine import simulate

    scn = prepared.scenario
    sim = scn.simulation
    ref = prepared.reference
    dist = prepared.disturbance
    result = simulate(
        prepared.model,
        prepared.params,
        prepared.x0,
        t_final=sim.t_final,
        dt=sim.dt,
        controller=prepared.controller,
        controller_params=prepared.controller_params,
        actuator=prepared.actuator,
        actuator_params=prepared.actuator_params,
        reference=ref if ref.shape[-1] else None,
        disturbance=dist if dist.shape[-1] else None,
        controller_dt=scn.controller.dt,
        integrator=sim.integrator,
        record_every=sim.record_every,
        bounds=dict(sim.bounds),
        throw=throw,
        progress=progress,
        seed=prepared.seed,
        metadata={"title": scn.title, "scenario_source": prepared.source,
                  "scenario_text": prepared.text},
    )
    return result


_ = INTEGRATORS  # the Literal above mirrors this registry; tests check they agree
