"""``seahelm replay RECORD --ship SHIP``: simulate a measured record with its measured inputs.

Reads the record (:func:`seahelm.identification.records.read_records`: a CSV file with a header, a
known format such as the FRT-DS-ESSO free-running tests read as it is, other headers through
``--column HEADER=CHANNEL``; or a seahelm NetCDF result), replays every record in it
(:func:`seahelm.analysis.replay.simulate.replay`: from its first sample, with its measured rudder
and rps as first-order hold inputs; ``--wind measured``: with its measured true wind) and prints
the measured and simulated metrics side by side and the RMS position error over the first 60 s and
the whole record in ship lengths. ``--json`` prints one JSON object; ``--out DIR`` writes
``replay.nc`` (both tracks) and ``replay.png`` (the overlay). ``--closed-loop`` replays a zig-zag
with its rudder switched by the simulated heading at the check angle. Exit codes: 0 done, 2 bad
input (a missing or misnamed column, a NaN, a time that goes backwards, degrees where radians are
expected, a record shorter than its manoeuvre needs: one line naming the file, column and row), 1
other failure.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from ._common import (
    ForceFlag,
    JsonFlag,
    console,
    handle_errors,
    input_file,
    output_dir,
    print_json,
)

__all__ = ["replay"]

#: Files ``--out`` receives (per record: ``replay-<k>`` when the file holds several).
_FILES = ("replay.nc", "replay.png")

#: Metric -> (label, unit shown, factor from SI).
_SHOWN: dict[str, tuple[str, str, float]] = {
    "advance": ("advance", "m", 1.0), "transfer": ("transfer", "m", 1.0),
    "tactical_diameter": ("tactical diameter", "m", 1.0),
    "steady_diameter": ("steady diameter", "m", 1.0),
    "speed_loss": ("speed loss 1 - U/U0", "-", 1.0),
    "overshoot_1": ("1st overshoot", "deg", 180.0 / math.pi),
    "overshoot_2": ("2nd overshoot", "deg", 180.0 / math.pi),
    "overshoot_3": ("3rd overshoot", "deg", 180.0 / math.pi),
    "execute_time_2": ("2nd execute (initial turning time)", "s", 1.0),
    "execute_time_3": ("3rd execute", "s", 1.0), "execute_time_4": ("4th execute", "s", 1.0),
    "time_to_check_yaw": ("time to check yaw", "s", 1.0), "period": ("period", "s", 1.0),
}


def _columns(items: list[str] | None) -> dict[str, str] | None:
    if not items:
        return None
    out = {}
    for item in items:
        header, sep, channel = item.rpartition("=")
        if not sep or not header.strip() or not channel.strip():
            raise ParameterError(f"`--column` must be HEADER=CHANNEL, got {item!r}")
        if header.strip() in out:
            raise ParameterError(f"`--column` maps header {header.strip()!r} twice "
                                 f"({out[header.strip()]} and {channel.strip()})")
        out[header.strip()] = channel.strip()
    return out


def _fmt(value: float) -> str:
    return "-" if not math.isfinite(value) else f"{value:.4g}"


def _payload(res: Any) -> dict[str, Any]:
    return {"record": res.record.name, "ship": res.ship, "kind": res.kind,
            "check_angle_deg": None if res.check_angle is None else math.degrees(res.check_angle),
            "dt_s": res.dt, "length_m": res.length,
            "rudder": "closed loop" if res.closed_loop else "measured",
            "wind": {k: (math.degrees(v) if k.startswith("direction") else v)
                     for k, v in res.wind.items()},
            "rms_position_error_60s_L": res.rms_error_window,
            "rms_position_error_L": res.rms_error,
            "metrics": {k: {"measured": m * _SHOWN[k][2], "simulated": s * _SHOWN[k][2],
                            "unit": _SHOWN[k][1]} for k, (m, s) in res.metrics.items()}}


def _show(res: Any) -> None:
    angle = ("" if res.check_angle is None
             else f", check angle {math.degrees(res.check_angle):.0f} deg")
    rudder = "rudder closed loop" if res.closed_loop else "measured rudder"
    if res.wind["kind"] == "measured":
        rudder += (f", measured wind {res.wind['mean_speed']:.3g} m/s mean from "
                   f"{math.degrees(res.wind['direction']):.0f} deg (spread "
                   f"{math.degrees(res.wind['direction_spread']):.0f} deg)")
    else:
        rudder += ", still air"
    table = Table(title=escape(f"Replay of {res.record.name} with {res.ship} ({res.kind}"
                               f"{angle}, {rudder}; dt {res.dt:.4g} s)"),
                  title_justify="left")
    for name, justify in (("metric", "left"), ("measured", "right"), ("simulated", "right")):
        table.add_column(name, justify=justify)  # type: ignore[arg-type]
    for key, (m, s) in res.metrics.items():
        label, unit, factor = _SHOWN[key]
        table.add_row(escape(f"{label} [{unit}]"), _fmt(m * factor), _fmt(s * factor))
    table.add_row("RMS position error, first 60 s [L]", "", _fmt(res.rms_error_window))
    table.add_row("RMS position error, whole record [L]", "", _fmt(res.rms_error))
    console.print(table)


@handle_errors
def replay(
    record: Annotated[Path, typer.Argument(metavar="RECORD", help=escape(
        "A measured record: a CSV file with a header row (a known format such as the "
        "FRT-DS-ESSO tests as it is, others with --column) or a seahelm NetCDF result."))],
    ship: Annotated[str, typer.Option("--ship", metavar="SHIP", help=escape(
        "Ship to simulate: a catalog name (`seahelm ship list`) or a ship file (*.toml)."))],
    kind: Annotated[str, typer.Option("--kind", metavar="auto|turning|zigzag|none", help=escape(
        "Manoeuvre whose metrics are compared (auto: read from the measured rudder)."))
    ] = "auto",
    check_angle: Annotated[float | None, typer.Option("--check-angle", help=escape(
        "A zig-zag's check angle [deg] (default: read from the record)."))] = None,
    dt: Annotated[float | None, typer.Option("--dt", help=escape(
        "Integration step [s] (default: the record's sampling interval, at most "
        "L/(100 U_max))."))] = None,
    angles: Annotated[str, typer.Option("--angles", metavar="deg|rad", help=escape(
        "Units of a CSV file's angles (a known format: its own)."))] = "deg",
    column: Annotated[list[str] | None, typer.Option("--column", metavar="HEADER=CHANNEL",
                                                     help=escape(
        "Map a CSV header to a channel (time, rudder_angle, heading, yaw_rate, surge_speed, "
        "sway_speed, x, y, propeller_rps); repeat for each column read."))] = None,
    closed_loop: Annotated[bool, typer.Option("--closed-loop", help=escape(
        "A zig-zag: switch the rudder by the simulated heading at the check angle (through "
        "the ship's steering gear) instead of replaying the measured rudder."))] = False,
    wind: Annotated[str, typer.Option("--wind", metavar="none|measured", help=escape(
        "Still air, or the record's measured true wind (its speed as a time series, its "
        "direction held at the circular mean) on the ship's windage (Blendermann 1994)."))
    ] = "none",
    json_out: JsonFlag = False,
    out: Annotated[Path | None, typer.Option("--out", help=escape(
        "Directory for replay.nc (both tracks) and replay.png (the overlay)."))] = None,
    force: ForceFlag = False,
) -> None:
    """Replay a measured record: simulated vs measured metrics and position error."""
    from ..identification.records import read_records
    from ..analysis.replay.simulate import KINDS, WIND
    from ..analysis.replay.simulate import replay as run_replay

    if kind not in KINDS:
        raise ParameterError(f"`--kind` must be one of {', '.join(KINDS)}, got {kind!r}")
    if check_angle is not None and not (math.isfinite(check_angle) and 0 < check_angle < 90):
        raise ParameterError(f"`--check-angle` must be in (0, 90) [deg], got {check_angle!r}")
    if wind not in WIND:
        raise ParameterError(f"`--wind` must be one of {', '.join(WIND)}, got {wind!r}")
    if angles not in ("deg", "rad"):
        raise ParameterError(f"`--angles` must be deg or rad, got {angles!r}")
    input_file("RECORD", record)
    mapping = _columns(column)
    records = read_records(record, angles=angles, columns=mapping)  # type: ignore[arg-type]
    if out is not None:  # (the names by the number of records, before the work)
        output_dir("--out", out, _names(len(records)), reads=(record,))
    results = [run_replay(r, ship, kind=kind, dt=dt,  # type: ignore[arg-type]
                          closed_loop=closed_loop, wind=wind,  # type: ignore[arg-type]
                          check_angle=None if check_angle is None
                          else math.radians(check_angle)) for r in records]
    payload: dict[str, Any] = {"replays": [_payload(r) for r in results]}
    if out is not None:
        payload["files"] = _write(out, results)
    if json_out:
        print_json(payload)
        return
    for res in results:
        _show(res)
    for kind_, path in payload.get("files", {}).items():
        console.print(f"{kind_}: {escape(path)}", highlight=False)


def _stem(k: int, n: int) -> str:
    return "replay" if n == 1 else f"replay-{k + 1}"


def _names(n: int) -> tuple[str, ...]:
    """The files ``--out`` receives for ``n`` records."""
    return tuple(_stem(k, n) + name[len("replay"):] for k in range(n) for name in _FILES)


def _write(out: Path, results: list[Any]) -> dict[str, str]:
    import matplotlib

    matplotlib.use("Agg")
    from ..plotting.replay import plot_replay
    from ..plotting.save import save_figure
    from ..results import write_netcdf, write_together

    files: dict[str, str] = {}
    with write_together():
        for k, res in enumerate(results):
            stem = _stem(k, len(results))
            files[f"{stem}.nc"] = str(write_netcdf(res.to_xarray(), out / f"{stem}.nc"))
            files[f"{stem}.png"] = str(save_figure(plot_replay(res), out / f"{stem}.png"))
    return files
