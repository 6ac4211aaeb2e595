"""Sphinx extension: the scenario-file reference, generated from the pydantic schema.

At every build (``builder-inited``) :func:`render` walks :class:`seahelm.scenario.schema.Scenario`
-- every section (a nested model), every key with its type, unit, default and allowed values --
and every signal kind of :data:`seahelm.simulation.signals.SIGNALS`, and writes
``docs/scenario-reference.rst``. A new section or key of the schema appears in the docs without
anyone editing them; ``tests/test_docs_site.py`` checks that the page lists every key.

Units come from the scenario layer's unit table (the one its error messages use); names that
a key must take (models, catalog entries, integrators, guidance laws) from the registries.
"""

from __future__ import annotations

import dataclasses
import enum
import inspect
import types
import typing
from pathlib import Path
from typing import Any

import annotated_types
from pydantic import BaseModel
from pydantic_core import PydanticUndefined

#: Where the generated page goes (next to index.rst).
OUTPUT = Path(__file__).resolve().parents[1] / "scenario-reference.rst"

#: Units of the signal kinds' fields; "channel" is the unit of the channel the signal drives.
SIGNAL_UNITS = {"time": "s", "times": "s", "period": "s", "start_time": "s", "end_time": "s",
                "phase": "rad", "h3": "m", "seed": "", "quantity": "", "spectrum": ""}


def _names() -> dict[str, list[str]]:
    """Keys whose value must be one of a registry's names."""
    from seahelm.control.path_following import GUIDANCE_LAWS
    from seahelm.environment.blendermann import BLENDERMANN_VESSEL_TYPES
    from seahelm.registry import ACTUATORS, CONTROLLERS, VESSEL_MODELS
    from seahelm.simulation.integrators import INTEGRATORS
    from seahelm.ships import CATALOG

    return {"vessel.model": sorted(VESSEL_MODELS), "vessel.ship": sorted(CATALOG),
            "vessel.catalog": sorted(CATALOG),
            "actuator.model": sorted(ACTUATORS), "controller.model": sorted(CONTROLLERS),
            "simulation.integrator": list(INTEGRATORS), "guidance.law": list(GUIDANCE_LAWS),
            "environment.wind.vessel_type": list(BLENDERMANN_VESSEL_TYPES),
            "vessel.particulars.vessel_type": list(BLENDERMANN_VESSEL_TYPES)}


def _units() -> dict[str, str]:
    from seahelm.scenario import loading

    return dict(loading._UNITS)  # the table scenario errors name units from


def sections(model: type[BaseModel] | None = None, prefix: str = "") -> list[tuple[str, type]]:
    """Every section of the schema as (dotted path, model), depth first ("" is the top)."""
    from seahelm.scenario.schema import Scenario

    model = Scenario if model is None else model
    out = [(prefix, model)]
    for name, field in model.model_fields.items():
        sub = _model_of(field.annotation)
        if sub is not None:
            path = f"{prefix}.{name}" if prefix else name
            if _is_mapping(field.annotation):
                path += ".<key>"
            out += sections(sub, path)
    return out


def _model_of(ann: Any) -> type[BaseModel] | None:
    """The model a field holds: itself, optional, or as the values of a mapping (the schema's
    own walker, :func:`seahelm.scenario.loading.section_model`)."""
    from seahelm.scenario.loading import section_model

    return section_model(ann)


def _is_mapping(ann: Any) -> bool:
    origin = typing.get_origin(ann)
    if origin in (types.UnionType, typing.Union):
        return any(_is_mapping(a) for a in typing.get_args(ann))
    return origin is dict


def type_name(ann: Any) -> str:
    """A TOML-reader's name for a type annotation."""
    origin, args = typing.get_origin(ann), typing.get_args(ann)
    if origin is typing.Annotated:
        base = type_name(args[0])
        bounds = _bounds(args[1:])
        return f"{base} {bounds}" if bounds else base
    if origin in (types.UnionType, typing.Union):
        parts = [type_name(a) for a in args if a is not type(None)]
        return " or ".join(dict.fromkeys(parts))
    if origin is typing.Literal:
        return "one of " + ", ".join(f'``"{a}"``' for a in args)
    if origin is list:
        return f"list of {type_name(args[0])}"
    if origin is tuple:
        return "[" + ", ".join(type_name(a) for a in args) + "]"
    if origin is dict:
        return f"table of {type_name(args[1])}"
    if ann is float:
        return "number"
    if ann is int:
        return "integer"
    if ann is str:
        return "string"
    if ann is bool:
        return "boolean"
    if ann is typing.Any:
        return "any"
    if inspect.isclass(ann) and issubclass(ann, BaseModel):
        return "table"
    if inspect.isclass(ann) and issubclass(ann, enum.Enum):
        return "one of " + ", ".join(f'``"{m.value}"``' for m in ann)
    return getattr(ann, "__name__", str(ann))


def _bounds(metadata: Any) -> str:
    signs = {"gt": ">", "ge": "≥", "lt": "<", "le": "≤"}
    out = []
    for m in metadata:
        for attr, sign in signs.items():
            value = getattr(m, attr, None)
            if value is not None and isinstance(m, annotated_types.BaseMetadata):
                out.append(f"{sign} {value:,}" if isinstance(value, int) else
                           f"{sign} {value:g}")
        if isinstance(m, annotated_types.MinLen) and m.min_length:
            out.append(f"at least {m.min_length}")
        if isinstance(m, annotated_types.MaxLen):
            out.append(f"at most {m.max_length}")
    return ", ".join(out)


