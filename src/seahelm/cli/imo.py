"""``seahelm imo SHIP``: check a ship (catalog name or ship file) against IMO Resolution
MSC.137(76).

Runs :func:`seahelm.analysis.imo.check.imo_check` (35° turning circles and 10° initial turning to
both sides, 10/10 and 20/20 zig-zags to both sides, the full-astern stopping test of a ship
with a propeller) and prints a table of the criteria with value, limit, margin (limit − value)
and pass/fail; stopping is "not evaluated" for a ship without a propeller, with the reason.
``--json`` prints exactly one JSON object (angles in degrees, lengths in ship lengths);
``--out DIR`` writes the runs and metrics as NetCDF, the report as JSON and the turning,
zig-zag (and stopping) figures as PNG. Exit codes: 0 the check ran (whether or not the ship
passes), 2 bad input, 1 other failure.

``--monte-carlo N`` checks N samples of the ship with uncertain coefficients instead
(:func:`seahelm.analysis.imo.probability.imo_probabilities`): the probability of passing each
criterion and the whole check with Wilson intervals, the samples that do not complete
excluded, counted and listed with their reason, and a table of the drawn parameters (name,
distribution, unit, mean, standard deviation, range); ``--out DIR`` writes
``imo-probabilities.nc`` (:mod:`seahelm.analysis.imo.ensemble`) and ``imo-probabilities.png``
(:func:`seahelm.plotting.imo_ensemble.plot_imo_ensemble`). A progress bar shows on a terminal. A ``kind = "imo"`` scenario with
``[batch.monte_carlo]`` is shown the same way by ``seahelm run`` (:func:`present_imo_ensemble`).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer
from rich.markup import escape
from rich.table import Table

from ..analysis.imo.ensemble import ENSEMBLE_FILE
from ..errors import ParameterError
from ._common import (
    ForceFlag,
    EXIT_NONCOMPLIANT,
    JsonFlag,
    _jsonable,
    console,
    handle_errors,
    output_dir,
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

__all__ = ["imo", "show_report", "show_ensemble", "present_imo_ensemble",
           "print_imo_probabilities"]


def _display(criterion: Any) -> dict[str, Any]:
    row = criterion.as_dict()
    if row["unit"] == "rad":
        for key in ("value", "limit", "margin"):
            row[key] = math.degrees(row[key])
        row["unit"] = "deg"
    return row


#: ``--uncertainty``'s default: the relative standard deviation of the default draws.
DEFAULT_UNCERTAINTY = 0.10


@handle_errors
def imo(
    model: Annotated[ShipName, typer.Argument(metavar="SHIP", help=SHIP_HELP)],
    speed: Speed = None,
    rps: Rps = None,
    dt: Dt = None,
    water_depth: Depth = None,
    monte_carlo: Annotated[Optional[int], typer.Option(
        "--monte-carlo", metavar="N", min=1, max=100_000, help=(
            "Check N ships with uncertain coefficients instead of one: the probability of "
            "passing each criterion (Wilson intervals), samples that do not complete excluded "
            "and counted. Default uncertainty: normal, --uncertainty of each linear "
            "derivative (Y_v, Y_r, N_v, N_r; Nomoto K, T). With --out, writes "
            "imo-probabilities.nc (every sample's values, draws and reasons) and "
            "imo-probabilities.png (each criterion's distribution and limit).")),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Seed of the Monte-Carlo draws.")]
    = 0,
    uncertainty: Annotated[Optional[float], typer.Option(
        "--uncertainty", show_default="0.10", help="Relative standard deviation of the "
        "default draws (with --monte-carlo, without --draws).")] = None,
    draws: Annotated[Optional[Path], typer.Option(
        "--draws", metavar="FILE.toml|FILE.csv", help=(
            "Your own draws: a TOML table [draws] of parameter = {distribution = \"normal\", "
            "mean = …, std = …} (normal, uniform, lognormal, truncnormal as in scenario "
            "files); or a CSV samples file (a column per vessel.params.<name>, a row per "
            "sample, e.g. `identify mmg --save-posterior`): sample i is row i, all rows "
            "without --monte-carlo.")),
    ] = None,
    force: ForceFlag = False,
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
    from ..analysis.imo.check import imo_check

    ship = ship_of(model, water_depth)
    check_speed_rps(ship, speed, rps)
    check_positive_opt("--dt", dt, "s")
    from_samples = draws is not None and draws.suffix.lower() == ".csv"
    if draws is not None and not from_samples and monte_carlo is None:
        raise ParameterError(f"`--draws` {draws}: draws from a TOML [draws] table need "
                             "`--monte-carlo N` (the number of samples); only a CSV samples "
                             "file is checked row by row without it")
    if uncertainty is not None and (monte_carlo is None or draws is not None):
        why = ("the draws come from `--draws`" if draws is not None
               else "it is the spread of `--monte-carlo`'s default draws")
        raise ParameterError(f"`--uncertainty` = {uncertainty!r} is used only with "
                             f"`--monte-carlo` and without `--draws` ({why}): drop it")
    if uncertainty is None:
        uncertainty = DEFAULT_UNCERTAINTY
    if monte_carlo is not None or from_samples:
        given = "--monte-carlo" if monte_carlo is not None else "--draws FILE.csv"
        if speed is not None or rps is not None:
            raise ParameterError(f"`{given}` runs every sample at the ship's test speed: "
                                 "drop `--speed`/`--rps`")
        if check:
            raise ParameterError(f"`--check` needs a pass or a fail; `{given}` gives "
                                 "probabilities: drop `--check`")
        reads = ship_reads(model) + (() if draws is None else (draws,))
        if out is not None:
            output_dir("--out", out, (ENSEMBLE_FILE, ENSEMBLE_FIGURE), reads=reads)
        if from_samples:
            _from_samples(ship, monte_carlo, draws, dt, json_out, out)
        else:
            _monte_carlo(ship, monte_carlo, seed, uncertainty, draws, dt, json_out, out)
        return
    check_out(out, "imo", ship_reads(model))
    report = imo_check(ship, speed=speed, rps=rps, dt=dt)
    show_report(report, out, json_out)
    if check and not report.passed:
        raise typer.Exit(EXIT_NONCOMPLIANT)


def _monte_carlo(ship: Any, n: int, seed: int, uncertainty: float, draws: Path | None,
                 dt: float | None, json_out: bool, out: Path | None) -> None:
    from ..analysis.imo.monte_carlo import imo_monte_carlo
    from ..analysis.imo.probability import MAX_UNCERTAINTY
    from ..analysis.imo.monte_carlo import SHARED_KEYS

    if not (math.isfinite(uncertainty) and 0 < uncertainty <= MAX_UNCERTAINTY):
        raise ParameterError(f"`--uncertainty` must be in (0, {MAX_UNCERTAINTY:g}] (the "
                             "relative standard deviation of the default draws), got "
                             f"{uncertainty!r}")
    dists = None if draws is None else _read_draws(draws)
    for key in dists or ():
        if f"vessel.params.{key}" in SHARED_KEYS:
            raise ParameterError(f"`--draws` [draws.{key}]: the samples of an IMO check share "
                                 "the ship's length, test speed and steering-gear limit (its "
                                 "criteria are in ship lengths and L/V): draw its other "
                                 "parameters")
    bar = _bar(n, json_out)
    try:
        ensemble = imo_monte_carlo(ship, n, seed=seed, draws=dists, uncertainty=uncertainty,
                                   dt=dt, progress=bar, source=str(draws))
    except ParameterError as exc:
        if dists is not None or exc.field in ("n", "uncertainty", "draws"):
            raise
        raise ParameterError(  # (a drawn coefficient the model cannot take)
            f"`--uncertainty` {uncertainty:g} drew a ship the model cannot take ({exc}); give "
            f"a smaller one (in (0, {MAX_UNCERTAINTY:g}]) or the draws (`--draws`)") from None
    finally:
        bar.close()
    show_ensemble(ensemble.probabilities, ensemble.metadata, ensemble.drawn, out, json_out,
                  ensemble.title)


def _bar(n: int | None, json_out: bool) -> Any:
    """The progress bar of an ensemble's check (on a terminal, after a second)."""
    from ._common import ProgressBar

    return ProgressBar(f"checking {n} sample(s)" if n else "checking the samples",
                       enabled=not json_out)


