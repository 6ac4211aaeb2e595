"""``seahelm autopilot tune SHIP``: autopilot gains from the ship's linear model.

Linearises the ship at its straight run (:mod:`seahelm.analysis.linearisation`), takes Nomoto's
K and T = T_1 + T_2 − T_3 (:mod:`seahelm.analysis.steering_indices`) and designs

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
import os
import warnings
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from ._common import ForceFlag, JsonFlag, OneLineErrors, console, handle_errors, output_file, print_json

__all__ = ["app", "tune", "scenario_text", "route_scenario_text"]

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
                  initial: dict[str, float] | None = None, name: str | None = None) -> str:
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
    name : str, optional
        The ship's name for the title (default: ``ship``; a path does not belong there).

    Returns
    -------
    str
    """
    lines = [f"# {c}" for c in comment.splitlines()]
    lines += [f'title = "{name or ship}: {heading_step_deg:g} deg course change, {controller}"',
              "",
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


def _cross_track_design(block: Any, states: tuple[str, ...], surge: float, max_cross_track: float,
                        max_heading_error: float, max_rudder: float, *, explicit: bool,
                        settles: Any) -> tuple[Any, float, float]:
    """The LQ cross-track design at the weights [m], [deg] if they were given (``explicit``);
    else at the smallest of them × 2^(k/4), k = 0 ... 7, whose nonlinear closed loop settles
    from the scenario's offset (``settles``: candidate designs -> one bool each, simulated as
    one batch). Returns the design and the weights used."""
    from ..control.lq_cross_track import lq_cross_track
    from ..errors import ParameterError

    candidates = []
    for k in range(1 if explicit else 8):
        grow = 2.0 ** (k / 4)
        design = lq_cross_track(block.A, block.B[:, 0], states, surge,
                                max_cross_track=max_cross_track * grow,
                                max_heading_error=math.radians(max_heading_error * grow),
                                max_rudder=max_rudder)
        candidates.append((design, max_cross_track * grow, max_heading_error * grow))
    if explicit:
        return candidates[0]
    for c, good in zip(candidates, settles([c[0] for c in candidates])):
        if good:
            return c
    raise ParameterError(
        f"none of the weights from {candidates[0][1]:.4g} m, {candidates[0][2]:.4g} deg to "
        f"{candidates[-1][1]:.4g} m, {candidates[-1][2]:.4g} deg settles the ship from the "
        "scenario's offset (simulated); give --max-cross-track and --max-heading-error",
        field="--max-cross-track")


def _cross_track_loop_poles(linear: Any, gains: dict[str, float]) -> np.ndarray:
    """Poles of the linearised ship and steering gear (states without ``north``; ``east`` is
    the cross-track error of a route due north) under
    δ_c = −k_i ∫y − k_y y − k_ψ ψ − k_r r − k_v v, with the integral state appended."""
    labels, n = linear.state_labels, len(linear.state_labels)
    row = {s: np.eye(n)[labels.index(s)] for s in ("east", "heading", "yaw_rate", "sway_speed")
           if s in labels}
    k = (gains["k_cross_track"] * row["east"] + gains["k_heading"] * row["heading"]
         + gains["k_yaw_rate"] * row["yaw_rate"]
         + gains["k_sway"] * row.get("sway_speed", np.zeros(n)))
    b = linear.B[:, linear.input_labels.index("rudder_command")]
    acl = np.zeros((n + 1, n + 1))
    acl[:n, :n] = linear.A - np.outer(b, k)
    acl[:n, n] = -b * gains["k_integral"]
    acl[n, :n] = row["east"]
    return np.linalg.eigvals(acl)


def _route_setup(ship: Any, bare: Any, full: Any, offset: float, t_final: float
                 ) -> tuple[dict[str, float], list[list[float]], float | None]:
    """The route scenario's initial state, route and held rps (for the check and the file)."""
    initial = {k: float(v) for k, v in zip(bare.state_labels, bare.x0)
               if k not in ("north", "east", "heading") and v != 0.0}
    leg = max(10.0 * bare.length, 1.2 * bare.speed * t_final)
    rps = (float(full.u0[full.input_labels.index("propeller_rps")]) if ship.has_propeller
           else None)
    return {**initial, "east": float(offset)}, [[0.0, 0.0], [float(f"{leg:.6g}"), 0.0]], rps


def _settles(ship: Any, bare: Any, full: Any, designs: list[Any], offset: float,
             dt: float) -> list[bool]:
    """(``full``: the linearised ship and steering gear without ``north``.) Whether each
    design's nonlinear closed loop (the route scenario: the ship ``offset``
    off a straight route) ends within 2 % of max(|offset|, L) of the route over the last
    quarter of its run (one batch; a diverged run does not)."""
    from ..registry import get_controller
    from ..simulation.engine import simulate

    t_final = float(max(300.0, 100.0 * math.ceil(0.1 * max(
        _settling(_cross_track_loop_poles(full, d.gains)) for d in designs))))
    initial, route, rps = _route_setup(ship, bare, full, offset, t_final)
    x0 = np.zeros(ship.model.n_states)
    for k, v in initial.items():
        x0[ship.model.state_labels.index(k)] = v
    name = "lq-cross-track" + ("-rps" if rps is not None else "")
    res = simulate(ship=ship, x0=x0, t_final=t_final, dt=0.1, controller=get_controller(name),
                   controller_params=[d.params(route, propeller_rps=rps,
                                               acceptance_radius=bare.length) for d in designs],
                   controller_dt=dt, record_every=10)
    xte = res["cross_track_error"]
    tail = np.abs(xte[:, int(0.75 * xte.shape[1]):]).max(axis=1)
    return list((res.status == 0) & (tail <= 0.02 * max(abs(offset), bare.length)))


def route_scenario_text(ship: str, controller: str, gains: dict[str, float], *, dt: float,
                        t_final: float, initial: dict[str, float], waypoints: Any,
                        acceptance_radius: float, comment: str, name: str | None = None
                        ) -> str:
    """A scenario (TOML) running the route follower ``controller`` with ``gains`` on ``ship``
    along ``waypoints`` (``[guidance]``).

    Parameters
    ----------
    ship : str
        Catalog name or ship-file path.
    controller : str
        Registry name of the controller (``lq-cross-track``, ``lq-cross-track-rps``).
    gains : dict of str to float
        Its parameters (``max_command`` is written in degrees).
    dt : float
        Controller sample period [s].
    t_final : float
        Duration [s].
    initial : dict of str to float
        The ship's initial state by name (SI units; ``east`` the offset from a route due
        north).
    waypoints : sequence of (float, float)
        The route (north, east) [m].
    acceptance_radius : float
        Waypoint acceptance circle [m].
    comment : str
        First lines (without ``#``).
    name : str, optional
        The ship's name for the title (default: ``ship``).

    Returns
    -------
    str
    """
    lines = [f"# {c}" for c in comment.splitlines()]
    lines += [f'title = "{name or ship}: {controller} on a route"', "", "[vessel]",
              f"ship = {_toml_string(ship)}", "", "[vessel.initial]"]
    lines += [f"{k} = {float(v)!r}" for k, v in initial.items()]
    lines += ["", "[controller]", f'model = "{controller}"', f"dt = {dt!r}", "",
              "[controller.params]"]
    for key, value in gains.items():
        if key == "max_command":
            lines.append(f"max_command_deg = {math.degrees(value)!r}")
        else:
            lines.append(f"{key} = {float(value)!r}")
    points = ", ".join(f"[{float(n)!r}, {float(e)!r}]" for n, e in waypoints)
    lines += ["", "[guidance]", f"waypoints = [{points}]",
              f"acceptance_radius = {float(acceptance_radius)!r}", "", "[simulation]",
              f"t_final = {t_final!r}", "dt = 0.1", ""]
    return "\n".join(lines)


def _scenario_duration(poles: Any) -> float:
    """The written scenario's ``t_final`` [s]: five time constants of the slowest stable pole
    of the linearised ship, steering gear and controller, in whole 100 s, at least 300 s.

    It was a hundred (``100 ceil(0.1 · 10 τ)``): a 10° course change of the Mariner under its
    PID ran 15,000 s, where the nonlinear run settles within 2 % in 360–400 s (10° and 30°;
    the slowest pole, about ω_n/10 of the pole-placement PID, 0.0067 1/s, gives 800 s)."""
    rates = [-p.real for p in np.asarray(poles) if p.real < -1e-9]
    settle = 5.0 / min(rates) if rates else 300.0
    return float(max(300.0, 100.0 * math.ceil(0.01 * settle)))


def _settling(poles: Any) -> float:
    """About ten time constants of the slowest stable pole [s] (the scenario's duration)."""
    rates = [-p.real for p in np.asarray(poles) if p.real < -1e-9]
    return 10.0 / min(rates) if rates else 300.0


def _toml_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


#: ``--dt`` at most |T| / MAX_PERIOD_SHARE (the Nomoto time constant): a controller is sampled
#: some 10-20 times per closed-loop time constant (Franklin, Powell & Workman 1998, ch. 11);
#: 5 per open-loop T is the least that still steers.
MAX_PERIOD_SHARE = 5.0


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
    from ..analysis.linearisation import linearize
    from ..analysis.steering_indices import steering_indices
    from ..control.autopilot_design import (AutopilotDesignWarning, heading_loop_poles,
                                            lq_heading, pid_pole_placement,
                                            state_space_response)
    from ..errors import ParameterError
    from ..ships import get_ship

    for option, value, unit in (("--bandwidth", bandwidth, "rad/s"), ("--damping", damping, "-"),
                                ("--dt", dt, "s"), ("--max-heading-error",
                                                    max_heading_error or 5.0, "deg"),
                                ("--max-cross-track", max_cross_track or 1.0, "m")):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=option,
                                 unit=unit, value=value)
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
    if integral_time is not None and not integral_time > 0:
        raise ParameterError(f"must be > 0 [s], got {integral_time!r}", field="--integral-time",
                             unit="s", value=integral_time)
    if out is not None:
        output_file("--out", out, "toml", force=force,
                    reads=(Path(ship),) if Path(ship).is_file() else ())
    the_ship = get_ship(ship)
    if the_ship.steering_gear is None:
        raise ParameterError(f"'{the_ship.name}' has no steering gear to design for",
                             field="SHIP")
    servo = the_ship.servo
    bare = linearize(the_ship, speed=speed, actuator=False)
    full = linearize(the_ship, speed=speed, actuator=True)
    whole = full.select(states=[s for s in full.state_labels if s != "north"])
    indices = steering_indices(bare)
    K, T = indices.nomoto.gain, indices.nomoto.time_constant
    if dt > abs(T) / MAX_PERIOD_SHARE:  # (a sampled loop that slow cannot steer the ship)
        raise ParameterError(
            f"= {dt:g} s is more than 1/{MAX_PERIOD_SHARE:g} of the ship's Nomoto time "
            f"constant |T| = {abs(T):.4g} s: an autopilot sampled that seldom cannot steer it; "
            f"give at most {abs(T) / MAX_PERIOD_SHARE:.3g} s", field="--dt", unit="s", value=dt)
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
            elif design == "lq":
                states = tuple(s for s in indices.steering_states)
                block = bare.select(states=states, inputs=["rudder_angle"])
                max_heading_error = 5.0 if max_heading_error is None else max_heading_error
                result = lq_heading(block.A, block.B[:, 0], states,
                                    max_heading_error=math.radians(max_heading_error),
                                    max_rudder=float(servo.max_angle))
            else:
                states = tuple(s for s in indices.steering_states)
                block = bare.select(states=states, inputs=["rudder_angle"])
                surge = float(bare.A[bare.state_labels.index("east"),
                                     bare.state_labels.index("heading")])  # ∂ė/∂ψ at ψ = 0
                offset = bare.length if offset is None else offset
                result, max_cross_track, max_heading_error = _cross_track_design(
                    block, states, surge, max_cross_track or bare.length / 3.0,
                    max_heading_error or 20.0, float(servo.max_angle),
                    explicit=max_cross_track is not None or max_heading_error is not None,
                    settles=lambda designs: _settles(the_ship, bare, whole, designs, offset,
                                                     dt))
        except ParameterError as exc:
            option = {"bandwidth": "--bandwidth", "gain": "SHIP", "model": "SHIP", "A": "SHIP",
                      "max_heading_error": "--max-heading-error",
                      "max_cross_track": "--max-cross-track"}.get(exc.field or "", exc.field)
            raise ParameterError(exc.reason, field=option, unit=exc.unit,
                                 value=exc.value) from None
    if design == "lq-cross-track":
        gains = {**result.gains, "max_command": result.max_command}
        controller = "lq-cross-track"
        actual = _cross_track_loop_poles(whole, result.gains)
    else:
        gains = dict(result.params.as_dict())
        controller = "pid-heading" if design == "pid" else "lq-heading"
        p = result.params
        if design == "pid":
            k = dict(k_heading=p.kp, k_yaw_rate=p.kd, k_integral=p.ki)
        else:
            k = dict(k_heading=p.k_heading, k_yaw_rate=p.k_yaw_rate, k_integral=p.k_integral,
                     k_sway=p.k_sway)
        actual = heading_loop_poles(full.A, full.B[:, i_cmd], row["heading"], row["yaw_rate"],
                                    c_sway=row.get("sway_speed"), **k)
    if the_ship.has_propeller:  # the rps of the self-propelled straight run, held
        controller += "-rps"
        gains["propeller_rps"] = float(full.u0[full.input_labels.index("propeller_rps")])
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
    if design == "lq-cross-track":
        payload.update(max_cross_track_m=max_cross_track, surge_speed=result.speed)
    if out is not None:
        from ..output_files import write_output, written_by_line

        from ._common import command_path

        # a ship file by its path from the scenario's folder (a scenario's paths are its
        # own): the file stays valid where it is copied with its ship (it held /abs/paths)
        ship_ref = (os.path.relpath(Path(ship).resolve(), Path(out).resolve().parent)
                    if Path(ship).suffix == ".toml" else ship)
        t_final = _scenario_duration(actual)
        initial = {k: float(v) for k, v in zip(bare.state_labels, bare.x0)
                   if k not in ("north", "east", "heading") and v != 0.0}
        comment = (f"seahelm autopilot tune {the_ship.name} --design {design}: Nomoto K = "
                   f"{K:.4g} 1/s, T = {T:.4g} s at U = {bare.speed:.4g} m/s\n"
                   "closed-loop poles (ship + steering gear, linear): "
                   + ", ".join(_poles_text(actual)))
        if design == "lq-cross-track":
            start, route, _ = _route_setup(the_ship, bare, full, offset, t_final)
            text = route_scenario_text(
                ship_ref, controller, gains, dt=dt, t_final=t_final, initial=start,
                waypoints=route, acceptance_radius=bare.length, comment=comment,
                name=the_ship.name)
        else:
            text = scenario_text(ship_ref, controller, gains, dt=dt,
                                 heading_step_deg=heading_step, t_final=t_final,
                                 initial=initial, comment=comment, name=the_ship.name)
        command = command_path()
        text += written_by_line(command) if command else ""
        write_output(out, lambda tmp: Path(tmp).write_text(text), "toml", option="--out",
                     force_word="--force", command=command)
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
    if design != "pid":
        console.print(escape(
            "  Bryson weights: "
            + (f"cross-track error {max_cross_track:.4g} m, " if design != "lq" else "")
            + f"heading error {max_heading_error:.4g} deg, rudder "
            f"{math.degrees(servo.max_angle):.4g} deg"), highlight=False)
    console.print(escape(f"  margins: gain {result.gain_margin:.3g}, phase "
                         f"{math.degrees(result.phase_margin):.3g} deg at "
                         f"{result.crossover:.3g} rad/s"), highlight=False)
    if out is not None:
        console.print(escape(f"  scenario: {out}"), highlight=False)
