"""What a :class:`~seahelm.simulation.stepping.Simulator` takes and gives by name: the
commands of a step, checked (:func:`check_commands`), and the outputs after it
(:class:`Observation`); and the compiled copy that sets runs back to their start
(:func:`restore_rows`)."""

from __future__ import annotations

import operator
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np
from numba import njit

from ..errors import ParameterError
from .inputs import check_rudder_angles

__all__ = ["Observation", "check_commands", "restore_rows", "run_index", "run_indices"]


class Observation(Mapping):
    """The outputs of every run after a step, by name: ``obs["heading"]`` is an array (runs,).

    Attributes
    ----------
    time : ndarray (runs,)
        Each run's time [s].
    values : ndarray (runs, outputs)
        The outputs, in the order of ``labels`` (the model's, the environment's, the
        first-order motions'; as recorded in :class:`~seahelm.results.SimResult`'s ``output``).
    labels, units : tuple of str
    status : ndarray of int (runs,)
        Each run's :class:`~seahelm.simulation.engine.RunStatus` (a diverged run stays
        diverged: stepping it is refused).
    """

    __slots__ = ("time", "values", "labels", "units", "status", "_index")

    def __init__(self, time: np.ndarray, values: np.ndarray, labels: tuple[str, ...],
                 units: tuple[str, ...], status: np.ndarray, index: dict[str, int]) -> None:
        self.time, self.values, self.labels, self.units = time, values, labels, units
        self.status, self._index = status, index

    def __getitem__(self, name: str) -> np.ndarray:
        j = self._index.get(name)
        if j is None:
            raise KeyError(f"no output {name!r}; outputs: {', '.join(self.labels)}")
        return self.values[:, j]

    def __iter__(self) -> Iterator[str]:
        return iter(self.labels)

    def __len__(self) -> int:
        return len(self.labels)

    def __repr__(self) -> str:
        return (f"Observation(runs={self.values.shape[0]}, t={self.time[:3]}, "
                f"outputs={', '.join(self.labels)})")


def check_commands(commands: Any, sel: np.ndarray, held: np.ndarray, labels: tuple[str, ...],
                   units: tuple[str, ...]) -> np.ndarray:
    """Commands given to :meth:`Simulator.step`, checked: (selected runs, commands).

    Parameters
    ----------
    commands : array_like or mapping
        (runs, commands) or (commands,) by ``labels``, or a mapping name -> value(s).
    sel : ndarray of int
        The runs stepped (one row of commands each).
    held : ndarray
        Their commands now (the commands a mapping does not name keep these).
    labels, units : tuple of str
        The command names and units.

    Returns
    -------
    ndarray (runs, commands)

    Raises
    ------
    ParameterError
        On a wrong shape, an unknown name, a value that is not a finite number (``None``
        included, which numpy would read as nan) or a rudder beyond ±90 deg
        (:func:`~seahelm.simulation.inputs.check_rudder_angles`).
    """
    nc = len(labels)
    index = {name: j for j, name in enumerate(labels)}
    units_text = ", ".join(f"{name} [{u}]" if u else name for name, u in zip(labels, units))
    if isinstance(commands, Mapping):
        values = held.copy()
        for name, v in commands.items():
            if name not in index:
                raise ParameterError(f": unknown command {name!r}; commands: {units_text}",
                                     field="commands", value=name)
            try:
                col = _numbers(v)
            except (TypeError, ValueError):
                raise ParameterError(f"[{name!r}] must be a number or numbers (one per stepped "
                                     f"run) [{units[index[name]]}], got {v!r}",
                                     field="commands", value=v) from None
            if col.ndim > 1 or (col.ndim == 1 and col.shape[0] != sel.size):
                raise ParameterError(f"[{name!r}] must be a number or have shape "
                                     f"({sel.size},) (one per stepped run), got "
                                     f"{col.shape}", field="commands", value=col.shape)
            values[:, index[name]] = col
    else:
        try:
            values = _numbers(commands)
        except (TypeError, ValueError):
            raise ParameterError(f"must be numbers (runs, {nc}) by {units_text}, got "
                                 f"{commands!r}", field="commands") from None
        if values.shape == (nc,):
            values = np.broadcast_to(values, (sel.size, nc))
        if values.shape != (sel.size, nc):
            raise ParameterError(f"must have shape ({sel.size}, {nc}) (stepped runs, "
                                 f"commands: {units_text}) or ({nc},), got {values.shape}",
                                 field="commands", value=values.shape)
    if not np.isfinite(values).all():
        r, j = np.argwhere(~np.isfinite(values))[0]
        raise ParameterError(f": command {labels[j]!r} of run {int(sel[r])} "
                             f"is {float(values[r, j])!r}; commands must be finite "
                             f"({units_text})",
                             field="commands", value=float(values[r, j]),
                             run=int(sel[r]))
    check_rudder_angles("commands", values, labels, units, sel)
    return values


def _numbers(value: Any) -> np.ndarray:
    """``value`` as float64, refusing ``None`` (numpy would make it nan, and the error would
    then say the command "is nan")."""
    if value is None:
        raise TypeError("None")
    if type(value) is np.ndarray and value.dtype != object:
        return np.asarray(value, dtype=float)
    raw = np.asarray(value)
    if raw.dtype == object and any(v is None for v in raw.flat):
        raise TypeError("None")
    return np.asarray(raw, dtype=float)


