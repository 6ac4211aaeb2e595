"""Lvov (2014): wind and wave compensation of a course autopilot — the paper's reproduction.

The reusable parts are components: the empirical wave loads of eq. (5)-(11) in
:mod:`seahelm.environment.wave_forces`, the wind of eq. (1)-(4) in
:mod:`seahelm.environment.wind`, the compensating rudder angle of eq. (12)-(14), the
loss-of-controllability monitor and the compensated autopilot of Fig. 1 in
:mod:`seahelm.control.compensation`, the course setter in :mod:`seahelm.control.guidance` and
the course-keeping metrics in :mod:`seahelm.analysis.maneuvers.course_keeping`. This module
holds the paper's reproduction on top of them:

* :class:`ShipParticulars` and :data:`MARINER_PARTICULARS` — the ship data eq. (5)-(14) need;
* :func:`compensation_summary` — every number of the paper's chain for one ship and sea (the
  ``seahelm compensate`` command);
* :func:`model_compensation` — δ_k as the ship model's steady balancing rudder angle;
* the two ways block 7 of Fig. 1 computes δ_k, as objects in the registry
  :data:`DELTA_K_METHODS`: :data:`MODEL_BALANCE` (``"model"``, the default) and
  :data:`PRINTED_EQ14` (``"paper"``, eq. (12)/(14) as printed);
* :class:`WindWaveCase` and :func:`wind_wave_scenario` — the closed loop of Fig. 1 on the
  Voitkunsky model with wind and wave loads as disturbances.

What the printed formula gets wrong on a simulated ship
-------------------------------------------------------
Eq. (12) adds the hull term (drift α) to the wind term with the same sign. Physically the two
moments oppose each other: the wind on a forward bearing turns the bow to leeward, while the
hull's lateral resistance, centred forward (the (0.5 + ℓ_lr/L − α/180) L arm of eq. (12)),
turns it to windward. On the Mariner Voitkunsky model the drift (Munk) moment dominates, and
the balancing rudder has the *opposite* sign of eq. (12)/(14): wind 15 m/s and h3% = 6.75 m
from 60° off the starboard bow need −9.6° in the model, eq. (14) gives +13.3°. Feeding the
printed δ_k forward then makes course keeping worse than PID alone (see
``examples/compensation_table.py``). :func:`wind_wave_scenario` therefore uses
:data:`MODEL_BALANCE` — block 7 computes δ_k as the steady balancing rudder angle of the ship
model for the loads the wind and wave compensators (blocks 5, 6) estimate — and keeps
:data:`PRINTED_EQ14` (eq. (12)/(14) as printed) reachable by name, ``delta_k_method="paper"``.

Longer than 600 lines because it holds the paper's whole reproduction, which is read
together: its ship data (made from a catalog ship by :meth:`ShipParticulars.from_ship`), the
δ_k variants, the one-shot summary and the closed-loop scenario builder.

References
----------
Lvov, V. E. (2014), eq. (1)-(14), Fig. 1. Lvov, V. E. (2008), Sudovozhdenie 15, 109-114
(the wind compensator, eq. (12)-(13)).
"""

from __future__ import annotations

import abc
import dataclasses
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, NamedTuple

import numpy as np

from .._validate import check_nonnegative, check_on_hull, check_positive
from ..constants import RHO_SEAWATER
from ..control.compensation import (
    COMPENSATED_PID,
    drift_angle,
    lateral_resistance_centre,
    wave_compensation,
    wind_compensation,
)
from ..control.guidance import course_to_steer
from ..errors import ParameterError
from ..parameters import Params, param
from ..registry import lookup
from ..vessels.voitkunsky import steady_course_keeping

__all__ = [
    "ShipParticulars",
    "MARINER_PARTICULARS",
    "CompensationSummary",
    "compensation_summary",
    "ModelCompensation",
    "model_compensation",
    "CompensationChannels",
    "DeltaKMethod",
    "ModelBalance",
    "PrintedEq14",
    "MODEL_BALANCE",
    "PRINTED_EQ14",
    "DELTA_K_METHODS",
    "get_delta_k_method",
    "WindWaveCase",
    "wind_wave_scenario",
]


