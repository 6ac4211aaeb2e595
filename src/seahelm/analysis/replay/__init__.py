"""Measured records replayed: a ship simulated from a record's first sample with its measured
inputs, and what is built on that.

:mod:`.simulate`
    :func:`replay` of one record (a sea trial or a free-running model test) by a ship, its
    :class:`ReplayResult` (both tracks, the manoeuvre's metrics of each, the position error).
:mod:`.dataset`
    the replay's file, ``replay.nc``, read back (:func:`is_replay_dataset`,
    :func:`replay_metrics`).
:mod:`.reversals`
    the propeller reversals in records (:func:`find_reversals`) and their stops replayed
    (:func:`replay_stop`): the stopping validation.
:mod:`.segments`
    records cut into segments from the measured state and simulated in one batch
    (:func:`build_segments`, :func:`simulate_segments`, :func:`residuals`).
:mod:`.mmg_multi_record`
    the output-error fit of an ``mmg-ls`` ship over the segments of many records
    (:func:`fit_mmg_ls`; multiple shooting).

The names below are the submodules' own objects, each imported on first use (reading a
``replay.nc`` imports no simulation). ``seahelm.analysis.replay_dataset``, ``reversals``,
``record_segments`` and ``mmg_multi_record`` are deprecated paths to these modules (issue 47).
"""

from ..._optional import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(__name__, {
    "simulate": ("ReplayResult", "replay", "manoeuvre_metrics", "classify", "REPLAY_CHANNELS",
                 "RMS_WINDOW", "KINDS", "WIND"),
    "dataset": ("REPLAY_FORMAT", "METRIC_UNITS", "check_replay_dataset", "is_replay_dataset",
                "replay_metrics"),
    "reversals": ("Reversal", "StopComparison", "find_reversals", "replay_stop", "slice_record",
                  "REVERSAL_RULE", "MIN_SPEED", "MIN_ASTERN_RPS"),
    "segments": ("OUTPUTS", "RECORD_CHANNELS", "Segments", "build_segments",
                 "simulate_segments", "residuals", "STATE_ORDER"),
    "mmg_multi_record": ("FREE_DEFAULT", "MultiRecordFit", "fit_mmg_ls", "laplace_samples"),
})
