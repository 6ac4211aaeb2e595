"""The structure of a scenario file (pydantic): sections, keys, types and simple ranges.

Numbers are strict: a TOML boolean or string where a number belongs is an error (``kp = true``
is not 1.0, ``t_final = "60"`` is not 60 s), as are ``inf`` and ``nan``. Names (models,
catalog entries, channels, parameters) are resolved by :mod:`.runs` and :mod:`.maneuver`,
which know the components.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import (
    AllowInfNan,
    BaseModel,
    ConfigDict,
    Field,
    Strict,
    StrictBool,
    field_validator,
    model_validator,
)

from .._validate import lookup_name
from ..simulation.integrators import INTEGRATORS

__all__ = ["Number", "VesselSection", "ActuatorSection", "ControllerSection",
           "EnvironmentSection", "CurrentSection",
           "WindSection", "WavesSection", "SimulationSection", "Distribution", "CorrelatedSection",
           "MonteCarloSection",
           "BatchSection", "ManeuverSection", "GuidanceSection", "Scenario", "MANEUVER_KEYS"]

#: A finite number: an integer or a float, never a boolean or a string.
Number = Annotated[float, Strict(), AllowInfNan(False)]
Positive = Annotated[float, Strict(), AllowInfNan(False), Field(gt=0)]
Count = Annotated[int, Strict(), Field(ge=1)]

SignalSpec = Number | dict[str, Any]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class VesselSection(_Strict):
    """``[vessel]``: a ship (``ship``: a catalog name or the path of a ship file, relative to
    the scenario file; ``catalog`` is its older name), a bare ``model``, or the ship's main
    ``particulars`` (``[vessel.particulars]``: the ship is estimated from them, an MMG ship as
    ``seahelm ship estimate`` makes; the keys are those of its particulars file, angles also in
    degrees with ``_deg``; in a ``[maneuver]`` scenario they may be drawn in
    ``[batch.monte_carlo]`` as ``vessel.particulars.<key>``, one estimated ship per sample).
    ``params`` override the ship's parameters (of an estimated ship: its estimated MMG
    coefficients), ``initial`` its initial state (the states not given are 0: without it the
    ship starts at rest, unlike a Python ``Problem(ship=...)`` without ``x0``, which starts on
    the ship's straight approach); ``water_depth`` [m] puts the ship in shallow
    water (its MMG coefficients corrected; ``params`` then change the deep-water ones)."""

    model: str | None = None  # the ship's model when a ship is named
    ship: str | None = None
    catalog: str | None = None
    particulars: dict[str, Number | str] | None = None
    water_depth: Positive | None = None
    params: dict[str, Number] = Field(default_factory=dict)
    initial: dict[str, Number] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _one_ship(self) -> "VesselSection":
        if self.ship is not None and self.catalog is not None:
            raise ValueError("give `ship` or `catalog` (its older name), not both")
        if self.particulars is not None:
            named = [k for k in ("ship", "catalog", "model") if getattr(self, k) is not None]
            if named:
                raise ValueError(
                    f"give `{named[0]}` or [vessel.particulars], not both: from its particulars "
                    "the ship is estimated (an MMG ship, as `seahelm ship estimate` makes; "
                    "write that ship file and name it in `ship` for another model)")
            if self.water_depth is not None and "water_depth" in self.particulars:
                raise ValueError("the water depth is given twice: as `water_depth` in [vessel] "
                                 "and in [vessel.particulars]; give it once")
        if (self.water_depth is not None and self.ship is None and self.catalog is None
                and self.particulars is None):
            raise ValueError("`water_depth` needs a `ship` or [vessel.particulars] (its "
                             "particulars and MMG coefficients are corrected)")
        return self


class ActuatorSection(_Strict):
    """``[actuator]``: the actuator between the controller and the model: the steering gear of
    the ship named in ``[vessel]`` (its actuator and parameters), else ``model`` (default the
    rudder servo); ``params`` override its parameters."""

    model: str = "rudder-servo"
    params: dict[str, Number] = Field(default_factory=dict)


class ControllerSection(_Strict):
    model: str = "open-loop"
    dt: Positive | None = None
    params: dict[str, Number] = Field(default_factory=dict)
    reference: dict[str, SignalSpec] = Field(default_factory=dict)


#: The fastest current a scenario may give [m/s]: the strongest tidal races run at about
#: 10 m/s (Saltstraumen, ~20 kn); a larger value is a unit mix-up (km/h, knots x 10, ...).
MAX_CURRENT = 15.0


class CurrentSection(_Strict):
    """``[environment.current]``: a uniform current, constant or with a speed profile in time.

    ``direction_deg`` is where the current sets to (flows towards), clockwise from north, in
    [0, 360) (the oceanographic convention; wind is given by where it comes from). ``speed``
    [m/s] is a number ≥ 0, or a signal table for a profile in time (e.g. a tidal
    ``{kind = "sine", ...}``; a negative value sets the other way). A current that changes in
    time is applied through the velocity relative to the water only: the inertia force of an
    accelerating current is left out."""

    speed: Annotated[Number, Field(ge=0, le=MAX_CURRENT)] | dict[str, Any]
    direction_deg: Annotated[Number, Field(ge=0, lt=360)]


class WindSection(_Strict):
    """``[environment.wind]``: the true wind and the load model (:mod:`seahelm.environment.loads`).

    ``direction_deg`` is where the wind comes **from**, clockwise from north, in [0, 360) (the
    meteorological convention). The ship's windage (areas, centre, length) defaults to the
    catalog ship's particulars (:mod:`seahelm.vessels.particulars`); ``vessel_type`` picks
    Blendermann's coefficients. ``gust`` is a signal [m/s] added to ``speed``."""

    model: str = "blendermann"
    speed: Annotated[Number, Field(ge=0)]
    direction_deg: Annotated[Number, Field(ge=0, lt=360)]
    gust: SignalSpec | None = None
    vessel_type: str | None = None
    frontal_area: Positive | None = None
    lateral_area: Positive | None = None
    centre: Number | None = None
    length_overall: Positive | None = None
    length: Positive | None = None
    rho_air: Positive | None = None


class WavesSection(_Strict):
    """``[environment.waves]``: waves and the load model (:mod:`seahelm.environment.loads`).

    The height is h3% (``height``) or the significant height (``hs``, converted with
    Hs = 4 √(0.143) h3%/2, the same variance); the wave length is ``length`` [m] or follows
    from ``period`` [s] (deep water, λ = g T²/2π). ``direction_deg``: where the waves come
    **from**, clockwise from north, in [0, 360). ``irregular = true`` modulates the mean loads
    by the envelope of a seeded sea of the ``spectrum`` (each run its own realisation); the
    hull's beam, draft and block coefficient default to the catalog ship's particulars. A
    height of 0 means no waves (zero loads, exactly). ``first_order_motions = true`` (with
    ``irregular = true``) adds the first-order heave, roll and pitch of the same sea to the
    result (:mod:`seahelm.scenario.first_order`): closed-form RAOs of the ship
    (``metacentric_height`` [m] for roll, else the particulars'), ``components`` per run,
    directional ``spreading`` (``"cos-2s"`` or ``"cos-n"`` with ``spreading_parameter``);
    ``rao_file`` (relative to the scenario file: a capytaine NetCDF, seahelm's RAO NetCDF or an
    RAO table) in place of the closed form; ``autopilot_sees_first_order = true`` evaluates
    them inside the loop and feeds the autopilot ψ + ψ₁, which needs a ``rao_file`` with yaw."""

    model: str = "lvov"
    height: Annotated[Number, Field(ge=0)] | None = None  # 0: no waves (an irregular sea: 1-10 m)
    hs: Annotated[Number, Field(ge=0)] | None = None
    length: Positive | None = None
    period: Positive | None = None
    direction_deg: Annotated[Number, Field(ge=0, lt=360)]
    irregular: bool = False
    spectrum: str = "rakhmanin-firsov-2"
    seed: Annotated[int, Strict(), Field(ge=0)] = 0
    a1: Annotated[Number, Field(ge=1, le=8.5)] | None = None
    hull_length: Positive | None = None
    beam: Positive | None = None
    draft: Positive | None = None
    block_coefficient: Annotated[Number, Field(gt=0, le=1)] | None = None
    first_order_motions: StrictBool = False
    metacentric_height: Positive | None = None
    # at most environment.first_order.MAX_COMPONENTS (10^11 was a MemoryError after the runs)
    components: Annotated[int, Strict(), Field(ge=1, le=100_000)] = 64
    spreading: Literal["cos-2s", "cos-n"] | None = None
    spreading_parameter: Positive = 2.0
    rao_file: str | None = None
    autopilot_sees_first_order: StrictBool = False

    @model_validator(mode="after")
    def _one_each(self) -> "WavesSection":
        if (self.height is None) == (self.hs is None):
            raise ValueError("give the wave height as `height` (h3%) [m] or `hs` "
                             "(significant) [m], one of them")
        if (self.length is None) == (self.period is None):
            raise ValueError("give the wave `length` [m] or the `period` [s], one of them")
        if "seed" in self.model_fields_set and not self.irregular:
            raise ValueError("`seed` draws an irregular sea: set `irregular = true` (regular "
                             "waves are not random)")
        extra = {"metacentric_height", "components", "spreading", "spreading_parameter",
                 "rao_file", "autopilot_sees_first_order"}
        if self.first_order_motions and not self.irregular:
            raise ValueError("`first_order_motions` are those of an irregular sea: set "
                             "`irregular = true`")
        if extra & self.model_fields_set and not self.first_order_motions:
            key = sorted(extra & self.model_fields_set)[0]
            raise ValueError(f"`{key}` belongs to the first-order motions: set "
                             "`first_order_motions = true`")
        return self


class EnvironmentSection(_Strict):
    """``[environment]``: disturbance channels, a current, wind and waves. ``loads`` says when
    the wind and wave loads are evaluated: at ``"every-stage"`` of the integrator (default:
    its order is kept) or ``"once-per-step"``, at the step's start and held over its stages
    (cheaper; the loads follow the state to first order within a step)."""

    loads: Literal["every-stage", "once-per-step"] = "every-stage"
    disturbance: dict[str, SignalSpec] = Field(default_factory=dict)
    current: CurrentSection | None = None
    wind: WindSection | None = None
    waves: WavesSection | None = None


class GuidanceSection(_Strict):
    """``[guidance]``: a waypoint route followed by LOS/ILOS (:mod:`seahelm.control.guided`)
    steering the heading controller, or by a controller that follows routes itself
    (``lq-cross-track``: then only ``waypoints`` and ``acceptance_radius``)."""

    law: str = "los"
    waypoints: list[tuple[Number, Number]]
    acceptance_radius: Positive | None = None
    lookahead: Positive | None = None
    lookahead_min: Annotated[Number, Field(ge=0)] | None = None
    lookahead_gamma: Annotated[Number, Field(ge=0)] | None = None
    kappa: Positive | None = None


class SimulationSection(_Strict):
    """``[simulation]``: duration and step [s], integrator, recording, state bounds, and
    ``exact_actuator`` (take the actuator's closed-form step, the default when it has one;
    ``false`` integrates it with the step, as before the closed form)."""

    t_final: Positive
    dt: Positive
    integrator: str = "rk4"
    record_every: Count = 1
    bounds: dict[str, tuple[Number, Number]] = Field(default_factory=dict)
    exact_actuator: StrictBool | None = None

    @field_validator("bounds")
    @classmethod
    def _ordered(cls, bounds: dict[str, tuple[float, float]]) -> dict[str, tuple[float, float]]:
        for key, (low, high) in bounds.items():
            if not low < high:
                raise ValueError(f"bounds of `{key}`: low {low!r} must be < high {high!r}")
        return bounds

    @field_validator("integrator")
    @classmethod
    def _known_integrator(cls, name: str) -> str:
        lookup_name("integrator", INTEGRATORS, name)
        return name


class Distribution(_Strict):
    """A drawn key of ``[batch.monte_carlo.draws]``: ``normal`` (mean, std), ``uniform``
    (low, high), ``lognormal`` (mean, std of the underlying normal) or ``truncnormal`` (mean,
    std, cut to [low, high]; one bound may be left out)."""

    distribution: Literal["normal", "uniform", "lognormal", "truncnormal"]
    mean: Number | None = None
    std: Annotated[Number, Field(ge=0)] | None = None
    low: Number | None = None
    high: Number | None = None

    @model_validator(mode="after")
    def _check(self) -> "Distribution":
        if self.distribution in ("normal", "lognormal", "truncnormal"):
            if self.mean is None or self.std is None:
                raise ValueError(f"a {self.distribution} draw needs `mean` and `std`")
        if self.distribution in ("normal", "lognormal"):
            if self.low is not None or self.high is not None:
                raise ValueError(f"a {self.distribution} draw takes `mean` and `std`, not "
                                 "`low`/`high`")
        if self.distribution == "truncnormal":
            if self.low is None and self.high is None:
                raise ValueError("a truncnormal draw needs `low` and/or `high` (a normal draw "
                                 "has neither)")
            if self.low is not None and self.high is not None and not self.high > self.low:
                raise ValueError("a truncnormal draw needs `low` < `high`")
            if not self.std > 0:  # type: ignore[operator]
                raise ValueError("a truncnormal draw needs `std` > 0")
        if self.distribution == "uniform":
            if self.low is None or self.high is None or not self.high > self.low:
                raise ValueError("a uniform draw needs `low` < `high`")
            if self.mean is not None or self.std is not None:
                raise ValueError("a uniform draw takes `low` and `high`, not `mean`/`std`")
        return self


class CorrelatedSection(_Strict):
    """``[[batch.monte_carlo.correlated]]``: keys drawn together from a normal distribution
    with the given ``mean`` (one per key) and ``covariance`` (one row per key; symmetric,
    positive definite; the keys' units squared)."""

    keys: Annotated[list[str], Field(min_length=1)]
    mean: list[Number]
    covariance: list[list[Number]]

    @model_validator(mode="after")
    def _check(self) -> "CorrelatedSection":
        from ..numerics.sampling import CorrelatedNormal

        if len(set(self.keys)) != len(self.keys):
            raise ValueError(f"`keys` repeat: {self.keys}")
        CorrelatedNormal(tuple(self.keys), self.mean, self.covariance)  # shapes, symmetry, PD
        return self


class MonteCarloSection(_Strict):
    """``[batch.monte_carlo]``: ``runs`` samples, each drawn from its own generator of
    ``seed`` (``[batch.monte_carlo.draws]``: key path = distribution;
    ``[[batch.monte_carlo.correlated]]``). A ``[simulation]`` draws any per-run key; a
    ``[maneuver]`` (turning, zigzag, pullout and imo) draws the ship's parameters
    (``vessel.params.<name>``), its steering gear's (``actuator.params.<name>``) or the
    particulars it is estimated from (``vessel.particulars.<name>``), one ship per sample. With
    ``kind = "imo"`` the samples give the probability of passing each IMO criterion and the
    whole check (Wilson intervals; samples whose manoeuvres do not complete are excluded and
    counted); they share the ship's length, test speed and steering-gear limit. ``samples =
    "FILE.csv"`` gives drawn values as numbers instead, sample i the file's row i (e.g. the
    posterior samples of ``seahelm identify mmg --save-posterior``; ``runs`` at most its
    rows)."""

    runs: Annotated[int, Strict(), Field(ge=1, le=1_000_000)]
    seed: Annotated[int, Strict(), Field(ge=0)]
    draws: dict[str, Distribution] = Field(default_factory=dict)
    correlated: list[CorrelatedSection] = Field(default_factory=list)
    #: a samples file (CSV, relative to the scenario file): sample i takes its row i
    #: (:mod:`seahelm.scenario.samples`)
    samples: Annotated[str, Field(min_length=1)] | None = None

    @model_validator(mode="after")
    def _once(self) -> "MonteCarloSection":
        keys = list(self.draws) + [k for block in self.correlated for k in block.keys]
        twice = sorted({k for k in keys if keys.count(k) > 1})
        if twice:
            raise ValueError(f"`{twice[0]}` is drawn twice (in `draws` and/or `correlated`)")
        return self


class BatchSection(_Strict):
    grid: dict[str, list[Number]] = Field(default_factory=dict)
    monte_carlo: MonteCarloSection | None = None

    @field_validator("grid")
    @classmethod
    def _distinct(cls, grid: dict[str, list[float]]) -> dict[str, list[float]]:
        for key, values in grid.items():
            seen = [v for i, v in enumerate(values) if v in values[:i]]
            if seen:
                raise ValueError(f"grid values of `{key}` repeat ({seen[0]!r}): a dimension's "
                                 "coordinates must be distinct")
        return grid


#: The keys each manoeuvre takes (angles also as ``<key>_deg``), besides ``kind``.
MANEUVER_KEYS: dict[str, tuple[str, ...]] = {
    "turning": ("rudder", "sides", "speed", "rps", "t_final", "dt", "record_dt"),
    "zigzag": ("rudder", "heading", "sides", "speed", "rps", "t_final", "dt", "record_dt"),
    "pullout": ("rudder", "sides", "speed", "rps", "t_final", "dt", "record_dt"),
    "spiral": ("max_rudder", "hold", "speed", "rps", "dt"),
    "imo": ("speed", "rps", "dt"),
    "stopping": ("order", "dead_fraction", "speed", "t_final", "dt", "record_dt"),
}
_ANGLES = ("rudder", "heading", "max_rudder")

Values = Number | Annotated[list[Number], Field(min_length=1)]


class ManeuverSection(_Strict):
    """``[maneuver]``: a standard manoeuvre of the vessel (see :mod:`.maneuver`)."""

    kind: Literal["turning", "zigzag", "pullout", "spiral", "imo", "stopping"]
    rudder: Values | None = None
    rudder_deg: Values | None = None
    heading: Values | None = None
    heading_deg: Values | None = None
    max_rudder: Number | None = None
    max_rudder_deg: Number | None = None
    sides: Literal["both", "starboard", "port"] | None = None
    speed: Values | None = None
    rps: Values | None = None
    t_final: Positive | None = None
    dt: Positive | None = None
    record_dt: Positive | None = None
    hold: Positive | None = None
    order: Values | None = None
    dead_fraction: Number | None = None

    @model_validator(mode="after")
    def _check(self) -> "ManeuverSection":
        allowed = MANEUVER_KEYS[self.kind]
        for key in self.model_fields_set - {"kind"}:
            base = key[:-4] if key.endswith("_deg") and key[:-4] in _ANGLES else key
            if base not in allowed:
                shown = ", ".join(f"{k} (or {k}_deg)" if k in _ANGLES else k for k in allowed)
                raise ValueError(f"`{key}` is not a key of a '{self.kind}' manoeuvre; its keys: "
                                 f"{shown}")
        for angle in _ANGLES:
            if {angle, f"{angle}_deg"} <= self.model_fields_set:
                raise ValueError(f"give `{angle}` [rad] or `{angle}_deg` [deg], not both")
        for key in ("rudder", "rudder_deg", "heading", "heading_deg", "max_rudder",
                    "max_rudder_deg"):
            value = getattr(self, key)
            for v in value if isinstance(value, list) else [value]:
                if v is not None and not v > 0:
                    unit = "deg" if key.endswith("_deg") else "rad"
                    raise ValueError(f"`{key}` must be > 0 [{unit}] (the side is `sides`), "
                                     f"got {v!r}")
        for key, unit in (("speed", "m/s"), ("rps", "1/s")):
            value = getattr(self, key)
            for v in value if isinstance(value, list) else [value]:
                if v is not None and not v > 0:
                    raise ValueError(f"`{key}` must be > 0 [{unit}], got {v!r}")
        if self.speed is not None and self.rps is not None:
            raise ValueError("give the approach `speed` [m/s] or the propeller `rps` [1/s], "
                             "not both")
        for v in self.order if isinstance(self.order, list) else [self.order]:
            if v is not None and not -1.0 <= v < 0.0:
                raise ValueError(f"`order` must be an astern engine order in [-1, 0) [-] (-1 "
                                 f"full astern), got {v!r}")
        if self.dead_fraction is not None and not 0.0 <= self.dead_fraction < 1.0:
            raise ValueError(f"`dead_fraction` must be in [0, 1) [-], got {self.dead_fraction!r}")
        return self


class SensorsSection(_Strict):
    """``[sensors]``: what the controller's ``north``, ``east`` and ``heading`` sensors see
    (:mod:`seahelm.simulation.sensor_stage`): seeded Gaussian noise of standard deviations
    ``noise_north``, ``noise_east`` [m] and ``noise_heading_deg`` [deg], and with
    ``wave_motion = true`` the first-order surge, sway and yaw of the sea evaluated in the
    loop (``[environment.waves]`` with ``autopilot_sees_first_order = true`` and a
    ``rao_file`` with those DOF); ``seed`` of the noise (run i: ``SeedSequence(seed,
    spawn_key=(i,))``)."""

    noise_north: Annotated[Number, Field(ge=0)] = 0.0
    noise_east: Annotated[Number, Field(ge=0)] = 0.0
    noise_heading_deg: Annotated[Number, Field(ge=0)] = 0.0
    wave_motion: StrictBool = False
    seed: Annotated[int, Strict(), Field(ge=0)] = 0


class Scenario(_Strict):
    """The validated structure of a scenario file: a simulation (``[simulation]``) or a
    standard manoeuvre (``[maneuver]``)."""

    title: str = ""
    description: str = ""
    vessel: VesselSection
    actuator: ActuatorSection = Field(default_factory=ActuatorSection)
    controller: ControllerSection = Field(default_factory=ControllerSection)
    environment: EnvironmentSection = Field(default_factory=EnvironmentSection)
    simulation: SimulationSection | None = None
    batch: BatchSection = Field(default_factory=BatchSection)
    maneuver: ManeuverSection | None = None
    guidance: GuidanceSection | None = None
    sensors: SensorsSection | None = None

    @model_validator(mode="after")
    def _simulation_or_maneuver(self) -> "Scenario":
        if self.maneuver is None and self.simulation is None:
            raise ValueError("a scenario needs a [simulation] section (t_final, dt, ...) or a "
                             "[maneuver] section (kind = turning, zigzag, pullout, spiral, "
                             "imo or stopping)")
        if self.maneuver is not None:
            extra = [s for s in ("simulation", "controller", "batch", "guidance")
                     if s in self.model_fields_set
                     and not (s == "batch" and not self.batch.grid)]
            if extra:
                raise ValueError(
                    f"a [maneuver] scenario takes no [{'], ['.join(extra)}] section: the "
                    "manoeuvre sets its own rudder orders, timing and batch (rudder angles, "
                    "speeds and sides as lists in [maneuver]; uncertain ship or steering-gear "
                    "parameters, or particulars, as [batch.monte_carlo]); [environment] may "
                    "give wind, waves and a current")
        varied = list(self.batch.grid) + ([] if self.batch.monte_carlo is None else [
            *self.batch.monte_carlo.draws,
            *(k for block in self.batch.monte_carlo.correlated for k in block.keys)])
        # the guidance law writes the controller's `heading` reference only; its other
        # reference channels (e.g. a thrust-heading controller's surge force) stay the user's
        referred = [f"controller.reference.{k}" for k in self.controller.reference] + [
            k for k in varied if k.startswith("controller.reference.")]
        referred = [k for k in referred
                    if k.removeprefix("controller.reference.").removesuffix("_deg") == "heading"]
        if self.guidance is not None and referred:
            keys = ", ".join(dict.fromkeys(referred))
            raise ValueError(
                f"[{keys}] and [guidance] both steer the ship: along a route the guidance law "
                f"'{self.guidance.law}' makes the controller's reference (the heading to "
                "steer) from the waypoints; drop "
                "[controller.reference] (and its [batch] keys), or [guidance] for a fixed "
                "reference")
        return self