def _field_type(field: Any) -> str:
    ann = field.annotation
    bounds = _bounds(field.metadata)
    if _model_of(ann) is not None and not _is_mapping(ann):
        return "section"
    name = type_name(ann)
    return f"{name} {bounds}" if bounds else name


def _default(field: Any) -> str:
    if field.is_required():
        return "required"
    if field.default_factory is not None:
        value = field.default_factory()
        if isinstance(value, BaseModel):
            return "its defaults"
        return "empty" if not value else f"``{value!r}``"
    if field.default is None:
        return "not set"
    if field.default is PydanticUndefined:
        return "required"
    return f'``"{field.default}"``' if isinstance(field.default, str) else f"``{field.default!r}``"


def _doc(obj: Any) -> str:
    return inspect.cleandoc(obj.__doc__ or "").strip()


def _row(cells: list[str]) -> str:
    return "   * - " + "\n     - ".join(c.replace("\n", " ") or "—" for c in cells) + "\n"


def keys() -> list[tuple[str, Any]]:
    """Every key of the schema as (dotted path, pydantic FieldInfo), sections included."""
    out = []
    for path, model in sections():
        for name, field in model.model_fields.items():
            out.append((f"{path}.{name}" if path else name, field))
    return out


def render() -> str:
    """The reStructuredText of the scenario reference."""
    from seahelm.simulation.signals import SIGNALS

    names, units = _names(), _units()
    lines = [
        ".. This page is generated by docs/_ext/scenario_reference.py from the pydantic schema",
        "   (seahelm.scenario.schema) at every build; do not edit it.",
        "",
        ".. _scenario-reference:",
        "",
        "Scenario file reference",
        "=======================",
        "",
        "A scenario file is TOML. It has a ``[simulation]`` section (a closed-loop run, a batch",
        "with ``[batch]``) or a ``[maneuver]`` section (a standard manoeuvre); everything else",
        "is optional. Every key below is checked before anything runs; an unknown key is an",
        "error. Numbers are strict (``true``, ``\"60\"``, ``inf`` and ``nan`` are errors).",
        "",
        "Angles: any parameter, initial state, reference or disturbance channel whose unit is",
        "radians may be written in degrees with a ``_deg`` suffix (``max_angle_deg = 35``).",
        "Keys under ``params``, ``initial``, ``reference`` and ``disturbance`` are the chosen",
        "components' own parameters and signals: ``seahelm models NAME`` lists them with units.",
        "",
        "This page is generated from the schema (:mod:`seahelm.scenario.schema`) when the",
        "documentation is built.",
        "",
    ]
    for path, model in sections():
        title = "Top level" if not path else f"[{path}]"
        lines += [title, "-" * len(title), ""]
        doc = _doc(model)
        if doc and model.__module__ == "seahelm.scenario.schema" and path:
            lines += [doc, ""]
        lines += [".. list-table::", "   :header-rows: 1", "   :widths: 18 30 10 14 28", ""]
        lines.append(_row(["key", "type", "unit", "default", "allowed values"]))
        for name, field in model.model_fields.items():
            key = f"{path}.{name}" if path else name
            generic = key.replace(".<key>", "")
            unit = "deg" if name.endswith("_deg") else units.get(generic, "")
            allowed = names.get(generic)
            shown = ", ".join(f"``{n}``" for n in allowed) if allowed else ""
            lines.append(_row([f"``{name}``", _field_type(field), unit, _default(field),
                               shown]))
        lines.append("")
    lines += [
        "Signals",
        "-------",
        "",
        "A reference or disturbance channel (``[controller.reference]``,",
        "``[environment.disturbance]``) takes a number (a constant) or a table with ``kind``",
        "and the kind's fields. Value fields are in the channel's unit (or degrees, for a",
        "channel written with ``_deg``); times in seconds.",
        "",
    ]
    for kind, cls in SIGNALS.items():
        lines += [f"``kind = \"{kind}\"``", "^" * (len(kind) + 13), "", _doc(cls), ""]
        lines += [".. list-table::", "   :header-rows: 1", "   :widths: 20 20 20 40", ""]
        lines.append(_row(["field", "type", "unit", "default"]))
        hints = typing.get_type_hints(cls)
        for f in dataclasses.fields(cls):
            default = ("required" if f.default is dataclasses.MISSING else
                       f'``"{f.default}"``' if isinstance(f.default, str) else
                       f"``{f.default!r}``")
            unit = SIGNAL_UNITS.get(f.name, "of the channel")
            lines.append(_row([f"``{f.name}``", type_name(hints[f.name]), unit, default]))
        lines.append("")
    return "\n".join(lines) + "\n"


def write(app: Any = None) -> Path:
    """Write the page (a Sphinx ``builder-inited`` handler); returns its path."""
    text = render()
    if not OUTPUT.exists() or OUTPUT.read_text() != text:  # keep the mtime for incremental builds
        OUTPUT.write_text(text)
    return OUTPUT


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
