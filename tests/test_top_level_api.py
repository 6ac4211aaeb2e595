"""``import seahelm`` gives a user's objects, first in ``__all__``, each the library's own."""
from __future__ import annotations

import subprocess
import sys

import seahelm

USER_OBJECTS = ["Ship", "get_ship", "read_ship", "Design", "estimate_ship", "Problem",
                "simulate", "Simulator", "turning_circle", "zigzag", "spirals", "pull_out",
                "crash_stop",
                "imo_check", "linearize", "read_records", "fit_nomoto", "regress_hull",
                "refine_mmg"]


def test_user_objects_come_first() -> None:
    assert seahelm.__all__[:len(USER_OBJECTS)] == USER_OBJECTS
    assert len(set(seahelm.__all__)) == len(seahelm.__all__)
    assert set(USER_OBJECTS) <= set(dir(seahelm))


def test_they_are_the_library_objects() -> None:
    from seahelm.analysis.imo.check import imo_check
    from seahelm.analysis.maneuvers import crash_stop, turning_circle, zigzag
    from seahelm.ships import Ship, get_ship
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.problem import Problem

    assert (seahelm.Ship, seahelm.get_ship, seahelm.Problem, seahelm.simulate) == (
        Ship, get_ship, Problem, simulate)
    assert (seahelm.turning_circle, seahelm.zigzag, seahelm.crash_stop, seahelm.imo_check) == (
        turning_circle, zigzag, crash_stop, imo_check)
    assert isinstance(seahelm.get_ship("kvlcc2-l7"), seahelm.Ship)


def test_import_stays_light() -> None:
    out = subprocess.run([sys.executable, "-c", "import sys, seahelm; "
                          "print(sorted(m for m in ('numba', 'xarray', 'scipy') "
                          "if m in sys.modules))"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
