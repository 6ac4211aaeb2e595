"""Chunks of a ``[maneuver]`` sweep: a manoeuvre's metrics per Monte-Carlo sample of the ship.

A chunk is a range of samples; its ships (the scenario's ship with each sample's drawn
parameters, :meth:`~seahelm.scenario.ManeuverJob.ships`) run as one batch of the manoeuvre
(:func:`~seahelm.analysis.maneuvers.turning_circle` and friends, a ``ship`` dimension), and
the metrics table is stored over ``run`` = sample index, with the manoeuvre's own dimensions
(``side``, ``rudder``, ...) after it. The IMO check's samples store their criteria's values
instead (:mod:`seahelm.sweep.imo`). The time series are not stored (a manoeuvre's metrics are
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
    if job.kind == "imo":
        from .imo import imo_chunk

        return imo_chunk(job, start, stop, with_attrs=with_attrs)
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
    _check_sweepable(job)
    template, attrs = maneuver_chunk(job, 0, 1, with_attrs=True)
    n = job.n_samples
    layout_vars: dict[str, Any] = {}
    coords: tuple[str, ...] = ()
    if job.monte_carlo is not None:
        layout_vars["sample"] = ("run", np.arange(n), {})
        coords = ("sample",)
        mc = job.monte_carlo
        described = job.draw_attrs()
        for key, values in job.draws(np.arange(n)).items():
            layout_vars[key] = ("run", values, {"kind": "batch_values", "key": key,
                                                **described[key]})
        attrs["seed"] = int(mc.seed)
    attrs["maneuver"] = job.kind
    return template, layout_vars, coords, attrs, n


def _check_sweepable(job: "ManeuverJob") -> None:
    """A sweep stores each sample's metrics: a spiral (two results, one of equilibria) and the
    IMO check of one ship (a report, not metrics) are runs of ``seahelm run``."""
    from ..errors import ParameterError

    source = job.metadata.get("scenario_source", "<string>")
    if job.kind == "spiral":
        raise ParameterError(f"{source}: [maneuver] a sweep stores the metrics of turning, "
                             "zigzag, pullout, stopping and (Monte-Carlo) imo manoeuvres, not "
                             "a spiral: run it with `seahelm run`")
    if job.kind == "imo" and job.monte_carlo is None:
        raise ParameterError(f"{source}: [maneuver] a sweep of the IMO check runs the samples "
                             "of [batch.monte_carlo] (the probability of passing each "
                             "criterion); the check of one ship is `seahelm run`")