# ------------------------------------------------------------------------------------------
# ship particulars, one-shot summary (CLI)
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True, kw_only=True)
class ShipParticulars(Params):
    """Hull, rudder and loading data used by eq. (5)-(14) (SI units)."""

    length: float = param(unit="m", symbol="L", low=0.0, low_inclusive=False, doc="length")
    beam: float = param(unit="m", symbol="B", low=0.0, low_inclusive=False, doc="beam")
    draft: float = param(unit="m", symbol="T", low=0.0, low_inclusive=False, doc="mean draft")
    draft_fore: float = param(0.0, unit="m", symbol="T_f", low=0.0,
                              doc="draft forward (0: the mean draft)")
    draft_aft: float = param(0.0, unit="m", symbol="T_a", low=0.0,
                             doc="draft aft (0: the mean draft)")
    block_coefficient: float = param(unit="", symbol="δ", low=0.0, low_inclusive=False,
                                     high=1.0, doc="block coefficient")
    speed: float = param(unit="m/s", symbol="V", low=0.0, low_inclusive=False,
                         doc="speed through the water (by log)")
    rudder_area: float = param(0.0, unit="m²", symbol="S_p", low=0.0,
                               doc="rudder area (0: 1.7 % of L·T)")
    rudder_aspect_ratio: float = param(1.6, unit="", symbol="λ_p", low=0.0, low_inclusive=False,
                                       doc="rudder aspect ratio")
    windage_area: float = param(0.0, unit="m²", symbol="S_a", low=0.0,
                                doc="lateral windage area (0: 0.8·L·T)")
    underwater_area: float = param(0.0, unit="m²", symbol="S_h", low=0.0,
                                   doc="lateral underwater area (0: L·T)")
    sail_centre: float = param(0.0, unit="m", symbol="ℓ_sail",
                               doc="centre of windage forward of midships")
    sway_mass: float = param(0.0, unit="kg", symbol="m − Y_v̇", low=0.0,
                             doc="mass plus added mass in sway (for the model's disturbances)")
    yaw_inertia: float = param(0.0, unit="kg·m²", symbol="I_z − N_ṙ", low=0.0,
                               doc="yaw inertia plus added inertia (for the model's disturbances)")

    def validate(self) -> None:
        check_on_hull("sail_centre", self.sail_centre, self.length)

    @classmethod
    def from_ship(cls, ship: Any, *, speed: float | None = None, **values: Any
                  ) -> "ShipParticulars":
        """Lvov's data of a :class:`~seahelm.ships.Ship`: its main particulars and windage
        (length, beam, draft, block coefficient, lateral windage area and its centre), its
        test speed, and ``values`` for what a ship does not hold (rudder, masses).

        Parameters
        ----------
        ship : Ship, str or path-like
            The ship (a catalog name or a ship file).
        speed : float, optional
            Speed through the water [m/s] (default: the ship's test speed).
        **values
            Any other field (SI units).

        Returns
        -------
        ShipParticulars
        """
        from ..ships import get_ship

        s = get_ship(ship)
        p = s.particulars
        if p is None:
            raise ParameterError(f"ship '{s.name}' has no particulars", field="ship")
        fields: dict[str, Any] = dict(length=p.length, beam=p.beam, draft=p.draft,
                                      block_coefficient=p.block_coefficient,
                                      speed=s.test_speed if speed is None else speed)
        if p.lateral_area is not None:
            fields["windage_area"] = p.lateral_area
        if p.windage_centre is not None:
            fields["sail_centre"] = p.windage_centre
        return cls(**{**fields, **values})

    @property
    def t_fore(self) -> float:
        return self.draft_fore or self.draft

    @property
    def t_aft(self) -> float:
        return self.draft_aft or self.draft

    @property
    def s_p(self) -> float:
        return self.rudder_area or 0.017 * self.length * self.draft

    @property
    def s_a(self) -> float:
        return self.windage_area or 0.8 * self.length * self.draft

    @property
    def s_h(self) -> float:
        return self.underwater_area or self.length * self.draft


