"""``[environment.wind]`` and ``[environment.waves]``: the loads a scenario's runs feel.

Turns the two sections (and their per-run overrides from ``[batch]``, e.g.
``environment.wind.speed = [5, 10, 15]``) into the engine's environment component, one
parameter set per run, and the environment's time signals (``wind_gust``; the irregular sea's
``wave_load_fluctuation``, a seeded realisation per run). Ship data the loads need (windage
areas, hull beam, draft, block coefficient) come from the catalog ship's particulars
(:mod:`seahelm.vessels.particulars`) unless the section gives them.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from .._validate import uniform_time_step
from ..constants import GRAVITY
from ..environment.loads import (
    Environment,
    blendermann_wind_params,
    environment,
    get_wave_loads,
    get_wind_loads,
    lvov_wave_params,
    wave_load_fluctuation,
)
from ..errors import ParameterError, ValidityRangeWarning
from ..vessels.particulars import Particulars
from .errors import at_key as _err
from .schema import Scenario

if TYPE_CHECKING:
    from .first_order import FirstOrderSettings

__all__ = ["KEY_UNITS", "WaveLoadFluctuation", "EnvironmentRuns", "environment_runs"]

#: Units of the keys of the two sections (for messages and batch dimensions).
KEY_UNITS: dict[str, str] = {
    "environment.wind.speed": "m/s", "environment.wind.frontal_area": "m²",
    "environment.wind.lateral_area": "m²", "environment.wind.centre": "m",
    "environment.wind.length_overall": "m", "environment.wind.length": "m",
    "environment.wind.rho_air": "kg/m³",
    "environment.waves.height": "m", "environment.waves.hs": "m",
    "environment.waves.length": "m", "environment.waves.period": "s",
    "environment.waves.a1": "-", "environment.waves.hull_length": "m",
    "environment.waves.beam": "m", "environment.waves.draft": "m",
    "environment.waves.block_coefficient": "-",
}

#: Hs = HS_PER_H3 · h3%: Hs = 4 √D_r with D_r = 0.143 (h3%/2)² (Sushchenko & Lutsko 2010).
HS_PER_H3 = 4.0 * math.sqrt(0.143) / 2.0


@dataclasses.dataclass(frozen=True)
class WaveLoadFluctuation:
    """The ``wave_load_fluctuation`` signal of an irregular sea (a random signal: each run of a
    batch draws its own realisation, see :func:`seahelm.environment.loads.wave_load_fluctuation`).
    """

    h3: float
    spectrum: str = "rakhmanin-firsov-2"
    seed: int = 0

    random = True

    def __call__(self, t: Any, *, seed: Any = None) -> np.ndarray:
        t, dt = uniform_time_step(t, "an irregular sea")
        return wave_load_fluctuation(self.h3, t.size, dt,
                                     self.seed if seed is None else seed,
                                     spectrum=self.spectrum)

    def draw_runs(self, t: Any, seeds: list[Any]) -> np.ndarray:
        """Many runs' realisations in one vectorised draw: row i equals
        ``self(t, seed=seeds[i])``.

        Parameters
        ----------
        t : array_like
            The uniform time grid [s].
        seeds : list
            One seed (int or SeedSequence) per run.

        Returns
        -------
        numpy.ndarray, shape (len(seeds), len(t))
        """
        t, dt = uniform_time_step(t, "an irregular sea")
        return wave_load_fluctuation(self.h3, t.size, dt, list(seeds),
                                     spectrum=self.spectrum, runs=len(seeds))


@dataclasses.dataclass(frozen=True)
class EnvironmentRuns:
    """What :func:`environment_runs` gives: the component, a parameter row per run (or one),
    and per run the environment's signal specifications (by channel name)."""

    environment: Environment
    params: np.ndarray
    signals: list[dict[str, Any]]
    #: per run, the first-order motions' settings (:mod:`seahelm.scenario.first_order`), or None
    first_order: list[FirstOrderSettings] | None = None


def _ship(scn: Scenario, source: str) -> Particulars | None:
    """The particulars of the scenario's ship (None without a ship or particulars)."""
    from .vessel import vessel_ship

    ship = vessel_ship(scn, source)
    return None if ship is None else ship.particulars


