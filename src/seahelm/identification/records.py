"""Manoeuvre records: what a sea trial or a free-running model test logged, for identification.

A :class:`ManoeuvreRecord` is one continuous record: times [s], the rudder angle [rad] and the
heading [rad] and/or yaw rate [rad/s], and optionally surge and sway speed [m/s], position
[m] and propeller rps [1/s]. :func:`read_records` reads them from

* a **CSV file** with a header row: columns ``time`` [s], ``rudder_angle``, ``heading`` or
  ``yaw_rate`` (or both), optional ``surge_speed``, ``sway_speed``, ``x`` (north) and ``y``
  (east) [m], ``propeller_rps`` [1/s]; angles in degrees by default (``angles="rad"`` for
  radians; angular rates then in deg/s or rad/s);
* a **CSV file** of recorded turns (:func:`read_turn_log`, ``seahelm identify steady-turn``):
  the numeric columns by header name, a time series (``time``, ``rudder_angle``,
  ``yaw_rate``, which :func:`~seahelm.identification.reduced.segments.extract_steady_segments`
  cuts into steady turns) or already-steady points (``rudder_angle``, ``yaw_rate``). Every CSV
  file is read by it: Python's :mod:`csv` with the checks a user needs to fix a file (the line
  and column of a cell that is not a number, a row with the wrong number of fields, an empty
  file, text that is not UTF-8; a UTF-8 byte-order mark is accepted);
* a **NetCDF result file** written by seahelm (``seahelm run --out``, a manoeuvre's
  ``*-runs.nc``): every run is a record (variables ``heading``, ``yaw_rate``,
  ``rudder_angle``, ``surge_speed``, ``sway_speed``, ``north``, ``east``,
  ``propeller_rps`` where present; SI units and radians), so a method can be checked on
  synthetic data.

Time must increase strictly (uneven sampling is fine). A **gap** — an interval longer than
five times the median sampling interval — splits a record in two (each part is then fitted
with its own initial state). NaN in a column, a time that does not increase, a missing column,
a rudder that does not move (no rudder activity: nothing to identify), a record shorter than
10 samples: :class:`~seahelm.errors.ParameterError` naming the file, the column and the row.
The heading is unwrapped (continuous through ±180°).

Other headers are read through a **column mapping** (``columns={"t [s]": "time", ...}``,
header -> channel). A file whose header holds every column of a known format in
:data:`RECORD_FORMATS` is read with that format's mapping and angle units without being told:
the free-running model tests of the Esso Osaka (the ``FRT-DS-ESSO`` data set of Osaka
University, Wakita et al. 2022, Miyauchi et al. 2022: ``t [s]``, ``x_position_mid [m]``,
``u_velo [m/s]``, ..., ``delta_rudder [rad]``, angles in radians) are read as they are. A
header that holds most of a format's columns but not all is an error naming the missing ones.
"""

from __future__ import annotations

import csv
import dataclasses
import math
import os
from pathlib import Path
from typing import Any, Literal

import numpy as np

from ..errors import ParameterError

__all__ = ["ManoeuvreRecord", "read_records", "record_from_arrays", "read_turn_log",
           "read_turn_log_lines", "GAP_FACTOR", "MIN_RUDDER_ACTIVITY", "RECORD_FORMATS"]

#: An interval longer than this many times the median sampling interval is a gap.
GAP_FACTOR = 5.0

#: The least rudder activity (standard deviation of the rudder angle) a record must have to
#: identify anything from it [rad] (0.1°).
MIN_RUDDER_ACTIVITY = math.radians(0.1)

#: The fewest samples of a record (each part after splitting at gaps).
MIN_SAMPLES = 10

_OPTIONAL = ("surge_speed", "sway_speed", "x", "y", "propeller_rps", "true_wind_speed",
             "true_wind_direction")
_ANGLES = ("rudder_angle", "heading", "true_wind_direction")

