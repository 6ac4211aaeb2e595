"""``seahelm models``: the registered vessel models, actuators and controllers, their
parameters (units, defaults) and signals, and the catalog's ships."""
from __future__ import annotations

from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from ._common import JsonFlag, console, handle_errors, print_json

__all__ = ["models"]


@handle_errors
def models(
    names: Annotated[list[str] | None, typer.Argument(
        metavar="[NAME]...", show_default=False,
        help="Show these in full: parameters with units and defaults, signals (a vessel "
             "model, actuator or controller, e.g. mmg, rudder-servo, pid-heading).")] = None,
    full: Annotated[bool, typer.Option(
        "--all", help="Show every component in full (a long listing).")] = False,
    json_out: JsonFlag = False,
) -> None:
    """List the registered vessel models, actuators and controllers with their parameters.

    Without NAME, one line per component and the catalog's ships; `seahelm models NAME`
    gives a component's parameters (units, defaults) and signals; --json gives them all.
    """
    from ..registry import (
        ACTUATORS,
        CONTROLLERS,
        VESSEL_MODELS,
        controller_signals,
        get_actuator,
        get_controller,
        get_model,
    )
    from ..ships import CATALOG

    payload: dict[str, Any] = {}
    for kind, table, getter in (("vessel_models", VESSEL_MODELS, get_model),
                                ("actuators", ACTUATORS, get_actuator),
                                ("controllers", CONTROLLERS, get_controller)):
        payload[kind] = {}
        for name in sorted(table):
            comp = getter(name)
            payload[kind][name] = {
                "description": comp.description,
                "parameters": [
                    {"name": i.name, "unit": i.unit, "symbol": i.symbol, "default": i.default,
                     "doc": i.doc}
                    for i in comp.params_type.info()
                ],
            }
            signals = controller_signals(comp) if kind == "controllers" else comp.signals()
            payload[kind][name]["signals"] = [
                {"kind": k, "name": n, "unit": u} for k, n, u in signals]
            if getattr(comp, "passthrough", False):
                payload[kind][name]["passthrough"] = True
    payload["catalog"] = {n: {"model": e.model.name, "provenance": e.provenance}
                          for n, e in sorted(CATALOG.items())}
    if names:
        kinds = ("vessel_models", "actuators", "controllers")
        known = [n for kind in kinds for n in payload[kind]]
        unknown = [n for n in names if n not in known]
        if unknown:
            raise ValueError(f"unknown component {', '.join(map(repr, unknown))}: not a vessel "
                             f"model, actuator or controller (valid: {', '.join(known)})")
        payload = {kind: {n: info for n, info in payload[kind].items() if n in names}
                   for kind in ("vessel_models", "actuators", "controllers")}
        payload = {kind: entries for kind, entries in payload.items() if entries}
    if json_out:
        print_json(payload)
        return
    if not names and not full:
        _models_overview(payload)
        return
    for kind, entries in payload.items():
        if kind == "catalog":
            continue
        for name, info in entries.items():
            table = Table(title=f"{kind[:-1].replace('_', ' ')} '{name}': {info['description']}",
                          title_justify="left")
            for col in ("parameter", "symbol", "unit", "default", "description"):
                table.add_column(col)
            for p in info["parameters"]:
                d = p["default"]
                default = ("required" if d is None else f"{d:.6g}" if not isinstance(d, tuple)
                           else f"{len(d)} values")
                table.add_row(p["name"], p["symbol"], p["unit"], default, p["doc"])
            console.print(table)
            if info["signals"] or info.get("passthrough"):
                sig = Table(title_justify="left", box=None, pad_edge=False)
                for col in ("signal", "name", "unit"):
                    sig.add_column(col)
                for row in info["signals"]:
                    sig.add_row(row["kind"], row["name"], escape(f"[{row['unit']}]")
                                if row["unit"] else "")
                if info.get("passthrough"):
                    sig.add_row("channels", "named after what it is wired to", "")
                console.print(sig)
    if "catalog" in payload:
        cat = Table(title="catalog ships (seahelm ship show NAME)", title_justify="left")
        cat.add_column("name")
        cat.add_column("model")
        cat.add_column("provenance")
        for name, e in payload["catalog"].items():
            cat.add_row(name, e["model"], e["provenance"])
        console.print(cat)


def _models_overview(payload: dict[str, Any]) -> None:
    """`seahelm models` without a name: one row per component (it printed every parameter of
    every component, 1,769 lines), then the catalog's ships by name and model."""
    for kind, entries in payload.items():
        if kind == "catalog":
            continue
        table = Table(title=kind.replace("_", " "), title_justify="left")
        table.add_column("name")
        table.add_column("parameters", justify="right")
        table.add_column("description")
        for name, info in entries.items():
            table.add_row(name, str(len(info["parameters"])), escape(info["description"]))
        console.print(table)
    ships = Table(title="catalog ships", title_justify="left")
    ships.add_column("name")
    ships.add_column("model")
    for name, e in payload["catalog"].items():
        ships.add_row(name, e["model"])
    console.print(ships)
    console.print("`seahelm models NAME` gives a component's parameters and signals, --all "
                  "every one; `seahelm ship show NAME` a ship", highlight=False, markup=False)
