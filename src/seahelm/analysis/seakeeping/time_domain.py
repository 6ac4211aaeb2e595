"""Per-run seakeeping statistics of a time-domain record with first-order wave motions.

A run of a scenario with ``[environment.waves] first_order_motions = true``
(:mod:`seahelm.scenario.first_order`) carries the first-order heave, pitch and roll
(``heave``, ``pitch``, ``roll_wave``; ``roll`` adds the model's roll angle). Its statistics,
one value per run, are what a sweep stores to draw a polar seakeeping diagram from
(:mod:`seahelm.sweep.seakeeping`):

* ``rms_heave_m``, ``rms_pitch_deg``, ``rms_roll_wave_deg``: the root mean square about zero,
  √(mean over the record's samples of η²) — the first-order motions have zero mean, and the
  mean square is the unbiased estimate of the variance m0 = ∫|H|²S dω of the frequency domain
  (:mod:`seahelm.environment.first_order`: E[η²] equals the integral over the band exactly);
* ``rms_roll_deg``: the same of the total roll (model roll + first-order roll), which also
  holds the model's low-frequency heel;
* ``mean_surge_speed_mps``: the mean surge speed [m/s], the speed the RAOs are evaluated at;
* ``mean_wave_heading_deg``: the mean wave heading relative to the ship,
  ε̄ = β̄ − ψ̄ in [0, 360) [deg] (:mod:`seahelm.environment.rao`: 0 following, 180 head, 90 waves
  travelling to starboard), β̄ the mean direction of travel of the waves (the scenario's
  ``direction_deg`` + 180°) and ψ̄ the circular mean of the recorded heading.

A diverged run has NaN (its motions are NaN).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["wave_motion_metrics", "METRICS"]

#: The metric of each first-order series: (series name, metric name, factor from SI).
METRICS: tuple[tuple[str, str, float], ...] = (
    ("heave", "rms_heave_m", 1.0),
    ("pitch", "rms_pitch_deg", 180.0 / math.pi),
    ("roll_wave", "rms_roll_wave_deg", 180.0 / math.pi),
    ("roll", "rms_roll_deg", 180.0 / math.pi),
)


def _wave_direction(result: Any) -> np.ndarray | None:
    """The direction the waves come from [rad] per run (the environment's parameters)."""
    entry = getattr(result, "params", {}).get("environment")
    if entry is None:
        return None
    cls, arr = entry
    names = [i.name for i in cls.info()]
    if "wave_direction" not in names:
        return None
    arr = np.broadcast_to(np.asarray(arr, dtype=float), (result.n_runs, len(names)))
    return arr[:, names.index("wave_direction")]


def wave_motion_metrics(result: Any) -> dict[str, np.ndarray]:
    """The seakeeping statistics of each run (module docstring); empty without first-order
    motions.

    Parameters
    ----------
    result : SimResult
        Runs with first-order motions in ``result.extra`` (after the run) or in its outputs
        (``metadata["first_order_in_loop"]``: in the loop) (flat ``run`` axis), the
        ``surge_speed`` and ``heading`` signals and the environment's ``wave_direction``.

    Returns
    -------
    dict of str to numpy.ndarray, shape (runs,)
        By metric name; NaN in diverged runs.
    """
    series = {k: v[0] for k, v in (getattr(result, "extra", {}) or {}).items()}
    if "first_order_in_loop" in (getattr(result, "metadata", {}) or {}):
        # in the loop (seahelm.environment.first_order_in_loop) they are the loop's outputs
        series.update({name: result[name] for name, _, _ in METRICS
                       if name in result.output_labels})
    if not any(name in series for name, _, _ in METRICS):
        return {}
    out: dict[str, np.ndarray] = {}
    for name, metric, factor in METRICS:
        if name in series:
            values = np.asarray(series[name], dtype=float)
            values = values.reshape(result.n_runs, -1)
            out[metric] = np.sqrt(np.mean(values * values, axis=1)) * factor
    speed = np.asarray(result["surge_speed"], dtype=float).reshape(result.n_runs, -1)
    out["mean_surge_speed_mps"] = np.mean(speed, axis=1)
    heading = np.asarray(result["heading"], dtype=float).reshape(result.n_runs, -1)
    from scipy.stats import circmean

    mean_heading = circmean(heading, axis=1)
    came_from = _wave_direction(result)
    if came_from is None:
        out["mean_wave_heading_deg"] = np.full(result.n_runs, np.nan)
    else:
        eps = np.mod(came_from + math.pi - mean_heading, 2.0 * math.pi)
        out["mean_wave_heading_deg"] = np.degrees(eps)
    bad = ~np.all([np.isfinite(out[m]) for _, m, _ in METRICS if m in out], axis=0)
    for v in out.values():
        v[bad] = np.nan
    return out
