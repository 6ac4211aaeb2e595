"""How ``seahelm maneuver spiral`` (and a ``kind = "spiral"`` scenario) shows the direct and
reverse spirals: the direct spiral's steps, the reverse spiral's r-δ points, the loop widths;
or one JSON object."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from rich.markup import escape
from rich.table import Table

from ._common import console, print_json
from .maneuver_output import _fmt, header, write_outputs

__all__ = ["show_spirals"]


def show_spirals(title: str, direct: Any, reverse: Any, out: Path | None,
                 as_json: bool, *, plot: bool = True) -> None:
    """Write (``out``) and print the direct and reverse spirals: a table of the direct
    spiral's steps and the loop widths, or one JSON object."""
    dm = direct.metrics
    rm = reverse.metrics
    rows = []
    for j in range(dm.sizes["step"]):
        rows.append({"run": f"{j}", "leg": "down" if int(dm["leg"][j]) < 0 else "up",
                     "rudder_deg": math.degrees(float(dm["step_rudder"][j])),
                     "yaw_rate_degps": math.degrees(float(dm["yaw_rate"][j])),
                     "yaw_rate_nd": float(dm["yaw_rate_nd"][j]),
                     "speed_mps": float(dm["speed"][j]), "settled": bool(dm["settled"][j])})
    reverse_rows = [{"yaw_rate_degps": math.degrees(float(r_)),
                     "rudder_deg": math.degrees(float(d_)), "yaw_rate_nd": float(n_)}
                    for r_, d_, n_ in zip(rm["yaw_rate"].values, rm["rudder_angle"].values,
                                          rm["yaw_rate_nd"].values) if math.isfinite(r_)]
    payload = header(direct)
    payload.update(
        maneuver="spiral",
        direct_loop_width_deg=math.degrees(float(dm["loop_width"])),
        direct_zero_crossing_down_deg=math.degrees(float(dm["zero_crossing_down"])),
        direct_zero_crossing_up_deg=math.degrees(float(dm["zero_crossing_up"])),
        direct_message=str(dm["message"].item()),
        reverse_loop_width_deg=math.degrees(float(rm["loop_width"])),
        reverse_loop_rudder_low_deg=math.degrees(float(rm["loop_rudder_low"])),
        reverse_loop_rudder_high_deg=math.degrees(float(rm["loop_rudder_high"])),
        reverse_method=rm.attrs["method"])
    if out is not None:
        from ..plotting.maneuvers import plot_spiral

        payload["files"] = write_outputs(
            out, [direct, reverse], (lambda: plot_spiral(direct, reverse)) if plot else None,
            "spiral.png")
    if as_json:
        print_json({**payload, "direct": rows, "reverse": reverse_rows})
        return
    table = Table(title=escape(title), title_justify="left")
    for col in ("step", "leg", "rudder [deg]", "r [deg/s]", "r' = rL/U", "U [m/s]", "settled"):
        table.add_column(escape(col), justify="right")
    for row in rows:
        table.add_row(row["run"], row["leg"], *(_fmt(row[k]) for k in (
            "rudder_deg", "yaw_rate_degps", "yaw_rate_nd", "speed_mps", "settled")))
    console.print(table)
    # the reverse spiral's r-delta curve too (it was only its loop width), at most 15 points
    shown = reverse_rows[::max(1, math.ceil(len(reverse_rows) / 15))]
    back = Table(title=escape(f"Reverse spiral (equilibria), {len(shown)} of "
                              f"{len(reverse_rows)} points (all: --json)"), title_justify="left")
    for col in ("r [deg/s]", "rudder [deg]", "r' = rL/U"):
        back.add_column(escape(col), justify="right")
    for row in shown:
        back.add_row(*(_fmt(row[k]) for k in ("yaw_rate_degps", "rudder_deg", "yaw_rate_nd")))
    console.print(back)
    for k, v in payload.items():
        if k not in ("files",):
            console.print(escape(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"),
                          highlight=False)
    for kind, path in payload.get("files", {}).items():
        console.print(f"  {kind}: {escape(path)}", highlight=False)