def _mariner() -> ShipParticulars:
    rho, L = RHO_SEAWATER, 160.93
    half = 0.5 * rho
    m = 798e-5 * half * L**3
    return ShipParticulars(
        length=L, beam=23.17, draft=8.23,
        block_coefficient=round(m / rho / (L * 23.17 * 8.23), 3),
        speed=7.7175, rudder_area=0.017 * L * 8.23, rudder_aspect_ratio=1.6,
        windage_area=0.8 * L * 8.23, sail_centre=0.0,
        sway_mass=(798e-5 + 748e-5) * half * L**3,
        yaw_inertia=(39.2e-5 + 43.8e-5) * half * L**5,
    )


#: Mariner-class ship (the hull of ``MARINER_VOITKUNSKY``): L, B, T and the masses from
#: Chislett & Strøm-Tejsen (1965) via Fossen's mariner.m (m' = 798e-5, I' = 39.2e-5, added
#: −Y_v̇' = 748e-5, −N_ṙ' = 43.8e-5); δ = ∇/(LBT) = 0.542 from m' — *below* the range of eq.
#: (5)-(7), so eq. (5)-(7) warn for it. Rudder area (1.7 % of L·T), aspect ratio 1.6 and
#: windage area (0.8 L·T, centred amidships) are assumed typical values, not Mariner data.
MARINER_PARTICULARS: ShipParticulars = _mariner()


class CompensationSummary(NamedTuple):
    """Everything the ``seahelm compensate`` command prints (SI units, radians)."""

    cx: float
    cy: float
    cm: float
    wave_length: float
    wave_celerity: float
    surge: float
    sway: float
    yaw: float
    arm: float
    apparent_wind_speed: float
    apparent_wind_angle: float
    wind_force: float
    wind_moment: float
    wind_drift: float
    wave_drift: float
    resistance_centre: float
    delta_k_wind: float
    delta_k_wave: float
    delta_k: float


def compensation_summary(
    ship: ShipParticulars,
    *,
    wind_speed: float,
    wind_angle: float,
    wave_height: float,
    wave_angle: float,
    wave_length: float | None = None,
    a0: float = 3.3,
    a1: float = 1.0,
    strict: bool | None = None,
) -> CompensationSummary:
    """Wave coefficients, wave and wind loads, drift angles and δ_k for one ship and sea.

    Parameters
    ----------
    ship : ShipParticulars
    wind_speed : float
        True wind speed [m/s] (sets the wave length by eq. (2) unless ``wave_length`` is given).
    wind_angle : float
        Bearing the true wind comes from, relative to the bow [rad] (positive from starboard);
        the apparent wind follows from the ship's speed.
    wave_height : float
        h3% [m].
    wave_angle : float
        q_w of the waves [rad] (bearing they come from, relative to the bow).
    wave_length : float, optional
        λ [m]; default 1.55 τ² of eq. (2) from the true wind speed (λ = L when there is no
        wind; it only matters when ``wave_height`` > 0).
    a0, a1 : float
        A0, A1 of eq. (8)-(10); V_n = −V cos q_w (ship speed along the wave travel).
    strict : bool, optional
        Validity-range warnings become errors.
    """
    from ..environment import wave_forces as wf
    from ..environment import wind as wd

    L, V = ship.length, ship.speed
    check_nonnegative("wind_speed", wind_speed, "m/s")
    check_nonnegative("wave_height", wave_height, "m")
    coeffs = wf.wave_force_coefficients(
        L, ship.beam, ship.draft, ship.block_coefficient, strict=strict
    )
    if wave_length is None:
        wave_length = float(wd.wave_length_from_wind(wind_speed)) if wind_speed > 0 else L
    check_positive("wave_length", wave_length, "m")
    vw = float(wd.deep_water_celerity(wave_length))
    forces = wf.wave_forces(
        wave_angle, wave_height, wave_length, coeffs, length=L,
        speed_along_waves=-V * math.cos(wave_angle), wave_celerity=vw, a0=a0, a1=a1, strict=strict,
    )
    arm = wf.wave_force_arm(wave_angle, coeffs, length=L)
    app = wd.apparent_wind(wind_speed, wind_angle, V, 0.0)
    y_a = wd.wind_lateral_force(app.speed, app.angle, ship.s_a)
    n_a = wd.wind_yaw_moment(app.speed, app.angle, ship.s_a, length=L, sail_centre=ship.sail_centre)
    common = dict(speed=V, underwater_area=ship.s_h, block_coefficient=ship.block_coefficient,
                  draft=ship.draft, length=L)
    alpha_wind = drift_angle(y_a, **common)
    alpha_wave = drift_angle(forces.sway, **common)
    l_lr = lateral_resistance_centre(ship.t_fore, ship.t_aft)
    dk_wind = wind_compensation(
        wind_speed=app.speed, wind_angle=app.angle, drift=alpha_wind, speed=V, length=L,
        draft=ship.draft, block_coefficient=ship.block_coefficient, rudder_area=ship.s_p,
        rudder_aspect_ratio=ship.rudder_aspect_ratio, windage_area=ship.s_a,
        underwater_area=ship.s_h, sail_centre=ship.sail_centre, resistance_centre=l_lr,
    )
    dk_wave = wave_compensation(forces.yaw, speed=V, length=L, rudder_area=ship.s_p,
                                rudder_aspect_ratio=ship.rudder_aspect_ratio)
    f = float
    return CompensationSummary(
        f(coeffs.cx), f(coeffs.cy), f(coeffs.cm), f(wave_length), vw,
        f(forces.surge), f(forces.sway), f(forces.yaw), f(arm),
        f(app.speed), f(app.angle), f(y_a), f(n_a), f(alpha_wind), f(alpha_wave), f(l_lr),
        f(dk_wind), f(dk_wave), f(dk_wind + dk_wave),
    )


