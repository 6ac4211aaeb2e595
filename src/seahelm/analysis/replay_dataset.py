"""A replay's file (``replay.nc`` of ``seahelm replay --out``) read back: what it is and its
metrics.

:meth:`seahelm.analysis.replay.ReplayResult.to_xarray` writes both tracks over a ``track``
dimension (``measured``, ``simulated``) and the record's ``time``, and the metrics, errors and
settings as attributes (``measured_<metric>``, ``simulated_<metric>``, ``rms_error_60s_L``,
``rms_error_L``, ``record``, ``ship``, ``kind``, ``dt_s``, ...), with ``format`` =
:data:`REPLAY_FORMAT`. ``seahelm inspect`` and ``seahelm report`` read it through
:func:`is_replay_dataset` and :func:`replay_metrics`.
"""

from __future__ import annotations

from typing import Any

__all__ = ["REPLAY_FORMAT", "METRIC_UNITS", "is_replay_dataset", "replay_metrics"]

#: The ``format`` attribute of a replay's Dataset.
REPLAY_FORMAT = "seahelm-replay/1"

#: The SI unit of each metric a replay compares (angles in radians; ``-`` dimensionless).
METRIC_UNITS = {
    "advance": "m", "transfer": "m", "tactical_diameter": "m", "steady_diameter": "m",
    "speed_loss": "-", "overshoot_1": "rad", "overshoot_2": "rad", "overshoot_3": "rad",
    "execute_time_2": "s", "execute_time_3": "s", "execute_time_4": "s",
    "time_to_check_yaw": "s", "period": "s"}


def is_replay_dataset(ds: Any) -> bool:
    """Whether ``ds`` is a replay's Dataset (also one written before it carried ``format``:
    both tracks over ``track`` and the replay's RMS error attribute).

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    bool
    """
    if ds.attrs.get("format") == REPLAY_FORMAT:
        return True
    return "track" in ds.dims and "rms_error_L" in ds.attrs and "record" in ds.attrs


def replay_metrics(ds: Any) -> dict[str, tuple[float, float, str]]:
    """The metrics of a replay's Dataset, in the order computed.

    Parameters
    ----------
    ds : xarray.Dataset
        A replay's Dataset (:func:`is_replay_dataset`).

    Returns
    -------
    dict of str to (float, float, str)
        Metric -> (measured, simulated, SI unit); NaN where not reached.
    """
    out = {}
    for key in ds.attrs:
        if key.startswith("measured_") and f"simulated_{key[9:]}" in ds.attrs:
            name = key[9:]
            out[name] = (float(ds.attrs[key]), float(ds.attrs[f"simulated_{name}"]),
                         METRIC_UNITS.get(name, ""))
    return out