def _section(over: dict[str, Any], prefix: str, base: dict[str, Any]) -> dict[str, Any]:
    out = dict(base)
    out.update({k[len(prefix):]: v for k, v in over.items() if k.startswith(prefix)})
    return out


#: Fields of the environment's parameters -> the scenario key they come from, and the factor
#: from the field's unit to the key's (directions are written in degrees).
_FIELD_KEYS: dict[str, tuple[str, float, str]] = {
    "wind_direction": ("environment.wind.direction_deg", 180.0 / math.pi, "deg"),
    "wave_direction": ("environment.waves.direction_deg", 180.0 / math.pi, "deg"),
    "wind_speed": ("environment.wind.speed", 1.0, "m/s"),
    "wave_height": ("environment.waves.height", 1.0, "m"),
}


def _in_scenario_words(exc: ParameterError, where: str) -> tuple[str, str]:
    """The key and message of an environment parameter's error, in the scenario's key and unit
    (from the error's field: "`direction_deg` 720 deg is out of [-360, 360] deg")."""
    key = _FIELD_KEYS.get(exc.field or "")
    if key is None or exc.value is None:
        return "environment", f"{exc}{where}"
    path, factor, unit = key
    name = path.rpartition(".")[2]
    from ..environment.loads import WaveParams, WindParams

    lo = hi = None
    for cls in (WindParams, WaveParams):
        f = {x.name: x for x in dataclasses.fields(cls)}.get(exc.field)
        if f is not None:
            lo, hi = f.metadata.get("low"), f.metadata.get("high")
    bounds = (f" must be in [{lo * factor:g}, {hi * factor:g}] [{unit}]"
              if lo is not None and hi is not None and math.isfinite(lo) and math.isfinite(hi)
              else f" is out of range [{unit}]")
    return path, f"`{name}`{bounds}, got {float(exc.value) * factor:g}{where}"


def _given(values: dict[str, Any], key: str, ship: Particulars | None, attr: str
           ) -> float | None:
    """The section's value of ``key``, else the ship's particulars' ``attr``, else None."""
    if values.get(key) is not None:
        return float(values[key])
    if ship is not None and getattr(ship, attr) is not None:
        return float(getattr(ship, attr))
    return None


def _missing(source: str, path: str, missing: list[tuple[str, str]],
             ship: Particulars | None) -> Exception:
    """One error naming every key a section needs and does not have, the first as its key
    (they came one run at a time: lateral_area, then vessel_type, then length_overall)."""
    def named(key: str, unit: str) -> str:
        if key == "vessel_type":
            from ..environment.blendermann import BLENDERMANN_VESSEL_TYPES

            return ("`vessel_type` (Blendermann's coefficients; valid: "
                    + ", ".join(sorted(BLENDERMANN_VESSEL_TYPES)) + ")")
        return f"`{key}` [{unit}]" if unit else f"`{key}`"

    (key, unit), rest = missing[0], missing[1:]
    why = ("the vessel has no catalog particulars to take it from (a ship with "
           "[particulars]: a catalog ship or a ship file)" if ship is None else
           f"the ship's particulars do not give `{key}`")
    first = (named(key, unit)[len(f"`{key}` "):] if key == "vessel_type"
             else f"[{unit}]" if unit else "")
    also = ("; also needed: " + ", ".join(named(k, u) for k, u in rest)) if rest else ""
    return _err(source, f"{path}.{key}", f"needed {first}: {why}{also}".replace("needed :",
                                                                                 "needed:"))