#: Known CSV record formats: name -> (header -> channel, angle units). ``FRT-DS-ESSO``: the
#: columns of the free-running tests of the Esso Osaka 3 m model (Osaka University, data set
#: ``NAOE-5thLab/FRT-DS-ESSO``; midship position and velocities, 10 Hz); its relative-wind
#: columns are not read. The true wind direction is the direction it comes from [rad].
RECORD_FORMATS: dict[str, tuple[dict[str, str], str]] = {
    "FRT-DS-ESSO": ({
        "t [s]": "time", "x_position_mid [m]": "x", "u_velo [m/s]": "surge_speed",
        "y_position_mid [m]": "y", "vm_velo [m/s]": "sway_speed", "psi_hat [rad]": "heading",
        "r_angvelo [rad/s]": "yaw_rate", "n_prop [rps]": "propeller_rps",
        "delta_rudder [rad]": "rudder_angle", "wind_velo_true [m/s]": "true_wind_speed",
        "wind_dir_true [rad]": "true_wind_direction"}, "rad"),
}
_RATES = ("yaw_rate",)


@dataclasses.dataclass(frozen=True)
class ManoeuvreRecord:
    """One continuous record of a manoeuvre (SI units, radians).

    Attributes
    ----------
    name : str
        Where it comes from (``file.csv``, ``file.nc[run 3]``, with ``#2`` for the second part
        of a record split at a gap).
    time : ndarray
        Times [s], strictly increasing.
    rudder_angle : ndarray
        δ [rad], positive turning to starboard.
    heading : ndarray or None
        ψ [rad], unwrapped (None when only the yaw rate was logged).
    yaw_rate : ndarray or None
        r [rad/s].
    channels : dict of str to ndarray
        The optional channels that were logged (surge_speed, sway_speed, x, y,
        propeller_rps, true_wind_speed, true_wind_direction).
    columns : dict of str to str
        Channel -> the file's own column name, where it differs (a mapped or known-format CSV
        header), for messages.
    """

    name: str
    time: np.ndarray
    rudder_angle: np.ndarray
    heading: np.ndarray | None = None
    yaw_rate: np.ndarray | None = None
    channels: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)
    columns: dict[str, str] = dataclasses.field(default_factory=dict)

    def column(self, channel: str) -> str:
        """The file's name of a channel's column (the channel's own name if not mapped).

        Parameters
        ----------
        channel : str
            A channel (``heading``, ``true_wind_speed``, ...).

        Returns
        -------
        str
        """
        return self.columns.get(channel, channel)

    @property
    def duration(self) -> float:
        """Length of the record [s]."""
        return float(self.time[-1] - self.time[0])

    @property
    def median_interval(self) -> float:
        """Median sampling interval [s]."""
        return float(np.median(np.diff(self.time)))

    def __len__(self) -> int:
        return int(self.time.size)

    def _summary(self) -> tuple[str, list[tuple[str, object]]]:
        from .._repr import names

        span = (f"{len(self)} samples, t = {self.time[0]:.6g} … {self.time[-1]:.6g} s, "
                f"every {self.median_interval:.3g} s" if len(self) > 1
                else f"{len(self)} sample(s)")
        logged = ["rudder_angle"] + [k for k in ("heading", "yaw_rate")
                                     if getattr(self, k) is not None] + list(self.channels)
        mapped = [f"{k} = {v!r}" for k, v in self.columns.items() if v != k]
        return f"ManoeuvreRecord: {self.name}", [
            ("record", span), ("channels", names(logged, 10)),
            ("columns", names(mapped, 4) if mapped else "the channels' own names")]

    def __repr__(self) -> str:
        from .._repr import summary_text

        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        from .._repr import summary_html

        return summary_html(*self._summary())


#: The largest magnitude a record's column may have [SI units]: beyond it a value is a unit
#: mix-up or garbage, not a ship's motion (a rudder of 1e300 deg ran into numpy overflow
#: warnings and an optimiser's message, a heading of 1e200 rad was fitted without a word).
COLUMN_LIMITS = {"rudder_angle": (math.pi / 2, "rad"), "heading": (2000.0 * math.pi, "rad"),
                 "yaw_rate": (2.0 * math.pi, "rad/s"), "surge_speed": (100.0, "m/s"),
                 "sway_speed": (100.0, "m/s"), "propeller_rps": (1000.0, "1/s"),
                 "x": (1e8, "m"), "y": (1e8, "m"), "time": (1e9, "s"),
                 # (the highest gust measured: 113 m/s, Barrow Island 1996, WMO)
                 "true_wind_speed": (150.0, "m/s"),
                 "true_wind_direction": (2000.0 * math.pi, "rad")}