def _from_samples(ship: Any, n: int | None, path: Path, dt: float | None, json_out: bool,
                  out: Path | None) -> None:
    """``--draws FILE.csv``: the ships of a samples file's rows
    (:func:`seahelm.analysis.imo.monte_carlo.imo_of_samples`), checked as ``--monte-carlo``
    checks its draws."""
    from ..analysis.imo.monte_carlo import imo_of_samples
    from ..identification.samples_file import read_samples
    from ._common import input_file

    input_file("--draws", path)
    try:
        table = read_samples(path)
    except ParameterError as exc:
        raise ParameterError(f"`--draws` {exc}") from None
    if n is not None and n > table.n_samples:
        raise ParameterError(f"`--monte-carlo` {n}: {path} holds only {table.n_samples} "
                             f"sample{'' if table.n_samples == 1 else 's'}")
    bar = _bar(n or table.n_samples, json_out)
    try:
        ensemble = imo_of_samples(ship, table, n=n, dt=dt, progress=bar, source=str(path))
    except ParameterError as exc:
        if exc.field == "draws":  # (a column or a row of the file)
            raise ParameterError(f"`--draws` {path}: {exc.reason}") from None
        if exc.field and exc.field.startswith("vessel."):  # (its units)
            raise ParameterError(f"`--draws` {exc}") from None
        raise
    finally:
        bar.close()
    show_ensemble(ensemble.probabilities, ensemble.metadata, ensemble.drawn, out, json_out,
                  ensemble.title)