def _wind_fields(w: dict[str, Any], name: str, ship: Particulars | None,
                 source: str) -> dict[str, float]:
    path = "environment.wind"
    fields: dict[str, Any] = {"wind_speed": float(w["speed"]),
                              "wind_direction": math.radians(float(w["direction_deg"]))}
    if w.get("rho_air") is not None:
        fields["rho_air"] = float(w["rho_air"])
    centre = float(w["centre"]) if w.get("centre") is not None else (
        ship.windage_centre if ship is not None and ship.windage_centre is not None else 0.0)
    if name == "lvov":
        extra = [k for k in ("frontal_area", "length_overall", "vessel_type") if w.get(k) is not None]
        if extra:
            raise _err(source, f"{path}.{extra[0]}",
                       "Lvov's wind loads take no frontal area, length overall or vessel type "
                       "(keys: speed, direction_deg, gust, lateral_area, centre, length, rho_air)")
        needs = (("lateral_area", "lateral_area", "m²"), ("length", "length", "m"))
    else:
        if w.get("length") is not None:
            raise _err(source, f"{path}.length",
                       "Blendermann's loads take `length_overall` [m], not `length`")
        needs = (("lateral_area", "lateral_area", "m²"), ("frontal_area", "frontal_area", "m²"),
                 ("length_overall", "length_overall", "m"))
    values = {key: _given(w, key, ship, attr) for key, attr, _ in needs}
    missing = [(key, unit) for key, _, unit in needs if values[key] is None]
    vessel_type = None
    if name != "lvov":
        vessel_type = w.get("vessel_type") or (ship.vessel_type if ship is not None else None)
        if vessel_type is None:
            missing.append(("vessel_type", ""))
    if missing:
        raise _missing(source, path, missing, ship)
    if name == "lvov":
        fields.update(windage_lateral_area=values["lateral_area"], windage_centre=centre,
                      windage_length=values["length"])
        return fields
    try:
        return blendermann_wind_params(
            vessel_type, **fields, windage_lateral_area=values["lateral_area"],
            windage_centre=centre, windage_frontal_area=values["frontal_area"],
            length_overall=values["length_overall"])
    except ValueError as exc:
        raise _err(source, f"{path}.vessel_type", str(exc)) from None


def _wave_fields(v: dict[str, Any], ship: Particulars | None, source: str
                 ) -> tuple[dict[str, float], float]:
    path = "environment.waves"
    h3 = float(v["height"]) if v.get("height") is not None else float(v["hs"]) / HS_PER_H3
    if v.get("length") is not None:
        wave_length = float(v["length"])
    else:
        wave_length = GRAVITY * float(v["period"]) ** 2 / (2.0 * math.pi)
    needs = (("hull_length", "length", "m"), ("beam", "beam", "m"), ("draft", "draft", "m"),
             ("block_coefficient", "block_coefficient", "-"))
    hull = {k: _given(v, k, ship, attr) for k, attr, _ in needs}
    missing = [(k, unit) for k, _, unit in needs if hull[k] is None]
    if missing:  # every one in one message
        raise _missing(source, path, missing, ship)
    with warnings.catch_warnings():
        if h3 == 0.0:  # no waves: the hull's coefficients multiply zero, their range is moot
            warnings.simplefilter("ignore", ValidityRangeWarning)
        fields = lvov_wave_params(
            length=hull["hull_length"], beam=hull["beam"], draft=hull["draft"],
            block_coefficient=hull["block_coefficient"], wave_height=h3,
            wave_length=wave_length, wave_direction=math.radians(float(v["direction_deg"])))
    if v.get("a1") is not None:
        fields["wave_a1"] = float(v["a1"])
    return fields, h3


def _check_sea(v: dict[str, Any], h3: float, checked: set[tuple[float, str]], source: str,
               where: str) -> None:
    """The irregular sea's spectrum exists and is defined for the height (Table 2: 1-10 m)."""
    from ..environment.sea_state import table2
    from ..environment.spectra import spectrum_from_wave_height, spectrum_names

    key = (h3, v["spectrum"])
    if key in checked:
        return
    checked.add(key)
    if v["spectrum"] not in spectrum_names():
        raise _err(source, "environment.waves.spectrum",
                   f"unknown spectrum {v['spectrum']!r}; valid: {', '.join(spectrum_names())}")
    hs = table2()["h3"]
    name = "height" if v.get("height") is not None else "hs"
    if not hs[0] <= h3 <= hs[-1]:
        shown = (f"{v['height']!r} [m]" if name == "height"
                 else f"{v['hs']!r} [m] (h3% = {h3:.3g} m)")
        raise _err(source, f"environment.waves.{name}",
                   f"an irregular sea's h3% must be in [{hs[0]:g}, {hs[-1]:g}] [m] (the sea-state "
                   f"Table 2 of Sushchenko & Lutsko (2010)), got {shown}{where}")
    try:
        spectrum_from_wave_height(v["spectrum"], h3)
    except (ValueError, ParameterError) as exc:
        raise _err(source, f"environment.waves.{name}", f"{exc}{where}") from None


