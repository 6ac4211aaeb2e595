"""``seahelm fmu SHIP -o ship.fmu``: an FMI 2.0 co-simulation FMU of a ship (pythonfmu).

Inputs the ship's commands (``rudder_command`` [rad], ``propeller_rps`` [1/s]), outputs
position, heading, speeds, yaw rate and rudder angle, with units and start values; parameters:
initial position and heading, integration step, wind (:mod:`seahelm.fmu.slave`). Exit codes: 0,
2 bad input (a ship without a steering gear, an output that may not be written or is not named
.fmu), 1 other.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.markup import escape

from ..errors import ParameterError
from ._common import ForceFlag, console, handle_errors

__all__ = ["fmu"]


@handle_errors
def fmu(
    ship: Annotated[str, typer.Argument(
        metavar="SHIP", help="A catalog ship (`seahelm ship list`) or a ship file, with a "
        "steering gear.")],
    out: Annotated[Path, typer.Option(
        "-o", "--out", help="The FMU to write (.fmu).")],
    force: ForceFlag = False,
) -> None:
    """Write an FMI 2.0 co-simulation FMU of SHIP (run it with fmpy, OSP libcosim, ...)."""
    from ..fmu import build_fmu
    from ._common import output_file

    reads = (Path(ship),) if Path(ship).is_file() else ()
    output_file("--out", out, "fmu", force=force, reads=reads)
    if out.suffix.lower() != ".fmu":  # (an FMU is a zip an importer finds by its suffix)
        raise ParameterError(f"`--out` must name an .fmu file, got {str(out)!r}"
                             + (f" (suffix {out.suffix!r})" if out.suffix else " (no suffix)"))
    path = build_fmu(ship, out, force=True, reads=reads, option="--out",
                     force_word="--force")
    console.print(f"wrote {escape(str(path))}: FMI 2.0 co-simulation FMU of {escape(ship)} "
                  f"({path.stat().st_size / 1e3:.0f} kB; the Python that runs it needs "
                  "seahelm)", highlight=False)
