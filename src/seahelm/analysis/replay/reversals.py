"""Propeller reversals in measured records, and their stops replayed: the stopping validation.

A free-running record with a propeller that goes astern while the ship still moves ahead is a
measured stop. :func:`find_reversals` finds them by a fixed rule, :func:`replay_stop`
replays each from its start with :func:`~.simulate.replay` (the measured rps and
rudder as inputs, first-order hold) and compares the time and the head reach to u ≤ 0.

The rule (:data:`REVERSAL_RULE`), on the record's samples k:

- **the reversal**: a sample k with n(k−1) > 0 and n(k) ≤ 0 (the rps leaves ahead);
- **clean**: from k on, n ≤ 0 at every sample until the first sample j > k with u(j) ≤ 0
  (the ship is stopped with the propeller never ahead again), and the record reaches j;
- **astern**: min n over [k, j] ≤ −``min_astern_rps`` (a reversal, not a stopped propeller:
  the stops with n = 0 throughout are *coasting* stops, found with ``coasting=True``);
- **moving**: u(k−1) ≥ ``min_speed`` (a stop from a speed worth measuring);
- the replay starts at sample s = k − 1 (the last sample ahead), so the measured fall of the
  rps through zero is in its input.

Time to stop: t(u = 0) − t_s, with t(u = 0) the first zero of the surge speed u, linearly
interpolated between samples (the measured u from the record, the simulated u from the replay
on the record's times). Head reach: the distance run along the heading at the start,
(x(t_0) − x_s) cos ψ_s + (y(t_0) − y_s) sin ψ_s, with the position interpolated to the zero.
The replay runs to ``2 (j − s)`` samples past s (or the record's end) so that a simulated stop
later than the measured one is still found; a simulated ship that has not stopped by then has
NaN time and reach.

References
----------
Miyauchi, Y., Maki, A., Umeda, N., Rachman, D. M. & Akimoto, Y. (2022). System parameter
exploration of ship maneuvering model for automatic docking/berthing using CMA-ES. J. Mar.
Sci. Technol. 27, 1065–1083 (the random and berthing records of the Esso Osaka model: the
FRT-DS-ESSO data set).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...identification.records import ManoeuvreRecord

__all__ = ["Reversal", "StopComparison", "find_reversals", "replay_stop", "slice_record",
           "REVERSAL_RULE", "MIN_SPEED", "MIN_ASTERN_RPS"]

#: Least surge speed at the start of a stop [m/s] (rule 4).
MIN_SPEED = 0.05
#: Least astern rps of a reversal [1/s] (rule 3).
MIN_ASTERN_RPS = 1.0

REVERSAL_RULE = (
    "reversal at sample k: n[k-1] > 0 and n[k] <= 0; clean: n <= 0 at every sample from k to "
    "the first j > k with u[j] <= 0 (inside the record); astern: min n over [k, j] <= "
    f"-{MIN_ASTERN_RPS:g} rps (else a coasting stop); moving: u[k-1] >= {MIN_SPEED:g} m/s; "
    "the replay starts at k - 1")


@dataclasses.dataclass(frozen=True)
class Reversal:
    """One clean propeller reversal (or coasting stop) of a record (module docstring).

    Attributes
    ----------
    record : str
        The record's name.
    start, stop : int
        Sample s = k − 1 (the last sample ahead) and j (the first with u ≤ 0).
    start_time : float
        t_s [s].
    start_speed : float
        u_s [m/s].
    ahead_rps, astern_rps : float
        n_s and min n over [k, j] [1/s].
    time_to_stop, head_reach : float
        Measured [s], [m] (module docstring).
    coasting : bool
        n = 0 throughout (no astern rps).
    """

    record: str
    start: int
    stop: int
    start_time: float
    start_speed: float
    ahead_rps: float
    astern_rps: float
    time_to_stop: float
    head_reach: float
    coasting: bool


@dataclasses.dataclass(frozen=True)
class StopComparison:
    """A stop measured and replayed.

    Attributes
    ----------
    reversal : Reversal
    wind : str
        ``"none"`` or ``"measured"``.
    time_to_stop, head_reach : float
        Simulated [s], [m] (NaN: not stopped within the replay).
    time_error, reach_error : float
        Simulated over measured, minus 1 [-].
    """

    reversal: Reversal
    wind: str
    time_to_stop: float
    head_reach: float

    @property
    def time_error(self) -> float:
        return self.time_to_stop / self.reversal.time_to_stop - 1.0

    @property
    def reach_error(self) -> float:
        return self.head_reach / self.reversal.head_reach - 1.0


def _zero_crossing(time: np.ndarray, u: np.ndarray, first: int) -> float:
    """The first t ≥ time[first] where u falls to 0, interpolated (NaN if never)."""
    below = np.flatnonzero(u[first:] <= 0.0)
    if below.size == 0:
        return math.nan
    j = first + int(below[0])
    if j == first:
        return float(time[j])
    t0, t1, u0, u1 = time[j - 1], time[j], u[j - 1], u[j]
    return float(t0 + (t1 - t0) * u0 / (u0 - u1))


def _reach(time: np.ndarray, north: np.ndarray, east: np.ndarray, heading: float,
           t_stop: float) -> float:
    if not math.isfinite(t_stop):
        return math.nan
    dx = float(np.interp(t_stop, time, north)) - north[0]
    dy = float(np.interp(t_stop, time, east)) - east[0]
    return dx * math.cos(heading) + dy * math.sin(heading)


def _need(record: ManoeuvreRecord, *names: str) -> None:
    missing = [n for n in names if n not in record.channels]
    if missing:
        raise ParameterError(f"{record.name}: finding propeller reversals needs column(s) "
                             f"{', '.join(missing)}", field=missing[0])


def find_reversals(record: ManoeuvreRecord, *, min_speed: float = MIN_SPEED,
                   min_astern_rps: float = MIN_ASTERN_RPS,
                   coasting: bool = False) -> list[Reversal]:
    """The clean propeller reversals of a record (the rule of the module docstring).

    Parameters
    ----------
    record : ManoeuvreRecord
        With ``propeller_rps``, ``surge_speed``, ``x``, ``y`` and ``heading``.
    min_speed : float, optional
        Least surge speed at the start [m/s] (default :data:`MIN_SPEED`).
    min_astern_rps : float, optional
        Least astern rps of a reversal [1/s] (default :data:`MIN_ASTERN_RPS`).
    coasting : bool, optional
        Return the coasting stops (n = 0 until u ≤ 0, rules 1, 2 and 4) instead of the
        reversals.

    Returns
    -------
    list of Reversal
        In time order.

    Raises
    ------
    ParameterError
        A record without the needed columns.
    """
    _need(record, "propeller_rps", "surge_speed", "x", "y")
    if record.heading is None:
        raise ParameterError(f"{record.name}: finding propeller reversals needs column "
                             "heading", field="heading")
    n = record.channels["propeller_rps"]
    u = record.channels["surge_speed"]
    t = record.time
    found: list[Reversal] = []
    for k in np.flatnonzero((n[:-1] > 0.0) & (n[1:] <= 0.0)) + 1:
        s = int(k) - 1
        if u[s] < min_speed:
            continue
        after = np.flatnonzero(u[k:] <= 0.0)
        if after.size == 0:
            continue
        j = int(k) + int(after[0])
        if np.any(n[k:j + 1] > 0.0):
            continue
        astern = float(np.min(n[k:j + 1]))
        is_coast = astern > -min_astern_rps
        if is_coast != coasting or (coasting and astern != 0.0):
            continue
        t_stop = _zero_crossing(t, u, s)
        found.append(Reversal(
            record=record.name, start=s, stop=j, start_time=float(t[s]),
            start_speed=float(u[s]), ahead_rps=float(n[s]), astern_rps=astern,
            time_to_stop=t_stop - float(t[s]),
            head_reach=_reach(t[s:], record.channels["x"][s:], record.channels["y"][s:],
                              float(record.heading[s]), t_stop),
            coasting=is_coast))
    return found


def slice_record(record: ManoeuvreRecord, start: int, stop: int) -> ManoeuvreRecord:
    """Samples ``start`` … ``stop − 1`` of a record, as a record of its own.

    Parameters
    ----------
    record : ManoeuvreRecord
    start, stop : int
        Sample range (``stop`` exclusive).

    Returns
    -------
    ManoeuvreRecord
    """
    cut = slice(start, stop)
    return dataclasses.replace(
        record, name=f"{record.name}[{start}:{stop}]", time=record.time[cut].copy(),
        rudder_angle=record.rudder_angle[cut].copy(),
        heading=None if record.heading is None else record.heading[cut].copy(),
        yaw_rate=None if record.yaw_rate is None else record.yaw_rate[cut].copy(),
        channels={k: v[cut].copy() for k, v in record.channels.items()})


def replay_stop(record: ManoeuvreRecord, reversal: Reversal, ship: Any, *,
                wind: str = "none", wind_loads: str = "fujiwara",
                dt: float | None = None) -> StopComparison:
    """Replay one stop from its start and compare the time and head reach to u ≤ 0.

    Parameters
    ----------
    record : ManoeuvreRecord
        The record the reversal was found in.
    reversal : Reversal
        From :func:`find_reversals`.
    ship : Ship or str
        The ship.
    wind : {"none", "measured"}, optional
        Still air or the record's measured true wind (:func:`~.simulate.replay`).
    wind_loads : str, optional
        The wind-load model with the measured wind (default ``"fujiwara"``).
    dt : float, optional
        Integration step [s] (default: the replay's).

    Returns
    -------
    StopComparison
    """
    from .simulate import replay

    s, j = reversal.start, reversal.stop
    end = min(len(record.time), s + 2 * (j - s) + 1)
    part = slice_record(record, s, end)
    result = replay(part, ship, kind="none", wind=wind, wind_loads=wind_loads, dt=dt)
    sim = result.simulated
    t_stop = _zero_crossing(result.time, sim["surge_speed"], 0)
    reach = _reach(result.time, sim["north"], sim["east"], float(sim["heading"][0]), t_stop)
    return StopComparison(reversal=reversal, wind=wind,
                          time_to_stop=t_stop - float(result.time[0]), head_reach=reach)
