"""The IMO check of a ship under uncertainty, in one call: draw, check, keep what was drawn.

:func:`imo_monte_carlo` draws ``n`` samples of a ship's coefficients
(:func:`~seahelm.analysis.imo.probability.monte_carlo_ships`: by default a normal
distribution of relative standard deviation ``uncertainty`` around the model's
:data:`~seahelm.analysis.imo.probability.UNCERTAIN_COEFFICIENTS`), checks them
(:func:`~seahelm.analysis.imo.probability.imo_probabilities`) and returns an
:class:`ImoEnsemble`: the probabilities, every sample's drawn values by key path
(``vessel.params.<name>``) with their distribution and unit, and what was checked.
:func:`imo_of_samples` does the same for the rows of a samples file
(:mod:`seahelm.identification.samples_file`, e.g. an identification's posterior). ``seahelm imo
SHIP --monte-carlo N`` (and ``--draws FILE.csv``) is these two calls; its ``--out`` writes
:meth:`ImoEnsemble.dataset` and the figure of :func:`seahelm.plotting.imo_ensemble.
plot_imo_ensemble`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from ...errors import ParameterError
from .probability import DEFAULT_UNCERTAINTY, UNCERTAIN_COEFFICIENTS

if TYPE_CHECKING:
    import xarray as xr

    from .probability import ImoProbabilities

__all__ = ["SHARED_KEYS", "ImoEnsemble", "drawn_statistics", "imo_monte_carlo", "imo_of_samples", "drawn_values",
           "ships_of_samples"]

#: The key path of a drawn ship parameter.
PARAMS = "vessel.params."
#: Keys an IMO ensemble may not draw: its members share the ship's length, test speed and
#: steering-gear limit (the criteria are in ship lengths and L/V, at the hard-over rudder).
SHARED_KEYS = ("vessel.params.length", "vessel.params.approach_speed",
               "vessel.params.nominal_speed", "actuator.params.max_angle",
               "actuator.params.max_angle_deg", "vessel.particulars.length",
               "vessel.particulars.speed", "vessel.particulars.max_rudder",
               "vessel.particulars.max_rudder_deg")


@dataclasses.dataclass(frozen=True)
class ImoEnsemble:
    """An ensemble's IMO check with what was drawn.

    Attributes
    ----------
    probabilities : ImoProbabilities
        The check (with every member's values).
    drawn : dict of str to (list of float, dict)
        Key path (``vessel.params.<name>``) -> (the value of every member, its attributes:
        ``distribution`` and, for a parameter with one, ``units``).
    metadata : dict
        What was checked: ``ship``, ``samples``, ``seed``, ``draws`` (``"default"`` or where
        the draws came from) and ``uncertainty`` (the default draws' relative standard
        deviation, None otherwise).
    title : str
        A one-line title (the CLI's table, the figure, the file's ``title``).
    """

    probabilities: "ImoProbabilities"
    drawn: dict[str, tuple[list[float], dict[str, str]]]
    metadata: dict[str, Any]
    title: str

    def dataset(self) -> "xr.Dataset":
        """The check as a Dataset (:func:`~seahelm.analysis.imo.ensemble.ensemble_dataset`:
        ``imo-probabilities.nc``).

        Returns
        -------
        xarray.Dataset
        """
        from .ensemble import ensemble_dataset

        return ensemble_dataset(self.probabilities, draws=self.drawn,
                                attrs={**self.metadata, "title": self.title})


def drawn_values(ships: list[Any], kinds: Mapping[str, str]) -> dict[str, tuple[list[float],
                                                                                 dict[str, str]]]:
    """Every member's value of each drawn parameter, by key path, with its distribution and
    the parameter's unit (from the parameter record's declaration).

    Parameters
    ----------
    ships : list of Ship
        The members (one model).
    kinds : mapping of str to str
        Drawn parameter name -> its distribution's name.

    Returns
    -------
    dict of str to (list of float, dict)
    """
    units = {i.name: i.unit for i in type(ships[0].params).info()} if ships else {}
    return {f"{PARAMS}{k}": ([float(getattr(s.params, k)) for s in ships],
                             {"distribution": kind, **({"units": units[k]} if units.get(k)
                                                       else {})})
            for k, kind in kinds.items()}


def imo_monte_carlo(ship: Any, n: int, *, seed: int = 0, draws: Mapping[str, Any] | None = None,
                    uncertainty: float = DEFAULT_UNCERTAINTY, dt: float | None = None,
                    progress: Callable[[int, int], None] | None = None,
                    source: str | None = None) -> ImoEnsemble:
    """The IMO check of ``n`` samples of ``ship`` with drawn coefficients.

    Parameters
    ----------
    ship : Ship
        The nominal ship (also the reference whose manoeuvres' durations bound the members').
    n : int
        Samples (≥ 1).
    seed : int, optional
        The seed of the draws (``SeedSequence(seed)``, one generator per sample).
    draws : mapping of parameter name to Distribution, optional
        What to draw (:mod:`seahelm.numerics.sampling`); default: the model's uncertain
        coefficients, normal with relative standard deviation ``uncertainty``.
    uncertainty : float, optional
        Of the default draws (ignored with ``draws``).
    dt : float, optional
        Integration step [s] (default: the manoeuvres').
    progress : callable(done, total), optional
        Called as the manoeuvres of the samples complete
        (:func:`~seahelm.analysis.imo.probability.imo_probabilities`).
    source : str, optional
        Where ``draws`` came from (a file), for the metadata (default ``"draws"``).

    Returns
    -------
    ImoEnsemble

    Raises
    ------
    ParameterError
        As :func:`~seahelm.analysis.imo.probability.monte_carlo_ships` and
        :func:`~seahelm.analysis.imo.probability.imo_probabilities`.
    """
    from .probability import imo_probabilities, monte_carlo_ships

    ships = monte_carlo_ships(ship, n, seed=seed, draws=draws, uncertainty=uncertainty)
    probs = imo_probabilities(ships, dt=dt, reference=ship, progress=progress)
    kinds = ({k: "normal" for k in UNCERTAIN_COEFFICIENTS.get(ship.model.name, ())}
             if draws is None else {k: d.name for k, d in draws.items()})
    meta = {"ship": ship.name, "samples": n, "seed": seed,
            "draws": "default" if draws is None else (source or "draws"),
            "uncertainty": uncertainty if draws is None else None}
    return ImoEnsemble(probs, drawn_values(ships, kinds), meta,
                       f"IMO MSC.137(76): {ship.name}, {n} Monte-Carlo samples (seed {seed})")


def ships_of_samples(ship: Any, table: Any, n: int | None = None) -> list[Any]:
    """The ships of a samples table's first ``n`` rows: ``ship`` with row i's
    ``vessel.params.<name>`` values, named ``<name> #i``.

    Parameters
    ----------
    ship : Ship
    table : SamplesTable
        :func:`~seahelm.identification.samples_file.read_samples`; every column a
        ``vessel.params.<name>`` of the ship's model, in its stored unit.
    n : int, optional
        Rows (default: all).

    Returns
    -------
    list of Ship

    Raises
    ------
    ParameterError
        ``field="draws"``: a column that is not a parameter of the ship (or is one the members
        of an IMO check share), more rows asked for than the table holds, units other than
        the stored ones, a row the ship cannot take (with ``run`` the row).
    """
    from ...identification.samples_file import check_units

    names = set(ship.params.field_names())
    for key in table.keys:
        if not key.startswith(PARAMS):
            raise ParameterError(f"column `{key}`: the samples of `seahelm imo` vary the "
                                 "ship's parameters (vessel.params.<name>); a scenario's "
                                 "[batch.monte_carlo] samples also its steering gear's",
                                 field="draws")
        if key in SHARED_KEYS:
            raise ParameterError(f"column `{key}`: the samples of an IMO check share the "
                                 "ship's length and test speed (its criteria are in ship "
                                 "lengths and L/V): draw its other parameters", field="draws")
    if n is None:
        n = table.n_samples
    elif n > table.n_samples:
        raise ParameterError(f"{n}: the samples hold only {table.n_samples} "
                             f"sample{'' if table.n_samples == 1 else 's'}", field="n")
    for key in table.keys:
        if key[len(PARAMS):] not in names:
            raise ParameterError(f"column `{key}`: not a parameter of model "
                                 f"'{ship.model.name}'", field="draws")
    check_units(table, {f"{PARAMS}{i.name}": i.unit for i in type(ship.params).info()})
    ships = []
    for i in range(n):
        values = {k[len(PARAMS):]: float(table.values[i, j]) for j, k in enumerate(table.keys)}
        try:
            ships.append(ship.replace(params=values, name=f"{ship.name} #{i}"))
        except ParameterError as exc:
            raise ParameterError(f"sample {i} (line {i + 1} after the header): {exc}",
                                 field="draws", run=i) from None
    return ships


def imo_of_samples(ship: Any, table: Any, *, n: int | None = None, dt: float | None = None,
                   progress: Callable[[int, int], None] | None = None,
                   source: str = "samples") -> ImoEnsemble:
    """The IMO check of the ships of a samples table's rows (:func:`ships_of_samples`).

    Parameters
    ----------
    ship : Ship
        The nominal ship (the reference of the members' durations).
    table : SamplesTable
        :func:`~seahelm.identification.samples_file.read_samples`.
    n : int, optional
        The first ``n`` rows (default: all).
    dt : float, optional
        Integration step [s].
    progress : callable(done, total), optional
        As :func:`imo_monte_carlo`'s.
    source : str, optional
        Where the table came from (its file), for the metadata and the title.

    Returns
    -------
    ImoEnsemble

    Raises
    ------
    ParameterError
        As :func:`ships_of_samples`.
    """
    from .probability import imo_probabilities
    from ...identification.samples_file import samples_attrs

    ships = ships_of_samples(ship, table, n)
    n = len(ships)
    probs = imo_probabilities(ships, dt=dt, reference=ship, progress=progress)
    attrs = samples_attrs(table)
    drawn = {k: (table.column(k)[:n].tolist(), attrs[k]) for k in table.keys}
    meta = {"ship": ship.name, "samples": n, "seed": None, "draws": source,
            "uncertainty": None}
    from pathlib import Path

    return ImoEnsemble(probs, drawn, meta,
                       f"IMO MSC.137(76): {ship.name}, {n} samples from {Path(source).name}")


def drawn_statistics(drawn: dict[str, Any]) -> list[dict[str, Any]]:
    """Per drawn parameter (key path -> (values, attributes)): its name, distribution, unit
    and the mean, standard deviation, least and greatest of the values drawn.

    Parameters
    ----------
    drawn : dict
        :attr:`seahelm.analysis.imo.monte_carlo.ImoEnsemble.drawn`.

    Returns
    -------
    list of dict
    """
    import math

    import numpy as np

    rows = []
    for key, (values, attrs) in drawn.items():
        v = np.asarray(values, dtype=float)
        v = v[np.isfinite(v)]
        rows.append({"parameter": key, "distribution": str(attrs.get("distribution", "")),
                     "units": str(attrs.get("units", "") or "-"),
                     **{name: (float(f(v)) if v.size else math.nan) for name, f in (
                         ("mean", np.mean), ("std", lambda x: np.std(x, ddof=1) if x.size > 1
                                             else 0.0), ("min", np.min), ("max", np.max))}})
    return rows
