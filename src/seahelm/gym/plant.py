"""The ship an environment of :mod:`seahelm.gym` steers: its :class:`~seahelm.Problem` (N runs
of one ship, in calm water or in wind and waves), its commands and their bounds.

A :class:`Plant` is built once per environment; every episode of every sub-environment is a run
of the same :class:`~seahelm.Simulator` (the compiled loop of ``simulate``), reset by run.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError, ValidityRangeWarning
from ..resources import WorkTooLarge, memory_limit
from ..ships import get_ship
from ..simulation.problem import Problem
from ..simulation.stepping import Simulator

__all__ = ["Plant", "build_plant", "autopilot_params_for", "state_views", "WEATHER_KEYS"]

#: Weather keywords an environment takes [SI units, radians; directions the waves and wind come
#: from, clockwise from north]: any non-zero ``wind_speed`` adds Blendermann's wind loads, any
#: non-zero ``wave_height`` Lvov's mean wave loads (:mod:`seahelm.environment.loads`).
WEATHER_KEYS = ("wind_speed", "wind_direction", "wave_height", "wave_length", "wave_direction")


@dataclass(frozen=True)
class Plant:
    """A ship's batch, ready to step, and what its commands are.

    Attributes
    ----------
    ship : Ship
    simulator : Simulator
        N runs, horizon = one episode.
    command_labels, command_units : tuple of str
        The simulator's commands (the actuator's).
    command_start : ndarray (commands,)
        The commands of the straight approach (rudder trim, self-propulsion rps) [SI]: the
        commands an action does not set.
    state_start : ndarray (states,)
        The approach state (vessel then actuator states) [SI].
    speed : float
        Approach speed U_0 [m/s].
    length : float
        Ship length L [m].
    max_rudder : float
        Largest rudder command [rad] (the steering gear's, else 35°).
    autopilot : Controller or None
        The heading autopilot run inside the compiled loop (set-point actions), else None
        (the actions are the commands).
    action_period : float
        Time between two actions [s].
    intervals_per_action : int
        Controller intervals per action (1 without an autopilot: the commands are held over
        ``action_period``; with one, the autopilot's samples in ``action_period``).
    """

    ship: Any
    simulator: Simulator
    command_labels: tuple[str, ...]
    command_units: tuple[str, ...]
    command_start: np.ndarray
    state_start: np.ndarray
    speed: float
    length: float
    max_rudder: float
    action_period: float = 1.0
    autopilot: Any = None
    intervals_per_action: int = 1


def _weather(ship: Any, weather: Mapping[str, float]) -> dict[str, Any]:
    """Problem keywords of the environment's loads for ``weather`` (none in calm water)."""
    unknown = sorted(set(weather) - set(WEATHER_KEYS))
    if unknown:
        raise ParameterError(f": unknown weather keyword {unknown[0]!r}; valid: "
                             f"{', '.join(WEATHER_KEYS)}", field=unknown[0])
    values = {k: float(v) for k, v in weather.items() if v is not None}
    for key, v in values.items():
        if not math.isfinite(v) or (key in ("wind_speed", "wave_height", "wave_length")
                                    and v < 0):
            unit = "rad" if key.endswith("direction") else "m/s" if key == "wind_speed" else "m"
            raise ParameterError(f"must be finite{' and >= 0' if unit != 'rad' else ''} "
                                 f"[{unit}], got {v!r}", field=key, unit=unit, value=v)
    wind = values.get("wind_speed", 0.0) > 0
    waves = values.get("wave_height", 0.0) > 0
    if not (wind or waves):
        return {}
    from ..environment.loads import environment, ship_load_params

    env = environment(wind="blendermann" if wind else None, waves="lvov" if waves else None)
    kw = {k: values[k] for k in values if (wind and k.startswith("wind"))
          or (waves and k.startswith("wave"))}
    if waves and "wave_length" not in kw:
        kw["wave_length"] = ship.particulars.length  # (λ/L = 1: the largest mean loads)
    with warnings.catch_warnings():
        # a hull just outside Lvov's eq. (5)-(7) range (the KVLCC2's C_b 0.81 > 0.8)
        warnings.simplefilter("ignore", ValidityRangeWarning)
        params = ship_load_params(ship, env, **kw)
    return {"environment": env, "environment_params": params}


#: Memory of one sub-environment [B] of a ship task (HeadingKeeping ...), about twice what
#: one takes (peak RSS over 1,000 and 200,000 sub-environments of HeadingKeeping-v0,
#: KVLCC2 L7, RK4, 2026-12-02: 2.1-2.2 kB).
BYTES_PER_ENV = 4096


def check_env_memory(num_envs: int, bytes_per_env: float) -> None:
    """Refuse, before anything is allocated, more sub-environments than fit in memory.

    Parameters
    ----------
    num_envs : int
        Sub-environments.
    bytes_per_env : float
        The memory one takes [B] (:data:`BYTES_PER_ENV` for a ship task).

    Raises
    ------
    ParameterError
        Naming ``num_envs``, the memory it needs and what this process may use
        (:func:`seahelm.resources.memory_limit`: the machine's, its cgroup's or its
        address-space limit, the smallest).
    """
    need = float(num_envs) * bytes_per_env
    if need <= 1 << 26:  # (every limit that matters is larger; asking the OS costs ~60 us)
        return
    limit = memory_limit()
    if limit is not None and need > limit.bytes:
        raise ParameterError(f"= {num_envs} needs about {need / 1e9:.3g} GB "
                             f"({bytes_per_env:g} B a sub-environment), more than the "
                             f"{limit.bytes / 1e9:.3g} GB this process may use ({limit.source})"
                             f"; give at most {int(limit.bytes // bytes_per_env)}",
                             field="num_envs", unit="B", value=num_envs)


@contextmanager
def episode_named(episode_seconds: float) -> Iterator[None]:
    """Refusals of the engine's ``t_final`` (the work budget) re-raised naming
    ``episode_seconds``, the environment's keyword for it (the user never gave a ``t_final``).
    """
    try:
        yield
    except WorkTooLarge as exc:
        if exc.field != "t_final":
            raise
        raise WorkTooLarge(f": {exc.over}; a shorter `episode_seconds` (got {episode_seconds:g} "
                           f"s), a larger `dt` or fewer `num_envs` {exc.anyway}",
                           field="episode_seconds", work=exc.work, budget=exc.budget,
                           over=exc.over, anyway=exc.anyway) from None


def build_plant(ship: Any, *, num_envs: int, episode_seconds: float, dt: float,
                action_period: float, weather: Mapping[str, float] | None = None,
                integrator: Any = "rk4", autopilot: Any = None,
                autopilot_params: Any = None) -> Plant:
    """The :class:`Plant` of ``num_envs`` runs of ``ship``.

    Parameters
    ----------
    ship : Ship or str
        A ship or its catalog name / ship file.
    num_envs : int
        Runs (sub-environments).
    episode_seconds : float
        One episode [s] (the simulator's horizon); a whole multiple of ``action_period``.
    dt : float
        Integration step [s].
    action_period : float
        Time between two actions [s] (the controller interval), a whole multiple of ``dt``.
    weather : mapping, optional
        :data:`WEATHER_KEYS` (default calm water).
    integrator : str or ButcherTableau
        The fixed-step method (default ``"rk4"``; ``"euler"`` is the explicit Euler method of
        most Python ship environments).
    autopilot : Controller or str, optional
        A heading autopilot (a controller whose references include ``heading``, e.g.
        ``"pid-heading-rps"``) run inside the compiled loop every ``dt`` (or at its own
        sample period) on a per-run heading set-point (:func:`autopilot_params_for`).
    autopilot_params : Params, optional
        Its parameters (default :func:`autopilot_params_for`).

    Raises
    ------
    ParameterError
        Naming the argument (``ship``, ``num_envs``, a weather keyword, a time, ``autopilot``).
    """
    from ..analysis.equilibria.equilibrium import approach_state

    if isinstance(ship, str):
        try:
            ship = get_ship(ship)
        except (ValueError, FileNotFoundError) as exc:
            raise ParameterError(f": {exc}", field="ship", value=ship) from None
    if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) \
            or num_envs < 1:
        raise ParameterError(f"must be an integer >= 1, got {num_envs!r}", field="num_envs",
                             value=num_envs)
    check_env_memory(int(num_envs), BYTES_PER_ENV)
    for name, v in (("episode_seconds", episode_seconds), ("dt", dt),
                    ("action_period", action_period)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ParameterError(f"must be > 0 [s], got {v!r}", field=name, unit="s", value=v)
    ratio = action_period / dt
    if abs(ratio - round(ratio)) > 1e-9 * max(1.0, ratio) or round(ratio) < 1:
        raise ParameterError(f"must be a whole multiple of dt = {dt:g} s, got {action_period!r}",
                             field="action_period", unit="s", value=action_period)
    ratio = episode_seconds / action_period
    if abs(ratio - round(ratio)) > 1e-9 * max(1.0, ratio):
        raise ParameterError(f"must be a whole multiple of action_period = {action_period:g} s, "
                             f"got {episode_seconds!r}", field="episode_seconds", unit="s",
                             value=episode_seconds)
    start = approach_state(ship, trim=True)
    env_kw = _weather(ship, weather or {})
    rudder0 = float(start.inputs.get("rudder_angle", 0.0))
    inputs = {"rudder_command": rudder0, **start.inputs}
    gear = getattr(ship, "steering_gear", None)
    max_rudder = float(getattr(getattr(gear, "params", None), "max_angle", math.radians(35.0)))
    particulars = getattr(ship, "particulars", None)
    length = float(getattr(particulars, "length", None) or getattr(ship, "length", 0.0) or 0.0)
    if not length > 0:
        raise ParameterError(": the ship has no length (its particulars are needed to scale "
                             "the tasks)", field="ship", value=getattr(ship, "name", ship))
    n = int(num_envs)
    loop_kw: dict[str, Any] = {"controller_dt": float(action_period)}
    every = 1
    if autopilot is not None:
        autopilot, loop_kw, every = _autopilot_loop(
            ship, autopilot, autopilot_params, n, dt=float(dt), action_period=float(action_period),
            length=length, max_rudder=max_rudder, inputs=inputs,
            heading=float(start.state[list(ship.model.state_labels).index("heading")]))
    try:
        problem = Problem(ship=ship, x0=np.repeat(start.state[None], n, axis=0),
                          actuator_x0=[rudder0], t_final=float(episode_seconds), dt=float(dt),
                          record_every=max(1, int(round(episode_seconds / dt))),
                          integrator=integrator, **loop_kw, **env_kw)
    except ParameterError as exc:  # (the environment's keyword for the loop's controller)
        if autopilot is None or exc.field not in ("controller", "controller_params"):
            raise
        field = "autopilot" if exc.field == "controller" else "autopilot_params"
        raise ParameterError(exc.reason, field=field, unit=exc.unit, value=exc.value) from None
    with episode_named(episode_seconds):
        sim = Simulator(problem)
    labels = sim.command_labels
    command_start = np.array([float(inputs.get(c, 0.0)) for c in labels])
    obs0 = sim.reset()
    speed = float(obs0["speed"][0]) if "speed" in obs0 else float(np.hypot(
        obs0["surge_speed"][0], obs0["sway_speed"][0]))
    if not speed > 0:
        raise ParameterError(f": the approach speed is {speed!r} m/s; the tasks need a ship "
                             "under way", field="ship", value=getattr(ship, "name", ship))
    return Plant(ship=ship, simulator=sim, command_labels=labels,
                 command_units=sim.command_units, command_start=command_start,
                 state_start=np.array([sim.state(0)[s] for s in sim.state_labels]),
                 speed=speed, length=length, max_rudder=max_rudder,
                 action_period=float(action_period), autopilot=autopilot,
                 intervals_per_action=every)


def state_views(sim: Simulator, labels: tuple[str, ...] | None
                ) -> dict[str, np.ndarray] | None:
    """Views of the simulator's live state array (runs,) by label, for a task that reads only
    ``labels``, when each is a state that the loop outputs unchanged (as the MMG family and
    the planar models do for position, heading, speeds and yaw rate); else None.

    An environment that reads the states needs no observation from the loop (its outputs at
    the interval's end: a model evaluation per run and step,
    :func:`~seahelm.simulation.stepping_reference.advance_unobserved`). Whether an output is
    its state is probed on run 0 of the freshly reset simulator, with every state moved off
    the approach (the heading past π, so that a wrapped heading output is seen), through the
    loop's own observation; the simulator is reset afterwards.

    Parameters
    ----------
    sim : Simulator
        The plant's simulator, just reset.
    labels : tuple of str or None
        What the task reads (:meth:`seahelm.gym.tasks.Task.declared_reads`); None: not declared.

    Returns
    -------
    dict or None
        Label -> view ``sim._z[:, j]`` (live: the loop writes it in place), or None.
    """
    if not labels or any(n not in sim.state_labels or n not in sim.output_labels
                         for n in labels):
        return None
    z0 = np.array([sim.state(0)[n] for n in sim.state_labels])
    probe = z0 + 0.01 * (np.arange(z0.size) + 1.0) * (1.0 + np.abs(z0))
    if "heading" in sim.state_labels:
        probe[sim.state_labels.index("heading")] += 4.0
    try:
        sim.set_state(0, probe)
    except ParameterError:  # (outside the model's declared bounds: not probed)
        sim.reset()
        return None
    seen = sim.observe()
    same = all(seen[n][0] == probe[sim.state_labels.index(n)] for n in labels)
    sim.reset()
    if not same:
        return None
    z = sim._z
    return {n: z[:, sim.state_labels.index(n)] for n in labels}


def autopilot_params_for(autopilot: Any, *, length: float, speed: float, max_rudder: float,
                         propeller_rps: float | None = None) -> Any:
    """Default parameters of a heading autopilot for a ship: the controller's defaults, with a
    PD law scaled to the ship where the controller has those gains.

    ``K_p = 1`` [rad/rad], ``K_d = 1.5 L/U_0`` [s] (the derivative time of
    :class:`seahelm.encounters.HeadingAutopilot`: 1.5 times the time to run one length), the
    saturation ``δ_max`` and the held ``propeller_rps`` of the approach, for the parameters
    the controller has (``kp``, ``kd``, ``max_command``, ``propeller_rps``); the others keep the
    controller's defaults.

    Parameters
    ----------
    autopilot : Controller
        The controller.
    length, speed, max_rudder : float
        Ship length L [m], approach speed U_0 [m/s], rudder limit δ_max [rad].
    propeller_rps : float, optional
        The approach's propeller rps [1/s] (for a ``-rps`` controller).

    Returns
    -------
    Params
        Of ``autopilot.params_type``.
    """
    fields = set(autopilot.params_type.field_names())
    wanted = {"kp": 1.0, "kd": 1.5 * length / speed, "max_command": max_rudder,
              "propeller_rps": propeller_rps}
    return autopilot.params_type(**{k: v for k, v in wanted.items()
                                    if k in fields and v is not None})


def _autopilot_loop(ship: Any, autopilot: Any, params: Any, n: int, *, dt: float,
                    action_period: float, length: float, max_rudder: float,
                    inputs: Mapping[str, float], heading: float
                    ) -> tuple[Any, dict[str, Any], int]:
    """The autopilot, the Problem keywords that run it in the loop, its samples per action."""
    from ..registry import get_controller

    try:
        autopilot = get_controller(autopilot)
    except (ValueError, TypeError) as exc:
        raise ParameterError(f": {exc}", field="autopilot", value=autopilot) from None
    refs = autopilot.reference_labels
    if "heading" not in refs:
        raise ParameterError(f": controller '{autopilot.name}' takes no heading set-point "
                             f"(its references: {', '.join(refs) or 'none'}); a set-point "
                             "action needs a heading autopilot, e.g. 'pid-heading-rps'",
                             field="autopilot", value=autopilot.name)
    ctrl_dt = dt if autopilot.sample_period is None else float(autopilot.sample_period)
    ratio = action_period / ctrl_dt
    if abs(ratio - round(ratio)) > 1e-9 * max(1.0, ratio) or round(ratio) < 1:
        raise ParameterError(f"must be a whole multiple of the autopilot's sample period "
                             f"{ctrl_dt:g} s, got {action_period!r}", field="action_period",
                             unit="s", value=action_period)
    speed = float(ship.approach_speed)
    if params is None:
        params = autopilot_params_for(autopilot, length=length, speed=speed,
                                      max_rudder=max_rudder,
                                      propeller_rps=inputs.get("propeller_rps"))
    # a per-run constant reference, the loop's own array (a mapping: built, not the caller's)
    reference = {r: np.full((n, 1, 1), heading if r == "heading" else 0.0) for r in refs}
    return autopilot, {"controller": autopilot, "controller_params": params,
                       "controller_dt": ctrl_dt, "reference": reference}, int(round(ratio))


def reset_selection(options: Mapping[str, Any] | None, num_envs: int,
                    started: bool) -> np.ndarray:
    """The sub-environments a vector environment's ``reset`` starts: all, or those of
    ``options["reset_mask"]`` (gymnasium's autoreset option), as indices.

    Parameters
    ----------
    options : mapping, optional
        ``reset``'s options; ``{"reset_mask": bool array (num_envs,)}`` starts only those.
    num_envs : int
        Sub-environments.
    started : bool
        Whether the environment was reset before (the first reset starts every one).

    Returns
    -------
    numpy.ndarray
        Indices of the sub-environments to start.

    Raises
    ------
    ParameterError
        Naming ``options``: a mask of another shape or dtype, or a mask at the first reset.
    """
    mask = (options or {}).get("reset_mask")
    if mask is None:
        return np.arange(num_envs)
    m = np.asarray(mask)
    if m.shape != (num_envs,) or m.dtype != bool:
        raise ParameterError(f"['reset_mask'] must be a bool array of shape ({num_envs},), "
                             f"got {m.dtype} {m.shape}", field="options", value=m.shape)
    if not started and not m.all():
        raise ParameterError(": the first reset starts every sub-environment (no reset_mask)",
                             field="options")
    return np.flatnonzero(m)
