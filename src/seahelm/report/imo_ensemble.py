"""The report section of an IMO check under uncertainty: the probability of passing each
criterion and the whole check with its Wilson interval, the excluded samples with their
reasons, the distribution of every criterion's value against its limit, and the values drawn
for the samples.

From either input that holds an ensemble's check: the file ``imo-probabilities.nc``
(:mod:`seahelm.analysis.imo.ensemble`; the probabilities as stored) or a sweep store of an
``imo`` Monte-Carlo scenario (:mod:`seahelm.sweep.imo`; the probabilities computed from the
stored values and limits of the samples written so far).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .blocks import Section, escape, fmt, paragraph, table
from .figures import histogram_figure
from .inputs import ReportData

__all__ = ["ensemble_sections", "MAX_EXCLUDED_ROWS"]

#: Excluded samples listed one per row (the counts cover all).
MAX_EXCLUDED_ROWS = 200


def ensemble_sections(data: ReportData) -> list[Section]:
    """The probabilities section of an ensemble's IMO check (none for other inputs).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    from ..analysis.imo.ensemble import ensemble_payload
    from ..sweep.imo import is_imo_store, store_probabilities

    if data.imo_ensemble is not None:
        ds = data.imo_ensemble
        payload = ensemble_payload(ds)
        counted = np.asarray(ds["complete"].values, dtype=bool)
        values = np.asarray(ds["value"].values, dtype=float)[counted]
        scope = "stored with the file"
    elif data.sweep is not None and is_imo_store(data.sweep):
        ds = data.sweep
        written = (np.asarray(ds["complete"].values, dtype=bool).reshape(ds.sizes["run"], -1)
                   .all(axis=1) if "complete" in ds else np.ones(ds.sizes["run"], bool))
        ds = ds.isel(run=np.flatnonzero(written))
        payload = store_probabilities(ds)
        counted = np.asarray(ds["failure"].values) == 0
        values = np.asarray(ds["value"].transpose("run", "criterion").values, float)[counted]
        scope = ("computed from the samples' stored values and limits" if written.all() else
                 f"computed from the {int(written.sum())} of {written.size} samples written so "
                 "far")
    else:
        return []
    sec = Section("imo-probabilities", "IMO MSC.137(76) under uncertainty: pass probabilities")
    if data.imo_ensemble is not None:  # (a store's metadata is in its sweep section)
        sec.blocks.extend(_metadata(data.imo_ensemble))
    level = f"{100 * payload['confidence_level']:g} %"
    verdict = (f"P(pass every evaluated criterion) = {fmt(payload['probability'], 3)} "
               f"({fmt(payload['ci_low'], 3)} .. {fmt(payload['ci_high'], 3)}, {level} Wilson "
               f"score interval) over {payload['total']} sample(s); {payload['excluded']} "
               f"excluded (manoeuvres not completed); {payload['note']}")
    sec.blocks.append(paragraph(verdict, cls="verdict"))
    rows, classes = [], []
    for r in payload["criteria"]:
        rows.append([r["ability"], r["criterion"], r["side"], r["median"], r["limit"], r["unit"],
                     f"{r['passed']} of {r['total']}", r["probability"], r["ci_low"],
                     r["ci_high"]])
        p = r["probability"]
        classes.append("pass" if p == 1 else ("fail" if p == 0 else "not-evaluated"))
    sec.blocks.append(table(["ability", "criterion", "side", "median", "limit", "unit",
                             "passed", "P(pass)", f"{level} low", f"{level} high"], rows,
                            cls="imo", row_classes=classes,
                            caption=f"probabilities {scope}; a sample passes a criterion "
                                    "when its value is at most the limit"))
    excluded = payload.get("excluded_samples") or []
    if excluded:
        caption = ("" if len(excluded) <= MAX_EXCLUDED_ROWS else
                   f"first {MAX_EXCLUDED_ROWS} of {len(excluded)} excluded samples")
        sec.blocks.append(table(["excluded sample", "reason"],
                                [[e["sample"], e["reason"]]
                                 for e in excluded[:MAX_EXCLUDED_ROWS]],
                                cls="status-counts", caption=caption))
    by_reason = payload.get("excluded_by_reason") or {}
    if by_reason:
        sec.blocks.append(table(["reason", "excluded samples"],
                                [[k, v] for k, v in by_reason.items()], cls="status-counts"))
    columns = {_label(r): values[:, k] for k, r in enumerate(payload["criteria"])}
    fig = histogram_figure({"": columns}) if columns and values.size else None
    if fig is not None:
        sec.blocks.append(paragraph("the counted samples' values of each criterion "
                                    "(the limit in the table above)"))
        sec.blocks.append(fig)
    if data.imo_ensemble is not None:  # (a store's drawn inputs are in its sweep section)
        from .batch import drawn_blocks, drawn_values

        drawn = drawn_values(data.imo_ensemble)
        sec.blocks.extend(drawn_blocks(drawn, f"all {len(next(iter(drawn.values()))[0])} "
                                              "samples (counted or not)" if drawn else ""))
    return [sec]


#: The file's attributes shown, in this order.
_SHOWN = ("ship", "samples", "seed", "draws", "uncertainty", "scenario_source", "dt",
          "seahelm_version", "created")


def _metadata(ds: Any) -> list[str]:
    """The file's metadata, its drawn keys and the scenario text."""
    a = ds.attrs
    rows = [[k, str(a[k])] for k in _SHOWN if k in a]
    for name, var in ds.data_vars.items():
        if var.attrs.get("kind") == "batch_values":
            units = var.attrs.get("units")
            rows.append(["drawn", f"{name} ({var.attrs.get('distribution', '')})"
                         + (f" [{units}]" if units else "")])
    out = [table(None, rows, cls="meta")]
    text = a.get("scenario_text")
    if text:
        out.append(f"<details><summary>scenario text ({len(str(text).splitlines())} lines)"
                   f"</summary><pre>{escape(text)}</pre></details>")
    return out


def _label(row: dict[str, Any]) -> str:
    side = "" if row["side"] == "-" else f", {row['side']}"
    return f"{row['ability']}: {row['criterion']}{side} [{row['unit']}]"