def environment_runs(scn: Scenario, model: Any, runs: list[dict[str, Any]], source: str
                     ) -> EnvironmentRuns | None:
    """The environment of a scenario's runs, or None without wind and waves.

    Parameters
    ----------
    scn : Scenario
        The validated scenario.
    model : VesselModel
        Its vessel model (the loads need its ``force_x``, ``force_y``, ``moment_z`` channels).
    runs : list of dict
        Per-run overrides ``{"environment.wind.speed": 10.0, ...}`` (may be empty dicts).
    source : str
        Scenario name for messages.

    Returns
    -------
    EnvironmentRuns or None

    Raises
    ------
    ScenarioError
        Naming the key, its unit and the value.
    """
    from ..simulation.environment_stage import check_environment

    env_sec = scn.environment
    if env_sec.wind is None and env_sec.waves is None:
        if "loads" in env_sec.model_fields_set:
            raise _err(source, "environment.loads", "says when the wind and wave loads are "
                       "evaluated, but there is no [environment.wind] or [environment.waves]")
        return None
    wind_name = waves_name = None
    if env_sec.wind is not None:
        try:
            wind_name = get_wind_loads(env_sec.wind.model).name
        except ValueError as exc:
            raise _err(source, "environment.wind.model", str(exc)) from None
    if env_sec.waves is not None:
        try:
            waves_name = get_wave_loads(env_sec.waves.model).name
        except ValueError as exc:
            raise _err(source, "environment.waves.model", str(exc)) from None
    env = environment(wind=wind_name, waves=waves_name,
                      hold_over_step=scn.environment.loads == "once-per-step")
    try:
        check_environment(env, model)
    except ParameterError as exc:
        raise _err(source, "environment.wind" if env_sec.wind is not None
                   else "environment.waves", str(exc)) from None
    ship = _ship(scn, source)
    wind_base = env_sec.wind.model_dump(exclude_none=True) if env_sec.wind else {}
    waves_base = env_sec.waves.model_dump(exclude_none=True) if env_sec.waves else {}
    rows, signals, first_order = [], [], []
    checked: set[tuple[float, str]] = set()
    for i, over in enumerate(runs):
        where = f" (run {i}: {over})" if over else ""
        fields: dict[str, Any] = {}
        sig: dict[str, Any] = {}
        if env_sec.wind is not None:
            w = _section(over, "environment.wind.", wind_base)
            fields.update(_wind_fields(w, wind_name or "", ship, source))
            if w.get("gust") is not None:
                gust = w["gust"]
                if isinstance(gust, dict) and gust.get("kind") == "gust":
                    # a gust spectrum's mean wind is the section's (and the run's) speed
                    gust = {"mean_speed": float(w["speed"]), **gust}
                sig["wind_gust"] = gust
        if env_sec.waves is not None:
            v = _section(over, "environment.waves.", waves_base)
            if v.get("irregular"):  # (errors before the hull's validity warnings)
                h3 = float(v["height"]) if v.get("height") is not None else \
                    float(v["hs"]) / HS_PER_H3
                _check_sea(v, h3, checked, source, where)
                sig["wave_load_fluctuation"] = WaveLoadFluctuation(
                    h3=h3, spectrum=v["spectrum"], seed=int(v.get("seed", 0)))
                if v.get("first_order_motions"):
                    from .first_order import first_order_settings

                    first_order.append(first_order_settings(v, h3, ship, source))
            fields.update(_wave_fields(v, ship, source)[0])
        try:
            rows.append(env.params_type(**fields).to_array())
        except ParameterError as exc:
            raise _err(source, *_in_scenario_words(exc, where)) from None
        signals.append(sig)
    return EnvironmentRuns(env, np.array(rows), signals,
                           first_order if len(first_order) == len(runs) else None)
