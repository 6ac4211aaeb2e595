"""The IMO check of an ensemble as a Dataset: every member's criterion values, pass/fail, counted
or excluded (with the reason) and drawn values, with the pass probabilities.

What ``seahelm imo SHIP --monte-carlo N --out DIR`` and a ``kind = "imo"`` scenario with
``[batch.monte_carlo]`` (``seahelm run --out DIR``) write as ``imo-probabilities.nc``
(:func:`ensemble_dataset`), and what ``seahelm inspect`` and ``seahelm report`` read back
(:func:`ensemble_payload`)::

    dimensions   sample (the members), criterion (a row of the IMO table, e.g.
                 "turning: advance (starboard)")
    value        (sample, criterion) the member's value in the criterion's unit (L or deg;
                 NaN where it was not computed)
    passes       (sample, criterion) value <= limit
    passes_all   (sample) every criterion passed
    complete     (sample) counted: every value computed
    reason       (sample) why the member was excluded ("" when it was counted)
    <key path>   (sample) each drawn value, e.g. ``vessel.params.Y_v`` (kind = batch_values)
    ability, quantity, side, limit, unit      coordinates over criterion
    probability, ci_low, ci_high, n_passed, median      (criterion) over the counted members

The whole check is in the attributes: ``all_probability``, ``all_ci_low``, ``all_ci_high``,
``all_passed``, ``n_counted``, ``n_excluded``, ``confidence_level``, ``interval`` (Wilson
score), ``stopping_note``; the criteria with their limits also as JSON (``imo_criteria``, as a
sweep store keeps them). Every probability is the fraction of the counted members whose
``passes`` is true: recomputing it from ``value``, ``limit`` and ``complete`` gives the stored
number.
"""

from __future__ import annotations

import datetime as _dt
import json
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from .probability import ImoProbabilities

__all__ = ["ENSEMBLE_FILE", "ensemble_dataset", "is_ensemble_dataset", "ensemble_payload",
           "criterion_label", "criteria_json", "excluded_samples"]

#: The file name of an ensemble's results in an output directory.
ENSEMBLE_FILE = "imo-probabilities.nc"
#: The interval the probabilities are given with.
INTERVAL = "Wilson score"


def criterion_label(row: Mapping[str, Any]) -> str:
    """A criterion's name in tables and coordinates: ``"turning: advance (starboard)"``.

    Parameters
    ----------
    row : mapping
        With ``ability``, ``criterion`` and ``side`` ("-" for none).

    Returns
    -------
    str
    """
    side = "" if row["side"] == "-" else f" ({row['side']})"
    return f"{row['ability']}: {row['criterion']}{side}"


def criteria_json(probs: "ImoProbabilities") -> str:
    """The criteria of an ensemble check with their limits and units, as JSON (the
    ``imo_criteria`` attribute of the file and of a sweep store).

    Parameters
    ----------
    probs : ImoProbabilities
        The check.

    Returns
    -------
    str
        A list of ``{"ability", "criterion", "side", "limit", "unit"}``.
    """
    return json.dumps([{k: r[k] for k in ("ability", "criterion", "side", "limit", "unit")}
                       for r in probs.rows])


