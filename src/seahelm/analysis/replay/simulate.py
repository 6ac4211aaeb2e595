"""Replay a measured record: simulate it from its initial state with its measured inputs.

:func:`replay` takes one :class:`~seahelm.identification.records.ManoeuvreRecord` (a sea trial or a
free-running model test, :func:`~seahelm.identification.records.read_records`) and a ship, and
simulates the ship

* from the record's **first sample** (surge and sway speed, yaw rate, position, heading: the
  record's columns ``surge_speed``, ``sway_speed``, ``yaw_rate``, ``x`` (north), ``y`` (east),
  ``heading``; the reference point is the record's, the midship point for an MMG ship),
* with the record's **measured inputs** as the model's inputs (``rudder_angle`` and, for a ship
  with a propeller, ``propeller_rps``), with no actuator in between (the ``direct`` actuator:
  the measured rudder *is* the rudder). Between record samples the inputs are interpolated
  linearly (first-order hold, the ``samples`` signal of :mod:`seahelm.simulation.signals`)
  onto the integration grid and held over each step, as the engine holds its commands.

Then it computes the **same metrics from both tracks with the same code**: a turning circle's
advance, transfer and tactical diameter
(:func:`~seahelm.analysis.maneuvers.advance_transfer.turning_metrics`),
steady diameter (:func:`~seahelm.analysis.maneuvers.metrics.turning_diameter`) and speed loss
1 − U_end/U_0; a zig-zag's overshoots, execute times and period
(:func:`~seahelm.analysis.maneuvers.zigzag.zigzag_metrics`); and the RMS distance between the
measured and the simulated position at the record's times, over the first 60 s and over the
whole record, in ship lengths.

What kind of manoeuvre a record is (``kind="auto"``) is read from the measured rudder after the
order (the start of the rudder's first move beyond 10 % of its largest |δ|): held on one side —
a turning circle; switched between two sides at a nearly constant angle (the held angles'
spread < 10 % of their mean) at least twice — a zig-zag, whose check angle is the median
heading deviation at which the rudder left its held angle, rounded to a whole degree; anything
else (random or berthing inputs) — only the position error is reported.

A zig-zag can also be replayed **closed loop** (``closed_loop=True``): from the first sample,
the rudder is switched by the *simulated* heading at the check angle (the zig-zag controller of
:mod:`seahelm.control.zigzag`, the rudder angle δ_z the median of the measured held angles, the
first side the measured rudder's, the base heading the measured one at the order) through the
ship's steering gear, the propeller held at its measured rps at the order.

The wind (``wind="measured"``): the record's true wind speed (``true_wind_speed``) is a
time-varying input (first-order hold, the environment's ``wind_gust`` channel over a zero mean
speed) and its direction (``true_wind_direction``, where it comes from, clockwise from north)
is held at its circular mean — the engine's wind direction is a parameter, not a signal; the
result gives the direction's circular standard deviation so that a record whose wind veered
shows it. The loads are the ship's wind-load model from its windage particulars
(:func:`~seahelm.environment.loads.ship_load_params`): Fujiwara et al. (1998) for a ship whose
particulars give their windage data (the Esso Osaka's published wind model), else Blendermann
(1994). With
``wind="none"`` (the default) the simulated ship is in still air. Currents are not replayed.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Literal

import numpy as np

from ...errors import ParameterError
from ...identification.records import ManoeuvreRecord

__all__ = ["ReplayResult", "replay", "manoeuvre_metrics", "classify", "REPLAY_CHANNELS",
           "RMS_WINDOW", "KINDS", "WIND"]

#: Record channels the replay needs: the initial state (the heading is the record's own).
REPLAY_CHANNELS = ("surge_speed", "sway_speed", "x", "y")

#: The first part of the record over which the early position error is taken [s].
RMS_WINDOW = 60.0

#: Manoeuvre kinds :func:`replay` computes metrics for (``"auto"``: read from the rudder).
KINDS = ("auto", "turning", "zigzag", "none")

#: The wind a replay can be given: none (still air) or the record's measured true wind.
WIND = ("none", "measured")

#: Fraction of the largest |δ| beyond which the rudder counts as ordered.
_ORDER_FRACTION = 0.1


@dataclasses.dataclass(frozen=True)
class ReplayResult:
    """A replayed record: the measured and the simulated track on the record's times.

    Attributes
    ----------
    record : ManoeuvreRecord
        The record replayed.
    ship : str
        Name of the ship simulated.
    kind : str
        ``"turning"``, ``"zigzag"`` or ``"none"`` (no standard manoeuvre: position error only).
    time : ndarray
        The record's times [s].
    measured, simulated : dict of str to ndarray
        ``north``, ``east`` [m], ``heading`` [rad], ``surge_speed``, ``sway_speed``, ``speed``
        [m/s], ``yaw_rate`` [rad/s], ``rudder_angle`` [rad] and ``propeller_rps`` [1/s] (where
        the record has it), on ``time``.
    metrics : dict of str to tuple of float
        Metric name -> (measured, simulated), SI units and radians (NaN where not reached).
    rms_error_window, rms_error : float
        RMS position error over the first :data:`RMS_WINDOW` seconds and over the whole record,
        in ship lengths [-].
    length : float
        The ship's length L [m].
    dt : float
        The integration step [s].
    check_angle : float or None
        A zig-zag's check angle ψ_z [rad].
    closed_loop : bool
        Whether the rudder was switched by the simulated heading (a zig-zag) rather than
        replayed.
    wind : dict
        ``{"kind": "none"}``, or for the measured wind its ``load_model``, the mean speed
        [m/s], the ``direction`` held [rad] and its circular standard deviation
        ``direction_spread`` [rad].
    """

    record: ManoeuvreRecord
    ship: str
    kind: str
    time: np.ndarray
    measured: dict[str, np.ndarray]
    simulated: dict[str, np.ndarray]
    metrics: dict[str, tuple[float, float]]
    rms_error_window: float
    rms_error: float
    length: float
    dt: float
    check_angle: float | None = None
    closed_loop: bool = False
    wind: dict[str, Any] = dataclasses.field(default_factory=lambda: {"kind": "none"})

    def _summary(self) -> tuple[str, list[tuple[str, object]]]:
        how = "closed loop" if self.closed_loop else "measured rudder"
        if self.check_angle is not None:
            how += f", check angle {math.degrees(self.check_angle):.3g} deg"
        return (f"ReplayResult: {self.record.name} with {self.ship}", [
            ("kind", f"{self.kind} ({how}; wind {self.wind['kind']})"),
            ("record", f"{len(self.time)} samples, t = {self.time[0]:.6g} … "
                       f"{self.time[-1]:.6g} s; dt {self.dt:.3g} s"),
            ("rms error", f"{self.rms_error_window:.4g} L (first {RMS_WINDOW:g} s), "
                          f"{self.rms_error:.4g} L (whole record)"),
            ("metrics", ", ".join(self.metrics) or "none")])

    def __repr__(self) -> str:
        from ..._repr import summary_text

        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        from ..._repr import summary_html

        return summary_html(*self._summary())

    def to_xarray(self) -> Any:
        """Both tracks as one :class:`xarray.Dataset` with a ``track`` dimension (measured,
        simulated) and the record's ``time``; the metrics and errors as attributes."""
        import xarray as xr

        units = {"north": "m", "east": "m", "heading": "rad", "surge_speed": "m/s",
                 "sway_speed": "m/s", "speed": "m/s", "yaw_rate": "rad/s",
                 "rudder_angle": "rad", "propeller_rps": "1/s"}
        data = {k: (("track", "time"), np.stack([self.measured[k], self.simulated[k]]),
                    {"units": units[k]}) for k in self.measured}
        from .dataset import REPLAY_FORMAT

        attrs = {"format": REPLAY_FORMAT, "record": self.record.name, "ship": self.ship,
                 "kind": self.kind,
                 "rms_error_60s_L": self.rms_error_window, "rms_error_L": self.rms_error,
                 "length_m": self.length, "dt_s": self.dt,
                 "rudder": "closed loop" if self.closed_loop else "measured",
                 **{f"wind_{k}": v for k, v in self.wind.items()}}
        if self.check_angle is not None:
            attrs["check_angle_rad"] = self.check_angle
        for name, (m, s) in self.metrics.items():
            attrs[f"measured_{name}"], attrs[f"simulated_{name}"] = m, s
        return xr.Dataset(data, coords={"track": ["measured", "simulated"],
                                        "time": ("time", self.time, {"units": "s"})},
                          attrs=attrs)


