"""A ``[maneuver]`` scenario: a standard manoeuvre or the IMO check of a ship, from a file.

::

    title = "KVLCC2 L7: turning circles"
    [vessel]
    ship = "kvlcc2-l7"              # a ship with a steering gear: catalog name or ship file
    params = { ... }                # optional: overrides of the entry's parameters
    [actuator]
    params = { rate_limit_deg = 2.32 }   # optional: overrides of the entry's steering gear
    [maneuver]
    kind = "turning"                # turning | zigzag | pullout | spiral | imo | stopping
    rudder_deg = [20, 35]           # a list gives a batch dimension
    sides = "both"                  # both | starboard | port
    speed = 1.179                   # approach speed [m/s] (or rps = ... [1/s]); may be a list

The keys of each kind are :data:`~seahelm.scenario.schema.MANEUVER_KEYS` (angles in radians,
or in degrees with ``_deg``); they are the keyword arguments of
:func:`~seahelm.analysis.maneuvers.turning_circle`, :func:`~seahelm.analysis.maneuvers.zigzag`
(``heading``: the heading trigger, default equal to the rudder angle),
:func:`~seahelm.analysis.maneuvers.pull_out`, :func:`~seahelm.analysis.maneuvers.spirals`
(``max_rudder``, ``hold``) and :func:`~seahelm.analysis.imo.check.imo_check`. Every run of a
manoeuvre is one compiled batch, as from the library or ``seahelm maneuver``.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..errors import ParameterError, ValidityRangeWarning
from ..analysis.imo.monte_carlo import SHARED_KEYS
from ..ships.water_depth import params_at_depth
from .errors import ScenarioError, at_key
from .particulars import PREFIX, EstimatedSamples, check_drawn_particulars
from .samples import drawn_kinds, samples_file
from .schema import Scenario

__all__ = ["ManeuverJob", "prepare_maneuver"]

_SIDES = {"both": (1, -1), "starboard": 1, "port": -1}


@dataclasses.dataclass(frozen=True, eq=False)
class ManeuverJob:
    """A manoeuvre a scenario describes, ready to run (:meth:`run`).

    Attributes
    ----------
    kind : str
        ``turning``, ``zigzag``, ``pullout``, ``spiral``, ``imo`` or ``stopping``.
    ship : Ship
        The ship with its steering gear (with the scenario's overrides).
    options : mapping
        Keyword arguments of the manoeuvre's function (SI units, radians).
    metadata : mapping
        ``title``, ``scenario_source`` and ``scenario_text``, stored with the results.
    """

    kind: str
    ship: Any
    options: Mapping[str, Any]
    metadata: Mapping[str, str]
    #: option -> the key the scenario wrote it as (``rudder`` -> ``rudder_deg``)
    written: Mapping[str, str] = dataclasses.field(default_factory=dict)
    #: ``[batch.monte_carlo]``: uncertain ship (``vessel.params.*``) and steering-gear
    #: (``actuator.params.*``) parameters, one ship per sample (a ``ship`` dimension)
    monte_carlo: Any = None
    #: drawn ``vessel.particulars.*``: the samples' estimated ships
    #: (:class:`~seahelm.scenario.particulars.EstimatedSamples`), and the scenario's own
    #: ``vessel.params`` and ``actuator.params`` overrides applied to each
    estimated: Any = None
    overrides: tuple[Mapping[str, float], Mapping[str, float]] = ({}, {})

    @property
    def n_samples(self) -> int:
        """Monte-Carlo samples (1 without ``[batch.monte_carlo]``)."""
        return 1 if self.monte_carlo is None else int(self.monte_carlo.runs)

    def draws(self, indices: Any) -> dict[str, np.ndarray]:
        """The drawn values of the samples ``indices`` (by key path; empty without draws).

        Parameters
        ----------
        indices : array_like of int
            Sample indices.

        Returns
        -------
        dict of str to ndarray
        """
        if self.monte_carlo is None:
            return {}
        from .runs import monte_carlo_draws

        source = str(self.metadata.get("scenario_source", "<string>"))
        idx = np.asarray(indices, dtype=np.int64)
        # every sample's draws, once drawn (a sweep's template draws them all, then each
        # chunk its range): a range of them is a slice, the same values
        every = self.__dict__.get("_every_draw")
        if every is not None and idx.size and idx.min() >= 0 and idx.max() < self.n_samples:
            return {k: v[idx] for k, v in every.items()}
        drawn = monte_carlo_draws(self.monte_carlo, idx, source)
        if idx.size == self.n_samples and (idx == np.arange(idx.size)).all():
            object.__setattr__(self, "_every_draw", {k: v.copy() for k, v in drawn.items()})
        return drawn

    def ships(self, start: int = 0, stop: int | None = None) -> list[Any]:
        """The ships of samples ``start:stop``: the scenario's ship with each sample's drawn
        parameters (its own steady approach is computed when it runs); with drawn particulars,
        the ship estimated from each sample's particulars, with the scenario's and the
        sample's parameters.

        Parameters
        ----------
        start, stop : int, optional
            Sample range (default: all samples).

        Returns
        -------
        list of Ship

        Raises
        ------
        ScenarioError
            When a drawn value is out of its parameter's range (naming the key and sample).
        """
        from ..analysis.maneuvers import maneuver_ship

        stop = self.n_samples if stop is None else stop
        if self.monte_carlo is None:
            return [self.ship][start:stop]
        drawn = self.draws(np.arange(start, stop))
        source = str(self.metadata.get("scenario_source", "<string>"))
        estimated = (None if self.estimated is None
                     else self.estimated.ships(drawn, range(start, stop)))
        if estimated is None and stop > start:
            fast = self._sample_ships(drawn, start, stop)
            if fast is not None:
                return fast
        out = []
        for n, i in enumerate(range(start, stop)):
            base = self.ship if estimated is None else estimated[n]
            fixed = ({}, {}) if estimated is None else self.overrides
            vessel = {**fixed[0], **{k[len("vessel.params."):]: float(v[n])
                                     for k, v in drawn.items() if k.startswith("vessel.params.")}}
            servo = {**fixed[1], **{k[len("actuator.params."):]: float(v[n])
                                    for k, v in drawn.items() if k.startswith("actuator.params.")}}
            try:
                deep = base.deep_water_params or base.params
                params = params_at_depth(base, type(deep).from_mapping(vessel, base=deep))
                gear = (type(base.servo).from_mapping(servo, base=base.servo) if servo
                        else base.servo)  # (frozen: shared when nothing is drawn)
            except (ParameterError, TypeError) as exc:
                raise ScenarioError(f"{source}: [batch.monte_carlo] sample {i}: {exc}") from None
            out.append(maneuver_ship(params, servo=gear, model=base.model,
                                     name=f"{self.ship.name} #{i}"))
        return out

    def _sample_ships(self, drawn: Mapping[str, np.ndarray], start: int,
                      stop: int) -> list[Any] | None:
        """:meth:`ships` of the scenario's own ship in deep water, built in one batch
        (:meth:`~seahelm.parameters.Params.replace_many`,
        :func:`~seahelm.analysis.maneuvers.ships.sample_ships`): the same ships. None when
        the batch does not apply (a ship in shallow water, a ``_deg`` or vector key, a value
        out of range: the sample-by-sample path then builds them or names the bad sample)."""
        from ..analysis.maneuvers.ships import sample_ships

        base = self.ship
        if base.in_shallow_water:
            return None
        vessel = {k[len("vessel.params."):]: v for k, v in drawn.items()
                  if k.startswith("vessel.params.")}
        servo = {k[len("actuator.params."):]: v for k, v in drawn.items()
                 if k.startswith("actuator.params.")}
        if len(vessel) + len(servo) != len(drawn):  # pragma: no cover - keys checked before
            return None
        deep = base.deep_water_params or base.params
        params = deep.replace_many(vessel) if vessel else [deep] * (stop - start)
        servos = base.servo.replace_many(servo) if servo else None
        if params is None or (servo and servos is None):
            return None
        names = [f"{self.ship.name} #{i}" for i in range(start, stop)]
        return sample_ships(base, params, servos, names)

    def run_ships(self, ships: list[Any]) -> Any:
        """Run the manoeuvre for the given ships (one batch, a ``ship`` dimension).

        Parameters
        ----------
        ships : list of Ship
            E.g. :meth:`ships` of a range of samples.

        Returns
        -------
        ManeuverResult
        """
        return dataclasses.replace(self, ship=ships, monte_carlo=None, estimated=None).run()

    @property
    def title(self) -> str:
        return str(self.metadata.get("title") or "")

    def run(self) -> Any:
        """Run the manoeuvre.

        Returns
        -------
        ManeuverResult, (ManeuverResult, ManeuverResult), ImoReport or ImoProbabilities
            A :class:`~seahelm.analysis.maneuvers.ManeuverResult` for ``turning``, ``zigzag``,
            ``pullout`` and ``stopping`` (:func:`~seahelm.analysis.maneuvers.crash_stop`); the
            direct and reverse spirals for ``spiral``; an
            :class:`~seahelm.analysis.imo.check.ImoReport` for ``imo``, and for ``imo`` with
            ``[batch.monte_carlo]`` the pass probabilities of the samples' ships
            (:func:`~seahelm.analysis.imo.probability.imo_probabilities`, the scenario's ship
            as the reference of the manoeuvres' durations). The scenario's metadata is in the
            attributes of every metrics Dataset.

        Raises
        ------
        ScenarioError
            When the manoeuvre rejects a value (naming the scenario file and the key).
        """
        from ..analysis import maneuvers
        from ..analysis.equilibria.equilibrium import EquilibriumError
        from ..analysis.imo.check import imo_check

        functions = {"turning": maneuvers.turning_circle, "zigzag": maneuvers.zigzag,
                     "pullout": maneuvers.pull_out, "spiral": maneuvers.spirals,
                     "imo": imo_check, "stopping": maneuvers.crash_stop}
        ship = self.ships() if self.monte_carlo is not None else self.ship
        try:
            if self.kind == "imo" and self.monte_carlo is not None:
                return self.imo_probabilities(ship)
            out = functions[self.kind](ship, **self.options)
        except ScenarioError:
            raise
        except (ParameterError, EquilibriumError) as exc:
            raise self._error(exc) from exc
        for result in _results(out):
            result.metrics.attrs.update(self.metadata)
        return out

    def imo_probabilities(self, ships: list[Any]) -> Any:
        """The IMO pass probabilities of ``ships`` (samples of an ``imo`` scenario's ship).

        Parameters
        ----------
        ships : list of Ship
            E.g. :meth:`ships` of a range of samples.

        Returns
        -------
        ImoProbabilities
            With every member's values (:func:`~seahelm.analysis.imo.probability.
            imo_probabilities`, the scenario's ship as the reference).
        """
        from ..analysis.imo.probability import imo_probabilities

        return imo_probabilities(ships, dt=self.options.get("dt"), reference=self.ship)

    def draw_attrs(self) -> dict[str, dict[str, str]]:
        """The attributes of each drawn key: its ``distribution`` and ``units`` (if any).

        Returns
        -------
        dict of str to dict
            Empty without ``[batch.monte_carlo]``.
        """
        mc = self.monte_carlo
        if mc is None:
            return {}
        kinds = drawn_kinds(mc, str(self.metadata.get("scenario_source", "<string>")))
        return {key: {"distribution": kind, **_units(self, key)} for key, kind in kinds.items()}

    def _error(self, exc: Exception) -> ScenarioError:
        source = str(self.metadata.get("scenario_source", "<string>"))
        message = str(exc)
        name = (getattr(exc, "field", None) or "").partition(".")[0].partition("[")[0]
        if name in self.options:  # the error's field names the option: the key from it
            written = self.written.get(name, name)
            if written != name:  # the user wrote degrees: say it in degrees too
                value = self.options[name]
                deg = ", ".join(f"{math.degrees(v):g}" for v in np.atleast_1d(value))
                message += f" (as written: {written} = {deg} deg)"
            return at_key(source, f"maneuver.{written}", message)
        return ScenarioError(f"{source}: [maneuver] {message}")


def _results(out: Any) -> list[Any]:
    if isinstance(out, tuple):
        return list(out)
    if hasattr(out, "turning") and hasattr(out, "zigzag"):  # an ImoReport
        return [out.turning, out.zigzag] + ([out.stopping] if out.stopping is not None else [])
    return [out]


def _units(job: ManeuverJob, key: str) -> dict[str, str]:
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


def _angle(section: Any, name: str) -> Any:
    """The value of ``name`` [rad], given as ``name`` or ``name_deg`` (None if neither)."""
    value = getattr(section, name)
    if value is None:
        deg = getattr(section, f"{name}_deg")
        if deg is None:
            return None
        return [math.radians(v) for v in deg] if isinstance(deg, list) else math.radians(deg)
    return value


def prepare_maneuver(scn: Scenario, *, source: str = "<string>", text: str = "") -> ManeuverJob:
    """The manoeuvre of a validated ``[maneuver]`` scenario; nothing runs.

    Parameters
    ----------
    scn : Scenario
        Validated scenario schema with a ``maneuver`` section.
    source : str, optional
        Name of the source used in error messages (default "<string>").
    text : str, optional
        Scenario text, stored with the results (default "").

    Returns
    -------
    ManeuverJob

    Raises
    ------
    ScenarioError
        Naming the source, the key path, the value and what was expected: a vessel that is
        not a ship with a steering gear, a model other than the ship's, an unknown or
        out-of-range parameter, initial states (a manoeuvre starts from its steady approach),
        an actuator other than the rudder servo.
    """
    from ..analysis.maneuvers import maneuver_ship
    from ..ships import with_steering_gear
    from .vessel import ship_key, vessel_ship

    man = scn.maneuver
    assert man is not None
    vessel = scn.vessel
    mc = scn.batch.monte_carlo
    drawn_keys = list(drawn_kinds(mc, source))
    varied = check_drawn_particulars(scn, drawn_keys, source)
    with warnings.catch_warnings():
        if varied:  # (the samples' ships are estimated and their warnings said when they run)
            warnings.simplefilter("ignore", ValidityRangeWarning)
        entry = vessel_ship(scn, source)
    key = ship_key(scn)
    if entry is None or entry.steering_gear is None:
        got = "none" if entry is None else repr(entry.name) + " (it has no [steering_gear])"
        raise at_key(source, key,
                     "a manoeuvre needs a ship with a steering gear: a catalog ship "
                     f"({', '.join(with_steering_gear())}) or a ship file with a "
                     f"[steering_gear], got {got}")
    if vessel.model is not None and vessel.model != entry.model.name:
        raise at_key(source, "vessel.model",
                     f"'{entry.name}' is a ship of model '{entry.model.name}', not "
                     f"'{vessel.model}'")
    if vessel.initial:
        raise at_key(source, "vessel.initial",
                     "a manoeuvre starts from its steady straight approach (set `speed` or "
                     f"`rps` in [maneuver]), got {dict(vessel.initial)}")
    if scn.actuator.model != entry.steering_gear.actuator.name:
        raise at_key(source, "actuator.model",
                     "a manoeuvre steers with the ship's steering gear, the "
                     f"'{entry.steering_gear.actuator.name}' (its params may be overridden), "
                     f"got {scn.actuator.model!r}")
    try:  # checked here (on a ship in shallow water: the deep-water values, as in its file)
        deep = entry.deep_water_params or entry.params
        params_at_depth(entry, type(deep).from_mapping(dict(vessel.params), base=deep))
    except (ParameterError, TypeError) as exc:
        raise at_key(source, "vessel.params", str(exc)) from None
    servo0 = entry.steering_gear.params
    try:
        servo = type(servo0).from_mapping(dict(scn.actuator.params), base=servo0)
    except (ParameterError, TypeError) as exc:
        raise at_key(source, "actuator.params", str(exc)) from None
    name = entry.name
    if vessel.params:
        name += f" (modified: {', '.join(vessel.params)})"
    try:
        ship = maneuver_ship(entry.replace(params=dict(vessel.params), name=name)
                             if vessel.params else entry,
                             servo=None if not scn.actuator.params else servo)
    except ParameterError as exc:  # (a ship whose model cannot run the manoeuvres)
        raise at_key(source, key, exc.reason.lstrip(": ")) from None

    options: dict[str, Any] = {}
    for key in ("speed", "rps", "t_final", "dt", "record_dt", "hold", "order", "dead_fraction"):
        value = getattr(man, key)
        if value is not None:
            options[key] = value
    written: dict[str, str] = {}
    for key in ("rudder", "heading", "max_rudder"):
        value = _angle(man, key)
        if value is not None:
            options[key] = value
            written[key] = key if getattr(man, key) is not None else f"{key}_deg"
    if man.sides is not None:
        options["sides"] = _SIDES[man.sides]
    conditions = _conditions(scn, ship.model, source)
    if conditions is not None:
        options["conditions"] = conditions
    metadata = {"title": scn.title, "scenario_source": source, "scenario_text": text}
    if mc is not None:
        if man.kind not in ("turning", "zigzag", "pullout", "imo"):
            raise at_key(source, "batch.monte_carlo",
                         f"Monte-Carlo samples of ships run turning, zigzag, pullout and imo "
                         f"manoeuvres, not '{man.kind}'")
        if man.kind == "imo":
            _check_imo_ensemble(man, drawn_keys, source)
        for key in drawn_keys:
            if not key.startswith(("vessel.params.", "actuator.params.", PREFIX)):
                raise at_key(source, f"batch.monte_carlo.{key}",
                             "a manoeuvre's draws vary the ship's parameters "
                             "(vessel.params.<name>), its steering gear's "
                             "(actuator.params.<name>) or the particulars it is estimated from "
                             f"(vessel.particulars.<name>), got '{key}'")
        if mc.samples is not None:  # a samples file holds stored units: say so if it does not
            from ..identification.samples_file import check_units

            units = {f"vessel.params.{i.name}": i.unit for i in type(ship.params).info()}
            units.update({f"actuator.params.{i.name}": i.unit
                          for i in type(ship.servo).info()})
            try:
                check_units(samples_file(mc, source), units)
            except ParameterError as exc:
                raise at_key(source, "batch.monte_carlo.samples", str(exc)) from None
    estimated = None if not varied else EstimatedSamples(
        particulars=dict(vessel.particulars or {}), water_depth=vessel.water_depth,
        source=source)
    job = ManeuverJob(kind=man.kind, ship=ship, options=options, metadata=metadata,
                      written=written, monte_carlo=mc, estimated=estimated,
                      overrides=(dict(vessel.params), dict(scn.actuator.params)))
    if mc is not None:
        with warnings.catch_warnings():  # (said when the samples run)
            warnings.simplefilter("ignore", ValidityRangeWarning)
            job.ships(0, 1)  # the names and ranges of the drawn parameters, checked once
    return job


def _check_imo_ensemble(man: Any, drawn_keys: list[str], source: str) -> None:
    """An ``imo`` scenario with ``[batch.monte_carlo]``: every sample at its ship's test speed,
    no draw of what the members share (:data:`SHARED_KEYS`)."""
    for key in ("speed", "rps"):
        if getattr(man, key) is not None:
            raise at_key(source, f"maneuver.{key}",
                         "the IMO check of Monte-Carlo samples runs every sample at the ship's "
                         "test speed (its approach_speed): drop `speed`/`rps`")
    for key in drawn_keys:
        if key in SHARED_KEYS:
            raise at_key(source, f"batch.monte_carlo.{key}",
                         "the samples of an IMO check share the ship's length, test speed and "
                         "steering-gear limit (its criteria are in ship lengths and L/V, at "
                         "the hard-over rudder): draw its other parameters")


def _conditions(scn: Scenario, model: Any, source: str) -> Any:
    """``[environment]`` of a manoeuvre as :class:`~seahelm.environment.loads.Conditions`:
    wind, regular waves and a uniform current (None in calm water)."""
    from ..environment.loads import Conditions
    from .environment import environment_runs

    env = scn.environment
    if "environment" not in scn.model_fields_set:
        return None
    if scn.maneuver is not None and scn.maneuver.kind in ("spiral", "imo"):
        raise at_key(source, "environment",
                     f"a '{scn.maneuver.kind}' manoeuvre is a calm-water test (IMO MSC.137(76)); "
                     "wind, waves and current act on turning, zigzag and pullout manoeuvres")
    if env.disturbance:
        raise at_key(source, "environment.disturbance",
                     "a manoeuvre takes wind, waves and current ([environment.wind], "
                     "[environment.waves], [environment.current]), not disturbance signals")
    if env.waves is not None and env.waves.irregular:
        raise at_key(source, "environment.waves.irregular",
                     "irregular waves need a [simulation] scenario (a realisation per run); a "
                     "manoeuvre takes regular waves")
    if env.wind is not None and env.wind.gust is not None:
        raise at_key(source, "environment.wind.gust",
                     "gusts need a [simulation] scenario; a manoeuvre takes a steady wind")
    runs = environment_runs(scn, model, [{}], source)
    kwargs: dict[str, Any] = {}
    if runs is not None:
        kwargs.update(environment=runs.environment,
                      params=runs.environment.params_type.from_array(runs.params[0]))
    if env.current is not None:
        if not {"current_north", "current_east"} <= set(model.disturbance_labels):
            raise at_key(source, "environment.current",
                         f"model '{model.name}' has no current channels")
        if isinstance(env.current.speed, dict):
            raise at_key(source, "environment.current.speed",
                         "a manoeuvre takes a steady current (a number [m/s]); a profile in "
                         "time needs a [simulation] scenario")
        kwargs.update(current_speed=env.current.speed,
                      current_direction=math.radians(env.current.direction_deg))
    return Conditions(**kwargs) if kwargs else None
