"""``seahelm identify``: identification of steering-model coefficients from turns.

``seahelm identify steady-turn FILE.csv`` fits the reduced steady-turn model of Romanov &
Chirkova, eq. (4) a ω² + b ω + α(1 + c ω) = 0, to a CSV file holding either a time series
(columns ``time``, ``rudder_angle``, ``yaw_rate``; the steady segments are extracted
automatically) or already-steady points (columns ``rudder_angle``, ``yaw_rate``). Mounted by the
main command as ``seahelm identify``; usable on its own as the typer app :data:`app`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Literal, Optional

import numpy as np
import typer
from rich.markup import escape

from ..identification.reduced.forms import REDUCED_FORMS
from ._common import (
    ForceFlag,
    JsonFlag,
    OneLineErrors,
    console,
    handle_errors,
    input_file,
    print_json,
)
from .identify_limits import check_bootstrap, check_record_count

app = typer.Typer(
    cls=OneLineErrors,
    help="Identify steering-model coefficients from recorded turns (Romanov & Chirkova: "
    "reduced steady-turn model a·ω² + b·ω + α(1 + c·ω) = 0).",
    no_args_is_help=True,
)

_UNITS = {"a": "s²/rad", "b": "s", "c": "s/rad", "d": "1/rad"}
#: Most posterior ships or samples drawn (as `seahelm imo --monte-carlo`; 10^12 was a
#: MemoryError, exit 1).
MAX_POSTERIOR = 100_000

#: The keys of :data:`~seahelm.identification.reduced.fitting.FIT_METHODS`, spelled out so that the
#: command line does not import the fitting code (numba, scipy; tests/test_cli_style.py checks
#: that they agree); those of :data:`~seahelm.identification.reduced.forms.REDUCED_FORMS` from
#: the registry (a light module).
FitMethod = Literal["lsq", "robust", "brute"]
FormName = Literal[tuple(REDUCED_FORMS)]  # type: ignore[valid-type]
AngleUnit = Literal["deg", "rad"]
PosteriorName = Literal["laplace", "mcmc"]


@app.callback()
def _main() -> None:
    """Identification of steering-model coefficients."""


@app.command("steady-turn")
@handle_errors
def steady_turn(
    file: Annotated[Path, typer.Argument(
        metavar="FILE.csv", help="Time series (time, rudder_angle, yaw_rate) or steady "
        "points (rudder_angle, yaw_rate).")],
    angles: Annotated[AngleUnit, typer.Option(
        "--angles", help="Units of rudder_angle [deg|rad] and yaw_rate [deg/s|rad/s].")] = "deg",
    method: Annotated[FitMethod, typer.Option(
        "--method", help="Linear least squares, robust soft-L1, or the paper's "
                         "brute-force search (eq. (5)).")] = "lsq",
    form: Annotated[FormName, typer.Option(
        "--form", help="Equation form: eq. (4), with the α² term of the exact "
                       "elimination, or made odd for turns to both sides.")] = "paper",
    rudder_tolerance: Annotated[float, typer.Option(
        "--rudder-tolerance",
        help="Constant rudder: deviation allowed, in --angles units.")] = 0.2,
    yaw_rate_tolerance: Annotated[Optional[float], typer.Option(
        "--yaw-rate-tolerance",
        help="Settled yaw rate: band half-width, in --angles units per second "
             "(default 3e-5 rad/s).")] = None,
    min_duration: Annotated[float, typer.Option(
        "--min-duration", help="Minimum settled duration [s].")] = 60.0,
    smoothing: Annotated[float | None, typer.Option(
        "--smoothing", help="Moving average [s] for the settling test (default 20).")] = None,
    json_out: JsonFlag = False,
) -> None:
    """Fit a, b, c of the reduced steady-turn model to turns recorded in a CSV file.

    Coefficients are reported in radian units (a [s²/rad], b [s], c [s/rad]) whatever --angles;
    the steady points in the log's units (--angles), as the JSON output's units block says.
    """
    from ..errors import ParameterError
    from ..identification.reduced.fitting import fit_steady_turns
    from ..identification.reduced.segments import extract_steady_segments
    from ..identification.records import read_turn_log

    scale = math.pi / 180.0 if angles == "deg" else 1.0
    input_file("FILE", file)
    cols = read_turn_log(file)
    missing = [c for c in ("rudder_angle", "yaw_rate") if c not in cols]
    if missing:
        raise ParameterError(
            f"{file}: missing column(s) {', '.join(missing)}; found {', '.join(cols) or 'none'} "
            "(need time, rudder_angle, yaw_rate or rudder_angle, yaw_rate)"
        )
    rudder = cols["rudder_angle"] * scale
    yaw = cols["yaw_rate"] * scale
    largest = float(np.nanmax(np.abs(cols["rudder_angle"]))) if cols["rudder_angle"].size else 0.0
    if angles == "rad" and largest > math.pi / 2:  # no rudder turns beyond 90 deg
        raise ParameterError(
            f"{file}: column `rudder_angle` reaches {largest:g}, read as radians "
            f"(`--angles rad`) that is {math.degrees(largest):.4g} deg, beyond any rudder; "
            "the log is in degrees? (`--angles deg`)")
    for name, arr in (("rudder_angle", rudder), ("yaw_rate", yaw)) + (
            (("time", cols["time"]),) if "time" in cols else ()):
        if not np.all(np.isfinite(arr)):
            bad = np.flatnonzero(~np.isfinite(arr))
            raise ParameterError(
                f"{file}: column `{name}` has NaN/inf on data row(s) {(bad + 1)[:6].tolist()}"
            )
    out: dict[str, Any] = {"file": str(file), "input": "points"}
    segments = None
    if "time" in cols:
        span = float(cols["time"][-1] - cols["time"][0]) if cols["time"].size else 0.0
        if smoothing is not None and smoothing > span:  # (the default is never an error)
            raise ParameterError(f"`--smoothing` = {smoothing:g} s is longer than the whole log "
                                 f"({span:g} s of {file})")
        seg_kw: dict[str, Any] = dict(rudder_tolerance=rudder_tolerance * scale,
                                      min_duration=min_duration,
                                      smoothing=20.0 if smoothing is None else smoothing)
        if yaw_rate_tolerance is not None:
            seg_kw["yaw_rate_tolerance"] = yaw_rate_tolerance * scale
        segments = extract_steady_segments(cols["time"], rudder, yaw, **seg_kw)
        rudder, yaw = segments.rudder_angle, segments.yaw_rate
        out["input"] = "time series"
        if len(segments) < 3:
            raise ParameterError(
                f"{file}: found {len(segments)} steady segment(s), need at least 3 distinct "
                "steady points (hold the rudder longer, or relax --yaw-rate-tolerance / "
                "--min-duration)"
            )
    try:
        fit = fit_steady_turns(yaw, rudder, method=method, form=form)
    except np.linalg.LinAlgError as exc:  # (numpy's words name no cause a user can act on)
        raise ParameterError(
            f"{file}: the fit failed: the steady points do not determine the coefficients of "
            f"form {form!r} ({exc}); give turns at more distinct rudder angles, to both "
            "sides") from None
    summary = fit.to_dict()
    out.update(summary)
    # the unit of every number below: the coefficients and residual in radians, the points
    # and segments in the log's own --angles
    out["units"] = {n: _UNITS[n] for n in fit.form.names}
    out["units"].update(residual_rms="rad", rudder_angle=angles, yaw_rate=f"{angles}/s")
    if segments is not None:
        out["units"].update(start_time="s", end_time="s")
    out["points"] = [
        {"rudder_angle": float(a / scale), "yaw_rate": float(w / scale)}
        for a, w in zip(fit.rudder_angle, fit.yaw_rate)
    ]
    if segments is not None:
        out["segments"] = [
            {"start_time": float(s0), "end_time": float(s1), "rudder_angle": float(a / scale),
             "yaw_rate": float(w / scale), "samples": int(n)}
            for s0, s1, a, w, n in zip(segments.start_time, segments.end_time,
                                       segments.rudder_angle, segments.yaw_rate,
                                       segments.n_samples)
        ]
    out["angles"] = angles
    if json_out:
        print_json(out)
        return
    from rich.table import Table

    console.print(f"[bold]{file}[/]: {out['input']}, {fit.points_used} steady points, "
                  f"method {method}, form {fit.form.name} ({fit.form.description})")
    table = Table("coefficient", "value", "std. error", "unit")
    for n, v, se in zip(fit.form.names, fit.coef, fit.stderr):
        table.add_row(n, f"{v:.6g}", "—" if not np.isfinite(se) else f"{se:.3g}", _UNITS[n])
    console.print(table)
    console.print(f"residual rms {fit.residual_rms:.3g} rad, condition number "
                  f"{fit.condition_number:.3g} (column-scaled {fit.condition_number_scaled:.3g})")


@app.command("nomoto")
@handle_errors
def nomoto(
    files: Annotated[list[Path], typer.Argument(
        metavar="LOG...", help="Records: CSV files (time, rudder_angle, heading and/or "
        "yaw_rate, ...) or seahelm NetCDF results; several are fitted together.")],
    order: Annotated[int, typer.Option("--order", help="Nomoto's first or second order.",
                                       min=1, max=2)] = 1,
    angles: Annotated[AngleUnit, typer.Option(
        "--angles", help="Units of the CSV angles [deg|rad] and rates [deg/s|rad/s].")] = "deg",
    bootstrap: Annotated[int, typer.Option(
        "--bootstrap", help="Moving-block bootstrap refits for percentile intervals (0: "
        "none; at most 10000, each a whole fit).", min=0)] = 0,
    seed: Annotated[Optional[int], typer.Option("--seed", help="Seed of the bootstrap.")] = None,
    level: Annotated[float, typer.Option("--level", help="Confidence level.")] = 0.95,
    speed: Annotated[Optional[float], typer.Option(
        "--speed", help="Ship speed U of the records [m/s] (for --out; default: the mean "
        "surge speed of the records where logged).")] = None,
    length: Annotated[Optional[float], typer.Option(
        "--length", help="Ship length L [m] (for --out).")] = None,
    name: Annotated[Optional[str], typer.Option("--name", help="Ship name (for --out).")] = None,
    max_rudder: Annotated[float, typer.Option(
        "--max-rudder", help="Steering-gear limit [deg] (for --out).")] = 35.0,
    rudder_rate: Annotated[float, typer.Option(
        "--rudder-rate", help=escape("Steering-gear rate [deg/s] (for --out; IMO's minimum, "
                                     "65° in 28 s).  [default: 2.32]"),
        show_default=False)] = 65.0 / 28.0,
    out: Annotated[Optional[Path], typer.Option(
        "--out", "-o", metavar="SHIP.toml", help="Write a ship file of the identified model "
        "(values, intervals, covariance in its provenance).")] = None,
    plot: Annotated[Optional[Path], typer.Option(
        "--plot", metavar="FIT.png", help="Draw measured and fitted output and the residuals.")]
    = None,
    imo: Annotated[int, typer.Option(
        "--imo", metavar="N", help="Draw N ships from the posterior and give the probability of "
        "passing each IMO criterion (needs --speed, --length; 0: no).", min=0,
        max=MAX_POSTERIOR)] = 0,
    posterior: Annotated[PosteriorName, typer.Option(
        "--posterior", help="Posterior of --imo: the Laplace Gaussian or MCMC (emcee, "
        "the extra seahelm[mcmc]).")] = "laplace",
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Identify Nomoto K, T (or K, T1, T2, T3) and the rudder offset from manoeuvre records."""
    from ..identification.nomoto_fit import fit_nomoto
    from ..identification.records import read_records
    from ..errors import ParameterError
    from ._common import output_file

    from .identify_mmg_ls import expand_logs, identify_mmg_ls, parse_free

    files = expand_logs(files)
    for f in files:
        input_file("LOG", f)
    if not 0.0 < level < 1.0:
        raise ParameterError(f"`--level` must be in (0, 1), got {level!r}")
    for opt, value in (("--speed", speed), ("--length", length)):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ParameterError(f"`{opt}` must be > 0, got {value!r}")
    if not (math.isfinite(max_rudder) and 0 < max_rudder <= 90):
        raise ParameterError(f"`--max-rudder` must be in (0, 90] [deg], got {max_rudder!r}")
    if not (math.isfinite(rudder_rate) and rudder_rate > 0):
        raise ParameterError(f"`--rudder-rate` must be > 0 [deg/s], got {rudder_rate!r}")
    if out is not None:
        output_file("--out", out, "toml", reads=tuple(files), force=force)
    if plot is not None:
        output_file("--plot", plot, "figure", reads=tuple(files), force=force)
        if out is not None and plot.resolve() == out.resolve():
            raise ParameterError("`--plot` and `--out` are the same file")
    check_bootstrap(bootstrap)
    records = read_records(files, angles=angles)
    check_record_count(records, order)
    fit = fit_nomoto(records, order, bootstrap=bootstrap, seed=seed)
    payload = fit.as_dict(level)
    boot = fit.bootstrap_intervals(level)
    if boot is not None:
        for row, (lo, hi) in zip(payload["parameters"], boot):
            row["bootstrap_low"], row["bootstrap_high"] = float(lo), float(hi)
    if out is not None:
        payload["ship_file"] = str(_write_ship(fit, records, out, speed, length, name,
                                               max_rudder, rudder_rate, level))
    if plot is not None:
        from ..plotting.identification import plot_nomoto_fit

        payload["plot"] = str(plot_nomoto_fit(fit, records, plot))
    if imo:
        payload["imo"] = _imo_given_fit(fit, records, imo, posterior, seed, speed, length,
                                        max_rudder, rudder_rate, level, json_out)
    if json_out:
        print_json(payload)
        return
    _print_nomoto(fit, payload, level)
    if imo:
        _print_imo_given_fit(payload["imo"])


