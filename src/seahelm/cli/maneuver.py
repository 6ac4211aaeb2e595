"""``seahelm maneuver``: standard manoeuvres of a catalog ship (turning, zigzag, spiral, pullout,
stopping: :mod:`seahelm.cli.stopping`).

Each command runs one batch of :mod:`seahelm.analysis.maneuvers` (both sides by default) and
prints a rich table of the metrics, or with ``--json`` exactly one JSON object on stdout; with
``--out DIR`` it writes the runs and metrics as NetCDF and a PNG figure (atomically). Angles
are in degrees on the command line and in the output (keys ending ``_deg``), lengths in metres
and in ship lengths (``_L``), times in seconds. Exit codes: 0 success, 2 bad input (one line on
stderr naming the option, its unit and the value), 1 other failure.

``seahelm imo MODEL`` (:mod:`seahelm.cli.imo`) checks a ship against IMO MSC.137(76).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from .maneuver_output import _fmt, header, write_outputs
from ..ships.catalog import with_steering_gear
from ._batch_summary import (
    SUMMARY_RUNS,
    maneuver_statistics,
    print_statistics,
)
from ._common import (
    ForceFlag,
    JsonFlag,
    OneLineErrors,
    console,
    handle_errors,
    output_dir,
    print_json,
)

app = typer.Typer(
    cls=OneLineErrors,
    help="Standard manoeuvres: turning circle, zig-zag, spiral, pull-out (both sides), stopping.",
    no_args_is_help=True,
)

#: A ship on the command line: a catalog name or the path of a ship file (checked by
#: :func:`ship_of`, which lists the catalog ships with a steering gear on a typo).
ShipName = str
SideName = Literal["both", "starboard", "port"]

_SIDES: dict[str, Any] = {"both": (1, -1), "starboard": 1, "port": -1}
_SIDE_NAMES = {1: "starboard", -1: "port"}

#: Help of a ship option or argument: the choices, from the catalog (its files' names).
SHIP_HELP = ("Ship: a catalog ship with a steering gear "
             f"({', '.join(with_steering_gear())}) or the path of a ship file (*.toml; "
             "`seahelm ship show NAME --toml` writes one).")
Catalog = Annotated[ShipName, typer.Option("--ship", "--catalog", metavar="SHIP",
                                           help=SHIP_HELP)]
Speed = Annotated[float | None, typer.Option(
    "--speed", help=escape("Approach speed U0 [m/s] (default: the entry's test speed)."))]
Rps = Annotated[float | None, typer.Option(
    "--rps", help=escape("Instead of --speed: propeller rps of the approach [1/s] (MMG)."))]
Side = Annotated[SideName, typer.Option("--side", help="Turn to both sides or one.")]
#: Each manoeuvre's --t-final, its default said as the code makes it (analysis.maneuvers):
#: "estimated from the steady turn" was said of all three, and the pull-out's is 60 L/U0.
TurningTFinal = Annotated[float | None, typer.Option("--t-final", help=escape(
    "Duration [s] (default: the rudder's travel time + 1.3 x 360 deg / the slowest yaw rate "
    "of the batch's steady turns, solved before the runs; for a constant-speed model plus 3 "
    "x its yaw time constant T)."))]
ZigzagTFinal = Annotated[float | None, typer.Option("--t-final", help=escape(
    "Duration [s] (default: 4 rudder swings + 24 x the trigger angle / the slowest yaw rate "
    "of the steady turns at the rudder angle, solved before the runs; for a constant-speed "
    "model plus 6 x its yaw time constant T). A given one is checked: each trigger must be "
    "reachable in it at that yaw rate."))]
PullOutTFinal = Annotated[float | None, typer.Option("--t-final", help=escape(
    "Duration after the rudder order [s] (default: 60 L/U0, the longest of the batch)."))]
Dt = Annotated[float | None, typer.Option(
    "--dt", help=escape("Integration step [s] (default: min(L/(100 U0), servo lag), "
                        "rounded down to 1-2-5)."))]
Out = Annotated[Path | None, typer.Option(
    "--out", help="Write NetCDF (runs, metrics) and a PNG here.")]
Depth = Annotated[float | None, typer.Option(
    "--depth", help=escape("Water depth h [m] (> draught; default: the ship's, deep water for a "
                           "catalog ship): the MMG coefficients corrected for shallow water."),
    show_default=False)]


@app.callback()
def _main() -> None:
    """Standard manoeuvres of a catalog ship."""


# ------------------------------------------------------------------------------------------
# input checks in command-line units
# ------------------------------------------------------------------------------------------
def ship_of(ship: ShipName, water_depth: float | None = None) -> Any:
    """The :class:`~seahelm.ships.Ship` of a catalog name or ship file, with a steering gear,
    in water of depth ``water_depth`` [m] (``--depth``) when given.

    Raises
    ------
    ParameterError
        For an unknown name (listing the catalog ships with a steering gear), an invalid ship
        file (naming its key and unit), or a ship without a steering gear.
    """
    from ..analysis.maneuvers import maneuver_ship
    from ..ships import get_ship

    try:
        found = get_ship(ship)
    except ParameterError:
        raise
    except ValueError:
        raise ParameterError(
            f"unknown ship '{ship}'; catalog ships with a steering gear: "
            f"{', '.join(with_steering_gear())} (or the path of a ship file, *.toml)") from None
    if found.steering_gear is None:
        raise ParameterError(
            f"ship '{found.name}' has no steering gear (a ship file's [steering_gear]); "
            f"catalog ships with one: {', '.join(with_steering_gear())}")
    if water_depth is not None:
        found = found.at_depth(water_depth)
    try:
        return maneuver_ship(found)
    except ParameterError as exc:  # (about the ship the user named: said without a field)
        if exc.field != "ship":
            raise
        raise ParameterError(exc.reason.lstrip(": ")) from None


#: The lowest approach speed of a manoeuvre, as a fraction of the speed the ship's parameter set
#: was identified at: the MMG standard method is one for manoeuvring at moderate speed, not the
#: low-speed manoeuvring of berthing (Yasukawa & Yoshimura 2015, sec. 1); the KVLCC2 model
#: still gives its tactical diameter at 1/20 of its speed, but at 1/100 no steady turn is found
#: and at 1e-4 m/s both turns diverged after 18 s of work (exit 0). Above
#: ``SPEED_VALIDITY`` (1.5) times that speed a manoeuvre warns. A model made for low speeds
#: (``mmg-ls``, with its ``min_speed``) takes any speed above that.
LOWEST_SPEED_FRACTION = 0.1


def check_speed_rps(ship: Any, speed: float | None, rps: float | None) -> None:
    """``--speed`` > 0 and not below the model's range (:data:`LOWEST_SPEED_FRACTION`),
    ``--rps`` > 0 (and only for a ship with a propeller), not both."""
    if speed is not None and not (math.isfinite(speed) and speed > 0):
        raise ParameterError(f"`--speed` must be > 0 [m/s], got {speed!r}")
    design = ship.approach_speed
    low_speed_model = "min_speed" in ship.params.field_names()
    if speed is not None and math.isfinite(design) and not low_speed_model \
            and speed < LOWEST_SPEED_FRACTION * design:
        raise ParameterError(
            f"`--speed` = {speed:g} m/s is below the range of '{ship.name}''s model "
            f"{ship.model.name}: from {LOWEST_SPEED_FRACTION:g} x the speed its parameter set "
            f"was identified at ({design:.4g} m/s), {LOWEST_SPEED_FRACTION * design:.4g} m/s "
            "(a model for manoeuvring at moderate speed; above 1.5 x it warns)")
    if rps is not None:
        if not (math.isfinite(rps) and rps > 0):
            raise ParameterError(f"`--rps` must be > 0 [1/s], got {rps!r}")
        if not ship.has_propeller:
            raise ParameterError(
                f"`--rps`: '{ship.name}' (model {ship.model.name}) has no propeller input, "
                f"got {rps!r} [1/s]")
    if speed is not None and rps is not None:
        raise ParameterError(
            f"give `--speed` [m/s] or `--rps` [1/s], not both (got {speed!r} and {rps!r})")


def check_rudder_deg(ship: Any, name: str, value: float, *, allow_zero: bool = False) -> float:
    """A rudder angle in degrees within the steering gear's limit; returns radians."""
    limit = math.degrees(ship.max_rudder)
    ok = math.isfinite(value) and abs(value) <= limit + 1e-9 and (allow_zero or value > 0)
    if not ok:
        lo = "[0" if allow_zero else "(0"
        raise ParameterError(
            f"`{name}` must be in {lo}, {limit:g}] [deg] (steering gear limit of "
            f"'{ship.name}'), got {value!r}")
    return math.radians(value)


