"""The equilibria modules moved into :mod:`seahelm.analysis.equilibria` (issue 47, item 3,
step F): the old paths still give the same modules, with a DeprecationWarning naming the new
one, and no module lives at the old path."""
from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

import seahelm.analysis

MOVED = {f"seahelm.analysis.{m}": f"seahelm.analysis.equilibria.{m}" for m in (
    "equilibrium", "batch_equilibrium", "batch_steady_turn", "constant_speed", "linearisation",
    "heel")}


def _forget(old: str) -> None:
    sys.modules.pop(old, None)
    parent, _, leaf = old.rpartition(".")
    sys.modules[parent].__dict__.pop(leaf, None)


@pytest.mark.parametrize("old, new", sorted(MOVED.items()))
def test_the_old_path_imports_the_new_module_and_warns(old, new):
    _forget(old)
    with pytest.warns(DeprecationWarning, match=rf"{old} is deprecated: use {new} "):
        module = importlib.import_module(old)
    real = importlib.import_module(new)
    assert module is real and sys.modules[old] is real
    assert real.__name__ == new and real.__spec__.name == new


@pytest.mark.parametrize("old", sorted(MOVED))
def test_no_module_lives_at_the_old_path(old):
    leaf = old.rpartition(".")[2]
    assert not (Path(seahelm.analysis.__file__).parent / f"{leaf}.py").exists()


def test_old_names_give_the_same_objects():
    code = ("import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            "import seahelm.analysis.equilibria.equilibrium as new\n"
            "warnings.simplefilter('ignore', DeprecationWarning)\n"
            "from seahelm.analysis.equilibrium import approach_state, EquilibriumError\n"
            "from seahelm.analysis.batch_equilibrium import approach_states\n"
            "from seahelm.analysis.equilibria.batch_equilibrium import approach_states as a2\n"
            "assert approach_state is new.approach_state and approach_states is a2\n"
            "assert EquilibriumError is new.EquilibriumError\n"
            "print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "ok", out.stderr


def test_the_library_imports_no_old_path():
    # importing the manoeuvres, the CLI and the equilibria warns nothing: every caller moved
    code = ("import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            "import seahelm.cli.main, seahelm.analysis.maneuvers, seahelm.analysis.imo\n"
            "import seahelm.analysis.equilibria.linearisation, seahelm.gym, seahelm.fmu\n"
            "print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "ok", out.stderr
