"""Every public function and method documents every argument (numpydoc ``Parameters``).

In the spirit of python-control's ``test_docstrings``: walk every module of
``seahelm`` (except the command line and the kernel template), take each plain
function named in the module's ``__all__`` -- and each public method defined by a
class named there -- and check that its docstring has a numpydoc ``Parameters``
section listing each argument as an entry (``name :`` at the start of a line, or
grouped ``name1, name2 :``). ``self``/``cls`` and ``*args``/``**kwargs`` are not
required; a function without other arguments needs no ``Parameters`` section.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import pytest

import seahelm

#: "module.function" names allowed to stay undocumented.  Keep this empty.
_UNDOCUMENTED: set[str] = set()

_SKIP_PREFIXES = ("seahelm.cli",)
_SKIP_MODULES = {"seahelm.simulation.kernel_template"}

_HEADER = re.compile(r"^(\S[^\n]*)\n-{3,}\s*$", re.MULTILINE)
_ENTRY = re.compile(r"^(\*{0,2}\w+(?:\s*,\s*\*{0,2}\w+)*)\s*:", re.MULTILINE)


def _skip_module(name: str) -> bool:
    if name in _SKIP_MODULES:
        return True
    return any(name == p or name.startswith(p + ".") for p in _SKIP_PREFIXES)


def _public_modules():
    modules = [seahelm.__name__] + [
        info.name
        for info in pkgutil.walk_packages(seahelm.__path__, seahelm.__name__ + ".")
    ]
    for mod_name in sorted(modules):
        if not _skip_module(mod_name):
            yield importlib.import_module(mod_name)


def _public_functions() -> list[tuple[str, object]]:
    found = []
    for module in _public_modules():
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name, None)
            if inspect.isfunction(obj):
                found.append((f"{module.__name__}.{name}", obj))
    return found


def _public_methods() -> list[tuple[str, object]]:
    """Public methods defined (not inherited) by the classes each module defines and exports."""
    found = []
    for module in _public_modules():
        for name in getattr(module, "__all__", ()):
            cls = getattr(module, name, None)
            if not inspect.isclass(cls) or cls.__module__ != module.__name__:
                continue
            for attr, member in vars(cls).items():
                if attr.startswith("_"):
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                if inspect.isfunction(member):
                    found.append((f"{module.__name__}.{name}.{attr}", member))
    return found


_FUNCTIONS = _public_functions()
_METHODS = _public_methods()


def _documented_arguments(func) -> list[str]:
    try:
        sig = inspect.signature(func)
    except (TypeError, ValueError):  # pragma: no cover - builtins
        return []
    return [
        name
        for name, p in sig.parameters.items()
        if name not in ("self", "cls")
        and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
    ]


def _sections(doc: str) -> dict[str, str]:
    """Split a numpydoc docstring into ``{header: body}``."""
    headers = list(_HEADER.finditer(doc))
    out = {}
    for i, m in enumerate(headers):
        end = headers[i + 1].start() if i + 1 < len(headers) else len(doc)
        out[m.group(1).strip()] = doc[m.end() : end]
    return out


def _parameter_entries(section: str) -> set[str]:
    names = set()
    for m in _ENTRY.finditer(section):
        for part in m.group(1).split(","):
            names.add(part.strip().lstrip("*"))
    return names


def test_functions_found():
    assert len(_FUNCTIONS) > 100
    assert len(_METHODS) > 50


def test_allowlist_is_current():
    known = {qualname for qualname, _ in _FUNCTIONS + _METHODS}
    assert _UNDOCUMENTED <= known, sorted(_UNDOCUMENTED - known)


@pytest.mark.parametrize(
    "qualname, func", _FUNCTIONS + _METHODS, ids=[q for q, _ in _FUNCTIONS + _METHODS]
)
def test_arguments_documented(qualname, func):
    if qualname in _UNDOCUMENTED:
        pytest.skip("listed in _UNDOCUMENTED")
    args = _documented_arguments(func)
    if not args:
        return
    doc = inspect.getdoc(func) or ""
    sections = _sections(doc)
    assert "Parameters" in sections, f"{qualname}: no numpydoc 'Parameters' section"
    entries = _parameter_entries(sections["Parameters"])
    missing = [a for a in args if a not in entries]
    assert not missing, f"{qualname}: undocumented argument(s) {missing}"