def check_positive_opt(name: str, value: float | None, unit: str) -> None:
    """An optional option that must be > 0 when given."""
    if value is not None and not (math.isfinite(value) and value > 0):
        what = "> 0" if math.isfinite(value) else "a finite number > 0"
        raise ParameterError(f"`{name}` must be {what} [{unit}], got {value!r}")


#: The files each command writes with --out (checked before anything runs).
OUT_FILES: dict[str, tuple[str, ...]] = {
    "turning": ("turning-circle-metrics.nc", "turning-circle-runs.nc", "turning.png"),
    "zigzag": ("zigzag-metrics.nc", "zigzag-runs.nc", "zigzag.png"),
    "pullout": ("pull-out-metrics.nc", "pull-out-runs.nc", "pullout.png"),
    "spiral": ("direct-spiral-metrics.nc", "direct-spiral-runs.nc",
               "reverse-spiral-metrics.nc", "spiral.png"),
    "stopping": ("stopping-metrics.nc", "stopping-runs.nc", "stopping.png"),
    "imo": ("turning-circle-metrics.nc", "turning-circle-runs.nc", "zigzag-metrics.nc",
            "zigzag-runs.nc", "imo-turning.png", "imo-zigzag.png", "imo-report.json",
            "stopping-metrics.nc", "stopping-runs.nc", "imo-stopping.png"),
}


