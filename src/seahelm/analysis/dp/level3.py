"""DP station-keeping capability, level 3 (time domain), after DNV-ST-0111's method.

Every case of the grid (failure case × environment direction θ × wind speed U) is one run of
one batch of the closed loop — the vessel's model (``dp-3dof``), the ``dp-pid`` controller
with the constrained allocation at every control step, for the layout of that failure case —
from rest at the set-point, under the mean environmental load of level 1
(:func:`seahelm.analysis.dp.level1.environment_loads`: wind, wave drift and current, same
models and environment) applied as a constant load from t = 0. A case is **held** when, over
the last half of the run,

* the position stays within ``excursion_limit`` of the set-point (default 5 m) and the
  heading within ``heading_limit`` (default 3°) — the excursion criterion, and
* the allocation meets the demand: the largest unmet demand is below ``unmet_tolerance`` of
  the thrusters' total rating (the thrust-utilisation criterion: at most 100 % of the
  available thrust in the direction asked).

DNV-ST-0111's own acceptance values for level 3 were not reachable here; the limits above are
seahelm's defaults, stated in the result. The capability per failure case and direction is
the largest wind speed of the grid held (0: none). With no wave-frequency motion and no
dynamics left at the end (constant loads, integral action), the mean thrust equals the static
demand −τ_env of level 1, so level 3 holds what level 1 holds, to the wind grid's step (checked
in tests/test_dp_capability_level3.py).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import ParameterError, ValidityRangeWarning, strict_validity
from .level1 import BEAUFORT_WIND, dp_vessel, environment_loads

__all__ = ["Level3Result", "level3_capability"]


@dataclass
class Level3Result:
    """Level-3 capability: per failure case, direction and wind speed whether it is held."""

    vessel: str
    directions: np.ndarray
    wind_speeds: np.ndarray
    cases: tuple
    #: held or not, shape (cases, directions, wind speeds)
    held: np.ndarray
    #: largest excursion [m] over the last half, same shape
    excursion: np.ndarray
    #: mean delivered thrust (surge [N], sway [N], yaw [N·m]) over the last half, (..., 3)
    mean_thrust: np.ndarray
    #: the mean environmental load (..., 3)
    load: np.ndarray
    #: the largest wind speed held [m/s], (cases, directions)
    wind_speed: np.ndarray
    criteria: tuple = field(default_factory=tuple)
    seconds: float = 0.0


def level3_capability(ship: Any, *, headings: int = 12, wind_speeds: Any = None,
                      failures: Any = "each", current_speed: float = 0.5, waves: bool = True,
                      duration: float = 600.0, dt: float = 0.5,
                      excursion_limit: float = 5.0, heading_limit: float = math.radians(3.0),
                      unmet_tolerance: float = 1e-3, controller_params: Any = None,
                      workers: int | None = None) -> Level3Result:
    """Level-3 capability of a ship with thrusters (see the module).

    Parameters
    ----------
    ship : str, path-like or Ship
        A ship with thrusters, particulars and a ``dp-3dof`` model (the catalog's
        ``supply``).
    headings : int, optional
        Directions over 360° (default 12).
    wind_speeds : array_like, optional
        Wind speeds [m/s] (default the Beaufort upper speeds from Beaufort 4).
    failures : "each", "none" or sequence of str
        As :func:`~seahelm.analysis.dp.level1.level1_capability`.
    current_speed : float, optional
        [m/s] (default 0.5).
    waves : bool, optional
        Include the mean wave drift.
    duration, dt : float, optional
        Run length and step [s] (the controller's step too).
    excursion_limit : float, optional
        [m] (default 5).
    heading_limit : float, optional
        [rad] (default 3°).
    unmet_tolerance : float, optional
        Largest unmet demand over the total rating [-] (default 1e-3).
    controller_params : mapping, optional
        :class:`~seahelm.control.dp_pid.DpPidParams` fields (gains) for every case.
    workers : int, optional
        Run the batch in chunks on a local Dask cluster of this many worker processes (the
        ``dask`` extra); default: one batch in this process (the engine's threads).

    Returns
    -------
    Level3Result
    """
    from ...control.dp_pid import dp_pid_params
    from ...ships.catalog import get

    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise ParameterError(f"must be an integer ≥ 1 [-], got {workers!r}", field="workers",
                             unit="-", value=workers)
    headings = int(headings)
    if headings < 1:
        raise ParameterError(f"must be ≥ 1 [-], got {headings}", field="headings", unit="-",
                             value=headings)
    winds = np.asarray(BEAUFORT_WIND[4:] if wind_speeds is None else wind_speeds, dtype=float)
    if winds.ndim != 1 or winds.size == 0 or np.any(~np.isfinite(winds)) or np.any(winds < 0):
        raise ParameterError(f"must be one or more speeds ≥ 0 [m/s], got {wind_speeds!r}",
                             field="wind_speeds", unit="m/s")
    if winds.max() > BEAUFORT_WIND[-1]:
        raise ParameterError(f"beyond the environment tables (≤ {BEAUFORT_WIND[-1]} m/s) "
                             f"[m/s], got {winds.max()!r}", field="wind_speeds", unit="m/s",
                             value=float(winds.max()))
    sh = get(ship)
    vessel = dp_vessel(sh)
    lay = sh.thrusters
    lost = (list(lay.names) if failures == "each" else [] if failures == "none"
            else list(failures))
    layouts = [("intact", lay)] + [(f"without {nm}", lay.without(nm)) for nm in lost]
    theta = np.arange(headings) * (2.0 * math.pi / headings)
    nc, nh, nw = len(layouts), headings, winds.size
    load = environment_loads(vessel, winds[None, :], theta[:, None], current_speed,
                             waves=waves)                          # (nh, nw, 3)
    gains = dict(controller_params or {})
    cparams = [dp_pid_params(sh.replace(thrusters=lyt), **gains).to_array()
               for _, lyt in layouts]
    cp = np.repeat(np.stack(cparams), nh * nw, axis=0)             # (nc·nh·nw, n_params)
    ld = np.broadcast_to(load, (nc, nh, nw, 3)).reshape(-1, 3)
    runs = ld.shape[0]
    f_ref = float(np.sum(lay.max_thrust))
    l_ref = max(1.0, float(np.max(np.hypot(lay.x, lay.y))))
    limits = (float(excursion_limit), float(heading_limit), unmet_tolerance * f_ref,
              unmet_tolerance * f_ref * l_ref)
    source = sh.name if sh.name in _catalog_names() and get(sh.name) == sh else \
        _mapping(sh)
    t0 = time.perf_counter()
    if workers is None:
        parts = [_run_chunk(source, cp, ld, float(duration), float(dt), limits)]
    else:
        parts = _on_dask(int(workers), source, cp, ld, float(duration), float(dt), limits)
    seconds = time.perf_counter() - t0
    ok, excursion, mean = (np.concatenate([pt[k] for pt in parts]) for k in range(3))
    shape = (nc, nh, nw)
    held = ok.reshape(shape)
    # the largest wind held with every lighter wind of the grid held too
    order = np.argsort(winds)
    run_ok = np.cumprod(held[:, :, order], axis=2).astype(bool)
    best = np.where(run_ok.any(axis=2), winds[order][np.maximum(run_ok.sum(axis=2) - 1, 0)],
                    0.0)
    criteria = (f"excursion ≤ {excursion_limit:g} m and heading within "
                f"{math.degrees(heading_limit):g} deg over the last half of {duration:g} s "
                "(seahelm's limits: DNV-ST-0111's level-3 values not reachable here)",
                f"thrust utilisation: unmet demand ≤ {unmet_tolerance:g} of the total rating",
                "environment and loads as level 1, the mean load constant from t = 0",
                "a run that loses position leaves dp-3dof's low-speed range (> 2 m/s through "
                "the water): it is not held, its excursion no prediction")
    return Level3Result(vessel.name, theta, winds, tuple(nm for nm, _ in layouts), held,
                        excursion.reshape(shape), mean.reshape(shape + (3,)),
                        np.broadcast_to(load, shape + (3,)).copy(), best, criteria, seconds)


def _catalog_names() -> tuple[str, ...]:
    from ...ships.catalog import names

    return names()


def _mapping(ship: Any) -> dict:
    from ...ships.writing import ship_to_mapping

    return ship_to_mapping(ship)


def _run_chunk(source: Any, cp: np.ndarray, ld: np.ndarray, duration: float, dt: float,
               limits: tuple) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Simulate the runs (controller parameters ``cp``, loads ``ld``) and judge them: held,
    the excursion [m] and the mean delivered thrust over the last half."""
    from ...ships.catalog import get
    from ...ships.files import ship_from_mapping
    from ...simulation.engine import simulate
    from ...simulation.problem import Problem

    sh = get(source) if isinstance(source, str) else ship_from_mapping(source, lookup=get)
    runs = ld.shape[0]
    with warnings.catch_warnings(), strict_validity(False):  # (runs that lose position leave
        # dp-3dof's low-speed range: they are not held, which the criteria say; no warning)
        warnings.simplefilter("ignore", ValidityRangeWarning)
        res = simulate(Problem(
            ship=sh, x0=np.zeros(6), t_final=duration, dt=dt, actuator="direct",
            controller="dp-pid", controller_params=cp,
            reference={"north": 0.0, "east": 0.0, "heading": 0.0, "wind_force_x": 0.0,
                       "wind_force_y": 0.0, "wind_moment_z": 0.0},
            disturbance={"force_x": ld[:, 0].reshape(runs, 1, 1),
                         "force_y": ld[:, 1].reshape(runs, 1, 1),
                         "moment_z": ld[:, 2].reshape(runs, 1, 1)}))
    t = np.asarray(res.time)
    late = t >= 0.5 * duration
    north, east, psi = (np.asarray(res[k])[:, late] for k in ("north", "east", "heading"))
    excursion = np.hypot(north, east).max(axis=1)
    dpsi = np.abs((psi + math.pi) % (2 * math.pi) - math.pi).max(axis=1)
    unmet = np.stack([np.abs(np.asarray(res[k])[:, late]).max(axis=1)
                      for k in ("unmet_surge", "unmet_sway")], axis=1).max(axis=1)
    unmet_n = np.abs(np.asarray(res["unmet_yaw"])[:, late]).max(axis=1)
    ex_lim, psi_lim, f_lim, n_lim = limits
    ok = (np.isfinite(excursion) & (excursion <= ex_lim) & (dpsi <= psi_lim)
          & (unmet <= f_lim) & (unmet_n <= n_lim) & np.asarray(res.ok))
    mean = np.stack([np.asarray(res[k])[:, late].mean(axis=1)
                     for k in ("thrust_surge", "thrust_sway", "thrust_yaw")], axis=1)
    return ok, excursion, mean


def _on_dask(workers: int, source: Any, cp: np.ndarray, ld: np.ndarray, duration: float,
             dt: float, limits: tuple) -> list:
    """The runs in chunks (4 per worker) on a local Dask cluster, in order."""
    from ..._dask import local_cluster
    from ..._optional import optional_import

    distributed = optional_import("distributed", extra="dask",
                                  purpose="level-3 capability on a dask cluster (--workers)")
    runs = ld.shape[0]
    n_chunks = min(runs, 4 * workers)
    edges = np.linspace(0, runs, n_chunks + 1).astype(int)
    cluster = local_cluster(workers, purpose="level-3 capability on a dask cluster (--workers)")
    try:
        with distributed.Client(cluster, set_as_default=False) as client:
            futures = [client.submit(_run_chunk, source, cp[a:b], ld[a:b], duration, dt,
                                     limits, pure=False)
                       for a, b in zip(edges[:-1], edges[1:]) if b > a]
            return client.gather(futures)
    finally:
        import logging

        # (dask logs its workers' shutdown as warnings: said once here, not per worker)
        quiet = [logging.getLogger(n) for n in ("distributed", "distributed.nanny")]
        levels = [lg.level for lg in quiet]
        for lg in quiet:
            lg.setLevel(logging.CRITICAL + 1)
        try:
            cluster.close()
        finally:
            for lg, level in zip(quiet, levels):
                lg.setLevel(level)
