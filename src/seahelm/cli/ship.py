"""``seahelm ship``: the catalog's ships and ship files.

``seahelm ship list`` lists the catalog; ``seahelm ship show SHIP`` prints one ship (a catalog
name or a ship file): model, steering gear, propulsion, particulars, every parameter with its
unit and source, validity notes. ``--toml`` prints its ship file instead (``seahelm ship show
kvlcc2-l7 --toml > my.toml`` starts a ship of your own); ``--json`` one JSON object.
``seahelm ship check FILE`` reads a ship file and says whether it is valid. ``seahelm ship scale
SHIP --length L`` Froude-scales a ship (steering gear included) and prints its ship file.
Exit codes: 0, 2 bad input (one line naming the file, the key and the unit), 1 other failure.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Annotated, Any, Optional

import typer
from rich import box
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from ._common import ForceFlag, JsonFlag, OneLineErrors, console, handle_errors, print_json

__all__ = ["app"]

app = typer.Typer(cls=OneLineErrors, help="Ships: the catalog, and ship files (TOML).",
                  no_args_is_help=True)

ShipArg = Annotated[str, typer.Argument(
    metavar="SHIP", help="A catalog ship (`seahelm ship list`) or the path of a ship file.")]


@app.callback()
def _main() -> None:
    """Ships: the catalog, and ship files (TOML)."""


def _payload(ship: Any) -> dict[str, Any]:
    from ..ships.writing import ship_to_mapping

    data = ship_to_mapping(ship)
    data["test_speed"] = ship.test_speed
    data["parameters"] = [
        {"name": i.name, "value": getattr(ship.params, i.name), "unit": i.unit,
         "symbol": i.symbol, "doc": i.doc, "source": ship.source_of(i.name)}
        for i in ship.params.info()]
    return data


@app.command("list")
@handle_errors
def list_cmd(json_out: JsonFlag = False) -> None:
    """List the catalog's ships: name, model, steering gear, test speed, description."""
    from ..ships import CATALOG

    rows = [{"name": n, "model": s.model.name,
             "steering_gear": s.steering_gear.actuator.name if s.steering_gear else None,
             "test_speed_mps": s.test_speed, "description": s.description}
            for n, s in CATALOG.items()]
    if json_out:
        print_json({"ships": rows})
        return
    table = Table(title="catalog ships (seahelm ship show NAME)", title_justify="left",
                  box=box.SIMPLE_HEAD, pad_edge=False)
    wide = console.width >= 100  # (a description squeezed into 10 columns reads as noise)
    for col in ("name", "model", "steering gear", "U0 [m/s]"):
        table.add_column(escape(col), no_wrap=True)  # (whole names: they are what one types)
    if wide:
        table.add_column("description")
    for r in rows:
        speed = "" if r["test_speed_mps"] is None else f"{r['test_speed_mps']:.4g}"
        cells = [r["name"], r["model"], r["steering_gear"] or "-", speed]
        table.add_row(*cells, *([escape(r["description"])] if wide else []))
    console.print(table)
    if not wide:
        console.print("descriptions: `seahelm ship show NAME`, `--json`, or a terminal of 100 "
                      "columns or more", highlight=False)


@app.command("show")
@handle_errors
def show(
    ship: ShipArg,
    toml: Annotated[bool, typer.Option("--toml", help="Print the ship file (TOML) instead.")]
    = False,
    json_out: JsonFlag = False,
) -> None:
    """Print a ship: model, steering gear, propulsion, particulars, parameters, provenance."""
    if toml and json_out:
        raise ParameterError("give `--toml` or `--json`, not both")
    from ..ships import get_ship

    s = get_ship(ship)
    if toml:
        from ..ships import ship_to_toml

        sys.stdout.write(ship_to_toml(s))
        sys.stdout.flush()
        return
    payload = _payload(s)
    if json_out:
        print_json(payload)
        return
    _print(s, payload)


@app.command("check")
@handle_errors
def check(path: Annotated[str, typer.Argument(metavar="FILE", help="A ship file.")],
          json_out: JsonFlag = False) -> None:
    """Read a ship file and say whether it is valid (exit 2 naming the key if not)."""
    from ..ships import read_ship

    s = read_ship(path)
    if json_out:
        print_json({"file": path, "valid": True, "name": s.name, "model": s.model.name})
        return
    console.print(f"{escape(path)}: valid ship '{escape(s.name)}' (model {s.model.name})",
                  highlight=False, soft_wrap=True)


