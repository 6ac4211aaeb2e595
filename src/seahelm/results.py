"""Simulation results: :class:`SimResult` and its xarray / NetCDF / CSV forms.

``SimResult.to_xarray()`` gives a Dataset with dimensions ``run`` and ``time``; every state,
navigation output, command, reference and disturbance channel is a labelled variable with its
unit in ``attrs["units"]``; parameters are ``run``-indexed variables named
``<component>.<field>``; run status, failure time and message are ``run`` variables; the
attributes hold the seahelm version, model/actuator/controller names, integrator, step, seed,
scenario text and creation time. Files are written atomically (temporary file in the same
directory, then rename), so a crash never leaves a half-written result.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from . import __version__
from .parameters import Params

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["SimResult", "atomic_write", "load_result"]

_STATUS_TEXT = {0: "ok", 1: "diverged: non-finite state", 2: "diverged: state out of bounds"}


def atomic_write(path: str | os.PathLike[str], writer: Callable[[str], None]) -> Path:
    """Call ``writer(tmp_path)`` then rename the temporary file onto ``path``.

    Parameters
    ----------
    path : str or os.PathLike
        Destination file (parent directories are created).
    writer : callable(str)
        Writes the content to the temporary path it is given.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        writer(tmp)
        # mkstemp creates the file private (0600); give it the permissions a plain open() would
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


@dataclasses.dataclass
class SimResult:
    """The recorded runs of a batch simulation (arrays have a leading ``run`` axis)."""

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

    @property
    def n_runs(self) -> int:
        return int(self.state.shape[0])

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the runs that finished without diverging."""
        return self.status == 0

    def messages(self) -> list[str]:
        """One line per run: 'ok' or what diverged and when."""
        out = []
        for s, t in zip(self.status, self.failure_time):
            out.append(_STATUS_TEXT[int(s)] + ("" if s == 0 else f" at t = {t:.6g} s"))
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
        return names

    # -- conversions ---------------------------------------------------------------------
    def to_xarray(self) -> "xr.Dataset":
        """The runs as an :class:`xarray.Dataset` (dims ``run``, ``time``)."""
        import xarray as xr

        n_runs = self.n_runs
        coords = {"run": np.arange(n_runs), "time": ("time", self.time, {"units": "s"})}
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
            add(lab, self.command[..., j], "", "command")
        for j, (lab, unit) in enumerate(zip(self.reference_labels, self.reference_units)):
            add(f"reference_{lab}", self.reference[..., j], unit, "reference")
        for j, (lab, unit) in enumerate(zip(self.disturbance_labels, self.disturbance_units)):
            add(lab, self.disturbance[..., j], unit, "disturbance")
        for comp, (cls, arr) in self.params.items():
            arr = np.broadcast_to(arr, (n_runs, arr.shape[-1]))
            for info, col in zip(cls.info(), arr.T):
                data[f"{comp}.{info.name}"] = ("run", np.asarray(col, dtype=float),
                                               {"units": info.unit, "kind": "parameter",
                                                "symbol": info.symbol})
        data["status"] = ("run", self.status.astype(np.int64),
                          {"flag_values": "0 1 2",
                           "flag_meanings": "ok diverged_nonfinite diverged_out_of_bounds"})
        data["failure_time"] = ("run", self.failure_time, {"units": "s"})
        data["status_message"] = ("run", np.array(self.messages(), dtype=object))
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
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def to_netcdf(self, path: str | os.PathLike[str]) -> Path:
        """Write the Dataset to NetCDF-4 (h5netcdf) atomically; returns the path.

        Parameters
        ----------
        path : str or os.PathLike
            Destination file.

        Returns
        -------
        pathlib.Path
        """
        ds = self.to_xarray()
        ds["status_message"] = ds["status_message"].astype(str)
        return atomic_write(path, lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write a long-format CSV (one row per run and time) atomically; returns the path.

        Parameters
        ----------
        path : str or os.PathLike
            Destination file.

        Returns
        -------
        pathlib.Path
        """
        ds = self.to_xarray()
        series = [v for v in ds.data_vars if ds[v].dims == ("run", "time")]
        frame = ds[series].to_dataframe().reset_index()
        return atomic_write(path, lambda tmp: frame.to_csv(tmp, index=False, float_format="%.10g"))

    def plot(self, *, runs: Any = None, fig: Any = None) -> Any:
        """Heading, rudder, yaw rate and the xy track (see :func:`seahelm.plotting.timeseries`).

        Parameters
        ----------
        runs : sequence of int, optional
            Runs to draw (default: all).
        fig : matplotlib Figure, optional
            Figure to draw into (default: a new one).

        Returns
        -------
        matplotlib Figure
        """
        from .plotting.timeseries import plot_result

        return plot_result(self.to_xarray(), runs=runs, fig=fig)


def load_result(path: str | os.PathLike[str]) -> "xr.Dataset":
    """Open a result file written by :meth:`SimResult.to_netcdf` (loaded into memory).

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
    """
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"result file not found: {path}")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        return ds.load()
