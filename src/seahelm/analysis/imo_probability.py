"""The probability of passing each IMO MSC.137(76) criterion over an ensemble of ships.

An uncertain ship — an identification's posterior, a Monte-Carlo of its coefficients — is an
ensemble of parameter sets. :func:`imo_probabilities` runs the manoeuvres of the IMO check
(:func:`seahelm.analysis.imo.imo_check`: 35° turning and 10° turning both sides, the 10/10 and
20/20 zig-zags both sides) for the whole ensemble in **one batch each**, evaluates every
criterion for every member with the limits of :mod:`seahelm.analysis.imo`, and gives the
fraction that passes each criterion and the whole check with a Wilson score interval (Wilson
1927; it stays inside [0, 1] and keeps its coverage for fractions near 0 or 1, where the normal
interval does not). A member whose manoeuvres did not complete (a diverged run, an event not
reached within 1.5 times the first member's durations) is excluded from the fractions and
counted. The stopping criterion (track reach ≤ 15 L,
:func:`seahelm.analysis.maneuvers.crash_stop`, one batch per chunk too) is part of the check when every member can stop (an ``mmg`` ship with a
propeller, given the engine estimate of :func:`~seahelm.analysis.maneuvers.stopping_ship`);
otherwise it is left out and said so.

References
----------
IMO (2002). Resolution MSC.137(76), Standards for ship manoeuvrability.
Wilson, E.B. (1927). Probable inference, the law of succession, and statistical inference.
J. Am. Stat. Assoc. 22(158), 209–212.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError

#: Members simulated together (a bound on the memory of the recorded manoeuvres).
CHUNK = 500

__all__ = ["ImoProbabilities", "imo_probabilities", "wilson_interval", "monte_carlo_ships",
           "UNCERTAIN_COEFFICIENTS", "DEFAULT_UNCERTAINTY"]


def wilson_interval(passed: int, total: int, level: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion.

    Parameters
    ----------
    passed, total : int
        Successes and trials (total ≥ 1).
    level : float
        Confidence level in (0, 1).

    Returns
    -------
    (float, float)
    """
    from scipy.stats import norm

    if total < 1:
        return (math.nan, math.nan)
    z = float(norm.ppf(0.5 + level / 2))
    p = passed / total
    den = 1 + z * z / total
    centre = (p + z * z / (2 * total)) / den
    half = z * math.sqrt(p * (1 - p) / total + z * z / (4 * total * total)) / den
    return (max(0.0, centre - half), min(1.0, centre + half))


