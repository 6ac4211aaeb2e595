"""The result of a manoeuvre batch: its metrics table, its runs and its ships.

:class:`ManeuverResult` is what every manoeuvre of :mod:`seahelm.analysis.maneuvers` returns
(the grid machinery that builds it is :mod:`seahelm.analysis.maneuvers.common`);
:func:`metrics_rows` flattens its metrics table for printing.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ...results import SimResult
    from ...ships import Ship

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
    ships : tuple of Ship
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
    ships: tuple["Ship", ...]
    simulation: "SimResult | None" = None
    runs_builder: Callable[[], "xr.Dataset"] | None = dataclasses.field(default=None,
                                                                         repr=False)

    @functools.cached_property
    def runs(self) -> "xr.Dataset | None":
        """The runs as an :class:`xarray.Dataset` (built once, on first access)."""
        return None if self.runs_builder is None else self.runs_builder()

    def _summary(self) -> tuple[str, list[tuple[str, object]]]:
        from ..._repr import names

        ship_names = list(dict.fromkeys(getattr(s, "name", str(s)) for s in self.ships))
        title = f"ManeuverResult: {self.maneuver} of {names(ship_names, 3)}"
        sizes = dict(self.metrics.sizes)
        rows: list[tuple[str, object]] = [
            ("batch", ", ".join(f"{d}: {n}" for d, n in sizes.items()) or "one run"),
            ("metrics", names(list(self.metrics.data_vars), 5)),
        ]
        if "complete" in self.metrics:
            done = np.asarray(self.metrics["complete"])
            rows.append(("complete", f"{int(done.sum())} of {done.size} run(s)"))
        sim = self.simulation
        rows.append(("runs", "none (computed from equilibria)" if sim is None else
                     f"{sim.n_runs} run(s), {len(sim.time)} samples each "
                     "(.runs: an xarray Dataset, .simulation: the SimResult)"))
        rows.append(("use", ".metrics, .runs, to_dataframe(), to_netcdf(directory)"))
        return title, rows

    def __repr__(self) -> str:
        from ..._repr import summary_text

        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        from ..._repr import summary_html

        return summary_html(*self._summary())

    def to_dataframe(self) -> Any:
        """The metrics table as a :class:`pandas.DataFrame`, one row per run, one run too.

        The columns of :func:`metrics_rows` (the coordinates first, then every metric; an
        extra dimension spread over ``name_1``, ``name_2``, ...). ``metrics.to_dataframe()``
        is xarray's, which refuses the 0-dimensional table of a single run ("no valid index
        for a 0-dimensional object"); this gives it one row.
        """
        import pandas as pd

        return pd.DataFrame(metrics_rows(self.metrics))

    def to_netcdf(self, directory: str | Path, *, prefix: str | None = None,
                  force: bool = False) -> dict[str, Path]:
        """Write ``<prefix>-metrics.nc`` and ``<prefix>-runs.nc`` atomically (h5netcdf).

        Parameters
        ----------
        directory : str or pathlib.Path
            Output directory (created if needed).
        prefix : str, optional
            File name prefix (default: the manoeuvre name).
        force : bool, optional
            Replace existing files that are not seahelm NetCDF files (default False;
            :func:`seahelm.output_files.check_output`).

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
            out[key] = write_netcdf(ds, directory / f"{prefix}-{key}.nc", force=force)
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
    sizes = {d: metrics.sizes[d] for d in batch}
    n = int(np.prod(list(sizes.values()), dtype=np.int64))
    columns: dict[str, list[Any]] = {}  # (one numpy pass per variable, not one per run)
    for name, coord in metrics.coords.items():
        if set(coord.dims) <= set(batch):
            columns[str(name)] = _flat(coord, sizes, n)[:, 0].tolist()
    for name, var in metrics.data_vars.items():
        extra = [d for d in var.dims if d not in batch]
        if len(extra) > 1:
            continue
        table = _flat(var, sizes, n)
        if not extra:
            columns[str(name)] = table[:, 0].tolist()
            continue
        for k in range(table.shape[1]):
            columns[f"{name}_{k + 1}"] = table[:, k].tolist()
    return [{key: values[i] for key, values in columns.items()} for i in range(n)]


def _flat(da: "xr.DataArray", sizes: dict[str, int], n: int) -> np.ndarray:
    """``da`` broadcast over the batch dims ``sizes``, as (runs, rest) in C order over them."""
    missing = {d: s for d, s in sizes.items() if d not in da.dims}
    if missing:
        da = da.expand_dims(missing)
    rest = [d for d in da.dims if d not in sizes]
    return np.asarray(da.transpose(*sizes, *rest).values).reshape(n, -1)
