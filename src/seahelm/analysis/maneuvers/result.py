"""The result of a manoeuvre batch: its metrics table, its runs and its ships.

:class:`ManeuverResult` is what every manoeuvre of :mod:`seahelm.analysis.maneuvers` returns
(the grid machinery that builds it is :mod:`seahelm.analysis.maneuvers.common`);
:func:`metrics_rows` flattens its metrics table for printing.
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ...results import SimResult
    from .common import ManeuverShip

__all__ = ["ManeuverResult", "metrics_rows"]


@dataclasses.dataclass(frozen=True, eq=False)
class ManeuverResult:
    """A batch of one manoeuvre: the metrics table, the runs and the ships.

    Attributes
    ----------
    maneuver : str
        ``"turning-circle"``, ``"zigzag"``, ``"direct-spiral"``, ``"reverse-spiral"`` or
        ``"pull-out"``.
    metrics : xarray.Dataset
        The metrics over the batch dims (see the module docstring).
    ships : tuple of ManeuverShip
        The ships of the batch (``ship`` index order).
    simulation : SimResult or None
        The engine's result (flat run order); None for a manoeuvre computed from equilibria
        (the reverse spiral).
    runs : xarray.Dataset or None
        Time series ``(*batch_dims, time)`` with the grid's coordinates, built from
        ``simulation`` on first access (None for the reverse spiral).
    """

    maneuver: str
    metrics: "xr.Dataset"
    ships: tuple[ManeuverShip, ...]
    simulation: "SimResult | None" = None
    runs_builder: Callable[[], "xr.Dataset"] | None = dataclasses.field(default=None,
                                                                         repr=False)

    @functools.cached_property
    def runs(self) -> "xr.Dataset | None":
        """The runs as an :class:`xarray.Dataset` (built once, on first access)."""
        return None if self.runs_builder is None else self.runs_builder()

    def to_netcdf(self, directory: str | Path, *, prefix: str | None = None
                  ) -> dict[str, Path]:
        """Write ``<prefix>-metrics.nc`` and ``<prefix>-runs.nc`` atomically (h5netcdf).

        Parameters
        ----------
        directory : str or pathlib.Path
            Output directory (created if needed).
        prefix : str, optional
            File name prefix (default: the manoeuvre name).

        Returns
        -------
        dict of str to pathlib.Path
            ``{"metrics": path, "runs": path}`` (no ``runs`` for the reverse spiral).
        """
        from ...results import write_netcdf

        directory = Path(directory)
        prefix = prefix or self.maneuver
        out = {}
        for key, ds in (("metrics", self.metrics), ("runs", self.runs)):
            if ds is None:
                continue
            ds = _netcdf_ready(ds)
            out[key] = write_netcdf(ds, directory / f"{prefix}-{key}.nc")
        return out


def _netcdf_ready(ds: "xr.Dataset") -> "xr.Dataset":
    """Object (string) arrays as fixed strings, booleans as int8 (h5netcdf writes both)."""
    ds = ds.copy()
    for name in list(ds.variables):
        var = ds[name]
        if var.dtype == object:
            ds[name] = var.astype(str)
        elif var.dtype == bool:
            ds[name] = var.astype(np.int8)
            ds[name].attrs.update(var.attrs, flag_values="0 1", flag_meanings="false true")
    return ds


def metrics_rows(metrics: "xr.Dataset") -> list[dict[str, Any]]:
    """The metrics table as one dict per run (flat, C order over the batch dims).

    Coordinates come first (``ship_name``, ``approach_speed``, ``rudder``, ``side``, ...),
    then every metric as a float (NaN where not reached), bool or string; a metric with an
    extra dimension (e.g. ``overshoot(…, n)``) becomes ``name_1``, ``name_2``, ...

    Parameters
    ----------
    metrics : xarray.Dataset
        A :attr:`ManeuverResult.metrics` Dataset.

    Returns
    -------
    list of dict
    """
    batch = [d for d in metrics["complete"].dims] if "complete" in metrics else []
    shape = [metrics.sizes[d] for d in batch]
    rows = []
    for idx in itertools.product(*(range(n) for n in shape)):
        sel = metrics.isel(dict(zip(batch, idx)))
        row: dict[str, Any] = {}
        for name, coord in sel.coords.items():
            if coord.ndim == 0:
                row[str(name)] = coord.item()
        for name, var in sel.data_vars.items():
            if var.ndim == 0:
                row[str(name)] = var.item()
            elif var.ndim == 1:
                for k, v in enumerate(var.values.tolist(), start=1):
                    row[f"{name}_{k}"] = v
        rows.append(row)
    return rows