def _check_column(source: str, name: str, values: np.ndarray, first_row: int,
                  channel: str | None = None) -> None:
    """Refuse a non-finite value and one beyond its channel's :data:`COLUMN_LIMITS` (named
    ``name``, the file's header; ``channel`` the channel it is read as, default ``name``)."""
    bad = ~np.isfinite(values)
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        raise ParameterError(f"{source}: column `{name}` row {first_row + i} is not a finite "
                             f"number ({float(values[i])!r})", field=name)
    limit, unit = COLUMN_LIMITS.get(name if channel is None else channel, (math.inf, ""))
    big = np.abs(values) > limit
    if np.any(big):
        i = int(np.flatnonzero(big)[0])
        raise ParameterError(f"{source}: column `{name}` row {first_row + i} is "
                             f"{values[i]:.6g} {unit}, beyond ±{limit:.6g} {unit} (in SI units; a "
                             "unit mix-up or a damaged value?)", field=name, unit=unit,
                             value=float(values[i]))


def record_from_arrays(name: str, time: Any, rudder_angle: Any, heading: Any = None,
                       yaw_rate: Any = None, *, first_row: int = 0,
                       **channels: Any) -> list[ManoeuvreRecord]:
    """Records from arrays (SI units, radians), checked and split at gaps.

    Parameters
    ----------
    name : str
        Source, for messages and labels.
    time, rudder_angle : array_like
        t [s] (strictly increasing), δ [rad].
    heading, yaw_rate : array_like, optional
        ψ [rad] (unwrapped here), r [rad/s]; at least one.
    first_row : int, optional
        Row number of the first sample in the source (for messages; a CSV file's data start
        at line 2).
    **channels : array_like
        Optional channels (surge_speed, sway_speed, x, y, propeller_rps).

    Returns
    -------
    list of ManoeuvreRecord
        One per part between gaps.
    """
    t = np.asarray(time, dtype=float)
    cols: dict[str, np.ndarray] = {"time": t, "rudder_angle": np.asarray(rudder_angle, float)}
    if heading is None and yaw_rate is None:
        raise ParameterError(f"{name}: a `heading` or `yaw_rate` column is needed",
                             field="heading")
    if heading is not None:
        cols["heading"] = np.asarray(heading, dtype=float)
    if yaw_rate is not None:
        cols["yaw_rate"] = np.asarray(yaw_rate, dtype=float)
    for key, values in channels.items():
        if key not in _OPTIONAL:
            raise ParameterError(f"{name}: unknown channel `{key}`; valid: "
                                 f"{', '.join(_OPTIONAL)}", field=key)
        cols[key] = np.asarray(values, dtype=float)
    for key, values in cols.items():
        if values.shape != t.shape or values.ndim != 1:
            raise ParameterError(f"{name}: column `{key}` has shape {values.shape}, time "
                                 f"{t.shape}", field=key)
        _check_column(name, key, values, first_row)
    if t.size < MIN_SAMPLES:
        raise ParameterError(f"{name}: {t.size} samples; a record needs at least "
                             f"{MIN_SAMPLES}", field="time")
    step = np.diff(t)
    if np.any(step <= 0):
        i = int(np.flatnonzero(step <= 0)[0]) + 1
        raise ParameterError(f"{name}: column `time` row {first_row + i} does not increase "
                             f"({t[i - 1]!r} then {t[i]!r})", field="time")
    if "heading" in cols:
        cols["heading"] = np.unwrap(cols["heading"])
    gaps = np.flatnonzero(step > GAP_FACTOR * np.median(step)) + 1
    bounds = [0, *gaps.tolist(), t.size]
    parts = []
    for k, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        label = name if len(bounds) == 2 else f"{name}#{k + 1}"
        if b - a < MIN_SAMPLES:
            continue  # (a few samples between gaps: nothing to fit)
        part = {key: v[a:b].copy() for key, v in cols.items()}
        if float(np.std(part["rudder_angle"])) < MIN_RUDDER_ACTIVITY:
            raise ParameterError(
                f"{label}: the rudder angle does not move (standard deviation "
                f"{math.degrees(float(np.std(part['rudder_angle']))):.3g} deg < "
                f"{math.degrees(MIN_RUDDER_ACTIVITY):g} deg): no rudder activity, nothing to "
                "identify", field="rudder_angle")
        parts.append(ManoeuvreRecord(
            name=label, time=part.pop("time"), rudder_angle=part.pop("rudder_angle"),
            heading=part.pop("heading", None), yaw_rate=part.pop("yaw_rate", None),
            channels=part))
    if not parts:
        raise ParameterError(f"{name}: every part between gaps is shorter than {MIN_SAMPLES} "
                             "samples", field="time")
    return parts


