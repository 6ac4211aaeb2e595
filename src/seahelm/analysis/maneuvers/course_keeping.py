"""Course-keeping metrics of recorded runs: heading error, rudder activity and reversals.

Numpy over leading batch axes, time last, radians in. Used for the wind and wave
compensation of Lvov (2014) (:mod:`seahelm.studies.lvov2014`), but nothing here is specific
to that paper: any heading autopilot's records can be scored.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..._validate import as_float_array
from ...constants import wrap_angle

__all__ = ["heading_metrics"]


def heading_metrics(
    heading_error: ArrayLike,
    rudder: ArrayLike,
    *,
    dt: float,
    delta_k: ArrayLike = 0.0,
    start: float = 0.0,
    band: float = math.radians(1.0),
    deadband: float = math.radians(0.05),
) -> dict[str, np.ndarray]:
    """Course-keeping metrics of recorded runs (leading batch axes, time last; radians in).

    Returns ``mean_abs_error`` and ``max_abs_error`` [rad], ``iae`` (∫|e| dt) [rad·s],
    ``reversals_per_min`` (sign changes of the rudder's motion, moves under ``deadband``
    ignored), ``mean_activity`` (mean |δ − δ_k|) [rad] and ``settling_time`` [s] (time after
    ``start`` from which |e| ≤ ``band``; NaN if never), all over t ≥ ``start``.

    Parameters
    ----------
    heading_error : array_like, shape (..., steps)
        Heading error e [rad] (only |e| is used; wrapped to [−π, π) internally).
    rudder : array_like, shape (..., steps)
        Rudder angle δ [rad].
    dt : float
        Sample period of the records [s].
    delta_k : float or array_like, optional
        Compensating rudder angle δ_k [rad], constant or per sample (default 0).
    start : float, optional
        Time from which the metrics are taken [s] (default 0).
    band : float, optional
        Settling band on |e| [rad] (default 1°).
    deadband : float, optional
        Rudder moves smaller than this are not counted as reversals [rad] (default 0.05°).

    Returns
    -------
    dict of str to numpy.ndarray
        The metrics listed above, each of the batch shape.
    """
    e = np.abs(wrap_angle(as_float_array("heading_error", heading_error, "rad", finite=False)))
    d = as_float_array("rudder", rudder, "rad", finite=False)
    k0 = int(round(start / dt))
    e, d = e[..., k0:], d[..., k0:]
    dk = np.asarray(delta_k, dtype=float)
    if dk.ndim and dk.shape[-1] == d.shape[-1] + k0:
        dk = dk[..., k0:]
    duration = (e.shape[-1] - 1) * dt
    out: dict[str, np.ndarray] = {
        "mean_abs_error": e.mean(axis=-1),
        "max_abs_error": e.max(axis=-1),
        "iae": np.trapezoid(e, dx=dt, axis=-1),
        "mean_activity": np.abs(d - dk).mean(axis=-1),
    }
    # rudder reversals with hysteresis
    flat_d = d.reshape(-1, d.shape[-1])
    rev = np.zeros(flat_d.shape[0])
    for i, row in enumerate(flat_d):
        anchor, direction, count = row[0], 0, 0
        for v in row[1:]:
            step = v - anchor
            if abs(step) >= deadband:
                s = 1 if step > 0 else -1
                if direction != 0 and s != direction:
                    count += 1
                direction, anchor = s, v
            elif direction != 0 and (v - anchor) * direction > 0:
                anchor = v
        rev[i] = count
    out["reversals_per_min"] = rev.reshape(d.shape[:-1]) / (duration / 60.0)
    outside = e > band
    any_out = outside.any(axis=-1)
    last = e.shape[-1] - 1 - np.argmax(outside[..., ::-1], axis=-1)
    settle = np.where(any_out, (last + 1) * dt, 0.0)
    out["settling_time"] = np.where(any_out & (last == e.shape[-1] - 1), np.nan, settle)
    return out
