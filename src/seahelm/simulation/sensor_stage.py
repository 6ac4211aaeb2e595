"""The position sensors' stage of the compiled closed loop: what a DP controller measures.

A DP system does not measure the vessel's low-frequency position: its position reference and
gyro compass see the total motion, the low-frequency one plus the first-order (wave-frequency)
surge, sway and yaw, and their own noise. :class:`PositionSensors` (``Problem(sensors=...)``)
asks for that; the stage (:class:`SensorStage`, :mod:`seahelm.simulation.stage`) writes, after
the outputs of the model and of the stages before it, at every recorded step and controller
sample of run i at step k::

    measured_north   = x_N + cos ψ · ξ₁ − sin ψ · ξ₂ + σ_N · n_i,k,0
    measured_east    = y_E + sin ψ · ξ₁ + cos ψ · ξ₂ + σ_E · n_i,k,1
    measured_heading = ψ + ξ₆ + σ_ψ · n_i,k,2

with ξ₁, ξ₂, ξ₆ the first-order surge, sway (body axes) and yaw of the in-loop first-order
stage (:mod:`seahelm.simulation.wave_motion_stage`: ``surge_wave``, ``sway_wave``,
``yaw_wave``, those of its DOF; zero without ``wave_motion`` or without that DOF) and n standard
normal numbers. The controller's ``north``, ``east`` and ``heading`` measurements are routed from
these outputs (a measurement it does not have is left alone, e.g. the velocities of ``dp-pid``).

**The noise** is a function of (run, step, channel), not a stream: n = Box–Muller on two
uniforms from the SplitMix64 finaliser (Steele, Lea & Flood 2014, "Fast splittable
pseudorandom number generators", OOPSLA '14, the ``mix64`` of their §3; the constants are
Stafford's "Mix13", as in Java's ``SplittableRandom``) of the run's 64-bit key plus a counter
of (step, channel). Run i's key is ``SeedSequence(seed, spawn_key=(i,))``'s first 64-bit word
(house rule 7), so a run's noise depends on its seed and index only: a batch gives each run's
values alone, stepping gives the whole horizon's, and a sweep's chunk (:meth:`select_runs`)
its runs' own. The stage does not act on the dynamics: with zero noise and no wave motion
the states are bit for bit those of a loop without it.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numba import njit

from ..errors import ParameterError
from .stage import Stage, StageCode, binding

__all__ = ["PositionSensors", "SensorStage", "SENSOR_OUTPUTS", "sensor_noise",
           "sensor_sample"]

#: The outputs the stage writes and their units.
SENSOR_OUTPUTS: tuple[tuple[str, str], ...] = (
    ("measured_north", "m"), ("measured_east", "m"), ("measured_heading", "rad"))
#: The controller measurements it replaces, in the order of :data:`SENSOR_OUTPUTS`.
MEASURED = ("north", "east", "heading")
#: The first-order DOF it adds (to north/east by the heading's rotation, yaw to the heading).
WAVE_DOFS = {"surge": "surge_wave", "sway": "sway_wave", "yaw": "yaw_wave"}
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_MIX1 = np.uint64(0xBF58476D1CE4E5B9)
_MIX2 = np.uint64(0x94D049BB133111EB)
_TO_UNIT = 2.0 ** -53


@dataclasses.dataclass(frozen=True, kw_only=True)
class PositionSensors:
    """What the controller's position and heading sensors see (module docstring).

    Attributes
    ----------
    noise_north, noise_east : float
        Standard deviation of the position noise [m] (default 0: none).
    noise_heading : float
        Standard deviation of the heading noise [rad] (default 0).
    wave_motion : bool
        Add the first-order surge, sway and yaw of the loop's first-order stage (``Problem(
        first_order=...)`` with one of those DOF; default False, as the scenario's ``[sensors]
        wave_motion``: a sensor adds nothing it is not asked for, so the defaults give the run
        without the stage bit for bit).
    seed : int
        Seed of the runs' noise keys (default 0).
    run_offset : int
        Index of the batch's first run in the whole (a sweep's chunk; default 0).
    """

    noise_north: float = 0.0
    noise_east: float = 0.0
    noise_heading: float = 0.0
    wave_motion: bool = False
    seed: int = 0
    run_offset: int = 0

    def __post_init__(self) -> None:
        for name, unit in (("noise_north", "m"), ("noise_east", "m"), ("noise_heading", "rad")):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                    or not (math.isfinite(v) and v >= 0.0):
                raise ParameterError(f"must be a finite number >= 0 [{unit}], got {v!r}",
                                     field=f"sensors.{name}", unit=unit, value=v)
            object.__setattr__(self, name, float(v))
        if not isinstance(self.wave_motion, (bool, np.bool_)):
            raise ParameterError(f"must be true or false, got {self.wave_motion!r}",
                                 field="sensors.wave_motion", value=self.wave_motion)
        for name in ("seed", "run_offset"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
                raise ParameterError(f"must be an integer >= 0, got {v!r}",
                                     field=f"sensors.{name}", value=v)

    @property
    def noise(self) -> tuple[float, float, float]:
        """(σ_N [m], σ_E [m], σ_ψ [rad])."""
        return (self.noise_north, self.noise_east, self.noise_heading)

    def keys(self, n_runs: int) -> np.ndarray:
        """The runs' 64-bit noise keys (module docstring), shape (n_runs,).

        Parameters
        ----------
        n_runs : int
            Runs of the batch.

        Returns
        -------
        numpy.ndarray of uint64
        """
        return np.array([np.random.SeedSequence(self.seed, spawn_key=(self.run_offset + i,))
                         .generate_state(1, np.uint64)[0] for i in range(n_runs)],
                        dtype=np.uint64)

    def select_runs(self, start: int, stop: int) -> "PositionSensors":
        """The sensors of runs ``start`` to ``stop`` − 1 alone (a sweep's chunk: run i keeps
        run i's noise).

        Parameters
        ----------
        start, stop : int
            Run indices of the batch, 0 <= start < stop.

        Returns
        -------
        PositionSensors
        """
        if not 0 <= start < stop:
            raise ParameterError(f"runs {start}:{stop} are not a slice of the batch",
                                 field="sensors")
        return dataclasses.replace(self, run_offset=self.run_offset + start)


@njit(cache=True)
def _mix64(z):  # pragma: no cover - compiled
    """SplitMix64's output function (Steele, Lea & Flood 2014) on a uint64."""
    z = z + _GOLDEN
    z = (z ^ (z >> np.uint64(30))) * _MIX1
    z = (z ^ (z >> np.uint64(27))) * _MIX2
    return z ^ (z >> np.uint64(31))


@njit(cache=True)
def sensor_noise(key, k, j):  # pragma: no cover - compiled
    """The standard normal number of run key ``key`` at step ``k``, channel ``j`` (0-7):
    Box–Muller on two uniforms in (0, 1] from :func:`_mix64` of key + 16 k + 2 j (+1)."""
    c = key + np.uint64(k) * np.uint64(16) + np.uint64(2 * j)
    a = _mix64(c)
    b = _mix64(c + np.uint64(1))
    u1 = (float(a >> np.uint64(11)) + 1.0) * _TO_UNIT
    u2 = float(b >> np.uint64(11)) * _TO_UNIT
    return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)