def check_out(out: Path | None, kind: str, reads: tuple[Path, ...] = ()) -> None:
    """``--out``: a writable directory where none of the kind's files is a directory, a file
    the command reads (``reads``: a ship file, a scenario) or inside a store."""
    if out is not None:
        output_dir("--out", out, OUT_FILES[kind], reads=reads)


def ship_reads(ship: str) -> tuple[Path, ...]:
    """The ship file a command reads, if ``ship`` names one (a catalog name reads none)."""
    from ..ships.file_format import is_ship_path

    return (Path(ship),) if is_ship_path(ship) else ()


def rudder_or_default(ship: Any, rudder: float | None, default: float) -> float:
    """``--rudder`` [deg], or ``default`` capped at the ship's steering-gear limit."""
    return rudder if rudder is not None else min(default, math.degrees(ship.max_rudder))


def checked(catalog: ShipName, rudder: float | None, side: SideName, speed: float | None,
            rps: float | None, t_final: float | None, dt: float | None, *,
            default_rudder: float = 35.0, water_depth: float | None = None
            ) -> tuple[Any, float, Any]:
    """The options every manoeuvre takes, checked: (ship, rudder [rad], sides: +1/−1 or the
    pair). Without ``--rudder``, ``default_rudder`` [deg], or the steering gear's limit where
    that is smaller (a default is never refused)."""
    ship = ship_of(catalog, water_depth)
    delta = check_rudder_deg(ship, "--rudder", rudder_or_default(ship, rudder, default_rudder))
    sides = _SIDES[side]
    check_speed_rps(ship, speed, rps)
    check_positive_opt("--t-final", t_final, "s")
    check_positive_opt("--dt", dt, "s")
    return ship, delta, sides


# ------------------------------------------------------------------------------------------
# output
# ------------------------------------------------------------------------------------------
Field = tuple[str, str, Callable[[dict[str, Any]], Any]]


def _deg(key: str) -> Callable[[dict[str, Any]], Any]:
    return lambda row: math.degrees(row[key])


def _per_l(key: str) -> Callable[[dict[str, Any]], Any]:
    return lambda row: row[key] / row["length"]


def _label(row: dict[str, Any], batch_keys: Sequence[str]) -> str:
    parts = []
    for key in batch_keys:
        if key == "side":
            parts.append(_SIDE_NAMES[int(row["side"])])
        elif key == "pair":
            parts.append(f"{math.degrees(row['rudder']):g}/{math.degrees(row['trigger']):g}")
        elif key == "rudder":
            parts.append(f"{math.degrees(row['rudder']):g} deg")
        else:
            parts.append(f"{key} {row[key]}")
    return ", ".join(parts) or "run"


