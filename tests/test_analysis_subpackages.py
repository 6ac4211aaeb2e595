"""The subpackages of seahelm.analysis (issue 47, item 2): each exports the public names of its
modules, as the modules' own objects, without importing its other modules; the old modules that
became packages (``imo``, ``seakeeping``, ``replay``) still give their names. The old module
paths are in tests/test_identification_moved_modules.py."""
from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

SUBPACKAGES = {
    "seahelm.analysis.imo": ("check", "probability", "monte_carlo", "ensemble", "given_fit"),
    "seahelm.analysis.seakeeping": ("frequency_domain", "response_statistics", "time_domain"),
    "seahelm.analysis.replay": ("simulate", "dataset", "reversals", "segments",
                                "mmg_multi_record"),
    "seahelm.analysis.steering": ("indices", "autopilot_tuning"),
    "seahelm.analysis.dp": ("level1", "level3"),
}


@pytest.mark.parametrize("package, modules", sorted(SUBPACKAGES.items()))
def test_a_subpackage_exports_every_public_name_of_its_modules(package, modules):
    pkg = importlib.import_module(package)
    names: set[str] = set()
    for leaf in modules:
        module = importlib.import_module(f"{package}.{leaf}")
        names |= set(module.__all__)
        for name in set(module.__all__) & set(pkg.__all__):
            assert getattr(pkg, name) is getattr(module, name), (package, leaf, name)
    assert names <= set(pkg.__all__), names - set(pkg.__all__)
    assert pkg.__doc__ and pkg.__doc__.split("\n")[0].strip()


@pytest.mark.parametrize("old, new", [
    ("seahelm.analysis.imo.imo_check", "seahelm.analysis.imo.check.imo_check"),
    ("seahelm.analysis.imo.STOPPING_LIMIT", "seahelm.analysis.imo.check.STOPPING_LIMIT"),
    ("seahelm.analysis.seakeeping.closed_form_moments",
     "seahelm.analysis.seakeeping.frequency_domain.closed_form_moments"),
    ("seahelm.analysis.seakeeping.ResponseMoments",
     "seahelm.analysis.seakeeping.frequency_domain.ResponseMoments"),
    ("seahelm.analysis.replay.replay", "seahelm.analysis.replay.simulate.replay"),
    ("seahelm.analysis.replay.RMS_WINDOW", "seahelm.analysis.replay.simulate.RMS_WINDOW"),
    ("seahelm.analysis.maneuvers.turning_metrics",
     "seahelm.analysis.maneuvers.advance_transfer.turning_metrics"),
    ("seahelm.analysis.maneuvers.heading_metrics",
     "seahelm.analysis.maneuvers.course_keeping.heading_metrics"),
])
def test_a_module_that_became_a_package_keeps_its_names(old, new):
    def get(path):
        module, _, name = path.rpartition(".")
        return getattr(importlib.import_module(module), name)

    assert get(old) is get(new)


@pytest.mark.parametrize("light, heavy", [
    ("seahelm.analysis.imo.ensemble", "seahelm.analysis.imo.check"),
    ("seahelm.analysis.replay.dataset", "seahelm.analysis.replay.simulate"),
    ("seahelm.analysis.seakeeping.time_domain", "seahelm.analysis.seakeeping.frequency_domain"),
])
def test_a_light_module_imports_no_heavy_sibling(light, heavy):
    code = f"import sys, {light}; print({heavy!r} in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"
