"""The layout of a result Dataset: its batch dimensions, and the flat ``run`` view.

Below :mod:`seahelm.results` and :mod:`seahelm.plotting` (both use it; neither needs the
other for it). :mod:`seahelm.results` re-exports both functions.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["batch_dims", "flatten_runs"]


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