def _imo_given_fit(fit: Any, records: Any, n: int, posterior: str, seed: int | None,
                   speed: float | None, length: float | None, max_rudder: float,
                   rudder_rate: float, level: float, json_out: bool) -> dict[str, Any]:
    """``identify nomoto --imo N``: :func:`seahelm.analysis.imo.given_fit.
    imo_given_nomoto_fit`, its errors in the command's words."""
    from ..analysis.imo.given_fit import imo_given_nomoto_fit
    from ..errors import ParameterError

    if speed is None or length is None:
        raise ParameterError("`--imo` needs `--speed` and `--length` (the ship's U [m/s] and "
                             "L [m]: the IMO limits are in ship lengths and L/V)")
    bar = _bar(n, json_out)
    try:
        return imo_given_nomoto_fit(fit, records, n, speed=speed, length=length,
                                    method=posterior, seed=seed,
                                    max_rudder=math.radians(max_rudder),
                                    rudder_rate=math.radians(rudder_rate), level=level,
                                    progress=bar)
    except ParameterError as exc:
        if exc.field != "fit":
            raise
        raise ParameterError(f"`--imo`: {exc.reason} (fit the other --order)") from None
    finally:
        bar.close()


def _bar(n: int, json_out: bool) -> Any:
    """The progress bar of the IMO check of the posterior ships (on a terminal)."""
    from ._common import ProgressBar

    return ProgressBar(f"checking {n} posterior ship(s)", enabled=not json_out)