def _known_format(path: Path, header: list[str]) -> tuple[dict[str, str], str] | None:
    """The mapping and angle units of the known format the header is (None if none)."""
    for name, (mapping, angles) in RECORD_FORMATS.items():
        present = [h for h in mapping if h in header]
        if len(present) == len(mapping):
            return mapping, angles
        if 2 * len(present) > len(mapping):
            missing = [h for h in mapping if h not in header]
            raise ParameterError(f"{path}: a {name} record without column(s) "
                                 f"{', '.join(f'`{m}`' for m in missing)} (row 1, the header)",
                                 field=mapping[missing[0]])
    return None


def _mapped(path: Path, cols: dict[str, np.ndarray], mapping: dict[str, str],
            first_row: int = 2) -> dict[str, np.ndarray]:
    """The mapped columns by channel, checked under their own header names (NaN, a time
    that does not increase: the file's column and row)."""
    known = ("time", "rudder_angle", "heading", "yaw_rate", *_OPTIONAL)
    out = {}
    for header, channel in mapping.items():
        if channel not in known:
            raise ParameterError(f"{path}: column `{header}` mapped to an unknown channel "
                                 f"`{channel}`; valid: {', '.join(known)}", field="column")
        if channel in out:
            other = next(h for h, c in mapping.items() if c == channel)
            raise ParameterError(f"{path}: columns `{other}` and `{header}` both mapped to "
                                 f"`{channel}` (one column per channel)", field="column")
        if header not in cols:
            raise ParameterError(f"{path}: no column `{header}` (mapped to {channel}; columns: "
                                 f"{', '.join(cols)})", field=channel)
        # (angles are limited once in radians, after --angles: record_from_arrays)
        _check_column(str(path), header, cols[header], first_row,
                      "" if channel in _ANGLES + _RATES else channel)
        out[channel] = cols[header]
    if "time" in out:
        step = np.diff(out["time"])
        if np.any(step <= 0):
            i = int(np.flatnonzero(step <= 0)[0]) + 1
            header = next(h for h, c in mapping.items() if c == "time")
            raise ParameterError(f"{path}: column `{header}` row {i + first_row} does not increase "
                                 f"({float(out['time'][i - 1])!r} then "
                                 f"{float(out['time'][i])!r})",
                                 field="time")
    return out


def _read_csv(path: Path, angles: str, columns: dict[str, str] | None
              ) -> list[ManoeuvreRecord]:
    cols, first_row = read_turn_log_lines(path)
    known = None if columns is not None else _known_format(path, list(cols))
    hint = "drop --angles rad"
    if known is not None:
        columns, angles = known
        hint = "this file's format is in radians"
    names = {"rudder_angle": "rudder_angle"}
    if columns is not None:
        cols = _mapped(path, cols, columns, first_row)
        names.update({c: h for h, c in columns.items()})
    for required in ("time", "rudder_angle"):
        if required not in cols:
            raise ParameterError(f"{path}: missing column `{required}` (columns: "
                                 f"{', '.join(cols)})", field=required)
    if "heading" not in cols and "yaw_rate" not in cols:
        raise ParameterError(f"{path}: missing column `heading` or `yaw_rate` (columns: "
                             f"{', '.join(cols)})", field="heading")
    scale = math.pi / 180.0 if angles == "deg" else 1.0
    widest = float(np.nanmax(np.abs(cols["rudder_angle"])))
    for key in _ANGLES + _RATES:
        if key in cols:
            cols[key] = cols[key] * scale
    if angles == "rad" and np.nanmax(np.abs(cols["rudder_angle"])) > math.pi / 2:
        row = int(np.flatnonzero(np.abs(cols["rudder_angle"]) > math.pi / 2)[0]) + first_row
        raise ParameterError(
            f"{path}: column `{names['rudder_angle']}` row {row} is "
            f"{cols['rudder_angle'][row - first_row]:.4g} rad (more than 90°) with angles in radians: "
            f"are they degrees? ({hint})", field="rudder_angle")
    channels = {k: cols[k] for k in _OPTIONAL if k in cols}
    parts = record_from_arrays(str(path), cols["time"], cols["rudder_angle"],
                               cols.get("heading"), cols.get("yaw_rate"), first_row=first_row,
                               **channels)
    if angles == "deg" and 0.0 < widest <= math.pi / 2:  # (a valid record, in radians?)
        import warnings

        warnings.warn(f"{path}: column `rudder_angle` stays within ±{widest:.4g} read as "
                      f"degrees (a manoeuvre's rudder is some 10-35°): are they radians? "
                      "(give --angles rad)", UserWarning, stacklevel=3)
    if columns is None:
        return parts
    renamed = {c: h for h, c in columns.items() if c != h}
    return [dataclasses.replace(p, columns=renamed) for p in parts]