def _order_index(rudder: np.ndarray) -> int:
    """The sample the rudder starts its first move from: back from the first sample beyond
    10 % of the largest |δ| while |δ| falls (the start of that monotone ramp)."""
    big = np.abs(rudder) > _ORDER_FRACTION * np.max(np.abs(rudder))
    k = int(np.argmax(big))
    while k > 0 and abs(rudder[k - 1]) < abs(rudder[k]):
        k -= 1
    return k


def _held(rudder: np.ndarray, k0: int) -> tuple[np.ndarray, np.ndarray]:
    """Signs and indices of the rudder samples after ``k0`` beyond half its largest |δ|."""
    amp = float(np.max(np.abs(rudder)))
    idx = k0 + np.flatnonzero(np.abs(rudder[k0:]) > 0.5 * amp)
    return np.sign(rudder[idx]), idx


def classify(record: ManoeuvreRecord) -> tuple[str, float | None]:
    """The kind of manoeuvre a record is, read from its rudder (module docstring).

    Parameters
    ----------
    record : ManoeuvreRecord
        The measured record (its rudder angle and heading are read).

    Returns
    -------
    kind : str
        ``"turning"``, ``"zigzag"`` or ``"none"``.
    check_angle : float or None
        A zig-zag's check angle [rad], rounded to a whole degree.
    """
    delta = record.rudder_angle
    k0 = _order_index(delta)
    signs, idx = _held(delta, k0)
    if signs.size == 0:
        return "none", None
    switches = np.flatnonzero(np.diff(signs) != 0)
    if switches.size == 0:
        return "turning", None
    held = np.abs(delta[idx])
    if switches.size < 2 or np.std(held) > 0.1 * np.mean(held):
        return "none", None
    return "zigzag", _check_angle(record, k0, signs, idx, switches)


