"""``seahelm compensate``: wave-force coefficients, wave and wind loads and the compensating
rudder angle δ_k of Lvov (2014), eq. (5)-(14), for one ship and one sea.

Mounted by the main ``seahelm`` command as ``seahelm compensate``; usable on its own as the
typer app :data:`app` (its callback is the command: ``app --length 160 ...``).

Angles are given in degrees on the command line and are the bearings the wind and the waves
come *from*, relative to the bow (0 = head, 90 = from starboard, −90 = from port).

Two compensating angles are printed side by side: the paper's (eq. (12)/(14) as printed) and
the ship model's (the steady rudder angle that balances the same loads on the Voitkunsky
model, :func:`seahelm.studies.lvov2014.model_compensation`), which is the one the
compensated autopilot uses. The model's needs a ship model: ``--ship mariner`` (the Mariner's
particulars and its Voitkunsky model; any particular given explicitly overrides its value).
"""

from __future__ import annotations

import enum
import math
import warnings
from typing import Annotated, Any, Optional

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


class Ship(str, enum.Enum):
    """Ships with particulars and a Voitkunsky model (for the model-based δ_k)."""

    mariner = "mariner"


#: What the compensated autopilot takes as δ_k, and why (printed with the angles).
AUTOPILOT_NOTE = (
    "The compensated autopilot ('compensated-pid' in seahelm.studies.lvov2014."
    "wind_wave_scenario) uses the ship model's δ_k (delta_k_method='model'). The printed eq. "
    "(12)/(14) add the hull's drift moment to the wind's with the same sign, which gives the "
    "wrong sign on the Mariner; they are kept to reproduce the paper (delta_k_method='paper').")


