"""Result files read back as :class:`~seahelm.results.SimResult`: the inverse of ``to_xarray``.

:func:`~seahelm.results.load_result` gives the Dataset a result file holds; :func:`read_result`
and :func:`result_from_dataset` give back the :class:`~seahelm.results.SimResult` it was
written from -- the same channels, units, parameters, run status and metadata, and the batch's
layout (grid axes and Monte-Carlo draws) -- so that everything computed from a result in memory
(``seahelm.analysis.maneuvers.summarize``, ``result.plot()``) works on a file too
(``seahelm inspect``).

What a file does not hold comes back empty: the state at which a diverged run failed
(``failure_state``, NaN; the failure time and reason are kept) and the parameter classes,
which are rebuilt from the file (same field names, units and symbols, in the file's order;
named as in the file's ``param_types`` attribute) rather than imported, so that a file written
by a generated or user-defined component reads back too.

Lives above :mod:`seahelm.results` and :mod:`seahelm.result_layout` (it needs both) and imports
no simulation module: the layout classes are :mod:`seahelm.result_layout`'s.
"""

from __future__ import annotations

import dataclasses
import os
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ParameterError
from .parameters import Params, param
from .result_layout import BatchAxis, BatchLayout, BatchValues, batch_dims, flatten_runs
from .results import SimResult, load_result

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["read_result", "result_from_dataset"]

#: Attributes ``to_xarray`` writes itself (not part of the run's metadata).
_OWN_ATTRS = ("state_labels", "param_types")


def read_result(path: str | os.PathLike[str]) -> SimResult:
    """Read a result file written by :meth:`SimResult.to_netcdf` back as a ``SimResult``.

    Parameters
    ----------
    path : str or os.PathLike
        NetCDF file of ``seahelm run --out`` or :meth:`SimResult.to_netcdf`.

    Returns
    -------
    SimResult
        With the file's batch layout (``result.dims``, ``result.layout``).

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ParameterError
        If ``path`` is not a seahelm simulation result (see :func:`load_result`).
    """
    return result_from_dataset(load_result(path))


def result_from_dataset(ds: "xr.Dataset") -> SimResult:
    """The :class:`SimResult` a result Dataset was made from (shaped or flat view).

    Parameters
    ----------
    ds : xarray.Dataset
        A Dataset of :meth:`SimResult.to_xarray` (either view) or :func:`load_result`.

    Returns
    -------
    SimResult
        Runs in the flat C order of the Dataset's batch dimensions; ``layout`` rebuilt from
        its batch coordinates and batch values (None for a ``run`` batch, and for the flat
        view of a grid, whose coordinates are over ``run``).

    Raises
    ------
    ParameterError
        If the Dataset lacks what every seahelm result has (``status`` over the runs, a
        ``time`` dimension, the ``state_labels`` attribute).
    """
    if "status" not in ds or "time" not in ds.dims or "state_labels" not in ds.attrs:
        raise ParameterError("not a seahelm simulation result (it needs `status` over the "
                             "runs, a `time` dimension and the `state_labels` attribute)")
    layout = _layout(ds)
    flat = flatten_runs(ds)
    n_runs = flat.sizes["run"]
    n_time = flat.sizes["time"]

    def series(kind: str) -> tuple[list[str], list[str], np.ndarray]:
        names = [str(n) for n, v in flat.data_vars.items() if v.attrs.get("kind") == kind
                 and v.dims == ("run", "time")]
        units = [str(flat[n].attrs.get("units", "")) for n in names]
        values = (np.stack([flat[n].values for n in names], axis=-1) if names
                  else np.zeros((n_runs, n_time, 0)))
        return names, units, np.asarray(values, dtype=float)

    state_labels = tuple(str(ds.attrs["state_labels"]).split(","))
    missing = [s for s in state_labels if s not in flat]
    if missing:
        raise ParameterError(f"not a complete seahelm result: state(s) {', '.join(missing)} "
                             "named in `state_labels` are missing")
    state = np.stack([flat[s].values for s in state_labels], axis=-1).astype(float)
    state_units = tuple(str(flat[s].attrs.get("units", "")) for s in state_labels)
    out_names, out_units, output = series("output")
    cmd_names, cmd_units, command = series("command")
    ref_names, ref_units, reference = series("reference")
    dist_names, dist_units, disturbance = series("disturbance")
    metadata = {k: (v.item() if isinstance(v, np.generic) else v)
                for k, v in ds.attrs.items() if k not in _OWN_ATTRS}
    failure_time = (flat["failure_time"].values.astype(float) if "failure_time" in flat
                    else np.full(n_runs, np.nan))
    return SimResult(
        time=np.asarray(flat["time"].values, dtype=float),
        state=state,
        state_labels=state_labels,
        state_units=state_units,
        output=output,
        output_labels=tuple(out_names),
        output_units=tuple(out_units),
        command=command,
        command_labels=tuple(cmd_names),
        command_units=tuple(cmd_units),
        reference=reference,
        reference_labels=tuple(n.removeprefix("reference_") for n in ref_names),
        reference_units=tuple(ref_units),
        disturbance=disturbance,
        disturbance_labels=tuple(dist_names),
        disturbance_units=tuple(dist_units),
        status=flat["status"].values.astype(np.int64),
        failure_time=failure_time,
        failure_state=np.full((n_runs, len(state_labels)), np.nan),
        params=_params(flat),
        metadata=metadata,
        layout=layout,
    )