def _check_angle(record: ManoeuvreRecord, k0: int, signs: np.ndarray, idx: np.ndarray,
                 switches: np.ndarray) -> float | None:
    if record.heading is None:
        return None
    delta, psi = record.rudder_angle, record.heading
    amp = float(np.median(np.abs(delta[idx])))
    devs = []
    for j in switches:
        s, k = signs[j], int(idx[j])  # the last sample past half the angle before the switch
        while k > k0 and s * delta[k] < 0.95 * amp:
            k -= 1  # back to the last sample at the held angle: the rudder leaves it after it
        devs.append(abs(psi[k] - psi[k0]))
    return math.radians(round(math.degrees(float(np.median(devs)))))


def manoeuvre_metrics(kind: str, time: np.ndarray, track: dict[str, np.ndarray],
                      rudder: np.ndarray, *, check_angle: float | None = None,
                      first_side: float = 1.0) -> dict[str, float]:
    """The standard metrics of one track (the same code for the measured and the simulated).

    Parameters
    ----------
    kind : {"turning", "zigzag", "none"}
        The manoeuvre.
    time : ndarray
        Times [s].
    track : dict of str to ndarray
        ``north``, ``east`` [m], continuous ``heading`` [rad], ``speed`` [m/s].
    rudder : ndarray
        The (measured) rudder angle [rad], for the order time and the first side.
    check_angle : float, optional
        A zig-zag's check angle ψ_z [rad].
    first_side : {1, -1}, optional
        A zig-zag's first turn: +1 heading increasing (default), −1 decreasing.

    Returns
    -------
    dict of str to float
        Turning: ``advance``, ``transfer``, ``tactical_diameter`` [m], ``steady_diameter``
        [m] (of the last full circle while the rudder is held; NaN below 360°),
        ``speed_loss`` [-] (1 − U_end/U_0, U_end at the last sample the rudder is held: a
        record that ends by stopping the propeller or easing the rudder is not counted).
        Zig-zag: ``overshoot_1..3`` [rad], ``execute_time_2..4`` [s] (from the first execute),
        ``time_to_check_yaw`` [s] and ``period`` [s]. None: empty.
    """
    from ..maneuvers.metrics import turning_diameter
    from ..maneuvers.zigzag import zigzag_metrics
    from ..maneuvers.advance_transfer import turning_metrics

    k0 = _order_index(rudder)
    north, east, psi = track["north"], track["east"], track["heading"]
    if kind == "turning":
        m = turning_metrics(time, north, east, psi, order_time=float(time[k0]))
        speed = track["speed"]
        held = _held(rudder, k0)[1]
        end = int(held[-1]) + 1 if held.size else time.size  # the turn ends with the rudder
        return {"advance": float(m.advance[0]), "transfer": float(m.transfer[0]),
                "tactical_diameter": float(m.tactical_diameter[0]),
                "steady_diameter": float(turning_diameter(north[k0:end], east[k0:end],
                                                          psi[k0:end])[0]),
                "speed_loss": (float(1.0 - speed[end - 1] / speed[k0]) if speed[k0] > 0
                               else math.nan)}  # (no approach speed: not defined)
    if kind == "zigzag":
        if check_angle is None:
            raise ParameterError("a zig-zag needs its check angle [rad] (a record with a "
                                 "heading)", field="check_angle")
        z = zigzag_metrics(time, psi, trigger=check_angle, first_side=first_side,
                           base_heading=float(psi[k0]), order_time=float(time[k0]))
        out = {f"overshoot_{j + 1}": float(z.overshoot[0, j]) for j in range(3)}
        out.update({f"execute_time_{j + 2}": float(z.execute_time[0, j]) for j in range(3)})
        out.update(time_to_check_yaw=float(z.time_to_check_yaw[0]), period=float(z.period[0]))
        return out
    return {}


