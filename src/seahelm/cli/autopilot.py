"""``seahelm autopilot tune SHIP``: heading-autopilot gains from the ship's linear model.

Linearises the ship at its straight run (:mod:`seahelm.analysis.linearisation`), takes Nomoto's
K and T = T_1 + T_2 − T_3 (:mod:`seahelm.analysis.steering_indices`) and designs

* ``--design pid`` (default): the ``pid-heading`` gains placing the Nomoto loop's poles at the
  bandwidth ``--bandwidth`` [rad/s], damping ``--damping`` and integral time
  ``--integral-time`` (:func:`seahelm.control.autopilot_design.pid_pole_placement`);
* ``--design lq``: the ``lq-heading`` gains of the LQ-integral design on the sway–yaw block
  (:func:`seahelm.control.autopilot_design.lq_heading`, Bryson weights ``--max-heading-error``
  and the rudder limit). A loop crossing over above the steering gear's δ̇_max/δ_max is
  refused (as a PID bandwidth is); by default the weight is the smallest of 5·2^(k/4) deg
  whose loop the rudder rate serves and whose first command for the course change stays
  within the rudder limit.

A ship with a propeller (MMG) is linearised at its self-propelled straight run (the rps that
holds the speed), and the design is the ``-rps`` variant of the controller (``pid-heading-rps``,
``lq-heading-rps``), which holds that rps.

It prints the gains, the designed closed-loop poles, the poles with the linearised ship and its
steering gear, and the margins of that loop; ``--out FILE.toml`` writes a scenario whose
``[controller]`` table holds the design (a course change of ``--heading-step`` degrees, from
the straight run it was designed at) for ``seahelm run``. Exit 2: a bandwidth or an LQ weight
the rudder rate cannot serve (``--bandwidth``, ``--max-heading-error``), a ship the rudder does
not steer, no equilibrium. A design below the minimum margins warns.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from ._common import JsonFlag, OneLineErrors, console, handle_errors, output_file, print_json

__all__ = ["app", "tune", "scenario_text"]

app = typer.Typer(cls=OneLineErrors, no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False)


@app.callback()
def _main() -> None:
    """Autopilot design: PID and LQ gains from the ship."""


def _poles_text(poles: Any) -> list[str]:
    return [f"{p.real:.5g}" + (f"{p.imag:+.5g}j" if abs(p.imag) > 0 else "")
            for p in sorted(np.asarray(poles), key=lambda p: (p.real, p.imag))]


def scenario_text(ship: str, controller: str, gains: dict[str, float], *, dt: float,
                  heading_step_deg: float, t_final: float, comment: str,
                  initial: dict[str, float] | None = None) -> str:
    """A scenario (TOML) running ``controller`` with ``gains`` on ``ship``: a course change.

    Parameters
    ----------
    ship : str
        Catalog name or ship-file path.
    controller : str
        Registry name of the controller.
    gains : dict of str to float
        Its parameters (angles in radians; ``max_command`` is written in degrees).
    dt : float
        Controller sample period [s].
    heading_step_deg : float
        The heading reference [deg].
    t_final : float
        Duration [s].
    comment : str
        First lines (without ``#``).
    initial : dict of str to float, optional
        The ship's initial state by name (SI units; the straight run the design is for),
        written as ``[vessel.initial]`` (default: the model's zero state).

    Returns
    -------
    str
    """
    lines = [f"# {c}" for c in comment.splitlines()]
    lines += [f'title = "{ship}: {heading_step_deg:g} deg course change, {controller}"', "",
              "[vessel]", f"ship = {_toml_string(ship)}", ""]
    if initial:
        lines += ["[vessel.initial]"] + [f"{k} = {float(v)!r}" for k, v in initial.items()] + [""]
    lines += ["[controller]",
              f'model = "{controller}"', f"dt = {dt!r}", "", "[controller.params]"]
    for key, value in gains.items():
        if key == "max_command":
            lines.append(f"max_command_deg = {math.degrees(value)!r}")
        else:
            lines.append(f"{key} = {float(value)!r}")
    lines += ["", "[controller.reference]", f"heading_deg = {heading_step_deg!r}", "",
              "[simulation]", f"t_final = {t_final!r}", "dt = 0.1", ""]
    return "\n".join(lines)


def _lq_design(block: Any, states: tuple[str, ...], max_heading_error: float | None,
               max_rudder: float, max_rate: float, step_deg: float) -> tuple[Any, float]:
    """The LQ design at ``max_heading_error`` [deg]; by default at the smallest of
    5·2^(k/4) deg whose loop crosses over below the steering gear's δ̇_max/δ_max and whose
    first command for the course change ``step_deg`` stays within the rudder limit
    (k_ψ |Δψ| ≤ δ_max: an unstable ship under a deeply saturated rudder falls into a limit
    cycle, as the KVLCC2 L7 does at 5 deg). Returns the design and the weight [deg]."""
    from ..control.autopilot_design import lq_heading
    from ..errors import ParameterError

    if max_heading_error is not None:
        try:
            return lq_heading(block.A, block.B[:, 0], states,
                              max_heading_error=math.radians(max_heading_error),
                              max_rudder=max_rudder, max_rate=max_rate), max_heading_error
        except ParameterError as exc:
            if exc.field != "max_heading_error":
                raise
            raise ParameterError(
                f"= {max_heading_error:g} deg {exc.reason.split(' rad ', 1)[1]}",
                field="--max-heading-error", unit="deg", value=max_heading_error) from None
    last: ParameterError | None = None
    for k in range(24):  # up to 5·2^(23/4) = 271 deg
        deg = 5.0 * 2.0 ** (k / 4)
        try:
            design = lq_heading(block.A, block.B[:, 0], states,
                                max_heading_error=math.radians(deg), max_rudder=max_rudder,
                                max_rate=max_rate)
        except ParameterError as exc:
            if exc.field != "max_heading_error":
                raise
            last = exc
            continue
        if design.params.k_heading * math.radians(abs(step_deg)) <= max_rudder:
            return design, deg
    raise ParameterError(f"no LQ weight up to 271 deg serves this steering gear ({last})",
                         field="--max-heading-error")


def _settling(poles: Any) -> float:
    """About ten time constants of the slowest stable pole [s] (the scenario's duration)."""
    rates = [-p.real for p in np.asarray(poles) if p.real < -1e-9]
    return 10.0 / min(rates) if rates else 300.0


def _toml_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


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
    design: Annotated[Literal["pid", "lq"], typer.Option(
        "--design", help="pid: pole placement from Nomoto K, T; lq: LQ-integral.")] = "pid",
    max_heading_error: Annotated[float | None, typer.Option(
        "--max-heading-error", help=(
            "LQ weight: allowed heading error [deg] (default: the smallest from 5 deg up, "
            "in steps of 2^(1/4), whose loop the rudder rate serves and whose first command "
            "for --heading-step is within the rudder limit)."))] = None,
    speed: Annotated[float | None, typer.Option(
        "--speed", help="Speed of the straight run [m/s] (default: the test speed).")
    ] = None,
    dt: Annotated[float, typer.Option(
        "--dt", help="Controller sample period [s] in the scenario.")] = 0.5,
    heading_step: Annotated[float, typer.Option(
        "--heading-step", help="Course change of the scenario [deg].")] = 10.0,
    out: Annotated[Path | None, typer.Option(
        "--out", help="Write a scenario (TOML) with the [controller] table here.")] = None,
    json_out: JsonFlag = False,
) -> None:
    """Design a heading autopilot: gains, closed-loop poles, margins, a scenario snippet."""
    from ..analysis.linearisation import linearize
    from ..analysis.steering_indices import steering_indices
    from ..control.autopilot_design import (AutopilotDesignWarning, heading_loop_poles,
                                            pid_pole_placement, state_space_response)
    from ..errors import ParameterError
    from ..ships import get_ship

    for option, value, unit in (("--bandwidth", bandwidth, "rad/s"), ("--damping", damping, "-"),
                                ("--dt", dt, "s"), ("--max-heading-error",
                                                    max_heading_error or 5.0, "deg")):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=option,
                                 unit=unit, value=value)
    if integral_time is not None and not integral_time > 0:
        raise ParameterError(f"must be > 0 [s], got {integral_time!r}", field="--integral-time",
                             unit="s", value=integral_time)
    if out is not None:
        output_file("--out", out)
    the_ship = get_ship(ship)
    if the_ship.steering_gear is None:
        raise ParameterError(f"'{the_ship.name}' has no steering gear to design for",
                             field="SHIP")
    servo = the_ship.servo
    bare = linearize(the_ship, speed=speed, actuator=False)
    full = linearize(the_ship, speed=speed, actuator=True)
    indices = steering_indices(bare)
    K, T = indices.nomoto.gain, indices.nomoto.time_constant
    # position does not feed back at the straight run: the loop's poles are those without it
    full = full.select(states=[s for s in full.state_labels if s not in ("north", "east")])
    i_cmd = full.input_labels.index("rudder_command")
    row = {name: np.eye(len(full.state_labels))[full.state_labels.index(name)]
           for name in ("heading", "yaw_rate", "sway_speed") if name in full.state_labels}

    def heading_response(w: np.ndarray) -> np.ndarray:
        return state_space_response(full.A, full.B[:, i_cmd], row["heading"], w)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AutopilotDesignWarning)
        try:
            if design == "pid":
                result = pid_pole_placement(
                    K, T, bandwidth=bandwidth, damping=damping, integral_time=integral_time,
                    max_command=float(servo.max_angle), max_rate=float(servo.max_rate),
                    heading_response=heading_response)
            else:
                states = tuple(s for s in indices.steering_states)
                block = bare.select(states=states, inputs=["rudder_angle"])
                result, max_heading_error = _lq_design(
                    block, states, max_heading_error, float(servo.max_angle),
                    float(servo.max_rate), heading_step)
        except ParameterError as exc:
            option = {"bandwidth": "--bandwidth", "gain": "SHIP", "model": "SHIP",
                      "max_heading_error": "--max-heading-error"}.get(exc.field or "",
                                                                      exc.field)
            raise ParameterError(exc.reason, field=option, unit=exc.unit,
                                 value=exc.value) from None
    gains = dict(result.params.as_dict())
    controller = "pid-heading" if design == "pid" else "lq-heading"
    if the_ship.has_propeller:  # the rps of the self-propelled straight run, held
        controller += "-rps"
        gains["propeller_rps"] = float(full.u0[full.input_labels.index("propeller_rps")])
    p = result.params
    if design == "pid":
        k = dict(k_heading=p.kp, k_yaw_rate=p.kd, k_integral=p.ki)
    else:
        k = dict(k_heading=p.k_heading, k_yaw_rate=p.k_yaw_rate, k_integral=p.k_integral,
                 k_sway=p.k_sway)
    actual = heading_loop_poles(full.A, full.B[:, i_cmd], row["heading"], row["yaw_rate"],
                                c_sway=row.get("sway_speed"), **k)
    payload: dict[str, Any] = {
        "ship": the_ship.name, "design": design, "controller": controller,
        "nomoto": {"K_per_s": K, "T_s": T, "T1_s": indices.nomoto.t1, "T2_s": indices.nomoto.t2,
                   "T3_s": indices.nomoto.t3},
        "gains": gains,
        "designed_poles": [[float(z.real), float(z.imag)] for z in result.poles],
        "poles_with_ship_and_steering_gear": [[float(z.real), float(z.imag)] for z in actual],
        "gain_margin": result.gain_margin, "phase_margin_deg": math.degrees(result.phase_margin),
        "crossover_rad_per_s": result.crossover,
        "warnings": [str(w.message) for w in caught],
    }
    if design == "pid":
        payload.update(natural_frequency=result.natural_frequency, damping=result.damping,
                       integral_time_s=result.integral_time, bandwidth=result.bandwidth)
    else:
        payload["max_heading_error_deg"] = max_heading_error
    if out is not None:
        from ..results import atomic_write

        ship_ref = str(Path(ship).resolve()) if Path(ship).suffix == ".toml" else ship
        text = scenario_text(
            ship_ref, controller, gains, dt=dt, heading_step_deg=heading_step,
            t_final=float(max(300.0, 100.0 * math.ceil(0.1 * _settling(actual)))),
            initial={k: float(v) for k, v in zip(bare.state_labels, bare.x0)
                     if k not in ("north", "east", "heading") and v != 0.0},
            comment=(f"seahelm autopilot tune {the_ship.name} --design {design}: Nomoto K = "
                     f"{K:.4g} 1/s, T = {T:.4g} s at U = {bare.speed:.4g} m/s\n"
                     "closed-loop poles (ship + steering gear, linear): "
                     + ", ".join(_poles_text(actual))))
        atomic_write(out, lambda tmp: Path(tmp).write_text(text))
        payload["files"] = {"scenario": str(out)}
    if json_out:
        print_json(payload)
        return
    for w in caught:
        console.print(escape(f"warning: {w.message}"), style="yellow", highlight=False)
    table = Table(title=escape(f"{the_ship.name}: {controller} ({design}) from K = {K:.4g} 1/s, "
                               f"T = {T:.4g} s"), title_justify="left")
    table.add_column("gain")
    table.add_column("value", justify="right")
    for key, value in gains.items():
        table.add_row(escape(key), f"{value:.5g}")
    console.print(table)
    console.print(escape("  designed poles: " + ", ".join(_poles_text(result.poles))
                         + " [1/s]"), highlight=False)
    console.print(escape("  with the linearised ship and steering gear: "
                         + ", ".join(_poles_text(actual)) + " [1/s]"), highlight=False)
    if design == "lq":
        console.print(escape(f"  Bryson weights: heading error {max_heading_error:.4g} deg, "
                             f"rudder {math.degrees(servo.max_angle):.4g} deg"),
                      highlight=False)
    console.print(escape(f"  margins: gain {result.gain_margin:.3g}, phase "
                         f"{math.degrees(result.phase_margin):.3g} deg at "
                         f"{result.crossover:.3g} rad/s"), highlight=False)
    if out is not None:
        console.print(escape(f"  scenario: {out}"), highlight=False)
