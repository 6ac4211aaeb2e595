"""The package surface: light import, lazy public API, typed marker."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import seahelm


def test_import_is_light():
    code = ("import sys, seahelm; heavy = [m for m in ('numba', 'xarray', 'matplotlib', 'scipy',"
            " 'plotly')"
            " if m in sys.modules]; print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_the_demo_path_imports_no_solver_or_plotting_library():
    """What `seahelm demo` imports before it simulates (the user waits for it): no
    scipy.integrate/optimize (0.8 s together; only reference solves and equilibria need them),
    no matplotlib before plotting, no plotly before the report."""
    code = ("import sys; import seahelm.cli.main, seahelm.scenario, seahelm.analysis.maneuvers; "
            "heavy = [m for m in ('scipy.integrate', 'scipy.optimize', 'matplotlib', 'plotly')"
            " if m in sys.modules]; print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


@pytest.mark.parametrize("name", sorted(seahelm._LAZY))
def test_lazy_public_api_resolves(name):
    assert getattr(seahelm, name) is not None
    assert name in dir(seahelm)


def test_unknown_attribute():
    with pytest.raises(AttributeError, match="has no attribute 'simulte'"):
        seahelm.simulte  # noqa: B018


def test_typed_marker_is_shipped():
    assert (Path(seahelm.__file__).parent / "py.typed").is_file()