def _rms(time: np.ndarray, measured: dict[str, np.ndarray], simulated: dict[str, np.ndarray],
         length: float, window: float) -> float:
    keep = time - time[0] <= window + 1e-9
    d2 = ((measured["north"] - simulated["north"]) ** 2
          + (measured["east"] - simulated["east"]) ** 2)[keep]
    return float(np.sqrt(np.mean(d2)) / length)


def _measured(record: ManoeuvreRecord) -> dict[str, np.ndarray]:
    ch = record.channels
    missing = [c for c in REPLAY_CHANNELS if c not in ch]
    if record.heading is None:
        missing.insert(0, "heading")
    if missing:
        raise ParameterError(f"{record.name}: a replay needs column(s) {', '.join(missing)} "
                             "(the initial state and the measured track)", field=missing[0])
    u, v = ch["surge_speed"], ch["sway_speed"]
    r = record.yaw_rate if record.yaw_rate is not None else np.gradient(record.heading,
                                                                        record.time)
    out = {"north": ch["x"], "east": ch["y"], "heading": record.heading, "surge_speed": u,
           "sway_speed": v, "speed": np.hypot(u, v), "yaw_rate": r,
           "rudder_angle": record.rudder_angle}
    if "propeller_rps" in ch:
        out["propeller_rps"] = ch["propeller_rps"]
    return out


def _time_step(record: ManoeuvreRecord, length: float, speed: np.ndarray,
               dt: float | None) -> tuple[float, int]:
    duration = record.duration
    if dt is None:
        dt = default_step(record, length, speed)
    elif not (math.isfinite(dt) and dt > 0):
        raise ParameterError(f"must be > 0 [s], got {dt!r}", field="dt")
    n = max(int(math.ceil(duration / dt - 1e-9)), 1)
    return duration / n, n


def default_step(record: ManoeuvreRecord, length: float, speed: np.ndarray) -> float:
    """The replay's default integration step [s]: the record's median sampling interval, at
    most L/(100 U_max) (a hundred steps per ship length at the record's top speed).

    Parameters
    ----------
    record : ManoeuvreRecord
        The measured record (its median sampling interval).
    length : float
        The ship's length L [m].
    speed : numpy.ndarray
        The record's speed samples [m/s] (their maximum is U_max).

    Returns
    -------
    float
        The step [s].
    """
    u_max = max(float(np.max(speed)), 1e-6)
    return min(record.median_interval, length / (100.0 * u_max))


