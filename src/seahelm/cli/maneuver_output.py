"""What every manoeuvre command writes and prints around its table: the header of a result
(ship, L, approach speed, rps, step), its files (NetCDF and figure, written together) and the
cell format. Shared by ``seahelm maneuver``'s commands, the spiral's output and ``seahelm imo``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from rich.markup import escape

from ..plotting.maneuver_runs import ship_names

__all__ = ["header", "write_outputs"]


def _fmt(value: Any) -> str:
    """A cell: yes/no, a number in 4 significant digits ("—" if not finite), or text."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return "—" if not math.isfinite(value) else f"{value:.4g}"
    return escape(str(value))


def header(result: Any) -> dict[str, Any]:
    """Ship, L, approach speed, rps, dt of a result (command-line units)."""
    m = result.metrics
    first = {d: 0 for d in m["complete"].dims}
    sel = m.isel(first)
    out: dict[str, Any] = {"maneuver": result.maneuver,
                           "ship": ship_names([s.name for s in result.ships]),
                           "length_m": float(sel["length"])}
    for key, name in (("approach_speed_value", "approach_speed_mps"),
                      ("propeller_rps", "propeller_rps")):
        values = np.asarray(m[key].values, dtype=float) if key in m else np.array([np.nan])
        if np.isfinite(values).all() and np.ptp(values) == 0.0:  # (else: per run, in the rows)
            out[name] = float(values.flat[0])
    for key in ("dt", "t_final", "hold"):
        if key in m.attrs:
            out[f"{key}_s"] = float(m.attrs[key])
    return out


def write_outputs(out: Path, results: Sequence[Any], plot: Callable[[], Any] | None,
                  png: str) -> dict[str, str]:
    """NetCDF of every result and one PNG (none if ``plot`` is None), atomically and together
    (all appear, or none); returns {kind: path}."""
    from ..results import write_together

    files: dict[str, str] = {}
    with write_together():  # all of them, or none (a full disk leaves no lone metrics file)
        for result in results:
            for kind, path in result.to_netcdf(out).items():
                files[f"{result.maneuver}-{kind}"] = str(path)
        if plot is not None:
            import matplotlib

            matplotlib.use("Agg")
            from ..plotting.save import save_figure

            files["plot"] = str(save_figure(plot(), out / png))
    return files