def _print_imo_given_fit(p: dict[str, Any]) -> None:
    """The table of the IMO check given the identification (shared by nomoto and mmg)."""
    from .imo import print_imo_probabilities

    print_imo_probabilities(p, f"IMO MSC.137(76) given the identification: {p['total']} "
                               f"ships from the {p['posterior']} posterior")


def _write_ship(fit: Any, records: Any, out: Path, speed: float | None, length: float | None,
                name: str | None, max_rudder: float, rudder_rate: float, level: float) -> Path:
    from ..identification.nomoto_fit_result import nomoto_ship
    from ..errors import ParameterError
    from ._common import write_ship_file

    if speed is None:
        logged = [r.channels["surge_speed"] for r in records if "surge_speed" in r.channels]
        if not logged:
            raise ParameterError("`--speed` is needed for --out (the records log no "
                                 "surge_speed): the ship's speed U [m/s] in the records")
        speed = float(np.mean(np.concatenate(logged)))
    if length is None:
        raise ParameterError("`--length` is needed for --out: the ship's length L [m]")
    ship = nomoto_ship(fit, name=name or out.stem, speed=speed, length=length,
                       max_rudder=math.radians(max_rudder),
                       rudder_rate=math.radians(rudder_rate), level=level)
    return write_ship_file(ship, out)


