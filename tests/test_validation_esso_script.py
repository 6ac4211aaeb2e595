"""``validation/esso_osaka.py``: a ``--data`` folder that is not the FRT-DS-ESSO data set is
an error of one line (exit 2); the tables it writes (no measured data: made-up rows)."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "validation" / "esso_osaka.py"


@pytest.fixture(scope="module")
def script():
    spec = importlib.util.spec_from_file_location("esso_osaka_script", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_not_the_data_set_is_exit_2_with_one_line(script, tmp_path, capsys):
    assert script.main(["--data", str(tmp_path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0
    assert err == (f"esso_osaka.py: error: --data {tmp_path}: not a clone of FRT-DS-ESSO "
                   "(no data/turning/*.csv)")
    assert not (tmp_path / "out").exists()


def test_a_wrong_header_names_the_file_and_the_column(script, tmp_path, capsys):
    for kind in script.KINDS:
        (tmp_path / "data" / kind).mkdir(parents=True)
        (tmp_path / "data" / kind / f"{kind}_1.csv").write_text("t [s],u_velo [m/s]\n0,0\n")
    assert script.main(["--data", str(tmp_path)]) == 2
    from seahelm.identification.records import RECORD_FORMATS

    first_missing = next(h for h in RECORD_FORMATS["FRT-DS-ESSO"][0]
                         if h not in ("t [s]", "u_velo [m/s]"))
    err = capsys.readouterr().err.strip()
    assert err == (f"esso_osaka.py: error: --data {tmp_path}: turning_1.csv row 1 lacks "
                   f"column `{first_missing}` (not the FRT-DS-ESSO format)")


def test_rst_tables_and_percentages(script):
    text = script._rst_table("t", ["a", "bb"], [["1", "22"], ["333", "4"]])
    assert text.splitlines()[2] == "   === ==" and "   333 4 " in text
    assert script._pct(math.nan) == "not stopped" and script._pct(0.123) == "+12 %"
    assert script._fmt(math.nan) == "–" and script._fmt(1.23456) == "1.23"
