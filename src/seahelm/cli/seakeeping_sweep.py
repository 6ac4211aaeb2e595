"""``seahelm seakeeping --sweep STORE``: the polar diagram of a time-domain sweep.

The cells of a sweep of first-order wave motions over wave heading × speed
(:func:`seahelm.sweep.seakeeping.sweep_seakeeping`): per cell the mean speed and heading, the
runs, the time-domain RMS with its standard error, the frequency-domain RMS of the same cells
and z = (m̂0 − m0)/se. Prints a table; ``--out DIR`` writes ``seakeeping-sweep.nc`` (every
dof, SI units) and ``seakeeping-sweep-<dof>.png`` (time domain beside frequency domain)
together; ``--json`` prints every cell. The sea, the ship and the speeds are the sweep's and the
statistic is the RMS: SHIP and every option but ``--dof``, ``--limit``, ``--out`` and ``--json``
(``--rao``, ``--hs``, ``--stat``, ``--exceed``, ...) are refused with it. Exit codes as the
command's.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from ._common import console, output_dir, print_json

__all__ = ["sweep_command", "NETCDF_NAME"]

#: The result file ``--out`` writes (the figure's name carries the dof).
NETCDF_NAME = "seakeeping-sweep.nc"


def _payload(store: Path, polar: Any, dof: str, factor: float, unit: str,
             limit: float | None) -> dict[str, Any]:
    rms, se = polar.rms(dof) * factor, polar.rms_standard_error(dof) * factor
    fd, z = polar.frequency_domain_rms(dof) * factor, polar.deviation(dof)

    def num(v: float) -> float | None:
        return float(v) if np.isfinite(v) else None

    cells = [{"speed_mps": float(polar.speed[i, j]),
              "heading_deg": math.degrees(float(polar.heading[i, j])),
              "runs": int(polar.n_runs[i, j]), f"rms_{unit}": float(rms[i, j]),
              f"rms_standard_error_{unit}": num(se[i, j]),
              f"significant_amplitude_{unit}": 2.0 * float(rms[i, j]),
              f"frequency_domain_rms_{unit}": num(fd[i, j]), "z": num(z[i, j])}
             for i, j in np.ndindex(*rms.shape)]
    payload: dict[str, Any] = {
        "store": str(store), "dof": dof, "unit": unit,
        "heading_key": polar.heading_key, "speed_key": polar.speed_key,
        "conventions": "heading 0 following, 180 head, 90 waves travelling to starboard; a "
                       "cell at its runs' mean surge speed and mean heading; rms = sqrt(mean "
                       "of the runs' mean squares), standard error sigma/sqrt(R)/(2 rms); z = "
                       "(time-domain m0 - frequency-domain m0)/its standard error",
        "cells": cells}
    if limit is not None:
        payload["limit"] = {"value": limit, "unit": unit, "cells_above": int(np.sum(rms > limit)),
                            "cells": int(rms.size)}
    return payload


def sweep_command(store: Path, *, dof: str, limit: float | None, out: Path | None,
                  json_out: bool) -> None:
    """Run ``seahelm seakeeping --sweep STORE`` (module docstring).

    Parameters
    ----------
    store : Path
        The sweep store.
    dof : str
        ``roll`` (first-order), ``pitch`` or ``heave``.
    limit : float or None
        A criterion on the RMS [deg or m], drawn and counted.
    out : Path or None
        Directory for the NetCDF and the figure.
    json_out : bool
        Print one JSON object.
    """
    from ..sweep.seakeeping import sweep_seakeeping
    from ..sweep.store import store_attrs

    if not store.exists():
        raise ParameterError(f"`--sweep`: no such sweep store: {store}")
    if store_attrs(store) is None:
        raise ParameterError(f"`--sweep`: {store} is not a sweep store of `seahelm sweep`")
    factor, unit = (1.0, "m") if dof == "heave" else (180.0 / math.pi, "deg")
    names = (NETCDF_NAME, f"seakeeping-sweep-{dof}.png")
    if out is not None:
        output_dir("--out", out, names, reads=(store,))
    polar = sweep_seakeeping(store)
    payload = _payload(store, polar, dof, factor, unit, limit)
    if out is not None:
        import matplotlib

        matplotlib.use("Agg", force=False)
        from ..plotting.save import save_figure
        from ..plotting.seakeeping import plot_sweep_polar
        from ..results import write_netcdf, write_together

        fig = plot_sweep_polar(polar, dof, limit=limit)
        with write_together():
            write_netcdf(polar.to_xarray(), out / names[0])
            save_figure(fig, out / names[1], dpi=100)
        payload["files"] = [str(out / n) for n in names]
    if json_out:
        print_json(payload)
        return
    table = Table(title=escape(f"first-order {dof} per cell of {store} (time domain ± se; "
                               "frequency domain; z)"), title_justify="left")
    for c in ("U [m/s]", "heading [deg]", "runs", f"RMS [{unit}]", f"± se [{unit}]",
              f"freq. domain [{unit}]", "z"):
        table.add_column(escape(c), justify="right")

    # round-off (sin π = 1.2e-16, roll in head seas): shown 0, without a z
    tiny = 1e-9 * max(c[f"rms_{unit}"] for c in payload["cells"])

    def shown(v: float | None, fmt: str = ".4g") -> str:
        return "-" if v is None else "0" if abs(v) <= tiny else format(v, fmt)

    for c in payload["cells"]:
        zero = c[f"rms_{unit}"] <= tiny
        table.add_row(f"{c['speed_mps']:.3g}", f"{c['heading_deg']:.4g}", str(c["runs"]),
                      shown(c[f"rms_{unit}"]), shown(c[f"rms_standard_error_{unit}"], ".2g"),
                      shown(c[f"frequency_domain_rms_{unit}"]),
                      "-" if zero else shown(c["z"], ".2f"))
    console.print(table)
    if "limit" in payload:
        lim = payload["limit"]
        console.print(escape(f"RMS {dof} above {lim['value']:g} {unit}: {lim['cells_above']} "
                             f"of {lim['cells']} cells"), highlight=False)
    for f in payload.get("files", []):
        console.print(f"wrote {escape(f)}", highlight=False)
