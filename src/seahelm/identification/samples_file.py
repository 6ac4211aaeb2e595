"""Samples files: Monte-Carlo draws given as numbers, one row per sample.

A posterior of identified coefficients (:mod:`seahelm.identification.mmg_posterior`,
``seahelm identify mmg --imo N --save-posterior FILE.csv``) is a set of samples, not a
distribution with a formula. A samples file holds them so that they can be used as the draws of
a Monte-Carlo study: ``seahelm imo SHIP --draws FILE.csv`` and a scenario's
``[batch.monte_carlo] samples = "FILE.csv"`` give sample *i* the values of row *i*.

The format is CSV (UTF-8):

* any number of comment lines first, starting with ``#`` (what the samples are, where they
  come from); a comment ``# units: KEY = UNIT, ...`` gives the columns' units, stored units
  as in a scenario (radians, SI; ``1`` for a non-dimensional value);
* a header row of **key paths** as a scenario writes them, ``vessel.params.<name>`` (the
  ship's parameters, its stored units) or ``actuator.params.<name>`` (its steering gear's);
* one row per sample, every value a finite number.

:func:`write_samples` writes one (each number as the shortest decimal that reads back as the
same double, Python's ``repr``: a study on the file repeats the one that wrote it to the last
bit);
:func:`read_samples` reads one, with a :class:`~seahelm.errors.ParameterError` naming the file,
the column and the row of what is wrong; :func:`check_units` refuses a column whose unit is not its
parameter's stored one (``seahelm imo --draws`` calls it).
"""

from __future__ import annotations

import csv
import dataclasses
import io
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..output_files import write_output

__all__ = ["SamplesFile", "read_samples", "write_samples", "samples_attrs", "check_units",
           "KEY_PREFIXES"]

#: What a samples file's columns may draw.
KEY_PREFIXES = ("vessel.params.", "actuator.params.")


@dataclasses.dataclass(frozen=True)
class SamplesFile:
    """The contents of a samples file.

    Attributes
    ----------
    keys : tuple of str
        The columns' key paths.
    values : ndarray, shape (samples, len(keys))
    units : dict of str to str
        The unit of each key that has one (from the ``# units:`` comment).
    comments : tuple of str
        The other comment lines, without the ``#``.
    path : str
        Where it was read from.
    """

    keys: tuple[str, ...]
    values: np.ndarray
    units: dict[str, str]
    comments: tuple[str, ...]
    path: str = ""

    @property
    def n_samples(self) -> int:
        """The number of samples (rows)."""
        return int(self.values.shape[0])

    def column(self, key: str) -> np.ndarray:
        """The values of one key, over the samples.

        Parameters
        ----------
        key : str
            A key path of :attr:`keys`.

        Returns
        -------
        ndarray, shape (samples,)
        """
        return self.values[:, self.keys.index(key)]


def write_samples(path: str | Path, columns: Mapping[str, Sequence[float]], *,
                  units: Mapping[str, str] | None = None,
                  comments: Sequence[str] = (), force: bool = False) -> Path:
    """Write a samples file (module docstring).

    Parameters
    ----------
    path : str or Path
        The file (``.csv``).
    columns : mapping of key path to values
        One entry per column, each with one value per sample.
    units : mapping of key path to unit, optional
        Written in the ``# units:`` comment.
    comments : sequence of str, optional
        Comment lines written first (one line each).
    force : bool, optional
        Replace an existing file that is not a seahelm table (default False; the output
        policy, :func:`seahelm.output_files.check_output`).

    Returns
    -------
    Path

    Notes
    -----
    Written atomically (:func:`seahelm.results.atomic_write`): an interrupted or failed write
    leaves no half-written file (nor a partly replaced old one).
    """
    path = Path(path)
    keys = list(columns)
    _check_keys(keys, str(path))
    values = np.column_stack([np.asarray(columns[k], dtype=float) for k in keys])
    bad = np.argwhere(~np.isfinite(values))
    if bad.size:
        i, j = (int(x) for x in bad[0])
        raise ParameterError(f"{path}: sample {i} of `{keys[j]}` is not a finite number "
                             f"({values[i, j]!r})", field=keys[j])
    text = io.StringIO()
    for line in comments:
        for part in str(line).splitlines() or [""]:
            text.write(f"# {part}\n")
    if units:
        text.write("# units: " + ", ".join(f"{k} = {units[k] or '1'}" for k in keys
                                           if k in units) + "\n")
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(keys)
    for row in values:
        writer.writerow([repr(float(x)) for x in row])
    data = text.getvalue().encode("utf-8")
    return write_output(path, lambda tmp: Path(tmp).write_bytes(data), "csv", force=force)


