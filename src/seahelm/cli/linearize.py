"""``seahelm linearize SHIP``: the linear model of a ship at an equilibrium and its steering indices.

Linearises the ship (catalog name or ship file) at its trimmed straight run at ``--speed``
(or at the steady turn at ``--rudder`` degrees) with :func:`seahelm.analysis.linearisation.
linearize`, and prints Nomoto's K, T_1, T_2, T_3, the first-order T, the course-stability
index and lever (:mod:`seahelm.analysis.steering_indices`), the poles, and with ``--matrices``
the A, B, C, D of the ship with its steering gear (input ``rudder_command``). A model with roll
(Son & Nomoto's container ship) gets Nomoto's indices of its sway–yaw block with roll held
quasi-static, the poles of the whole block, and the size of the roll coupling. ``--json`` prints
one JSON object (the matrices always, with their row and column names and units). Exit codes:
0 done, 2 bad input (no equilibrium at that speed or rudder, a speed the model does not admit),
1 other failure.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from ._common import JsonFlag, console, handle_errors, print_json

__all__ = ["linearize"]

_SHIP_HELP = ("Ship: a catalog name (`seahelm ship list`) or the path of a ship file (*.toml).")


def _matrix_table(title: str, M: np.ndarray, rows: tuple[str, ...], cols: tuple[str, ...]
                  ) -> Table:
    table = Table(title=escape(title), title_justify="left")
    table.add_column("")
    for c in cols:
        table.add_column(escape(c), justify="right")
    for name, row in zip(rows, M):
        table.add_row(escape(name), *(f"{v:.4g}" for v in row))
    return table


def _matrices(lin: Any) -> dict[str, Any]:
    out = lin.to_numpy()
    return {k: (v.tolist() if isinstance(v, np.ndarray) else list(v)) for k, v in out.items()}


@handle_errors
def linearize(
    ship: Annotated[str, typer.Argument(metavar="SHIP", help=_SHIP_HELP)],
    speed: Annotated[float | None, typer.Option(
        "--speed", help="Speed U of the straight run [m/s] (default: the ship's test "
                    "speed).")] = None,
    rudder: Annotated[float | None, typer.Option(
        "--rudder", help="Linearise at the steady turn at this rudder angle [deg] "
                     "instead of the straight run.")] = None,
    rps: Annotated[float | None, typer.Option(
        "--rps", help="Propeller rps of the turn [1/s] (default: the straight run's).")
    ] = None,
    matrices: Annotated[bool, typer.Option(
        "--matrices", help="Also print A, B, C, D (ship with steering gear).")] = False,
    json_out: JsonFlag = False,
) -> None:
    """Linearise a ship at an equilibrium: Nomoto K, T1, T2, T3, T and course stability."""
    from ..analysis.linearisation import linearize as _linearize
    from ..analysis.steering_indices import ROLL_STATES, steering_indices
    from ..errors import ParameterError
    from ..ships import get_ship

    for option, value, unit in (("--speed", speed, "m/s"), ("--rps", rps, "1/s")):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=option,
                                 unit=unit, value=value)
    if rudder is not None and not (math.isfinite(rudder) and abs(rudder) < 90):
        raise ParameterError(f"must be in (-90, 90) [deg], got {rudder!r}", field="--rudder",
                             unit="deg", value=rudder)
    the_ship = get_ship(ship)
    delta = None if rudder is None else math.radians(rudder)
    bare = _linearize(the_ship, speed=speed, rudder=delta, rps=rps, actuator=False)
    full = _linearize(the_ship, speed=speed, rudder=delta, rps=rps, actuator=True)
    indices = steering_indices(bare)
    payload: dict[str, Any] = {
        "ship": the_ship.name, "operating_point": bare.name, "speed_mps": bare.speed,
        "length_m": bare.length, "rudder_deg": math.degrees(
            float(bare.u0[bare.input_labels.index("rudder_angle")])),
        "indices": indices.as_dict(),
        "linear_model": _matrices(full),
        "max_error": {k: float(np.max(v, initial=0.0)) for k, v in full.error.items()},
    }
    if json_out:
        print_json(payload)
        return
    n = indices.nomoto
    table = Table(title=escape(f"{bare.name}: U = {bare.speed:.4g} m/s, rudder "
                               f"{payload['rudder_deg']:.3g} deg"), title_justify="left")
    for col in ("index", "value", "unit"):
        table.add_column(col, justify="right" if col == "value" else "left")
    rows = [("Nomoto K", n.gain, "1/s"), ("T1", n.t1, "s"), ("T2", n.t2, "s"),
            ("T3", n.t3, "s"), ("T = T1 + T2 - T3", n.time_constant, "s"),
            ("stability index sigma1' = -L/(U T1)", indices.stability_index, "-"),
            ("stability lever sigma1' sigma2'", indices.stability_lever, "-"),
            ("surge coupling (dropped)", indices.surge_coupling, "-")]
    if set(ROLL_STATES) & set(indices.steering_states):  # Nomoto's form of the heeled ship
        rows.append(("roll coupling (roll quasi-static)", indices.roll_coupling, "-"))
    for name, value, unit in rows:
        table.add_row(escape(name), f"{value:.5g}", unit)
    console.print(table)
    verdict = "course stable" if indices.course_stable else "course UNSTABLE"
    console.print(escape(f"  {verdict}; poles of {', '.join(indices.steering_states)}: "
                         + ", ".join(f"{p.real:.4g}" + (f"{p.imag:+.4g}j" if p.imag else "")
                                     for p in indices.poles) + " [1/s]"), highlight=False)
    if matrices:
        for key, rows_, cols in (("A", full.state_labels, full.state_labels),
                                 ("B", full.state_labels, full.input_labels),
                                 ("C", full.output_labels, full.state_labels),
                                 ("D", full.output_labels, full.input_labels)):
            console.print(_matrix_table(f"{key} (max. est. error "
                                        f"{payload['max_error'][key]:.2g})",
                                        getattr(full, key), rows_, cols))