@njit(cache=True)
def sensor_sample(k, key, std, north, east, heading, surge1, sway1, yaw1,
                  out):  # pragma: no cover - compiled
    """The measured north, east, heading (module docstring) into ``out[0:3]``."""
    c, s = math.cos(heading), math.sin(heading)
    out[0] = north + (c * surge1 - s * sway1)
    out[1] = east + (s * surge1 + c * sway1)
    out[2] = heading + yaw1
    for j in range(3):
        if std[j] > 0.0:
            out[j] += std[j] * sensor_noise(key, k, j)


@dataclasses.dataclass(frozen=True)
class SensorStage(Stage):
    """The position sensors in the loop as a stage (module docstring).

    Attributes
    ----------
    waves : tuple of (str, int)
        The first-order DOF the loop has (``surge``, ``sway``, ``yaw``) and each one's index
        among the outputs of the stage before this one (the first-order stage's); they are
        added with ``wave_motion`` (a per-run gain of 1, else 0).
    before : int
        The number of those outputs (they end where this stage's begin).
    """

    waves: tuple[tuple[str, int], ...]
    before: int
    name = "sensors"
    members = ("noise", "keys", "wave_gain")

    @classmethod
    def from_problem(cls, problem: Any) -> "SensorStage | None":
        """The stage a problem asks for, or None (the loop then runs without it).

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        """
        sensors = problem.sensors
        if sensors is None:
            return None
        fo = problem.first_order
        if fo is None:
            return cls((), 0)
        labels = fo.output_signals("roll_angle" in problem.model.output_labels)[0]
        waves = tuple((d, labels.index(n)) for d, n in WAVE_DOFS.items() if n in labels)
        return cls(waves, len(labels))

    def outputs(self, model: Any) -> tuple[tuple[str, ...], tuple[str, ...]]:
        return tuple(n for n, _ in SENSOR_OUTPUTS), tuple(u for _, u in SENSOR_OUTPUTS)

    def check(self, problem: Any, model: Any) -> None:
        check_sensors(problem.sensors, problem.first_order, model, problem.controller)

    def code(self, model: Any, controller: Any, measurement_from: tuple[int, ...],
             first_output: int, jit: bool) -> StageCode:
        outs = model.output_labels
        x, y, psi = (outs.index(n) for n in MEASURED)
        base = first_output - self.before
        wave = dict(self.waves)
        # (× g[2][0]: 1 with wave_motion, else 0 — the same kernel either way, and x + 0.0
        # is x: the states are then those of a loop without the stage)
        parts = [f"g[2][0] * ym[{base + wave[d]}]" if d in wave else "0.0" for d in WAVE_DOFS]
        lines = (f"sensor_sample(k, g[1][i], g[0], ym[{x}], ym[{y}], ym[{psi}], "
                 f"{', '.join(parts)}, s[0])",
                 *(f"ym[{first_output + j}] = s[0][{j}]" for j in range(3)))
        meas = list(measurement_from)
        for j, name in enumerate(MEASURED):
            if name in controller.measurement_labels:
                meas[controller.measurement_labels.index(name)] = first_output + j
        return StageCode(bindings=(binding(sensor_sample, "sensor_sample", jit=jit),),
                         lines={"outputs": lines}, measurement_from=tuple(meas))

    def inputs(self, problem: Any, model: Any) -> Any:
        return problem.sensors

    def arrays(self, inputs: Any, n_runs: int) -> tuple[np.ndarray, ...]:
        return (np.array(inputs.noise, dtype=np.float64), inputs.keys(n_runs),
                np.array([1.0 if inputs.wave_motion else 0.0]))

    def scratch(self, model: Any, arrays: tuple[np.ndarray, ...],
                n_outputs: int) -> tuple[np.ndarray, ...]:
        from .stage import aligned_buffers

        return aligned_buffers([(3,)])

    def metadata(self, problem: Any) -> dict[str, Any]:
        s = problem.sensors
        return {"sensors": (f"position noise {s.noise_north:g} m / {s.noise_east:g} m, heading "
                            f"{math.degrees(s.noise_heading):g} deg, seed {s.seed}; wave motion: "
                            + ((", ".join(d for d, _ in self.waves) or "none")
                               if s.wave_motion else "none")
                            + " (seahelm.simulation.sensor_stage)")}


