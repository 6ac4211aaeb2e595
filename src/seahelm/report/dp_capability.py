"""The report section of a DP capability file (``seahelm dp capability --out``, level 1 or 3):
what was assumed, a polar plot of the largest wind speed held per direction (intact and the
worst single failure, bow up and starboard to the right, as the command's ``--plot``), and per
failure case the least and largest wind held with the direction of the least.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .blocks import Section, fmt, paragraph, table

__all__ = ["dp_capability_sections"]


def _polar(directions_deg: np.ndarray, cases: list[str], wind: np.ndarray) -> dict[str, Any]:
    theta = np.append(directions_deg, directions_deg[:1]).tolist()

    def trace(values: np.ndarray, name: str, dash: str) -> dict[str, Any]:
        return {"type": "scatterpolar", "theta": theta,
                "r": np.append(values, values[:1]).tolist(), "mode": "lines+markers",
                "name": name, "line": {"dash": dash},
                "hovertemplate": f"{name}: %{{r:.4g}} m/s from %{{theta:.4g}}°<extra></extra>"}

    data = [trace(wind[0], cases[0], "solid")]
    if len(cases) > 1:
        data.append(trace(wind[1:].min(axis=0), "worst single failure (per direction)", "dash"))
    return {"data": data, "layout": {
        "polar": {"angularaxis": {"rotation": 90, "direction": "clockwise",
                                  "tickvals": list(range(0, 360, 30)),
                                  "ticktext": [f"{d}°" for d in range(0, 360, 30)]},
                  "radialaxis": {"title": {"text": "wind speed held [m/s]"}, "angle": 45}},
        "height": 460, "margin": {"l": 40, "r": 40, "t": 30, "b": 30}}}


def dp_capability_sections(data: Any) -> list[Section]:
    """The DP capability section (none for other inputs).

    Parameters
    ----------
    data : ReportData
        What the report shows (:class:`seahelm.report.inputs.ReportData`).

    Returns
    -------
    list of Section
    """
    ds = data.dp_capability
    if ds is None:
        return []
    a = ds.attrs
    level = int(a.get("level", 1))
    sec = Section("dp-capability", f"DP station-keeping capability, level {level}")
    meta = [["vessel", str(a.get("vessel", "?"))], ["level", str(level)]]
    if "current_speed" in a:
        meta.append(["current [m/s]", fmt(float(a["current_speed"]), 4)])
    if "wind" in ds.coords:
        meta.append(["wind speeds simulated [m/s]",
                     ", ".join(fmt(float(w), 4) for w in ds["wind"].values)])
    sec.blocks.append(table(None, meta, cls="meta"))
    notes = str(a.get("assumptions") or a.get("criteria") or "")
    for note in [n.strip() for n in notes.split(";") if n.strip()]:
        sec.blocks.append(paragraph(f"• {note}"))
    cases = [str(c) for c in ds["case"].values]
    directions = np.degrees(np.asarray(ds["direction"].values, dtype=float))
    wind = np.asarray(ds["wind_speed"].values, dtype=float)
    sec.blocks.append(paragraph("largest wind speed held [m/s] by the direction the "
                                "environment comes from (bow up, starboard to the right)"))
    sec.blocks.append(_polar(directions, cases, wind))
    rows = []
    for case, row in zip(cases, wind):
        j = int(np.argmin(row))
        rows.append([case, fmt(float(row.min()), 4), fmt(float(directions[j]), 4),
                     fmt(float(row.max()), 4)])
    sec.blocks.append(table(["case", "least wind held [m/s]", "from [deg]",
                             "largest wind held [m/s]"], rows, cls="metrics",
                            caption=f"over {directions.size} direction(s)"))
    if level == 3 and "held" in ds:
        held = np.asarray(ds["held"].values, dtype=bool)
        excursion = np.asarray(ds["excursion"].values)
        largest = fmt(float(excursion[held].max()), 4) if held.any() else "–"
        sec.blocks.append(paragraph(
            f"{int(held.sum())} of {held.size} runs held (case × direction × wind); the "
            f"largest excursion of a held run: {largest} m"))
    return [sec]
