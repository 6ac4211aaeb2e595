"""The IMO check given an identification, in one call: fit → posterior → ships → probabilities.

An identified model is uncertain; the probability that the ship passes IMO MSC.137(76) given
the records is the fraction of ships drawn from the fit's posterior that pass
(:func:`~seahelm.analysis.imo.probability.imo_probabilities`, Wilson intervals).
:func:`imo_given_nomoto_fit` draws the posterior of a Nomoto fit
(:func:`~seahelm.identification.nomoto_posterior.posterior_samples`) and builds its ships with the
given speed, length and steering gear (:func:`~seahelm.identification.nomoto_posterior.
posterior_ships`); :func:`imo_given_mmg_fit` draws the hull derivatives of an MMG fit
(:func:`~seahelm.identification.mmg_posterior.mmg_posterior`) into the base ship, the identified
ship bounding the members' runs. :func:`write_posterior_samples` writes an MMG posterior as a
samples file (:mod:`seahelm.identification.samples_file`) that ``seahelm imo SHIP --draws`` and a
scenario's ``[batch.monte_carlo] samples`` read. ``seahelm identify nomoto|mmg --imo N`` is
these calls and a rendering.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ...errors import ParameterError

__all__ = ["imo_given_nomoto_fit", "imo_given_mmg_fit", "write_posterior_samples"]


def imo_given_nomoto_fit(fit: Any, records: Sequence[Any], n: int, *, speed: float | None,
                         length: float | None, method: str = "laplace",
                         seed: int | None = None, max_rudder: float = math.radians(35.0),
                         rudder_rate: float = math.radians(65.0 / 28.0), level: float = 0.95,
                         progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The IMO pass probabilities of ``n`` ships from a Nomoto fit's posterior.

    Parameters
    ----------
    fit : NomotoFit
        :func:`~seahelm.identification.nomoto_fit.fit_nomoto`.
    records : sequence of ManoeuvreRecord
        The records it was fitted to.
    n : int
        Posterior ships.
    speed, length : float
        The ship's U [m/s] and L [m] (the IMO limits are in ship lengths and L/V).
    method : {"laplace", "mcmc"}, optional
        Of the posterior.
    seed : int, optional
    max_rudder : float, optional
        Rudder limit [rad].
    rudder_rate : float, optional
        Rudder rate [rad/s].
    level : float, optional
        Of the Wilson intervals.
    progress : callable(done, total), optional
        As :func:`~seahelm.analysis.imo.probability.imo_probabilities`'.

    Returns
    -------
    dict
        :meth:`~seahelm.analysis.imo.probability.ImoProbabilities.as_dict` with ``samples``,
        ``posterior`` and ``seed``.

    Raises
    ------
    ParameterError
        No speed or length (``field="speed"``/``"length"``); a fit that does not identify
        its parameters (``field="fit"``): no posterior to draw from.
    """
    from ...identification.nomoto_posterior import posterior_samples, posterior_ships

    for field, value in (("speed", speed), ("length", length)):
        if value is None:
            raise ParameterError("is needed for the IMO check (the ship's U [m/s] and L [m]: "
                                 "the IMO limits are in ship lengths and L/V)", field=field)
    bad = {k for k in fit.unidentifiable() if k != "rudder_offset"}
    if bad:
        raise ParameterError(f"the records do not identify {', '.join(sorted(bad))}; no "
                             "posterior to draw ships from", field="fit")
    samples = posterior_samples(fit, records, n=n, method=method, seed=seed)
    ships = posterior_ships(fit, samples, name="posterior", speed=speed, length=length,
                            max_rudder=max_rudder, rudder_rate=rudder_rate)
    return _probabilities(ships, n, method, seed, level, None, progress)


def imo_given_mmg_fit(fit: Any, records: Sequence[Any], base: Any, n: int, *,
                      method: str = "laplace", seed: int | None = None, level: float = 0.95,
                      name: str | None = None, posterior: Any = None,
                      progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The IMO pass probabilities of ``n`` ships from an MMG hull fit's posterior.

    Parameters
    ----------
    fit : HullFit
        :func:`~seahelm.identification.mmg_fit.identify_mmg`.
    records : sequence of ManoeuvreRecord
    base : Ship
        The base ship the fit's derivatives go into.
    n : int
        Posterior ships.
    method : {"laplace", "mcmc"}, optional
    seed : int, optional
    level : float, optional
    name : str, optional
        The identified ship's name (the reference bounding the runs).
    posterior : MMGPosterior, optional
        Already drawn (:func:`~seahelm.identification.mmg_posterior.mmg_posterior`; e.g. also
        written with :func:`write_posterior_samples`); default: drawn here.
    progress : callable(done, total), optional

    Returns
    -------
    dict
        As :func:`imo_given_nomoto_fit`'s, with ``posterior_samples`` (the posterior's
        diagnostics).
    """
    from ...identification.mmg_posterior import mmg_posterior, posterior_ships

    post = posterior if posterior is not None else mmg_posterior(fit, records, n=n,
                                                                 method=method, seed=seed)
    out = _probabilities(posterior_ships(fit, post, base), n, method, seed, level,
                         fit.ship(base, name=name), progress)
    out["posterior_samples"] = post.as_dict()
    return out


def _probabilities(ships: list[Any], n: int, method: str, seed: int | None, level: float,
                   reference: Any, progress: Any) -> dict[str, Any]:
    from .probability import imo_probabilities

    out = imo_probabilities(ships, level=level, reference=reference,
                            progress=progress).as_dict()
    out.update(samples=n, posterior=method, seed=seed)
    return out


def write_posterior_samples(path: str | os.PathLike[str], fit: Any, post: Any, base: Any,
                            seed: int | None) -> Path:
    """An MMG posterior's ships' hull derivatives as a samples file, a row per sample, with
    the units and comments saying what was sampled.

    Parameters
    ----------
    path : str or os.PathLike
        ``FILE.csv``.
    fit : HullFit
    post : MMGPosterior
    base : Ship
    seed : int or None
        The posterior's seed (for the comment).

    Returns
    -------
    pathlib.Path
    """
    from ...identification.mmg_posterior import posterior_columns
    from ...identification.samples_file import write_samples

    columns = posterior_columns(fit, post)
    units = {i.name: i.unit for i in type(base.params).info()}
    fixed = ", ".join(fit.fixed) or "none"
    return write_samples(path, columns, units={k: units.get(k.rpartition(".")[2], "")
                                               for k in columns}, comments=(
        f"seahelm posterior samples of the MMG hull derivatives of '{base.name}' "
        f"({post.method}, {post.samples.shape[0]} samples, "
        + (f"seed {seed})" if seed is not None else "unseeded)"),
        f"identified ({fit.method}) from {', '.join(fit.records)}",
        f"sampled: {', '.join(fit.names)}; not identified, at the base ship's values: "
        f"{fixed}; the others at the fit's values",
        "one row per sample; use: seahelm imo SHIP.toml --draws FILE.csv, or a scenario's "
        "[batch.monte_carlo] samples = \"FILE.csv\""))
