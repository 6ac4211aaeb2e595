"""The package's import graph has no cycle, counting imports inside functions too.

An import inside a function ("local: analysis depends on vessels") hides a cycle from Python
but not from the design: `vessels.cpp_ship` and `analysis.averaging` imported each other that
way until the periodic mean moved down to `seahelm.numerics`. Imports under
``if TYPE_CHECKING:`` are annotations only and are not counted.
"""

from __future__ import annotations

import ast
import graphlib
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "seahelm"


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


MODULES = {_module_name(p): p for p in PACKAGE.rglob("*.py")}


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _imports(name: str, path: Path) -> set[str]:
    """seahelm modules that ``name`` imports anywhere in its code (not under TYPE_CHECKING)."""
    is_package = path.name == "__init__.py"
    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and _is_type_checking(node):
            for child in node.orelse:
                visit(child)
            return
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".") if is_package else name.split(".")[:-1]
                base = base[:len(base) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            targets = [module] + [f"{module}.{a.name}" for a in node.names]
        for target in targets:
            if target in MODULES and target != name:
                found.add(target)
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(ast.parse(path.read_text()))
    return found


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


def test_no_import_cycle():
    try:
        list(graphlib.TopologicalSorter(GRAPH).static_order())
    except graphlib.CycleError as err:  # pragma: no cover - the failure being tested for
        pytest.fail("import cycle: " + " -> ".join(reversed(err.args[1])))


def test_the_scan_sees_imports_inside_functions():
    # the guard itself: cpp_ship's periodic mean is imported at module level now, and the
    # scan still reports function-level imports (results imports plotting in .plot())
    assert "seahelm.numerics.periodic" in GRAPH["seahelm.vessels.cpp_ship"]
    assert "seahelm.plotting.timeseries" in GRAPH["seahelm.results"]
    assert "seahelm.simulation.batch" not in GRAPH["seahelm.results"]  # TYPE_CHECKING only


def test_generic_numerics_import_no_component():
    for name, deps in GRAPH.items():
        if name.startswith("seahelm.numerics"):
            assert deps <= {"seahelm.errors", "seahelm.numerics", "seahelm.numerics.periodic"}, (
                name, deps)


def test_a_cycle_is_detected():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}}
    with pytest.raises(graphlib.CycleError):
        list(graphlib.TopologicalSorter(graph).static_order())