def display_rows(result: Any, fields: Sequence[Field]) -> list[dict[str, Any]]:
    """The metrics of every run in command-line units, with the run's coordinates."""
    from ..analysis.maneuvers import metrics_rows

    batch = list(result.metrics["complete"].dims)
    out = []
    for row in metrics_rows(result.metrics):
        shown: dict[str, Any] = {"run": _label(row, batch)}
        if "side" in row:
            shown["side"] = _SIDE_NAMES[int(row["side"])]
        if "rudder" in row:
            shown["rudder_deg"] = math.degrees(row["rudder"])
        if "trigger" in row:
            shown["heading_trigger_deg"] = math.degrees(row["trigger"])
        for key, _, get in fields:
            try:
                shown[key] = get(row)
            except KeyError:  # pragma: no cover - a field the result does not have
                continue
        for key, name in (("approach_speed_value", "approach_speed_mps"),
                          ("propeller_rps", "propeller_rps")):
            if isinstance(row.get(key), float) and math.isfinite(row[key]):
                shown[name] = row[key]
        if "ship" in batch:
            shown["ship"] = int(row["ship"])
        shown["complete"] = bool(row["complete"])
        shown["message"] = str(row["message"])
        out.append(shown)
    return out


def print_table(title: str, rows: list[dict[str, Any]], fields: Sequence[Field]) -> None:
    """Metrics down, runs across; messages under the table."""
    table = Table(title=escape(title), title_justify="left")
    table.add_column("metric")
    for row in rows:
        table.add_column(escape(row["run"]), justify="right")
    for key, label, _ in fields:
        if any(key in row for row in rows):
            table.add_row(escape(label), *(_fmt(row.get(key, math.nan)) for row in rows))
    console.print(table)
    for row in rows:
        if row["message"] != "ok":
            console.print(f"  {escape(row['run'])}: {escape(row['message'])}", highlight=False)


def finish(title: str, result: Any, payload: dict[str, Any], fields: Sequence[Field],
           plot: Callable[[Any], Any] | None, png: str, out: Path | None,
           as_json: bool, drawn: dict[str, np.ndarray] | None = None) -> None:
    """Write the files (``--out``; no figure if ``plot`` is None), then print the JSON object
    or the table (or the statistics of a big batch, with the values ``drawn`` per ship)."""
    if out is not None:
        payload["files"] = write_outputs(out, [result], None if plot is None else (
            lambda: plot(result)), png)
    emit(title, payload, display_rows(result, fields), fields, as_json, drawn)


def emit(title: str, payload: dict[str, Any], rows: list[dict[str, Any]],
         fields: Sequence[Field], as_json: bool,
         drawn: dict[str, np.ndarray] | None = None) -> None:
    """JSON (one object) or the table and the header lines; a batch of more than
    :data:`~seahelm.cli._batch_summary.SUMMARY_RUNS` runs as statistics per group of runs
    (with those of the values ``drawn`` per ship) and its notes counted."""
    payload = {**payload, "runs": rows}
    big = len(rows) > SUMMARY_RUNS
    labels = {key: label for key, label, _ in fields}
    field_keys = set(labels)
    labels.update(approach_speed_mps="approach speed [m/s]", propeller_rps="propeller [1/s]")
    if big:
        keys = [k for k in labels if any(isinstance(r.get(k), float) for r in rows)
                and (k in field_keys or len({r.get(k) for r in rows}) > 1)]
        payload["statistics"] = maneuver_statistics(rows, keys, drawn)
    if as_json:
        print_json(payload)
        return
    if big:
        print_statistics(title, payload["statistics"], rows, labels)
    else:
        print_table(title, rows, fields)
    extras = [f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
              for k, v in payload.items()
              if k not in ("runs", "files", "maneuver", "statistics")]
    console.print(escape(", ".join(extras)), highlight=False)
    for kind, path in payload.get("files", {}).items():
        console.print(f"  {kind}: {escape(path)}", highlight=False)