def check_sensors(sensors: Any, first_order: Any, model: Any, controller: Any) -> None:
    """Raise a :class:`~seahelm.errors.ParameterError` if a problem cannot take its sensors.

    Parameters
    ----------
    sensors : PositionSensors or None
        The problem's sensors.
    first_order : FirstOrderInLoop or None
        Its first-order motions in the loop.
    model : VesselModel
        Its vessel model (outputs ``north``, ``east``, ``heading``).
    controller : Controller
        Its controller (measures one of ``north``, ``east``, ``heading``).
    """
    if sensors is None:
        return
    if not isinstance(sensors, PositionSensors):
        raise ParameterError("must be a PositionSensors (seahelm.simulation.sensor_stage), got "
                             f"{type(sensors).__name__}", field="sensors")
    missing = [n for n in MEASURED if n not in model.output_labels]
    if missing:
        raise ParameterError(f": model '{model.name}' does not output {', '.join(missing)}",
                             field="sensors")
    if not set(MEASURED) & set(controller.measurement_labels):
        raise ParameterError(
            f": controller '{controller.name}' measures none of north, east, heading (it "
            f"measures {', '.join(controller.measurement_labels) or 'nothing'})",
            field="sensors")
    if sensors.wave_motion:
        labels = () if first_order is None else first_order.output_signals()[0]
        if not set(WAVE_DOFS.values()) & set(labels):
            raise ParameterError(
                ".wave_motion: needs first-order motions in the loop with surge, sway or yaw "
                "(Problem(first_order=first_order_in_loop(..., dofs=('surge', 'sway', 'yaw')))"
                "), got " + ("none" if first_order is None else
                             f"DOF {', '.join(first_order.dofs)}"),
                field="sensors", value=True)
