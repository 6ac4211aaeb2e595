"""``seahelm linearize SHIP``: the linear model of a ship at an equilibrium and its steering indices.

Linearises the ship (catalog name or ship file) at its trimmed straight run at ``--speed``
(or at the steady turn at ``--rudder`` degrees) with
:func:`seahelm.analysis.equilibria.linearisation.linearize`, and prints Nomoto's K, T_1, T_2,
T_3, the first-order T, the course-stability index and lever (:mod:`seahelm.analysis.steering.indices`), the poles, and with ``--matrices``
the A, B, C, D of the ship with its steering gear (input ``rudder_command``). A model with roll
(Son & Nomoto's container ship) gets Nomoto's indices of its sway–yaw block with roll held
quasi-static, the poles of the whole block, and the size of the roll coupling. At a point
where the model has no derivative (the MMG ships' straight run: γ_R switches with the sign of
β_R) it prints both one-sided linearisations, which of them is course stable and why, never
their mean (``--json``: ``smooth: false``, ``kinks``, ``why``, ``one_sided``). ``--json`` prints
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
    from ..analysis.equilibria.linearisation import linearize as _linearize
    from ..analysis.steering.indices import steering_indices
    from ..errors import ParameterError
    from ..ships import get_ship

    for option, value, unit in (("--speed", speed, "m/s"), ("--rps", rps, "1/s")):
        if value is not None and not (math.isfinite(value) and value > 0):
            what = "> 0" if math.isfinite(value) else "a finite number > 0"
            raise ParameterError(f"must be {what} [{unit}], got {value!r}", field=option,
                                 unit=unit, value=value)
    if rudder is not None and not (math.isfinite(rudder) and abs(rudder) < 90):
        raise ParameterError(f"must be in (-90, 90) [deg], got {rudder!r}", field="--rudder",
                             unit="deg", value=rudder)
    the_ship = get_ship(ship)
    if rps is not None and rudder is None:  # (the straight run's rps follows from --speed)
        raise ParameterError(f"= {rps!r} [1/s] is the propeller rps of the steady turn at "
                             "`--rudder`; give `--rudder` too (the straight run's rps follows "
                             "from `--speed`)", field="--rps", unit="1/s", value=rps)
    delta = None if rudder is None else math.radians(rudder)
    bare = _linearize(the_ship, speed=speed, rudder=delta, rps=rps, actuator=False)
    full = _linearize(the_ship, speed=speed, rudder=delta, rps=rps, actuator=True)
    try:
        if not bare.smooth:
            _kinked(the_ship.name, bare, full, json_out, matrices)
            return
        indices = steering_indices(bare)
    except ParameterError as exc:  # (either side of a kink too: the same words)
        if exc.field != "model":
            raise
        # said about what the user chose: the straight run at --speed (and --rudder, --rps)
        at = (f"`--speed` {bare.speed:.4g} m/s" + (f", `--rudder` {rudder:g} deg"
                                                   if rudder is not None else ""))
        test = getattr(the_ship, "test_speed", None)
        hint = f" (its test speed is {test:.4g} m/s)" if test else ""
        raise ParameterError(
            f"{at}: the ship's linear model there has no Nomoto form ({exc.reason}); give a "
            f"speed at which the ship moves and is straight-line stable{hint}") from None
    payload: dict[str, Any] = {
        "ship": the_ship.name, "operating_point": bare.name, "speed_mps": bare.speed,
        "length_m": bare.length, "rudder_deg": _rudder_deg(bare),
        "indices": indices.as_dict(),
        "linear_model": _matrices(full),
        "max_error": _max_error(full),
    }
    if json_out:
        print_json(payload)
        return
    _print_indices(f"{bare.name}: U = {bare.speed:.4g} m/s, rudder "
                   f"{payload['rudder_deg']:.3g} deg", indices)
    if matrices:
        _print_matrices(full, payload["max_error"])


def _rudder_deg(lin: Any) -> float:
    return math.degrees(float(lin.u0[lin.input_labels.index("rudder_angle")]))


def _max_error(lin: Any) -> dict[str, float]:
    return {k: float(np.max(v, initial=0.0)) for k, v in lin.error.items()}


def _print_indices(title: str, indices: Any) -> None:
    from ..analysis.steering.indices import ROLL_STATES

    n = indices.nomoto
    table = Table(title=escape(title), title_justify="left")
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


def _print_matrices(full: Any, max_error: dict[str, float]) -> None:
    for key, rows_, cols in (("A", full.state_labels, full.state_labels),
                             ("B", full.state_labels, full.input_labels),
                             ("C", full.output_labels, full.state_labels),
                             ("D", full.output_labels, full.input_labels)):
        console.print(_matrix_table(f"{key} (max. est. error {max_error[key]:.2g})",
                                    getattr(full, key), rows_, cols))


def _kinked(ship: str, bare: Any, full: Any, json_out: bool, matrices: bool) -> None:
    """A non-smooth point: both one-sided linearisations, which is stable, and why; never the
    central difference (their mean)."""
    from ..analysis.steering.indices import steering_indices

    sides = []
    for b, f in zip(bare.sides, full.sides):
        ind = steering_indices(b)
        sides.append({"side": b.side, "indices": ind.as_dict(), "linear_model": _matrices(f),
                      "max_error": _max_error(f), "_ind": ind, "_full": f})
    stable = [s["side"] for s in sides if s["indices"]["course_stable"]]
    payload: dict[str, Any] = {
        "ship": ship, "operating_point": bare.name, "speed_mps": bare.speed,
        "length_m": bare.length, "rudder_deg": _rudder_deg(bare), "smooth": False,
        "kinks": list(bare.kinks), "why": bare.note, "indices": None, "linear_model": None,
        "one_sided": [{k: v for k, v in s.items() if not k.startswith("_")} for s in sides],
        "course_stable_sides": stable,
    }
    if json_out:
        print_json(payload)
        return
    console.print(escape(f"{bare.name}: no single linear model here; {bare.note}. The two "
                         "one-sided linearisations follow (their mean, which a central "
                         "difference gives, is a model of neither side)."),
                  highlight=False, soft_wrap=True)
    for s in sides:
        _print_indices(f"side {s['side']}: U = {bare.speed:.4g} m/s, rudder "
                       f"{payload['rudder_deg']:.3g} deg", s["_ind"])
        if matrices:
            _print_matrices(s["_full"], s["max_error"])
    verdict = ("course stable on side " + " and ".join(stable) + " only" if len(stable) == 1
               else "course stable on both sides" if stable else "course unstable on both sides")
    console.print(escape(f"  {verdict}: small motions about this point switch between the two "
                         "linear models."), highlight=False, soft_wrap=True)