# ------------------------------------------------------------------------------------------
# commands
# ------------------------------------------------------------------------------------------
TURNING_FIELDS: tuple[Field, ...] = (
    ("advance_m", "advance [m]", lambda r: r["advance"]),
    ("advance_L", "advance [L]", _per_l("advance")),
    ("transfer_m", "transfer [m]", lambda r: r["transfer"]),
    ("tactical_diameter_m", "tactical diameter [m]", lambda r: r["tactical_diameter"]),
    ("tactical_diameter_L", "tactical diameter [L]", _per_l("tactical_diameter")),
    ("time_90_s", "time to 90° [s]", lambda r: r["time_90"]),
    ("time_180_s", "time to 180° [s]", lambda r: r["time_180"]),
    ("time_10_s", "time to 10° [s]", lambda r: r["time_10"]),
    ("distance_10_L", "distance to 10° [L]", _per_l("distance_10")),
    ("steady_radius_m", "steady turning radius [m]", lambda r: r["steady_radius"]),
    ("steady_radius_L", "steady turning radius [L]", _per_l("steady_radius")),
    ("steady_speed_mps", "steady speed [m/s]", lambda r: r["steady_speed"]),
    ("speed_loss_pct", "speed loss [%]", lambda r: 100.0 * r["speed_loss"]),
    ("drift_angle_deg", "steady drift angle [deg]", _deg("steady_drift_angle")),
    ("yaw_rate_degps", "steady yaw rate [deg/s]", _deg("steady_yaw_rate")),
    ("steady", "steady at the end", lambda r: bool(r["steady"])),
)
#: Of a model with roll (:func:`seahelm.analysis.equilibria.heel.heel_metrics`), after
#: TURNING_FIELDS.
HEEL_FIELDS: tuple[Field, ...] = (
    ("max_heel_deg", "maximum heel [deg] (+ starboard down)", _deg("max_heel_angle")),
    ("steady_heel_deg", "steady heel [deg] (+ starboard down)", _deg("steady_heel_angle")),
)


def turning_fields(result: Any) -> tuple[Field, ...]:
    """The rows of a turning circle's table: with the heel's for a model with roll."""
    return TURNING_FIELDS + (HEEL_FIELDS if "max_heel_angle" in result.metrics else ())


@app.command("turning")
@handle_errors
def turning_cmd(
    catalog: Catalog = "kvlcc2-l7",
    rudder: Annotated[float | None, typer.Option("--rudder", help=escape(
        "Rudder angle [deg], in (0, steering gear limit] (default 35 deg, or the gear's limit if smaller)."))] = None,
    side: Side = "both",
    speed: Speed = None,
    rps: Rps = None,
    t_final: TurningTFinal = None,
    dt: Dt = None,
    water_depth: Depth = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    out: Out = None,
) -> None:
    """Turning circle: advance, transfer, tactical diameter, times, steady turn."""
    from ..analysis.maneuvers import turning_circle
    from ..plotting.maneuvers import plot_turning

    ship, delta, sides = checked(catalog, rudder, side, speed, rps, t_final, dt,
                                 default_rudder=35.0, water_depth=water_depth)
    rudder = rudder_or_default(ship, rudder, 35.0)
    check_out(out, "turning", ship_reads(catalog))
    result = turning_circle(ship, delta, sides=sides, speed=speed, rps=rps, t_final=t_final,
                            dt=dt)
    finish(f"Turning circle, {ship.name}, {rudder:g} deg rudder", result, header(result),
           turning_fields(result), plot_turning, "turning.png", out, json_out)


def _overshoot(k: int) -> Callable[[dict[str, Any]], Any]:
    return lambda r: math.degrees(r[f"overshoot_{k}"])


ZIGZAG_FIELDS: tuple[Field, ...] = (
    *((f"overshoot_{k}_deg", f"{('first', 'second', 'third')[k - 1]} overshoot [deg]",
       _overshoot(k)) for k in (1, 2, 3)),
    *((f"overshoot_time_{k}_s", f"time of overshoot {k} [s]",
       (lambda k: lambda r: r[f"overshoot_time_{k}"])(k)) for k in (1, 2, 3)),
    ("initial_turning_time_s", "initial turning time [s]", lambda r: r["initial_turning_time"]),
    ("time_to_check_yaw_s", "time to check yaw [s]", lambda r: r["time_to_check_yaw"]),
    ("period_s", "period [s]", lambda r: r["period"]),
)


