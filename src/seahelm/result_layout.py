"""The layout of a batch's results: the dimensions its runs span, and the flat ``run`` view.

:class:`BatchLayout` (its :class:`BatchAxis` dimensions and :class:`BatchValues` per-run
values) describes the shape of the question a batch answers: a 3 × 4 grid over ``kp`` and
``kd`` spans ``kp × kd`` (runs in C order), a Monte-Carlo batch adds ``sample``, a plain batch
spans one ``run`` dimension. :func:`batch_dims` and :func:`flatten_runs` read the same layout
back from a result Dataset.

Below :mod:`seahelm.results`, :mod:`seahelm.simulation` and :mod:`seahelm.plotting` (all use
it; it imports nothing of theirs): the simulation builds a layout
(:mod:`seahelm.simulation.batch` re-exports the classes), the results keep it and shape their
Dataset by it, so :mod:`seahelm.results` needs no simulation import, not even for typing.
:mod:`seahelm.results` re-exports both functions.
"""

from __future__ import annotations

import dataclasses
import math
import types
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ParameterError

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["BatchAxis", "BatchValues", "BatchLayout", "batch_dims", "flatten_runs"]

#: Names a batch dimension may not take (the result's own dimensions).
RESERVED_DIMS = ("time",)


def _frozen_array(name: str, values: Any) -> np.ndarray:
    arr = np.array(values)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"`{name}` must be a non-empty 1-D sequence, got shape {arr.shape}")
    if arr.dtype.kind not in "biuf":
        raise ParameterError(f"`{name}` must hold numbers, got dtype {arr.dtype}")
    arr.setflags(write=False)
    return arr


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class BatchAxis:
    """One dimension of a batch: its name, coordinate values and the key path it varies.

    Parameters
    ----------
    name : str
        Dimension name, e.g. ``"kp"`` (the last component of the key path when that is unique).
    values : sequence of float
        Coordinate values, one per position along the dimension (as written, e.g. degrees for a
        ``_deg`` key).
    key : str, optional
        Full key path the dimension varies, e.g. ``"controller.params.kp"`` (default "": an index
        dimension such as ``sample`` or ``run``).
    units : str, optional
        Unit of the coordinate values (default "").
    """

    name: str
    values: np.ndarray
    key: str = ""
    units: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ParameterError(f"`name` of a batch axis must be a non-empty string, "
                                 f"got {self.name!r}")
        object.__setattr__(self, "values", _frozen_array(f"values of axis '{self.name}'",
                                                         self.values))

    @property
    def size(self) -> int:
        """Number of positions along the dimension."""
        return int(self.values.size)

    @property
    def attrs(self) -> dict[str, str]:
        """Attributes of the coordinate in a result Dataset (``key``, ``units``)."""
        out = {}
        if self.key:
            out["key"] = self.key
        if self.units:
            out["units"] = self.units
        return out


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class BatchValues:
    """Per-run values that are not coordinates, e.g. the draws of a Monte-Carlo batch.

    Parameters
    ----------
    name : str
        Variable name in the result Dataset, e.g. ``"vessel.params.gain"``.
    values : sequence of float, shape (runs,)
        One value per run, runs in the C order of the layout.
    units : str, optional
        Unit of the values (default "").
    attrs : mapping of str to str, optional
        Further attributes, e.g. ``{"distribution": "normal"}`` (default none).
    """

    name: str
    values: np.ndarray
    units: str = ""
    attrs: Mapping[str, str] = dataclasses.field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ParameterError(f"`name` of batch values must be a non-empty string, "
                                 f"got {self.name!r}")
        values = np.array(self.values, dtype=float)
        if values.ndim != 1 or values.size == 0:
            raise ParameterError(f"values of '{self.name}' must be a non-empty 1-D sequence, "
                                 f"got shape {values.shape}")
        values.setflags(write=False)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "attrs", types.MappingProxyType(dict(self.attrs)))


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class BatchLayout:
    """The dimensions a batch of runs spans; runs are numbered in C order over them.

    Parameters
    ----------
    axes : sequence of BatchAxis
        The batch dimensions, outermost first (the last varies fastest).
    values : sequence of BatchValues, optional
        Per-run values stored with the results (Monte-Carlo draws; default none).
    """

    axes: tuple[BatchAxis, ...]
    values: tuple[BatchValues, ...] = ()

    def __post_init__(self) -> None:
        axes = tuple(self.axes)
        values = tuple(self.values)
        object.__setattr__(self, "axes", axes)
        object.__setattr__(self, "values", values)
        if not axes:
            raise ParameterError("a batch layout needs at least one axis")
        names = [a.name for a in axes]
        for name in names:
            if names.count(name) > 1:
                raise ParameterError(f"batch dimension '{name}' appears twice in {names}")
            if name in RESERVED_DIMS:
                raise ParameterError(f"batch dimension '{name}' is reserved; "
                                     f"reserved: {', '.join(RESERVED_DIMS)}")
        for v in values:
            if v.values.size != self.size:
                raise ParameterError(f"batch values '{v.name}' have {v.values.size} entries, "
                                     f"the layout {self.shape} has {self.size} runs")
            if v.name in names:
                raise ParameterError(f"batch values '{v.name}' have the name of a dimension")

    @classmethod
    def runs(cls, n: int) -> "BatchLayout":
        """The layout of ``n`` runs that span no grid: one ``run`` dimension.

        Parameters
        ----------
        n : int
            Number of runs (>= 1).

        Returns
        -------
        BatchLayout
        """
        if isinstance(n, bool) or int(n) != n or n < 1:
            raise ParameterError(f"`n` must be a whole number >= 1 [runs], got {n!r}")
        return cls(axes=(BatchAxis(name="run", values=np.arange(int(n))),))

    @property
    def dims(self) -> tuple[str, ...]:
        """Dimension names, outermost first."""
        return tuple(a.name for a in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of positions along each dimension."""
        return tuple(a.size for a in self.axes)

    @property
    def size(self) -> int:
        """Number of runs."""
        return math.prod(self.shape)

    @property
    def is_flat(self) -> bool:
        """True for the plain layout: a single ``run`` dimension."""
        return self.dims == ("run",)

    def point(self, run: int) -> dict[str, Any]:
        """Coordinates of one run, ``{dim: value}`` (C order over the dimensions).

        Parameters
        ----------
        run : int
            Flat run index, 0 <= run < size.

        Returns
        -------
        dict
            The run's coordinate value along every dimension.
        """
        if not 0 <= run < self.size:
            raise IndexError(f"run {run} is outside the batch of {self.size} run(s)")
        index = np.unravel_index(run, self.shape)
        return {a.name: a.values[i].item() for a, i in zip(self.axes, index)}





def batch_dims(ds: "xr.Dataset") -> tuple[str, ...]:
    """The batch dimensions of a result Dataset (those of its ``status`` variable).

    Parameters
    ----------
    ds : xarray.Dataset
        A Dataset of :meth:`SimResult.to_xarray` or :func:`load_result`.

    Returns
    -------
    tuple of str
        E.g. ``("kp", "kd")``, ``("sample",)`` or ``("run",)``.
    """
    if "status" not in ds:
        raise KeyError("not a seahelm result: no `status` variable")
    return tuple(str(d) for d in ds["status"].dims)


def flatten_runs(ds: "xr.Dataset") -> "xr.Dataset":
    """The flat run view of a result Dataset: batch dimensions stacked into ``run``.

    Runs are numbered in C order over the batch dimensions (the last varies fastest), as in the
    arrays of :class:`SimResult`; the batch coordinates become coordinates over ``run`` (no
    MultiIndex). A Dataset that already has the dims ``(run, time)`` is returned unchanged.

    Parameters
    ----------
    ds : xarray.Dataset
        A Dataset of :meth:`SimResult.to_xarray` or :func:`load_result`.

    Returns
    -------
    xarray.Dataset
        Variables with dims ``(run, time)`` or ``(run,)``.
    """
    dims = batch_dims(ds)
    if dims == ("run",):
        return ds
    if not dims:  # one run stored without a run dimension (a manoeuvre's single run)
        return ds.expand_dims(run=[0]).transpose("run", ...)
    if "run" in ds.variables:
        raise ValueError(f"cannot flatten batch dims {dims}: the Dataset already has `run`")
    flat = ds.stack(run=dims, create_index=False)
    flat = flat.assign_coords(run=np.arange(flat.sizes["run"]))
    return flat.transpose("run", ...)
