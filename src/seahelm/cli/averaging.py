"""``seahelm averaging``: full averaging of the CPP ship in waves (Platonov & Platonova).

Mounted by the main ``seahelm`` command as ``seahelm averaging``; usable on its own as the
typer app :data:`app`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

import typer

from ._common import (
    ForceFlag,
    JsonFlag,
    OneLineErrors,
    check_figure_suffix,
    console,
    err_console,
    handle_errors,
    output_file,
    print_json,
)

#: Largest --grid: N × N/2 directions, each a support-function evaluation (2,000: 2e6).
MAX_GRID = 2000

app = typer.Typer(
    cls=OneLineErrors,
    help="Full averaging of a controllable-pitch-propeller ship in waves and its admissible "
    "control set (Platonov & Platonova).",
    no_args_is_help=True,
)


@app.callback()
def _main() -> None:
    """Full averaging and admissible control sets."""


@app.command("cpp")
@handle_errors
def cpp(
    immersion: Annotated[float, typer.Option(
        "--immersion", metavar="H0_OVER_R",
        help="Propeller immersion h0/R at zero pitch angle, in propeller radii.")] = 1.2,
    amplitude: Annotated[float, typer.Option(
        "--amplitude", metavar="EPSI0_OVER_R",
        help="Vertical oscillation amplitude eψ0/R of the propeller, in propeller radii.")] = 0.96,
    grid: Annotated[int, typer.Option(
        "--grid", metavar="N",
        help="Directions: N azimuths × N/2 elevations on the unit sphere (eq. (17)).")] = 200,
    plot: Annotated[Optional[Path], typer.Option(
        "--plot", metavar="FILE.png", help="Draw V and Y (Figs. 1 and 2) to this file.")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """β1, β2, β3, the boundary of V and the Hausdorff distances of the flat sets Y to V.

    Defaults give the paper's α(τ) = 0.5 − 0.4 sin τ.
    """
    from ..studies.platonov.flat_set import cpp_admissible_set
    from ..errors import ParameterError

    if not 6 <= grid <= MAX_GRID:
        raise ParameterError(f"`--grid` must be in [6, {MAX_GRID}] [directions], got {grid}")
    if plot is not None:  # checked before any work
        output_file("--plot", plot, "figure", force=force)
        check_figure_suffix("--plot", plot)
    result = cpp_admissible_set(immersion, amplitude, n_azimuth=grid, n_elevation=grid // 2)
    summary = result.summary()
    if plot is not None:
        from ..studies.platonov.figures import plot_control_sets
        from ..plotting.save import save_figure

        written = save_figure(plot_control_sets(result), plot, dpi=120)
        summary["plot"] = str(written)
        (err_console if json_out else console).print(f"wrote {written}", highlight=False)
    if json_out:
        print_json(summary)
        return
    b1, b2, b3 = result.betas
    console.print(
        f"α(τ) = {immersion / 2.4:.4g} − {amplitude / 2.4:.4g} sin τ, "
        f"{result.grid_points} directions", highlight=False,
    )
    console.print(f"β1 = ⟨c1²/c2⟩ = {b1:.5f}   β2 = ⟨c1⟩ = {b2:.5f}   β3 = ⟨c2⟩ = {b3:.5f}",
                  highlight=False)
    console.print(f"Hausdorff(V, Y hull of the arc)   = {result.hausdorff_V_Y:.5f}",
                  highlight=False)
    console.print(f"Hausdorff(V, Y printed eq. (24))  = {result.hausdorff_V_Y_printed:.5f}",
                  highlight=False)
    console.print(f"width of V across (1, −1, 0)/√2   = {result.width:.5f}", highlight=False)
