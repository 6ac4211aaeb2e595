"""Record segments for output-error fits: cut from measured records, simulated in one batch.

The segments of :mod:`seahelm.analysis.replay.mmg_multi_record` (its module docstring: why
segments, the residuals): :func:`build_segments` cuts records into segments that start from
the measured state, with the inputs (δ, n) and the measured true wind on the integration grid;
:func:`simulate_segments` runs every segment with every parameter set as one batched engine
run; :func:`residuals` compares the simulated and the measured outputs.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...identification.records import ManoeuvreRecord

__all__ = ["OUTPUTS", "RECORD_CHANNELS", "Segments", "build_segments", "simulate_segments",
           "residuals", "STATE_ORDER"]

#: The outputs compared, in the order of the residual blocks.
OUTPUTS = ("north", "east", "heading", "surge_speed", "sway_speed", "yaw_rate")

#: Channels a record needs (the heading besides).
RECORD_CHANNELS = ("x", "y", "surge_speed", "sway_speed", "propeller_rps")

_WIND_CHANNELS = ("true_wind_speed", "true_wind_direction")


@dataclasses.dataclass(frozen=True)
class Segments:
    """Record segments ready for one batched engine run (:func:`build_segments`).

    Attributes
    ----------
    names : tuple of str
        ``<record>@<start time>`` of each segment.
    x0 : ndarray, shape (S, 6)
        Measured initial state (u, v, r, north, east, heading in the model's order).
    x0_std : ndarray, shape (S, 6)
        Its standard errors (of the quadratic fit at the start, :func:`build_segments`).
    rudder, rps, gust : ndarray, shape (S, K + 1)
        Inputs on the integration grid (gust: the true wind speed [m/s], zero without wind).
    direction : ndarray, shape (S,)
        Wind direction held over each segment [rad].
    measured : ndarray, shape (S, 6, M + 1)
        :data:`OUTPUTS` measured at every ``sample`` seconds.
    mask : ndarray of bool, shape (S, M + 1)
        Samples inside the record (a record's last segment may be shorter).
    dt, sample : float
        Integration step and sampling interval [s] (``sample`` a whole number of steps).
    wind : str
        ``"measured"`` or ``"none"``.
    speed : float
        U_0, the records' mean speed [m/s] (the velocity scale).
    """

    names: tuple[str, ...]
    x0: np.ndarray
    x0_std: np.ndarray
    rudder: np.ndarray
    rps: np.ndarray
    gust: np.ndarray
    direction: np.ndarray
    measured: np.ndarray
    mask: np.ndarray
    dt: float
    sample: float
    wind: str
    speed: float

    @property
    def steps(self) -> int:
        """Integration steps per segment."""
        return self.rudder.shape[1] - 1


def _check(record: ManoeuvreRecord, wind: str) -> None:
    need = list(RECORD_CHANNELS) + (list(_WIND_CHANNELS) if wind == "measured" else [])
    missing = [c for c in need if c not in record.channels]
    if record.heading is None:
        missing.insert(0, "heading")
    if record.yaw_rate is None:
        missing.insert(0, "yaw_rate")
    if missing:
        raise ParameterError(f"{record.name}: missing column(s) {', '.join(missing)}: the "
                             "mmg-ls identification needs x, y, heading, u, v, r, δ, n"
                             + (" and the true wind" if wind == "measured" else ""),
                             field=missing[0])


def build_segments(records: ManoeuvreRecord | Sequence[ManoeuvreRecord], ship: Any, *,
                   segment: float = 60.0, sample: float = 1.0, wind: str = "measured",
                   dt: float | None = None, min_length: float = 10.0,
                   start_window: float = 2.0) -> Segments:
    """Cut records into segments from measured states (module docstring).

    Parameters
    ----------
    records : ManoeuvreRecord or sequence of them
    ship : Ship
        For its length (the default step).
    segment : float
        Segment length [s]; ``math.inf``: one segment per record, the whole record.
    sample : float
        Interval of the compared samples [s].
    wind : {"measured", "none"}
    dt : float, optional
        Integration step [s] (default: the replay's, the records' interval and at most
        L/(100 U_max), rounded down to a whole fraction of ``sample``).
    min_length : float
        Record ends shorter than this [s] make no segment.
    start_window : float
        A segment's initial state is the value at its start of a quadratic fitted to the
        samples within ``start_window``/2 of it (0: the sample interpolated): the
        measurement noise of one sample would otherwise be an initial-state error that the
        fit turns into a bias of the coefficients.

    Returns
    -------
    Segments
    """
    from .simulate import default_step

    if wind not in ("measured", "none"):
        raise ParameterError(f"must be 'measured' or 'none', got {wind!r}", field="wind")
    for name, value in (("segment", segment), ("sample", sample), ("min_length", min_length)):
        if not (value > 0) or (name != "segment" and not math.isfinite(value)):
            raise ParameterError(f"must be > 0 [s], got {value!r}", field=name, unit="s",
                                 value=value)
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    if not recs:
        raise ParameterError("no records given", field="records")
    for rec in recs:
        _check(rec, wind)
    length = float(ship.length)
    if dt is None:
        dt = min(default_step(r, length, np.hypot(r.channels["surge_speed"],
                                                  r.channels["sway_speed"])) for r in recs)
    every = max(int(math.ceil(sample / dt - 1e-9)), 1)
    dt = sample / every
    longest = max(r.duration for r in recs)
    span = min(segment, longest)
    n_samples = int(math.ceil(span / sample - 1e-9))
    K = n_samples * every
    grid = dt * np.arange(K + 1)
    tk = sample * np.arange(n_samples + 1)
    rows: dict[str, list] = {k: [] for k in ("names", "x0", "x0_std", "rudder", "rps", "gust",
                                             "direction", "measured", "mask")}
    speeds = []
    for rec in recs:
        t = rec.time
        ch = rec.channels
        psi = np.unwrap(rec.heading)
        series = (ch["x"], ch["y"], psi, ch["surge_speed"], ch["sway_speed"], rec.yaw_rate)
        speeds.append(float(np.mean(np.hypot(ch["surge_speed"], ch["sway_speed"]))))
        start = float(t[0])
        while start <= float(t[-1]) - min(min_length, rec.duration) + 1e-9:
            def at(times: np.ndarray, values: np.ndarray) -> np.ndarray:
                return np.interp(start + times, t, values)
            meas = np.stack([at(tk, s) for s in series])
            first = [_start_value(t, s, start, start_window) for s in series]
            rows["names"].append(f"{rec.name}@{start - t[0]:.6g}s")
            rows["x0"].append([first[k][0] for k in STATE_ORDER])
            rows["x0_std"].append([first[k][1] for k in STATE_ORDER])
            rows["rudder"].append(at(grid, rec.rudder_angle))
            rows["rps"].append(at(grid, ch["propeller_rps"]))
            rows["measured"].append(meas)
            rows["mask"].append(start + tk <= float(t[-1]) + 1e-9)
            if wind == "measured":
                rows["gust"].append(at(grid, ch["true_wind_speed"]))
                keep = (t >= start) & (t <= start + span)
                theta = ch["true_wind_direction"][keep]
                rows["direction"].append(math.atan2(float(np.mean(np.sin(theta))),
                                                    float(np.mean(np.cos(theta)))))
            else:
                rows["gust"].append(np.zeros(K + 1))
                rows["direction"].append(0.0)
            if not math.isfinite(segment):
                break
            start += segment
    return Segments(names=tuple(rows["names"]), x0=np.array(rows["x0"]),
                    x0_std=np.array(rows["x0_std"]),
                    rudder=np.array(rows["rudder"]), rps=np.array(rows["rps"]),
                    gust=np.array(rows["gust"]), direction=np.array(rows["direction"]),
                    measured=np.array(rows["measured"]), mask=np.array(rows["mask"]),
                    dt=dt, sample=sample, wind=wind, speed=float(np.mean(speeds)))


#: The records' series (OUTPUTS order) in the order of the model's state.
STATE_ORDER = (3, 4, 5, 0, 1, 2)


def _start_value(t: np.ndarray, values: np.ndarray, start: float,
                 window: float) -> tuple[float, float]:
    """The value at ``start`` of a quadratic least-squares fit over the samples within
    ``window``/2 of it, and its standard error (0 without a fit)."""
    keep = np.abs(t - start) <= 0.5 * window + 1e-9
    if window <= 0 or np.count_nonzero(keep) < 5:
        return float(np.interp(start, t, values)), 0.0
    X = np.vander(t[keep] - start, 3, increasing=True)
    coef, *_ = np.linalg.lstsq(X, values[keep], rcond=None)
    resid = values[keep] - X @ coef
    s2 = float(resid @ resid) / (keep.sum() - 3)
    return float(coef[0]), math.sqrt(s2 * float(np.linalg.inv(X.T @ X)[0, 0]))


def simulate_segments(ship: Any, segments: Segments, params: Sequence[Any]) -> np.ndarray:
    """Every segment with every parameter set: one batched engine run.

    Parameters
    ----------
    ship : Ship
        An ``mmg-ls`` ship (its wind particulars give the loads).
    segments : Segments
    params : sequence of MMGLowSpeedParams
        P parameter sets.

    Returns
    -------
    ndarray, shape (P, S, 6, M + 1)
        :data:`OUTPUTS` at the segments' samples (NaN for a diverged run).
    """
    from ...environment.loads import environment, ship_load_params
    from ...simulation.engine import simulate
    from ...simulation.problem import Problem

    P, S = len(params), len(segments.names)
    every = int(round(segments.sample / segments.dt))
    tile = (lambda a: np.ascontiguousarray(np.tile(a, (P,) + (1,) * (a.ndim - 1))))
    kwargs: dict[str, Any] = {}
    if segments.wind == "measured":
        env = environment(wind="fujiwara" if _fujiwara(ship) else "blendermann")
        loads = [ship_load_params(ship, env, wind_speed=0.0, wind_direction=float(d))
                 for d in segments.direction]
        kwargs = {"environment": env, "environment_params": loads * P,
                  "disturbance": {"wind_gust": tile(segments.gust)[:, :, None]}}
    problem = Problem(
        ship=ship, params=[p for p in params for _ in range(S)], x0=tile(segments.x0),
        actuator="direct", t_final=segments.steps * segments.dt, dt=segments.dt,
        record_every=every,
        reference={"rudder_angle": tile(segments.rudder)[:, :, None],
                   "propeller_rps": tile(segments.rps)[:, :, None]}, **kwargs)
    result = simulate(problem)
    out = np.stack([np.asarray(result[k], dtype=float) for k in OUTPUTS], axis=1)
    out = out[:, :, :segments.measured.shape[2]]
    bad = ~np.all(np.isfinite(out.reshape(P * S, -1)), axis=1)
    out[bad] = np.nan
    return out.reshape(P, S, len(OUTPUTS), -1)


def _fujiwara(ship: Any) -> bool:
    from .simulate import _default_wind_loads

    return _default_wind_loads(ship) == "fujiwara"


def _scales(segments: Segments, length: float) -> np.ndarray:
    U0 = segments.speed
    return np.array([length, length, 1.0, U0, U0, U0 / length])


def residuals(sim: np.ndarray, segments: Segments, length: float) -> np.ndarray:
    """(P, n_residuals): (measured − simulated)/scale over the masked samples.

    Parameters
    ----------
    sim : ndarray
        The simulated segments (parameter sets, segments, channels, samples).
    segments : Segments
        The measured segments (:func:`build_segments`).
    length : float
        The ship's length [m], the scale of the position residuals.
    """
    scale = _scales(segments, length)[None, None, :, None]
    err = (segments.measured[None] - sim) / scale
    err = np.where(np.isfinite(err), err, 10.0)
    keep = np.broadcast_to(segments.mask[:, None, :], segments.measured.shape)
    return err[:, keep]
