"""A replay's file (``replay.nc`` of ``seahelm replay --out``) read back: what it is and its
metrics.

:meth:`seahelm.analysis.replay.simulate.ReplayResult.to_xarray` writes both tracks over a ``track``
dimension (``measured``, ``simulated``) and the record's ``time``, and the metrics, errors and
settings as attributes (``measured_<metric>``, ``simulated_<metric>``, ``rms_error_60s_L``,
``rms_error_L``, ``record``, ``ship``, ``kind``, ``dt_s``, ...), with ``format`` =
:data:`REPLAY_FORMAT`. ``seahelm inspect`` and ``seahelm report`` read it through
:func:`is_replay_dataset` and :func:`replay_metrics`.
"""

from __future__ import annotations

from typing import Any

from ...errors import ParameterError

__all__ = ["REPLAY_FORMAT", "METRIC_UNITS", "check_replay_dataset", "is_replay_dataset",
           "replay_metrics"]

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


def check_replay_dataset(ds: Any, path: Any) -> None:
    """Refuse a replay's Dataset that cannot be shown: no time samples, not both tracks, a
    metric that is not a number (a damaged or hand-edited file).

    Parameters
    ----------
    ds : xarray.Dataset
    path : str or pathlib.Path
        The file, for the message.

    Raises
    ------
    ParameterError
    """
    if int(ds.sizes.get("time", 0)) == 0:
        raise ParameterError(f"{path}: the replay holds no time samples")
    if int(ds.sizes.get("track", 0)) != 2:
        raise ParameterError(f"{path}: a replay holds two tracks (measured, simulated), this "
                             f"one {int(ds.sizes.get('track', 0))}")
    replay_metrics(ds, path)


def replay_metrics(ds: Any, path: Any = None) -> dict[str, tuple[float, float, str]]:
    """The metrics of a replay's Dataset, in the order computed.

    Parameters
    ----------
    ds : xarray.Dataset
        A replay's Dataset (:func:`is_replay_dataset`).
    path : str or path-like, optional
        The file it was read from, named in the error of a damaged attribute.

    Returns
    -------
    dict of str to (float, float, str)
        Metric -> (measured, simulated, SI unit); NaN where not reached.
    """
    out = {}
    for key in ds.attrs:
        if key.startswith("measured_") and f"simulated_{key[9:]}" in ds.attrs:
            name = key[9:]
            pair = []
            for attr in (key, f"simulated_{name}"):
                try:
                    pair.append(float(ds.attrs[attr]))
                except (TypeError, ValueError):
                    raise ParameterError(
                        f"{path or 'the replay'}: attribute `{attr}` must be a number, got "
                        f"{ds.attrs[attr]!r}") from None
            out[name] = (pair[0], pair[1], METRIC_UNITS.get(name, ""))
    return out