# ------------------------------------------------------------------------------------------
# block 7 from the ship model
# ------------------------------------------------------------------------------------------
class ModelCompensation(NamedTuple):
    """The compensating rudder angle computed from the ship model (radians).

    ``delta_k_wind`` balances the wind loads alone (channel 5 of Fig. 1), ``delta_k_wave`` is
    the extra angle the wave loads need on top (channel 6), ``delta_k`` their sum (the steady
    rudder angle under both) and ``drift`` the steady drift angle β under both.
    """

    delta_k_wind: float
    delta_k_wave: float
    delta_k: float
    drift: float


def model_compensation(
    summary: CompensationSummary,
    *,
    ship: ShipParticulars | None = None,
    vessel_params: Any = None,
) -> ModelCompensation:
    """δ_k from the ship model: the steady rudder angle that balances the loads of ``summary``.

    The wind force and moment and the wave sway force and yaw moment that
    :func:`compensation_summary` computes (Lvov 2014, eq. (9)-(12); the paper's signs, turned
    into seahelm's body axes) are converted to the Voitkunsky model's normalised disturbances
    (yaw moment / (I_z − N_ṙ), sway force / ((m − Y_v̇) V)) and its steady state with ω = 0 is
    solved for β and δ. This is the δ_k that :func:`wind_wave_scenario` feeds the autopilot by
    default (:data:`MODEL_BALANCE`); eq. (12)/(14) as printed have the wrong sign on the
    Mariner (module docstring).

    Parameters
    ----------
    summary : CompensationSummary
        The loads, from :func:`compensation_summary` for ``ship``.
    ship : ShipParticulars, optional
        Its masses convert the loads (default: the Mariner particulars); ``sway_mass`` and
        ``yaw_inertia`` must be > 0.
    vessel_params : VoitkunskyParams, optional
        The ship model (default: the Mariner set, ``MARINER_VOITKUNSKY``).

    Returns
    -------
    ModelCompensation

    Raises
    ------
    ParameterError
        If the ship's masses are not given or the model is not course-stable.
    """
    from ..vessels.voitkunsky import MARINER_VOITKUNSKY

    ship = MARINER_PARTICULARS if ship is None else ship
    vp = MARINER_VOITKUNSKY if vessel_params is None else vessel_params
    if ship.sway_mass <= 0 or ship.yaw_inertia <= 0:
        raise ParameterError("`ship.sway_mass` and `ship.yaw_inertia` must be > 0 [kg, kg·m²]")
    m_scale, f_scale = ship.yaw_inertia, ship.sway_mass * ship.speed
    # seahelm body axes: the negatives of the paper-signed loads
    md_wind, fd_wind = -summary.wind_moment / m_scale, -summary.wind_force / f_scale
    md_wave, fd_wave = -summary.yaw / m_scale, -summary.sway / f_scale
    _, dk_w = steady_course_keeping(vp, np.asarray(md_wind), np.asarray(fd_wind))
    beta_t, dk_t = steady_course_keeping(vp, np.asarray(md_wind + md_wave),
                                  np.asarray(fd_wind + fd_wave))
    return ModelCompensation(float(dk_w), float(dk_t - dk_w), float(dk_t), float(beta_t))


