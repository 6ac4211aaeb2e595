"""``seahelm maneuver stopping``: the full-astern stopping test of a ship with a propeller.

Runs :func:`seahelm.analysis.maneuvers.crash_stop` (the rudder held amidships; an ``mmg`` ship
is given its engine by :func:`~seahelm.analysis.maneuvers.stopping_ship`) and prints the
metrics like the other manoeuvres (:mod:`seahelm.cli.maneuver`: a table, or one JSON object
with ``--json``; NetCDF and a PNG of the track with the rps and engine order with ``--out``).
A ship without a propeller cannot stop: exit 2, naming ``--ship``.
"""

from __future__ import annotations

import math
from typing import Annotated

import typer
from rich.markup import escape

from ..errors import ParameterError
from ._common import ForceFlag, JsonFlag, handle_errors
from .maneuver import (
    Depth,
    Dt,
    Out,
    SHIP_HELP,
    ShipName,
    Speed,
    Field,
    _per_l,
    app,
    check_out,
    check_positive_opt,
    check_speed_rps,
    finish,
    header,
    ship_of,
    ship_reads,
)

__all__ = ["stopping_cmd", "STOPPING_FIELDS"]

#: The stopping test's own duration: not from a steady turn (the other manoeuvres' --t-final)
#: but the momentum bound of :func:`seahelm.analysis.maneuvers.crash_stop`.
TFinal = Annotated[float | None, typer.Option(
    "--t-final", help=escape("Duration [s] (default: 1.2 x the time to stop by momentum with "
                             "the bollard astern thrust, an upper bound)."))]

STOPPING_FIELDS: tuple[Field, ...] = (
    ("head_reach_m", "head reach [m]", lambda r: r["head_reach"]),
    ("head_reach_L", "head reach [L]", _per_l("head_reach")),
    ("track_reach_m", "track reach [m]", lambda r: r["track_reach"]),
    ("track_reach_L", "track reach [L]", _per_l("track_reach")),
    ("lateral_deviation_m", "lateral deviation [m]", lambda r: r["lateral_deviation"]),
    ("max_lateral_deviation_m", "largest lateral deviation [m]",
     lambda r: r["max_lateral_deviation"]),
    ("heading_change_deg", "heading change [deg]", lambda r: math.degrees(r["heading_change"])),
    ("time_dead_s", "time to dead in the water [s]", lambda r: r["time_dead"]),
    ("time_astern_s", "time to astern rotation [s]", lambda r: r["time_astern"]),
    ("speed_dead_mps", "speed when dead in the water [m/s]", lambda r: r["speed_dead"]),
    ("reversal_delay_s", "reversal delay [s]", lambda r: r["reversal_delay"]),
)


#: ``--hull`` values: the ``hull_model`` of :class:`~seahelm.vessels.mmg_four_quadrant.MMG4QParams`.
_HULLS = {"cross-flow": 0.0, "mirror": 1.0}


@app.command("stopping")
@handle_errors
def stopping_cmd(
    ship: Annotated[ShipName, typer.Option("--ship", "--catalog", metavar="SHIP", help=(
        SHIP_HELP + " It needs a propeller: an mmg ship is given an engine estimate."))
    ] = "kvlcc2-l7",
    order: Annotated[float, typer.Option("--order", help=escape(
        "Engine order at t = 0, in [-1, 0) (-1 full astern)."))] = -1.0,
    reversal_delay: Annotated[float | None, typer.Option("--reversal-delay", help=escape(
        "Time from the order to the air start [s] (fuel cut, propeller windmilling; default: "
        "60 s full scale, Froude-scaled for a model)."))] = None,
    dead_fraction: Annotated[float, typer.Option("--dead-fraction", help=escape(
        "Dead in the water at surge speed <= this x U0, in [0, 1)."))] = 0.05,
    hull: Annotated[str | None, typer.Option("--hull", metavar="cross-flow|mirror", help=escape(
        "Hull astern and at large drift: cross-flow (the low-speed model of Yoshimura et al. "
        "2009) or mirror (the fore-aft mirrored MMG hull) (default: the ship's own, "
        "cross-flow for an mmg ship)."))] = None,
    speed: Speed = None,
    t_final: TFinal = None,
    dt: Dt = None,
    water_depth: Depth = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    out: Out = None,
) -> None:
    """Stopping (crash-stop) test: head reach, track reach, lateral deviation, times."""
    from ..analysis.maneuvers import crash_stop, stopping_ship
    from ..plotting.maneuvers import plot_stopping

    found = ship_of(ship, water_depth)
    check_speed_rps(found, speed, None)
    check_positive_opt("--t-final", t_final, "s")
    check_positive_opt("--dt", dt, "s")
    if not (math.isfinite(order) and -1.0 <= order < 0.0):
        raise ParameterError(f"`--order` must be in [-1, 0) [-] (-1 full astern), got {order!r}")
    if not (math.isfinite(dead_fraction) and 0.0 <= dead_fraction < 1.0):
        raise ParameterError(f"`--dead-fraction` must be in [0, 1) [-], got {dead_fraction!r}")
    if reversal_delay is not None and not (math.isfinite(reversal_delay)
                                           and reversal_delay >= 0.0):
        raise ParameterError(f"`--reversal-delay` must be >= 0 [s], got {reversal_delay!r}")
    if hull is not None and hull not in _HULLS:
        raise ParameterError(f"`--hull` must be one of {', '.join(_HULLS)}, got {hull!r}")
    engine = {} if reversal_delay is None else {"reversal_delay": reversal_delay}
    if hull is not None:
        engine["hull_model"] = _HULLS[hull]
    stopper = stopping_ship(found, **engine)
    check_out(out, "stopping", ship_reads(ship))
    result = crash_stop(stopper, order=order, speed=speed, t_final=t_final, dt=dt,
                        dead_fraction=dead_fraction)
    payload = header(result)
    hull_of = {v: k for k, v in _HULLS.items()}
    payload.update(engine_order=order, dead_fraction=dead_fraction,
                   hull=hull_of.get(stopper.params.hull_model, "cross-flow"))
    finish(f"Stopping test, {stopper.name}, engine order {order:g}, rudder amidships", result,
           payload, STOPPING_FIELDS, plot_stopping, "stopping.png", out, json_out)
