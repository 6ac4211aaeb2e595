"""The report section of an encounter study (``encounters.nc`` of ``seahelm encounter --out``,
:meth:`seahelm.encounters.result.EncounterResult.to_xarray`): the outcome table by the own
ship's COLREG situation at the start (collision and domain-intrusion rates with 95 % Wilson
intervals, the Rule 8/16/17 verdicts, as ``seahelm encounter`` printed it), the tracks of the
encounters with the least ranges with the own ship's domain (Fujii & Tanaka ellipse) at time
marks, range and DCPA over time, and a rose of outcomes by the target's relative bearing at
the start (as the PNGs of :mod:`seahelm.plotting.encounters`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .blocks import Section, fmt, paragraph, table
from .figures import LEGEND, run_colors, typed_array
from .inputs import ReportData
from .signals import decimated_index

__all__ = ["encounter_sections", "TRACKS_SHOWN", "CPA_SHOWN", "ROSE_SECTORS"]

#: Encounters whose tracks are drawn (those with the least ranges, in that order).
TRACKS_SHOWN = 4
#: Encounters whose range and DCPA are drawn over time (the least ranges first).
CPA_SHOWN = 8
#: Bearing sectors of the rose (22.5° each).
ROSE_SECTORS = 16
#: Time between marks on the tracks [s].
MARKS = 120.0


def _pct(v: Any) -> str:
    return "—" if v is None else f"{100 * v:.1f} %"


def _ci(value: float, ci: tuple[float, float]) -> str:
    return f"{100 * value:.1f} % [{100 * ci[0]:.1f}, {100 * ci[1]:.1f}]"


def outcome_rows(result: Any) -> list[list[str]]:
    """The outcome table's rows (situation, n, collision, near miss, give-way acted,
    substantial, stand-on kept course, crossing stand-on altered to port (Rule 17(c)), median
    least range) of ``result.summary()``."""
    return [[r["situation"], str(r["encounters"]), _ci(r["collision"], r["collision_ci"]),
             _ci(r["near_miss"], r["near_miss_ci"]), _pct(r["own_acted"]),
             _pct(r["own_substantial"]), _pct(r["own_kept_course"]),
             _pct(r.get("own_altered_to_port")),
             f"{fmt(r['min_range_median'], 4)} m"] for r in result.summary()]


def _order(result: Any) -> np.ndarray:
    """Encounters by the least range to the first target, smallest first."""
    return np.argsort(np.where(np.isfinite(result.min_range[:, 0]), result.min_range[:, 0],
                               np.inf), kind="stable")


def _track_figure(result: Any, e: int) -> dict[str, Any]:
    tr, t = result.tracks, result.time
    nv = tr["north"].shape[1]
    idx = decimated_index(t.size)
    step = max(1, int(round(MARKS / max(t[1] - t[0], 1e-9)))) if t.size > 1 else 1
    marks = np.arange(0, t.size, step)
    colors = run_colors(nv)
    traces: list[dict[str, Any]] = []
    for v in range(nv):
        n, east = tr["north"][e, v], tr["east"][e, v]
        traces.append({"type": "scatter", "mode": "lines", "name": result.names[v],
                       "x": typed_array(east[idx]), "y": typed_array(n[idx]),
                       "line": {"color": colors[v], "width": 1.5}})
        traces.append({"type": "scatter", "mode": "markers+text", "showlegend": False,
                       "x": typed_array(east[marks]), "y": typed_array(n[marks]),
                       "text": [f"{t[k] / 60:.0f}" for k in marks], "textposition": "top right",
                       "textfont": {"size": 9, "color": colors[v]},
                       "marker": {"size": 4, "color": colors[v]},
                       "hovertemplate": f"{result.names[v]}: %{{text}} min<extra></extra>"})
    along, across = result.domain_axes
    L = float(result.lengths[0])
    s = np.linspace(0.0, 2 * math.pi, 49)
    k_min = int(np.nanargmin(result.pair["range"][e, 0])) if nv > 1 else 0
    xs: list[float | None] = []
    ys: list[float | None] = []
    for k in sorted(set(marks.tolist()) | {k_min}):
        psi = tr["heading"][e, 0, k]
        x, y = along * L * np.cos(s), across * L * np.sin(s)
        xs += (tr["east"][e, 0, k] + x * math.sin(psi) + y * math.cos(psi)).tolist() + [None]
        ys += (tr["north"][e, 0, k] + x * math.cos(psi) - y * math.sin(psi)).tolist() + [None]
    traces.append({"type": "scatter", "mode": "lines", "name": "own ship's domain",
                   "x": xs, "y": ys, "connectgaps": False, "hoverinfo": "skip",
                   "line": {"color": colors[0], "width": 0.6, "dash": "dot"}})
    return {"data": traces, "layout": {
        "xaxis": {"title": {"text": "east [m]"}},
        "yaxis": {"title": {"text": "north [m]"}, "scaleanchor": "x", "scaleratio": 1},
        "height": 480, "margin": dict(l=60, r=20, t=20, b=50), "legend": LEGEND}}


def _cpa_figure(result: Any, shown: np.ndarray) -> dict[str, Any]:
    t = result.time / 60.0
    idx = decimated_index(t.size)
    colors = run_colors(len(shown))
    traces: list[dict[str, Any]] = []
    for c, e in enumerate(shown):
        rng = result.pair["range"][e, 0]
        dcpa = np.where(result.pair["tcpa"][e, 0] > 0, result.pair["dcpa"][e, 0], np.nan)
        traces.append({"type": "scatter", "mode": "lines", "name": f"{e}: range",
                       "x": typed_array(t[idx]), "y": typed_array(rng[idx]),
                       "line": {"color": colors[c], "width": 1.4}})
        traces.append({"type": "scatter", "mode": "lines", "name": f"{e}: DCPA (ahead)",
                       "x": typed_array(t[idx]), "y": typed_array(dcpa[idx]),
                       "line": {"color": colors[c], "width": 1.0, "dash": "dash"}})
    touch = 0.5 * float(result.lengths[0] + result.lengths[1])
    traces.append({"type": "scatter", "mode": "lines", "name": "collision (half lengths)",
                   "x": [float(t[0]), float(t[-1])], "y": [touch, touch],
                   "line": {"color": "#000000", "width": 0.8, "dash": "dot"}})
    return {"data": traces, "layout": {
        "xaxis": {"title": {"text": "time [min]"}},
        "yaxis": {"title": {"text": "distance [m]"}, "type": "log"},
        "height": 380, "margin": dict(l=60, r=20, t=20, b=50), "legend": LEGEND}}


def rose_counts(result: Any, sectors: int = ROSE_SECTORS) -> dict[str, np.ndarray]:
    """Collisions, domain intrusions and clear passings per sector of the first target's
    relative bearing at the start (sector 0 centred on the bow, clockwise)."""
    from ..plotting.encounters import initial_bearing

    beta = initial_bearing(result)
    width = 2 * math.pi / sectors
    k = np.floor(((beta + width / 2) % (2 * math.pi)) / width).astype(int) % sectors
    coll, near = result.collision[:, 0], result.near_miss[:, 0]
    return {"collision": np.bincount(k[coll], minlength=sectors),
            "near miss": np.bincount(k[near], minlength=sectors),
            "clear": np.bincount(k[~(coll | near)], minlength=sectors)}


def _rose_figure(result: Any) -> dict[str, Any]:
    counts = rose_counts(result)
    theta = (np.arange(ROSE_SECTORS) * 360.0 / ROSE_SECTORS).tolist()
    colors = {"collision": "#d62728", "near miss": "#ff7f0e", "clear": "#2ca02c"}
    data = [{"type": "barpolar", "name": name, "theta": theta, "r": c.tolist(),
             "width": [360.0 / ROSE_SECTORS] * ROSE_SECTORS,
             "marker": {"color": colors[name], "line": {"width": 0.5, "color": "#ffffff"}},
             "hovertemplate": f"bearing %{{theta}}°: %{{r}} {name}<extra></extra>"}
            for name, c in counts.items()]
    return {"data": data, "layout": {
        "barmode": "stack",
        "polar": {"angularaxis": {"rotation": 90, "direction": "clockwise",
                                  "tickvals": list(range(0, 360, 45)),
                                  "ticktext": [f"{d}°" for d in range(0, 360, 45)]},
                  "radialaxis": {"title": {"text": "encounters"}, "angle": 45}},
        "height": 460, "margin": {"l": 40, "r": 40, "t": 30, "b": 30}, "legend": LEGEND}}


def encounter_sections(data: ReportData) -> list[Section]:
    """The encounter study's section (none for other inputs).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    ds = data.encounters
    if ds is None:
        return []
    from ..encounters.result import EncounterResult

    result = EncounterResult.from_xarray(ds)
    a = ds.attrs
    sec = Section("encounters", "Ships meeting ships")
    ne, nv = result.n_encounters, len(result.names)
    duration = float(np.nanmax(result.time)) if result.time.size else 0.0
    meta = [["encounters", str(ne)], ["vessels", ", ".join(
        f"{n} (L = {fmt(float(L), 4)} m)" for n, L in zip(result.names, result.lengths))],
        ["duration", f"{fmt(duration, 5)} s"],
        ["own ship's avoidance", str(a.get("avoidance", "—"))],
        ["own ship's domain", f"ellipse {fmt(result.domain_axes[0], 3)} L along × "
                              f"{fmt(result.domain_axes[1], 3)} L across (semi-axes)"]]
    if "seahelm_command" in a:
        meta.append(["command", str(a["seahelm_command"])])
    sec.blocks.append(table(None, meta, cls="meta"))
    if nv < 2:
        sec.blocks.append(paragraph("one vessel: no encounter to count"))
        return [sec]
    sec.blocks.append(table(
        ["situation", "n", "collision [95% CI]", "near miss [95% CI]",
         "give-way acted", "substantial", "stand-on kept course",
         "stand-on altered to port (Rule 17(c))", "least range (median)"],
        outcome_rows(result), cls="metrics",
        caption="by the own ship's COLREG situation at the start, against the first target; "
                "intervals: Wilson 95 %; a collision is a least range below the half "
                "lengths' sum, a domain intrusion the target inside the own ship's domain "
                "without one; Rule 17(c): of the crossing encounters where the own ship "
                "stands on, those where it turned to port (for a vessel on its port side) "
                "by more than the action threshold before the closest point of approach"))
    order = _order(result)
    for e in order[:TRACKS_SHOWN]:
        e = int(e)
        sec.blocks.append(paragraph(
            f"encounter {e}: least range {fmt(float(result.min_range[e, 0]), 4)} m at "
            f"{fmt(float(result.t_min_range[e, 0]) / 60, 3)} min"
            + (" — collision" if result.collision[e, 0] else "")
            + (" — near miss (inside the domain)" if result.near_miss[e, 0] else "")
            + f"; marks every {MARKS / 60:g} min (labels: minutes), the own ship's domain "
              "at the marks and at the least range; east right, north up", cls="caption"))
        sec.blocks.append(_track_figure(result, e))
    shown = order[:CPA_SHOWN]
    sec.blocks.append(paragraph(
        f"range and DCPA (while the target closes) over time, the {shown.size} encounter(s) "
        "with the least ranges", cls="caption"))
    sec.blocks.append(_cpa_figure(result, shown))
    sec.blocks.append(paragraph(
        "outcomes by the target's relative bearing at the start (bow up, clockwise; "
        f"{360 / ROSE_SECTORS:g}° sectors)", cls="caption"))
    sec.blocks.append(_rose_figure(result))
    return [sec]