# ------------------------------------------------------------------------------------------
# block 7: how δ_k is computed — the corrected way and the printed one, as objects
# ------------------------------------------------------------------------------------------
class CompensationChannels(NamedTuple):
    """What block 7 feeds the autopilot: the two δ_k channels and the drift for the course
    setter (radians)."""

    delta_k_wind: float
    delta_k_wave: float
    drift: float


class DeltaKMethod(abc.ABC):
    """How block 7 of Fig. 1 turns the compensators' loads into δ_k (a registry entry)."""

    #: Registry name (:data:`DELTA_K_METHODS`).
    name: str = ""

    @abc.abstractmethod
    def channels(self, summary: CompensationSummary,
                 model: ModelCompensation) -> CompensationChannels:
        """The wind and wave channels of δ_k and the drift angle for the course setter.

        Parameters
        ----------
        summary : CompensationSummary
            The paper's chain for the ship and sea (:func:`compensation_summary`).
        model : ModelCompensation
            The ship model's steady balance under the same loads (:func:`model_compensation`).

        Returns
        -------
        CompensationChannels
        """


class ModelBalance(DeltaKMethod):
    """δ_k from the ship model (the default): the rudder angle that balances the wind loads
    (channel 5) and the extra angle for the wave loads (channel 6) in the model's steady state,
    with the steady drift angle β for the course setter."""

    name = "model"

    def channels(self, summary: CompensationSummary,
                 model: ModelCompensation) -> CompensationChannels:
        """The model's steady balancing rudder angles and drift.

        Parameters
        ----------
        summary : CompensationSummary
            The paper's chain (not used: the loads are already in ``model``).
        model : ModelCompensation
            The ship model's steady balance (:func:`model_compensation`).

        Returns
        -------
        CompensationChannels
        """
        return CompensationChannels(model.delta_k_wind, model.delta_k_wave, model.drift)


class PrintedEq14(DeltaKMethod):
    """δ_k as printed: eq. (12) (channel 5) and the wave term of eq. (14) (channel 6), with
    the paper's wind and wave drift angles. Its sign is wrong for the Mariner (module
    docstring); kept to reproduce the paper."""

    name = "paper"

    def channels(self, summary: CompensationSummary,
                 model: ModelCompensation) -> CompensationChannels:
        """The printed eq. (12)/(14) angles and the paper's drift.

        Parameters
        ----------
        summary : CompensationSummary
            The paper's chain (:func:`compensation_summary`).
        model : ModelCompensation
            The ship model's steady balance (not used).

        Returns
        -------
        CompensationChannels
        """
        return CompensationChannels(summary.delta_k_wind, summary.delta_k_wave,
                                    summary.wind_drift + summary.wave_drift)