def ensemble_dataset(probs: "ImoProbabilities", *,
                     draws: Mapping[str, tuple[Any, Mapping[str, Any]]] | None = None,
                     attrs: Mapping[str, Any] | None = None) -> "xr.Dataset":
    """The Dataset of an ensemble check (module docstring).

    Parameters
    ----------
    probs : ImoProbabilities
        From :func:`~seahelm.analysis.imo.probability.imo_probabilities` (with its per-member
        values).
    draws : mapping of key path to (values, attrs), optional
        The drawn values of every member and their attributes (``distribution``, ``units``).
    attrs : mapping, optional
        Metadata (title, scenario, ship, seed, ...), stored as attributes.

    Returns
    -------
    xarray.Dataset

    Raises
    ------
    ValueError
        If ``probs`` holds no per-member values.
    """
    import xarray as xr

    from ... import __version__

    if probs.complete is None or len(probs.values) != len(probs.rows):
        raise ValueError("the check holds no per-member values (an ImoProbabilities of an "
                         "older seahelm?)")
    rows = probs.rows
    values = np.column_stack(probs.values) if rows else np.empty((probs.complete.size, 0))
    n = values.shape[0]
    limits = np.array([r["limit"] for r in rows], dtype=float)
    passes = values <= limits
    coords: dict[str, Any] = {
        "sample": ("sample", np.arange(n), {"long_name": "member of the ensemble"}),
        "criterion": ("criterion", np.array([criterion_label(r) for r in rows], dtype=str)),
        "ability": ("criterion", np.array([r["ability"] for r in rows], dtype=str)),
        "quantity": ("criterion", np.array([r["criterion"] for r in rows], dtype=str)),
        "side": ("criterion", np.array([r["side"] for r in rows], dtype=str)),
        "limit": ("criterion", limits, {"long_name": "a member passes when value <= limit"}),
        "unit": ("criterion", np.array([r["unit"] for r in rows], dtype=str)),
    }
    level = f"{100 * probs.level:g} %"
    data: dict[str, Any] = {
        "value": (("sample", "criterion"), values,
                  {"long_name": "the criterion's value (its unit: `unit`; NaN: not computed)"}),
        "passes": (("sample", "criterion"), passes, {"long_name": "value <= limit"}),
        "passes_all": ("sample", passes.all(axis=1) if rows else np.ones(n, bool),
                       {"long_name": "every criterion passed"}),
        "complete": ("sample", np.asarray(probs.complete, dtype=bool),
                     {"long_name": "counted in the probabilities (every value computed)"}),
        "reason": ("sample", np.array(list(probs.reasons) or [""] * n, dtype=str),
                   {"long_name": "why the member was excluded (empty when counted)"}),
        "probability": ("criterion", np.array([r["probability"] for r in rows], dtype=float),
                        {"long_name": "fraction of the counted members that pass"}),
        "ci_low": ("criterion", np.array([r["ci_low"] for r in rows], dtype=float),
                   {"long_name": f"{INTERVAL} interval of the probability, {level}: low"}),
        "ci_high": ("criterion", np.array([r["ci_high"] for r in rows], dtype=float),
                    {"long_name": f"{INTERVAL} interval of the probability, {level}: high"}),
        "n_passed": ("criterion", np.array([r["passed"] for r in rows], dtype=np.int64),
                     {"long_name": "counted members that pass"}),
        "median": ("criterion", np.array([r["median"] for r in rows], dtype=float),
                   {"long_name": "median of the counted members' values"}),
    }
    for key, (drawn, vattrs) in (draws or {}).items():
        data[key] = ("sample", np.asarray(drawn, dtype=float).reshape(n),
                     {"kind": "batch_values", "key": key, **dict(vattrs)})
    meta = {k: v for k, v in (attrs or {}).items() if v is not None}
    meta.update({
        "maneuver": "imo", "imo_ensemble": 1, "imo_criteria": criteria_json(probs),
        "confidence_level": float(probs.level), "interval": INTERVAL,
        "all_probability": float(probs.probability), "all_ci_low": float(probs.ci_low),
        "all_ci_high": float(probs.ci_high), "all_passed": int(probs.passed),
        "n_counted": int(probs.total), "n_excluded": int(probs.excluded),
        "stopping_note": probs.stopping_note or "stopping (track reach) evaluated",
        "seahelm_version": __version__,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")})
    return xr.Dataset(data, coords=coords, attrs=meta)


def is_ensemble_dataset(ds: "xr.Dataset") -> bool:
    """Whether ``ds`` is the Dataset of an ensemble check (:func:`ensemble_dataset`).

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    bool
    """
    return bool(ds.attrs.get("imo_ensemble")) and "value" in ds and "criterion" in ds.dims


def excluded_samples(ds: "xr.Dataset") -> list[dict[str, Any]]:
    """The members excluded from the probabilities, with the reason.

    Parameters
    ----------
    ds : xarray.Dataset
        Of :func:`ensemble_dataset`.

    Returns
    -------
    list of dict
        ``{"sample", "reason"}`` per excluded member.
    """
    complete = np.asarray(ds["complete"].values, dtype=bool)
    reasons = np.asarray(ds["reason"].values).astype(str)
    samples = np.asarray(ds["sample"].values)
    return [{"sample": int(samples[i]), "reason": str(reasons[i])}
            for i in np.flatnonzero(~complete)]


def ensemble_payload(ds: "xr.Dataset") -> dict[str, Any]:
    """The probabilities a file holds, as ``seahelm imo --monte-carlo --json`` prints them.

    Parameters
    ----------
    ds : xarray.Dataset
        Of :func:`ensemble_dataset` (read from a file).

    Returns
    -------
    dict
        ``criteria`` (rows), ``passed``, ``total``, ``excluded``, ``probability``, ``ci_low``,
        ``ci_high``, ``confidence_level``, ``note``, ``samples``, ``excluded_samples``.
    """
    a = ds.attrs

    def num(v: Any) -> float:
        return float(v)

    rows = []
    for i in range(ds.sizes["criterion"]):
        rows.append({"ability": str(ds["ability"].values[i]),
                     "criterion": str(ds["quantity"].values[i]),
                     "side": str(ds["side"].values[i]),
                     "passed": int(ds["n_passed"].values[i]), "total": int(a["n_counted"]),
                     "probability": num(ds["probability"].values[i]),
                     "ci_low": num(ds["ci_low"].values[i]),
                     "ci_high": num(ds["ci_high"].values[i]),
                     "limit": num(ds["limit"].values[i]), "unit": str(ds["unit"].values[i]),
                     "median": num(ds["median"].values[i])})
    return {"criteria": rows, "passed": int(a["all_passed"]), "total": int(a["n_counted"]),
            "excluded": int(a["n_excluded"]), "probability": num(a["all_probability"]),
            "ci_low": num(a["all_ci_low"]), "ci_high": num(a["all_ci_high"]),
            "confidence_level": num(a["confidence_level"]), "note": str(a["stopping_note"]),
            "samples": int(ds.sizes["sample"]), "excluded_samples": excluded_samples(ds)}
