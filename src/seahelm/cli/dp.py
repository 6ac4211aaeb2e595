"""``seahelm dp``: dynamic positioning — the station-keeping capability rose (levels 1 and 3).

Exit codes: 0 success, 2 bad input (one-line reason on stderr), 1 other failure.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import typer

from ..errors import ParameterError
from ..output_files import WRITTEN_BY_ATTR
from ._common import ForceFlag, JsonFlag, OneLineErrors, command_path, console, handle_errors, \
    output_file, print_json

app = typer.Typer(cls=OneLineErrors, no_args_is_help=True,
                  help="Dynamic positioning: thrust allocation and station-keeping capability.")


#: the library's parameter names and the options that set them
_MAX_HEADINGS = 3600
_OPTIONS = {"failure": "--failures", "current_speed": "--current", "headings": "--headings"}


def _failures(text: str) -> Any:
    if text in ("each", "none"):
        return text
    names = [t.strip() for t in text.split(",") if t.strip()]
    if not names:
        raise ParameterError(f"must be each, none or thruster names, got {text!r}",
                             field="--failures", value=text)
    return names


def _payload(res: Any) -> dict:
    return {
        "seahelm_command": command_path() or "seahelm dp capability",
        "vessel": res.vessel,
        "level": 1,
        "directions_deg": [round(math.degrees(t), 9) for t in res.directions],
        "cases": list(res.cases),
        "wind_speed_m_s": {c: [float(v) for v in row] for c, row in
                           zip(res.cases, res.wind_speed)},
        "beaufort": {c: [int(v) for v in row] for c, row in zip(res.cases, res.beaufort)},
        "current_speed_m_s": res.current_speed,
        "assumptions": list(res.assumptions),
    }


def _dataset(res: Any) -> Any:
    import xarray as xr

    ds = xr.Dataset(
        {"wind_speed": (("case", "direction"), res.wind_speed,
                        {"units": "m/s", "long_name": "largest wind speed held (10 m)"}),
         "beaufort": (("case", "direction"), res.beaufort.astype(np.int64),
                      {"units": "1", "long_name": "Beaufort number of that wind"})},
        coords={"case": list(res.cases),
                "direction": ("direction", res.directions,
                              {"units": "rad", "long_name": "environment from, rel. to bow"})})
    ds.attrs.update({"vessel": res.vessel, "level": 1, "current_speed": res.current_speed,
                     "assumptions": "; ".join(res.assumptions),
                     WRITTEN_BY_ATTR: command_path() or "seahelm dp capability"})
    return ds


def _dataset3(res: Any) -> Any:
    """Level 3 as a Dataset: per case, direction and wind speed whether it was held, the
    excursion, the mean thrust and load; per case and direction the largest wind held."""
    import xarray as xr

    dims3 = ("case", "direction", "wind")
    ds = xr.Dataset(
        {"wind_speed": (("case", "direction"), res.wind_speed,
                        {"units": "m/s", "long_name": "largest wind speed held (10 m)"}),
         "held": (dims3, res.held.astype(np.int8),
                  {"units": "1", "long_name": "held (1) by the level-3 criteria"}),
         "excursion": (dims3, res.excursion,
                       {"units": "m", "long_name": "largest excursion over the last half"}),
         "mean_thrust": (dims3 + ("dof",), res.mean_thrust,
                         {"units": "N, N, N·m", "long_name": "mean delivered thrust, last half"}),
         "load": (dims3 + ("dof",), res.load,
                  {"units": "N, N, N·m", "long_name": "mean environmental load"})},
        coords={"case": list(res.cases),
                "direction": ("direction", res.directions,
                              {"units": "rad", "long_name": "environment from, rel. to bow"}),
                "wind": ("wind", np.asarray(res.wind_speeds, dtype=float),
                         {"units": "m/s", "long_name": "wind speed simulated (10 m)"}),
                "dof": ["surge", "sway", "yaw"]})
    ds.attrs.update({"vessel": res.vessel, "level": 3, "criteria": "; ".join(res.criteria),
                     "seconds": float(res.seconds),
                     WRITTEN_BY_ATTR: command_path() or "seahelm dp capability"})
    return ds


def _plot(res: Any, path: Path, level: int = 1, note: str = "") -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from ..plotting.save import save_figure

    fig = plt.figure(figsize=(6.4, 6.4))
    try:
        ax = fig.add_subplot(projection="polar")
        ax.set_theta_zero_location("N")          # bow up
        ax.set_theta_direction(-1)               # starboard to the right (clockwise)
        th = np.append(res.directions, res.directions[:1])
        r = np.append(res.wind_speed[0], res.wind_speed[0, :1])
        ax.plot(th, r, lw=2, label="intact")
        if len(res.cases) > 1:             # the worst single failure, direction by direction
            worst = res.wind_speed[1:].min(axis=0)
            ax.plot(th, np.append(worst, worst[:1]), lw=1.5, ls="--",
                    label=f"worst single failure (of {len(res.cases) - 1}, per direction)")
        ax.set_rlim(0, max(1.0, float(res.wind_speed.max()) * 1.1))
        ax.set_title(f"DP capability level {level} — {res.vessel}\nwind speed held [m/s], "
                     + (note or f"current {res.current_speed:g} m/s"), fontsize=10)
        ax.legend(loc="lower left", bbox_to_anchor=(-0.1, -0.12), fontsize=8)
    except BaseException:
        plt.close(fig)
        raise
    save_figure(fig, path, dpi=100)


def _level3(ship: str, headings: int, failures: str, current: float, no_waves: bool,
            winds: str, duration: float, json_out: bool, workers: int | None,
            out: Path | None = None, json_file: Path | None = None, plot: Path | None = None,
            force: bool = False) -> None:
    from ..analysis.dp.level3 import level3_capability

    speeds = None
    if winds.strip():
        try:
            speeds = [float(w) for w in winds.split(",") if w.strip()]
        except ValueError:
            raise ParameterError(f"must be wind speeds [m/s], comma-separated, got {winds!r}",
                                 field="--winds", unit="m/s", value=winds) from None
    if not (duration > 0 and math.isfinite(duration)):
        raise ParameterError(f"must be > 0 [s], got {duration!r}", field="--duration",
                             unit="s", value=duration)
    if workers is not None and workers < 1:
        raise ParameterError(f"must be ≥ 1 [-], got {workers}", field="--workers", unit="-",
                             value=workers)
    options = {**_OPTIONS, "wind_speeds": "--winds", "workers": "--workers"}
    _check_outputs(out, json_file, plot)
    try:
        res = level3_capability(ship, headings=headings, wind_speeds=speeds,
                                failures=_failures(failures), current_speed=current,
                                waves=not no_waves, duration=duration, workers=workers)
    except ParameterError as exc:
        option = options.get(exc.field or "")
        if option is None:
            raise
        raise ParameterError(exc.reason, field=option, unit=exc.unit, value=exc.value) from exc
    payload = {
        "seahelm_command": command_path() or "seahelm dp capability",
        "vessel": res.vessel, "level": 3,
        "directions_deg": [round(math.degrees(t), 9) for t in res.directions],
        "wind_speeds_m_s": [float(w) for w in res.wind_speeds], "cases": list(res.cases),
        "wind_speed_m_s": {c: [float(v) for v in row] for c, row in
                           zip(res.cases, res.wind_speed)},
        "criteria": list(res.criteria), "seconds": res.seconds,
    }
    if out is not None:
        from ..results import write_netcdf

        write_netcdf(_dataset3(res), out, force=force)
    if json_file is not None:
        _write_json(json_file, payload, force)
    if plot is not None:
        _plot(res, plot, level=3, note=f"time domain, {len(res.wind_speeds)} winds, "
              f"current {current:g} m/s")
    if json_out:
        print_json(payload)
        return
    console.print(f"DP capability level 3 — {res.vessel} ({len(res.cases)} cases x "
                  f"{len(res.directions)} directions x {len(res.wind_speeds)} winds in one "
                  f"batch, {res.seconds:.1f} s)", highlight=False, markup=False)
    for note in res.criteria:
        console.print(f"  * {note}", highlight=False, markup=False)
    console.print("  largest wind speed held [m/s]: min / max over directions", highlight=False,
                  markup=False)
    for case, row in zip(res.cases, res.wind_speed):
        console.print(f"  {case:>28}: {row.min():6.2f} / {row.max():6.2f}", highlight=False,
                      markup=False)


def _check_outputs(out: Path | None, json_file: Path | None, plot: Path | None) -> None:
    """The output files checked before the work (the shared output policy)."""
    if out is not None:
        output_file("--out", out, "netcdf")
    if json_file is not None:
        output_file("--json-out", json_file, "json")
    if plot is not None:
        output_file("--plot", plot, "figure")


def _write_json(path: Path, payload: dict, force: bool) -> None:
    from ..output_files import write_output

    text = json.dumps(payload, indent=1)
    write_output(path, lambda tmp: Path(tmp).write_text(text), "json", force=force)


@app.command("capability")
@handle_errors
def capability(
    ship: Annotated[str, typer.Argument(metavar="SHIP", help="A ship with thrusters: a catalog ship (supply, shushlyapin2017-dp) or a ship file with [[thrusters]] and [particulars].")],
    headings: Annotated[int, typer.Option("--headings", help="Directions over 360°.")] = 36,
    failures: Annotated[str, typer.Option(
        "--failures", help="each (every thruster lost in turn), none, or names (a,b).")
    ] = "each",
    current: Annotated[float, typer.Option("--current", help="Current speed [m/s].")] = 0.5,
    no_waves: Annotated[bool, typer.Option("--no-waves", help="Without the wave drift.")] = False,
    level: Annotated[int, typer.Option(
        "--level", help="1: quasi-static; 3: time domain, one batch of the closed loop "
        "(a dp-3dof ship such as supply).")] = 1,
    winds: Annotated[str, typer.Option(
        "--winds", help="Level 3: wind speeds [m/s], comma-separated (default: the Beaufort "
        "upper speeds from Beaufort 4).")] = "",
    duration: Annotated[float, typer.Option("--duration", help="Level 3: run length [s].")
                        ] = 600.0,
    workers: Annotated[int | None, typer.Option(
        "--workers", help="Level 3: run the batch in chunks on a local Dask cluster of N "
        "processes.")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Write a NetCDF file.")] = None,
    json_file: Annotated[Path | None, typer.Option("--json-out", help="Write a JSON file.")] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Polar capability plot.")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """DP capability: the largest wind held per direction, intact and with each single
    thruster failure; level 1 quasi-static (DNV-ST-0111's method; environment as stated),
    level 3 in the time domain (one batch). Both write --out (NetCDF), --json-out, --plot."""
    from ..analysis.dp.level1 import dp_vessel, level1_capability

    if level not in (1, 3):
        raise ParameterError(f"must be 1 or 3 [-], got {level}", field="--level", unit="-",
                             value=level)
    if level == 1 and workers is not None:
        raise ParameterError(f"is for level 3 only (level 1 takes under a second), got "
                             f"{workers}", field="--workers", value=workers)
    if level == 3:
        _level3(ship, headings, failures, current, no_waves, winds, duration, json_out,
                workers, out, json_file, plot, force)
        return
    if headings < 1:
        raise ParameterError(f"must be ≥ 1 [-], got {headings}",
                             field="--headings", unit="-", value=headings)
    if headings > _MAX_HEADINGS:  # (0.1°; ~10 ms a direction: 1e8 would run for days)
        raise ParameterError(f"must be ≤ {_MAX_HEADINGS} (0.1° apart) [-], got {headings}",
                             field="--headings", unit="-", value=headings)
    _check_outputs(out, json_file, plot)
    vessel = dp_vessel(ship)
    try:
        res = level1_capability(vessel, headings=headings, failures=_failures(failures),
                                current_speed=current, waves=not no_waves)
    except ParameterError as exc:      # the library's names → the options
        option = _OPTIONS.get(exc.field or "")
        if option is None:
            raise
        raise ParameterError(exc.reason, field=option, unit=exc.unit, value=exc.value) from exc
    payload = _payload(res)
    if out is not None:
        from ..results import write_netcdf

        write_netcdf(_dataset(res), out, force=force)
    if json_file is not None:
        _write_json(json_file, payload, force)
    if plot is not None:
        _plot(res, plot)
    if json_out:
        print_json(payload)
        return
    console.print(f"DP capability level 1 — {res.vessel} (current {res.current_speed:g} m/s)",
                  highlight=False, markup=False)
    for note in res.assumptions:
        console.print(f"  * {note}", highlight=False, markup=False)
    console.print("  largest wind speed held [m/s]: min / max over directions", highlight=False,
                  markup=False)
    for case, row in zip(res.cases, res.wind_speed):
        console.print(f"  {case:>28}: {row.min():6.2f} / {row.max():6.2f}", highlight=False,
                      markup=False)


def _poles_text(poles: Any) -> str:
    return ", ".join(f"{p.real:.4g}" if abs(p.imag) < 1e-12 else
                     f"{p.real:.4g}{p.imag:+.4g}j" for p in poles)


@app.command("tune")
@handle_errors
def tune(
    ship: Annotated[str, typer.Argument(metavar="SHIP", help=(
        "A ship with thrusters and a dp-3dof model: a catalog ship (supply) or a ship file."))],
    bandwidth: Annotated[str, typer.Option(
        "--bandwidth", help="Closed-loop bandwidth ω [rad/s]: one for every DOF, or surge,sway,"
        "yaw.")] = "0.1,0.1,0.2",
    damping: Annotated[float, typer.Option("--damping", help="Relative damping ζ [-].")] = 1.0,
    dt: Annotated[float, typer.Option("--dt", help="Controller sample period [s].")] = 0.1,
    north: Annotated[float, typer.Option("--north", help="Scenario: set-point north [m].")
                     ] = 10.0,
    east: Annotated[float, typer.Option("--east", help="Scenario: set-point east [m].")] = 10.0,
    heading: Annotated[float, typer.Option(
        "--heading", help="Scenario: set-point heading [deg].")] = 10.0,
    t_final: Annotated[float, typer.Option("--t-final", help="Scenario: run length [s].")
                       ] = 300.0,
    out: Annotated[Path | None, typer.Option(
        "--out", help="Write a set-point scenario (TOML) with these gains here.")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Design the dp-pid gains by pole placement (Fossen 2021 §12.2.6), with the closed loop
    checked on the vessel's full M and D, and a set-point scenario."""
    from ..control.dp_tuning import tune_dp
    from ..ships import get_ship

    try:
        ws = [float(w) for w in bandwidth.split(",") if w.strip()]
    except ValueError:
        raise ParameterError(f"must be one or three bandwidths [rad/s], comma-separated, got "
                             f"{bandwidth!r}", field="--bandwidth", unit="rad/s",
                             value=bandwidth) from None
    for option, value, unit in (("--north", north, "m"), ("--east", east, "m"),
                                ("--heading", heading, "deg")):
        if not math.isfinite(value):
            raise ParameterError(f"must be finite [{unit}], got {value!r}", field=option,
                                 unit=unit, value=value)
    if not (math.isfinite(t_final) and t_final > 0):
        raise ParameterError(f"must be > 0 [s], got {t_final!r}", field="--t-final", unit="s",
                             value=t_final)
    if out is not None:
        output_file("--out", out, "toml", force=force,
                    reads=(Path(ship),) if Path(ship).is_file() else ())
    the_ship = get_ship(ship)
    try:
        tuning = tune_dp(the_ship, bandwidth=ws if len(ws) != 1 else ws[0], damping=damping,
                         dt=dt)
    except ParameterError as exc:
        option = {"bandwidth": "--bandwidth", "damping": "--damping", "dt": "--dt"}.get(
            exc.field or "")
        if option is None:
            raise
        value = bandwidth if option == "--bandwidth" else exc.value
        raise ParameterError(exc.reason, field=option, unit=exc.unit, value=value) from None
    payload = tuning.as_dict()
    if out is not None:
        from ._common import write_scenario_file

        write_scenario_file(out, ship, lambda ref: tuning.scenario(
            ref, north=north, east=east, heading_deg=heading, t_final=t_final),
            tuning.comment())
        payload["files"] = {"scenario": str(out)}
    if json_out:
        print_json(payload)
        return
    say = dict(highlight=False, markup=False)
    for w in tuning.warnings:
        console.print(f"warning: {w}", style="yellow", **say)
    console.print(f"{tuning.vessel}: dp-pid by pole placement, ω = "
                  + ", ".join(f"{w:g}" for w in tuning.bandwidth)
                  + f" rad/s (surge, sway, yaw), ζ = {tuning.damping:g}", **say)
    for dof, row in zip(("surge", "sway", "yaw"), tuning.designed):
        g = tuning.gains
        console.print(f"  {dof:>5}: K_p {g[f'kp_{dof}']:.5g}  K_d {g[f'kd_{dof}']:.5g}  K_i "
                      f"{g[f'ki_{dof}']:.5g}   designed poles {_poles_text(row)} [1/s]", **say)
    console.print("  closed loop on the full M, D (about ψ = 0): " + _poles_text(tuning.poles)
                  + " [1/s] — " + ("stable" if tuning.stable else "UNSTABLE"), **say)
    if out is not None:
        console.print(f"  scenario: {out} (seahelm run {out})", **say)