#: δ_k from the ship model's steady balance (``"model"``, the default).
MODEL_BALANCE: DeltaKMethod = ModelBalance()
#: δ_k of eq. (12)/(14) as printed (``"paper"``).
PRINTED_EQ14: DeltaKMethod = PrintedEq14()
#: The ways block 7 computes δ_k, by name.
DELTA_K_METHODS: Mapping[str, DeltaKMethod] = MappingProxyType(
    {m.name: m for m in (MODEL_BALANCE, PRINTED_EQ14)})


def get_delta_k_method(method: str | DeltaKMethod) -> DeltaKMethod:
    """A way of computing δ_k by name (a key of :data:`DELTA_K_METHODS`) or the object itself.

    Parameters
    ----------
    method : str or DeltaKMethod
        ``"model"``, ``"paper"``, or a :class:`DeltaKMethod`.

    Returns
    -------
    DeltaKMethod

    Raises
    ------
    ValueError
        If ``method`` is an unknown name (the message lists the valid ones).
    """
    return lookup("delta_k_method", DELTA_K_METHODS, method, DeltaKMethod)


# ------------------------------------------------------------------------------------------
# closed loop of Fig. 1 on the Voitkunsky model
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class WindWaveCase:
    """One weather case of the course-keeping scenario (SI units, radians).

    Attributes
    ----------
    name : str
    wind_speed : float
        True wind speed W [m/s].
    wind_angle : float
        Bearing the wind comes from, relative to the course to steer [rad].
    wave_height : float
        h3% [m] (0: no waves).
    wave_angle : float
        Bearing the waves come from, relative to the course to steer [rad].
    irregular : bool
        Irregular sea: the wave loads of eq. (8)-(10) with (h3%/2)² replaced by the
        instantaneous ζ(t)² scaled to the same mean, ζ a Rakhmanin–Firsov sea sampled by
        :mod:`seahelm.environment.shaping` (quasi-steady, no encounter-frequency correction).
    onset : float
        Time [s] at which wind and waves set in (a step; the compensators see it at once).
    a1 : float
        A1 of eq. (8)-(10).
    """

    name: str
    wind_speed: float = 0.0
    wind_angle: float = 0.0
    wave_height: float = 0.0
    wave_angle: float = 0.0
    irregular: bool = False
    onset: float = 30.0
    a1: float = 1.0


