"""Reading a turn log (CSV with a header row) in the library: columns by name, and the errors
that tell the user which line and column to fix."""

from __future__ import annotations

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.identification.records import read_turn_log


def test_columns_by_header_name_with_blank_rows_and_a_byte_order_mark(tmp_path):
    f = tmp_path / "log.csv"
    f.write_bytes("\ufefftime, rudder_angle ,yaw_rate\n0,5,0.1\n\n1,5.5,-2e-3\n".encode())
    cols = read_turn_log(f)
    assert list(cols) == ["time", "rudder_angle", "yaw_rate"]
    np.testing.assert_array_equal(cols["time"], [0.0, 1.0])
    np.testing.assert_array_equal(cols["rudder_angle"], [5.0, 5.5])
    np.testing.assert_array_equal(cols["yaw_rate"], [0.1, -2e-3])
    assert read_turn_log(str(f)).keys() == cols.keys()  # a str path too


def test_the_example_log_reads():
    from pathlib import Path

    cols = read_turn_log(Path(__file__).parents[1] / "examples" / "steady_turn_log.csv")
    assert {"time", "rudder_angle", "yaw_rate"} <= set(cols)
    assert len({v.size for v in cols.values()}) == 1 and cols["time"].size > 100


@pytest.mark.parametrize(("content", "match"), [
    (b"", r"empty file \(a header row is needed\)"),
    (b"a,b\n1,2\n3\n", r"line 3: 1 fields, the header has 2"),
    (b"a,b\n1,x\n", r"line 2: column `b` is not a number: 'x'"),
    (b"a,b\n1,\xff\n", r"not UTF-8 text \(byte 6\)"),
])
def test_bad_files_name_the_file_line_and_column(tmp_path, content, match):
    f = tmp_path / "bad.csv"
    f.write_bytes(content)
    with pytest.raises(ParameterError, match=match) as err:
        read_turn_log(f)
    assert str(f) in str(err.value)


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(ParameterError, match="no such file"):
        read_turn_log(tmp_path / "nope.csv")
    with pytest.raises(ParameterError, match="is not a regular file"):
        read_turn_log(tmp_path)
