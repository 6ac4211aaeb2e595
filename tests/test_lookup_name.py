"""One lookup by name (issue 47, item 4): every "unknown X 'name'; valid: ..." error of the
library comes from :func:`seahelm._validate.lookup_name` (the registry's ``lookup`` uses it
too), with the messages the hand-written lookups had."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from seahelm._validate import lookup_name
from seahelm.errors import ParameterError

SRC = Path(__file__).resolve().parents[1] / "src" / "seahelm"

#: The single-name lookups still written by hand, each with the reason. Exact: one converted
#: must leave the list.
HAND_WRITTEN = {
    "numerics/sampling.py": "generic numerics import nothing above seahelm.errors",
    "numerics/runge_kutta.py": "generic numerics import nothing above seahelm.errors",
    "vessels/base.py": "several names at once (the capabilities a model declares)",
    "scenario/runs.py": "a channel of a scenario, said with the scenario's keys after the list",
    "scenario/environment.py": "said as a scenario error at its TOML key (_err)",
    "encounters/files.py": "a key of an encounter scenario or situation file, said at its key path",
    "gym/plant.py": "a keyword of the environment's weather, said as the keyword",
}

#: ``unknown <what> {name}; valid:`` or ``unknown <what> '{name}'; valid:`` in a string,
#: possibly continued on the next line
_LOOKUP = re.compile(r"""unknown [\w ]+ '?\{[^}]+\}'?(?:;|"\s*\n\s*f?")\s*(?:f?")?\s*valid:""")


def test_the_message_of_a_lookup():
    table = {"b": 2, "a": 1}
    assert lookup_name("thing", table, "a") == 1
    with pytest.raises(ValueError, match=r"^unknown thing 'c'; valid: b, a$"):
        lookup_name("thing", table, "c")
    with pytest.raises(ValueError, match=r"^unknown thing 'c'; valid: a, b$"):
        lookup_name("thing", table, "c", sort=True)
    with pytest.raises(ValueError, match=r"^unknown thing 'c'; valid: 'b', 'a'$"):
        lookup_name("thing", table, "c", quoted=True)
    with pytest.raises(ValueError, match=r"^unknown thing 'c'; valid: x \(or None\)$"):
        lookup_name("thing", table, "c", valid=["x"], suffix=" (or None)")
    with pytest.raises(ParameterError, match="unknown thing None") as err:
        lookup_name("thing", table, None, error=ParameterError, field="thing", value=None)
    assert err.value.field == "thing"
    with pytest.raises(KeyError):
        lookup_name("thing", table, ["unhashable"], error=KeyError)
    # a table of names only (a tuple of the valid sets)
    assert lookup_name("set", ("x", "y"), "y") == "y"
    with pytest.raises(ValueError, match=r"^unknown set 'z'; valid: x, y$"):
        lookup_name("set", ("x", "y"), "z")


def test_the_registry_lookup_says_what_it_said():
    from seahelm.registry import get_model

    with pytest.raises(ValueError, match=r"^unknown vessel model 'nope'; valid: catamaran, "
                                         r"catamaran-servo, container, "):
        get_model("nope")


@pytest.mark.parametrize("call, message", [
    ("seahelm.hydrodynamics.resistance:_method", "unknown Holtrop method 'x'; valid: "),
    ("seahelm.environment.wind_gust:get_gust_spectrum", "unknown gust spectrum 'x'; valid: "),
    ("seahelm.control.path_following:get_guidance_law", "unknown guidance law 'x'; valid: "),
    ("seahelm.identification.reduced.forms:get_form", "unknown reduced form 'x'; valid: paper, "),
    ("seahelm.ships.catalog:get", "unknown catalog ship 'x'; valid: esso-osaka-3m, "),
])
def test_converted_lookups_keep_their_messages(call, message):
    import importlib

    module, name = call.split(":")
    function = getattr(importlib.import_module(module), name)
    with pytest.raises(ValueError, match=re.escape(message)):
        function("x")


def test_no_other_hand_written_lookup():
    found = {}
    for path in SRC.rglob("*.py"):
        rel = path.relative_to(SRC).as_posix()
        if rel == "_validate.py":
            continue
        hits = _LOOKUP.findall(path.read_text())
        if hits:
            found[rel] = hits
    assert set(found) == set(HAND_WRITTEN), {k: v for k, v in found.items()
                                              if k not in HAND_WRITTEN}


def test_the_scan_sees_a_hand_written_lookup():
    text = '''raise ValueError(f"unknown fit method '{method}'; valid: {', '.join(M)}")'''
    assert _LOOKUP.findall(text)
    text = '''raise ValueError(f"unknown Holtrop method {method!r}; valid: "\n    f"{x}")'''
    assert _LOOKUP.findall(text)