def _print_nomoto(fit: Any, payload: dict[str, Any], level: float) -> None:
    from rich.markup import escape
    from rich.table import Table

    console.print(escape(f"Nomoto {fit.order}, output error on the {fit.output}, "
                         f"{len(fit.records)} record(s): {', '.join(fit.records)}"),
                  highlight=False, soft_wrap=True)
    from rich.table import Column

    table = Table("parameter", Column("value", min_width=14, no_wrap=True), "std. error",
                  f"{100 * level:g} % interval", "unit", "start")
    for row in payload["parameters"]:
        deg = row["name"] == "rudder_offset"
        k = 180.0 / math.pi if deg else 1.0
        unit = "deg" if deg else row["unit"]
        start = f"{row['equation_error_start'] * k:.4g}"
        if not row["identified"]:
            table.add_row(escape(row["symbol"]), "unidentifiable", "—", "—", unit, start)
            continue
        table.add_row(escape(row["symbol"]), f"{row['value'] * k:.5g}",
                      f"{row['standard_error'] * k:.3g}",
                      f"{row['ci_low'] * k:.5g} .. {row['ci_high'] * k:.5g}", unit, start)
    console.print(table)
    for row in payload["parameters"]:
        if not row["identified"]:
            console.print(escape(f"  {row['symbol']} is not identified by these records: "
                                 f"{row['evidence']}"), highlight=False, soft_wrap=True)
    unit = "deg" if fit.output == "heading" else "deg/s"
    console.print("start: the equation-error least-squares estimate the output-error fit "
                  "began from", highlight=False, soft_wrap=True)
    console.print(f"residual σ {math.degrees(fit.residual_std):.3g} {unit}, condition number "
                  f"{fit.condition_number:.3g}, {fit.dof} degrees of freedom"
                  + ("" if fit.bootstrap is None else f", {len(fit.bootstrap)} bootstrap refits"),
                  highlight=False)
    if fit.residual_autocorrelation > 0.9 and fit.bootstrap is None:
        console.print(f"  the residuals are correlated (lag-one autocorrelation "
                      f"{fit.residual_autocorrelation:.3f}: model mismatch or coloured noise), "
                      "so these intervals are too narrow; --bootstrap N gives honest ones",
                      highlight=False, soft_wrap=True)
    if "ship_file" in payload:
        console.print(escape(f"wrote {payload['ship_file']}"), highlight=False, soft_wrap=True)
    if "plot" in payload:
        console.print(escape(f"wrote {payload['plot']}"), highlight=False, soft_wrap=True)


