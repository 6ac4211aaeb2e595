"""The probability of passing each IMO MSC.137(76) criterion over an ensemble of ships.

An uncertain ship — an identification's posterior, a Monte-Carlo of its coefficients — is an
ensemble of parameter sets. :func:`imo_probabilities` runs the manoeuvres of the IMO check
(:func:`seahelm.analysis.imo.check.imo_check`: 35° turning and 10° turning both sides, the
10/10 and 20/20 zig-zags both sides) for the whole ensemble in **one batch each** (per chunk of
members), evaluates every criterion for every member with the limits of
:mod:`seahelm.analysis.imo.check`, and gives the
fraction that passes each criterion and the whole check with a Wilson score interval (Wilson
1927; it stays inside [0, 1] and keeps its coverage for fractions near 0 or 1, where the normal
interval does not). Every member's runs last :data:`FIRST_PASS` (1.15) times the time the
reference ship takes to the last event a criterion needs — the 180° heading change of the 35°
turning circles, the 10° heading change at 10° rudder, the 10/10's second and the 20/20's
first overshoot (two batches), dead in the water; the reference is by default the first
member — and the members that do not reach it run again, :data:`LAST_PASS` (1.5) times as
long; from :data:`LEARN` members of a manoeuvre on, the first pass lasts what minimises the
expected simulated time given their needs. A member whose manoeuvres did not complete (a diverged run, an event not reached in the
second pass, a zig-zag trigger never reached) is excluded from the fractions and counted, with the reason; so is a member
whose steady straight approach is not found (it is not run). The stopping criterion (track
reach ≤ 15 L, :func:`seahelm.analysis.maneuvers.crash_stop`, one batch per chunk too) is
part of the check when every member can stop (an ``mmg`` ship with a propeller, given the
engine estimate of :func:`~seahelm.analysis.maneuvers.stopping_ship`); otherwise it is left
out and said so.

References
----------
IMO (2002). Resolution MSC.137(76), Standards for ship manoeuvrability.
Wilson, E.B. (1927). Probable inference, the law of succession, and statistical inference.
J. Am. Stat. Assoc. 22(158), 209–212.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ...errors import ParameterError

#: Members simulated together (a bound on the memory of the recorded manoeuvres).
CHUNK = 500

__all__ = ["ImoProbabilities", "imo_probabilities", "probabilities_from_values",
           "wilson_interval", "monte_carlo_ships", "UNCERTAIN_COEFFICIENTS",
           "DEFAULT_UNCERTAINTY", "NO_APPROACH"]

#: How the reason of a member left out for want of a steady straight approach begins.
NO_APPROACH = "no straight approach"


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
    stopping_note : str
        Why the stopping criterion was left out ("" when it was evaluated).
    values : tuple of ndarray
        Per row (in the order of ``rows``), the value of every member in the order of the
        ensemble (NaN where it was not computed), in the row's unit.
    complete : ndarray of bool or None
        Per member, whether it was counted (every value computed).
    reasons : tuple of str
        Per member, why it was excluded ("" when it was counted): a reason beginning with
        :data:`NO_APPROACH` (its steady straight approach was not found, so nothing was run)
        or the criteria that have no value (an event not reached, a diverged run).
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
    values: tuple[np.ndarray, ...] = dataclasses.field(default=(), compare=False, repr=False)
    complete: np.ndarray | None = dataclasses.field(default=None, compare=False, repr=False)
    reasons: tuple[str, ...] = dataclasses.field(default=(), compare=False, repr=False)

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


def _last(times: Any, fallback: float) -> float:
    """The latest of the reference's event times [s] (``fallback``, its manoeuvre's whole
    duration, where an event was not reached)."""
    values = np.asarray(times.values, dtype=float)
    return float(values.max()) if np.isfinite(values).all() else float(fallback)


def imo_probabilities(ships: Sequence[Any], *, level: float = 0.95, dt: float | None = None,
                      reference: Any = None,
                      progress: Callable[[int, int], None] | None = None) -> ImoProbabilities:
    """Pass fractions of every IMO criterion over ``ships`` (module docstring).

    A member whose steady straight approach is not found is not run: it is excluded, with the
    reason (:attr:`ImoProbabilities.reasons`), as a member whose manoeuvres do not complete.

    Parameters
    ----------
    ships : sequence of Ship
        The ensemble (same length, test speed and steering gear, as a posterior's members).
    level : float, optional
        Confidence level of the Wilson intervals.
    dt : float, optional
        Integration step [s] (default: the manoeuvres').
    reference : Ship, optional
        The ship whose manoeuvres' durations (× 1.5) bound every member's runs, e.g. the
        nominal ship of a Monte-Carlo ensemble, so that a member's values do not depend on
        the ensemble it is run with (default: the first member with a straight approach).
    progress : callable(done, total), optional
        Called with the manoeuvres run so far and their number: the reference's, then each
        manoeuvre (turning, initial turning, the two zig-zags, stopping) of each chunk of
        :data:`CHUNK` members (a progress bar; the values do not depend on it).

    Returns
    -------
    ImoProbabilities

    Raises
    ------
    ParameterError
        An empty ensemble, members (or the reference) of different lengths, test speeds or
        steering-gear limits; an ensemble none of whose members has a straight approach.
    """
    from .check import (
        ADVANCE_LIMIT,
        INITIAL_TURNING_LIMIT,
        TACTICAL_DIAMETER_LIMIT,
        ZIGZAG_20_FIRST_OVERSHOOT_LIMIT,
        imo_overshoot_limits,
    )
    from ..maneuvers import maneuver_ship, turning_circle, zigzag

    members = [maneuver_ship(s) for s in ships]
    if not members:
        raise ParameterError("no ships in the ensemble", field="ships")
    given = members + ([] if reference is None else [maneuver_ship(reference)])
    for what, key in (("length", lambda s: round(s.length, 9)),
                      ("test speed (approach speed)", lambda s: round(s.approach_speed, 9)),
                      ("steering-gear limit", lambda s: round(s.max_rudder, 12))):
        if len({key(s) for s in given}) > 1:
            raise ParameterError(f"the members of an ensemble must share their length, test "
                                 f"speed and steering-gear limit; their {what} differ",
                                 field="ships")
    if not 0 < level < 1:
        raise ParameterError(f"must be in (0, 1), got {level!r}", field="level")
    everyone = members
    members, ref, no_approach = _with_approach(members, given[len(members):])
    kept = np.array([i for i in range(len(everyone)) if i not in no_approach], dtype=int)
    hard = min(math.radians(35.0), ref.max_rudder)
    rudders = np.array([hard, math.radians(10.0)])
    pairs = np.radians([10.0, 20.0])
    # every member runs FIRST_PASS times as long as the reference takes to the last event its
    # criteria need (the 180 deg heading change at 35 deg, the 10 deg change at 10 deg; the
    # 10/10's second and the 20/20's first overshoot; dead in the water), and the members
    # that do not reach it again LAST_PASS times as long (_Passes): estimating the durations
    # member by member (a steady turn each) would cost more than the runs, and the
    # manoeuvres' own durations (a steady turn, three overshoots) ran 2-4 times longer
    first_turn = turning_circle(ref, rudders, sides=(1, -1), dt=dt,
                                heading_change=math.pi).metrics
    ref_zz = zigzag(ref, pairs, pairs, sides=(1, -1), dt=dt).metrics
    t_turn = _last(first_turn["time_180"].isel(rudder=0), first_turn.attrs["t_final"])
    t_initial = _last(first_turn["time_10"].isel(rudder=1), first_turn.attrs["t_final"])
    overshoots = ref_zz["overshoot_time"]
    t_zz10 = _last(overshoots.isel(pair=0, n=1), ref_zz.attrs["t_final"])
    t_zz20 = _last(overshoots.isel(pair=1, n=0), ref_zz.attrs["t_final"])
    L = ref.length
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
    passes = _Passes(record_dt)
    stopping_note, stoppers = "", None
    try:
        from ..maneuvers import crash_stop, stopping_ship

        stoppers = [stopping_ship(s) for s in members]
    except ParameterError as exc:
        if exc.field != "ship":
            raise
        stopping_note = f"stopping (track reach) not evaluated: {exc.reason.lstrip(': ')}"
    n_chunks = -(-len(members) // CHUNK)
    done, total = 1, 1 + n_chunks * (4 + (stoppers is not None))

    def advanced(result: Any) -> Any:
        nonlocal done
        done += 1
        if progress is not None:
            progress(done, total)
        return result

    if progress is not None:
        progress(done, total)
    for start in range(0, len(members), CHUNK):
        chunk = members[start:start + CHUNK]

        def turning(ships: list[Any], t_final: float, rudder: float, event: str,
                    names: tuple[str, ...]) -> tuple[dict[str, np.ndarray], np.ndarray]:
            m = turning_circle(ships, rudder, sides=(1, -1), dt=dt, heading_change=math.pi,
                               t_final=t_final, record_dt=record_dt).metrics
            got = {f"{v}/{side}": _member_values(m[v].sel(side=s), len(ships))
                   for v in names for s, side in sides}
            return got, passes.needed([m[event].sel(side=s) for s, _ in sides], len(ships))

        def zigzags(ships: list[Any], t_final: float, pair: int, n: int
                    ) -> tuple[dict[str, np.ndarray], np.ndarray]:
            m = zigzag(ships, pairs[pair], pairs[pair], sides=(1, -1), dt=dt, t_final=t_final,
                       record_dt=record_dt, check_reachable=False).metrics
            got = {f"overshoot {k}/{side}": _member_values(
                m["overshoot"].sel(side=s, n=k), len(ships)) for k in range(1, n + 1)
                for s, side in sides}
            return got, passes.needed([m["overshoot_time"].sel(side=s, n=n) for s, _ in sides],
                                      len(ships))

        t35 = advanced(passes.run("turning", lambda s, t: turning(
            s, t, rudders[0], "time_180", ("advance", "tactical_diameter")), chunk, t_turn))
        t10 = advanced(passes.run("initial turning", lambda s, t: turning(
            s, t, rudders[1], "time_10", ("distance_10",)), chunk, t_initial))
        z10 = advanced(passes.run("10/10", lambda s, t: zigzags(s, t, 0, 2), chunk, t_zz10))
        z20 = advanced(passes.run("20/20", lambda s, t: zigzags(s, t, 1, 1), chunk, t_zz20))
        for side, name in sides:
            got = (t35[f"advance/{name}"] / L, t35[f"tactical_diameter/{name}"] / L,
                   t10[f"distance_10/{name}"] / L,
                   np.degrees(z10[f"overshoot 1/{name}"]), np.degrees(z10[f"overshoot 2/{name}"]),
                   np.degrees(z20[f"overshoot 1/{name}"]))
            for (a, c, _, _), v in zip(names, got):
                parts[(a, c, name)].append(v)
    checks = [(a, c, side, np.concatenate(parts[(a, c, side)]), limit, unit)
              for side in ("starboard", "port") for a, c, unit, limit in names]
    if stoppers is not None:
        from .check import STOPPING_LIMIT

        ref_stop = crash_stop(stopping_ship(ref), speed=V, dt=dt).metrics
        t_stop = _last(ref_stop["time_dead"], ref_stop.attrs["t_final"])

        def stops(ships: list[Any], t_final: float) -> tuple[dict[str, np.ndarray], np.ndarray]:
            # recorded as the other manoeuvres (every step: 6x the memory and 1.6x the time
            # for track reaches that differ by ~2e-6 relative, measured on the KVLCC2 L7)
            m = crash_stop(ships, speed=V, dt=dt, t_final=t_final, record_dt=record_dt).metrics
            return ({"track_reach": _member_values(m["track_reach"], len(ships))},
                    passes.needed([m["time_dead"]], len(ships)))

        reach = [advanced(passes.run("stopping", stops, stoppers[i:i + CHUNK], t_stop)
                          )["track_reach"] for i in range(0, len(stoppers), CHUNK)]
        checks.append(("stopping", "track reach (full astern)", "-",
                       np.concatenate(reach) / L, STOPPING_LIMIT, "L"))
    criteria, values = [], []
    for ability, criterion, side, vals, limit, unit in checks:
        criteria.append({"ability": ability, "criterion": criterion, "side": side,
                         "limit": float(limit), "unit": unit})
        values.append(np.full(len(everyone), math.nan))
        values[-1][kept] = vals[:kept.size]  # (none kept: the reference ran as a stand-in)
    return probabilities_from_values(values, criteria, level=level, stopping_note=stopping_note,
                                     reasons=no_approach)


#: The members' runs last this many times the reference's time to the last event the criteria
#: need; the members that do not reach it (or, for an interpolated event, reach it within two
#: recordings of the end) run again, :data:`LAST_PASS` times as long. Once :data:`LEARN`
#: members of a manoeuvre have run, the first pass of the next chunk lasts what minimises the
#: expected simulated time given their needs, f + LAST_PASS · P(need > f) (in units of the
#: reference's time). The events are found from the samples around them, so a member's values
#: do not depend on the pass they came from (the runs are the same step by step).
FIRST_PASS = 1.15
#: Of the second pass: a member whose events are not reached then is excluded.
LAST_PASS = 1.5
#: Members of a manoeuvre whose needs are known before the first pass adapts to them.
LEARN = 200


class _Passes:
    """Runs a manoeuvre of members for a first pass (:data:`FIRST_PASS` times the reference's
    duration, then what the members seen so far need), then again for :data:`LAST_PASS` times
    it the members that did not reach their event (counted in :attr:`rerun`)."""

    def __init__(self, record_dt: float) -> None:
        self.record_dt = record_dt
        self.rerun = 0
        #: per manoeuvre, the members' needs / the reference's time (inf: not within the
        #: second pass)
        self.needs: dict[str, list[np.ndarray]] = {}

    def needed(self, times: Sequence[Any], n: int) -> np.ndarray:
        """The time each member needs [s]: its latest event (one DataArray per side, NaN where
        not reached: NaN) and two recordings more (the cubic through the four samples around
        a heading change, the parabola through the samples around an overshoot and the line
        to the sample after dead in the water need them)."""
        need = np.zeros(n)
        for da in times:
            need = np.maximum(need, _member_values(da, n))  # (NaN propagates)
        return need + 2.0 * self.record_dt

    def first_pass(self, key: str) -> float:
        """The first pass's length for ``key`` in units of the reference's time."""
        seen = np.concatenate(self.needs.get(key, [np.zeros(0)]))
        if seen.size < LEARN:
            return FIRST_PASS
        candidates = np.unique(np.clip(seen[np.isfinite(seen)], 0.0, LAST_PASS))
        if candidates.size == 0:
            return FIRST_PASS
        over = 1.0 - np.searchsorted(np.sort(seen), candidates, side="right") / seen.size
        cost = candidates + LAST_PASS * over
        return float(candidates[np.argmin(cost)])

    def run(self, key: str, measure: Any, ships: list[Any], t_event: float
            ) -> dict[str, np.ndarray]:
        """``measure(ships, t_final) -> (values by name, needed time)`` in two passes."""
        t_first = self.first_pass(key) * t_event
        got, need = measure(ships, t_first)
        with np.errstate(invalid="ignore"):
            again = np.flatnonzero(~(need <= t_first))
        if again.size:
            self.rerun += int(again.size)
            t_last = LAST_PASS * t_event
            more, need_more = measure([ships[i] for i in again], t_last)
            for name, v in got.items():
                v[again] = more[name]
            with np.errstate(invalid="ignore"):
                need[again] = np.where(need_more <= t_last, need_more, np.inf)
        self.needs.setdefault(key, []).append(need / t_event)
        return got


def _member_values(da: Any, n: int) -> np.ndarray:
    """A metric of ``n`` members as a float array (n,), in the order of the members."""
    return np.array(da.transpose("ship", ...).values if "ship" in da.dims else da.values,
                    dtype=float).reshape(n)


def _with_approach(members: list[Any], reference: list[Any]
                   ) -> tuple[list[Any], Any, dict[int, str]]:
    """The members whose steady straight approach is found (one batch, memoised for the
    manoeuvres that follow), the reference ship (``reference``'s if it has an approach, else
    the first such member) and why each other member has none (by index). With no such
    member, the reference alone stands in (its values are not the ensemble's)."""
    from ..equilibria.equilibrium import EquilibriumError
    from ..maneuvers.ships import steady_approaches

    both = members + reference
    found = steady_approaches(both[0].model, [s.params for s in both],
                              [s.approach_speed for s in both])
    failed = {i: f"{NO_APPROACH} of '{s.name}' at {s.approach_speed:.6g} m/s ({a})"
              for i, (s, a) in enumerate(zip(members, found)) if isinstance(a, str)}
    kept = [s for i, s in enumerate(members) if i not in failed]
    ref = reference[0] if reference and not isinstance(found[-1], str) else None
    if ref is None and not kept:
        raise EquilibriumError(f": none of the {len(members)} members has a straight approach "
                               f"(member 0: {failed[0]})", field="ships")
    return kept or [ref], ref if ref is not None else kept[0], failed


def probabilities_from_values(values: Sequence[Any], criteria: Sequence[dict[str, Any]], *,
                              complete: Any = None, level: float = 0.95,
                              stopping_note: str = "",
                              reasons: dict[int, str] | Sequence[str] = ()
                              ) -> ImoProbabilities:
    """The pass fractions of an ensemble from its members' criterion values.

    What :func:`imo_probabilities` gives from the values it computed; also what a file or a
    sweep store of the values gives back (a member passes a criterion when its value is at
    most the limit; it is counted when it has every value).

    Parameters
    ----------
    values : sequence of array_like
        Per criterion, the value of every member (NaN where it was not computed), in the
        criterion's unit.
    criteria : sequence of dict
        Per criterion, ``ability``, ``criterion``, ``side``, ``limit`` and ``unit``.
    complete : array_like of bool, optional
        The members counted (default: those with every value finite).
    level : float, optional
        Confidence level of the Wilson intervals.
    stopping_note : str, optional
        Why the stopping criterion is left out ("" when it is evaluated).
    reasons : dict of int to str, or sequence of str, optional
        Why members were excluded: by member index, or one per member ("" when counted);
        excluded members without one get the criteria that have no value.

    Returns
    -------
    ImoProbabilities

    Raises
    ------
    ParameterError
        Values of different lengths than ``criteria`` or than each other; a bad ``level``.
    """
    if not 0 < level < 1:
        raise ParameterError(f"must be in (0, 1), got {level!r}", field="level")
    arrays = [np.asarray(v, dtype=float).reshape(-1) for v in values]
    if len(arrays) != len(criteria) or len({a.size for a in arrays}) > 1 or not arrays:
        raise ParameterError("one array of member values per criterion, of one length, is "
                             "needed", field="values")
    n = arrays[0].size
    finite = np.all([np.isfinite(a) for a in arrays], axis=0)
    complete = finite if complete is None else np.asarray(complete, dtype=bool).reshape(n)
    given = dict(reasons) if isinstance(reasons, dict) else dict(enumerate(reasons))
    why = []
    for i in range(n):
        missing = [f"{c['ability']}: {c['criterion']}"
                   + (f" ({c['side']})" if c["side"] != "-" else "")
                   for c, a in zip(criteria, arrays) if not math.isfinite(a[i])]
        why.append("" if complete[i] else given.get(i) or (
            "no value for " + "; ".join(missing) + " (an event not reached within the run, "
            "or a diverged run)" if missing else "excluded"))
    total = int(complete.sum())
    rows = []
    every = np.ones(n, dtype=bool)
    for c, vals in zip(criteria, arrays):
        ok = vals <= c["limit"]
        every &= ok
        passed = int(ok[complete].sum())
        lo, hi = wilson_interval(passed, total, level)
        rows.append({"ability": c["ability"], "criterion": c["criterion"], "side": c["side"],
                     "passed": passed, "total": total,
                     "probability": passed / total if total else math.nan,
                     "ci_low": lo, "ci_high": hi, "limit": float(c["limit"]),
                     "unit": c["unit"],
                     "median": float(np.median(vals[complete])) if total else math.nan})
    passed_all = int(every[complete].sum())
    lo, hi = wilson_interval(passed_all, total, level)
    return ImoProbabilities(rows=tuple(rows), passed=passed_all, total=total,
                            excluded=n - total,
                            probability=passed_all / total if total else math.nan,
                            ci_low=lo, ci_high=hi, level=level, stopping_note=stopping_note,
                            values=tuple(arrays), complete=complete, reasons=tuple(why))


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
#: The largest relative standard deviation of the default draws: at 1 (100 %) a normal draw
#: changes a coefficient's sign in Φ(−1) = 16 % of the samples -- beyond it the ensemble is
#: of other ships (a straight-line unstable hull, a cross-flow drag that is negative) rather
#: than an uncertainty of this one.
MAX_UNCERTAINTY = 1.0


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
        Relative standard deviation of the default draws, in (0, :data:`MAX_UNCERTAINTY`].

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
    from ...numerics.sampling import draw_samples, get_distribution

    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ParameterError(f"must be a whole number >= 1, got {n!r}", field="n", value=n)
    if not (math.isfinite(uncertainty) and 0 < uncertainty <= MAX_UNCERTAINTY):
        raise ParameterError(f"must be in (0, {MAX_UNCERTAINTY:g}] (a relative standard "
                             f"deviation), got {uncertainty!r}", field="uncertainty",
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
