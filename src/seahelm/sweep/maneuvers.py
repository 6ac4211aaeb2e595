"""Chunks of a ``[maneuver]`` sweep: a manoeuvre's metrics per Monte-Carlo sample of the ship.

A chunk is a range of samples; its ships (the scenario's ship with each sample's drawn
parameters, :meth:`~seahelm.scenario.ManeuverJob.ships`) run as one batch of the manoeuvre
(:func:`~seahelm.analysis.maneuvers.turning_circle` and friends, a ``ship`` dimension), and
the metrics table is stored over ``run`` = sample index, with the manoeuvre's own dimensions
(``side``, ``rudder``, ...) after it. The time series are not stored (a manoeuvre's metrics are
the question; the runs of one sample are one ``seahelm run`` away).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ..scenario import ManeuverJob

__all__ = ["maneuver_chunk", "maneuver_template", "maneuver_dims"]


def maneuver_chunk(job: "ManeuverJob", start: int, stop: int, *, with_attrs: bool = False
                   ) -> Any:
    """The manoeuvre's metrics of samples ``start:stop`` over the global ``run``.

    Parameters
    ----------
    job : ManeuverJob
        The scenario's manoeuvre.
    start, stop : int
        Sample range.
    with_attrs : bool, optional
        Also return the metrics' attributes (scenario, manoeuvre), as ``(dataset, attrs)``.

    Returns
    -------
    xarray.Dataset
        Numeric metrics (``kind = "metric"``) and ``complete`` over ``(run, ...)``.
    """
    result = job.run_ships(job.ships(start, stop))
    metrics = result.metrics
    if "ship" in metrics.dims:
        ds = metrics.rename({"ship": "run"})
    else:
        ds = metrics.expand_dims("run")
    drop = [name for name, var in ds.variables.items()
            if var.dtype.kind in "USO" or ("run" not in var.dims and name not in ds.dims)]
    ds = ds.drop_vars(drop)
    ds = ds.assign_coords(run=np.arange(start, stop))
    for name, var in ds.data_vars.items():
        if var.dtype.kind in "fiu":
            var.attrs["kind"] = "metric"
    ds = ds.transpose("run", ...)
    attrs = {k: v for k, v in metrics.attrs.items()
             if isinstance(v, (str, int, float)) and k not in ("created", "wall_time_s")}
    if result.simulation is not None:  # (the time series recorded while a chunk runs)
        sim = result.simulation
        recorded = sum(getattr(sim, name).nbytes for name in
                       ("state", "output", "command", "reference", "disturbance"))
        attrs["sweep_bytes_per_run"] = int(recorded + ds.nbytes) // (stop - start)
    ds.attrs = {}
    return (ds, attrs) if with_attrs else ds


def maneuver_dims(job: "ManeuverJob") -> list[list[Any]]:
    """The batch dimensions over ``run``: ``sample`` for Monte-Carlo, else none.

    Parameters
    ----------
    job : ManeuverJob
        The scenario's manoeuvre.

    Returns
    -------
    list of [name, size]
    """
    return [["sample", job.n_samples]] if job.monte_carlo is not None else []


def maneuver_template(job: "ManeuverJob") -> tuple["xr.Dataset", dict[str, Any],
                                                   tuple[str, ...], dict[str, Any], int]:
    """The store's template of a manoeuvre sweep: sample 0's metrics, the drawn values of
    every sample (and the ``sample`` coordinate) over ``run``, which of them are coordinates,
    the root attributes and the number of samples.

    Parameters
    ----------
    job : ManeuverJob
        The scenario's manoeuvre.

    Returns
    -------
    tuple
        ``(template, layout_vars, coords, attrs, n_runs)``.
    """
    template, attrs = maneuver_chunk(job, 0, 1, with_attrs=True)
    n = job.n_samples
    layout_vars: dict[str, Any] = {}
    coords: tuple[str, ...] = ()
    if job.monte_carlo is not None:
        layout_vars["sample"] = ("run", np.arange(n), {})
        coords = ("sample",)
        mc = job.monte_carlo
        kinds = {key: dist.distribution for key, dist in mc.draws.items()}
        kinds.update({key: "correlated-normal" for b in mc.correlated for key in b.keys})
        for key, values in job.draws(np.arange(n)).items():
            layout_vars[key] = ("run", values, {"kind": "batch_values", "key": key,
                                                "distribution": kinds[key],
                                                **_units(job, key)})
        attrs["seed"] = int(mc.seed)
    attrs["maneuver"] = job.kind
    return template, layout_vars, coords, attrs, n


def _units(job: "ManeuverJob", key: str) -> dict[str, str]:
    """``{"units": ...}`` of a drawn key (the parameter's or the particular's, in degrees for a
    ``_deg`` key; empty if it has none)."""
    section, _, name = key.rpartition(".")
    degrees = name.endswith("_deg")
    name = name[:-4] if degrees else name
    if section == "vessel.particulars":
        from ..ships.estimate import DESIGN_FIELDS

        unit = {n: u for n, u, _, _ in DESIGN_FIELDS}.get(name, "")
    else:
        params = {"vessel.params": job.ship.params, "actuator.params": job.ship.servo}.get(section)
        unit = "" if params is None else {i.name: i.unit for i in type(params).info()}.get(name, "")
    if degrees:
        unit = unit.replace("rad", "deg") if unit.startswith("rad") else "deg"
    return {"units": unit} if unit else {}