def replay(record: ManoeuvreRecord, ship: Any, *,
           kind: Literal["auto", "turning", "zigzag", "none"] = "auto",
           check_angle: float | None = None, dt: float | None = None,
           closed_loop: bool = False, wind: Literal["none", "measured"] = "none",
           wind_loads: str | None = None) -> ReplayResult:
    """Simulate a measured record from its first sample with its measured inputs.

    Parameters
    ----------
    record : ManoeuvreRecord
        The record (:func:`~seahelm.identification.records.read_records`); it needs ``heading``,
        ``surge_speed``, ``sway_speed``, ``x``, ``y`` and, for a ship with a propeller,
        ``propeller_rps``.
    ship : Ship or str
        The ship (a catalog name or a ship file).
    kind : {"auto", "turning", "zigzag", "none"}, optional
        The manoeuvre whose metrics are computed (default: read from the rudder, see the
        module docstring).
    check_angle : float, optional
        A zig-zag's check angle ψ_z [rad] (default: read from the record).
    dt : float, optional
        Integration step [s] (default: the record's median sampling interval, at most L/(100
        U_max)); rounded down so that the record's duration is a whole number of steps.
    closed_loop : bool, optional
        A zig-zag only: switch the rudder by the simulated heading at the check angle
        through the ship's steering gear (module docstring) instead of replaying the measured
        rudder (default False).
    wind : {"none", "measured"}, optional
        Still air (default) or the record's measured true wind (module docstring).
    wind_loads : str, optional
        The wind-load model with the measured wind (a name in
        :data:`~seahelm.environment.loads.WIND_LOADS`); default: ``"fujiwara"`` for a ship
        whose particulars give Fujiwara's windage data (``superstructure_lateral_area``, ...:
        ``esso-osaka-3m``), else ``"blendermann"``.

    Returns
    -------
    ReplayResult

    Raises
    ------
    ParameterError
        A record without a needed column, a kind not in :data:`KINDS`, a record shorter than
        the manoeuvre needs (a turn that does not reach 180° of heading change, a zig-zag
        without its third execute), a simulation that diverged.
    """
    from ...ships import get_ship
    from ...simulation.engine import simulate
    from ...simulation.problem import Problem
    from ...simulation.signals import Samples

    if kind not in KINDS:
        raise ParameterError(f"must be one of {', '.join(KINDS)}, got {kind!r}", field="kind")
    if wind not in WIND:
        raise ParameterError(f"must be one of {', '.join(WIND)}, got {wind!r}", field="wind")
    found = get_ship(ship)
    measured = _measured(record)
    model = found.model
    t = record.time
    step, n_steps = _time_step(record, found.length, measured["speed"], dt)
    inputs = {"rudder_angle": measured["rudder_angle"]}
    if "propeller_rps" in model.input_labels:
        if "propeller_rps" not in measured:
            raise ParameterError(f"{record.name}: ship {found.name} has a propeller; the "
                                 "replay needs column propeller_rps", field="propeller_rps")
        inputs["propeller_rps"] = measured["propeller_rps"]
    t0 = float(t[0])
    chosen, angle = (classify(record) if kind == "auto" else (kind, None))
    if check_angle is not None:
        angle = float(check_angle)
    elif chosen == "zigzag" and angle is None:
        angle = classify(record)[1]
    if check_angle is not None and chosen != "zigzag":
        raise ParameterError(f"{record.name}: a check angle is a zig-zag's; this record is "
                             f"{chosen!r} (drop it, or give kind 'zigzag')", field="check_angle")
    if chosen == "zigzag" and angle is None:
        raise ParameterError(f"{record.name}: the rudder does not switch between two sides "
                             "at a constant angle, so the check angle cannot be read from the "
                             "record; give it explicitly", field="check_angle")
    if closed_loop and chosen != "zigzag":
        raise ParameterError(f"{record.name}: a closed-loop replay is for a zig-zag; this "
                             f"record is {chosen!r}", field="closed_loop")
    first = {"surge_speed": measured["surge_speed"][0], "sway_speed": measured["sway_speed"][0],
             "yaw_rate": measured["yaw_rate"][0], "north": measured["north"][0],
             "east": measured["east"][0], "heading": measured["heading"][0]}
    x0 = model.initial_state(**{k: v for k, v in first.items() if k in model.state_labels})
    timing = {"t_final": step * n_steps, "dt": step, "ship": found, "x0": x0,
              "metadata": {"replay_of": record.name}}
    air: dict[str, Any] = {"kind": "none"}
    if wind == "measured":
        air, loads = _measured_wind(record, found, wind_loads or _default_wind_loads(found))
        timing.update(loads)
    if closed_loop:
        problem = _closed_loop(record, found, measured, float(angle), timing)  # type: ignore
    else:
        reference = {k: Samples(tuple((t - t0).tolist()), tuple(v.tolist()))
                     for k, v in inputs.items()}
        problem = Problem(actuator="direct", reference=reference, **timing)
    result = _simulate(simulate, problem, record, step, n_steps)
    status = result.messages()[0]
    if status != "ok":
        usual = default_step(record, found.length, measured["speed"])
        if dt is not None and step > usual * (1.0 + 1e-9):  # (the step given, not the ship)
            raise ParameterError(
                f"= {dt:g} s: the replay of {record.name} with ship {found.name} {status}; "
                f"the step is coarser than the default {usual:.3g} s (the record's interval "
                f"{record.median_interval:.3g} s, at most L/(100 U_max)): give a smaller "
                "step, or leave the default", field="dt", unit="s", value=dt)
        raise ParameterError(f"{record.name}: the replay with ship {found.name} failed: "
                             f"{status}", field="ship")
    grid = result.time + t0
    simulated = {}
    for key in measured:
        source = key
        values = np.asarray(result[source])[0]
        if key == "heading":
            values = np.unwrap(values)
        simulated[key] = np.interp(t, grid, values)
    side = _first_side(measured["heading"], _order_index(record.rudder_angle))
    metrics_m, metrics_s = (manoeuvre_metrics(chosen, t, track, record.rudder_angle,
                                              check_angle=angle, first_side=side)
                            for track in (measured, simulated))
    _check_long_enough(record, chosen, metrics_m)
    return ReplayResult(
        record=record, ship=found.name, kind=chosen, time=t, measured=measured,
        simulated=simulated, metrics={k: (metrics_m[k], metrics_s[k]) for k in metrics_m},
        rms_error_window=_rms(t, measured, simulated, found.length, RMS_WINDOW),
        rms_error=_rms(t, measured, simulated, found.length, math.inf),
        length=found.length, dt=step, check_angle=angle, closed_loop=closed_loop, wind=air)


