"""``validation/esso_osaka.py --part identify``: the train/test split read from the data set's
README (a made-up README in its table format; no measured data), and a README without the
table is an error of one line (exit 2)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parents[1] / "validation"

README = """# FRT-DS-ESSO

Intro naming [Wakita (2022)](https://x) and [Miyauchi (2022)](https://y).

- [Wakita (2022)](https://x)

| File path | Train-TZB | Train-TZRB | Train-TZRB+ | Test (TZRB) |
| --- | :-: | :-: | :-: | :-: |
| `data/random/random_a.csv`     |     ✖️     |     ✖️      |      ⭕️      |      ✖️      |
| `data/random/random_b.csv`     |     ✖️     |     ✖️      |      ✖️      |      ⭕️      |
| `data/turning/turn_c.csv`      |     ⭕️     |     ⭕️      |      ⭕️      |      ✖️      |

- [Miyauchi (2022)](https://y)

| File path | Train-R | Train-TR | Train-TRZ | Test |
| --- | :-: | :-: | :-: | :-: |
| `data/random/random_a.csv`     |     ⭕️     |     ✖️      |      ✖️      |      ⭕️      |
"""


@pytest.fixture(scope="module")
def ident():
    spec = importlib.util.spec_from_file_location("esso_osaka_identify",
                                                  HERE / "esso_osaka_identify.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_wakita_split_is_read_from_the_readme(ident, tmp_path):
    (tmp_path / "README.md").write_text(README, encoding="utf-8")
    train, test = ident.split(tmp_path)
    assert [p.name for p in train] == ["random_a.csv", "turn_c.csv"]
    assert [p.name for p in test] == ["random_b.csv"]  # not Miyauchi's test column
    train, _ = ident.split(tmp_path, "Train-TZB")
    assert [p.name for p in train] == ["turn_c.csv"]
    with pytest.raises(SystemExit, match="--train 'Train-R': one of Train-TZB"):
        ident.split(tmp_path, "Train-R")


def test_a_readme_without_the_table_is_exit_2_with_one_line(tmp_path, capsys):
    spec = importlib.util.spec_from_file_location("esso_osaka_script", HERE / "esso_osaka.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    for kind in script.KINDS:  # a folder that passes the data set's header check
        (tmp_path / "data" / kind).mkdir(parents=True)
        from seahelm.identification.records import RECORD_FORMATS

        header = ",".join(RECORD_FORMATS["FRT-DS-ESSO"][0])
        (tmp_path / "data" / kind / f"{kind}_1.csv").write_text(header + "\n")
    (tmp_path / "README.md").write_text("# not the data set's README\n")
    try:
        code = script.main(["--data", str(tmp_path), "--out", str(tmp_path / "out"),
                            "--part", "identify"])
    finally:
        sys.path[:] = [p for p in sys.path if p != str(HERE)]
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"esso_osaka.py: error: --data {tmp_path}: README.md has no Wakita "
                   "(2022) train/test table")
