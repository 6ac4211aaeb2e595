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

from ._common import (
    JsonFlag,
    OneLineErrors,
    console,
    handle_errors,
    input_file,
    print_json,
)

app = typer.Typer(
    cls=OneLineErrors,
    help="Identify steering-model coefficients from recorded turns (Romanov & Chirkova: "
    "reduced steady-turn model a·ω² + b·ω + α(1 + c·ω) = 0).",
    no_args_is_help=True,
)

_UNITS = {"a": "s²/rad", "b": "s", "c": "s/rad", "d": "1/rad"}

#: The keys of :data:`~seahelm.identification.fitting.FIT_METHODS` and
#: :data:`~seahelm.identification.reduced_forms.REDUCED_FORMS`, spelled out so that the
#: command line does not import the fitting code (tests/test_cli_style.py checks that they
#: agree).
FitMethod = Literal["lsq", "robust", "brute"]
FormName = Literal["paper", "exact", "paper-odd", "exact-odd"]
AngleUnit = Literal["deg", "rad"]


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

    Coefficients are reported in radian units (a [s²/rad], b [s], c [s/rad]) whatever --angles.
    """
    from ..errors import ParameterError
    from ..identification.fitting import fit_steady_turns
    from ..identification.segments import extract_steady_segments
    from ..identification.turn_log import read_turn_log

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
    out["units"] = {n: _UNITS[n] for n in fit.form.names}
    out["units"]["residual_rms"] = "rad"
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