def _simulate(simulate: Any, problem: Any, record: ManoeuvreRecord, step: float,
              n_steps: int) -> Any:
    """``simulate(problem)``; too much work or recording said in the replay's words (the
    step, the record's duration), not the engine's (``t_final``, ``record_every``)."""
    from ...resources import WorkTooLarge
    from ...simulation.engine import RecordingTooLarge

    try:
        return simulate(problem)
    except WorkTooLarge as exc:
        too_much, anyway = exc.over, f" {exc.anyway}" if exc.anyway else ""
    except RecordingTooLarge as exc:
        too_much, anyway = f"it would record {exc.size_text()}", ""
    raise ParameterError(
        f"= {step:g} s: the replay of {record.name} ({record.duration:.6g} s) takes "
        f"{n_steps:,} steps: {too_much}; a larger step (the record's interval is "
        f"{record.median_interval:.3g} s){anyway}", field="dt", unit="s", value=step)


def _default_wind_loads(ship: Any) -> str:
    """Fujiwara's loads for a ship with their windage data, else Blendermann's."""
    part = ship.particulars
    fujiwara = ("superstructure_lateral_area", "superstructure_centre", "superstructure_height",
                "windage_height")
    if part is not None and all(getattr(part, n) is not None for n in fujiwara):
        return "fujiwara"
    return "blendermann"