def present_imo_ensemble(job: Any, out: Path | None, as_json: bool, *,
                         reads: tuple[Path, ...] = ()) -> None:
    """Run an ``imo`` scenario with ``[batch.monte_carlo]`` and show it as ``seahelm imo
    --monte-carlo`` does: the probabilities table (or one JSON object) and, with ``out``,
    ``imo-probabilities.nc`` (:mod:`seahelm.analysis.imo.ensemble`).

    Parameters
    ----------
    job : ManeuverJob
        The scenario's manoeuvre (``kind = "imo"``, with Monte-Carlo samples).
    out : Path or None
        Directory of the file (None: no file).
    as_json : bool
        Print one JSON object instead of the table.
    reads : tuple of Path, optional
        The files the command read (the scenario), never written over.
    """
    import numpy as np

    if out is not None:
        output_dir("--out", out, (ENSEMBLE_FILE, ENSEMBLE_FIGURE), reads=reads)
    probs = job.run()
    n = job.n_samples
    described = job.draw_attrs()
    drawn = {k: (v, described[k]) for k, v in job.draws(np.arange(n)).items()}
    source = str(job.metadata.get("scenario_source", ""))
    meta = {**job.metadata, "scenario": job.title or source, "ship": job.ship.name,
            "samples": n, "seed": int(job.monte_carlo.seed), "draws": "scenario"}
    show_ensemble(probs, meta, drawn, out, as_json, job.title or (
        f"IMO MSC.137(76): {job.ship.name}, {n} Monte-Carlo samples "
        f"(seed {job.monte_carlo.seed})"))


def show_ensemble(probs: Any, meta: dict[str, Any], drawn: dict[str, Any], out: Path | None,
                  as_json: bool, title: str) -> None:
    """Write (``out``) and print the IMO check of an ensemble.

    Parameters
    ----------
    probs : ImoProbabilities
        The check, with every member's values.
    meta : dict
        What was checked (ship, samples, seed, draws, the scenario), printed in the JSON
        and stored as the file's attributes.
    drawn : dict
        Key path -> (values per member, attributes) of the drawn values.
    out : Path or None
        Directory of ``imo-probabilities.nc`` (None: no file).
    as_json : bool
        Print one JSON object instead of the table.
    title : str
        The table's title.
    """
    from ..analysis.imo.ensemble import ensemble_dataset

    payload = probs.as_dict()
    payload.update({k: v for k, v in meta.items() if k not in ("scenario_text", "title")})
    payload["excluded_samples"] = [{"sample": i, "reason": why}
                                   for i, why in enumerate(probs.reasons) if why]
    from ..analysis.imo.monte_carlo import drawn_statistics

    payload["drawn_parameters"] = drawn_statistics(drawn)
    if out is not None:
        from ..plotting.imo_ensemble import plot_imo_ensemble
        from ..plotting.save import save_figure
        from ..results import write_netcdf, write_together

        ds = ensemble_dataset(probs, draws=drawn, attrs={**meta, "title": title})
        with write_together():  # the file and its figure appear together or not
            payload["files"] = {"netcdf": str(write_netcdf(ds, out / ENSEMBLE_FILE)),
                                "plot": str(save_figure(plot_imo_ensemble(ds),
                                                        out / ENSEMBLE_FIGURE))}
    if as_json:
        print_json(payload)
        return
    print_imo_probabilities(payload, title)
    for kind, path in payload.get("files", {}).items():
        console.print(f"  {kind}: {escape(path)}", highlight=False)


