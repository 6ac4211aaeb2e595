"""``seahelm autopilot tune SHIP``: autopilot gains from the ship's linear model.

The command parses, calls :func:`seahelm.analysis.steering.autopilot_tuning.tune_autopilot`
and renders its result (the scenario written by
:meth:`~seahelm.analysis.steering.autopilot_tuning.AutopilotTuning.scenario` and
:func:`~seahelm.analysis.steering.autopilot_tuning.scenario_toml`). It linearises the ship at
its straight run (:mod:`seahelm.analysis.equilibria.linearisation`), takes Nomoto's K and
T = T_1 + T_2 − T_3 (:mod:`seahelm.analysis.steering.indices`) and designs

* ``--design pid`` (default): the ``pid-heading`` gains placing the Nomoto loop's poles at the
  bandwidth ``--bandwidth`` [rad/s], damping ``--damping`` and integral time
  ``--integral-time`` (:func:`seahelm.control.autopilot_design.pid_pole_placement`);
* ``--design lq``: the ``lq-heading`` gains of the LQ-integral design on the sway–yaw block
  (:func:`seahelm.control.autopilot_design.lq_heading`, Bryson weights ``--max-heading-error``
  and the rudder limit);
* ``--design lq-cross-track``: the ``lq-cross-track`` gains
  (:func:`seahelm.control.lq_cross_track.lq_cross_track`: state feedback on the cross-track
  error, its integral, the heading relative to the route, yaw rate and sway; Bryson weights
  ``--max-cross-track`` [m], ``--max-heading-error``; by default L/3 and 20 deg, grown
  together by 2^(1/4) until the nonlinear ship, the candidates simulated in one batch, settles
  from the offset), and a scenario on a straight route starting ``--offset`` m (default L)
  off it.

A ship with a propeller (MMG) is linearised at its self-propelled straight run (the rps that
holds the speed), and the design is the ``-rps`` variant of the controller (``pid-heading-rps``,
``lq-heading-rps``, ``lq-cross-track-rps``), which holds that rps.

It prints the gains, the designed closed-loop poles, the poles with the linearised ship and its
steering gear, and the margins of that loop; ``--out FILE.toml`` writes a scenario whose
``[controller]`` table holds the design (a course change of ``--heading-step`` degrees, or the
route, from the straight run it was designed at, with the ship's steering gear) for
``seahelm run``. Exit 2: a bandwidth above what the rudder rate gives (``--bandwidth``), a ship
the rudder does not steer, no equilibrium, no cross-track weights that settle the ship. A design
below the minimum margins warns.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Literal

import typer
from rich.markup import escape
from rich.table import Table

from ._common import (ForceFlag, JsonFlag, OneLineErrors, console, handle_errors, output_file,
                      print_json)

__all__ = ["app", "tune"]

app = typer.Typer(cls=OneLineErrors, no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False)


@app.callback()
def _main() -> None:
    """Autopilot design: PID and LQ gains from the ship."""


#: The library's argument -> the option (or argument) naming it in this command's errors.
_OPTIONS = {"bandwidth": "--bandwidth", "damping": "--damping", "dt": "--dt",
            "integral_time": "--integral-time", "max_heading_error": "--max-heading-error",
            "max_cross_track": "--max-cross-track", "offset": "--offset",
            "heading_step": "--heading-step", "speed": "--speed", "ship": "SHIP",
            "gain": "SHIP", "model": "SHIP", "A": "SHIP"}


@app.command("tune")
@handle_errors
def tune(
    ship: Annotated[str, typer.Argument(metavar="SHIP", help=(
        "Ship: a catalog name (`seahelm ship list`) or the path of a ship file (*.toml)."))],
    bandwidth: Annotated[float, typer.Option(
        "--bandwidth", help="Closed-loop bandwidth ω_b [rad/s] (PID).")] = 0.05,
    damping: Annotated[float, typer.Option(
        "--damping", help="Relative damping ζ [-] (PID).")] = 0.8,
    integral_time: Annotated[float | None, typer.Option(
        "--integral-time", help="Integral time T_i [s] (default 10/ω_n; PID).")
    ] = None,
    design: Annotated[Literal["pid", "lq", "lq-cross-track"], typer.Option(
        "--design", help=("pid: pole placement from Nomoto K, T; lq: LQ-integral heading; "
                          "lq-cross-track: LQ-integral cross-track (a route)."))] = "pid",
    max_heading_error: Annotated[float | None, typer.Option(
        "--max-heading-error", help=(
            "LQ weight: allowed heading error [deg] (default 5; cross-track 20)."))] = None,
    max_cross_track: Annotated[float | None, typer.Option(
        "--max-cross-track", help=(
            "Cross-track LQ weight: allowed cross-track error [m] (default L/3; with both "
            "weights defaulted they grow by 2^(1/4) until the simulated ship settles)."))
    ] = None,
    offset: Annotated[float | None, typer.Option(
        "--offset", help="Cross-track: the scenario's initial offset [m] (default L).")
    ] = None,
    speed: Annotated[float | None, typer.Option(
        "--speed", help="Speed of the straight run [m/s] (default: the test speed).")
    ] = None,
    dt: Annotated[float, typer.Option(
        "--dt", help="Controller sample period [s] in the scenario.")] = 0.5,
    heading_step: Annotated[float, typer.Option(
        "--heading-step", help="Course change of the scenario [deg].")] = 10.0,
    out: Annotated[Path | None, typer.Option(
        "--out", help="Write a scenario (TOML) with the [controller] table here.")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Design a heading or cross-track autopilot: gains, closed-loop poles, margins, a scenario."""
    from ..analysis.steering.autopilot_tuning import poles_text, tune_autopilot
    from ..errors import ParameterError
    from ..ships import get_ship

    if not (math.isfinite(heading_step) and heading_step != 0 and abs(heading_step) <= 180):
        raise ParameterError(f"must be a course change in [-180, 180] [deg], not 0, got "
                             f"{heading_step!r}", field="--heading-step", unit="deg",
                             value=heading_step)
    for option, value, designs in (("--max-cross-track", max_cross_track, ("lq-cross-track",)),
                                   ("--offset", offset, ("lq-cross-track",)),
                                   ("--max-heading-error", max_heading_error,
                                    ("lq", "lq-cross-track"))):
        if value is not None and design not in designs:
            raise ParameterError(f"= {value!r} is an option of `--design "
                                 f"{' or '.join(designs)}`, not of `--design {design}`: drop it",
                                 field=option, value=value)
    if out is not None:
        output_file("--out", out, "toml", force=force,
                    reads=(Path(ship),) if Path(ship).is_file() else ())
    the_ship = get_ship(ship)
    try:
        tuning = tune_autopilot(the_ship, design=design, bandwidth=bandwidth,
                                damping=damping, integral_time=integral_time,
                                max_heading_error=max_heading_error,
                                max_cross_track=max_cross_track, offset=offset, speed=speed,
                                dt=dt)
    except ParameterError as exc:
        reason = exc.reason.replace("give max_cross_track and max_heading_error",
                                    "give --max-cross-track and --max-heading-error")
        raise ParameterError(reason, field=_OPTIONS.get(exc.field or "", exc.field),
                             unit=exc.unit, value=exc.value) from None
    result, gains = tuning.result, tuning.gains
    K, T = tuning.nomoto.gain, tuning.nomoto.time_constant
    payload = tuning.as_dict()
    if out is not None:
        from ._common import write_scenario_file

        # a ship file by its path from the scenario's folder (it held /abs/paths)
        write_scenario_file(out, ship, lambda ref: tuning.scenario(
            ship=ref, heading_step=heading_step), tuning.comment())
        payload["files"] = {"scenario": str(out)}
    if json_out:
        print_json(payload)
        return
    for w in tuning.warnings:
        console.print(escape(f"warning: {w}"), style="yellow", highlight=False)
    table = Table(title=escape(f"{the_ship.name}: {tuning.controller} ({design}) from K = "
                               f"{K:.4g} 1/s, T = {T:.4g} s"), title_justify="left")
    table.add_column("gain")
    table.add_column("value", justify="right")
    for key, value in gains.items():
        table.add_row(escape(key), f"{value:.5g}")
    console.print(table)
    console.print(escape("  designed poles: " + ", ".join(poles_text(result.poles))
                         + " [1/s]"), highlight=False)
    console.print(escape("  with the linearised ship and steering gear: "
                         + ", ".join(poles_text(tuning.poles)) + " [1/s]"), highlight=False)
    if design != "pid":
        console.print(escape(
            "  Bryson weights: "
            + (f"cross-track error {tuning.max_cross_track:.4g} m, " if design != "lq" else "")
            + f"heading error {tuning.max_heading_error:.4g} deg, rudder "
            f"{math.degrees(the_ship.servo.max_angle):.4g} deg"), highlight=False)
    console.print(escape(f"  margins: gain {result.gain_margin:.3g}, phase "
                         f"{math.degrees(result.phase_margin):.3g} deg at "
                         f"{result.crossover:.3g} rad/s"), highlight=False)
    if out is not None:
        console.print(escape(f"  scenario: {out}"), highlight=False)