@dataclasses.dataclass(frozen=True)
class ImoProbabilities:
    """Pass fractions of the IMO criteria over an ensemble.

    Attributes
    ----------
    rows : tuple of dict
        One per criterion and side: ``ability``, ``criterion``, ``side``, ``passed``,
        ``total``, ``probability``, ``ci_low``, ``ci_high``, ``median`` (of the value), ``limit``,
        ``unit``.
    passed, total, excluded : int
        Members passing every criterion, members counted, members excluded (incomplete).
    probability, ci_low, ci_high : float
        Of passing every criterion.
    level : float
        Confidence level of the intervals.
    """

    rows: tuple[dict[str, Any], ...]
    passed: int
    total: int
    excluded: int
    probability: float
    ci_low: float
    ci_high: float
    level: float
    stopping_note: str = ""

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON).

        Returns
        -------
        dict
        """
        return {"criteria": list(self.rows), "passed": self.passed, "total": self.total,
                "excluded": self.excluded, "probability": self.probability,
                "ci_low": self.ci_low, "ci_high": self.ci_high, "confidence_level": self.level,
                "note": self.stopping_note or "stopping (track reach) evaluated"}


def imo_probabilities(ships: Sequence[Any], *, level: float = 0.95, dt: float | None = None
                      ) -> ImoProbabilities:
    """Pass fractions of every IMO criterion over ``ships`` (module docstring).

    Parameters
    ----------
    ships : sequence of Ship
        The ensemble (same length, test speed and steering gear, as a posterior's members).
    level : float, optional
        Confidence level of the Wilson intervals.
    dt : float, optional
        Integration step [s] (default: the manoeuvres').

    Returns
    -------
    ImoProbabilities

    Raises
    ------
    ParameterError
        An empty ensemble, members of different lengths or steering-gear limits.
    """
    from .imo import (
        ADVANCE_LIMIT,
        INITIAL_TURNING_LIMIT,
        TACTICAL_DIAMETER_LIMIT,
        ZIGZAG_20_FIRST_OVERSHOOT_LIMIT,
        imo_overshoot_limits,
    )
    from .maneuvers import maneuver_ship, turning_circle, zigzag

    members = [maneuver_ship(s) for s in ships]
    if not members:
        raise ParameterError("no ships in the ensemble", field="ships")
    lengths = {round(s.length, 9) for s in members}
    gears = {round(s.max_rudder, 12) for s in members}
    if len(lengths) > 1 or len(gears) > 1:
        raise ParameterError("the members of an ensemble must share their length and "
                             "steering-gear limit", field="ships")
    if not 0 < level < 1:
        raise ParameterError(f"must be in (0, 1), got {level!r}", field="level")
    hard = min(math.radians(35.0), members[0].max_rudder)
    rudders = np.array([hard, math.radians(10.0)])
    pairs = np.radians([10.0, 20.0])
    # the durations of the first member's manoeuvres, with room (× 1.5), for all: estimating
    # them member by member (a steady turn each) would cost more than the ensemble's runs
    first_turn = turning_circle(members[0], rudders, sides=(1, -1), dt=dt,
                                heading_change=math.pi).metrics
    t_turn = 1.5 * first_turn.attrs["t_final"]
    t_zz = 1.5 * zigzag(members[0], pairs, pairs, sides=(1, -1), dt=dt).metrics.attrs["t_final"]
    L = members[0].length
    V = float(np.asarray(first_turn["approach_speed_value"].values).reshape(-1)[0])
    limits = imo_overshoot_limits(L / V)
    dt = float(first_turn.attrs["dt"])
    # records every ~L/(20 V) (at most 1 s), a whole number of steps: the overshoots are
    # extremes, found to about r·Δt²; every step would be gigabytes for thousands of members
    record_dt = dt * max(1, math.floor(min(1.0, L / V / 20.0) / dt + 1e-9))
    names = [("turning", "advance", "L", ADVANCE_LIMIT),
             ("turning", "tactical diameter", "L", TACTICAL_DIAMETER_LIMIT),
             ("initial turning", "distance to 10 deg heading change", "L",
              INITIAL_TURNING_LIMIT),
             ("10/10 zig-zag", "first overshoot", "deg", math.degrees(limits.first)),
             ("10/10 zig-zag", "second overshoot", "deg", math.degrees(limits.second)),
             ("20/20 zig-zag", "first overshoot", "deg",
              math.degrees(ZIGZAG_20_FIRST_OVERSHOOT_LIMIT))]
    sides = ((1, "starboard"), (-1, "port"))
    parts: dict[tuple[str, str, str], list[np.ndarray]] = {
        (a, c, side): [] for side in ("starboard", "port") for a, c, _, _ in names}
    for start in range(0, len(members), CHUNK):
        chunk = members[start:start + CHUNK]

        def values(da: Any, n: int = len(chunk)) -> np.ndarray:
            return np.asarray(da.transpose("ship", ...).values if "ship" in da.dims
                              else da.values, dtype=float).reshape(n)

        turning = turning_circle(chunk, rudders, sides=(1, -1), dt=dt,
                                 heading_change=math.pi, t_final=t_turn,
                                 record_dt=record_dt).metrics
        zz = zigzag(chunk, pairs, pairs, sides=(1, -1), dt=dt, t_final=t_zz,
                    record_dt=record_dt).metrics
        for side, name in sides:
            t35 = turning.isel(rudder=0).sel(side=side)
            t10 = turning.isel(rudder=1).sel(side=side)
            z10 = zz.isel(pair=0).sel(side=side)
            z20 = zz.isel(pair=1).sel(side=side)
            got = (values(t35["advance"]) / L, values(t35["tactical_diameter"]) / L,
                   values(t10["distance_10"]) / L,
                   np.degrees(values(z10["overshoot"].sel(n=1))),
                   np.degrees(values(z10["overshoot"].sel(n=2))),
                   np.degrees(values(z20["overshoot"].sel(n=1))))
            for (a, c, _, _), v in zip(names, got):
                parts[(a, c, name)].append(v)
    checks = [(a, c, side, np.concatenate(parts[(a, c, side)]), limit, unit)
              for side in ("starboard", "port") for a, c, unit, limit in names]
    stopping_note = ""
    try:
        from .maneuvers import crash_stop, stopping_ship

        stoppers = [stopping_ship(s) for s in members]
    except ParameterError as exc:
        if exc.field != "ship":
            raise
        stopping_note = f"stopping (track reach) not evaluated: {exc.reason.lstrip(': ')}"
    else:
        from .imo import STOPPING_LIMIT

        reach = [np.asarray(crash_stop(stoppers[i:i + CHUNK], speed=V, dt=dt)
                            .metrics["track_reach"].values, dtype=float).reshape(-1)
                 for i in range(0, len(stoppers), CHUNK)]
        checks.append(("stopping", "track reach (full astern)", "-",
                       np.concatenate(reach) / L, STOPPING_LIMIT, "L"))
    complete = np.all([np.isfinite(c[3]) for c in checks], axis=0)
    total = int(complete.sum())
    rows = []
    every = np.ones(len(members), dtype=bool)
    for ability, criterion, side, vals, limit, unit in checks:
        ok = vals <= limit
        every &= ok
        passed = int(ok[complete].sum())
        lo, hi = wilson_interval(passed, total, level)
        rows.append({"ability": ability, "criterion": criterion, "side": side,
                     "passed": passed, "total": total,
                     "probability": passed / total if total else math.nan,
                     "ci_low": lo, "ci_high": hi, "limit": float(limit), "unit": unit,
                     "median": float(np.median(vals[complete])) if total else math.nan})
    passed_all = int(every[complete].sum())
    lo, hi = wilson_interval(passed_all, total, level)
    return ImoProbabilities(rows=tuple(rows), passed=passed_all, total=total,
                            excluded=len(members) - total,
                            probability=passed_all / total if total else math.nan,
                            ci_low=lo, ci_high=hi, level=level, stopping_note=stopping_note)


#: The coefficients an uncertain ship's default Monte-Carlo draws (their relative standard
#: deviation :data:`DEFAULT_UNCERTAINTY`), per model: the linear manoeuvring derivatives, whose
#: uncertainty dominates the IMO manoeuvres (examples/kvlcc2_imo_uncertainty.py).
UNCERTAIN_COEFFICIENTS: dict[str, tuple[str, ...]] = {
    "mmg": ("Y_v", "Y_r", "N_v", "N_r"),
    "mariner": ("Y_v", "Y_r", "N_v", "N_r"),
    "nomoto1": ("gain", "time_constant"),
    "nomoto2": ("gain", "t1", "t2", "t3"),
}

#: Default relative standard deviation of :data:`UNCERTAIN_COEFFICIENTS` (10 %).
DEFAULT_UNCERTAINTY = 0.10


def monte_carlo_ships(ship: Any, n: int, *, seed: int = 0, draws: Any = None,
                      uncertainty: float = DEFAULT_UNCERTAINTY) -> list[Any]:
    """``n`` copies of ``ship`` with drawn coefficients (one generator per sample, from
    ``SeedSequence(seed)``: any subset of samples has the values the whole set has).

    Parameters
    ----------
    ship : Ship
    n : int
        Samples (≥ 1).
    seed : int, optional
        The study's seed (≥ 0).
    draws : mapping of parameter name to Distribution, optional
        What to draw (:mod:`seahelm.numerics.sampling` distributions). Default: a normal
        distribution of relative standard deviation ``uncertainty`` around each of the
        model's :data:`UNCERTAIN_COEFFICIENTS`.
    uncertainty : float, optional
        Relative standard deviation of the default draws.

    Returns
    -------
    list of Ship
        Named ``<name> #i``.

    Raises
    ------
    ParameterError
        A bad ``n``, ``seed`` or ``uncertainty``; a draw on a parameter the ship does not have;
        a drawn value outside the parameter's range (naming the sample).
    """
    from ..numerics.sampling import draw_samples, get_distribution

    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ParameterError(f"must be a whole number >= 1, got {n!r}", field="n", value=n)
    if not (math.isfinite(uncertainty) and uncertainty > 0):
        raise ParameterError(f"must be > 0, got {uncertainty!r}", field="uncertainty",
                             value=uncertainty)
    names = ship.params.field_names()
    if draws is None:
        coefficients = UNCERTAIN_COEFFICIENTS.get(ship.model.name)
        if coefficients is None:
            raise ParameterError(f"no default uncertainty for model '{ship.model.name}': give "
                                 "the draws", field="draws")
        draws = {k: get_distribution("normal", mean=float(getattr(ship.params, k)),
                                     std=uncertainty * abs(float(getattr(ship.params, k))))
                 for k in coefficients}
    unknown = [k for k in draws if k not in names]
    if unknown:
        raise ParameterError(f"`{unknown[0]}` is not a parameter of model '{ship.model.name}'"
                             f" ({', '.join(names)})", field="draws")
    drawn = draw_samples(dict(draws), seed, np.arange(n))
    ships = []
    for i in range(n):
        values = {k: float(v[i]) for k, v in drawn.items()}
        try:
            ships.append(ship.replace(params=values, name=f"{ship.name} #{i}"))
        except ParameterError as exc:
            raise ParameterError(f"sample {i}: {exc} (drawn: "
                                 + ", ".join(f"{k} = {v:.6g}" for k, v in values.items()) + ")",
                                 field="draws", run=i) from None
    return ships