def _read_draws(path: Path) -> dict[str, Any]:
    """``--draws FILE.toml``: :func:`seahelm.scenario.draws.read_draws`, its errors naming the
    option."""
    from ..scenario.draws import read_draws
    from ._common import input_file

    input_file("--draws", path)
    try:
        return read_draws(path)
    except ParameterError as exc:
        raise ParameterError(f"`--draws` {path}: {exc.reason}") from None


#: The figure of ``--monte-carlo --out DIR``: every criterion's distribution over the samples.
ENSEMBLE_FIGURE = "imo-probabilities.png"


#: Excluded samples listed with their reason (the JSON output and the file have all).
MAX_EXCLUDED_SHOWN = 10


def print_imo_probabilities(p: dict[str, Any], title: str) -> None:
    """The pass probabilities of an ensemble (:func:`~seahelm.analysis.imo.probability.
    imo_probabilities`), as a table and a line for the whole check with the count of the
    excluded samples, and the first of them with their reasons.

    Parameters
    ----------
    p : dict
        :meth:`~seahelm.analysis.imo.probability.ImoProbabilities.as_dict`, optionally with
        ``excluded_samples`` (``{"sample", "reason"}``) or ``excluded_by_reason`` (counts),
        and ``drawn_parameters`` (:func:`~seahelm.analysis.imo.monte_carlo.
        drawn_statistics`: printed as a second table).
    title : str
        The table's title.
    """
    level = 100 * p["confidence_level"]
    table = Table(title=escape(title), title_justify="left")
    table.add_column("criterion", overflow="fold")
    for col in ("side", "median", "limit", "P(pass)", f"{level:g} % interval"):
        table.add_column(col, no_wrap=True, justify="left" if col == "side" else "right")
    for r in p["criteria"]:
        table.add_row(escape(f"{r['ability']}: {r['criterion']}"), r["side"],
                      f"{r['median']:.3g} {r['unit']}", f"{r['limit']:.4g}",
                      f"{r['probability']:.3f}", f"{r['ci_low']:.3f} .. {r['ci_high']:.3f}")
    console.print(table)
    if p.get("drawn_parameters"):
        drawn = Table(title="drawn parameters (over the samples)", title_justify="left")
        for col in ("parameter", "distribution", "unit", "mean", "std", "min", "max"):
            drawn.add_column(col, no_wrap=True,
                             justify="right" if col in ("mean", "std", "min", "max") else "left")
        for r in p["drawn_parameters"]:
            drawn.add_row(escape(r["parameter"]), escape(r["distribution"]), escape(r["units"]),
                          *(f"{r[k]:.4g}" for k in ("mean", "std", "min", "max")))
        console.print(drawn)
    console.print(f"all evaluated criteria: P(pass) = {p['probability']:.3f} "
                  f"({p['ci_low']:.3f} .. {p['ci_high']:.3f}, Wilson) over {p['total']} "
                  f"sample(s); {p['excluded']} sample(s) excluded (manoeuvres not completed); "
                  f"{escape(p['note'])}", highlight=False)  # (wrapped between words)
    excluded = p.get("excluded_samples") or []
    for row in excluded[:MAX_EXCLUDED_SHOWN]:
        console.print(escape(f"  excluded: sample {row['sample']}: {row['reason']}"),
                      highlight=False)
    if len(excluded) > MAX_EXCLUDED_SHOWN:
        console.print(f"  ... {len(excluded) - MAX_EXCLUDED_SHOWN} more excluded sample(s) "
                      "(--json lists all)", highlight=False)
    for why, count in (p.get("excluded_by_reason") or {}).items():
        console.print(escape(f"  excluded: {count} sample(s): {why}"), highlight=False)


def show_report(report: Any, out: Path | None, as_json: bool, *, plot: bool = True) -> None:
    """Write (``out``) and print an :class:`~seahelm.analysis.imo.check.ImoReport`: the criteria
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