@app.command("scale")
@handle_errors
def scale(
    ship: ShipArg,
    length: Annotated[float, typer.Option(
        "--length", help="New length L [m]; the scale is lambda = L / the ship's length.")],
    rho: Annotated[Optional[float], typer.Option(
        "--rho", help="Water density of the scaled ship [kg/m³] (default: the ship's).")]
    = None,
    name: Annotated[Optional[str], typer.Option(
        "--name", help="Name of the scaled ship (default: NAME-L<length>).")] = None,
    out: Annotated[Optional[Path], typer.Option(
        "--out", help="Write the ship file here (atomically) instead of printing it.")] = None,
    force: ForceFlag = False,
) -> None:
    """Froude-scale a ship to another length and print (or write) its ship file.

    lambda = L_new/L_old: lengths x lambda, areas x lambda², volumes x lambda³, times and
    speeds x sqrt(lambda), rates (K, rudder rate, rps) / sqrt(lambda), masses and forces
    x lambda³; angles and non-dimensional coefficients unchanged; the steering gear too.
    """
    from ..ships import get_ship, ship_to_toml
    from ._common import output_file, write_ship_file

    source = get_ship(ship)
    if out is not None:
        output_file("--out", out, "toml", force=force,
                    reads=(Path(ship),) if Path(ship).is_file() else ())
    scaled = source.scaled(length, rho=rho, name=name)
    if out is None:
        sys.stdout.write(ship_to_toml(scaled))
        sys.stdout.flush()
        return
    write_ship_file(scaled, out)
    console.print(f"wrote {escape(str(out))}: ship '{escape(scaled.name)}', L = {length:g} m "
                  f"(lambda = {length / source.length:.6g})", highlight=False, soft_wrap=True)


def _print(ship: Any, payload: dict[str, Any]) -> None:
    head = Table(title=f"ship '{ship.name}'", title_justify="left", show_header=False)
    head.add_column("what")
    head.add_column("value")
    head.add_row("description", escape(ship.description or "-"))
    head.add_row("model", escape(f"{ship.model.name}: {ship.model.description}"))
    head.add_row("test speed", "-" if ship.test_speed is None else
                 escape(f"{ship.test_speed:.6g} [m/s]"))
    head.add_row("water depth", "deep" if not ship.in_shallow_water else escape(
        f"{ship.water_depth:.6g} [m] (parameters below corrected from the deep-water ones)"))
    if ship.steering_gear is not None:
        g = ship.steering_gear
        p = g.params
        text = g.actuator.name
        if hasattr(p, "max_angle"):
            text += (f": ±{math.degrees(p.max_angle):.4g} deg, "
                     f"{math.degrees(p.max_rate):.4g} deg/s, lag {p.time_constant:.4g} s")
        head.add_row("steering gear", escape(text))
    else:
        head.add_row("steering gear", "- (manoeuvres and the IMO check need one)")
    head.add_row("propulsion", "-" if ship.propulsion is None else escape(
        f"{ship.propulsion.kind} (inputs: {', '.join(ship.propulsion.inputs) or '-'})"))
    for note in ship.validity:
        head.add_row("valid for", escape(note))
    console.print(head)
    if ship.particulars is not None:
        from ..vessels.particulars import FIELD_UNITS

        part = Table(title="particulars", title_justify="left")
        for col in ("particular", "value", "unit"):
            part.add_column(col)
        for n, unit, _ in FIELD_UNITS:
            value = getattr(ship.particulars, n)
            if value is not None:
                part.add_row(n, value if isinstance(value, str) else f"{value:.6g}",
                             escape(f"[{unit}]") if unit else "")
        console.print(part)
    params = Table(title=f"parameters ({type(ship.params).__name__})", title_justify="left")
    for col in ("parameter", "symbol", "value", "unit", "description"):
        params.add_column(col)
    own = dict(ship.coefficient_sources)
    for row in payload["parameters"]:
        value = row["value"]
        text = (f"{len(value)} values" if isinstance(value, tuple) else f"{value:.6g}")
        doc = row["doc"] + (f" (source: {own[row['name']]})" if row["name"] in own else "")
        params.add_row(row["name"], row["symbol"], text,
                       escape(f"[{row['unit']}]") if row["unit"] else "", escape(doc))
    console.print(params)
    prov = Table(title="provenance", title_justify="left", show_header=False)
    prov.add_column("of")
    prov.add_column("source")
    for key, text in payload.get("provenance", {}).items():
        if isinstance(text, str):
            prov.add_row(key, escape(text))
    console.print(prov)




def _opt(*names: str, unit: str, text: str) -> Any:
    return typer.Option(*names, help=f"{text} [{unit}].", show_default=False)


