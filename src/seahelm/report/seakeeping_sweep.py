"""The report section of a time-domain seakeeping sweep (a sweep store whose runs have
first-order wave motions, :mod:`seahelm.sweep.seakeeping`): per degree of freedom the polar
diagram of the time-domain RMS over mean wave heading × mean speed beside the frequency-domain
RMS of the same cells (one colour scale, plotly ``barpolar``: head seas up, following seas
down, waves from port on the left, as :mod:`seahelm.report.seakeeping`), and a table of every
cell: its speed and heading, runs, the RMS with its standard error, the frequency-domain RMS
and their difference in standard errors of the mean square. Roll and pitch in degrees, heave
in metres.

A sweep with first-order motions whose grid cannot make a polar diagram (one heading, no
seeded runs per cell, ...) gets the section with the reason instead.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .blocks import Section, fmt, paragraph, table
from .inputs import ReportData
from .seakeeping import _display, _polar_figure

__all__ = ["sweep_seakeeping_sections", "MAX_CELL_ROWS"]

#: Cells listed one per row in a degree of freedom's table.
MAX_CELL_ROWS = 200


def _side_by_side(dof: str, speed: np.ndarray, heading_deg: np.ndarray, td: np.ndarray,
                  fd: np.ndarray | None, unit: str) -> dict[str, Any]:
    """The time-domain polar (left) and the frequency-domain one (right), one colour scale."""
    left = _polar_figure(dof, speed, heading_deg, td, unit)
    if fd is None or not np.any(np.isfinite(fd)):
        return left
    right = _polar_figure(dof, speed, heading_deg, np.where(np.isfinite(fd), fd, np.nan), unit)
    both = np.concatenate([td[np.isfinite(td)], fd[np.isfinite(fd)]])
    lo, hi = float(both.min()), float(both.max())
    for trace in right["data"]:
        trace["subplot"] = "polar2"
        trace["hovertemplate"] = trace["hovertemplate"].replace("RMS", "frequency-domain RMS")
    for trace in left["data"]:
        trace["hovertemplate"] = trace["hovertemplate"].replace("RMS", "time-domain RMS")
    layout = left["layout"]
    polar = layout["polar"]
    layout["polar"] = {**polar, "domain": {"x": [0.0, 0.42]}}
    layout["polar2"] = {**polar, "domain": {"x": [0.5, 0.92]}}
    layout["coloraxis"].update(cmin=lo, cmax=hi if hi > lo else lo + 1.0)
    layout["annotations"] = [
        {"text": "time domain (sweep)", "x": 0.21, "y": 1.08, "xref": "paper",
         "yref": "paper", "showarrow": False},
        {"text": "frequency domain, same cells", "x": 0.71, "y": 1.08, "xref": "paper",
         "yref": "paper", "showarrow": False}]
    layout["margin"] = {"l": 40, "r": 40, "t": 50, "b": 30}
    return {"data": left["data"] + right["data"], "layout": layout}


def sweep_seakeeping_sections(data: ReportData) -> list[Section]:
    """The time-domain seakeeping section of a sweep store (none for other inputs).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    from ..sweep.seakeeping import DOF_METRICS, frequency_domain_moments, sweep_seakeeping

    ds = data.sweep
    if ds is None or not any(m in ds for m, *_ in DOF_METRICS.values()):
        return []
    sec = Section("seakeeping-sweep", "Seakeeping from the time-domain sweep")
    try:
        polar = sweep_seakeeping(ds, frequency_domain=False)
    except ParameterError as exc:
        key = f"[{exc.field}] " if exc.field else ""
        sec.blocks.append(paragraph(f"no polar diagram: {key}{exc.reason.lstrip(': ')}"))
        return [sec]
    try:
        polar = dataclasses.replace(polar, frequency_domain=frequency_domain_moments(
            polar, str(ds.attrs.get("scenario_text", "")),
            str(ds.attrs.get("scenario_source", "the sweep"))))
    except (ParameterError, ValueError) as exc:  # (a ScenarioError is a ValueError)
        sec.blocks.append(paragraph(f"no frequency-domain comparison: {exc}"))
    sec.blocks.append(paragraph(
        "per cell (mean wave heading relative to the ship: 0° following, 180° head, 90° waves "
        "travelling to starboard; mean surge speed) the mean square m̂0 of the runs' first-order "
        "motions, RMS = √m̂0 with its standard error se(m̂0)/(2√m̂0), se(m̂0) = σ̂/√R over the R "
        "seeded runs; beside it the frequency-domain m0 = ∫∫|H|²S D dθ dω of the same RAO "
        "tables, sea and band at the cell's speed and heading. z = (m̂0 − m0)/se(m̂0): |z| ≤ 3 "
        "with 99.7 % when they agree. Where the first-order response vanishes at the exact "
        "heading (pitch in beam seas, roll in head and following seas) the autopilot's "
        "heading wander alone gives the time domain its (small) value and z means little."))
    speed = polar.row_speed
    heading = np.degrees(polar.column_heading)
    for dof in polar.dofs:
        factor, unit = _display("roll" if dof == "roll_total" else dof)
        td = polar.rms(dof) * factor
        se = polar.rms_standard_error(dof) * factor
        fd = polar.frequency_domain_rms(dof) * factor
        z = polar.deviation(dof)
        name = "total roll (model + first-order)" if dof == "roll_total" else (
            f"first-order {dof}")
        sec.blocks.append(paragraph(f"RMS {name} [{unit}] over heading (angle) and speed "
                                    "(radius)" + ("" if dof == "roll_total" else
                                                  ": time domain and frequency domain")))
        sec.blocks.append(_side_by_side(dof, speed, heading, td,
                                        None if dof == "roll_total" else fd, unit))
        rows = []
        for i, j in list(np.ndindex(*td.shape))[:MAX_CELL_ROWS]:
            rows.append([fmt(polar.speed[i, j], 4), fmt(math.degrees(polar.heading[i, j]), 4),
                         str(polar.n_runs[i, j]), fmt(td[i, j], 4), fmt(se[i, j], 2),
                         fmt(fd[i, j], 4), fmt(z[i, j], 2)])
        n_cells = td.size
        caption = (f"{n_cells} cells" + ("" if n_cells <= MAX_CELL_ROWS else
                                          f"; first {MAX_CELL_ROWS}"))
        sec.blocks.append(table(["U [m/s]", "heading [deg]", "runs", f"RMS [{unit}]",
                                 f"± se [{unit}]", f"frequency domain [{unit}]", "z"],
                                rows, cls="metrics", caption=caption))
    return [sec]
