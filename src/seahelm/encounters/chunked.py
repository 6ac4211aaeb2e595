"""Encounters in chunks, in this process or on a dask.distributed cluster (as ``seahelm sweep
--workers N`` runs a scenario's chunks).

An encounter's vessels see only each other (an encounter in a batch equals it run alone, bit
for bit, with avoidance on: ``tests/test_encounters.py``), so a batch splits along the
encounter axis into chunks of ``chunk_size`` encounters that run anywhere, and their results
put back together in order are those of the whole batch run at once. A chunk travels as its
vessels (sliced; a catalog ship by its name) and the encounter's settings; the worker builds
and runs it. A noisy sensor's noise is a function of the encounter's index in the study
(:mod:`.sensing`): each chunk runs with its first encounter's index, and a sensor without a
seed gets one drawn once for all the chunks, so chunks see the noise of the whole batch.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from .._dask import local_cluster
from .._optional import optional_import
from ..errors import ParameterError
from .encounter import Encounter, Vessel
from .result import EncounterResult

__all__ = ["split_encounter", "concat_results", "run_chunked", "encounter_settings",
           "portable_vessel", "run_chunk"]


def encounter_settings(enc: Encounter) -> dict[str, Any]:
    """The settings a chunk of ``enc`` carries: the keyword arguments of :class:`Encounter`
    other than its vessels and ``first_encounter`` (horizon, steps, sensor, avoidance,
    autopilot, sectors, domain, verdict rules, record interval).

    Parameters
    ----------
    enc : Encounter

    Returns
    -------
    dict
        ``Encounter(vessels, **settings)`` builds the same encounter for other vessels.
    """
    return {"t_final": enc.t_final, "dt": enc.dt, "controller_dt": enc.controller_dt,
            "sensor": enc.sensor, "avoidance": enc.avoidance, "autopilot": enc.autopilot,
            "sectors": enc.sectors, "domain": enc.domain, "verdicts": enc.verdict_rules,
            "record_every": enc.record_every}


def _slice(v: Vessel, lo: int, hi: int, ne: int) -> Vessel:
    def cut(value: Any, ndim: int) -> Any:
        if value is None:
            return None
        a = np.asarray(value)
        return a[lo:hi] if a.ndim == ndim and a.shape[0] == ne else value
    return dataclasses.replace(v, north=cut(v.north, 1), east=cut(v.east, 1),
                               course=cut(v.course, 1), speed=cut(v.speed, 1),
                               route=cut(v.route, 3))


def split_encounter(enc: Encounter, chunk_size: int) -> list[tuple[list[Vessel], dict]]:
    """The chunks of ``enc``: for each, its vessels (every per-encounter array sliced) and the
    encounter's settings (keyword arguments of :class:`Encounter`).

    Parameters
    ----------
    enc : Encounter
    chunk_size : int
        Encounters per chunk (the last may be shorter).

    Returns
    -------
    list of (vessels, settings)
    """
    if not (isinstance(chunk_size, (int, np.integer)) and chunk_size >= 1):
        raise ParameterError(f"must be an integer >= 1 [encounters], got {chunk_size!r}",
                             field="chunk_size", value=chunk_size)
    ne, settings = enc.n_encounters, encounter_settings(enc)
    if enc.sensor.noisy and enc.sensor.seed is None:  # (one seed for every chunk)
        settings["sensor"] = dataclasses.replace(
            enc.sensor, seed=int(np.random.SeedSequence().generate_state(1)[0]))
    first = enc.first_encounter
    return [([_slice(v, lo, min(lo + chunk_size, ne), ne) for v in enc.vessels],
             {**settings, "first_encounter": first + lo})
            for lo in range(0, ne, chunk_size)]


def portable_vessel(v: Vessel) -> Vessel:
    """``v`` ready to travel to another process: a ship equal to a catalog ship is sent by its
    name (a Ship object's compiled model functions do not travel as themselves); any other
    vessel is returned as it is.

    Parameters
    ----------
    v : Vessel

    Returns
    -------
    Vessel
    """
    from ..ships import Ship, get_ship

    if isinstance(v.ship, Ship):
        try:
            same = get_ship(v.ship.name) == v.ship
        except (ParameterError, KeyError, ValueError):
            same = False
        if same:
            return dataclasses.replace(v, ship=v.ship.name)
    return v


def _run_chunk(vessels: list[Vessel], settings: dict[str, Any]) -> EncounterResult:
    return Encounter(vessels, **settings).run()


def run_chunk(vessels: list[Vessel], settings: dict[str, Any]) -> EncounterResult:
    """Run one chunk of :func:`split_encounter` (here or on a worker).

    Parameters
    ----------
    vessels : list of Vessel
        The chunk's vessels (sliced; :func:`portable_vessel` to send them elsewhere).
    settings : dict
        The chunk's settings (:func:`encounter_settings` and its ``first_encounter``).

    Returns
    -------
    EncounterResult
        The chunk's encounters, as in the whole batch run at once.
    """
    # (through the module's _run_chunk: the seam the store tests interrupt)
    return _run_chunk(vessels, settings)


def concat_results(results: list[EncounterResult]) -> EncounterResult:
    """Chunks' results as one, along the encounter axis, in the order given.

    Parameters
    ----------
    results : list of EncounterResult
        Of the same vessels, horizon and records.

    Returns
    -------
    EncounterResult
    """
    first = results[0]
    for r in results[1:]:
        if r.names != first.names or not np.array_equal(r.time, first.time, equal_nan=True):
            raise ParameterError(": results of other vessels or records cannot be joined",
                                 field="results")
    out = EncounterResult.__new__(EncounterResult)
    out.names, out.lengths, out.domain_axes = first.names, first.lengths, first.domain_axes
    out.time = first.time
    out.tracks = {k: np.concatenate([r.tracks[k] for r in results]) for k in first.tracks}
    out.pair = {k: np.concatenate([r.pair[k] for r in results]) for k in first.pair}
    out.verdicts = {k: np.concatenate([r.verdicts[k] for r in results])
                    for k in first.verdicts}
    for name in ("status", "min_range", "t_min_range", "min_domain_distance", "situation",
                 "collision", "near_miss"):
        setattr(out, name, np.concatenate([getattr(r, name) for r in results]))
    return out


def run_chunked(enc: Encounter, *, chunk_size: int | None = None, workers: int | None = None,
                scheduler: str | None = None) -> EncounterResult:
    """Run ``enc`` in chunks (module notes): one after the other in this process, or on a
    local dask cluster of ``workers`` processes, or on a running one at ``scheduler``.

    Parameters
    ----------
    enc : Encounter
    chunk_size : int, optional
        Encounters per chunk (default: the encounters over 4 per worker, at least 1).
    workers : int, optional
        Processes of a local cluster (``dask.distributed``; one thread each).
    scheduler : str, optional
        Address of a running dask scheduler.

    Returns
    -------
    EncounterResult
        Equal to ``enc.run()`` (bit for bit).
    """
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise ParameterError(f"must be an integer >= 1, got {workers!r}", field="workers",
                             value=workers)
    if workers is not None and scheduler is not None:
        raise ParameterError(": give workers (a local cluster) or scheduler (a running one), "
                             "not both", field="workers")
    ne = enc.n_encounters
    if chunk_size is None:
        chunk_size = max(1, math.ceil(ne / (4 * (workers or 1))))
    chunks = split_encounter(enc, chunk_size)
    if workers is None and scheduler is None:
        return concat_results([run_chunk(*c) for c in chunks])
    distributed = optional_import("distributed", extra="dask",
                                  purpose="encounters on a dask cluster")
    vessels = [[portable_vessel(v) for v in c[0]] for c in chunks]
    settings = [c[1] for c in chunks]
    if scheduler is not None:
        with distributed.Client(scheduler, set_as_default=False) as client:
            results = client.gather(client.map(run_chunk, vessels, settings, pure=False))
    else:
        with local_cluster(workers, purpose="encounters on a dask cluster") as cluster, \
                distributed.Client(cluster, set_as_default=False) as client:
            results = client.gather(client.map(run_chunk, vessels, settings, pure=False))
    return concat_results(list(results))
