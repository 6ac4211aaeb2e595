"""Chunks of the sweep of an IMO check under uncertainty (``[maneuver] kind = "imo"`` with
``[batch.monte_carlo]``): every member's criterion values, the probabilities at the end.

A chunk is a range of samples; their ships run the IMO manoeuvres as one ensemble
(:meth:`~seahelm.scenario.ManeuverJob.imo_probabilities`: the scenario's ship is the reference
of the manoeuvres' durations, so a sample's values do not depend on the chunk it runs in). The
store holds, over ``run`` (= sample):

* ``value(run, criterion)`` -- each criterion's value in its unit (NaN: not computed), a
  metric of the summary statistics;
* ``failure(run)`` -- 0 counted, 1 excluded for want of a straight approach (not run), 2
  excluded because a criterion has no value (an event not reached, a diverged run);

and, as root attributes, the criteria with their limits and units (``imo_criteria``, JSON, in
the order of ``criterion``), ``confidence_level`` and ``stopping_note``. The probability of
passing each criterion and the whole check, with its Wilson interval and the count of excluded
samples, is computed from the stored values (:func:`store_probabilities`) -- by
:func:`~seahelm.sweep.summary_statistics` when the sweep ends (``sweep_summary["imo"]``) and by
``seahelm report STORE`` from whatever chunks are written.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ..scenario import ManeuverJob

__all__ = ["imo_chunk", "store_probabilities", "is_imo_store", "FAILURE_MEANINGS"]

#: The codes of ``failure``: 0, 1, 2.
FAILURE_MEANINGS = ("counted", "no straight approach (not run)",
                    "a criterion without value (an event not reached, or a diverged run)")


def imo_chunk(job: "ManeuverJob", start: int, stop: int, *, with_attrs: bool = False) -> Any:
    """The criterion values of samples ``start:stop`` over the global ``run``.

    Parameters
    ----------
    job : ManeuverJob
        An ``imo`` scenario with ``[batch.monte_carlo]``.
    start, stop : int
        Sample range.
    with_attrs : bool, optional
        Also return the store's attributes (the criteria and their limits, the scenario), as
        ``(dataset, attrs)``.

    Returns
    -------
    xarray.Dataset
        ``value(run, criterion)`` and ``failure(run)`` (module docstring).
    """
    import xarray as xr

    from ..analysis.imo.ensemble import INTERVAL, criteria_json, criterion_label
    from ..analysis.imo.probability import NO_APPROACH

    probs = job.imo_probabilities(job.ships(start, stop))
    failure = np.array([0 if ok else (1 if why.startswith(NO_APPROACH) else 2)
                        for ok, why in zip(probs.complete.tolist(), probs.reasons)],
                       dtype=np.int8)
    labels = [f"{criterion_label(r)} [{r['unit']}]" for r in probs.rows]
    ds = xr.Dataset(
        {"value": (("run", "criterion"), np.column_stack(probs.values),
                   {"kind": "metric", "long_name": "the IMO criterion's value (its unit in "
                                                   "the criterion's label; NaN: not computed)"}),
         "failure": ("run", failure, {"long_name": "why a sample is excluded",
                                      "flag_values": [0, 1, 2],
                                      "flag_meanings": "; ".join(FAILURE_MEANINGS)})},
        coords={"run": np.arange(start, stop),
                "criterion": ("criterion", np.arange(len(labels)),
                              {"labels": json.dumps(labels)})})
    if not with_attrs:
        return ds
    attrs = {k: v for k, v in job.metadata.items() if isinstance(v, str)}
    attrs.update({"imo_criteria": criteria_json(probs), "confidence_level": float(probs.level),
                  "interval": INTERVAL,
                  "stopping_note": probs.stopping_note or "stopping (track reach) evaluated"})
    return ds, attrs


def is_imo_store(ds: "xr.Dataset") -> bool:
    """Whether ``ds`` (a sweep store, flat) holds the criterion values of an IMO check.

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    bool
    """
    return "imo_criteria" in ds.attrs and "value" in ds and "failure" in ds


def store_probabilities(ds: "xr.Dataset") -> dict[str, Any]:
    """The pass probabilities of the samples a store holds, from their stored values and the
    stored limits (:func:`~seahelm.analysis.imo.probability.probabilities_from_values`).

    Parameters
    ----------
    ds : xarray.Dataset
        The flat view of an IMO sweep store (:func:`is_imo_store`), or the runs of it written
        so far.

    Returns
    -------
    dict
        As ``seahelm imo --monte-carlo --json`` (``criteria``, ``probability``, ``ci_low``,
        ``ci_high``, ``excluded``, ...), with ``samples`` and ``excluded_by_reason``.
    """
    from ..analysis.imo.probability import probabilities_from_values

    criteria = json.loads(ds.attrs["imo_criteria"])
    values = np.asarray(ds["value"].transpose("run", "criterion").values, dtype=float)
    failure = np.asarray(ds["failure"].values).reshape(-1)
    reasons = {i: FAILURE_MEANINGS[int(code)] for i, code in enumerate(failure.tolist())
               if code}
    probs = probabilities_from_values(list(values.T), criteria, complete=failure == 0,
                                      level=float(ds.attrs.get("confidence_level", 0.95)),
                                      stopping_note=str(ds.attrs.get("stopping_note", "")),
                                      reasons=reasons)
    out = probs.as_dict()
    out["note"] = str(ds.attrs.get("stopping_note") or out["note"])
    out["samples"] = int(failure.size)
    out["excluded_by_reason"] = {FAILURE_MEANINGS[c]: int((failure == c).sum()) for c in (1, 2)
                                 if (failure == c).any()}
    return out
