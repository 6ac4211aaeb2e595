"""Sphinx extension: the ship-file reference, generated from the format and the catalog.

At every build (``builder-inited``) :func:`render` writes ``docs/ship-file-reference.rst``: every
key of a ship file from :data:`seahelm.ships.file_format.FORMAT_REFERENCE` (unit, whether it is
required, what it is), the catalog's ships (model, steering gear, test speed, description) and
one catalog ship file in full. A new key or catalog ship appears in the docs without anyone
editing them; ``tests/test_docs_site.py`` checks that the page lists every key.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

#: Where the generated page goes (next to index.rst).
OUTPUT = Path(__file__).resolve().parents[1] / "ship-file-reference.rst"


def _table(header: tuple[str, ...], rows: list[tuple[str, ...]]) -> list[str]:
    out = [".. list-table::", "   :header-rows: 1", ""]
    for row in (header, *rows):
        out.append(f"   * - {row[0] or ' '}")
        out += [f"     - {cell or ' '}" for cell in row[1:]]
    return out + [""]


def render() -> str:
    """The page's reStructuredText."""
    from seahelm.ships import CATALOG, ship_to_toml
    from seahelm.ships.file_format import FORMAT, FORMAT_REFERENCE

    lines = ["Ship files", "==========", "",
             f"A ship file (format {FORMAT}) is a :class:`seahelm.ships.Ship` on disk: the "
             "manoeuvring model and its parameters, the steering gear, the propulsion, the main "
             "particulars and the provenance of every number. ``seahelm ship show NAME --toml`` "
             "writes one; ``seahelm ship check FILE`` checks one; every command and scenario key "
             "that takes a ship takes its path. SI units, angles in radians (or ``<name>_deg`` "
             "in degrees). A file gives every parameter of its model, or names a ``base`` ship "
             "to take the others from. This page is generated from the format's own table "
             "(``seahelm.ships.file_format.FORMAT_REFERENCE``) and the catalog.", "",
             "Keys", "----", ""]
    lines += _table(("key", "unit", "required", "what it is"),
                    [(f"``{k}``", u, r, d) for k, u, r, d in FORMAT_REFERENCE])
    lines += ["The catalog", "-----------", "",
              "One ship file each in ``src/seahelm/ships/data/``; adding a file adds a ship.", ""]
    rows = []
    for name, ship in CATALOG.items():
        gear = ship.steering_gear.actuator.name if ship.steering_gear else "-"
        speed = "-" if ship.test_speed is None else f"{ship.test_speed:.6g}"
        rows.append((f"``{name}``", ship.model.name, gear, speed, ship.description))
    lines += _table(("ship", "model", "steering gear", "test speed [m/s]", "description"), rows)
    lines += ["A catalog ship file in full", "---------------------------", "",
              ".. code-block:: toml", ""]
    lines += ["   " + ln if ln else "" for ln in ship_to_toml(CATALOG["kvlcc2-l7"]).splitlines()]
    return "\n".join(lines) + "\n"


def write(app: Any = None) -> None:
    """Write :data:`OUTPUT` (only when its text changes, so Sphinx does not rebuild it)."""
    text = render()
    if not OUTPUT.exists() or OUTPUT.read_text() != text:
        OUTPUT.write_text(text)


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
