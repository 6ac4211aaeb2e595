"""``seahelm imo SHIP``: check a ship (catalog name or ship file) against IMO Resolution MSC.137(76).

Runs :func:`seahelm.analysis.imo.imo_check` (35° turning circles and 10° initial turning to
both sides, 10/10 and 20/20 zig-zags to both sides) and prints a table of the criteria with
value, limit, margin (limit − value) and pass/fail; stopping is reported as not evaluated.
``--json`` prints exactly one JSON object (angles in degrees, lengths in ship lengths);
``--out DIR`` writes the runs and metrics as NetCDF, the report as JSON and the turning and
zig-zag figures as PNG. Exit codes: 0 the check ran (whether or not the ship passes), 2 bad
input, 1 other failure.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from ._common import JsonFlag, _jsonable, console, handle_errors, print_json
from .maneuver import (
    Depth,
    Dt,
    Out,
    Rps,
    SHIP_HELP,
    ShipName,
    Speed,
    check_out,
    check_positive_opt,
    check_speed_rps,
    ship_reads,
    ship_of,
)

__all__ = ["imo", "show_report"]


def _display(criterion: Any) -> dict[str, Any]:
    row = criterion.as_dict()
    if row["unit"] == "rad":
        for key in ("value", "limit", "margin"):
            row[key] = math.degrees(row[key])
        row["unit"] = "deg"
    return row


@handle_errors
def imo(
    model: Annotated[ShipName, typer.Argument(metavar="SHIP", help=SHIP_HELP)],
    speed: Speed = None,
    rps: Rps = None,
    dt: Dt = None,
    water_depth: Depth = None,
    json_out: JsonFlag = False,
    out: Out = None,
) -> None:
    """Check a ship against IMO MSC.137(76): turning, initial turning, zig-zags, stopping."""
    from ..analysis.imo import imo_check

    ship = ship_of(model, water_depth)
    check_speed_rps(ship, speed, rps)
    check_positive_opt("--dt", dt, "s")
    check_out(out, "imo", ship_reads(model))
    show_report(imo_check(ship, speed=speed, rps=rps, dt=dt), out, json_out)


def show_report(report: Any, out: Path | None, as_json: bool, *, plot: bool = True) -> None:
    """Write (``out``) and print an :class:`~seahelm.analysis.imo.ImoReport`: the criteria
    table with notes, or one JSON object."""
    rows = [_display(c) for c in report.criteria]
    payload: dict[str, Any] = {
        "ship": report.ship, "length_m": report.length, "speed_mps": report.speed,
        "L_over_V_s": report.L_over_V, "passed": report.passed, "criteria": rows,
        "notes": list(report.notes)}
    if out is not None:
        payload["files"] = _write(out, report, payload, plot)
    if as_json:
        print_json(payload)
        return
    verdict = "PASSES" if report.passed else "FAILS"
    table = Table(title=escape(f"IMO MSC.137(76): {report.ship} (L = {report.length:g} m, "
                               f"V = {report.speed:.4g} m/s, L/V = {report.L_over_V:.4g} s) "
                               f"{verdict} the evaluated criteria"), title_justify="left")
    for col in ("ability", "criterion", "side", "value", "limit", "margin", "unit", "status"):
        table.add_column(col, justify="right" if col in ("value", "limit", "margin") else "left",
                         no_wrap=col in ("side", "unit", "status"))
    for row in rows:
        style = {"pass": "green", "fail": "bold red"}.get(row["status"], "yellow")
        table.add_row(*(escape(str(row[k])) for k in ("ability", "criterion", "side")),
                      *(("—" if not math.isfinite(row[k]) else f"{row[k]:.4g}")
                        for k in ("value", "limit", "margin")),
                      row["unit"], f"[{style}]{escape(row['status'])}[/{style}]")
    console.print(table)
    for row in rows:
        if row["note"]:
            console.print(escape(f"  {row['ability']} ({row['side']}): {row['note']}"),
                          highlight=False)
    for note in report.notes:
        console.print(escape(f"  note: {note}"), highlight=False)
    for kind, path in payload.get("files", {}).items():
        console.print(f"  {kind}: {escape(path)}", highlight=False)


def _write(out: Path, report: Any, payload: dict[str, Any], plot: bool = True
           ) -> dict[str, str]:
    from ..results import write_together

    with write_together():  # the runs, metrics, figures and report appear together or not
        return _write_files(out, report, payload, plot)


def _write_files(out: Path, report: Any, payload: dict[str, Any], plot: bool
                 ) -> dict[str, str]:
    from ..plotting.maneuvers import plot_turning, plot_zigzag
    from ..results import atomic_write
    from .maneuver import write_outputs

    files = write_outputs(out, [report.turning], (lambda: plot_turning(report.turning))
                          if plot else None, "imo-turning.png")
    if plot:
        files["plot_turning"] = files.pop("plot")
    more = write_outputs(out, [report.zigzag], (lambda: plot_zigzag(report.zigzag))
                         if plot else None, "imo-zigzag.png")
    if plot:
        more["plot_zigzag"] = more.pop("plot")
    files.update(more)
    text = json.dumps(_jsonable({k: v for k, v in payload.items() if k != "files"}), indent=2,
                      allow_nan=False)
    files["report"] = str(atomic_write(out / "imo-report.json",
                                       lambda tmp: Path(tmp).write_text(text + "\n")))
    return files
