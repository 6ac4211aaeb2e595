"""Manoeuvre metrics from recorded runs: settling time, overshoot, turning diameter, reversals.

All functions work on arrays with a leading run axis (``(runs, time)``) and return one value
per run.
"""

from __future__ import annotations

import numpy as np

from ...constants import wrap_angle
from ...units import metric_units
from ..seakeeping.time_domain import wave_motion_metrics

__all__ = ["settling_time", "overshoot", "turning_diameter", "rudder_reversals", "summarize",
           "summary_units"]


def settling_time(time: np.ndarray, signal: np.ndarray, target: np.ndarray | float,
                  tolerance: float, *, angle: bool = False) -> np.ndarray:
    """First time after which |signal − target| stays within ``tolerance`` (NaN if never).

    ``target`` may vary in time (same shape as ``signal``); with ``angle=True`` the error is
    wrapped to [−π, π).

    Parameters
    ----------
    time : numpy.ndarray, shape (steps,)
        Time grid [s].
    signal : array_like, shape (steps,) or (runs, steps)
        Recorded signal (SI units, radians).
    target : float or array_like
        Target value, constant or with the shape of ``signal``.
    tolerance : float
        Half-width of the settling band, in the unit of ``signal``.
    angle : bool, optional
        Wrap the error to [−π, π) (for angles [rad]; default False).

    Returns
    -------
    numpy.ndarray, shape (runs,)
        Settling time [s] per run.
    """
    signal = np.atleast_2d(signal)
    err = signal - np.broadcast_to(target, signal.shape)
    if angle:
        err = wrap_angle(err)
    outside = ~(np.abs(err) <= tolerance)  # NaN counts as outside
    out = np.full(signal.shape[0], np.nan)
    for i, row in enumerate(outside):
        if not row[-1]:
            idx = np.flatnonzero(row)
            out[i] = time[0] if idx.size == 0 else time[min(idx[-1] + 1, time.size - 1)]
    return out


def overshoot(signal: np.ndarray, start: float | np.ndarray, target: float | np.ndarray
              ) -> np.ndarray:
    """Largest excursion beyond ``target`` in the direction of the step from ``start``.

    Parameters
    ----------
    signal : array_like, shape (steps,) or (runs, steps)
        Recorded signal (SI units, radians).
    start : float or array_like, shape (runs,)
        Initial value of the step.
    target : float or array_like, shape (runs,)
        Final value of the step.

    Returns
    -------
    numpy.ndarray, shape (runs,)
        Overshoot (>= 0) in the unit of ``signal``.
    """
    signal = np.atleast_2d(signal)
    direction = np.sign(np.asarray(target) - np.asarray(start)) * np.ones(signal.shape[0])
    beyond = (signal - np.reshape(target, (-1, 1))) * direction[:, None]
    return np.clip(np.nanmax(beyond, axis=1), 0.0, None)