RegressionMethod = Literal["ridge", "ols", "tsvd"]


@app.command("mmg")
@handle_errors
def mmg(
    files: Annotated[list[Path], typer.Argument(
        metavar="LOG...", help="Free-running records with u, v, r, δ, n: CSV (time, "
        "rudder_angle, yaw_rate, surge_speed, sway_speed, propeller_rps, ...) or seahelm "
        "NetCDF results.")],
    ship: Annotated[str, typer.Option(
        "--ship", metavar="BASE", help="The MMG ship whose masses, propeller and rudder are "
        "taken as given (a catalog name or a ship file, e.g. from `seahelm ship estimate`).")],
    method: Annotated[RegressionMethod, typer.Option(
        "--method", help="Regression on accelerations: ridge (by generalised cross-validation), "
        "ordinary least squares or truncated SVD.")] = "ridge",
    output_error: Annotated[bool, typer.Option(
        "--output-error/--regression-only", help="Refine the regression by output error over "
        "all records (the engine simulates each record).")] = True,
    angles: Annotated[AngleUnit, typer.Option(
        "--angles", help="Units of the CSV angles [deg|rad] and rates [deg/s|rad/s].")] = "deg",
    out: Annotated[Optional[Path], typer.Option(
        "--out", "-o", metavar="SHIP.toml", help="Write the base ship with the identified "
        "derivatives (each with its source).")] = None,
    name: Annotated[Optional[str], typer.Option("--name", help="Ship name (for --out).")] = None,
    imo: Annotated[int, typer.Option(
        "--imo", metavar="N", help="Draw N ships from the posterior of the hull derivatives and "
        "give the probability of passing each IMO criterion (0: no).", min=0,
        max=MAX_POSTERIOR)] = 0,
    posterior: Annotated[PosteriorName, typer.Option(
        "--posterior", help="Posterior of --imo: the Laplace Gaussian or MCMC (emcee, "
        "the extra seahelm[mcmc]).")] = "laplace",
    seed: Annotated[Optional[int], typer.Option("--seed", help="Seed of the posterior "
                                                "draws.")] = None,
    level: Annotated[float, typer.Option(
        "--level", help="Confidence level of the Wilson intervals.")] = 0.95,
    save_posterior: Annotated[Optional[Path], typer.Option(
        "--save-posterior", metavar="FILE.csv", help="Write the posterior samples (the --imo N "
        "ships' hull derivatives, or --samples N of them): a samples file for `seahelm imo "
        "SHIP.toml --draws FILE.csv` or a scenario's [batch.monte_carlo] samples.")] = None,
    samples: Annotated[int, typer.Option(
        "--samples", metavar="N", help="Without --imo: the number of posterior samples "
        "--save-posterior writes.", min=0, max=MAX_POSTERIOR)] = 0,
    wind: Annotated[Literal["none", "measured"], typer.Option(
        "--wind", help="mmg-ls ship: the records' measured true wind as a known input, or "
        "still air.")] = "none",
    free: Annotated[Optional[str], typer.Option(
        "--free", metavar="NAMES", help="mmg-ls ship: the coefficients to fit, comma-separated "
        "(default: the hull's sway/yaw derivatives, cross-flow and rudder terms, X_0F).")] = None,
    segment: Annotated[float, typer.Option(
        "--segment", metavar="S", help="mmg-ls ship: records are fitted in segments of S "
        "seconds, each from its measured state.")] = 60.0,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Identify the MMG hull derivatives from free-running records, the rest from a base ship.

    LOG may be a folder. An mmg-ls ship (esso-osaka-3m): its coefficients (--free) by
    output error over record segments, the wind an input (seahelm.cli.identify_mmg_ls).

    With --imo N the IMO check runs on N ships drawn from the posterior, the identified ship
    bounding their runs' durations; `--imo N -o SHIP.toml --save-posterior FILE.csv` and then
    `seahelm imo SHIP.toml --draws FILE.csv` give the same probabilities.
    """
    from ..identification.mmg_fit import identify_mmg
    from ..identification.records import read_records
    from ..errors import ParameterError
    from ..ships import get_ship
    from ._common import output_file, write_ship_file

    from .identify_mmg_ls import expand_logs, identify_mmg_ls, parse_free

    files = expand_logs(files)
    for f in files:
        input_file("LOG", f)
    if not 0.0 < level < 1.0:
        raise ParameterError(f"`--level` must be in (0, 1), got {level!r}")
    try:
        base = get_ship(ship)
    except ValueError as exc:
        raise ParameterError(f"`--ship`: {exc}") from None
    low_speed = base.model.supports("record-identification")
    if not base.model.supports("hull-identification") and not low_speed:
        raise ParameterError(f"`--ship` '{base.name}' uses model '{base.model.name}'; the MMG "
                             "identification needs an MMG ship (mmg, e.g. `seahelm ship "
                             "estimate`, or mmg-ls)")
    if low_speed and imo:
        raise ParameterError("`--imo` is for an mmg ship; mmg-ls: `--samples N --save-posterior`")
    if not low_speed and (wind != "none" or free is not None):
        raise ParameterError(f"`--{'wind' if wind != 'none' else 'free'}` is for an mmg-ls "
                             f"ship; '{base.name}' uses model mmg (its hull derivatives)")
    names = parse_free(free) if low_speed else None
    n_post = _posterior_count(imo, samples, save_posterior)
    reads = (*files, *((Path(ship),) if Path(ship).is_file() else ()))
    if out is not None:
        output_file("--out", out, "toml", reads=reads, force=force)
    if save_posterior is not None:
        output_file("--save-posterior", save_posterior, "csv", reads=reads, force=force)
        if out is not None and save_posterior.resolve() == out.resolve():
            raise ParameterError("`--save-posterior` and `--out` are the same file")
    if low_speed:
        return identify_mmg_ls(files, base, wind=wind, free=names, segment=segment, out=out,
                               name=name, samples=n_post, save_posterior=save_posterior,
                               seed=seed, angles=angles, json_out=json_out)
    records = read_records(files, angles=angles)
    for rec in records:
        rps = rec.channels.get("propeller_rps")
        if rps is not None and not np.any(np.abs(rps) > 0):
            raise ParameterError(
                f"`LOG` {rec.name}: `propeller_rps` is 0 throughout: a free-running record "
                "has its propeller turning (the MMG rudder's inflow and the thrust come from "
                "it); a record without it identifies the hull against a model it never ran")
    fit = identify_mmg(records, base, method=method, output_error=output_error)
    payload = fit.as_dict()
    if n_post:
        from ..identification.mmg_posterior import mmg_posterior

        option = "--imo" if imo else "--samples"
        try:
            post = mmg_posterior(fit, records, n=n_post, method=posterior, seed=seed)
        except ParameterError as exc:
            raise ParameterError(f"`{option}`: {exc}") from None
        if save_posterior is not None:
            from ..analysis.imo.given_fit import write_posterior_samples

            payload["posterior_file"] = str(write_posterior_samples(save_posterior, fit, post,
                                                                    base, seed))
        if imo:
            from ..analysis.imo.given_fit import imo_given_mmg_fit

            bar = _bar(imo, json_out)
            try:
                payload["imo"] = imo_given_mmg_fit(fit, records, base, imo, method=posterior,
                                                   seed=seed, level=level, name=name,
                                                   posterior=post, progress=bar)
            finally:
                bar.close()
        else:
            payload["posterior_samples"] = post.as_dict()
    if out is not None:
        # Written last, after the posterior (and its file): a failed draw writes neither
        # the ship nor the samples it would be paired with.
        payload["ship_file"] = str(write_ship_file(fit.ship(base, name=name), out))
    if json_out:
        print_json(payload)
        return
    _print_mmg(fit, base, payload)
    if "posterior_file" in payload:
        from rich.markup import escape

        console.print(escape(f"wrote {n_post} posterior samples to {payload['posterior_file']}"),
                      highlight=False, soft_wrap=True)
    if imo:
        _print_posterior_diagnostics(payload["imo"]["posterior_samples"])
        _print_imo_given_fit(payload["imo"])


def _posterior_count(imo: int, samples: int, save: Path | None) -> int:
    """How many posterior samples ``identify mmg`` draws (0: none), checked."""
    from ..errors import ParameterError

    if samples and imo and samples != imo:
        raise ParameterError(f"`--samples` {samples} and `--imo` {imo}: the IMO check runs "
                             "on the samples written; give one of them")
    if samples and save is None:
        raise ParameterError("`--samples` draws posterior samples for `--save-posterior "
                             "FILE.csv`; give it (or `--imo N` to check them against IMO)")
    n = imo or samples
    if save is not None:
        if not n:
            raise ParameterError("`--save-posterior` needs the number of samples: `--imo N` "
                                 "(draws N ships and checks them) or `--samples N` (draws "
                                 "them only)")
        if save.suffix.lower() != ".csv":
            raise ParameterError(f"`--save-posterior` writes a CSV samples file (FILE.csv), "
                                 f"got {save}")
    return n


def _print_posterior_diagnostics(post: dict[str, Any]) -> None:
    if post["method"] != "mcmc":
        return
    tau = post["autocorr_time"] or {}
    worst = max(tau.values(), default=float("nan"))
    console.print(f"MCMC: {post['walkers']} walkers, {post['steps']} steps ({post['burn']} "
                  f"burn-in, thinned by {post['thin']}), acceptance fraction "
                  f"{post['acceptance_fraction']:.2f}, autocorrelation time <= {worst:.3g} "
                  "steps", highlight=False, soft_wrap=True)


def _print_mmg(fit: Any, base: Any, payload: dict[str, Any]) -> None:
    from rich.markup import escape
    from rich.table import Table

    console.print(escape(f"MMG hull derivatives of '{base.name}' ({fit.method}), "
                         f"{len(fit.records)} record(s)"), highlight=False, soft_wrap=True)
    table = Table("derivative", "value", "std. error", f"{base.name}")
    for row in payload["parameters"]:
        ref = f"{getattr(base.params, row['name']):.4g}"
        if row["identified"]:
            table.add_row(row["name"], f"{row['value']:.5g}", f"{row['standard_error']:.3g}",
                          ref)
        else:
            table.add_row(row["name"], "base value" if row.get("fixed_at_base") else
                          "unidentifiable", "—", ref)
    console.print(table)
    for row in payload["parameters"]:
        if not row["identified"]:
            kept = " (kept at the base ship's value)" if row.get("fixed_at_base") else ""
            console.print(escape(f"  {row['name']} not identified{kept}: {row['evidence']}"),
                          highlight=False, soft_wrap=True)
    console.print("condition numbers " + ", ".join(
        f"{k} {v:.3g}" for k, v in fit.condition_numbers.items()), highlight=False)
    if "ship_file" in payload:
        console.print(escape(f"wrote {payload['ship_file']}"), highlight=False, soft_wrap=True)