@app.callback(invoke_without_command=True)
@handle_errors
def compensate(
    *,
    ship_name: Annotated[Optional[Ship], typer.Option(
        "--ship", help="A ship with particulars and a ship model: its values are the defaults "
        "of the options below, and the model gives the model-based δ_k.")] = None,
    length: Annotated[Optional[float], typer.Option(
        "--length", metavar="L", help="Waterline length L [m].")] = None,
    beam: Annotated[Optional[float], typer.Option(
        "--beam", metavar="B", help="Beam B [m].")] = None,
    draft: Annotated[Optional[float], typer.Option(
        "--draft", metavar="T", help="Mean draft T [m].")] = None,
    draft_fore: Annotated[Optional[float], typer.Option(
        "--draft-fore", metavar="TF", help="Draft forward [m] (eq. (13); default T).")] = None,
    draft_aft: Annotated[Optional[float], typer.Option(
        "--draft-aft", metavar="TA", help="Draft aft [m] (eq. (13); default T).")] = None,
    block_coefficient: Annotated[Optional[float], typer.Option(
        "--block-coefficient", metavar="CB", help="Block coefficient δ [-].")] = None,
    speed: Annotated[Optional[float], typer.Option(
        "--speed", metavar="V", help="Ship speed through the water [m/s].")] = None,
    wind_speed: Annotated[float, typer.Option(
        "--wind-speed", metavar="W", help="True wind speed [m/s] (also sets λ by eq. (2)).")],
    wind_angle: Annotated[float, typer.Option(
        "--wind-angle", metavar="DEG",
        help="Bearing the true wind comes from, relative to the bow [deg].")],
    wave_height: Annotated[float, typer.Option(
        "--wave-height", metavar="H", help="Wave height h3% [m].")],
    wave_angle: Annotated[float, typer.Option(
        "--wave-angle", metavar="DEG",
        help="Bearing the waves come from, relative to the bow, q_w [deg].")],
    wave_length: Annotated[Optional[float], typer.Option(
        "--wave-length", metavar="LAMBDA",
        help="Wave length λ [m] (default 1.55 τ², τ = 0.65·0.8·W, eq. (2)).")] = None,
    rudder_area: Annotated[Optional[float], typer.Option(
        "--rudder-area", metavar="SP",
        help="Rudder area S_p [m²] (default 1.7 % of L·T).")] = None,
    rudder_aspect_ratio: Annotated[Optional[float], typer.Option(
        "--rudder-aspect-ratio", metavar="LP",
        help="Rudder aspect ratio λ_p [-] (default 1.6).")] = None,
    windage_area: Annotated[Optional[float], typer.Option(
        "--windage-area", metavar="SA",
        help="Lateral windage area [m²] (default 0.8·L·T).")] = None,
    sail_centre: Annotated[Optional[float], typer.Option(
        "--sail-centre", metavar="M",
        help="Centre of windage forward of midships [m] (default 0).")] = None,
    a1: Annotated[float, typer.Option(
        "--a1", metavar="A1", help="Speed coefficient A1 ∈ [1, 8.5] of eq. (8)-(10).")] = 1.0,
    strict: Annotated[bool, typer.Option(
        "--strict",
        help="Outside the published validity ranges: fail (exit 2) instead of warning.")] = False,
    json_out: JsonFlag = False,
) -> None:
    """C_x^w, C_y^w, C_m^w, X_w, Y_w, M_w, the arm ℓ_w and δ_k (Lvov 2014).

    Forces are signed as in the paper (module docs of seahelm.environment.wave_forces):
    X_w positive forward, Y_w and M_w positive for waves from starboard.
    """
    from ..studies.lvov2014 import compensation_summary, model_compensation

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
    given = {"length": length, "beam": beam, "draft": draft, "draft_fore": draft_fore,
             "draft_aft": draft_aft, "block_coefficient": block_coefficient, "speed": speed,
             "rudder_area": rudder_area, "rudder_aspect_ratio": rudder_aspect_ratio,
             "windage_area": windage_area, "sail_centre": sail_centre}
    try:
        ship, vessel_params = _ship(ship_name, {k: v for k, v in given.items() if v is not None})
    except ParameterError as exc:  # in the user's words: the option, not the field
        raise ParameterError(str(exc).replace("`sail_centre`", "`--sail-centre`")) from None
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
    model = (model_compensation(s, ship=ship, vessel_params=vessel_params)
             if vessel_params is not None else None)
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
        "delta_k_model_wind_deg": None if model is None else math.degrees(model.delta_k_wind),
        "delta_k_model_wave_deg": None if model is None else math.degrees(model.delta_k_wave),
        "delta_k_model_deg": None if model is None else math.degrees(model.delta_k),
        "autopilot_delta_k": "model",
        "autopilot_note": AUTOPILOT_NOTE,
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
        if key in ("warnings", "autopilot_delta_k", "autopilot_note") or key.startswith(
                "delta_k"):
            continue
        unit = "deg" if key.endswith("_deg") else units.get(key, "-")
        table.add_row(key, f"{value:.6g}", unit)
    console.print(table)
    dk = Table(title="compensating rudder angle δ_k [deg]", title_justify="left")
    dk.add_column("channel")
    if model is not None:  # the autopilot's δ_k first: the one that steers right
        dk.add_column("ship model (the autopilot's)", justify="right")
    dk.add_column("paper, eq. (12)/(14)", justify="right")
    for label, key in (("wind (block 5)", "wind_"), ("waves (block 6)", "wave_"),
                       ("total δ_k", "")):
        paper, modelled = out[f"delta_k_{key}deg"], out[f"delta_k_model_{key}deg"]
        cells = [f"{paper:.4g}"] if modelled is None or model is None else [
            f"{modelled:.4g}", f"{paper:.4g}"]
        dk.add_row(label, *cells)
    console.print(dk)
    console.print(AUTOPILOT_NOTE if model is not None else
                  f"{AUTOPILOT_NOTE} The model's δ_k needs a ship model: --ship mariner.",
                  highlight=False)


def _ship(name: "Ship | None", given: dict[str, float]) -> tuple[Any, Any]:
    """The ship particulars (a named ship's, overridden by the options given, or the options
    alone) and the ship model's parameters (None without ``--ship``)."""
    from ..studies.lvov2014 import MARINER_PARTICULARS, ShipParticulars

    if name is not None:  # (one ship so far: the Mariner, whose Voitkunsky set is the default)
        from ..vessels.voitkunsky import MARINER_VOITKUNSKY

        return MARINER_PARTICULARS.replace(**given), MARINER_VOITKUNSKY
    for option, unit in (("length", "m"), ("beam", "m"), ("draft", "m"),
                         ("block_coefficient", "-"), ("speed", "m/s")):
        if option not in given:
            raise ParameterError(f"`--{option.replace('_', '-')}` [{unit}] is needed (or "
                                 "--ship mariner for the Mariner's particulars)")
    return ShipParticulars(**given), None