def turning_diameter(north: np.ndarray, east: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """Diameter [m] of the last full circle of the track (NaN if the ship turned < 360°).

    The track after the heading has changed by 360° is taken from the last full turn; the
    diameter is the mean of its north and east extents (a steady circle has both equal).

    Parameters
    ----------
    north, east : array_like, shape (steps,) or (runs, steps)
        Position [m].
    heading : array_like, shape (steps,) or (runs, steps)
        Heading ψ [rad].

    Returns
    -------
    numpy.ndarray, shape (runs,)
        Turning diameter [m].
    """
    north, east, heading = (np.atleast_2d(a) for a in (north, east, heading))
    out = np.full(north.shape[0], np.nan)
    for i in range(north.shape[0]):
        psi = np.unwrap(heading[i][np.isfinite(heading[i])])
        n = psi.size
        if n < 3 or abs(psi[-1] - psi[0]) < 2 * np.pi:
            continue
        # start of the last full turn
        j = np.flatnonzero(np.abs(psi[-1] - psi) >= 2 * np.pi)[-1]
        x = north[i][j:n]
        y = east[i][j:n]
        out[i] = 0.5 * ((x.max() - x.min()) + (y.max() - y.min()))
    return out


def rudder_reversals(time: np.ndarray, rudder: np.ndarray, *, deadband: float = 0.0
                     ) -> np.ndarray:
    """Number of sign reversals of the rudder rate per minute (moves smaller than the deadband
    [rad] are ignored).

    Parameters
    ----------
    time : numpy.ndarray, shape (steps,)
        Time grid [s].
    rudder : array_like, shape (steps,) or (runs, steps)
        Rudder angle δ [rad].
    deadband : float, optional
        Moves smaller than this are ignored [rad] (default 0).

    Returns
    -------
    numpy.ndarray, shape (runs,)
        Reversals per minute [1/min].
    """
    rudder = np.atleast_2d(rudder)
    out = np.zeros(rudder.shape[0])
    minutes = (time[-1] - time[0]) / 60.0
    for i, row in enumerate(rudder):
        row = row[np.isfinite(row)]
        count, last_extreme, direction = 0, row[0] if row.size else 0.0, 0
        for v in row[1:]:
            step = v - last_extreme
            if direction >= 0 and step < -deadband:
                count += direction > 0
                direction, last_extreme = -1, v
            elif direction <= 0 and step > deadband:
                count += direction < 0
                direction, last_extreme = 1, v
            elif (direction > 0 and v > last_extreme) or (direction < 0 and v < last_extreme):
                last_extreme = v
        out[i] = count / minutes if minutes > 0 else 0.0
    return out


def on_track(xte: np.ndarray, leg: np.ndarray) -> np.ndarray:
    """Where each run is on its track: on every leg, from the first time its cross-track
    error crosses zero (or is at 1 % of its value at the leg's start) to the leg's end.

    Right after a waypoint switch the cross-track error is the distance to the new leg (about
    the acceptance radius): the approach to the leg, not how the ship keeps it. From the first
    crossing of the leg's line on, the error is the overshoot onto the leg and then the track
    keeping.

    Parameters
    ----------
    xte : numpy.ndarray, shape (runs, samples)
        Cross-track error [m].
    leg : numpy.ndarray, shape (runs, samples)
        Active leg (waypoint index) at each sample.

    Returns
    -------
    numpy.ndarray of bool, shape (runs, samples)
    """
    xte, leg = np.atleast_2d(xte), np.atleast_2d(leg)
    out = np.zeros(xte.shape, dtype=bool)
    for i in range(xte.shape[0]):
        starts = np.flatnonzero(np.r_[True, leg[i, 1:] != leg[i, :-1]])
        for a, b in zip(starts, np.r_[starts[1:], xte.shape[1]]):
            x = xte[i, a:b]
            first = x[0] if np.isfinite(x[0]) else 0.0
            near = (np.sign(x) != np.sign(first)) | (np.abs(x) <= 0.01 * abs(first))
            if near.any():
                out[i, a + int(np.argmax(near)):b] = True
    return out


def path_following_metrics(result) -> dict[str, np.ndarray]:  # noqa: ANN001 - SimResult
    """Per-run metrics of guided runs (a :mod:`seahelm.control.guided` controller): largest
    cross-track error [m] over the run (with the approach to each leg after a waypoint switch,
    where the error starts near the acceptance radius) and on track (:func:`on_track`: from the
    first crossing of each leg's line), the RMS error over the run, the error at its end, time
    to complete the route [s] (NaN if it was not completed), rudder activity (mean |δ| [deg],
    reversals per minute).

    Parameters
    ----------
    result : SimResult
        A result whose controller recorded ``cross_track_error`` and ``waypoint_index``.

    Returns
    -------
    dict of str to numpy.ndarray
        ``max_abs_cross_track_error_m``, ``max_abs_cross_track_error_on_track_m``,
        ``rms_cross_track_error_m``, ``final_cross_track_error_m``, ``time_to_complete_s``
        and, with a ``rudder_angle`` state, ``mean_abs_rudder_deg`` and
        ``rudder_reversals_per_min``; empty for a run without guidance.
    """
    if "cross_track_error" not in result.command_labels:
        return {}
    xte = result["cross_track_error"]
    wp = result["waypoint_index"]
    cls, arr = result.params["controller"]
    n_wp = np.broadcast_to(arr[:, cls.value_names().index("n_waypoints")], (result.n_runs,))
    done = wp >= (n_wp[:, None] - 1.0)
    t = result.time
    settled = on_track(xte, wp)
    out = {
        "max_abs_cross_track_error_m": np.nanmax(np.abs(xte), axis=1),
        "max_abs_cross_track_error_on_track_m": np.array([
            np.nanmax(np.abs(x[k])) if k.any() else np.nan for x, k in zip(xte, settled)]),
        "rms_cross_track_error_m": np.sqrt(np.nanmean(xte * xte, axis=1)),
        "final_cross_track_error_m": xte[:, -1],
        "time_to_complete_s": np.where(done.any(axis=1), t[np.argmax(done, axis=1)], np.nan),
    }
    if "rudder_angle" in result.state_labels:
        rudder = result["rudder_angle"]
        out["mean_abs_rudder_deg"] = np.degrees(np.nanmean(np.abs(rudder), axis=1))
        out["rudder_reversals_per_min"] = rudder_reversals(t, rudder,
                                                           deadband=np.radians(0.5))
    return out


def summarize(result) -> list[dict[str, float | str]]:  # noqa: ANN001 - SimResult
    """Per-run summary metrics of a :class:`~seahelm.results.SimResult` (SI units unless
    the key says ``_deg``; each metric's unit: :func:`summary_units`). Runs with first-order
    wave motions also get their RMS heave, pitch and roll, mean surge speed and mean wave
    heading (:func:`seahelm.analysis.seakeeping.time_domain.wave_motion_metrics`).

    Parameters
    ----------
    result : SimResult
        Simulation result with ``heading``, ``yaw_rate``, ``north`` and ``east`` signals.

    Returns
    -------
    list of dict
        One dict of metrics per run.
    """
    out: list[dict[str, float | str]] = []
    t = result.time
    heading = result["heading"]
    yaw_rate = result["yaw_rate"]
    diam = turning_diameter(result["north"], result["east"], heading)
    ref_labels = result.reference_labels
    settle = np.full(result.n_runs, np.nan)
    tracking: dict[str, np.ndarray] = {}
    if ref_labels and ref_labels[0] in ("heading", "yaw_rate"):
        lab = ref_labels[0]
        target = result[f"reference_{lab}"]
        sig = heading if lab == "heading" else yaw_rate
        final_target = np.broadcast_to(target, sig.shape)[:, -1:]
        span = np.abs(final_target[:, 0] - sig[:, 0])
        if lab == "heading":
            tol = np.maximum(0.02 * span, np.radians(0.2))
        else:
            tol = np.maximum(0.05 * np.abs(final_target[:, 0]), 1e-5)
        for i in range(result.n_runs):
            settle[i] = settling_time(t, sig[i], final_target[i], tol[i],
                                      angle=lab == "heading")[0]
        if lab == "heading":
            err = wrap_angle(final_target[:, 0] - sig[:, -1])
            unwrapped = sig[:, 0:1] + np.unwrap(sig - sig[:, 0:1], axis=1)
            goal = sig[:, 0] + wrap_angle(final_target[:, 0] - sig[:, 0])
            tracking["heading_error_deg"] = np.degrees(err)
            tracking["overshoot_deg"] = np.degrees(overshoot(unwrapped, sig[:, 0], goal))
        else:
            tracking["yaw_rate_error"] = final_target[:, 0] - sig[:, -1]
    tracking.update(path_following_metrics(result))
    tracking.update(wave_motion_metrics(result))
    messages = result.messages()
    for i in range(result.n_runs):
        row: dict[str, float | str] = {"run": i, "status": messages[i]}
        for j, (lab, unit) in enumerate(zip(result.state_labels, result.state_units)):
            value = float(result.state[i, -1, j])
            row[f"final_{lab}"] = value
            if unit == "rad":
                row[f"{lab}_deg"] = float(np.degrees(value))
                row[f"max_abs_{lab}_deg"] = float(
                    np.degrees(np.nanmax(np.abs(result.state[i, :, j]))))
        row["final_yaw_rate"] = float(yaw_rate[i, -1])
        row["final_heading_rad"] = float(heading[i, -1])
        row["turning_diameter_m"] = float(diam[i])
        row["settling_time_s"] = float(settle[i])
        for key, values in tracking.items():
            row[key] = float(values[i])
        out.append(row)
    return out


def summary_units(result, keys=None) -> dict[str, str]:  # noqa: ANN001 - SimResult
    """The unit of each summary metric of :func:`summarize` (:func:`seahelm.units.metric_unit`:
    the unit its name says, or that of the signal it is a value of; "" for none).

    Parameters
    ----------
    result : SimResult
        The result the metrics are of (its signals' units).
    keys : iterable of str, optional
        The metric names (default: those of :func:`summarize` of ``result``'s first run).

    Returns
    -------
    dict of str to str
        Unit by metric name (``run`` and ``status`` excluded).
    """
    if keys is None:
        keys = summarize(result)[0]
    return metric_units((k for k in keys if k not in ("run", "status")), result.units())