def _layout(ds: "xr.Dataset") -> BatchLayout | None:
    """The batch layout of a shaped Dataset: its batch dims with their coordinates and keys,
    and its batch values (Monte-Carlo draws); None for a plain ``run`` batch."""
    dims = batch_dims(ds)
    if dims in (("run",), ()):  # (a flat view of a grid has its coordinates over `run`)
        return None
    axes = []
    for dim in dims:
        coord = ds[dim] if dim in ds.coords else None
        values = np.asarray(coord.values) if coord is not None else np.arange(ds.sizes[dim])
        attrs = dict(coord.attrs) if coord is not None else {}
        axes.append(BatchAxis(name=dim, values=values, key=str(attrs.get("key", "")),
                              units=str(attrs.get("units", ""))))
    values = []
    for name, var in ds.data_vars.items():
        if var.attrs.get("kind") != "batch_values":
            continue
        attrs = {k: str(v) for k, v in var.attrs.items() if k not in ("kind", "units")}
        flat = np.asarray(var.transpose(*dims).values).reshape(-1)
        values.append(BatchValues(name=str(name), values=flat,
                                  units=str(var.attrs.get("units", "")), attrs=attrs))
    return BatchLayout(axes=tuple(axes), values=tuple(values))


def _params(flat: "xr.Dataset") -> dict[str, tuple[type[Params], np.ndarray]]:
    """Per component: a parameter class rebuilt from the file and the ``(runs, n)`` array."""
    names = dict(item.split("=", 1) for item in str(flat.attrs.get("param_types", "")).split(",")
                 if "=" in item)
    found: dict[str, list[str]] = {}
    for name, var in flat.data_vars.items():
        if var.attrs.get("kind") == "parameter" and "." in str(name):
            comp = str(name).split(".", 1)[0]
            found.setdefault(comp, []).append(str(name))
    n_runs = flat.sizes["run"]
    out: dict[str, tuple[type[Params], np.ndarray]] = {}
    for comp, variables in found.items():
        fields: list[tuple[str, Any, Any]] = []
        columns: list[np.ndarray] = []
        for var_name in variables:
            var = flat[var_name]
            field = var_name.split(".", 1)[1]
            size = var.shape[1] if var.ndim == 2 else 0
            fields.append((field, tuple if size else float,
                           param(unit=str(var.attrs.get("units", "")),
                                 symbol=str(var.attrs.get("symbol", "")), size=size)))
            values = np.asarray(var.values, dtype=float)
            columns.append(values.reshape(n_runs, -1))
        cls = dataclasses.make_dataclass(names.get(comp, f"{comp.title()}Params"), fields,
                                         bases=(Params,), frozen=True, kw_only=True)
        cls.__doc__ = f"Parameters of the {comp} as read back from a result file."
        out[comp] = (cls, np.concatenate(columns, axis=1) if columns
                     else np.zeros((n_runs, 0)))
    return out