@app.command("zigzag")
@handle_errors
def zigzag_cmd(
    catalog: Catalog = "kvlcc2-l7",
    rudder: Annotated[float | None, typer.Option("--rudder", help=escape(
        "Rudder angle δ [deg], in (0, steering gear limit] (default 10 deg, or the gear's limit if smaller)."))] = None,
    heading: Annotated[float | None, typer.Option("--heading", help=escape(
        "Heading trigger ψ [deg], in (0, 180) (default: equal to --rudder)."))] = None,
    side: Annotated[SideName, typer.Option(
        "--side", help="First execute: to both sides or one.")] = "both",
    speed: Speed = None,
    rps: Rps = None,
    t_final: ZigzagTFinal = None,
    dt: Dt = None,
    water_depth: Depth = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    out: Out = None,
) -> None:
    """Zig-zag δ/ψ: overshoots, initial turning time, time to check yaw, period."""
    from ..analysis.maneuvers import zigzag
    from ..plotting.maneuvers import plot_zigzag

    ship, delta, sides = checked(catalog, rudder, side, speed, rps, t_final, dt,
                                 default_rudder=10.0, water_depth=water_depth)
    rudder = rudder_or_default(ship, rudder, 10.0)
    check_out(out, "zigzag", ship_reads(catalog))
    psi = rudder if heading is None else heading
    if not (math.isfinite(psi) and 0 < psi < 180):
        raise ParameterError(f"`--heading` must be in (0, 180) [deg], got {psi!r}")
    result = zigzag(ship, delta, math.radians(psi), sides=sides, speed=speed, rps=rps,
                    t_final=t_final, dt=dt)
    payload = header(result)
    payload.update(rudder_deg=rudder, heading_trigger_deg=psi)
    finish(f"Zig-zag {rudder:g}/{psi:g}, {ship.name}", result, payload, ZIGZAG_FIELDS,
           plot_zigzag, "zigzag.png", out, json_out)


PULLOUT_FIELDS: tuple[Field, ...] = (
    ("initial_yaw_rate_degps", "steady yaw rate before [deg/s]", _deg("initial_yaw_rate")),
    ("residual_yaw_rate_degps", "residual yaw rate [deg/s]", _deg("residual_yaw_rate")),
    ("half_time_s", "time to half the yaw rate [s]", lambda r: r["half_time"]),
    ("settled", "settled", lambda r: bool(r["settled"])),
)


@app.command("pullout")
@handle_errors
def pullout_cmd(
    catalog: Catalog = "kvlcc2-l7",
    rudder: Annotated[float | None, typer.Option("--rudder", help=escape(
        "Rudder angle of the steady turn [deg], in (0, steering gear limit] (default 20 deg, or the gear's limit if smaller)."))] = None,
    side: Side = "both",
    speed: Speed = None,
    rps: Rps = None,
    t_final: PullOutTFinal = None,
    dt: Dt = None,
    water_depth: Depth = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    out: Out = None,
) -> None:
    """Pull-out: rudder to zero after a steady turn; residual yaw rates to both sides."""
    from ..analysis.maneuvers import pull_out
    from ..plotting.maneuvers import plot_pullout

    ship, delta, sides = checked(catalog, rudder, side, speed, rps, t_final, dt,
                                 default_rudder=20.0, water_depth=water_depth)
    rudder = rudder_or_default(ship, rudder, 20.0)
    check_out(out, "pullout", ship_reads(catalog))
    result = pull_out(ship, delta, sides=sides, speed=speed, rps=rps, t_final=t_final, dt=dt)
    payload = header(result)
    if "residual_gap" in result.metrics:
        payload["residual_gap_degps"] = math.degrees(float(result.metrics["residual_gap"]))
    finish(f"Pull-out from {rudder:g} deg, {ship.name}", result, payload, PULLOUT_FIELDS,
           plot_pullout, "pullout.png", out, json_out)


@app.command("spiral")
@handle_errors
def spiral_cmd(
    catalog: Catalog = "kvlcc2-l7",
    max_rudder: Annotated[float, typer.Option("--max-rudder", help=escape(
        "Largest rudder angle of the spirals [deg]: the direct program is 20, 15, 10, 5, 3, "
        "2, 1, 0.5, 0 deg scaled to it, down to port and back; the reverse spiral spans the "
        "yaw rates of ±this angle."))] = 20.0,
    hold: Annotated[float | None, typer.Option("--hold", help=escape(
        "Time each rudder angle of the direct spiral is held [s] (default 50 L/U0)."))] = None,
    speed: Speed = None,
    rps: Rps = None,
    dt: Dt = None,
    water_depth: Depth = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    out: Out = None,
) -> None:
    """Direct (simulated) and reverse (equilibria) spiral: r–δ curve and loop width."""
    from ..analysis.maneuvers import spirals

    ship = ship_of(catalog, water_depth)
    top = check_rudder_deg(ship, "--max-rudder", max_rudder)
    check_speed_rps(ship, speed, rps)
    check_positive_opt("--hold", hold, "s")
    check_positive_opt("--dt", dt, "s")
    check_out(out, "spiral", ship_reads(catalog))
    direct, reverse = spirals(ship, top, speed=speed, rps=rps, hold=hold, dt=dt)
    from .spiral_output import show_spirals

    show_spirals(f"Direct spiral, {ship.name}", direct, reverse, out, json_out)
