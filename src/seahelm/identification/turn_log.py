"""Recorded turns from a CSV file: the numeric columns of a log with a header row.

A turn log is either a time series (columns ``time``, ``rudder_angle``, ``yaw_rate``, which
:func:`~seahelm.identification.reduced.segments.extract_steady_segments` cuts into steady turns) or
already-steady points (``rudder_angle``, ``yaw_rate``); other columns are read too and left to
the caller. ``seahelm identify steady-turn FILE.csv`` reads its file with :func:`read_turn_log`.

The reader is Python's :mod:`csv` with the checks a user needs to fix a file: the line and
column of a cell that is not a number, a row with the wrong number of fields, an empty file,
text that is not UTF-8 (a UTF-8 byte-order mark is accepted) -- each a
:class:`~seahelm.errors.ParameterError` naming the file.
"""

from __future__ import annotations

import csv
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["read_turn_log", "read_turn_log_lines"]


def read_turn_log(path: str | os.PathLike[str]) -> dict[str, np.ndarray]:
    """The numeric columns of a CSV file with a header row, by header name.

    Parameters
    ----------
    path : str or os.PathLike
        A CSV file: a header row, then one row of numbers per sample (blank rows and comment
        lines, starting with ``#``, skipped: ``# units: ...`` above the header is a comment).

    Returns
    -------
    dict of str to numpy.ndarray
        One float array per column, in the header's order (names stripped of blanks).

    Raises
    ------
    ParameterError
        If the file is missing, not a regular file, empty, not UTF-8 text, has a header name
        twice or no data rows, a row with another number of fields than the header, or a cell
        that is not a number.
    """
    return read_turn_log_lines(path)[0]


def read_turn_log_lines(path: str | os.PathLike[str]) -> tuple[dict[str, np.ndarray], int]:
    """:func:`read_turn_log`, and the line number of the first row of values (comments and
    blank lines before it counted).

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    (dict of str to numpy.ndarray, int)
    """
    path = Path(path)
    if not path.exists():
        raise ParameterError(f"no such file: {path}")
    if not path.is_file():
        raise ParameterError(f"{path} is not a regular file")

    def content(reader: Any) -> Any:
        for row in reader:  # (blank rows and comment lines are not rows of the table)
            if any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#"):
                yield reader.line_num, row

    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            reader = csv.reader(fh)
            rows = content(reader)
            try:
                _, header = next(rows)
            except StopIteration:
                raise ParameterError(f"{path}: empty file (a header row is needed)") from None
            header = [h.strip() for h in header]
            rows = list(rows)
    except UnicodeDecodeError as exc:
        raise ParameterError(f"{path}: not UTF-8 text (byte {exc.start}); a CSV file with a "
                             "header row is needed") from None
    twice = [h for k, h in enumerate(header) if h in header[:k]]
    if twice:
        first, again = [k + 1 for k, h in enumerate(header) if h == twice[0]][:2]
        raise ParameterError(f"{path}: column `{twice[0]}` appears twice in the header "
                             f"(columns {first} and {again}; row 1)")
    if not rows:
        raise ParameterError(f"{path}: a header and no data rows (a record needs its samples)")
    cols: dict[str, list[float]] = {h: [] for h in header}
    for i, row in rows:
        if len(row) != len(header):
            raise ParameterError(
                f"{path}, line {i}: {len(row)} fields, the header has {len(header)}"
            )
        for h, cell in zip(header, row):
            try:
                cols[h].append(float(cell))
            except ValueError:
                raise ParameterError(
                    f"{path}, line {i}: column `{h}` is not a number: {cell!r}"
                ) from None
    first = rows[0][0] if rows else 2
    return {h: np.asarray(v, dtype=float) for h, v in cols.items()}, first
