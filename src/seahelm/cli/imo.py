"""``seahelm imo SHIP``: check a ship (catalog name or ship file) against IMO Resolution MSC.137(76).

Runs :func:`seahelm.analysis.imo.imo_check` (35° turning circles and 10° initial turning to
both sides, 10/10 and 20/20 zig-zags to both sides, the full-astern stopping test of a ship
with a propeller) and prints a table of the criteria with value, limit, margin (limit − value)
and pass/fail; stopping is "not evaluated" for a ship without a propeller, with the reason.
``--json`` prints exactly one JSON object (angles in degrees, lengths in ship lengths);
``--out DIR`` writes the runs and metrics as NetCDF, the report as JSON and the turning,
zig-zag (and stopping) figures as PNG. Exit codes: 0 the check ran (whether or not the ship
passes), 2 bad input, 1 other failure.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from ._common import (
    EXIT_NONCOMPLIANT,
    JsonFlag,
    _jsonable,
    console,
    handle_errors,
    print_json,
)
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
    monte_carlo: Annotated[int, typer.Option(
        "--monte-carlo", metavar="N", min=0, max=100_000, help=(
            "Check N ships with uncertain coefficients instead of one: the probability of "
            "passing each criterion (Wilson intervals). Default uncertainty: normal, "
            "--uncertainty of each linear derivative (Y_v, Y_r, N_v, N_r; Nomoto K, T).")),
    ] = 0,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Seed of the Monte-Carlo draws.")]
    = 0,
    uncertainty: Annotated[float, typer.Option(
        "--uncertainty", help="Relative standard deviation of the default draws.")] = 0.10,
    draws: Annotated[Optional[Path], typer.Option(
        "--draws", metavar="FILE.toml", help=(
            "Your own draws: a TOML table [draws] of parameter = {distribution = \"normal\", "
            "mean = …, std = …} (normal, uniform, lognormal, truncnormal as in scenario "
            "files).")),
    ] = None,
    json_out: JsonFlag = False,
    out: Out = None,
    check: Annotated[bool, typer.Option("--check", help=(
        "Exit with code 4 when the ship fails an evaluated criterion (after printing the "
        "report); without it the exit code is 0 whatever the verdict."))] = False,
) -> None:
    """Check a ship against IMO MSC.137(76): turning, initial turning, zig-zags, stopping.

    Exit codes: 0 the check ran (the verdict is in the report, "passed" in the JSON); with
    --check, 4 when the ship fails a criterion; 2 bad input; 1 any other failure.
    """
    from ..analysis.imo import imo_check

    ship = ship_of(model, water_depth)
    check_speed_rps(ship, speed, rps)
    check_positive_opt("--dt", dt, "s")
    if monte_carlo:
        if speed is not None or rps is not None or out is not None:
            raise ParameterError("`--monte-carlo` runs at the ship's test speed and writes no "
                                 "files: drop `--speed`/`--rps`/`--out`")
        if check:
            raise ParameterError("`--check` needs a pass or a fail; `--monte-carlo` gives "
                                 "probabilities: drop `--check`")
        _monte_carlo(ship, monte_carlo, seed, uncertainty, draws, dt, json_out)
        return
    check_out(out, "imo", ship_reads(model))
    report = imo_check(ship, speed=speed, rps=rps, dt=dt)
    show_report(report, out, json_out)
    if check and not report.passed:
        raise typer.Exit(EXIT_NONCOMPLIANT)


def _monte_carlo(ship: Any, n: int, seed: int, uncertainty: float, draws: Path | None,
                 dt: float | None, json_out: bool) -> None:
    from ..analysis.imo_probability import imo_probabilities, monte_carlo_ships

    if not (math.isfinite(uncertainty) and uncertainty > 0):
        raise ParameterError(f"`--uncertainty` must be > 0, got {uncertainty!r}")
    dists = None if draws is None else _read_draws(draws)
    ships = monte_carlo_ships(ship, n, seed=seed, draws=dists, uncertainty=uncertainty)
    payload = imo_probabilities(ships, dt=dt).as_dict()
    payload.update(ship=ship.name, samples=n, seed=seed,
                   draws="default" if draws is None else str(draws),
                   uncertainty=uncertainty if draws is None else None)
    if json_out:
        print_json(payload)
        return
    print_imo_probabilities(payload, f"IMO MSC.137(76): {ship.name}, {n} Monte-Carlo "
                                     f"samples (seed {seed})")


def _read_draws(path: Path) -> dict[str, Any]:
    """The ``[draws]`` of a TOML file as sampling distributions (names, units checked later
    against the ship's parameters)."""
    import tomllib

    from pydantic import ValidationError

    from ..numerics.sampling import get_distribution
    from ..scenario.schema import Distribution
    from ._common import input_file

    input_file("--draws", path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError(f"`--draws` {path}: not a TOML file ({exc})") from None
    table = data.get("draws")
    if not isinstance(table, dict) or not table:
        raise ParameterError(f"`--draws` {path}: needs a table [draws] of parameter = "
                             "{distribution = ..., ...}")
    out = {}
    for key, spec in table.items():
        try:
            d = Distribution.model_validate(spec)
        except ValidationError as exc:
            why = "; ".join(e["msg"] for e in exc.errors())
            raise ParameterError(f"`--draws` {path}: [draws.{key}] {why}") from None
        params = {k: getattr(d, k) for k in ("mean", "std", "low", "high")
                  if getattr(d, k) is not None}
        out[key] = get_distribution(d.distribution, **params)
    return out


def print_imo_probabilities(p: dict[str, Any], title: str) -> None:
    """The pass probabilities of an ensemble (:func:`~seahelm.analysis.imo_probability.
    imo_probabilities`), as a table and a line for the whole check."""
    level = 100 * p["confidence_level"]
    table = Table("criterion", "side", "median", "limit", "P(pass)", f"{level:g} % interval",
                  title=escape(title), title_justify="left")
    for r in p["criteria"]:
        table.add_row(escape(f"{r['ability']}: {r['criterion']}"), r["side"],
                      f"{r['median']:.3g} {r['unit']}", f"{r['limit']:.4g}",
                      f"{r['probability']:.3f}", f"{r['ci_low']:.3f} .. {r['ci_high']:.3f}")
    console.print(table)
    console.print(f"all evaluated criteria: P(pass) = {p['probability']:.3f} "
                  f"({p['ci_low']:.3f} .. {p['ci_high']:.3f}, Wilson); {p['excluded']} "
                  f"incomplete run(s) excluded; {p['note']}", highlight=False, soft_wrap=True)


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
    from ..plotting.maneuvers import plot_stopping, plot_turning, plot_zigzag
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
    if report.stopping is not None:
        stop = write_outputs(out, [report.stopping], (lambda: plot_stopping(report.stopping))
                             if plot else None, "imo-stopping.png")
        if plot:
            stop["plot_stopping"] = stop.pop("plot")
        files.update(stop)
    text = json.dumps(_jsonable({k: v for k, v in payload.items() if k != "files"}), indent=2,
                      allow_nan=False)
    files["report"] = str(atomic_write(out / "imo-report.json",
                                       lambda tmp: Path(tmp).write_text(text + "\n")))
    return files