def _check_keys(keys: Sequence[str], where: str) -> None:
    if not keys:
        raise ParameterError(f"{where}: no columns (a header row of key paths such as "
                             "vessel.params.N_v)", field="samples")
    for k in keys:
        if not k.startswith(KEY_PREFIXES) or k.count(".") != 2 or k.endswith("."):
            raise ParameterError(f"{where}: column `{k}` is not a key path "
                                 f"({' or '.join(p + '<name>' for p in KEY_PREFIXES)})",
                                 field=k)
    twice = sorted({k for k in keys if keys.count(k) > 1})
    if twice:
        raise ParameterError(f"{where}: column `{twice[0]}` appears twice", field=twice[0])


def read_samples(path: str | Path) -> SamplesFile:
    """Read a samples file (module docstring).

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    SamplesFile

    Raises
    ------
    ParameterError
        A missing file, no header, a column that is not a key path or appears twice, a row of
        the wrong length, a value that is not a finite number (naming the column and the row,
        counted in lines of the file), no samples.
    """
    path = Path(path)
    try:
        lines = path.read_text(encoding="utf-8-sig").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise ParameterError(f"{path}: cannot be read ({exc})", field="samples") from None
    comments, units, start = [], {}, 0
    while start < len(lines) and (lines[start].startswith("#") or not lines[start].strip()):
        line = lines[start].lstrip("#").strip()
        if line.startswith("units:"):
            for item in line[len("units:"):].split(","):
                key, _, unit = item.partition("=")
                if key.strip():
                    units[key.strip()] = unit.strip()
        elif line:
            comments.append(line)
        start += 1
    rows = list(csv.reader(lines[start:]))
    if not rows:
        raise ParameterError(f"{path}: no header row (key paths such as vessel.params.N_v)",
                             field="samples")
    keys = [k.strip() for k in rows[0]]
    _check_keys(keys, str(path))
    values = np.empty((len(rows) - 1, len(keys)))
    for i, row in enumerate(rows[1:]):
        line_no = start + 2 + i
        if len(row) != len(keys):
            raise ParameterError(f"{path}: line {line_no} has {len(row)} values, the header "
                                 f"{len(keys)}", field="samples")
        for j, cell in enumerate(row):
            try:
                x = float(cell)
            except ValueError:
                x = math.nan
            if not math.isfinite(x):
                raise ParameterError(f"{path}: column `{keys[j]}` line {line_no} is not a "
                                     f"finite number ({cell.strip()!r})", field=keys[j])
            values[i, j] = x
    if values.shape[0] == 0:
        raise ParameterError(f"{path}: no samples (rows) after the header", field="samples")
    return SamplesFile(keys=tuple(keys), values=values,
                       units={k: u for k, u in units.items() if k in keys},
                       comments=tuple(comments), path=str(path))


def samples_attrs(samples: SamplesFile) -> dict[str, Any]:
    """Attributes of a samples file's keys for a result: ``distribution = "samples"``, the
    file, and the unit where it has one.

    Parameters
    ----------
    samples : SamplesFile

    Returns
    -------
    dict of key path to dict
    """
    return {k: {"distribution": "samples", "samples_file": samples.path,
                **({"units": samples.units[k]} if samples.units.get(k) not in (None, "", "1")
                   else {})}
            for k in samples.keys}


#: Ways of writing "no unit" (the writer's ``1``, a parameter table's ``-``).
_NO_UNIT = ("", "1", "-")


def check_units(samples: SamplesFile, units: Mapping[str, str]) -> None:
    """Refuse a column whose ``# units:`` unit is not the stored unit of its parameter.

    A samples file holds stored units (module docstring); a column in other units (degrees
    for radians, a dimensional unit for a non-dimensional coefficient) would be taken as
    stored numbers. Columns without a unit in the file, and keys not in ``units``, pass.

    Parameters
    ----------
    samples : SamplesFile
    units : mapping of key path to unit
        The stored unit of each key (``-``, ``1`` or empty for none).

    Raises
    ------
    ParameterError
        Naming the file, the column, its unit and the stored one.
    """
    for key, unit in samples.units.items():
        if key not in units:
            continue
        want = units[key] or "1"
        have = unit or "1"
        if (have in _NO_UNIT) != (want in _NO_UNIT) or (have not in _NO_UNIT
                                                        and have != want):
            raise ParameterError(f"{samples.path}: column `{key}` is in {have!r}; its stored "
                                 f"unit is {want!r} (a samples file holds stored units)",
                                 field=key, unit=want, value=have)
