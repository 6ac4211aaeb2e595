"""The report section of a seakeeping result (``seakeeping.nc`` of ``seahelm seakeeping
--out``, :meth:`seahelm.analysis.seakeeping.frequency_domain.ResponseMoments.to_xarray`): what
was computed, a polar diagram of each degree of freedom's RMS over wave heading × speed (plotly
``barpolar``: head seas up, following seas down, waves from port on the left, as the PNG of
:mod:`seahelm.plotting.seakeeping`), and per speed the largest RMS and significant amplitude
over the headings with the heading where it occurs. Roll and pitch are shown in degrees, heave
in metres.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .blocks import Section, fmt, paragraph, table
from .inputs import ReportData

__all__ = ["seakeeping_sections", "MAX_SPEED_ROWS"]

#: Speeds listed one per row in a degree of freedom's table (the figure shows all).
MAX_SPEED_ROWS = 40

#: The file's attributes shown, in this order.
_SHOWN = ("ship", "spectrum", "spreading", "raos")


def _display(dof: str) -> tuple[float, str]:
    return (1.0, "m") if dof in ("heave", "surge", "sway") else (180.0 / math.pi, "deg")


def _polar_figure(dof: str, speed: np.ndarray, heading_deg: np.ndarray,
                  rms: np.ndarray, unit: str) -> dict[str, Any]:
    """Each (speed, heading) cell as a ring sector coloured by the RMS."""
    order = np.argsort(np.mod(heading_deg, 360.0))
    theta = np.mod(heading_deg, 360.0)[order]
    if theta.size > 1:
        gaps = np.diff(np.append(theta, theta[0] + 360.0))
        width = float(np.min(gaps[gaps > 1e-9])) if np.any(gaps > 1e-9) else 360.0
    else:
        width = 360.0
    edges = (np.concatenate([[0.0], 0.5 * (speed[1:] + speed[:-1]), [speed[-1] + (
        0.5 * (speed[-1] - speed[-2]) if speed.size > 1 else max(speed[-1], 1.0))]])
        if speed.size else np.array([0.0, 1.0]))
    lo, hi = float(np.nanmin(rms)), float(np.nanmax(rms))
    data = []
    for i, U in enumerate(speed):
        values = rms[i, order]
        data.append({
            "type": "barpolar", "theta": theta.tolist(), "width": [width] * theta.size,
            "base": [float(edges[i])] * theta.size,
            "r": [float(edges[i + 1] - edges[i])] * theta.size,
            "marker": {"color": values.tolist(), "coloraxis": "coloraxis",
                       "line": {"width": 0}},
            "name": f"{fmt(float(U), 4)} m/s", "showlegend": False,
            "hovertemplate": (f"U {fmt(float(U), 4)} m/s, heading %{{theta:.4g}}°: RMS {dof} "
                              f"%{{marker.color:.4g}} {unit}<extra></extra>")})
    return {"data": data, "layout": {
        "polar": {"angularaxis": {"rotation": 270, "direction": "clockwise",
                                  "tickvals": list(range(0, 360, 30)),
                                  "ticktext": [f"{d}°" for d in range(0, 360, 30)]},
                  "radialaxis": {"title": {"text": "speed [m/s]"}, "angle": 135}},
        "coloraxis": {"colorscale": "Viridis", "cmin": lo, "cmax": hi if hi > lo else lo + 1,
                      "colorbar": {"title": {"text": f"RMS {dof} [{unit}]"}}},
        "height": 460, "margin": {"l": 40, "r": 40, "t": 30, "b": 30}}}


def seakeeping_sections(data: ReportData) -> list[Section]:
    """The seakeeping section (none for other inputs).

    Parameters
    ----------
    data : ReportData
        What the report shows.

    Returns
    -------
    list of Section
    """
    ds = data.seakeeping
    if ds is None:
        return []
    sec = Section("seakeeping", "Seakeeping in the frequency domain")
    a = ds.attrs
    sec.blocks.append(table(None, [[k, str(a[k])] for k in _SHOWN if k in a], cls="meta"))
    sec.blocks.append(paragraph(
        "response spectral moments m_n = ∫ ω_eⁿ |H|² S(ω) D(θ) dθ dω over the mean wave heading "
        "relative to the ship (0° following, 180° head, 90° waves travelling to starboard, "
        "i.e. from port) and the ship's speed; significant amplitude = 2√m0 (significant "
        "height, crest to trough, 4√m0); T_z = 2π√(m0/m2), in encounter"))
    speed = np.asarray(ds["speed"].values, dtype=float)
    heading = np.degrees(np.asarray(ds["heading"].values, dtype=float))
    for dof in [str(d) for d in ds["dof"].values]:
        factor, unit = _display(dof)
        rms = np.asarray(ds["rms"].sel(dof=dof).values, dtype=float) * factor
        sig = np.asarray(ds["significant_amplitude"].sel(dof=dof).values, dtype=float) * factor
        tz = np.asarray(ds["zero_crossing_period"].sel(dof=dof).values, dtype=float)
        sec.blocks.append(paragraph(f"RMS {dof} [{unit}] over heading (angle) and speed "
                                    "(radius)"))
        sec.blocks.append(_polar_figure(dof, speed, heading, rms, unit))
        rows = []
        for i in range(min(speed.size, MAX_SPEED_ROWS)):
            j = int(np.argmax(rms[i]))
            rows.append([fmt(speed[i], 4), fmt(rms[i, j], 4), fmt(heading[j], 4),
                         fmt(sig[i, j], 4), fmt(tz[i, j], 4)])
        caption = (f"largest over {heading.size} heading(s) per speed"
                   + ("" if speed.size <= MAX_SPEED_ROWS else
                      f"; first {MAX_SPEED_ROWS} of {speed.size} speeds"))
        sec.blocks.append(table(["U [m/s]", f"max RMS {dof} [{unit}]", "at heading [deg]",
                                 f"significant amplitude there [{unit}]", "T_z there [s]"],
                                rows, cls="metrics", caption=caption))
    return [sec]
