"""``seahelm run`` on a ``[maneuver]`` scenario: shown as ``seahelm maneuver``/``seahelm imo``
show the same manoeuvre."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from .imo import show_report
from .maneuver import (
    PULLOUT_FIELDS,
    ZIGZAG_FIELDS,
    check_out,
    finish,
    header,
    turning_fields,
)
from .spiral_output import show_spirals

__all__ = ["present_job"]


def _deg_text(value: Any) -> str:
    values = value if isinstance(value, (list, tuple)) else [value]
    return ", ".join(f"{math.degrees(v):g}" for v in values)


def present_job(job: Any, out: Path | None, as_json: bool, *, plot: bool = True,
                reads: tuple[Path, ...] = ()) -> None:
    """Run a ``[maneuver]`` scenario's :class:`~seahelm.scenario.ManeuverJob` and show it as
    the matching ``seahelm maneuver``/``seahelm imo`` command would (files with ``out``,
    figures unless ``plot`` is False; never over ``reads``, the files the command read)."""
    from ..plotting.maneuvers import plot_pullout, plot_stopping, plot_turning, plot_zigzag
    from .stopping import STOPPING_FIELDS

    if job.kind == "imo" and job.monte_carlo is not None:  # as `seahelm imo --monte-carlo`
        from .imo import present_imo_ensemble

        present_imo_ensemble(job, out, as_json, reads=reads)
        return
    check_out(out, job.kind, reads)
    result = job.run()
    name = job.ship.name
    opts = job.options
    if job.kind == "imo":
        show_report(result, out, as_json, plot=plot)
        return
    if job.kind == "spiral":
        show_spirals(job.title or f"Direct spiral, {name}", *result, out, as_json, plot=plot)
        return
    rudder = _deg_text(opts.get("rudder", math.radians(
        {"turning": 35.0, "zigzag": 10.0, "pullout": 20.0}.get(job.kind, 0.0))))
    kinds = {
        "turning": (f"Turning circle, {name}, {rudder} deg rudder", turning_fields(result),
                    plot_turning, "turning.png"),
        "zigzag": (f"Zig-zag, {name}, {rudder} deg rudder", ZIGZAG_FIELDS, plot_zigzag,
                   "zigzag.png"),
        "pullout": (f"Pull-out from {rudder} deg, {name}", PULLOUT_FIELDS, plot_pullout,
                    "pullout.png"),
        "stopping": (f"Stopping test, {name}, rudder amidships", STOPPING_FIELDS,
                     plot_stopping, "stopping.png"),
    }
    title, fields, draw, png = kinds[job.kind]
    payload = {"scenario": job.title or job.metadata.get("scenario_source", ""),
               **header(result)}
    drawn = job.draws(range(job.n_samples)) if job.n_samples > 1 else None
    finish(job.title or title, result, payload, fields, draw if plot else None, png, out,
           as_json, drawn)
