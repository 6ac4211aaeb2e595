"""``seahelm fmu`` writes only a file named ``.fmu`` (an FMU is a zip an importer finds by its
suffix). Before: ``seahelm fmu kvlcc2-l7 -o a.txt`` wrote a 668 kB zip named a.txt, exit 0."""
from __future__ import annotations

import os

import pytest

from conftest import one_error


@pytest.mark.parametrize("name, said", [("a.txt", "(suffix '.txt')"), ("ship", "(no suffix)"),
                                        ("ship.fmu.zip", "(suffix '.zip')")])
def test_an_output_not_named_fmu_is_refused_before_any_work(tmp_path, name, said):
    out = tmp_path / name
    line = one_error(["fmu", "kvlcc2-l7", "-o", str(out)])
    assert line == f"error: `--out` must name an .fmu file, got {str(out)!r} {said}"
    assert os.listdir(tmp_path) == []
