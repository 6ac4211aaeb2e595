"""Shushlyapin, Karapetyan, Bezuglaya & Afonina (2017): the catamaran's strong manoeuvres —
the paper's reproduction.

The reusable parts are components: the research catamaran with two azimuth thrusters
(eq. (1)-(11), (22)) and its two parameter sets, the MathCAD listing of Table 1 and a physically
consistent one, in :mod:`seahelm.vessels.catamaran` (catalog names
``shushlyapin2017-listing`` and ``shushlyapin2017-consistent``); the general final-state method
(eq. (12)-(15)) in :mod:`seahelm.control.final_state_general`; the compiled yaw-rate and heading
controllers (eq. (17)-(23)) in :mod:`seahelm.control.final_state`; the introduction's baselines
in :mod:`seahelm.control.baselines`. This module holds what only reproducing the paper needs:

* the ship as the paper prints it, as parameter-set objects next to the listing's: registry
  :data:`SHIP_VARIANTS` with :data:`LISTING` (``"listing"``, the model that produced the
  figures), :data:`CONSISTENT` (``"consistent"``), :data:`PRINTED_SWAY_EQ3`
  (``"printed-eq3"``: the sway equation without the lateral resistance) and
  :data:`PRINTED_RESISTANCE_EQ6_7` (``"printed-eq6-7"``: the resistance with the extra
  factor V); :func:`get_ship_variant` looks one up;
* :data:`PUBLISHED` — the paper's published behaviour, each with the scenario of
  ``examples/`` that reproduces it, and :func:`steady_turn_comparison`, the published steady
  turns next to the model's (thruster angle and turning-circle diameter at ω*, no
  simulation).

Errata these objects carry (verified by simulation against the published figures): the
printed sway equation omits −R_y, so ω* = 0.08 rad/s is unreachable with it (the steady turn
saturates near 0.071 rad/s); printed eq. (6)-(7) carry an extra factor V that the listing does
not; the listing's J_zz = 0.05/1000 · rov · D · L² is about 1000× below a physical value
(≈ 4.8e6 kg·m²) and M_D mixes kN·m with N·m — the paper's strong oscillations at constant δ
come from this, so the listing is the reproduction set and :data:`CONSISTENT` the physical one;
"steady δ = 0.6 rad" for ω* = 0.00072 rad/s is 0.6 degrees.

References
----------
Shushlyapin, E. A., Karapetyan, V. A., Bezuglaya, A. E., Afonina, A. A. (2017). Nonlinear
regulators for keeping a ship on a given trajectory in "strong" manoeuvres. SPIIRAS
Proceedings 4(53), 179-196, eq. (1)-(23), Table 1 and the figures.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import NamedTuple

from ..errors import ParameterError
from ..registry import lookup
from ..vessels.catamaran import CatamaranParams, consistent_params, paper_params, steady_turn

__all__ = [
    "LISTING",
    "CONSISTENT",
    "PRINTED_SWAY_EQ3",
    "PRINTED_RESISTANCE_EQ6_7",
    "SHIP_VARIANTS",
    "get_ship_variant",
    "PublishedResult",
    "PUBLISHED",
    "SteadyTurnComparison",
    "steady_turn_comparison",
]

#: The MathCAD listing of Table 1 (T_m = 1.55 m): the model that produced the paper's figures.
LISTING: CatamaranParams = paper_params()
#: The listing's ship with a physical J_zz = D (L/4)², ρ = 1025 kg/m³ and π_l = π.
CONSISTENT: CatamaranParams = consistent_params()
#: The listing with the sway equation (3) as printed: no lateral resistance −R_y
#: (``sway_resistance`` = 0). ω* = 0.08 rad/s cannot be reached.
PRINTED_SWAY_EQ3: CatamaranParams = paper_params(sway_resistance=0.0)
#: The listing with the resistance of eq. (6)-(7) as printed, R = 2000 R_K(V) V cos β
#: (``resistance_speed_power`` = 1): the straight-run speed drops from 4.42 to 3.13 m/s.
PRINTED_RESISTANCE_EQ6_7: CatamaranParams = paper_params(resistance_speed_power=1.0)

#: The ship's parameter sets by name: ``"listing"`` (the default of the reproduction),
#: ``"consistent"``, ``"printed-eq3"`` and ``"printed-eq6-7"``.
SHIP_VARIANTS: Mapping[str, CatamaranParams] = MappingProxyType({
    "listing": LISTING,
    "consistent": CONSISTENT,
    "printed-eq3": PRINTED_SWAY_EQ3,
    "printed-eq6-7": PRINTED_RESISTANCE_EQ6_7,
})


def get_ship_variant(name: str | CatamaranParams) -> CatamaranParams:
    """A parameter set of :data:`SHIP_VARIANTS` by name, or the parameters themselves.

    Parameters
    ----------
    name : str or CatamaranParams
        ``"listing"``, ``"consistent"``, ``"printed-eq3"``, ``"printed-eq6-7"`` or parameters.

    Returns
    -------
    CatamaranParams

    Raises
    ------
    ParameterError
        For an unknown name (the message lists the valid ones).
    """
    return lookup("catamaran variant", SHIP_VARIANTS, name, CatamaranParams,
                  error=ParameterError)


class PublishedResult(NamedTuple):
    """One behaviour the paper publishes, and where seahelm reproduces it."""

    #: What is claimed, in words.
    claim: str
    #: The published value(s), as printed (with the erratum in brackets where there is one).
    published: str
    #: The example scenario (``examples/``) or test that reproduces it.
    reproduced_by: str


#: The paper's published behaviour (listing parameters, controller eq. (21) with
#: T_u·h = 0.01 s² unless stated).
PUBLISHED: tuple[PublishedResult, ...] = (
    PublishedResult("yaw rate 0.08 rad/s tracked", "δ ≈ 85°, turning circle ≈ 95 m",
                    "examples/catamaran_turn_0p08.toml"),
    PublishedResult("constant δ = 0.6 rad, open loop", "strongly oscillatory motion",
                    "examples/catamaran_constant_thruster.toml"),
    PublishedResult("yaw rate 0.00072 rad/s tracked",
                    "steady δ = 0.6 rad (a misprint: 0.6°), settling ≈ 50 s",
                    "examples/catamaran_yaw_rate_0p00072.toml"),
    PublishedResult("heading 0.8 rad with ω* = 0.0022 rad/s, eq. (17)",
                    "reached to three decimals", "examples/catamaran_heading_0p8.toml"),
    PublishedResult("sinusoidal ω*(t) = 0.0072 sin(8πt/t_f)", "tracked closely (t_f ≳ 1000 s)",
                    "examples/catamaran_sine.toml"),
)


class SteadyTurnComparison(NamedTuple):
    """A published steady turn next to the model's."""

    #: Yaw rate ω* of the turn [rad/s].
    yaw_rate: float
    #: Published thruster angle [deg] (the paper's "0.6 rad" read as degrees).
    published_thruster_angle: float
    #: Published turning-circle diameter [m] (NaN where the paper gives none).
    published_diameter: float
    #: The model's steady thruster angle δ [deg].
    thruster_angle: float
    #: The model's turning-circle diameter 2V/ω [m].
    diameter: float


_PUBLISHED_TURNS = ((0.08, 85.0, 95.0), (0.00072, 0.6, math.nan))


def steady_turn_comparison(ship: str | CatamaranParams = "listing"
                           ) -> tuple[SteadyTurnComparison, ...]:
    """The paper's published steady turns next to the model's (no simulation).

    Parameters
    ----------
    ship : str or CatamaranParams, optional
        A name of :data:`SHIP_VARIANTS` (default ``"listing"``) or parameters.

    Returns
    -------
    tuple of SteadyTurnComparison
        One row per published turn: ω* = 0.08 rad/s (δ ≈ 85°, ≈ 95 m) and ω* = 0.00072 rad/s
        (δ = 0.6°).

    Raises
    ------
    ParameterError
        If a published yaw rate has no steady turn for ``ship`` (e.g. 0.08 rad/s with the
        printed sway equation, :data:`PRINTED_SWAY_EQ3`).
    """
    params = get_ship_variant(ship)
    rows = []
    for w, delta, diameter in _PUBLISHED_TURNS:
        vx, vy, d = steady_turn(params, w)
        rows.append(SteadyTurnComparison(w, delta, diameter, math.degrees(d),
                                         2.0 * math.hypot(vx, vy) / w))
    return tuple(rows)