def _spans(sel: np.ndarray) -> list[tuple[int, int]]:
    """Sorted unique indices as contiguous spans [i0, i1)."""
    if sel.size == 0:
        return []
    if sel.size <= 16:  # (a few runs: a loop over them costs less than the array calls)
        idx = sel.tolist()
        spans, start = [], idx[0]
        for prev, i in zip(idx, idx[1:]):
            if i != prev + 1:
                spans.append((start, prev + 1))
                start = i
        spans.append((start, idx[-1] + 1))
        return spans
    cut = np.flatnonzero(np.diff(sel) != 1) + 1
    starts = np.concatenate([[0], cut])
    stops = np.concatenate([cut, [sel.size]])
    return [(int(sel[s]), int(sel[e - 1]) + 1) for s, e in zip(starts, stops)]


def _out_of_range(what: str, i: int, n_runs: int) -> ParameterError:
    """The one message of a run index out of range (``run`` and ``runs`` alike)."""
    return ParameterError(f"must be a run index in {-n_runs} ... {n_runs - 1} (negative: from "
                          f"the end, as numpy), got {i}", field=what, value=i)


def run_index(run: Any, n_runs: int) -> int:
    """``run`` as the index of one of ``n_runs`` runs (negative from the end, as numpy), or a
    :class:`ParameterError` naming ``run``.

    Parameters
    ----------
    run : int
        A run index (negative: from the end).
    n_runs : int
        Runs of the batch.
    """
    try:
        if isinstance(run, (bool, np.bool_)):  # (True was run 1)
            raise TypeError
        i = operator.index(run)
    except TypeError:
        raise ParameterError(f"must be a run index (an integer), got {run!r}", field="run",
                             value=run) from None
    if not -n_runs <= i < n_runs:
        raise _out_of_range("run", i, n_runs)
    return i % n_runs


def run_indices(runs: Any, n_runs: int, *, as_given: bool = False) -> np.ndarray:
    """``runs`` (None: all; indices or a boolean mask) as sorted unique indices of ``n_runs``
    runs, or a :class:`ParameterError` naming ``runs``.

    Negative indices count from the end, as in :func:`run_index` (and numpy); a run given
    twice is refused (its commands would be ambiguous).

    Parameters
    ----------
    runs : None, int, sequence of int or ndarray of bool
        The runs (None: all), as indices or a mask of ``n_runs``.
    n_runs : int
        Runs of the batch.
    as_given : bool
        Return the indices in the order given (the order of a step's command rows), not
        sorted.
    """
    if runs is None:
        return np.arange(n_runs)
    if type(runs) is np.ndarray and runs.dtype == np.int64 and runs.ndim == 1 \
            and runs.size and 0 <= runs[0] and runs[-1] < n_runs \
            and (runs.size == 1 or bool((runs[1:] > runs[:-1]).all())):
        # (sorted unique indices in range, as np.flatnonzero gives them: np.unique costs
        # some 10 µs, most of a restart of a few sub-environments)
        return runs.copy()
    arr = np.atleast_1d(np.asarray(runs))
    if arr.dtype == bool:
        if arr.shape != (n_runs,):
            raise ParameterError(f"as a mask must have shape ({n_runs},), got {arr.shape}",
                                 field="runs", value=arr.shape)
        arr = np.flatnonzero(arr)
    if arr.ndim != 1 or (arr.size and arr.dtype.kind not in "iu"):
        raise ParameterError(f"must be run indices (integers), got {runs!r}", field="runs",
                             value=runs)
    arr = arr.astype(np.int64)
    bad = (arr < -n_runs) | (arr >= n_runs)
    if bad.any():
        raise _out_of_range("runs", int(arr[np.argmax(bad)]), n_runs)
    arr = arr % max(n_runs, 1)
    unique, counts = np.unique(arr, return_counts=True)
    if (counts > 1).any():
        i = int(unique[np.argmax(counts > 1)])
        raise ParameterError(f"must name each run once, got run {i} {int(counts.max())} times "
                             f"in {runs!r}", field="runs", value=i)
    return arr if as_given else unique


@njit(cache=True)
def restore_rows(sel, state, outcome, record, fresh_state, fresh_outcome,
                 fresh_record):  # pragma: no cover - compiled
    """The rows ``sel`` of the kernel's ``state``, ``outcome`` and ``record`` groups
    (:data:`~seahelm.simulation.kernel_args.GROUPS`) set back to those of their copies at the
    start (``Simulator._fresh_groups``): the arrays of runs started again
    (:meth:`Simulator.reset`, :func:`~seahelm.simulation.stepping_reference.restart_runs`).
    One compiled call: the ten
    fancy-indexed assignments it replaces cost some 30 µs, a third of the restart of a few
    sub-environments of :mod:`seahelm.gym` (issue 52, speed). A copy: the same numbers.

    Parameters
    ----------
    sel : ndarray of int64
        The runs.
    state, outcome, record : tuple of ndarray
        The kernel's groups (runs first).
    fresh_state, fresh_outcome, fresh_record : tuple of ndarray
        Their copies at the start, alike in shapes and dtypes.
    """
    z, cs, cmd, ca = state
    z0, cs0, cmd0, ca0 = fresh_state
    status, t_fail, z_fail = outcome
    status0, t_fail0, z_fail0 = fresh_outcome
    rec_z, rec_y, rec_cmd = record
    rec_z0, rec_y0, rec_cmd0 = fresh_record
    for i in sel:
        z[i] = z0[i]
        cs[i] = cs0[i]
        cmd[i] = cmd0[i]
        ca[i] = ca0[i]
        status[i] = status0[i]
        t_fail[i] = t_fail0[i]
        z_fail[i] = z_fail0[i]
        rec_z[i] = rec_z0[i]
        rec_y[i] = rec_y0[i]
        rec_cmd[i] = rec_cmd0[i]
