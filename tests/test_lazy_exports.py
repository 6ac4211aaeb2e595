"""seahelm._optional.lazy_exports: a package's names from its submodules, imported on first
use (the analysis subpackages' ``__init__``, issue 47 item 2)."""
from __future__ import annotations

import importlib
import sys

import pytest

from seahelm._optional import lazy_exports


@pytest.fixture
def package(tmp_path, monkeypatch):
    root = tmp_path / "lazypkg"
    root.mkdir()
    (root / "__init__.py").write_text(
        "from seahelm._optional import lazy_exports\n"
        "__all__, __getattr__, __dir__ = lazy_exports(__name__, {'light': ('small',),"
        " 'heavy': ('big', 'BIG')})\n")
    (root / "light.py").write_text("def small():\n    return 1\n")
    (root / "heavy.py").write_text("BIG = 2\n\ndef big():\n    return 3\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    yield "lazypkg"
    for name in [m for m in sys.modules if m == "lazypkg" or m.startswith("lazypkg.")]:
        del sys.modules[name]


def test_names_resolve_to_the_submodules_objects_on_first_use(package):
    pkg = importlib.import_module(package)
    assert pkg.__all__ == ["small", "big", "BIG"]
    assert f"{package}.heavy" not in sys.modules
    from lazypkg import small

    assert small is importlib.import_module(f"{package}.light").small
    assert f"{package}.heavy" not in sys.modules  # a light name imports no heavy sibling
    assert pkg.BIG == 2 and pkg.big() == 3
    assert "big" in vars(pkg)  # cached
    assert {"small", "big", "BIG"} <= set(dir(pkg))


def test_an_unknown_name_is_an_attribute_error(package):
    pkg = importlib.import_module(package)
    with pytest.raises(AttributeError, match="module 'lazypkg' has no attribute 'smal'"):
        pkg.smal  # noqa: B018
    with pytest.raises(ImportError):
        from lazypkg import smal  # noqa: F401


@pytest.mark.parametrize("exports", [{"a": ("x",), "b": ("x",)}, {"a": ("b",), "b": ("y",)}])
def test_a_name_twice_or_a_submodules_name_is_refused(exports):
    with pytest.raises(ValueError, match="exported twice or is also a submodule's name"):
        lazy_exports("pkg", exports)
