"""The probability of passing each IMO MSC.137(76) criterion over an ensemble of ships.

An uncertain ship — an identification's posterior, a Monte-Carlo of its coefficients — is an
ensemble of parameter sets. :func:`imo_probabilities` runs the manoeuvres of the IMO check
(:func:`seahelm.analysis.imo.imo_check`: 35° turning and 10° turning both sides, the 10/10 and
20/20 zig-zags both sides) for the whole ensemble in **one batch each**, evaluates every
criterion for every member with the limits of :mod:`seahelm.analysis.imo`, and gives the
fraction that passes each criterion and the whole check with a Wilson score interval (Wilson
1927; it stays inside [0, 1] and keeps its coverage for fractions near 0 or 1, where the normal
interval does not). A member whose manoeuvres did not complete (a diverged run, an event not
reached) is excluded from the fractions and counted. The stopping criterion needs a model that
can stop and is not part of the ensemble check.

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

__all__ = ["ImoProbabilities", "imo_probabilities", "wilson_interval"]


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

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON).

        Returns
        -------
        dict
        """
        return {"criteria": list(self.rows), "passed": self.passed, "total": self.total,
                "excluded": self.excluded, "probability": self.probability,
                "ci_low": self.ci_low, "ci_high": self.ci_high, "confidence_level": self.level,
                "note": "stopping (track reach) not evaluated in the ensemble check"}


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
    turning = turning_circle(members, np.array([hard, math.radians(10.0)]), sides=(1, -1),
                             dt=dt, heading_change=math.pi).metrics
    zz = zigzag(members, np.radians([10.0, 20.0]), np.radians([10.0, 20.0]), sides=(1, -1),
                dt=dt).metrics
    L = members[0].length
    speed = np.asarray(turning["approach_speed_value"].values, dtype=float).reshape(-1)
    limits = imo_overshoot_limits(L / float(np.median(speed)))

    def values(da: Any) -> np.ndarray:
        return np.asarray(da.transpose("ship", ...).values, dtype=float).reshape(len(members))

    checks = []  # (ability, criterion, side, values, limit, unit)
    for side, name in ((1, "starboard"), (-1, "port")):
        t35 = turning.isel(rudder=0).sel(side=side)
        t10 = turning.isel(rudder=1).sel(side=side)
        checks += [("turning", "advance", name, values(t35["advance"]) / L, ADVANCE_LIMIT, "L"),
                   ("turning", "tactical diameter", name, values(t35["tactical_diameter"]) / L,
                    TACTICAL_DIAMETER_LIMIT, "L"),
                   ("initial turning", "distance to 10 deg heading change", name,
                    values(t10["distance_10"]) / L, INITIAL_TURNING_LIMIT, "L")]
    for side, name in ((1, "starboard"), (-1, "port")):
        z10 = zz.isel(pair=0).sel(side=side)
        z20 = zz.isel(pair=1).sel(side=side)
        checks += [("10/10 zig-zag", "first overshoot", name,
                    np.degrees(values(z10["overshoot"].sel(n=1))), math.degrees(limits.first),
                    "deg"),
                   ("10/10 zig-zag", "second overshoot", name,
                    np.degrees(values(z10["overshoot"].sel(n=2))),
                    math.degrees(limits.second), "deg"),
                   ("20/20 zig-zag", "first overshoot", name,
                    np.degrees(values(z20["overshoot"].sel(n=1))),
                    math.degrees(ZIGZAG_20_FIRST_OVERSHOOT_LIMIT), "deg")]
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
                            ci_low=lo, ci_high=hi, level=level)