@app.command("estimate")
@handle_errors
def estimate(
    particulars: Annotated[str | None, typer.Argument(
        metavar="[FILE]", help="A TOML file of particulars (keys as the options, with "
                               "underscores: length, beam, draft, block_coefficient, speed, "
                               "...; max_rudder_deg, rudder_rate_deg); options override it.")]
    = None,
    length: Annotated[float | None, _opt("--length", unit="m", text="Length between "
                                                                    "perpendiculars L_pp")] = None,
    beam: Annotated[float | None, _opt("--beam", unit="m", text="Moulded breadth B")] = None,
    draft: Annotated[float | None, _opt("--draft", unit="m", text="Mean draught T")] = None,
    draft_fore: Annotated[float | None, _opt("--draft-fore", unit="m",
                                             text="Draught at the fore perpendicular")] = None,
    draft_aft: Annotated[float | None, _opt("--draft-aft", unit="m",
                                            text="Draught at the aft perpendicular")] = None,
    block_coefficient: Annotated[float | None, _opt("--cb", "--block-coefficient", unit="-",
                                                    text="Block coefficient C_b")] = None,
    speed: Annotated[float | None, _opt("--speed", unit="m/s",
                                        text="Test (approach) speed U_0")] = None,
    displacement: Annotated[float | None, _opt("--displacement", unit="m³", text=(
        "Displacement volume (default C_b L B T)"))] = None,
    x_G: Annotated[float | None, _opt("--x-g", unit="m", text=(
        "Centre of gravity forward of midship (default 0)"))] = None,
    propeller_diameter: Annotated[float | None, _opt("--propeller-diameter", unit="m", text=(
        "Propeller diameter D_P (default 0.65 T)"))] = None,
    pitch_ratio: Annotated[float | None, _opt("--pitch-ratio", unit="-", text=(
        "Propeller pitch ratio P/D (default 0.8)"))] = None,
    area_ratio: Annotated[float | None, _opt("--area-ratio", unit="-", text=(
        "Expanded blade-area ratio A_E/A_0 (default 0.55)"))] = None,
    blades: Annotated[int | None, _opt("--blades", unit="-", text="Number of blades (default "
                                                                  "4)")] = None,
    rudder_area: Annotated[float | None, _opt("--rudder-area", unit="m²", text=(
        "Movable rudder area A_R (default DNV's minimum)"))] = None,
    rudder_span: Annotated[float | None, _opt("--rudder-span", unit="m", text=(
        "Rudder span H_R (default 0.75 T)"))] = None,
    max_rudder: Annotated[float | None, _opt("--max-rudder", unit="deg", text=(
        "Steering-gear angle limit (default 35)"))] = None,
    rudder_rate: Annotated[float | None, _opt("--rudder-rate", unit="deg/s", text=(
        "Steering-gear rate (default IMO's minimum 2.32)"))] = None,
    rho: Annotated[float | None, _opt("--rho", unit="kg/m³", text="Water density (default "
                                                                  "1025)")] = None,
    water_depth: Annotated[float | None, _opt("--depth", unit="m", text=(
        "Water depth h (default deep water)"))] = None,
    wetted_surface: Annotated[float | None, _opt("--wetted-surface", unit="m²", text=(
        "Wetted surface (default Holtrop's estimate)"))] = None,
    metacentric_height: Annotated[float | None, _opt("--gm", unit="m", text=(
        "Transverse metacentric height GM, kept in the particulars (the closed-form roll RAO; "
        "default unknown)"))] = None,
    vessel_type: Annotated[str | None, typer.Option("--vessel-type", help=(
        "Blendermann's (1994) vessel type (tanker-loaded, container-loaded, ...): with it the "
        "ship file gets its windage for the wind loads, what is not given of it estimated "
        "(tanker types only; the ship file says which) (default: no windage)."),
        show_default=False)] = None,
    hull_depth: Annotated[float | None, _opt("--hull-depth", unit="m", text=(
        "Moulded depth D, for the windage's freeboard D - T (default T/0.693, a loaded "
        "tanker's)"))] = None,
    length_overall: Annotated[float | None, _opt("--length-overall", unit="m", text=(
        "Length overall L_oa (windage; default 1.0156 L_pp)"))] = None,
    lateral_area: Annotated[float | None, _opt("--lateral-area", unit="m²", text=(
        "Lateral windage area A_L (default estimated for a tanker)"))] = None,
    frontal_area: Annotated[float | None, _opt("--frontal-area", unit="m²", text=(
        "Frontal windage area A_F (default estimated for a tanker)"))] = None,
    windage_centre: Annotated[float | None, _opt("--windage-centre", unit="m", text=(
        "Centre of A_L forward of midships s_L (default estimated; midships with both areas "
        "given)"))] = None,
    lcb: Annotated[float | None, typer.Option("--lcb", help=(
        "Longitudinal centre of buoyancy [% of L forward of midship] (default 0)."),
        show_default=False)] = None,
    name: Annotated[str | None, typer.Option("--name", help="The ship's name.",
                                             show_default=False)] = None,
    model: Annotated[str, typer.Option("--model", help=(
        "mmg (the full model), nomoto2 or nomoto1 (Clarke et al. 1983's linear hull with the "
        "estimated rudder)."))] = "mmg",
    out: Annotated[str | None, typer.Option("--out", "-o", metavar="FILE", help=(
        "Write the ship file here (default: print it)."), show_default=False)] = None,
    force: ForceFlag = False,
    strict: Annotated[bool, typer.Option("--strict", help=(
        "A regression used outside its data is an error, not a warning."))] = False,
) -> None:
    """Estimate a complete ship from its main particulars and write its ship file."""
    from pathlib import Path

    from ..errors import strict_validity
    from ..ships.estimate import Design, estimate_nomoto, estimate_ship
    from ..ships.writing import ship_to_toml
    from ._common import output_file, write_ship_file

    if model not in ("mmg", "nomoto1", "nomoto2"):
        raise ParameterError(f"must be mmg, nomoto2 or nomoto1, got '{model}'", field="model")
    given = {k: v for k, v in dict(
        length=length, beam=beam, draft=draft, draft_fore=draft_fore, draft_aft=draft_aft,
        block_coefficient=block_coefficient, speed=speed, displacement=displacement, x_G=x_G,
        propeller_diameter=propeller_diameter, pitch_ratio=pitch_ratio, area_ratio=area_ratio,
        blades=blades, rudder_area=rudder_area, rudder_span=rudder_span, rho=rho,
        water_depth=water_depth, wetted_surface=wetted_surface, lcb=lcb, name=name,
        metacentric_height=metacentric_height, vessel_type=vessel_type, hull_depth=hull_depth,
        length_overall=length_overall, lateral_area=lateral_area, frontal_area=frontal_area,
        windage_centre=windage_centre).items()
        if v is not None}
    for option, value, high in (("max_rudder", max_rudder, 90.0), ("rudder_rate", rudder_rate,
                                                                    math.inf)):
        if value is None:
            continue
        unit = "deg" if option == "max_rudder" else "deg/s"
        if not (math.isfinite(value) and 0 < value <= high):
            raise ParameterError(f"must be in (0, {high:g}] [{unit}], got {value!r}",
                                 field=option, unit=unit, value=value)
        given[option] = math.radians(value)
    values: dict[str, Any] = {}
    reads: tuple[Path, ...] = ()
    if particulars is not None:
        values = _particulars_file(particulars)
        reads = (Path(particulars),)
    target = None if out is None else output_file("--out", Path(out), "toml", reads=reads,
                                                  force=force)
    merged = {**values, **given}
    try:
        design = Design.from_mapping(merged)
        with strict_validity(strict) if strict else _nothing():
            ship = (estimate_ship(design) if model == "mmg"
                    else estimate_nomoto(design, order=int(model[-1])))
    except ParameterError as exc:
        key = (exc.field or "").partition(".")[0]
        if particulars is not None and key in values and key not in given:
            raise ParameterError(f"{particulars}: `{exc.field}` {exc.reason}") from None
        raise
    unstable = [v for v in ship.validity if v.startswith("course-unstable")]
    if target is None:
        sys.stdout.write(ship_to_toml(ship))
        sys.stdout.flush()
        if unstable:  # the ship file says so in `validity`; say it where a person reads it
            from ._common import err_console

            err_console.print(f"note: {escape(unstable[0])}", highlight=False, soft_wrap=True)
        return
    write_ship_file(ship, target)
    console.print(f"wrote {escape(str(target))}: ship '{escape(ship.name)}' (model "
                  f"{ship.model.name}"
                  + (f", {escape(unstable[0])}" if unstable else "")
                  + f"); `seahelm imo {escape(str(target))}` checks it",
                  highlight=False, soft_wrap=True)


def _nothing() -> Any:
    import contextlib

    return contextlib.nullcontext()


def _particulars_file(path: str) -> dict[str, Any]:
    """The particulars TOML file's keys (a ``[particulars]`` table or top-level keys)."""
    import tomllib
    from pathlib import Path

    p = Path(path)
    if not p.is_file():
        raise ParameterError(f"{path}: no such file" if not p.exists() else
                             f"{path}: not a regular file")
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError(f"{path}: not a TOML file ({exc})") from None
    if set(data) == {"particulars"} and isinstance(data["particulars"], dict):
        data = data["particulars"]
    return dict(data)