def wind_wave_scenario(
    case: WindWaveCase,
    *,
    ship: ShipParticulars | None = None,
    vessel_params: Any = None,
    course: float = 0.0,
    t_final: float = 900.0,
    dt: float = 0.1,
    delta_k_method: str | DeltaKMethod = "model",
    seed: int = 0,
    strict: bool | None = None,
) -> dict[str, Any]:
    """Inputs of :func:`seahelm.simulation.engine.simulate` for the closed loop of Fig. 1.

    The Voitkunsky model (default: the Mariner set) is loaded by the wind force and moment
    of eq. (12) and the wave sway force and yaw moment of eq. (9)-(10), converted to the
    model's normalised disturbances (yaw moment / (I_z − N_ṙ), sway force / ((m − Y_v̇) U)),
    evaluated on the course to steer (small heading errors). The course setter gives the
    heading ψ* = C + β (drift from the same steady balance that gives δ_k), and the two
    compensation channels of :data:`COMPENSATED_PID` get

    * ``delta_k_method="model"`` (:data:`MODEL_BALANCE`) — the rudder angle that balances the
      wind loads (channel 5) and the extra angle for the wave loads (channel 6) in the ship
      model's steady state;
    * ``delta_k_method="paper"`` (:data:`PRINTED_EQ14`) — eq. (12) (channel 5) and the wave
      term of eq. (14) (channel 6) as printed (module docstring), with the paper's drift angles.

    Parameters
    ----------
    case : WindWaveCase
        The weather case (wind and wave speeds [m/s], heights [m], angles [rad], onset [s]).
    ship : ShipParticulars, optional
        Hull, rudder and loading data (default: the Mariner particulars).
    vessel_params : VoitkunskyParams, optional
        Parameters of the simulated Voitkunsky model (default: the Mariner set).
    course : float, optional
        Wanted course over ground C [rad] (default 0).
    t_final : float, optional
        Duration [s] (default 900).
    dt : float, optional
        Integration step [s] (default 0.1).
    delta_k_method : str or DeltaKMethod, optional
        How the compensating rudder angles are computed: a key of :data:`DELTA_K_METHODS`
        (``"model"``, the default, or ``"paper"``) or a :class:`DeltaKMethod`, see above.
    seed : int, optional
        Seed of the irregular-wave realisation (default 0).
    strict : bool, optional
        Raise instead of warning outside the validity ranges of the empirical formulas
        (default: the global strict mode).

    Returns
    -------
    dict
        ``model, params, x0, t_final, dt, reference, disturbance, actuator, actuator_params,
        controller, controller_dt`` for ``simulate(**...)`` (minus ``controller_params``),
        plus ``info`` (loads, drift, δ_k, the course to steer).
    """
    from ..actuators.servo import RUDDER_SERVO, ServoParams
    from ..vessels.voitkunsky import MARINER_VOITKUNSKY, VOITKUNSKY

    method = get_delta_k_method(delta_k_method)
    ship = MARINER_PARTICULARS if ship is None else ship
    vp = MARINER_VOITKUNSKY if vessel_params is None else vessel_params
    if ship.sway_mass <= 0 or ship.yaw_inertia <= 0:
        raise ParameterError("`ship.sway_mass` and `ship.yaw_inertia` must be > 0 [kg, kg·m²]")
    V = ship.speed
    n = int(round(t_final / dt))
    t = np.arange(n + 1) * dt
    on = (t >= case.onset).astype(float)

    summ = compensation_summary(
        ship, wind_speed=case.wind_speed, wind_angle=case.wind_angle,
        wave_height=case.wave_height, wave_angle=case.wave_angle, a1=case.a1, strict=strict,
    )
    # seahelm body axes: the negatives of the paper-signed loads
    n_wind, y_wind = -summ.wind_moment, -summ.wind_force
    n_wave, y_wave = -summ.yaw, -summ.sway
    m_scale, f_scale = ship.yaw_inertia, ship.sway_mass * V
    md_wind, fd_wind = n_wind / m_scale, y_wind / f_scale
    md_wave, fd_wave = n_wave / m_scale, y_wave / f_scale

    wave_mod = np.ones_like(t)
    if case.irregular and case.wave_height > 0:
        from ..environment.shaping import shaping_filter
        from ..environment.spectra import spectrum_from_wave_height

        filt = shaping_filter(spectrum_from_wave_height("rakhmanin-firsov-2", case.wave_height),
                              ["ordinate"])
        zeta = filt.sample(n_steps=n + 1, dt=dt, seed=seed, runs=1).values[0, :, 0]
        wave_mod = zeta**2 / float(filt.output_variance()[0])
    dist = np.zeros((n + 1, VOITKUNSKY.n_disturbances))
    dist[:, 0] = on * (md_wind + md_wave * wave_mod)
    dist[:, 1] = on * (fd_wind + fd_wave * wave_mod)

    model = model_compensation(summ, ship=ship, vessel_params=vp)
    dk_t = model.delta_k
    ch_wind, ch_wave, drift = method.channels(summ, model)
    heading = float(course_to_steer(course, drift))
    ref = np.zeros((n + 1, 3))
    ref[:, 0] = heading
    ref[:, 1] = on * ch_wind
    ref[:, 2] = on * ch_wave
    x0 = np.array([0.0, 0.0, heading, 0.0, 0.0])
    info = dict(summary=summ, heading_to_steer=heading, drift=drift,
                delta_k_wind=ch_wind, delta_k_wave=ch_wave, delta_k=ch_wind + ch_wave,
                steady_rudder=dk_t, steady_drift=model.drift, onset=case.onset)
    return dict(model=VOITKUNSKY, params=vp, x0=x0, t_final=t_final, dt=dt, reference=ref,
                disturbance=dist, actuator=RUDDER_SERVO, actuator_params=ServoParams(),
                controller=COMPENSATED_PID, controller_dt=1.0, info=info)

