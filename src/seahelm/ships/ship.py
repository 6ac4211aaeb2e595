"""A ship as one object: its manoeuvring model and parameters, steering gear, propulsion, main
particulars, test speed, and where every number comes from.

A :class:`Ship` is what a user means by "the KVLCC2" or "my ship": everything seahelm needs to
simulate it, check it against the IMO criteria or put wind and waves on it. The catalog
(:mod:`seahelm.ships.catalog`) is a registry of ships, and a ship file
(:mod:`seahelm.ships.files`) is the same object on disk, so a user's own ship goes wherever a
catalog ship goes.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..control.thruster_layout import ThrusterLayout
from ..errors import ParameterError
from ..parameters import Params
from ..vessels.particulars import Particulars

if TYPE_CHECKING:  # (the registry imports them when a ship is made: listing ships needs no numba)
    from ..actuators.base import Actuator
    from ..vessels.base import VesselModel

__all__ = ["Ship", "SteeringGear", "Propulsion", "SPEED_FIELDS"]

#: Parameter fields that hold a model's design (test) speed, in the order they are looked for:
#: the MMG model's approach speed, the Mariner's nominal speed U_0, the Nomoto and Voitkunsky
#: models' speed U.
SPEED_FIELDS: tuple[str, ...] = ("approach_speed", "nominal_speed", "speed")


@dataclasses.dataclass(frozen=True, kw_only=True)
class SteeringGear:
    """The steering gear: an actuator (by registry name or object) and its parameters.

    Attributes
    ----------
    actuator : Actuator
        The actuator (``seahelm models`` lists them; a name is looked up on construction).
    params : Params
        Its parameters (for ``rudder-servo``: angle limit [rad], rate limit [rad/s], lag [s]).
    provenance : str
        Where the numbers come from.
    """

    actuator: Actuator
    params: Params
    provenance: str = ""

    def __post_init__(self) -> None:
        from ..registry import get_actuator

        try:
            actuator = get_actuator(self.actuator)
        except ValueError as exc:
            raise ParameterError(str(exc), field="actuator") from None
        object.__setattr__(self, "actuator", actuator)
        if not isinstance(self.params, actuator.params_type):
            raise ParameterError(
                f"actuator '{actuator.name}' takes {actuator.params_type.__name__}, got "
                f"{type(self.params).__name__}", field="params")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Propulsion:
    """What drives the ship, as far as the manoeuvring model represents it.

    Attributes
    ----------
    kind : str
        In words, e.g. ``"single fixed-pitch propeller"``.
    inputs : tuple of str
        The model inputs it is commanded through (e.g. ``("propeller_rps",)``); empty when the
        model holds the propulsion constant (a speed-perturbation model).
    provenance : str
        Where the description and its coefficients come from.
    """

    kind: str
    inputs: tuple[str, ...] = ()
    provenance: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.kind, str) or not self.kind.strip():
            raise ParameterError(f"must be a non-empty text, got {self.kind!r}", field="kind")
        object.__setattr__(self, "inputs", tuple(self.inputs))


#: How far a ship's particulars may be from its parameters' length, beam and draft (relative):
#: 5 % takes a mean draft beside the draft amidships (the KVLCC2 L7's 0.455 and 0.46 m are 1.1 %
#: apart) and refuses a unit or a digit wrong (a length of 70 m against 7 m).
PARTICULARS_AGREE = 0.05


@dataclasses.dataclass(frozen=True, kw_only=True)
class Ship:
    """A ship: manoeuvring model and parameters, steering gear, propulsion, particulars.

    Frozen and validated on construction; change one with :meth:`replace`. Two ships are equal
    when every field is (the model by identity).

    Attributes
    ----------
    name : str
        Label in results and tables (the catalog name for a catalog ship).
    model : VesselModel
        The manoeuvring model (``seahelm models`` lists them; a registry name is looked up on
        construction).
    params : Params
        Its parameter set (SI units, radians), of ``model.params_type``.
    description : str
        One line: what ship this is.
    steering_gear : SteeringGear or None
        The steering gear, where the ship has one that seahelm knows (manoeuvres and the IMO
        check need it).
    propulsion : Propulsion or None
        What drives the ship, where the model represents it.
    particulars : Particulars or None
        Main dimensions (L, B, T, C_b, displacement, …) and windage, with units.
    test_speed : float or None
        Approach (test) speed U_0 [m/s]. Default: the parameter set's design speed
        (:data:`SPEED_FIELDS`); given together with one, the two must agree.
    provenance : str
        Where the parameter set comes from.
    coefficient_sources : tuple of (str, str)
        Per-coefficient sources where they differ from ``provenance`` (a formula, a paper, a
        fit with its standard error), as ``(parameter name, source)`` pairs.
    validity : tuple of str
        What the parameter set is valid for (speed range, water depth, loading, …), one note a
        line.
    water_depth : float
        Water depth h [m] the parameters hold at; ``inf`` (the default) is deep water. A ship
        in shallow water is made by :meth:`at_depth`, which keeps the deep-water parameters.
    deep_water_params : Params or None
        The deep-water parameters a shallow-water ship was corrected from (``None`` in deep
        water).
    thrusters : ThrusterLayout or None
        The thrusters in the horizontal plane (a ship file's ``[[thrusters]]``), for dynamic
        positioning (:mod:`seahelm.control.thruster_layout`); None: none declared.
    thruster_provenance : str
        Where the thruster layout comes from.
    """

    name: str
    model: VesselModel
    params: Params
    description: str = ""
    steering_gear: SteeringGear | None = None
    propulsion: Propulsion | None = None
    particulars: Particulars | None = None
    test_speed: float | None = None
    provenance: str = ""
    coefficient_sources: tuple[tuple[str, str], ...] = ()
    validity: tuple[str, ...] = ()
    water_depth: float = math.inf
    deep_water_params: Params | None = None
    thrusters: ThrusterLayout | None = None
    thruster_provenance: str = ""

    def __post_init__(self) -> None:
        from ..registry import get_model

        if not isinstance(self.name, str) or not self.name.strip():
            raise ParameterError(f"must be a non-empty text, got {self.name!r}", field="name")
        if not self.name.isprintable():  # (it labels files, tables and terminals)
            raise ParameterError(f"must be printable text (no control characters), got "
                                 f"{self.name!r}", field="name")
        try:
            model = get_model(self.model)
        except ValueError as exc:
            raise ParameterError(str(exc), field="model") from None
        object.__setattr__(self, "model", model)
        if not isinstance(self.params, model.params_type):
            raise ParameterError(
                f"model '{model.name}' takes {model.params_type.__name__}, got "
                f"{type(self.params).__name__}", field="params")
        for attr, cls in (("steering_gear", SteeringGear), ("propulsion", Propulsion),
                          ("particulars", Particulars), ("thrusters", ThrusterLayout)):
            value = getattr(self, attr)
            if value is not None and not isinstance(value, cls):
                raise ParameterError(f"must be {cls.__name__} or None, got "
                                     f"{type(value).__name__}", field=attr)
        gear = self.steering_gear
        if gear is not None and not set(gear.actuator.output_labels) & set(model.input_labels):
            raise ParameterError(
                f": the actuator '{gear.actuator.name}' drives "
                f"{', '.join(gear.actuator.output_labels)}, which model '{model.name}' takes "
                f"no input of (its inputs: {', '.join(model.input_labels)})",
                field="steering_gear.actuator")
        vessel_type = None if self.particulars is None else self.particulars.vessel_type
        if vessel_type is not None:
            from ..environment.blendermann import BLENDERMANN_VESSEL_TYPES

            if vessel_type not in BLENDERMANN_VESSEL_TYPES:
                raise ParameterError(
                    f"'{vessel_type}' is not one of Blendermann's vessel types: "
                    f"{', '.join(sorted(BLENDERMANN_VESSEL_TYPES))}",
                    field="particulars.vessel_type", value=vessel_type)
        if self.particulars is not None:  # one ship has one length, beam and draft
            given = set(self.params.field_names())
            for dim in ("length", "beam", "draft"):
                mine = getattr(self.particulars, dim, None)
                theirs = getattr(self.params, dim, None) if dim in given else None
                if mine and theirs and abs(mine - theirs) > PARTICULARS_AGREE * max(mine,
                                                                                   theirs):
                    raise ParameterError(
                        f"= {mine!r} m, but the parameters' `{dim}` = {theirs!r} m (more than "
                        f"{PARTICULARS_AGREE:.0%} apart): one ship has one {dim}",
                        field=f"particulars.{dim}", unit="m", value=mine)
        if self.propulsion is not None:
            missing = [n for n in self.propulsion.inputs if n not in model.input_labels]
            if missing:
                raise ParameterError(
                    f"model '{model.name}' has no input {', '.join(map(repr, missing))}; its "
                    f"inputs: {', '.join(model.input_labels)}", field="propulsion.inputs")
        design = self.design_speed
        if design is not None and not (math.isfinite(design) and design > 0):
            # (a Nomoto ship at U = 0: its K and T hold at U only, and at rest the rudder
            # steers nothing; every manoeuvre then refused it as '`--speed` must be > 0')
            raise ParameterError(
                f"must be > 0 [m/s]: the ship's steering coefficients hold at this speed, "
                f"and at rest the rudder turns nothing, got {design!r}",
                field=f"params.{self._speed_field}", unit="m/s", value=design)
        if self.test_speed is None:
            object.__setattr__(self, "test_speed", design)
        else:
            if isinstance(self.test_speed, bool) or not isinstance(self.test_speed, (int, float)):
                raise ParameterError(f"must be a number [m/s], got {self.test_speed!r}",
                                     field="test_speed", unit="m/s", value=self.test_speed)
            speed = float(self.test_speed)
            if not (math.isfinite(speed) and speed > 0):
                raise ParameterError(f"must be > 0 [m/s], got {speed!r}", field="test_speed",
                                     unit="m/s", value=speed)
            if design is not None and speed != design:
                raise ParameterError(
                    f"is {speed!r} [m/s] but the parameter set's design speed "
                    f"`params.{self._speed_field}` is {design!r} [m/s]; give one of them",
                    field="test_speed", unit="m/s", value=speed)
            object.__setattr__(self, "test_speed", speed)
        sources = self.coefficient_sources
        if isinstance(sources, Mapping):
            sources = tuple(sources.items())
        sources = tuple((str(k), str(v)) for k, v in sources)
        unknown = [k for k, _ in sources if k not in self.params.field_names()]
        if unknown:
            raise ParameterError(
                f"names no parameter of {type(self.params).__name__}: "
                f"{', '.join(unknown)}", field="coefficient_sources")
        object.__setattr__(self, "coefficient_sources", sources)
        validity = (self.validity,) if isinstance(self.validity, str) else self.validity
        object.__setattr__(self, "validity", tuple(str(v) for v in validity))
        self._check_depth()

    def _check_depth(self) -> None:
        depth = self.water_depth
        if isinstance(depth, bool) or not isinstance(depth, (int, float)) or math.isnan(depth) \
                or not depth > 0:
            raise ParameterError(f"must be a number > 0 [m] (inf: deep water), got {depth!r}",
                                 field="water_depth", unit="m", value=depth)
        object.__setattr__(self, "water_depth", float(depth))
        draft = None if self.particulars is None else self.particulars.draft
        if draft is not None and not depth > draft:
            raise ParameterError(f"must be greater than the draft {round(draft, 12)!r} [m], "
                                 f"got {depth!r}",
                                 field="water_depth", unit="m", value=depth)
        deep = self.deep_water_params
        if math.isinf(depth) and deep is not None:
            raise ParameterError("is given but the ship is in deep water (water_depth = inf)",
                                 field="deep_water_params")
        if deep is not None and not isinstance(deep, type(self.params)):
            raise ParameterError(f"must be {type(self.params).__name__}, got "
                                 f"{type(deep).__name__}", field="deep_water_params")

    # -- derived -----------------------------------------------------------------------
    @property
    def _speed_field(self) -> str | None:
        names = self.params.field_names()
        return next((n for n in SPEED_FIELDS if n in names), None)

    @property
    def design_speed(self) -> float | None:
        """The parameter set's own design speed [m/s] (:data:`SPEED_FIELDS`), if it has one."""
        name = self._speed_field
        return None if name is None else float(getattr(self.params, name))

    @property
    def approach_speed(self) -> float:
        """Test speed U_0 [m/s] (NaN when the ship has none)."""
        return math.nan if self.test_speed is None else float(self.test_speed)

    @property
    def length(self) -> float:
        """Ship length L [m]: the parameter set's ``length``, else the particulars'."""
        if "length" in self.params.field_names():
            return float(self.params.length)
        if self.particulars is not None:
            return float(self.particulars.length)
        return math.nan

    @property
    def servo(self) -> Params:
        """The steering gear's parameters (ParameterError if the ship has no steering gear)."""
        if self.steering_gear is None:
            raise ParameterError(f"ship '{self.name}' has no steering gear", field="steering_gear")
        return self.steering_gear.params

    @property
    def max_rudder(self) -> float:
        """Steering-gear angle limit [rad]."""
        return float(self.servo.max_angle)

    @property
    def has_propeller(self) -> bool:
        """Whether the model has a ``propeller_rps`` input."""
        return "propeller_rps" in self.model.input_labels

    def source_of(self, parameter: str) -> str:
        """Where one coefficient comes from (its own source, else the parameter set's).

        Parameters
        ----------
        parameter : str
            A field of :attr:`params`.

        Returns
        -------
        str
        """
        if parameter not in self.params.field_names():
            raise ParameterError(f"unknown parameter `{parameter}` for "
                                 f"{type(self.params).__name__}")
        return dict(self.coefficient_sources).get(parameter, self.provenance)

    @property
    def in_shallow_water(self) -> bool:
        """Whether the ship's parameters hold at a finite water depth."""
        return not math.isinf(self.water_depth)

    def at_depth(self, depth: float, *, strict: bool | None = None) -> "Ship":
        """The ship in water of depth ``depth`` [m] (``inf``: deep water).

        The MMG coefficients are corrected from the deep-water ones by the shallow-water set of
        :mod:`seahelm.hydrodynamics.shallow_water` (hull: Taimuri et al. 2020; resistance R'_0:
        Lackenby 1963; needs the MMG model and the ship's particulars). Deep water gives the
        deep-water parameters back unchanged.

        Parameters
        ----------
        depth : float
            Water depth h [m], greater than the draft.
        strict : bool, optional
            Raise instead of warning below h/d = 1.2.

        Returns
        -------
        Ship
        """
        from .water_depth import ship_at_depth

        return ship_at_depth(self, depth, strict=strict)

    def scaled(self, length: float, *, rho: float | None = None,
               name: str | None = None) -> "Ship":
        """This ship Froude-scaled to another length, steering gear included
        (:func:`seahelm.ships.scaling.scale_ship`: λ = L_new/L_old; lengths × λ, times and
        speeds × √λ, rates / √λ, masses and forces × λ³, each parameter by its unit).

        Parameters
        ----------
        length : float
            New length L [m].
        rho : float, optional
            Water density of the scaled ship [kg/m³] (default: this ship's).
        name : str, optional
            Its name (default ``"<name>-L<length>"``).

        Returns
        -------
        Ship
        """
        from .scaling import scale_ship

        return scale_ship(self, length, rho=rho, name=name)

    def _summary(self) -> tuple[str, list[tuple[str, object]]]:
        from .._repr import names

        title = f"Ship {self.name!r}: {self.model.name} model"
        n_params = len(dataclasses.fields(self.params)) if dataclasses.is_dataclass(
            self.params) else "?"
        rows: list[tuple[str, object]] = []
        if self.description:
            rows.append(("description", self.description))
        rows.append(("parameters", f"{type(self.params).__name__}, {n_params} values "
                                   "(.params; source_of(name))"))
        gear = self.steering_gear
        if gear is None:
            rows.append(("steering gear", "—"))
        else:
            gp, bits = gear.params, [gear.actuator.name]
            if hasattr(gp, "max_angle"):
                bits.append(f"±{math.degrees(gp.max_angle):.4g}°")
            if hasattr(gp, "max_rate"):
                bits.append(f"{math.degrees(gp.max_rate):.4g}°/s")
            rows.append(("steering gear", ", ".join(bits)))
        rows.append(("propulsion", self.propulsion.kind if self.propulsion else "—"))
        p = self.particulars
        if p is not None:
            dims = [f"L {p.length:.4g} m", f"B {p.beam:.4g} m", f"T {p.draft:.4g} m"]
            if p.block_coefficient is not None:
                dims.append(f"C_b {p.block_coefficient:.4g}")
            rows.append(("particulars", ", ".join(dims)))
        if self.test_speed is not None:
            rows.append(("test speed", f"{self.test_speed:.4g} m/s"))
        rows.append(("water depth", "deep" if math.isinf(self.water_depth)
                     else f"{self.water_depth:g} m"))
        if self.provenance:
            rows.append(("provenance", self.provenance))
        if self.coefficient_sources:
            rows.append(("own sources", names([k for k, _ in self.coefficient_sources])))
        if self.validity:
            rows.append(("validity", "; ".join(self.validity)))
        return title, rows

    def __repr__(self) -> str:
        from .._repr import summary_text

        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        from .._repr import summary_html

        return summary_html(*self._summary())

    def replace(self, **changes: Any) -> "Ship":
        """A copy with some fields changed (validated again).

        ``params=`` may be a mapping of parameter changes (applied to this ship's parameters,
        ``<name>_deg`` for angles) instead of a whole parameter set; a changed parameter set
        drops the test speed taken from the old one. On a ship in shallow water, a parameter
        change is to the deep-water parameters, which are corrected for the depth again.
        """
        params = changes.get("params")
        if self.in_shallow_water and params is not None and "deep_water_params" not in changes:
            # in shallow water a change is to the deep-water parameters, corrected again
            deep = self.deep_water_params or self.params
            if isinstance(params, Mapping):
                params = type(deep).from_mapping(params, base=deep)
            depth = changes.pop("water_depth", self.water_depth)
            changes.pop("params")
            speed = None if self.design_speed is not None else self.test_speed
            shallow = dataclasses.replace(self, params=params, water_depth=math.inf,
                                          deep_water_params=None, test_speed=speed)
            return dataclasses.replace(shallow.at_depth(depth), **changes)
        if isinstance(params, Mapping):
            changes["params"] = type(self.params).from_mapping(params, base=self.params)
        if "params" in changes and "test_speed" not in changes and self.design_speed is not None:
            changes["test_speed"] = None
        return dataclasses.replace(self, **changes)
