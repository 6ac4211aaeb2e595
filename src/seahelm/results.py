"""Simulation results: :class:`SimResult` and its xarray / NetCDF / CSV forms.

Results keep the shape of the question. ``SimResult.to_xarray()`` gives a Dataset whose
dimensions are the batch's (its :class:`~seahelm.result_layout.BatchLayout`) and ``time``:
``(kp, kd, time)`` for a grid over two controller gains, with the grid values as coordinates
(``attrs["key"]`` holds the full key path, e.g. ``controller.params.kp``); ``(sample, time)``
for Monte-Carlo, with the drawn values as variables over ``sample`` (named by their key path);
``(run, time)`` for a batch that spans no grid (e.g. :func:`~seahelm.simulation.engine.simulate`
called directly). Every state, navigation output, command, reference and disturbance channel
is a labelled variable with its unit in ``attrs["units"]``; parameters are variables over the
batch dimensions named ``<component>.<field>``; run status, failure time and message likewise;
the attributes hold the seahelm version, model/actuator/controller names, integrator, step,
seed, scenario text and creation time.

The flat view, for code that iterates runs: ``to_xarray(flat=True)`` (or
:func:`flatten_runs` on any result Dataset, e.g. one read back by :func:`load_result`) stacks
the batch dimensions into one ``run`` dimension in C order (the last batch dimension varies
fastest), with the batch coordinates as coordinates over ``run`` (``kp(run)``, ``kd(run)``;
no MultiIndex, so it can be written to NetCDF too). The numpy arrays of :class:`SimResult`
(``result.state[i]``, ``result["heading"]``) are in that flat run order.

NetCDF files hold the shaped Dataset; CSV files the flat view (one row per run and time, the
batch coordinates as columns). Files are written atomically (temporary file in the same
directory, then rename), so a crash never leaves a half-written result.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from . import __version__
from .parameters import Params
from .errors import ParameterError
from .output_files import atomic_write, write_output, write_together
from .result_layout import BatchLayout, batch_dims, flatten_runs

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["SimResult", "atomic_write", "write_together", "write_netcdf", "netcdf_bytes",
           "open_result_file", "load_result", "flatten_runs", "batch_dims",
           "CorruptResultError", "STATUS_TEXT"]

_STATUS_TEXT = {0: "ok", 1: "diverged: non-finite state", 2: "diverged: state out of bounds",
                3: "not run: no initial state (its steady approach was not found)"}
#: What each status code says (a run's message without its time; a sweep store keeps codes).
STATUS_TEXT = _STATUS_TEXT


class CorruptResultError(ParameterError):
    """A result file's data do not match their checksums (or cannot be read): the file was
    damaged after it was written. ``field`` names the variable; the message names the file."""

    def _render(self) -> str:
        return self.reason


def write_netcdf(ds: "xr.Dataset", path: str | os.PathLike[str], *, force: bool = False
                 ) -> Path:
    """Write a Dataset to NetCDF-4 (h5netcdf) atomically, each numeric variable with an HDF5
    Fletcher-32 checksum, so that reading it finds damage (:func:`open_result_file`).

    Parameters
    ----------
    ds : xarray.Dataset
    path : str or os.PathLike
        Destination file.
    force : bool, optional
        Replace an existing file that is not a seahelm NetCDF file (default False; the output
        policy, :func:`seahelm.output_files.check_output`).

    Returns
    -------
    pathlib.Path
    """
    data = netcdf_bytes(ds)
    return write_output(path, lambda tmp: Path(tmp).write_bytes(data), "netcdf", force=force)


def netcdf_bytes(ds: "xr.Dataset") -> memoryview:
    """The NetCDF-4 file of ``ds`` (h5netcdf) in memory, each numeric variable with a
    Fletcher-32 checksum.

    Built in memory and written to disk by plain file I/O (:func:`write_netcdf`): a full disk
    or an I/O error is then an ``OSError`` naming the file, with nothing half-written, where
    HDF5 failing inside its own writer left its handles half-closed (the process crashed
    with a segmentation fault on the next clean-up).

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    memoryview
        The file's bytes.
    """
    import io

    encoding = {name: {"fletcher32": True} for name, var in ds.variables.items()
                if var.ndim > 0 and var.dtype.kind in "biufc" and var.size > 0}
    out = ds.copy()
    out.attrs = {**ds.attrs, "seahelm_checksums": "fletcher32"}
    buffer = io.BytesIO()
    out.to_netcdf(buffer, engine="h5netcdf", encoding=encoding)
    return buffer.getbuffer()


@dataclasses.dataclass
class SimResult:
    """The recorded runs of a batch simulation.

    The arrays have a leading flat ``run`` axis (C order over the batch dimensions);
    ``layout`` (a :class:`~seahelm.result_layout.BatchLayout`, set by
    :func:`~seahelm.simulation.batch.simulate_batch`) gives the dimensions the runs span and
    shapes :meth:`to_xarray`. Without it the runs span one ``run`` dimension.
    """

    time: np.ndarray
    state: np.ndarray
    state_labels: tuple[str, ...]
    state_units: tuple[str, ...]
    output: np.ndarray
    output_labels: tuple[str, ...]
    output_units: tuple[str, ...]
    command: np.ndarray
    command_labels: tuple[str, ...]
    reference: np.ndarray
    reference_labels: tuple[str, ...]
    reference_units: tuple[str, ...]
    disturbance: np.ndarray
    disturbance_labels: tuple[str, ...]
    disturbance_units: tuple[str, ...]
    status: np.ndarray
    failure_time: np.ndarray
    failure_state: np.ndarray
    params: dict[str, tuple[type[Params], np.ndarray]]
    metadata: dict[str, Any]
    layout: BatchLayout | None = None
    command_units: tuple[str, ...] = ()  # (the controller's recorded outputs have units)
    #: series computed from the record after the run, by name: (values (runs, time), unit,
    #: long name), e.g. the first-order wave motions (:mod:`seahelm.scenario.first_order`)
    extra: dict[str, tuple[np.ndarray, str, str]] = dataclasses.field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.layout is not None and self.layout.size != self.n_runs:
            raise ParameterError(
                f"batch layout {dict(zip(self.layout.dims, self.layout.shape))} spans "
                f"{self.layout.size} run(s), but the engine ran {self.n_runs}"
            )

    @property
    def n_runs(self) -> int:
        """Number of runs (the length of the flat ``run`` axis)."""
        return int(self.state.shape[0])

    @property
    def dims(self) -> tuple[str, ...]:
        """The batch dimensions of :meth:`to_xarray` (``("run",)`` without a layout)."""
        return ("run",) if self.layout is None else self.layout.dims

    @property
    def shape(self) -> tuple[int, ...]:
        """Sizes of the batch dimensions (``(n_runs,)`` without a layout)."""
        return (self.n_runs,) if self.layout is None else self.layout.shape

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the runs that finished without diverging."""
        return self.status == 0

    def __repr__(self) -> str:
        from ._repr import sim_result_summary, summary_text

        return summary_text(*sim_result_summary(self))

    def _repr_html_(self) -> str:
        from ._repr import sim_result_summary, summary_html

        return summary_html(*sim_result_summary(self))

    def messages(self) -> list[str]:
        """One line per run: 'ok' or what diverged and when."""
        out = []
        for s, t in zip(self.status, self.failure_time):
            out.append(_STATUS_TEXT[int(s)] + ("" if s == 0 or s == 3 else f" at t = {t:.6g} s"))
        return out

    def __getitem__(self, label: str) -> np.ndarray:
        """A channel by label: state, model output, command, reference or disturbance."""
        if label in self.state_labels:
            return self.state[..., self.state_labels.index(label)]
        if label in self.output_labels:
            return self.output[..., self.output_labels.index(label)]
        if label in self.command_labels:
            return self.command[..., self.command_labels.index(label)]
        if label.startswith("reference_") and label[10:] in self.reference_labels:
            return self.reference[..., self.reference_labels.index(label[10:])]
        if label in self.disturbance_labels:
            return self.disturbance[..., self.disturbance_labels.index(label)]
        if label in self.extra:
            return self.extra[label][0]
        raise KeyError(
            f"no channel '{label}'; channels: "
            + ", ".join(self.channel_names())
        )

    def channel_names(self) -> list[str]:
        names = list(self.state_labels)
        names += [n for n in self.output_labels if n not in names]
        names += list(self.command_labels)
        names += [f"reference_{n}" for n in self.reference_labels]
        names += list(self.disturbance_labels)
        names += [n for n in self.extra if n not in names]
        return names

    def units(self) -> dict[str, str]:
        """The unit of every state, output, command and reference by name ("" where none).

        Returns
        -------
        dict of str to str
        """
        out = dict(zip(self.state_labels, self.state_units))
        for lab, unit in zip(self.output_labels, self.output_units):
            out.setdefault(lab, unit)
        for j, lab in enumerate(self.command_labels):
            out[lab] = self.command_units[j] if j < len(self.command_units) else ""
        for lab, unit in zip(self.reference_labels, self.reference_units):
            out[f"reference_{lab}"] = unit
        return out

    # -- conversions ---------------------------------------------------------------------
    def to_xarray(self, *, flat: bool = False) -> "xr.Dataset":
        """The runs as an :class:`xarray.Dataset`, dims ``(*batch_dims, time)``.

        Parameters
        ----------
        flat : bool, optional
            Stack the batch dimensions into one ``run`` dimension (C order), with the batch
            coordinates as coordinates over ``run`` (default False: the batch's own
            dimensions, e.g. ``(kp, kd, time)``). Same as :func:`flatten_runs` of the shaped
            Dataset.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr

        n_runs = self.n_runs
        coords: dict[str, Any] = {"run": np.arange(n_runs),
                                  "time": ("time", self.time, {"units": "s"})}
        data: dict[str, Any] = {}

        def add(name: str, values: np.ndarray, unit: str, kind: str) -> None:
            values = np.broadcast_to(values, (n_runs, self.time.size))
            data[name] = (("run", "time"), np.ascontiguousarray(values),
                          {"units": unit, "kind": kind})

        for j, (lab, unit) in enumerate(zip(self.state_labels, self.state_units)):
            add(lab, self.state[..., j], unit, "state")
        for j, (lab, unit) in enumerate(zip(self.output_labels, self.output_units)):
            if lab not in self.state_labels:
                add(lab, self.output[..., j], unit, "output")
        for j, lab in enumerate(self.command_labels):
            add(lab, self.command[..., j],
                self.command_units[j] if j < len(self.command_units) else "", "command")
        for j, (lab, unit) in enumerate(zip(self.reference_labels, self.reference_units)):
            add(f"reference_{lab}", self.reference[..., j], unit, "reference")
        for j, (lab, unit) in enumerate(zip(self.disturbance_labels, self.disturbance_units)):
            add(lab, self.disturbance[..., j], unit, "disturbance")
        for lab, (values, unit, long_name) in self.extra.items():
            add(lab, values, unit, "first-order")
            data[lab][2]["long_name"] = long_name
        for comp, (cls, arr) in self.params.items():
            arr = np.broadcast_to(arr, (n_runs, arr.shape[-1]))
            i = 0
            for info in cls.info():
                attrs = {"units": info.unit, "kind": "parameter", "symbol": info.symbol}
                if info.size:  # a vector parameter: a dimension of its own
                    data[f"{comp}.{info.name}"] = (
                        ("run", f"{comp}.{info.name}_index"),
                        np.asarray(arr[:, i:i + info.size], dtype=float), attrs)
                    i += info.size
                else:
                    data[f"{comp}.{info.name}"] = ("run", np.asarray(arr[:, i], dtype=float),
                                                   attrs)
                    i += 1
        data["status"] = ("run", self.status.astype(np.int64),
                          {"flag_values": "0 1 2 3",
                           "flag_meanings": "ok diverged_nonfinite diverged_out_of_bounds "
                                            "not_run"})
        data["failure_time"] = ("run", self.failure_time, {"units": "s"})
        data["status_message"] = ("run", np.array(self.messages(), dtype=object))
        layout = self.layout
        if layout is not None and not layout.is_flat:
            for v in layout.values:
                if v.name in data:
                    raise ParameterError(f"batch values '{v.name}' have the name of a result "
                                         "variable")
                attrs = {"kind": "batch_values", **dict(v.attrs)}
                if v.units:
                    attrs["units"] = v.units
                data[v.name] = ("run", np.asarray(v.values), attrs)
            for a in layout.axes:
                if a.name in data:
                    raise ParameterError(f"batch dimension '{a.name}' has the name of a result "
                                         "variable; name it by its key path")
                point = np.unravel_index(np.arange(n_runs), layout.shape)[layout.dims.index(a.name)]
                coords[a.name] = ("run", a.values[point], a.attrs)
        attrs = {
            "seahelm_version": __version__,
            "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            "state_labels": ",".join(self.state_labels),
            "param_types": ",".join(f"{c}={cls.__name__}" for c, (cls, _) in self.params.items()),
        }
        for key, value in self.metadata.items():
            if isinstance(value, (bool, np.bool_)):
                value = int(value)
            attrs[key] = value if isinstance(value, (int, float, str)) else str(value)
        ds = xr.Dataset(data, coords=coords, attrs=attrs)
        if flat or layout is None or layout.is_flat:
            return ds
        return _shape_runs(ds, layout)

    def to_netcdf(self, path: str | os.PathLike[str], *, force: bool = False) -> Path:
        """Write the (shaped) Dataset to NetCDF-4 (h5netcdf) atomically; returns the path.

        Parameters
        ----------
        path : str or os.PathLike
            Destination file.
        force : bool, optional
            Replace an existing file that is not a seahelm NetCDF file (default False;
            :func:`seahelm.output_files.check_output`).

        Returns
        -------
        pathlib.Path
        """
        ds = self.to_xarray()
        ds["status_message"] = ds["status_message"].astype(str)
        return write_netcdf(ds, path, force=force)

    def to_csv(self, path: str | os.PathLike[str], *, force: bool = False) -> Path:
        """Write a long-format CSV of the flat view atomically; returns the path.

        One row per run and time; the batch coordinates (e.g. ``kp``, ``kd``) are columns.

        Parameters
        ----------
        path : str or os.PathLike
            Destination file.
        force : bool, optional
            Replace an existing file that is not a seahelm CSV table (default False;
            :func:`seahelm.output_files.check_output`).

        Returns
        -------
        pathlib.Path
        """
        ds = self.to_xarray(flat=True)
        series = [v for v in ds.data_vars if ds[v].dims == ("run", "time")]
        frame = ds[series].to_dataframe().reset_index()
        return write_output(path, lambda tmp: frame.to_csv(tmp, index=False, float_format="%.10g"),
                            "csv", force=force)

    def plot(self, *, runs: Any = None, fig: Any = None) -> Any:
        """Heading, rudder, yaw rate and the xy track (see :func:`seahelm.plotting.timeseries`).

        Parameters
        ----------
        runs : sequence of int, optional
            Runs to draw, as flat run indices (default: all).
        fig : matplotlib Figure, optional
            Figure to draw into (default: a new one).

        Returns
        -------
        matplotlib Figure
        """
        from .plotting.timeseries import plot_result

        return plot_result(self.to_xarray(flat=True), runs=runs, fig=fig)


def _shape_runs(ds: "xr.Dataset", layout: BatchLayout) -> "xr.Dataset":
    """The flat Dataset of :meth:`SimResult.to_xarray` with ``run`` reshaped to the layout."""
    import xarray as xr

    data = {}
    for name, var in ds.data_vars.items():
        dims = var.dims
        if "run" in dims:
            i = dims.index("run")
            values = var.values.reshape(var.shape[:i] + layout.shape + var.shape[i + 1:])
            dims = dims[:i] + layout.dims + dims[i + 1:]
        else:
            values = var.values
        data[name] = xr.Variable(dims, values, var.attrs)
    coords: dict[str, Any] = {"time": ds["time"].variable}
    for a in layout.axes:
        coords[a.name] = (a.name, np.asarray(a.values), a.attrs)
    return xr.Dataset(data, coords=coords, attrs=ds.attrs)


def open_result_file(path: str | os.PathLike[str]) -> "xr.Dataset":
    """Open a NetCDF file written by seahelm (loaded into memory), whatever it holds.

    Checks that the path is a regular NetCDF-4/HDF5 file that xarray can read; what it holds
    (a simulation result, a manoeuvre's metrics) is for the caller to check --
    :func:`load_result` requires a simulation result.

    Parameters
    ----------
    path : str or os.PathLike
        NetCDF file.

    Returns
    -------
    xarray.Dataset

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ParameterError
        If ``path`` is not a regular file, not NetCDF-4/HDF5, or cannot be read.
    CorruptResultError
        A :class:`ParameterError` naming the variable whose data do not match their checksum
        (files written by :func:`write_netcdf`) or cannot be read.
    """
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"result file not found: {path}")
    if not path.is_file():
        raise ParameterError(f"{path} is not a regular file (a seahelm result file is needed)")
    with path.open("rb") as fh:
        magic = fh.read(8)
    if magic != b"\x89HDF\r\n\x1a\n":
        raise ParameterError(f"{path}: not a NetCDF-4/HDF5 file written by seahelm (a results "
                             "file of `seahelm run --out` or SimResult.to_netcdf)")
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            for name in list(ds.variables):  # one by one: a damaged one is named
                try:
                    ds[name].load()
                except (OSError, ValueError, RuntimeError) as exc:
                    text = str(exc)
                    checksum = ("letcher" in text or "checksum" in text.lower()
                                or "filter returned failure" in text)
                    why = ("its data do not match their checksum (Fletcher-32)" if checksum
                           else f"it cannot be read ({' '.join(text.split())[:200]})")
                    raise CorruptResultError(
                        f"{path}: variable `{name}` is damaged: {why}; the file was changed "
                        "after seahelm wrote it (write it again from its scenario)",
                        field=str(name)) from None
            return ds.load()
    except CorruptResultError:
        raise
    except (OSError, ValueError) as exc:
        raise ParameterError(f"{path}: cannot be read as NetCDF ({exc})") from None


def load_result(path: str | os.PathLike[str]) -> "xr.Dataset":
    """Open a result file written by :meth:`SimResult.to_netcdf` (loaded into memory).

    The Dataset has the batch's dimensions and coordinates as written (e.g. ``(kp, kd,
    time)``); :func:`flatten_runs` gives the flat ``run`` view.

    Parameters
    ----------
    path : str or os.PathLike
        NetCDF file written by :meth:`SimResult.to_netcdf`.

    Returns
    -------
    xarray.Dataset

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ParameterError
        If ``path`` is not a NetCDF file seahelm wrote, or holds no simulation result.
    """
    path = Path(path)
    ds = open_result_file(path)
    if "status" not in ds or "time" not in ds.dims:
        kind = ds.attrs.get("maneuver")
        what = (f"a '{kind}' manoeuvre file" if kind else
                "a `seahelm replay` file (a measured and a simulated track, not runs)"
                if "track" in ds.dims and "record" in ds.attrs else
                "not a seahelm simulation result")
        raise ParameterError(f"{path}: {what} (no `status` over runs and `time`); a "
                             "simulation result is a result.nc of `seahelm run --out` or a "
                             "manoeuvre's *-runs.nc")
    return ds
