"""``seahelm compensate``: wave-force coefficients, wave and wind loads and the compensating
rudder angle δ_k of Lvov (2014), eq. (5)-(14), for one ship and one sea.

Mounted by the main ``seahelm`` command as ``seahelm compensate``; usable on its own as the
typer app :data:`app` (its callback is the command: ``app --length 160 ...``).

Angles are given in degrees on the command line and are the bearings the wind and the waves
come *from*, relative to the bow (0 = head, 90 = from starboard, −90 = from port).
"""

from __future__ import annotations

import math
import warnings
from typing import Annotated, Optional

import typer

from ..errors import ParameterError
from ._common import (
    JsonFlag,
    OneLineErrors,
    console,
    err_console,
    handle_errors,
    print_json,
)

#: A compensating angle beyond this [rad] no steering gear can give (35° is the usual limit).
RUDDER_LIMIT = math.radians(35.0)

app = typer.Typer(
    cls=OneLineErrors,
    help="Wave and wind loads on the hull and the compensating rudder angle δ_k "
    "(Lvov 2014, eq. (5)-(14)).",
    no_args_is_help=True,
)


@app.callback(invoke_without_command=True)
@handle_errors
def compensate(
    *,
    length: Annotated[float, typer.Option(
        "--length", metavar="L", help="Waterline length L \\[m].")],
    beam: Annotated[float, typer.Option("--beam", metavar="B", help="Beam B \\[m].")],
    draft: Annotated[float, typer.Option("--draft", metavar="T", help="Mean draft T \\[m].")],
    draft_fore: Annotated[Optional[float], typer.Option(
        "--draft-fore", metavar="TF", help="Draft forward \\[m] (eq. (13); default T).")] = None,
    draft_aft: Annotated[Optional[float], typer.Option(
        "--draft-aft", metavar="TA", help="Draft aft \\[m] (eq. (13); default T).")] = None,
    block_coefficient: Annotated[float, typer.Option(
        "--block-coefficient", metavar="CB", help="Block coefficient δ \\[-].")],
    speed: Annotated[float, typer.Option(
        "--speed", metavar="V", help="Ship speed through the water \\[m/s].")],
    wind_speed: Annotated[float, typer.Option(
        "--wind-speed", metavar="W", help="True wind speed \\[m/s] (also sets λ by eq. (2)).")],
    wind_angle: Annotated[float, typer.Option(
        "--wind-angle", metavar="DEG",
        help="Bearing the true wind comes from, relative to the bow \\[deg].")],
    wave_height: Annotated[float, typer.Option(
        "--wave-height", metavar="H", help="Wave height h3% \\[m].")],
    wave_angle: Annotated[float, typer.Option(
        "--wave-angle", metavar="DEG",
        help="Bearing the waves come from, relative to the bow, q_w \\[deg].")],
    wave_length: Annotated[Optional[float], typer.Option(
        "--wave-length", metavar="LAMBDA",
        help="Wave length λ \\[m] (default 1.55 τ², τ = 0.65·0.8·W, eq. (2)).")] = None,
    rudder_area: Annotated[Optional[float], typer.Option(
        "--rudder-area", metavar="SP",
        help="Rudder area S_p \\[m²] (default 1.7 % of L·T).")] = None,
    rudder_aspect_ratio: Annotated[float, typer.Option(
        "--rudder-aspect-ratio", metavar="LP", help="Rudder aspect ratio λ_p \\[-].")] = 1.6,
    windage_area: Annotated[Optional[float], typer.Option(
        "--windage-area", metavar="SA",
        help="Lateral windage area \\[m²] (default 0.8·L·T).")] = None,
    sail_centre: Annotated[float, typer.Option(
        "--sail-centre", metavar="M", help="Centre of windage forward of midships \\[m].")] = 0.0,
    a1: Annotated[float, typer.Option(
        "--a1", metavar="A1", help="Speed coefficient A1 ∈ \\[1, 8.5] of eq. (8)-(10).")] = 1.0,
    strict: Annotated[bool, typer.Option(
        "--strict",
        help="Outside the published validity ranges: fail (exit 2) instead of warning.")] = False,
    json_out: JsonFlag = False,
) -> None:
    """C_x^w, C_y^w, C_m^w, X_w, Y_w, M_w, the arm ℓ_w and δ_k (Lvov 2014).

    Forces are signed as in the paper (module docs of seahelm.environment.wave_forces):
    X_w positive forward, Y_w and M_w positive for waves from starboard.
    """
    from ..control.compensation import ShipParticulars, compensation_summary

    # every number finite, named as the user wrote it (the library names its own parameters)
    for option, value, unit in (
            ("--length", length, "m"), ("--beam", beam, "m"), ("--draft", draft, "m"),
            ("--draft-fore", draft_fore, "m"), ("--draft-aft", draft_aft, "m"),
            ("--block-coefficient", block_coefficient, "-"), ("--speed", speed, "m/s"),
            ("--wind-speed", wind_speed, "m/s"), ("--wind-angle", wind_angle, "deg"),
            ("--wave-height", wave_height, "m"), ("--wave-angle", wave_angle, "deg"),
            ("--wave-length", wave_length, "m"), ("--rudder-area", rudder_area, "m²"),
            ("--rudder-aspect-ratio", rudder_aspect_ratio, "-"),
            ("--windage-area", windage_area, "m²"), ("--sail-centre", sail_centre, "m"),
            ("--a1", a1, "-")):
        if value is not None and not math.isfinite(value):
            raise ParameterError(f"`{option}` must be a finite number [{unit}], got {value!r}")
    for option, value, unit in (("--rudder-area", rudder_area, "m²"),
                                ("--windage-area", windage_area, "m²"),
                                ("--draft-fore", draft_fore, "m"), ("--draft-aft", draft_aft, "m")):
        if value is not None and not (math.isfinite(value) and value > 0):
            # (0 would mean "not given" below: the empirical default)
            raise ParameterError(f"`{option}` must be > 0 [{unit}], got {value!r}")
    ship = ShipParticulars(
        length=length, beam=beam, draft=draft,
        draft_fore=draft_fore if draft_fore is not None else 0.0,
        draft_aft=draft_aft if draft_aft is not None else 0.0,
        block_coefficient=block_coefficient, speed=speed,
        rudder_area=rudder_area if rudder_area is not None else 0.0,
        rudder_aspect_ratio=rudder_aspect_ratio,
        windage_area=windage_area if windage_area is not None else 0.0,
        sail_centre=sail_centre,
    )
    if (draft_fore is None) != (draft_aft is None):
        raise ParameterError("give both `--draft-fore` and `--draft-aft` [m], or neither")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        s = compensation_summary(
            ship, wind_speed=wind_speed, wind_angle=math.radians(wind_angle),
            wave_height=wave_height, wave_angle=math.radians(wave_angle),
            wave_length=wave_length, a1=a1, strict=True if strict else None,
        )
    notes = [str(w.message) for w in caught]
    for name, value in (("delta_k_wind", s.delta_k_wind), ("delta_k_wave", s.delta_k_wave),
                        ("delta_k", s.delta_k)):
        if abs(value) > RUDDER_LIMIT:  # no steering gear gives it: the formulas are past use
            if strict:
                raise ParameterError(f"{name} = {math.degrees(value):.4g} deg is beyond any "
                                     f"rudder's {math.degrees(RUDDER_LIMIT):g} deg (--strict)")
            notes.append(f"{name} = {math.degrees(value):.4g} deg is beyond any rudder's "
                         f"{math.degrees(RUDDER_LIMIT):g} deg: the loads are outside the range "
                         "where a compensating rudder angle means anything")
    for note in notes:
        err_console.print(f"[yellow]warning:[/] {note}", highlight=False, soft_wrap=True)
    out = {
        "Cx": s.cx, "Cy": s.cy, "Cm": s.cm,
        "X_w": s.surge, "Y_w": s.sway, "M_w": s.yaw, "arm": s.arm,
        "wave_length": s.wave_length, "wave_celerity": s.wave_celerity,
        "apparent_wind_speed": s.apparent_wind_speed,
        "apparent_wind_angle_deg": math.degrees(s.apparent_wind_angle),
        "wind_force": s.wind_force, "wind_moment": s.wind_moment,
        "wind_drift_deg": math.degrees(s.wind_drift), "wave_drift_deg": math.degrees(s.wave_drift),
        "lateral_resistance_centre": s.resistance_centre,
        "delta_k_wind_deg": math.degrees(s.delta_k_wind),
        "delta_k_wave_deg": math.degrees(s.delta_k_wave),
        "delta_k_deg": math.degrees(s.delta_k),
        "warnings": notes,
    }
    if json_out:
        print_json(out)
        return
    from rich.table import Table

    units = {"X_w": "N", "Y_w": "N", "M_w": "N·m", "arm": "m", "wave_length": "m",
             "wave_celerity": "m/s", "apparent_wind_speed": "m/s", "wind_force": "N",
             "wind_moment": "N·m"}
    table = Table(title="Lvov (2014): wave and wind loads, compensating rudder angle")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    for key, value in out.items():
        if key == "warnings":
            continue
        unit = "deg" if key.endswith("_deg") else units.get(key, "-")
        table.add_row(key, f"{value:.6g}", unit)
    console.print(table)
