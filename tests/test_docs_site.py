"""The documentation's scenario-file reference is generated from the pydantic schema, and
lists every section, key and signal kind of it (so the two cannot drift apart); the docs
configuration and pages the site is built from are in place."""

from __future__ import annotations

import dataclasses
import importlib.util
import re
import typing
from pathlib import Path

import pytest
from pydantic import BaseModel

from seahelm.scenario.schema import Scenario
from seahelm.simulation.signals import SIGNALS

DOCS = Path(__file__).resolve().parents[1] / "docs"


def _generator():
    spec = importlib.util.spec_from_file_location("scenario_reference",
                                                  DOCS / "_ext" / "scenario_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def page() -> dict[str, str]:
    """The generated page, split into its sections: title -> body."""
    text = _generator().render()
    parts = re.split(r"^(\S.*)\n[-^]{3,}\n", text, flags=re.MULTILINE)
    return {parts[i]: parts[i + 1] for i in range(1, len(parts) - 1, 2)}


def _models(model: type[BaseModel], prefix: str = ""):
    """Every section of the schema, walked here independently of the generator."""
    yield prefix, model
    for name, field in model.model_fields.items():
        for ann in (field.annotation, *typing.get_args(field.annotation)):
            args = typing.get_args(ann) if typing.get_origin(ann) is dict else ()
            target = args[1] if args else ann
            if isinstance(target, type) and issubclass(target, BaseModel):
                path = f"{prefix}.{name}" if prefix else name
                yield from _models(target, path + (".<key>" if args else ""))
                break


def test_every_section_and_key_of_the_schema_is_listed(page):
    sections = list(_models(Scenario))
    assert len(sections) >= 10  # top level, vessel, ..., batch.monte_carlo.draws.<key>
    for path, model in sections:
        title = "Top level" if not path else f"[{path}]"
        assert title in page, f"section {title} missing from the scenario reference"
        rows = re.findall(r"^   \* - ``(\w+)``$", page[title], flags=re.MULTILINE)
        assert rows == list(model.model_fields), title


def test_types_defaults_units_and_allowed_values(page):
    def row(title: str, key: str) -> str:
        body = page[title]
        start = body.index(f"   * - ``{key}``")
        end = body.find("   * - ", start + 1)
        return body[start:end if end > 0 else None]

    assert "number > 0" in row("[simulation]", "t_final")
    assert "\n     - s\n" in row("[simulation]", "dt") and "required" in row("[simulation]", "dt")
    integrator = row("[simulation]", "integrator")
    assert '``"rk4"``' in integrator and "``rk38``" in integrator and "``euler``" in integrator
    assert "``kvlcc2-l7``" in row("[vessel]", "catalog")
    assert "``pid-heading``" in row("[controller]", "model")
    assert '``"turning"``' in row("[maneuver]", "kind") and '``"imo"``' in row("[maneuver]",
                                                                                 "kind")
    assert '``"normal"``' in row("[batch.monte_carlo.draws.<key>]", "distribution")
    assert "integer ≥ 1, ≤ 1,000,000" in row("[batch.monte_carlo]", "runs")
    assert "\n     - m/s\n" in row("[environment.current]", "speed")
    assert "\n     - deg\n" in row("[environment.current]", "direction_deg")
    assert "\n     - ``1``\n" in row("[simulation]", "record_every")


def test_every_signal_kind_and_field_is_listed(page):
    for kind, cls in SIGNALS.items():
        title = f'``kind = "{kind}"``'
        assert title in page, kind
        rows = re.findall(r"^   \* - ``(\w+)``$", page[title], flags=re.MULTILINE)
        assert rows == [f.name for f in dataclasses.fields(cls)], kind
    assert "\n     - s\n" in page['``kind = "step"``']  # its time


def test_a_new_section_appears_without_editing_the_docs():
    from seahelm.scenario.schema import EnvironmentSection, Number, _Strict

    class WindSection(_Strict):
        """``[environment.wind]``: a steady wind."""

        speed: Number

    class Environment(EnvironmentSection):
        wind: WindSection | None = None

    class Extended(Scenario):
        environment: Environment = Environment()

    found = dict(_generator().sections(Extended))
    assert found["environment.wind"] is WindSection


def test_the_site_sources_are_in_place():
    conf = (DOCS / "conf.py").read_text()
    for ext in ("numpydoc", "sphinx_gallery.gen_gallery", "sphinx.ext.autosummary",
                "scenario_reference"):
        assert f'"{ext}"' in conf
    assert "pydata_sphinx_theme" in conf and "Why Sphinx" in conf
    index = (DOCS / "index.rst").read_text()
    for page_name in ("getting-started", "guide/index", "scenario-reference",
                      "auto_examples/index", "api"):
        assert page_name in index
    assert sorted(p.name for p in (DOCS / "examples").glob("plot_*.py"))
    makefile = (DOCS.parent / "Makefile").read_text()
    assert re.search(r"^docs:.*\n\t.*sphinx -W", makefile, flags=re.MULTILINE)


def test_the_ship_file_reference_lists_every_key_and_catalog_ship():
    spec = importlib.util.spec_from_file_location("ship_reference",
                                                  DOCS / "_ext" / "ship_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    from seahelm.ships import ship_names
    from seahelm.ships.file_format import FORMAT_REFERENCE

    page = module.render()
    for key, unit, _, _ in FORMAT_REFERENCE:
        assert f"``{key}``" in page, key
    for name in ship_names():
        assert f"``{name}``" in page, name
    assert "[m]" in page and "max_angle = 0.6108652381980153" in page
    conf = (DOCS / "conf.py").read_text()
    assert '"ship_reference"' in conf and "ship-file-reference" in (DOCS / "index.rst").read_text()
