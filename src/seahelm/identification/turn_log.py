"""Recorded turns from a CSV file: the numeric columns of a log with a header row.

A turn log is either a time series (columns ``time``, ``rudder_angle``, ``yaw_rate``, which
:func:`~seahelm.identification.segments.extract_steady_segments` cuts into steady turns) or
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

import numpy as np

from ..errors import ParameterError

__all__ = ["read_turn_log"]


def read_turn_log(path: str | os.PathLike[str]) -> dict[str, np.ndarray]:
    """The numeric columns of a CSV file with a header row, by header name.

    Parameters
    ----------
    path : str or os.PathLike
        A CSV file: a header row, then one row of numbers per sample (blank rows skipped).

    Returns
    -------
    dict of str to numpy.ndarray
        One float array per column, in the header's order (names stripped of blanks).

    Raises
    ------
    ParameterError
        If the file is missing, not a regular file, empty, not UTF-8 text, has a row with
        another number of fields than the header, or a cell that is not a number.
    """
    path = Path(path)
    if not path.exists():
        raise ParameterError(f"no such file: {path}")
    if not path.is_file():
        raise ParameterError(f"{path} is not a regular file")
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            reader = csv.reader(fh)
            try:
                header = [h.strip() for h in next(reader)]
            except StopIteration:
                raise ParameterError(f"{path}: empty file (a header row is needed)") from None
            rows = [r for r in reader if any(cell.strip() for cell in r)]
    except UnicodeDecodeError as exc:
        raise ParameterError(f"{path}: not UTF-8 text (byte {exc.start}); a CSV file with a "
                             "header row is needed") from None
    cols: dict[str, list[float]] = {h: [] for h in header}
    for i, row in enumerate(rows, start=2):
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
    return {h: np.asarray(v, dtype=float) for h, v in cols.items()}