def _measured_wind(record: ManoeuvreRecord, ship: Any, load_model: str
                   ) -> tuple[dict[str, Any], dict[str, Any]]:
    """The record's true wind as the Problem's environment fields (module docstring)."""
    from ...environment.loads import environment, ship_load_params
    from ...simulation.signals import Samples

    missing = [c for c in ("true_wind_speed", "true_wind_direction") if c not in record.channels]
    if missing:
        raise ParameterError(f"{record.name}: the measured wind needs column(s) "
                             f"{', '.join(missing)}", field=missing[0])
    speed = record.channels["true_wind_speed"]
    if np.any(speed < 0):
        row = int(np.flatnonzero(speed < 0)[0]) + 2
        raise ParameterError(f"{record.name}: column `{record.column('true_wind_speed')}` "
                             f"row {row} is "
                             f"{float(speed[row - 2])!r} [m/s] (< 0)", field="true_wind_speed")
    theta = record.channels["true_wind_direction"]
    c, s = float(np.mean(np.cos(theta))), float(np.mean(np.sin(theta)))
    direction = math.atan2(s, c)
    spread = math.sqrt(-2.0 * math.log(min(max(math.hypot(c, s), 1e-300), 1.0)))
    env = environment(wind=load_model)
    params = ship_load_params(ship, env, wind_speed=0.0, wind_direction=direction)
    t = record.time - record.time[0]
    gust = Samples(tuple(t.tolist()), tuple(speed.tolist()))
    air = {"kind": "measured", "load_model": env.wind.name, "mean_speed": float(np.mean(speed)),
           "direction": direction, "direction_spread": spread}
    return air, {"environment": env, "environment_params": params,
                 "disturbance": {"wind_gust": gust}}


def _closed_loop(record: ManoeuvreRecord, ship: Any, measured: dict[str, np.ndarray],
                 trigger: float, timing: dict[str, Any]) -> Any:
    """The zig-zag controller through the ship's steering gear (module docstring)."""
    from ...control.zigzag import ZIGZAG, ZIGZAG_RPS, ZigZagParams, ZigZagRpsParams
    from ...simulation.problem import Problem

    delta = record.rudder_angle
    k0 = _order_index(delta)
    signs, idx = _held(delta, k0)
    common = {"rudder_amplitude": float(np.median(np.abs(delta[idx]))),
              "heading_trigger": trigger, "first_side": float(signs[0]),
              "base_heading": float(measured["heading"][k0])}
    if "propeller_rps" in ship.model.input_labels:
        controller, params = ZIGZAG_RPS, ZigZagRpsParams(
            propeller_rps=float(measured["propeller_rps"][k0]), **common)
    else:
        controller, params = ZIGZAG, ZigZagParams(**common)
    return Problem(controller=controller, controller_params=params,
                   actuator_x0=[float(delta[0])], **timing)


def _first_side(heading: np.ndarray, k0: int) -> float:
    """+1 if the measured heading first turns to increase after the order, else −1 (the sign
    convention of the record's rudder is not assumed)."""
    dev = heading[k0:] - heading[k0]
    far = np.flatnonzero(np.abs(dev) >= min(0.5 * np.max(np.abs(dev)), math.radians(2.0)))
    return 1.0 if far.size == 0 or dev[far[0]] >= 0 else -1.0


def _check_long_enough(record: ManoeuvreRecord, kind: str, metrics: dict[str, float]) -> None:
    last = len(record) + 1  # the CSV row of the last sample (data from line 2)
    if kind == "turning" and not math.isfinite(metrics["tactical_diameter"]):
        change = float(np.max(np.abs(record.heading - record.heading[0])))
        raise ParameterError(
            f"{record.name}: column `{record.column('heading')}` row {last}: the record ends "
            "at a heading change "
            f"of {math.degrees(change):.4g} deg; a turning circle needs 180 deg (shorter than "
            "the manoeuvre needs)", field="heading")
    if kind == "zigzag" and not math.isfinite(metrics["execute_time_3"]):
        raise ParameterError(
            f"{record.name}: column `{record.column('heading')}` row {last}: the record ends "
            "before the zig-zag's third execute (shorter than the manoeuvre needs)",
            field="heading")
