"""Wind and wave load models, as registries, and the environment component that uses them.

An :class:`Environment` is a component of the closed loop (like a vessel model, an actuator or a
controller): at every stage of every step the engine hands it the model's outputs (heading,
surge and sway speed through the water) and the run's disturbance inputs, and it writes the
loads of the wind and the waves onto the model's disturbance channels ``force_x`` [N],
``force_y`` [N] and ``moment_z`` [N·m] (added to what is given there), so the loads follow the
**live** heading and speed of each run. A uniform current is not a load: models that declare
``current_north``/``current_east`` channels take the velocity through the water for their
hydrodynamics and move with the current (:mod:`seahelm.vessels.mariner`, ``mmg``, ``nomoto``);
the environment reads those channels to form the wind relative to the moving ship.

Load models come from registries, by name or as objects (house style rule 4):

* :data:`WIND_LOADS` — ``"lvov"``: Lvov (2014) eq. (12) (lateral force and yaw moment only, no
  longitudinal force); ``"blendermann"``: Blendermann (1994), the coefficient model of
  :mod:`seahelm.environment.blendermann` (surge, sway, yaw) with the vessel-type tables;
  ``"fujiwara"``: Fujiwara, Ueno & Nimura (1998), the regression on the windage geometry of
  :mod:`seahelm.environment.fujiwara` (surge, sway, yaw);
* :data:`WAVE_LOADS` — ``"lvov"``: the mean (second-order) wave loads of Lvov (2014)
  eq. (8)-(10) with the coefficients of eq. (5)-(7).

Each takes the relative wind (speed [m/s], bearing it comes from relative to the bow [rad],
positive from starboard) or the relative wave bearing and the ship's speed along the waves,
and returns body-axis loads ``(X, Y, N)``: x forward, y to starboard, N positive turning the bow
to starboard (the negatives of the paper's leeward-positive Y, M for wind and waves from
starboard, see :mod:`seahelm.environment.wind` and :mod:`seahelm.environment.wave_forces`).

Irregular seas (stated simplification)
    Eq. (8)-(10) are mean loads in regular waves of height h3%. In an irregular sea the loads
    are taken as quasi-steady and proportional to the square of the wave-height envelope
    A(t): the mean loads times 1 + f(t), f = A²/E[A²] − 1 the ``wave_load_fluctuation``
    channel (zero mean), with A² = ζ² + (ζ̇/ω̄)², ω̄² = E[ζ̇²]/E[ζ²], ζ the sea elevation from
    the exact shaping filter of the spectrum (:func:`wave_load_fluctuation`). This is the
    slowly varying (envelope) part only: the first-order, wave-frequency forces, the
    encounter-frequency shift and memory effects of the drift force are left out.

Gusts
    ``wind_gust`` [m/s] is added to the true wind speed (zero when not given); any signal may
    drive it.

References
----------
Lvov, V. E. (2014), eq. (5)-(12). Blendermann, W. (1994). Parameter identification of wind
loads on ships. J. Wind Eng. Ind. Aerodyn. 51, 339-351.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import Any

import numpy as np
from numba import njit

from .._validate import as_float_array, check_on_hull, check_positive, lookup_name
from ..constants import GRAVITY, RHO_AIR, RHO_SEAWATER
from ..errors import ParameterError
from ..parameters import Params, as_records, param
from .blendermann import blendermann_loads_folded, get_blendermann_type
from .fujiwara import fujiwara_constants, fujiwara_wind_loads

__all__ = [
    "WindParams",
    "WaveParams",
    "LvovWindParams",
    "BlendermannWindParams",
    "FujiwaraWindParams",
    "LvovWaveParams",
    "LoadModel",
    "WIND_LOADS",
    "WAVE_LOADS",
    "get_wind_loads",
    "get_wave_loads",
    "Environment",
    "environment",
    "lvov_wave_params",
    "blendermann_wind_params",
    "wave_load_fluctuation",
    "ship_load_params",
    "Conditions",
]


# ------------------------------------------------------------------------------------------
# parameters: the weather, then each load model's ship data
# ------------------------------------------------------------------------------------------
_POSITIVE = dict(low=0.0, low_inclusive=False)


@dataclasses.dataclass(frozen=True, kw_only=True)
class WindParams(Params):
    """The true wind: speed and the direction it comes from."""

    wind_speed: float = param(0.0, unit="m/s", symbol="W", low=0.0,
                              doc="true wind speed (gusts: the `wind_gust` channel)")
    wind_direction: float = param(0.0, unit="rad", symbol="θ_w", low=-2.0 * math.pi,
                                  high=2.0 * math.pi,
                                  doc="direction the wind comes from, clockwise from north")
    rho_air: float = param(RHO_AIR, unit="kg/m³", symbol="ρ_a", low=0.0, low_inclusive=False,
                           doc="air density")


@dataclasses.dataclass(frozen=True, kw_only=True)
class WaveParams(Params):
    """Regular waves (or the mean of an irregular sea): height, length, direction."""

    wave_height: float = param(0.0, unit="m", symbol="h3%", low=0.0,
                               doc="wave height of 3 % exceedance")
    wave_length: float = param(100.0, unit="m", symbol="λ", low=0.0, low_inclusive=False,
                               doc="wave length (deep water: λ = g τ²/2π)")
    wave_direction: float = param(0.0, unit="rad", symbol="θ_v", low=-2.0 * math.pi,
                                  high=2.0 * math.pi,
                                  doc="direction the waves come from, clockwise from north")
    rho_water: float = param(RHO_SEAWATER, unit="kg/m³", symbol="ρ", low=0.0,
                             low_inclusive=False, doc="water density")


@dataclasses.dataclass(frozen=True, kw_only=True)
class LvovWindParams(WindParams):
    """Ship data of Lvov's wind loads, eq. (12): Y_a = 0.37 sin q ρ_a S_n W²,
    N_a = (0.25 + ℓ_sail/L − |q|°/360) L Y_a."""

    windage_lateral_area: float = param(unit="m²", symbol="S_n", low=0.0, low_inclusive=False,
                                        doc="lateral windage area (hull and superstructure)")
    windage_centre: float = param(0.0, unit="m", symbol="ℓ_sail",
                                  doc="centre of the lateral windage area, forward of midships")
    windage_length: float = param(unit="m", symbol="L", low=0.0, low_inclusive=False,
                                  doc="ship length of the moment arm")

    def validate(self) -> None:
        check_on_hull("windage_centre", self.windage_centre, self.windage_length)


@dataclasses.dataclass(frozen=True, kw_only=True)
class BlendermannWindParams(WindParams):
    """Ship data and coefficients of Blendermann's (1994) wind loads
    (:mod:`seahelm.environment.blendermann`; coefficients from a vessel type by name:
    :func:`blendermann_wind_params`)."""

    windage_frontal_area: float = param(unit="m²", symbol="A_F", low=0.0, low_inclusive=False,
                                        doc="frontal (transverse) projected windage area")
    windage_lateral_area: float = param(unit="m²", symbol="A_L", low=0.0, low_inclusive=False,
                                        doc="lateral projected windage area")
    windage_centre: float = param(0.0, unit="m", symbol="s_L",
                                  doc="centre of the lateral windage area, forward of midships")
    length_overall: float = param(unit="m", symbol="L_oa", low=0.0, low_inclusive=False,
                                  doc="length overall")
    cd_transverse: float = param(unit="-", symbol="CD_t", low=0.0, low_inclusive=False,
                                 doc="transverse drag coefficient")
    cd_longitudinal_head: float = param(unit="-", symbol="CD_l,AF(0)", low=0.0,
                                        low_inclusive=False,
                                        doc="longitudinal drag coefficient, head wind (on A_F)")
    cd_longitudinal_stern: float = param(unit="-", symbol="CD_l,AF(π)", low=0.0,
                                         low_inclusive=False,
                                         doc="longitudinal drag coefficient, stern wind (on A_F)")
    cd_delta: float = param(unit="-", symbol="δ", low=0.0, doc="cross-force parameter")
    cd_kappa: float = param(unit="-", symbol="κ", low=0.0, doc="rolling-moment factor")

    def validate(self) -> None:
        check_on_hull("windage_centre", self.windage_centre, self.length_overall)


@dataclasses.dataclass(frozen=True, kw_only=True)
class FujiwaraWindParams(WindParams):
    """Windage geometry of Fujiwara et al.'s (1998) wind loads
    (:mod:`seahelm.environment.fujiwara`)."""

    windage_length: float = param(unit="m", symbol="L", **_POSITIVE, doc="L_pp")
    windage_breadth: float = param(unit="m", symbol="B", **_POSITIVE, doc="breadth")
    windage_frontal_area: float = param(unit="m²", symbol="A_T", **_POSITIVE,
                                        doc="transverse (frontal) projected windage area")
    windage_lateral_area: float = param(unit="m²", symbol="A_L", **_POSITIVE,
                                        doc="lateral projected windage area")
    superstructure_lateral_area: float = param(unit="m²", symbol="A_OD", **_POSITIVE,
                                               doc="lateral area of the superstructure")
    windage_centre: float = param(0.0, unit="m", symbol="C",
                                  doc="centre of A_L, forward of midships")
    superstructure_centre: float = param(0.0, unit="m", symbol="C_BR",
                                         doc="centre of A_OD, forward of midships")
    superstructure_height: float = param(unit="m", symbol="H_BR", **_POSITIVE,
                                         doc="top of the superstructure above the waterline")
    windage_height: float = param(unit="m", symbol="H_C", **_POSITIVE,
                                  doc="centre of A_L above the waterline")

    def validate(self) -> None:
        check_on_hull("windage_centre", self.windage_centre, self.windage_length)
        check_on_hull("superstructure_centre", self.superstructure_centre, self.windage_length)


@dataclasses.dataclass(frozen=True, kw_only=True)
class LvovWaveParams(WaveParams):
    """Ship data of Lvov's mean wave loads, eq. (8)-(10) (coefficients from the hull by
    eq. (5)-(7): :func:`lvov_wave_params`)."""

    wave_cx: float = param(unit="-", symbol="C_x^w", doc="surge coefficient, eq. (5)")
    wave_cy: float = param(unit="-", symbol="C_y^w", doc="sway coefficient, eq. (6)")
    wave_cm: float = param(unit="-", symbol="C_m^w", doc="yaw coefficient, eq. (7)")
    wave_a0: float = param(3.3, unit="-", symbol="A0", low=0.0, doc="length attenuation A0")
    wave_a1: float = param(1.0, unit="-", symbol="A1", low=1.0, high=8.5,
                           doc="speed coefficient A1 (published range 1-8.5)")
    hull_length: float = param(unit="m", symbol="L", low=0.0, low_inclusive=False,
                               doc="ship length of eq. (8)-(10)")
    gravity: float = param(GRAVITY, unit="m/s²", symbol="g", low=0.0, low_inclusive=False,
                           doc="gravitational acceleration")


_TWO_PI = 2.0 * math.pi


# ------------------------------------------------------------------------------------------
# compiled loads (scalar, allocation-free: they run inside the closed loop)
# ------------------------------------------------------------------------------------------
@njit(cache=True)
def lvov_wind_loads(p, speed, angle, cos_angle, sin_angle):  # pragma: no cover - compiled
    """Lvov (2014) eq. (12) wind loads in body axes: (0, −Y_a, −N_a)."""
    y_a = 0.37 * sin_angle * p.rho_air * p.windage_lateral_area * speed * speed
    arm = 0.25 + p.windage_centre / p.windage_length - abs(angle) * (180.0 / math.pi) / 360.0
    return 0.0, -y_a, -arm * p.windage_length * y_a


@njit(cache=True)
def blendermann_wind_loads_compiled(p, speed, angle, cos_angle,
                                    sin_angle):  # pragma: no cover - compiled
    """Blendermann (1994) wind loads in body axes (:mod:`seahelm.environment.blendermann`),
    with the per-run constants of :data:`BLENDERMANN_WIND`."""
    return blendermann_loads_folded(
        speed * speed, -1.0 if sin_angle < 0.0 else 1.0, abs(angle), abs(sin_angle), cos_angle,
        p.cd_transverse, p.cd_l_head, p.cd_l_stern, p.cd_delta, p.centre_ratio,
        p.dynamic_area, p.length_overall)


def _blendermann_constants(r: Any) -> dict[str, np.ndarray]:
    ratio = r["windage_frontal_area"] / r["windage_lateral_area"]
    return {"cd_l_head": r["cd_longitudinal_head"] * ratio,
            "cd_l_stern": r["cd_longitudinal_stern"] * ratio,
            "centre_ratio": r["windage_centre"] / r["length_overall"],
            "dynamic_area": 0.5 * r["rho_air"] * r["windage_lateral_area"]}


@njit(cache=True)
def lvov_wave_loads(p, angle, cos_angle, sin_angle, speed_along,
                    factor):  # pragma: no cover - compiled
    """Lvov (2014) eq. (8)-(10) mean wave loads in body axes: (X_w, −Y_w, −M_w), times
    ``factor`` (1 + the irregular-sea fluctuation); the per-run constants of
    :data:`LVOV_WAVES`."""
    f = p.wave_force_scale * (1.0 + p.wave_a1 * speed_along * p.wave_slowness) * factor
    x = p.wave_cx * (0.1 - cos_angle) * f
    y = p.wave_cy * sin_angle * f
    m = (p.wave_cm * (2.0 * sin_angle * cos_angle) / (1.0 + (math.pi - abs(angle)) / math.pi)
         * f * p.hull_length)
    return x, -y, -m


def _lvov_wave_constants(r: Any) -> dict[str, np.ndarray]:
    length, half = r["hull_length"], 0.5 * r["wave_height"]
    return {"wave_force_scale": (r["rho_water"] * r["gravity"] * length * half * half
                                 * np.exp(-r["wave_a0"] * r["wave_length"] / length)),
            "wave_slowness": 1.0 / np.sqrt(r["gravity"] * r["wave_length"] / (2.0 * math.pi))}


# ------------------------------------------------------------------------------------------
# registries
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True, eq=False)
class LoadModel:
    """A wind or wave load model: its parameters and its compiled loads.

    Attributes
    ----------
    name : str
        Registry name.
    description : str
        One line, with the source.
    params_type : type[Params]
        Its parameters (a :class:`WindParams` or :class:`WaveParams` subclass).
    loads : numba dispatcher
        Wind: ``loads(p, speed, angle, cos_angle, sin_angle) -> (X, Y, N)`` of the relative
        wind (speed [m/s], bearing it comes from relative to the bow in [−π, π] [rad], positive
        from starboard, and that bearing's cosine and sine). Waves:
        ``loads(p, angle, cos_angle, sin_angle, speed_along, factor) -> (X, Y, N)`` of the
        relative bearing the waves come from in [−π, π] [rad] (and its cosine and sine), the
        ship's speed along the wave travel [m/s] and the load factor (1 + fluctuation). Body
        axes, [N, N, N·m]. The closed loop has the cosines and sines from the velocity
        components, without a trigonometric call.
    constants : callable, optional
        ``constants(r) -> {name: array}``: values of each run that do not change during the
        run, from its parameter fields (``r["wave_length"]``, arrays over the runs), computed
        once, before the loop, and appended to the record ``loads`` reads (``p.name``).
    """

    name: str
    description: str
    params_type: type[Params]
    loads: Any
    constants: Any = None


LVOV_WIND = LoadModel(
    "lvov", "Lvov (2014) eq. (12): lateral force 0.37 sin q ρ_a S_n W² and its yaw moment "
    "(no longitudinal force)", LvovWindParams, lvov_wind_loads)
BLENDERMANN_WIND = LoadModel(
    "blendermann", "Blendermann (1994): surge, sway and yaw coefficients of the relative-wind "
    "angle per vessel type (Fossen 2021, §10.1.2)", BlendermannWindParams,
    blendermann_wind_loads_compiled, _blendermann_constants)
FUJIWARA_WIND = LoadModel(
    "fujiwara", "Fujiwara, Ueno & Nimura (1998): surge, sway and yaw coefficients regressed on "
    "the windage geometry (A_T, A_L, A_OD, C, C_BR, H_BR, H_C)", FujiwaraWindParams,
    fujiwara_wind_loads, fujiwara_constants)
LVOV_WAVES = LoadModel(
    "lvov", "Lvov (2014) eq. (8)-(10): mean wave surge, sway and yaw loads, coefficients of "
    "eq. (5)-(7) (Yurkansky 2005)", LvovWaveParams, lvov_wave_loads, _lvov_wave_constants)

#: Wind load models by name.
WIND_LOADS: dict[str, LoadModel] = {"blendermann": BLENDERMANN_WIND, "lvov": LVOV_WIND,
                                    "fujiwara": FUJIWARA_WIND}
#: Wave load models by name.
WAVE_LOADS: dict[str, LoadModel] = {"lvov": LVOV_WAVES}


def _lookup(registry: dict[str, LoadModel], value: "LoadModel | str", what: str) -> LoadModel:
    if isinstance(value, LoadModel):
        return value
    return lookup_name(f"{what} model", registry, value)


def get_wind_loads(model: "LoadModel | str") -> LoadModel:
    """A wind load model by name or as given.

    Parameters
    ----------
    model : LoadModel or str
        A name in :data:`WIND_LOADS` or a model.

    Returns
    -------
    LoadModel

    Raises
    ------
    ValueError
        For an unknown name (the message lists the valid ones).
    """
    return _lookup(WIND_LOADS, model, "wind load")


def get_wave_loads(model: "LoadModel | str") -> LoadModel:
    """A wave load model by name or as given.

    Parameters
    ----------
    model : LoadModel or str
        A name in :data:`WAVE_LOADS` or a model.

    Returns
    -------
    LoadModel

    Raises
    ------
    ValueError
        For an unknown name (the message lists the valid ones).
    """
    return _lookup(WAVE_LOADS, model, "wave load")


# ------------------------------------------------------------------------------------------
# the environment component
# ------------------------------------------------------------------------------------------
WIND_OUTPUTS = ("apparent_wind_speed", "apparent_wind_angle", "wind_force_x", "wind_force_y",
                "wind_moment_z")
WIND_OUTPUT_UNITS = ("m/s", "rad", "N", "N", "N·m")
WAVE_OUTPUTS = ("wave_force_x", "wave_force_y", "wave_moment_z")
WAVE_OUTPUT_UNITS = ("N", "N", "N·m")


@dataclasses.dataclass(frozen=True, eq=False)
class Environment:
    """Wind and/or waves acting on a vessel model in the closed loop (module docstring).

    Build one with :func:`environment` (the same combination gives the same object, so its
    compiled stage is generated once).

    Attributes
    ----------
    wind, waves : LoadModel or None
        The load models.
    params_type : type[Params]
        The parameters of both (one record per run).
    signal_labels, signal_units : tuple of str
        Time-varying inputs it reads after the model's disturbance channels: ``wind_gust``
        [m/s] (with wind), ``wave_load_fluctuation`` [-] (with waves); zero when not given.
    output_labels, output_units : tuple of str
        What it reports after the model's outputs: the apparent wind and the wind loads, the
        wave loads (body axes).
    hold_over_step : bool
        Evaluate the loads once per integration step, at its start, and hold them over the
        step's stages (cheaper; the loads then follow the state to first order within a step),
        instead of at every stage (the default: the integrator's order is kept).
    """

    wind: LoadModel | None
    waves: LoadModel | None
    params_type: type[Params]
    signal_labels: tuple[str, ...]
    signal_units: tuple[str, ...]
    output_labels: tuple[str, ...]
    output_units: tuple[str, ...]
    hold_over_step: bool = False

    @property
    def name(self) -> str:
        parts = ([f"wind={self.wind.name}"] if self.wind else []) + (
            [f"waves={self.waves.name}"] if self.waves else []) + (
            ["loads held over each step"] if self.hold_over_step else [])
        return ", ".join(parts)

    def kernel_records(self, rows: np.ndarray) -> np.ndarray:
        """The records the compiled stage reads: the parameter fields of every run, then the
        per-run constants (the directions' cosines and sines, the load models' ``constants``),
        computed once here instead of at every stage of every step.

        Parameters
        ----------
        rows : numpy.ndarray, shape (runs, n_values)
            Packed parameter rows of :attr:`params_type`.

        Returns
        -------
        numpy.ndarray, shape (runs,)
            Structured records (``rec.wave_length``, ``rec.wave_from_cos``, ...).
        """
        base = as_records(rows, self.params_type)
        extra: dict[str, np.ndarray] = {}
        if self.wind is not None:
            extra["wind_from_cos"] = np.cos(base["wind_direction"])
            extra["wind_from_sin"] = np.sin(base["wind_direction"])
        if self.waves is not None:
            extra["wave_from_cos"] = np.cos(base["wave_direction"])
            extra["wave_from_sin"] = np.sin(base["wave_direction"])
        for model in (self.wind, self.waves):
            if model is not None and model.constants is not None:
                extra.update(model.constants(base))
        dtype = np.dtype(base.dtype.descr + [(name, np.float64) for name in extra])
        out = np.zeros(base.shape[0], dtype=dtype)
        for name in base.dtype.names:
            out[name] = base[name]
        for name, values in extra.items():
            out[name] = values
        return out.view(np.dtype((np.record, dtype)))

    def params(self, **values: Any) -> Params:
        """A parameter set of this environment (``params_type(**values)``).

        Parameters
        ----------
        **values
            Field values (SI units, radians).

        Returns
        -------
        Params
        """
        return self.params_type(**values)


@functools.lru_cache(maxsize=None)
def environment(wind: "LoadModel | str | None" = None,
                waves: "LoadModel | str | None" = None, *,
                hold_over_step: bool = False) -> Environment:
    """The environment component of a wind and/or a wave load model.

    Parameters
    ----------
    wind : LoadModel or str, optional
        A name in :data:`WIND_LOADS` or a model.
    waves : LoadModel or str, optional
        A name in :data:`WAVE_LOADS` or a model.
    hold_over_step : bool, optional
        Evaluate the loads once per step and hold them over its stages (default False: at
        every stage). See :class:`Environment`.

    Returns
    -------
    Environment

    Raises
    ------
    ValueError
        For an unknown name (the message lists the valid ones), or neither wind nor waves.
    """
    if wind is None and waves is None:
        raise ValueError("an environment needs wind and/or waves (a current alone is a "
                         "disturbance channel of the model: current_north, current_east)")
    w = None if wind is None else get_wind_loads(wind)
    v = None if waves is None else get_wave_loads(waves)
    bases = tuple(m.params_type for m in (w, v) if m is not None)
    if len(bases) == 1:
        params_type = bases[0]
    else:
        params_type = dataclasses.make_dataclass(
            f"{w.params_type.__name__[:-6]}{v.params_type.__name__}", [], bases=bases,
            frozen=True, kw_only=True)
        params_type.__doc__ = (f"Parameters of the wind ('{w.name}') and wave ('{v.name}') "
                               "loads.")
    signals, units, outs, out_units = [], [], [], []
    if w is not None:
        signals.append("wind_gust")
        units.append("m/s")
        outs += WIND_OUTPUTS
        out_units += WIND_OUTPUT_UNITS
    if v is not None:
        signals.append("wave_load_fluctuation")
        units.append("-")
        outs += WAVE_OUTPUTS
        out_units += WAVE_OUTPUT_UNITS
    if not isinstance(hold_over_step, bool):
        raise ParameterError(f"`hold_over_step` must be True or False, got {hold_over_step!r}")
    return Environment(w, v, params_type, tuple(signals), tuple(units), tuple(outs),
                       tuple(out_units), hold_over_step)


# ------------------------------------------------------------------------------------------
# parameters from ship data, irregular seas
# ------------------------------------------------------------------------------------------
def lvov_wave_params(*, length: float, beam: float, draft: float, block_coefficient: float,
                     strict: bool | None = None, **values: Any) -> dict[str, float]:
    """The fields of :class:`LvovWaveParams` from the hull (eq. (5)-(7)), plus ``values``.

    Parameters
    ----------
    length, beam, draft : float
        L, B, T [m].
    block_coefficient : float
        δ [-].
    strict : bool, optional
        Raise instead of warning outside the published range of eq. (5)-(7).
    **values
        Other fields (``wave_height``, ``wave_length``, ``wave_direction``, ``wave_a1``, ...).

    Returns
    -------
    dict
        ``hull_length``, ``wave_cx``, ``wave_cy``, ``wave_cm`` and ``values``.

    Warns
    -----
    ValidityRangeWarning
        Hull ratios outside 10 < L/T < 23, 1 < B/T < 3.7, 5 < L/B < 12, 0.6 < δ < 0.8.
    """
    from .wave_forces import wave_force_coefficients

    c = wave_force_coefficients(length, beam, draft, block_coefficient, strict=strict)
    return dict(hull_length=float(length), wave_cx=float(c.cx), wave_cy=float(c.cy),
                wave_cm=float(c.cm), **values)


def blendermann_wind_params(vessel_type: Any, **values: Any) -> dict[str, float]:
    """The coefficient fields of :class:`BlendermannWindParams` for a vessel type, plus
    ``values``.

    Parameters
    ----------
    vessel_type : str or BlendermannCoefficients
        A name in :data:`seahelm.environment.blendermann.BLENDERMANN_VESSEL_TYPES` (e.g.
        ``"tanker-loaded"``) or coefficients.
    **values
        Other fields (``wind_speed``, ``windage_lateral_area``, ...).

    Returns
    -------
    dict
    """
    c = get_blendermann_type(vessel_type)
    return dict(cd_transverse=c.cd_transverse, cd_longitudinal_head=c.cd_longitudinal_head,
                cd_longitudinal_stern=c.cd_longitudinal_stern, cd_delta=c.delta,
                cd_kappa=c.kappa, **values)


def ship_load_params(ship: Any, environment: Environment, **values: Any) -> Params:
    """The parameters of ``environment`` for a ship's particulars, plus the weather.

    Windage (areas, centre, length, Blendermann's vessel type) and hull data (length, beam,
    draft, block coefficient) come from ``ship``; ``values`` give the weather (``wind_speed``,
    ``wind_direction``, ``wave_height``, ...) and may override any field.

    Parameters
    ----------
    ship : Ship or Particulars
        The ship (:class:`seahelm.ships.Ship`, its particulars are used) or its particulars
        (:class:`seahelm.vessels.particulars.Particulars`).
    environment : Environment
        The load models.
    **values
        Field values (SI units, radians).

    Returns
    -------
    Params
        ``environment.params_type``.

    Warns
    -----
    ValidityRangeWarning
        With Lvov's waves, a hull outside the published range of eq. (5)-(7).
    """
    from ..vessels.particulars import Particulars

    particulars = getattr(ship, "particulars", ship)  # a Ship, or its particulars
    if not isinstance(particulars, Particulars):
        raise ParameterError(
            "`ship` must be a Ship with particulars or a Particulars (a catalog ship: "
            f"seahelm.ships.get_ship(name)), got {type(ship).__name__}"
            + (" without particulars" if particulars is None else ""))
    ship = particulars
    need = "the environment's loads"
    fields: dict[str, Any] = {}
    if environment.wind is LVOV_WIND:
        fields.update(windage_lateral_area=ship.require("lateral_area", need),
                      windage_centre=ship.require("windage_centre", need),
                      windage_length=ship.length)
    elif environment.wind is BLENDERMANN_WIND:
        fields.update(blendermann_wind_params(
            ship.require("vessel_type", need),
            windage_frontal_area=ship.require("frontal_area", need),
            windage_lateral_area=ship.require("lateral_area", need),
            windage_centre=ship.require("windage_centre", need),
            length_overall=ship.require("length_overall", need)))
    elif environment.wind is FUJIWARA_WIND:
        fields.update(
            windage_length=ship.length, windage_breadth=ship.beam,
            windage_frontal_area=ship.require("frontal_area", need),
            windage_lateral_area=ship.require("lateral_area", need),
            superstructure_lateral_area=ship.require("superstructure_lateral_area", need),
            windage_centre=ship.require("windage_centre", need),
            superstructure_centre=ship.require("superstructure_centre", need),
            superstructure_height=ship.require("superstructure_height", need),
            windage_height=ship.require("windage_height", need))
    if environment.waves is LVOV_WAVES:
        fields.update(lvov_wave_params(length=ship.length, beam=ship.beam, draft=ship.draft,
                                       block_coefficient=ship.block_coefficient))
    return environment.params(**{**fields, **values})


@functools.lru_cache(maxsize=64)
def _envelope_filter(spectrum: str, wave_height: float) -> tuple[Any, np.ndarray]:
    from .shaping import shaping_filter
    from .spectra import spectrum_from_wave_height

    filt = shaping_filter(spectrum_from_wave_height(spectrum, wave_height),
                          outputs=("ordinate", "ordinate_rate"))
    return filt, np.asarray(filt.output_variance(), dtype=float)


def wave_load_fluctuation(wave_height: float, n_steps: int, dt: float, seed: Any, *,
                          spectrum: str = "rakhmanin-firsov-2",
                          runs: int | None = None) -> np.ndarray:
    """The irregular-sea factor f(t) = A²/E[A²] − 1 of the wave loads on a uniform grid.

    A² = ζ² + (ζ̇/ω̄)² is the squared envelope of the sea elevation ζ (module docstring), ζ and
    ζ̇ sampled exactly by the shaping filter of the spectrum
    (:func:`seahelm.environment.shaping.shaping_filter`), started in its stationary
    distribution, so f has zero mean from t = 0 on.

    Parameters
    ----------
    wave_height : float
        h3% [m] (> 0).
    n_steps : int
        Samples t_k = k dt, k = 0 … n_steps − 1.
    dt : float
        Step [s].
    seed : int, SeedSequence, Generator or a sequence of these
        The realisation. With ``runs``, a sequence of ``runs`` seeds gives run i the
        realisation ``seed[i]`` gives alone; a single seed is spawned into ``runs`` children
        (:meth:`~seahelm.environment.shaping.ShapingFilter.sample`).
    spectrum : str, optional
        Registry name of the sea spectrum (default "rakhmanin-firsov-2").
    runs : int, optional
        Draw this many realisations at once (one vectorised draw: ~10× faster per run than
        one call per run).

    Returns
    -------
    numpy.ndarray, shape (n_steps,), or (runs, n_steps) with ``runs``
        f [-], ≥ −1.
    """
    check_positive("wave_height", wave_height, "m")
    check_positive("dt", dt, "s")
    from .discretisation import single_run_stream

    filt, var = _envelope_filter(spectrum, float(wave_height))
    if runs is not None and isinstance(seed, (list, tuple)):
        seed = [single_run_stream(s) for s in seed]  # run i: seed[i]'s own stream
    draw = filt.sample(n_steps=int(n_steps), dt=float(dt), seed=seed,
                       runs=1 if runs is None else int(runs)).values
    f = 0.5 * (draw[..., 0] ** 2 / var[0] + draw[..., 1] ** 2 / var[1]) - 1.0
    return f[0] if runs is None else f


@dataclasses.dataclass(frozen=True)
class Conditions:
    """Wind, waves and a uniform current for a run or a manoeuvre (SI units, radians).

    Attributes
    ----------
    environment : Environment, optional
        The wind/wave load models (:func:`environment`).
    params : Params, optional
        Its parameters (``environment.params(...)``), required with an environment.
    current_speed : float
        Speed of a uniform, constant current [m/s] (≥ 0; on models with ``current_north``,
        ``current_east`` channels).
    current_direction : float
        Direction the current sets to (flows towards), clockwise from north [rad].
    """

    environment: Environment | None = None
    params: Params | None = None
    current_speed: float = 0.0
    current_direction: float = 0.0

    def __post_init__(self) -> None:
        if self.environment is not None and self.params is None:
            raise ParameterError("`params` of the environment are required (environment.params"
                                 "(wind_speed=..., ...))")
        if self.environment is None and self.params is not None:
            raise ParameterError("`params` given without an `environment`")
        if self.environment is not None and not isinstance(self.params,
                                                           self.environment.params_type):
            raise ParameterError(
                f"`params` must be {self.environment.params_type.__name__}, got "
                f"{type(self.params).__name__}")
        speed = float(as_float_array("current_speed", self.current_speed, "m/s"))
        if not speed >= 0:
            raise ParameterError(f"`current_speed` must be >= 0 [m/s], got {speed!r}")
        as_float_array("current_direction", self.current_direction, "rad")

    def disturbance(self, model: Any) -> dict[str, float]:
        """The current as the model's ``current_north``, ``current_east`` channels [m/s].

        Parameters
        ----------
        model : VesselModel
            The model the current acts on.

        Returns
        -------
        dict
            Channel values (empty without a current).

        Raises
        ------
        ParameterError
            If there is a current and the model has no current channels.
        """
        if self.current_speed == 0.0:
            return {}
        if not {"current_north", "current_east"} <= set(model.disturbance_labels):
            raise ParameterError(
                f"model '{model.name}' has no current channels (current_north, current_east "
                "[m/s])")
        return {"current_north": self.current_speed * math.cos(self.current_direction),
                "current_east": self.current_speed * math.sin(self.current_direction)}