def _read_netcdf(path: Path) -> list[ManoeuvreRecord]:
    from ..result_layout import flatten_runs
    from ..results import load_result

    ds = flatten_runs(load_result(path))
    if "rudder_angle" not in ds:
        raise ParameterError(f"{path}: no variable `rudder_angle` (a model whose input it is, "
                             "e.g. the Nomoto, Mariner or MMG model, is needed)",
                             field="rudder_angle")
    names = {"north": "x", "east": "y"}
    out: list[ManoeuvreRecord] = []
    runs = ds.sizes.get("run", 1)
    time = np.asarray(ds["time"].values, dtype=float)
    for i in range(runs):
        run = ds.isel(run=i) if "run" in ds.dims else ds
        if "status" in run and int(np.asarray(run["status"].values)) != 0:
            continue  # a diverged run is no record

        def get(v: str, run: Any = run) -> np.ndarray | None:
            return np.asarray(run[v].values, dtype=float) if v in run else None

        channels = {names.get(v, v): get(v) for v in ("surge_speed", "sway_speed", "north",
                                                      "east", "propeller_rps") if v in run}
        out += record_from_arrays(f"{path}[run {i}]", time, get("rudder_angle"),
                                  get("heading"), get("yaw_rate"), **channels)
    return out


def read_records(paths: Any, *, angles: Literal["deg", "rad"] = "deg",
                 columns: dict[str, str] | None = None) -> list[ManoeuvreRecord]:
    """Records from CSV and NetCDF files (module docstring), split at gaps.

    Parameters
    ----------
    paths : path-like or sequence of path-like
        CSV files (``*.csv``) and seahelm NetCDF result files (``*.nc``).
    angles : {"deg", "rad"}
        Units of the CSV files' angles and angular rates (NetCDF files are always SI; a file of
        a known format, :data:`RECORD_FORMATS`, in that format's units).
    columns : dict of str to str, optional
        CSV header -> channel (``time``, ``rudder_angle``, ``heading``, ``yaw_rate`` and the
        optional channels); only the mapped columns are read (default: the header names are
        the channels, or a known format's mapping).

    Returns
    -------
    list of ManoeuvreRecord

    Raises
    ------
    ParameterError
        A missing file or column, a bad value (naming the file, column and row), no rudder
        activity, too few samples.
    """
    if angles not in ("deg", "rad"):
        raise ParameterError(f"must be 'deg' or 'rad', got {angles!r}", field="angles")
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    out: list[ManoeuvreRecord] = []
    for p in paths:
        path = Path(p)
        if not path.exists():
            raise ParameterError(f"no such file: {path}")
        if path.suffix.lower() in (".nc", ".nc4", ".h5", ".netcdf"):
            out += _read_netcdf(path)
        else:
            out += _read_csv(path, angles, columns)
    if not out:
        raise ParameterError("no records (every run of the files diverged)")
    return out


# ------------------------------------------------------------------------------------------
# the CSV reader (every CSV record, and the turn log of the reduced steady-turn model)
# ------------------------------------------------------------------------------------------
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
